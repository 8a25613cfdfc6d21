#pragma once
// Static states by Newton (-solver static): a body without failure has one static state
// per stretch, the minimum of its stored energy W(u) with the grips held (docs/method.md
// section 3). The static solver finds it directly, in load steps along the schedule:
//
//   for each ramp of -load_schedule, in load steps of the applied stretch:
//     predict: the secant through the last two states; at the first step and after a
//              cutback one tangent step with the grips' increment imposed
//     solve:   PETSc SNES (Newton with line search) on R(u) = dW/du = -V f(u) = 0 over
//              the free dofs, the grips' dofs Dirichlet rows, the exact symmetric tangent
//              (tangent_operator.hpp, ba_tangent.hpp)
//     accept:  a history row; grow the step after a fast solve. Not converged: back to
//              the last state with half the step (cutback), down to -static_stretch_step_min
//     break:   with failure, the dynamic route's breaking pass at the static state
//              (Failure::Break and its cascade); bonds broke: Newton again at the same
//              load, then the criterion again, until no bond breaks (re-equilibration,
//              a history row after each). The first load step that breaks bonds is cut
//              back until it is at most -static_onset_tolerance (lambda - 1) wide
//   at the start of each hold and at the end: a row of static_states.csv (and fields)
//
// It reuses the dynamic driver's set-up (body, layout, force operator, failure, loading,
// history and field output: SimulationD is its friend) and changes none of it: -solver
// dynamic runs as before. Not yet: softening bonds, checkpoints and restart (refused).
#include <petscsnes.h>

#include <vector>

#include "bapd/solver/driver/simulation.hpp"
#include "bapd/solver/operators/tangent_operator.hpp"

namespace bapd {

// What the static solver cannot do yet, refused before any work with the option to
// change: softening bonds (-failure_softening), checkpoints and restart, the bond-only force (no energy),
// a schedule that does not start undeformed. Nothing with -solver dynamic (run). Collective.
PetscErrorCode StaticSolverCheckScene(MPI_Comm comm, const RunSection &run, const FailureSection &failure, ForceForm force_form,
                                      const Schedule &schedule, const CheckpointOptions &checkpoint);

template <int D> class StaticSolver {
public:
  explicit StaticSolver(SimulationD<D> &simulation) : sim_(simulation) {}
  ~StaticSolver();
  StaticSolver(const StaticSolver &)            = delete;
  StaticSolver &operator=(const StaticSolver &) = delete;

  // The tangent, the matrix and the SNES (with the PETSc options: -snes_*, -ksp_*, -pc_*).
  PetscErrorCode Setup();
  // Every load step of the schedule, the outputs, the summary. Fails (PETSC_ERR_NOT_CONVERGED)
  // with the stretch and the options to change if a load step cannot converge.
  PetscErrorCode Run();
  // Solves for the static state at schedule time t from the current state (cutbacks
  // included); *converged false if it could not (the state is then the last one).
  PetscErrorCode SolveTo(double t, PetscBool *converged);

  // For tests and tools. The nodal internal force -V f (D per owned point, every dof,
  // the grips' too) at the owned displacements u, and the tangent dW/du at u (no
  // Dirichlet rows), both without changing the state.
  PetscErrorCode NodalForce(Vec u, Vec force);
  PetscErrorCode Tangent(Vec u, Mat H);
  PetscErrorCode CreateMatrix(Mat *H) const { return tangent_.CreateMatrix(H); }
  void           set_law_tangent(bool exact) { tangent_.set_law_tangent(exact); } // TangentOperator::set_law_tangent
  Vec            displacement() const { return u_; } // the current state (owned dofs)
  PetscInt       newton_iterations() const { return newton_iterations_; }
  PetscInt       krylov_iterations() const { return krylov_iterations_; }
  PetscInt       load_steps() const { return load_steps_; }
  PetscInt       cutbacks() const { return cutbacks_; }
  PetscInt       reequilibrations() const { return reequilibrations_; }
  // The bonds that meet the failure criterion at the owned displacements u (the grips
  // held at the current load) broken, as after a load step; *broken: how many, over the
  // ranks. For tests (a tangent with broken bonds). Collective.
  PetscErrorCode BreakAt(Vec u, PetscInt *broken);

private:
  static PetscErrorCode FormFunction(SNES, Vec u, Vec r, void *ctx);
  static PetscErrorCode FormJacobian(SNES, Vec u, Mat H, Mat P, void *ctx);
  static PetscErrorCode ConvergenceTest(SNES, PetscInt it, PetscReal xnorm, PetscReal step, PetscReal fnorm, SNESConvergedReason *reason,
                                        void *ctx);
  // One load step from the current state (time t_) to t: predictor and Newton.
  PetscErrorCode LoadStep(double t, PetscBool *converged, PetscInt *iterations);
  // Newton from u_ at the grips of t_target_ (the tangent fresh at its first iteration).
  PetscErrorCode Newton(PetscBool *converged, PetscInt *iterations);
  // The breaking (static_breaking.cpp). After the load step from t_before converged at
  // t_: the onset search, the load step's history row, breaking and re-equilibrating.
  // *retry: the step was taken back (the first break not yet located); *stable false:
  // a re-equilibration did not converge (the state is the last static one).
  PetscErrorCode AfterLoadStep(double t_before, PetscInt iterations, bool *retry, bool *stable);
  PetscErrorCode BreakAtState(const double *u_owned, bool *broke); // Failure::Break and the cascade at u_owned
  PetscErrorCode UndoBreaking();  // the bond state before the last BreakAtState
  PetscErrorCode KeepBreaking();  // its released energy into the budget (fracture_dissipation_J)
  PetscErrorCode Reequilibrate(bool *stable); // Newton at t_ and breaking until no bond breaks
  PetscInt       Solves() const { return load_steps_ + reequilibrations_; } // history.csv's step column
  PetscErrorCode Predict(double t);
  // Owned displacements with the grips at their values at time t.
  void           HoldGrips(double t, double *u) const;
  PetscErrorCode CopyHeld(Vec U); // u_scratch_ = U with the grips held at t_target_
  PetscErrorCode Evaluate(const double *u, bool *ok); // force_density_ at u, committed warm starts
  PetscErrorCode CopyToPreconditioner(); // P_ = H_ after an assembly
  PetscErrorCode CopyToState(); // u_ into the driver's state X_ (v = 0), for its history and fields
  PetscErrorCode WriteStaticState(double t);
  PetscErrorCode Summary(double cpu);

  SimulationD<D>       &sim_;
  TangentOperator       tangent_;
  SNES                  snes_ = nullptr;
  Mat                   H_    = nullptr; // the tangent (BAIJ unless -mat_type)
  Mat                   P_    = nullptr; // its AIJ copy for the preconditioner (H_ itself if H_ is AIJ)
  Vec                   u_ = nullptr, r_ = nullptr, u_last_ = nullptr, du_ = nullptr, b_ = nullptr;
  Vec                   u_before_ = nullptr; // the state before the last converged step (the secant predictor)
  double                lambda_before_ = 1;  // ...and its stretch
  bool                  secant_ = false, use_secant_ = true;
  std::vector<PetscInt> held_;          // global dof indices of the grips' dofs on this rank
  std::vector<double>   u_scratch_;     // D per owned point
  std::vector<double>   force_density_; // D per owned point
  std::vector<double>   grips_before_, grips_after_; // the predictor's grips at the two times, D per owned point
  std::vector<double>   c33_last_;      // the warm starts at the start of the load step (a cutback's)
  double                dirichlet_diagonal_ = 0; // the grips' rows' diagonal (FormJacobian), set at the first tangent
  int                   block_copy_ = -1; // CopyToPreconditioner: -1 not tried yet, 1 block by block, 0 MatConvert
  double                t_              = 0;    // schedule time of the current state
  double                t_target_       = 0;    // of the load step being solved
  double                reaction_norm_  = 0;    // |V f| over the grips' dofs at the last evaluation
  double                last_fnorm_     = 0;    // |R| at the last convergence test
  bool                  reuse_tangent_  = true; // modified Newton (StaticSolver::Setup); false with -snes_lag_jacobian
  PetscInt              step_tangents_  = 0;    // tangents Newton built in the current load step
  double                step_           = 0;    // the load step in stretch (0: -static_stretch_step)
  PetscInt              newton_iterations_ = 0, krylov_iterations_ = 0, load_steps_ = 0, cutbacks_ = 0, jacobians_ = 0;
  PetscInt              static_states_ = 0;
  PetscInt              reequilibrations_ = 0; // Newton solves at a load after bonds broke
  PetscInt              unstable_bonds_ = 0;   // bonds broken when a re-equilibration did not converge (0: none failed)
  double                onset_stretch_ = 0;    // the stretch of the load step that broke the first bonds (0: none yet)
  double                onset_width_   = 0;    // ...and its width in stretch
  bool                  onset_search_  = false; // a first break seen and taken back: the load step does not grow
  bool                  crack_grew_    = false; // the last load step broke bonds: the next does not grow
  double                peak_reaction_ = 0;    // the largest |reactions| of a converged state (ConvergenceTest's floor)
  std::vector<FailedBond> no_failed_;          // Failure::Break's list of bonds whose law failed: none at a static state
  PetscInt              linear_failures_ = 0; // consecutive load steps ended by a failed linear solve
  SNESConvergedReason   last_reason_   = SNES_CONVERGED_ITERATING;
};

} // namespace bapd
