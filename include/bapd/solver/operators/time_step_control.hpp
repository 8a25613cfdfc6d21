#pragma once
// Time-step control: the stable step of the linearised system (a Krylov search on the
// force operator, or the power iteration, -time_step_estimate; the estimate is
// time_step_estimate.cpp, the policy time_step_control.cpp), re-estimated during the
// run as the material stiffens or
// softens (-time_step_reestimate), and the shortening while points fly
// (-time_step_travel, docs/stability.md sections 5 and 8). SetBaseStep is where a new
// base step enters (the -ts_dt override at set-up).
//
// The step in use is dt = min(dt_stiffness, dt_travel):
//  - dt_stiffness = base x sqrt(lambda_rest / lambda_now), at most the base step,
//    where lambda is the largest eigenvalue of M^{-1} K (Velocity Verlet is stable for
//    dt < 2 / sqrt(lambda_max)); lambda_now comes from a Krylov search on the
//    current tangent, K v = -(f(u + eps v) - f(u)) / eps (the largest Rayleigh
//    quotient over the space of the evaluations, -time_step_krylov; or the power
//    iteration's), warm-started from the last
//    eigenvector: a few force evaluations every -time_step_reestimate steps (more
//    often while lambda moves, up to -time_step_reestimate_backoff x less often while
//    the estimates find nothing that would move the step). It shrinks at once when
//    lambda grows by more than the dead band and grows back (bounded by the base
//    step) only when lambda falls by more than it: the band keeps the step from
//    flapping on the estimate's noise.
//  - dt_travel: no point with bonds moves more than -time_step_travel dx in one step.
// With failure, a step that broke bonds is followed by a crack-tip search: a short
// Krylov search from a start vector on the points whose bonds broke (-time_step_crack_tip),
// which finds the stiff mode a partly broken family makes at the tip, a mode that the
// whole-body estimate, warm-started from the body's own mode, does not see
// (time_step_crack_tip.cpp).
// Every sum is a reproducible sum and every maximum exact, so the step is the same on
// any number of ranks; the estimate's state (eigenvector, lambda, the stiffness step)
// is in checkpoints, so a restart continues bit for bit.
#include <petscts.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/operators/force_operator.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/operators/loading.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/input/scene_time_stepping.hpp"

namespace bapd {

// What a checkpoint carries of the re-estimate (natural order is the caller's job).
struct TimeStepState {
  double   lambda        = 0; // the latest estimate of lambda_max [1/s^2]
  double   stiffness_dt  = 0; // the stiffness step [s]
  PetscInt next_estimate = 0; // the step after which the next re-estimate runs
  double   stretch       = 1; // the applied stretch at the last re-estimate
  PetscInt by_stiffness = 0, by_travel = 0; // the counters of the summary
  double   shortest = 0;
  PetscInt interval_now = 0;      // steps between re-estimates now (backed off while quiet); 0: not stored (format 3)
  double   stretch_increment = 0; // ...and the stretch increment now
  double   indicator = 0;         // the stiffening indicator at the last search; 0: not stored (format 4)
};

class TimeStepControl {
public:
  // lambda_max of M^{-1} K at the reference state (-time_step_estimate: the Krylov
  // search until its largest Ritz value settles, or 60 power iterations), then the step
  // -time_step or -time_step_safety x stable. Leaves the operator as it was (the
  // estimate reads or carries its own warm starts). Collective; prints the steps.
  // From the scene: the step asked for and the re-estimate's options (stepping), the
  // law's stiffening span and the mass (material), whether bonds break (failure: the
  // travel limit and the step's floor) and the spacing dx [m] (the probes' size).
  PetscErrorCode EstimateStable(MPI_Comm comm, const TimeSteppingSection &stepping, const MaterialSection &material,
                                bool failure, double dx, const Layout &layout, const Loading &loading, ForceOperator &force);
  // A new base step (and step in use); the TS takes it with the next step.
  // The solver's travel limit is off for a step above the stable one.
  void SetBaseStep(double dt);
  // A step fixed by `option` (-time_step, -ts_dt) more than fixed_step_margin above the
  // stable step at rest is refused before the first step (the explicit scheme
  // amplifies its fastest mode every step, and a short run ends in one or two steps,
  // before any divergence check sees it), unless -time_step_allow_unstable; a step
  // above the stable one within the margin, or allowed, draws a loud warning.
  // Collective (every rank has the same estimate).
  PetscErrorCode CheckFixedStep(MPI_Comm comm, const char *option, double dt) const;
  // The stable step is 2 / sqrt(1.1 lambda_max) (the estimate padded by 10 %), i.e.
  // 0.953 x the explicit scheme's limit 2 / sqrt(lambda_max) of the estimate: a step up
  // to 1.05 x it is at most that limit (and a value copied from the 4 digits printed
  // rounds within it).
  static constexpr double fixed_step_margin = 1.05;

  // Every acceleration the dynamics evaluates (owned u and the free acceleration, 2
  // per point): kept (a copy, no allocation) when the next re-estimate will use it as
  // its base point f(u), which saves a force evaluation.
  void Record(const double *u, const double *a);
  // After a step: the re-estimate when due (about the last recorded evaluation, with
  // the operator's committed warm starts copied: side-effect free), then the travel
  // limit over the owned velocities v (2 per point), then the step the TS takes next.
  // touched: the local points whose bonds the step's breaking passes broke
  // (Failure::touched; nullptr without failure); broke: whether they broke any on some
  // rank (the driver's one reduction a step of it). Broken bonds make the recorded
  // evaluation stale as the re-estimate's base point, and call the crack-tip search.
  // Collective.
  PetscErrorCode AfterStep(MPI_Comm comm, PetscInt step, double stretch, const Layout &layout, const Families &families, const BondState &state,
                           ForceOperator &force, const double *v, const std::vector<std::size_t> *touched, bool broke, TS ts);
  // The stable step of the state (u: owned, 2 per point; c33: its warm starts, 1 per
  // bond) by `iterations` shifted power iterations from the current eigenvector: for
  // the diagnosis of a divergence (divergence.hpp), once. Collective.
  PetscErrorCode SharpEstimate(MPI_Comm comm, ForceOperator &force, const double *u, const std::vector<double> &c33, PetscInt iterations,
                               double *stable);
  // Restart: the step in use (header time_step) and the estimate's state.
  PetscErrorCode Restore(double dt, const TimeStepState &state, TS ts);

  double   stable() const { return stable_dt_; }           // at rest
  double   stable_now() const { return stable_now_; }      // of the latest estimate
  double   lambda_rest() const { return lambda_rest_; }
  double   base() const { return base_dt_; }
  double   current() const { return dt_; }
  double   stiffness_step() const { return stiffness_dt_; }
  double   travel() const { return travel_; }              // [m], 0: off
  bool     travel_automatic() const { return travel_auto_; }
  bool     reestimating() const { return options_.interval > 0; }
  PetscInt shortened_steps() const { return by_stiffness_ + by_travel_; }
  PetscInt shortened_by_stiffness() const { return by_stiffness_; } // steps shorter than base because of lambda_now
  PetscInt shortened_by_travel() const { return by_travel_; }       // ...shorter still because points flew
  PetscInt estimates() const { return estimates_; }                 // re-estimates so far (this process's run)
  PetscInt estimate_evaluations() const { return evaluations_; }    // force evaluations they cost
  PetscInt startup_evaluations() const { return startup_evaluations_; } // force evaluations of the estimate at rest (EstimateStable)
  PetscInt kinks() const { return kinks_; }                         // estimates dropped as a kink of the force (Kink)
  PetscInt tip_searches() const { return tip_searches_; }           // crack-tip searches (CrackTipSearch)
  PetscInt tip_shortenings() const { return tip_shortenings_; }     // ...that shortened the step
  double   estimate_seconds() const { return estimate_wall_; }      // wall time they cost (this rank)
  double   shortest() const { return shortest_dt_; }
  double   largest_lambda() const { return lambda_largest_; }
  // Checkpoints: the state and the eigenvector (owned points, 2 each).
  TimeStepState state() const;
  double       *eigenvector() { return v_.data(); }

private:
  void           SeedStart(const Layout &layout); // the searches' deterministic start, v_ and seed_
  PetscErrorCode ReportStartup(MPI_Comm comm, bool step_given, double lambda) const; // the set-up's lines on the step
  // The acceleration of the free dofs, M^{-1} f, the held ones zero, of a probe u: the
  // C33 warm starts c33 only read, or read from and advanced in *advance (the set-up's
  // iteration). time_step_estimate.cpp.
  static PetscErrorCode ProbeAcceleration(ForceOperator &force, const std::vector<double> &c33, std::vector<double> *advance, double inv_rho,
                                          const std::vector<char> &held, const double *u, double *a);
  // loading: the applied stretch moved since the last estimate; psi: the stiffening
  // indicator of the state (0: not computed, -time_step_reestimate_indicator 0).
  // broke: bonds broke after the recorded evaluation (its a(u) is evaluated again).
  PetscErrorCode Reestimate(MPI_Comm comm, ForceOperator &force, bool loading, double psi, bool broke, PetscInt *iterations);
  // The crack-tip search (time_step_crack_tip.cpp): options_.tip Krylov steps about the
  // recorded state from the start vector's entries on the owned points of `touched`
  // (zero elsewhere); the base point a(u) is evaluated again first (the bonds just
  // broke). A quotient above the estimate in use by more than the dead band, and
  // smooth from both sides (Kink), becomes the estimate, its Ritz vector the warm start of the next
  // re-estimates; *raised says so. Collective.
  PetscErrorCode CrackTipSearch(MPI_Comm comm, ForceOperator &force, const std::vector<std::size_t> &touched, PetscInt n_owned, bool *raised);
  // The travel limit's speed: the largest |v|^2 over the owned points with a bond. Collective.
  PetscErrorCode FastestBondedSpeed2(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state, const double *v,
                                     double *v2_max) const;
  // After a step that broke bonds: the search, and a step shortened at once when it
  // found the tip stiffer than the dead band allows. Collective.
  PetscErrorCode FollowCrackTip(MPI_Comm comm, ForceOperator &force, const std::vector<std::size_t> &touched, PetscInt n_owned, PetscInt step);
  // What a re-estimate's iterations stop on (Reestimate decides it, Iterate runs it).
  struct IterationPlan {
    bool     rising, at_base, search, near;
    double   threshold;
    PetscInt fewest;
  };
  PetscErrorCode Iterate(MPI_Comm comm, ForceOperator &force, const std::vector<double> &committed, const IterationPlan &plan,
                         double *lambda, PetscInt *iterations);
  // The lambda_max above which the base step would be shortened (outside the dead band).
  double ShorteningThreshold() const { return lambda_rest_ / ((1.0 - options_.band) * (1.0 - options_.band)); }
  // The back-off and the early stop spend part of the margin the safety factor leaves
  // (0.8 / sqrt(1.1) covers an estimate 1.7 x below lambda_max): with a base step above
  // 0.9 x the stable one at rest there is too little of it (the map's safety-1.0 cell
  // stopped with them), and every estimate runs as without them.
  bool Margin() const { return base_dt_ <= 0.9 * stable_dt_; }
  // The stiffness step the latest lambda asks for: base x sqrt(lambda_rest / lambda),
  // within [floor x base, base].
  double StiffnessTarget() const { return std::clamp(base_dt_ * std::sqrt(lambda_rest_ / lambda_), floor_ * base_dt_, base_dt_); }
  // Mixes seed_weight x the start vector into the eigenvector (Reestimate explains).
  PetscErrorCode MixSeed(MPI_Comm comm);
  static constexpr double seed_weight = 0.05;
  // With the Krylov search: the Krylov space keeps the warm start's mode whatever the
  // weight (it holds v and A v, ...), so the seed can carry more of the modes that rose
  // elsewhere. The Jm = 8 plate's stretch-2 mode near the hole (2.0 x lambda_rest) was
  // found at once with 0.5 and never with 0.05 (the estimate stayed at 1.3 x through the
  // hold; docs/stability.md section 8).
  static constexpr double krylov_seed_weight = 0.5;
  static constexpr PetscInt rising_iterations = 4;
  static constexpr double   near_limit = 4.0; // -time_step_reestimate_bonds: the Gent factor from which every shortened estimate searches (Reestimate)
  PetscErrorCode PowerStep(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, std::vector<double> *advance,
                           const double *u0, const double *a0, double shift, double *lambda);
  // The Krylov search (-time_step_krylov): KrylovStart takes v_ (any length) as the
  // first basis vector; KrylovStep j (from 0) applies A to basis vector j (one force
  // evaluation), orthogonalises the result against the basis (twice: classical
  // Gram-Schmidt, reproducible sums) into vector j + 1, and returns the largest
  // eigenvalue of the symmetric part of the projected (j + 1) x (j + 1) matrix: the
  // largest Rayleigh quotient over the whole space, never below the power iterate's
  // (which lies in it). KrylovFinish leaves the Ritz vector of the last step in v_.
  PetscErrorCode KrylovStart(MPI_Comm comm);
  PetscErrorCode KrylovStep(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, const double *u0, const double *a0, PetscInt j, double *lambda, bool *exhausted);
  void           KrylovFinish(PetscInt steps);
  PetscErrorCode Dot(MPI_Comm comm, const double *x, const double *y, double *result);
  // Restarted Krylov about (u_rec_, a_rec_) from v_ with the seed mixed in, `iterations`
  // evaluations (probes with the warm starts c33, read only): the largest quotient found. Leaves the Ritz vector in v_.
  PetscErrorCode RestartedKrylov(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, PetscInt iterations, double *best);
  // The set-up's Krylov search (-time_step_estimate krylov) about (u0, a0) from v_, the
  // warm starts c33 only read: cycles of krylov_cap steps, each from the last one's Ritz
  // vector, until the largest Ritz value moves by less than startup_tolerance in two steps in a row,
  // at most startup_limit evaluations. *lambda: the largest Ritz value found; leaves its
  // Ritz vector in v_. time_step_estimate.cpp explains the stop.
  PetscErrorCode StartupKrylov(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, const double *u0, const double *a0,
                               double *lambda);
  static constexpr double   startup_tolerance  = 1e-3;
  static constexpr PetscInt startup_iterations = 60; // the power iteration's count (-time_step_estimate power)
  static constexpr PetscInt startup_limit      = 60; // the Krylov search's most: never more than the power iteration
  // Whether the force has a kink (a bond switching its state) at the recorded state along
  // the unit Ritz vector: the Rayleigh quotient from both sides disagrees
  // (time_step_control.cpp explains); two force evaluations.
  PetscErrorCode Kink(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, double lambda, bool *kink);
  static constexpr double kink_jump     = 4.0; // an estimate above this x the last one (or lambda_rest) is checked
  static constexpr double kink_mismatch = 0.5; // ...and dropped when its two sides differ by more than this fraction
  // -time_step_monitor_reference: the converged lambda_max of the state of the latest
  // evaluation, printed next to the estimate in use; leaves the estimate's state as it was.
  PetscErrorCode Reference(MPI_Comm comm, ForceOperator &force, PetscInt step);
  // The stiffening indicator of the recorded state (u_rec_): the largest over the owned
  // points of psi_i = g_i^2 I1bar_i / 3, with F_i the point's own deformation gradient
  // (intact bonds, volume weights), I1bar_i its isochoric first invariant (plane stress:
  // C33 = 1 / det C~, i.e. J = 1; plane strain: C33 = 1) and g_i = 1 / (1 - (I1bar_i -
  // 3) / (I1bar_limit - 3)) the Gent factor (1 for a law without a limit). A bond loop
  // with a handful of flops per bond, no constitutive solve: about 1/50 of a force
  // evaluation. The maximum is exact (MPI_MAX): the same on any number of ranks.
  PetscErrorCode StiffeningIndicator(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state,
                                     ForceOperator &force, double *psi);
  // -time_step_reestimate_bonds: the indicator from the dynamics' own evaluation, the
  // Gent factor g = 1 / (1 - (tr C - 3) / (I1bar_limit - 3)) of the bond with the
  // largest tr C the kernel saw (KernelStats::largest_trC; tr C / 3 for a law without a
  // limit); an exact maximum over the ranks. No bond loop here: the kernel kept the
  // maximum as it went.
  PetscErrorCode BondIndicator(MPI_Comm comm, const ForceOperator &force, double *psi) const;

  TimeStepOptions options_;
  double   stable_dt_ = 0, stable_now_ = 0, lambda_rest_ = 0, lambda_ = 0, lambda_largest_ = 0;
  double   base_dt_      = 0; // the step chosen at setup (safety x stable, or -time_step)
  double   stiffness_dt_ = 0; // base_dt_, or less while the material is stiffer than at rest
  double   dt_           = 0; // the step being taken: the stiffness step, or less while points fly
  double   travel_       = 0; // -time_step_travel x dx (0: off)
  bool     travel_auto_  = false;
  double   travel_given_ = 0; // [m] the limit asked for (or chosen), before SetBaseStep
  double   inv_rho_ = 0, eps_ = 0, floor_ = 0.1;
  double   span_ = 0;          // I1bar_limit - 3 of the law (0: no limit)
  bool     plane_strain_ = false, failure_ = false;
  int      dimension_    = 2; // D: dofs a point (the loading's)
  double   psi_ = 0;           // the stiffening indicator at the last search (0: none yet)
  PetscInt next_estimate_ = 0, estimates_ = 0, evaluations_ = 0, kinks_ = 0, startup_evaluations_ = 0;
  PetscInt tip_searches_ = 0, tip_shortenings_ = 0;
  double   estimate_stretch_ = 1; // the applied stretch at the last re-estimate
  PetscInt interval_now_ = 0;     // steps between re-estimates now: the option's, or up to backoff x it while quiet
  double   stretch_now_  = 0;     // the stretch increment that triggers one now (likewise)
  PetscInt by_stiffness_ = 0, by_travel_ = 0;
  double   shortest_dt_ = 0, estimate_wall_ = 0;
  bool     recording_ = false, recorded_ = false;
  // Scratch sized at set-up: no allocation in a step.
  std::vector<char>   held_;
  std::vector<double> v_, seed_, u_rec_, a_rec_, u_probe_, a_probe_, sq_; // (no C33 copy: the probes read the operator's)
  std::vector<double> v_kept_; // the warm start, kept through a crack-tip search that finds nothing (failure only)
  // Krylov: max_iterations + 1 basis vectors of the owned dofs, one after another; the
  // projected matrix (row-major, krylov_cap x krylov_cap) and the Ritz vector's
  // coefficients.
  static constexpr PetscInt krylov_cap = 16;
  PetscInt            krylov_size_ = 0; // basis vectors allocated
  std::vector<double> basis_, projected_, ritz_;
  PetscErrorCode      KrylovReserve(PetscInt vectors);
};

} // namespace bapd
