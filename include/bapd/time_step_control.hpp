#pragma once
// Time-step control: the stable step of the linearised system (power iteration on
// the force operator), the step in use, and its shortening while points fly
// (-time_step_travel, docs/stability.md section 5). SetBaseStep is where a new base
// step enters during a run (the -ts_dt override at set-up today; a re-estimate of
// the stable step later).
#include <petscts.h>

#include <vector>

#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/force_operator.hpp"
#include "bapd/layout.hpp"
#include "bapd/loading.hpp"
#include "bapd/scene.hpp"

namespace bapd {

class TimeStepControl {
public:
  // Power iteration for lambda_max of M^{-1} K at the reference state, then the step
  // -time_step or -time_step_safety x stable. Leaves the operator as it was (the
  // iteration carries its own warm starts). Collective; prints the steps.
  PetscErrorCode EstimateStable(MPI_Comm comm, const Scene &scene, const Layout &layout, const Loading &loading,
                                ForceOperator &force);
  // A new base step (and step in use); the TS takes it with the next step.
  void SetBaseStep(double dt) { dt_ = base_dt_ = dt; }
  // After a step: shortens the next one so that no bonded point travels more than
  // -time_step_travel dx (v: owned velocities, 2 per point). Collective.
  PetscErrorCode AdaptToTravel(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state,
                               const double *v, TS ts);
  // Restart: a step that -time_step_travel shortened goes on as it was.
  PetscErrorCode ContinueShortened(double dt, TS ts);

  double   stable() const { return stable_dt_; }
  double   base() const { return base_dt_; }
  double   current() const { return dt_; }
  PetscInt shortened_steps() const { return shortened_steps_; }
  double   shortest() const { return shortest_dt_; }

private:
  double   stable_dt_ = 0;
  double   base_dt_   = 0; // the step chosen at setup (safety x stable, or -time_step)
  double   dt_        = 0; // the step being taken: base_dt_, or less while points fly
  double   travel_    = 0; // -time_step_travel x dx (0: off)
  PetscInt shortened_steps_ = 0; // steps taken shorter than base_dt_
  double   shortest_dt_     = 0; // the shortest of them
};

} // namespace bapd
