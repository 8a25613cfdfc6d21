// Bonds breaking in the static solver (static_solver.hpp; docs/options_run.md "Static
// solver"): after a load step converges, the breaking pass the dynamic route runs after
// a time step (Failure::Break, and the fracture-energy cascade of docs/method.md 5.2),
// at the static state; then Newton again at the same load, from that state with the
// bonds broken, and the criterion again, until no bond breaks.
#include "bapd/solver/driver/static_solver.hpp"

#include <algorithm>

namespace bapd {

// The passes at the owned displacements u_owned (the grips held): the criterion's, then
// the cascade's (SimulationD::BreakFurther, -failure_passes). No bond whose law failed
// is handed to Break: a static state has none (Evaluate rejects such a state). The bond
// state before is kept in intact_before_ (UndoBreaking, ReleasedEnergy). Collective.
template <int D> PetscErrorCode StaticSolver<D>::BreakAtState(const double *u_owned, bool *broke)
{
  SimulationD<D> &s = sim_;

  PetscFunctionBegin;
  PetscCall(s.force_.UpdatePositions(u_owned));
  if (s.failure_.by_energy()) s.force_.BondEnergies(s.failure_.bond_energies());
  std::copy(s.bond_state_.intact.begin(), s.bond_state_.intact.end(), s.intact_before_.begin());
  no_failed_.clear();
  PetscCall(s.failure_.Break(s.force_.positions(), 0.0, no_failed_, s.bond_state_, s.geometry_));
  PetscCall(s.BreakFurther(broke));
  PetscFunctionReturn(0);
}

// Every local copy of the masks back as before the passes (the owners' and the ghosts'
// alike, so every rank is as it was), and the geometry of the points they touched.
template <int D> PetscErrorCode StaticSolver<D>::UndoBreaking()
{
  SimulationD<D> &s = sim_;

  PetscFunctionBegin;
  std::copy(s.intact_before_.begin(), s.intact_before_.end(), s.bond_state_.intact.begin());
  if (!s.failure_.touched().empty())
    nd::compute_bond_geometry<D>(s.layout_.cloud, s.families_, s.bond_state_, s.geometry_, s.failure_.touched());
  PetscFunctionReturn(0);
}

// The energy the broken bonds held at the state they broke in (exact, ReleasedEnergy):
// history.csv's fracture_dissipation_J.
template <int D> PetscErrorCode StaticSolver<D>::KeepBreaking()
{
  double released;

  PetscFunctionBegin;
  PetscCall(sim_.ReleasedEnergy(true, &released));
  sim_.budget_.Release(released);
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::BreakAt(Vec U, PetscInt *broken)
{
  PetscInt before, after;
  bool     broke;

  PetscFunctionBegin;
  PetscCall(CopyHeld(U));
  PetscCall(sim_.BrokenBondCount(&before));
  PetscCall(BreakAtState(u_scratch_.data(), &broke));
  PetscCall(sim_.BrokenBondCount(&after));
  *broken = after - before;
  PetscFunctionReturn(0);
}

// The onset: until bonds have broken once, a converged load step whose state meets the
// criterion is taken back and its width halved (the load step does not grow meanwhile),
// until it is at most -static_onset_tolerance (lambda - 1) wide (or
// -static_stretch_step_min): the first break is placed that closely in stretch, however
// far past the criterion the first load step went. Then the load step's history row
// (the static state before any bond breaks), the breaking and the re-equilibrations.
template <int D> PetscErrorCode StaticSolver<D>::AfterLoadStep(double t_before, PetscInt iterations, bool *retry, bool *stable)
{
  const StaticOptions &o       = sim_.scene_.run.static_options;
  const bool           failure = sim_.scene_.failure.enabled;
  const double        *u;
  bool                 broke = false, check = failure;

  PetscFunctionBegin;
  *retry = false, *stable = true;
  crack_grew_ = false;
  if (failure && onset_stretch_ == 0) {
    PetscCall(VecGetArrayRead(u_, &u));
    PetscCall(BreakAtState(u, &broke));
    PetscCall(VecRestoreArrayRead(u_, &u));
    if (!broke) check = false; // (nothing breaks at this state: no second pass)
    else {
      PetscCall(UndoBreaking());
      const double from = sim_.loading_.stretch_at(t_before), to = sim_.loading_.stretch_at(t_), width = to - from;
      if (width > std::max(o.onset_tolerance * (to - 1.0), o.stretch_step_min)) {
        PetscCall(PetscPrintf(sim_.comm_, "Bonds break between stretch %.5f and %.5f: the load step is taken back and halved\n", from, to));
        PetscCall(VecCopy(u_last_, u_));
        sim_.force_.warm_start() = c33_last_;
        t_                       = t_before;
        --load_steps_;
        secant_       = false;
        step_         = 0.5 * width;
        onset_search_ = true;
        *retry        = true;
        PetscFunctionReturn(0);
      }
      onset_stretch_ = to, onset_width_ = width, onset_search_ = false;
    }
  }
  PetscCall(CopyToState());
  PetscCall(sim_.WriteHistoryRow(Solves(), t_, false));
  PetscCall(PetscPrintf(sim_.comm_, "Load step %" PetscInt_FMT ": stretch %.5f, %" PetscInt_FMT " Newton iterations, |R| %.3e N, |reactions| %.3e N\n",
                        load_steps_, sim_.loading_.stretch_at(t_), iterations, last_fnorm_, reaction_norm_));
  if (!check) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(u_, &u));
  PetscCall(BreakAtState(u, &broke));
  PetscCall(VecRestoreArrayRead(u_, &u));
  if (!broke) PetscFunctionReturn(0);
  crack_grew_ = true;
  PetscCall(KeepBreaking());
  secant_ = false; // a secant through this load step would extrapolate the crack's jump: the tangent predicts the next
  PetscCall(Reequilibrate(stable));
  PetscFunctionReturn(0);
}

// Newton at the load of t_ from the state the breaking left (its tangent fresh, with
// the bonds broken), a history row, and the criterion at the new state, until no bond
// breaks: the crack grows at this load as far as the static states let it. Each pass
// breaks at least one bond, so the passes end. A Newton solve that does not converge
// (the crack runs unstably at this load: no static state holds the sheet with it) ends
// the run with its message (Run): the state is the last static one, its bonds broken.
template <int D> PetscErrorCode StaticSolver<D>::Reequilibrate(bool *stable)
{
  bool broke = true;

  PetscFunctionBegin;
  *stable = true;
  while (broke) {
    PetscBool converged;
    PetscInt  its, broken;
    PetscCall(VecCopy(u_, u_last_));
    c33_last_ = sim_.force_.warm_start();
    t_target_ = t_;
    PetscCall(Newton(&converged, &its));
    PetscCall(sim_.BrokenBondCount(&broken));
    if (!converged) {
      PetscCall(VecCopy(u_last_, u_));
      sim_.force_.warm_start() = c33_last_;
      unstable_bonds_          = broken;
      *stable                  = false;
      PetscFunctionReturn(0);
    }
    double *u;
    PetscCall(VecGetArray(u_, &u));
    HoldGrips(t_, u);
    PetscCall(VecRestoreArray(u_, &u));
    ++reequilibrations_;
    PetscCall(CopyToState());
    PetscCall(sim_.WriteHistoryRow(Solves(), t_, false));
    PetscCall(PetscPrintf(sim_.comm_, "Re-equilibrated at stretch %.5f: %" PetscInt_FMT " bonds broken, %" PetscInt_FMT " Newton iterations, |reactions| %.3e N\n",
                          sim_.loading_.stretch_at(t_), broken, its, reaction_norm_));
    const double *state;
    PetscCall(VecGetArrayRead(u_, &state));
    PetscCall(BreakAtState(state, &broke));
    PetscCall(VecRestoreArrayRead(u_, &state));
    if (broke) PetscCall(KeepBreaking());
  }
  PetscFunctionReturn(0);
}

template PetscErrorCode StaticSolver<2>::AfterLoadStep(double, PetscInt, bool *, bool *);
template PetscErrorCode StaticSolver<3>::AfterLoadStep(double, PetscInt, bool *, bool *);
template PetscErrorCode StaticSolver<2>::BreakAt(Vec, PetscInt *);
template PetscErrorCode StaticSolver<3>::BreakAt(Vec, PetscInt *);

} // namespace bapd
