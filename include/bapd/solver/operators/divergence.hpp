#pragma once
// Divergence by runaway energy: the signature of an explicit time step above the
// stability limit, caught early and without false alarms (docs/options.md,
// "Divergence").
//
// Velocity Verlet (and every explicit scheme) multiplies the amplitude of a mode whose
// frequency exceeds 2/dt by a fixed factor |g| > 1 every step, so its energy grows
// geometrically: from round-off to NaN within tens of steps. Before the NaN (and,
// with failure enabled, before the bonds break and the body shatters, which NaN and
// inverted-bond checks never see) the kinetic energy KE runs away. A legitimate run
// can raise KE quickly too (a crack running converts stored strain energy into motion,
// a vibration exchanges the two), but it cannot create energy: the total energy
// KE + internal energy grows only by the work of the grips. Hence two stages:
//
//  1. Suspicion, every step, cheap (one sum over the owned points and its reduction):
//     KE >= 1000 x its smallest value over the last 50 ticks of the current loading
//     segment (a schedule knot changes the grip speed, and so KE: the window restarts
//     there), and KE above a floor: the kinetic energy of the whole body moving at
//     the fastest grip speed of the schedule, or the highest KE already cleared.
//  2. Confirmation, only while suspected (one internal-energy evaluation per tick):
//     the total energy at the suspicion is ten times that of the step before it plus
//     the floor (when that state is kept, -checkpoint_on_error: a blow-up that created
//     its energy in one step and then stopped growing, a body shattered in one step,
//     is caught here; it would pass the next test), or the total energy grows tenfold
//     within the next 10 ticks. Otherwise the
//     suspicion is cleared, and the largest total energy measured becomes the floor:
//     KE cannot exceed it unless the grips do more work (or the run blows up).
//
// A tick is the full time step (the step at the start of the run): growth is measured
// over simulated time, not over steps. While the step is shortened (a running crack's
// travel limit cut it by up to 1e5 in the notched scene), a window of 50 steps spans a
// tiny fraction of a tick, and a blow-up that multiplies KE by 2e4 within one tick of
// time (the bond-only form fluttering at the running tip: KE from 9e-3 to 223 J over
// 3300 steps of 1e-7 s, with 0.03 J stored) grows by only a few per cent a step and was
// never suspected: it ran to the end with exit 0 and every bond broken. On full steps
// a tick is a step. The steps of one tick share one window slot (its
// smallest KE); while suspected, the total energy is measured once a tick and whenever
// KE doubled since it was last measured.
#include <petscvec.h>

#include <functional>
#include <string>
#include <vector>

#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/input/scene_loading.hpp"
#include "bapd/solver/input/scene_schedule.hpp"

namespace bapd {

struct RunawayCriterion {
  PetscInt window         = 50;  // ticks over which the growth of KE is measured
  double   growth         = 1e3; // KE growth over the window that raises suspicion
  PetscInt confirm_steps  = 10;  // ticks within which the total energy must grow...
  double   confirm_growth = 10;  // ...by this factor to confirm the divergence
};

// The decision, plain numbers in and out (no MPI: every rank feeds it the same
// reduced values, so every rank reaches the same verdict at the same step).
class RunawayEnergyMonitor {
public:
  enum class Verdict { fine, measure_total, diverged };
  static constexpr double overflow = 1e250; // [J] a kinetic energy past any physics: diverged

  explicit RunawayEnergyMonitor(RunawayCriterion criterion = {});
  // floor: the kinetic energy of the whole body moving at the fastest grip speed [J];
  // tick: the full time step [s] (0: a tick is a step).
  void Start(double floor, double tick = 0);
  bool started() const { return started_; }
  // The kinetic energy after `step`, at time t (read with a tick); `segment` numbers the
  // loading segment (schedule knots passed). measure_total: call Total with the total
  // energy of this step.
  Verdict Kinetic(PetscInt step, PetscInt segment, double kinetic, double t = 0);
  // before: the total energy of the step before (< 0: not known).
  Verdict Total(PetscInt step, double total, double before = -1);
  // What was seen, for the message: "the kinetic energy grew from ... to ...".
  std::string Describe() const;
  // Room for one value per owned point, kept between steps (CheckRunawayEnergy).
  std::vector<double> &scratch() { return scratch_; }

private:
  RunawayCriterion    criterion_;
  bool                started_ = false;
  double              floor_   = 0;
  PetscInt            segment_ = -1;
  double              tick_    = 0;
  std::vector<double> kinetic_; // ring buffer: the smallest KE of each of the last `window` ticks
  std::vector<PetscInt> steps_;   // ...and the step it was measured at
  std::size_t         head_ = 0, count_ = 0;
  long long           bin_ = 0, last_bin_ = -1; // the tick of this step, of the newest slot
  // The suspicion being confirmed.
  bool      suspected_ = false;
  long long suspect_bin_ = 0, total_bin_ = -1; // the tick of the suspicion, of the last total measured
  double    measured_kinetic_ = 0;             // KE when the total was last measured
  PetscInt  suspect_step_ = 0, low_step_ = 0, total_step_ = 0;
  double   suspect_kinetic_ = 0, low_kinetic_ = 0, first_total_ = -1, total_ = 0, max_total_ = 0;
  double   before_total_ = -1; // the total energy of the step before the suspicion, when it decided

  std::vector<double> scratch_;
};

// The cause of a divergence, as the solver sees it at the last good state
// (docs/stability.md section 8), and the fix the message names. Plain numbers
// in, the sentence out (no MPI: every rank has the same reduced values).
struct DivergenceFacts {
  double dt           = 0;     // the step that was taken [s]
  double base         = 0;     // the base step (safety x the step at rest, or -time_step) [s]
  double stable       = 0;     // stable step of the last good state (a sharp power iteration) [s]
  double stable_rest  = 0;     // stable step at rest [s]
  bool   step_given   = false; // -time_step (or -ts_dt) set the base step, not the safety factor
  double safety       = 0.8;   // -time_step_safety
  double chain_reach  = 0;     // max over bonds of (I1bar - 3) / (I1bar_limit - 3) (Gent: / Jm; 0 for laws without a limit)
  const char *limit        = "the Gent chain limit (I1bar - 3 >= Jm)"; // the law's (law.hpp: limit)
  const char *limit_option = "-material_Jm";                          // the option that moves it
  double      limit_value  = 0;                                       // its value (0: no limit)
  double bond_stretch = 1;     // the largest principal stretch of a bond's F there [-]
  double applied_stretch = 1;  // the schedule's stretch at that time [-]
  bool   plane_strain = false, bond_only = true;
  double bulk_ratio   = 0;     // K / mu
  double critical_stretch = 0; // -failure_critical_stretch with failure on (0: off)
  double damping      = 0;     // [1/s] (the floor, with -relaxation adaptive)
  bool   reestimating = true;  // -time_step_reestimate > 0: the step followed the material
  double horizon_factor = 3.015;
  double stiffening   = 1;     // the largest lambda_max of the run's re-estimates over the one at rest
  double stable_earlier = 0;   // stable step of a state 10 to 20 steps before the last good one [s] (0: none)
  PetscInt earlier_steps = 0;  // how many steps before the last good state that state is
  double chain_reach_earlier = 0, bond_stretch_earlier = 1, applied_stretch_earlier = 1; // ...and its chain reach
};
// In this order (the first that fits): a step above the stable step at rest ->
// -time_step_safety (or -time_step); a step fixed at rest above 0.9 x the stable step
// of the state 10 to 20 steps before the failure (the safety factor's margin spent
// while the material stiffens) -> -time_step_safety or -time_step_reestimate; the chain limit (0.8 <= reach <= 1.05: the Gent
// stiffness mu Jm / (Jm + 3 - I1bar) is 5 x its rest value and unbounded beyond; a
// larger reach is a state the blow-up already wrecked) -> the law's limit option
// (-material_Jm; Arruda-Boyce: -material_lambda_m) and the stretch (also when the last
// good state is wrecked but the state 10 to 20 steps before it was at 0.75 or more: the Jm = 3
// plate on a 2 mm grid); plane strain with K >= 1000 mu (a real negative eigenvalue at rest,
// docs/stability.md section 1) -> -material_bulk_ratio; a fixed step above the stable
// step of the state reached, or of the state 10 to 20 steps earlier (a blow-up wrecks
// the last good state: plane strain with K = 10 mu on the fixed step showed only the
// wreck's negative eigenvalue there) -> -time_step_safety or -time_step_reestimate (a state
// already wrecked, reach > 1.05, in a run whose lambda_max rose 4 x: the chain limit); the
// bond-only form with less damping than its free edges need (100 1/s, section 1), in a
// state less than half-way to the law's limit 10 to 20 steps before (closer, the
// stiffening is the cause) -> -damping or -force_form energy_consistent (before it:
// the bond-only form below 2.5 dx, whose rest state can be unstable, section 1 ->
// -force_form energy_consistent or -horizon_factor); a
// re-estimated step above the state's -> -time_step_safety; with everything else sound,
// the bond-only form's own instability (the corners next to outside grips in pure
// shear, stretch 4.7 to 6.6) -> -force_form energy_consistent. The order matters: a chain-limited state has a tiny stable
// step too, and a fluttering one looks stiff once the flutter has grown, but neither
// is cured by a shorter step.
std::string DivergenceAdvice(const DivergenceFacts &facts);

// What the post-step check reads, handed to it by the driver.
struct RunawayInputs {
  MPI_Comm        comm     = MPI_COMM_NULL;
  double                      density          = 0;       // [kg/m^3]
  double                      dx               = 0;       // the spacing [m]: the kinetic floor's round-off guard
  const std::vector<LoadSet> *loads            = nullptr; // the stretch grips' scales: the fastest grip speed
  double                      reference_length = 0;       // [m]: u = scale (lambda - 1) reference_length
  const Schedule             *schedule         = nullptr; // as it stands (static holds move it: loading.hpp)
  const Layout   *layout   = nullptr;
  Vec             state    = nullptr; // [u, v] of the owned points
  double          dt = 0, stable_dt = 0;
  // Kinetic and internal energy of the state, reproducible sums (collective).
  std::function<PetscErrorCode(double *kinetic, double *internal)> energies;
  // The same for the state after the previous step, if the driver keeps it (*known).
  std::function<PetscErrorCode(double *kinetic, double *internal, bool *known)> energies_before;
};

// The post-step check: sums KE over the owned points (a reproducible sum: the same
// bits on every rank and any rank count), feeds the monitor, measures the total
// energy while suspected (inputs.energies) and, on divergence, fills *message with
// the step, the time, the energies, the point moving fastest and the fix. Collective.
PetscErrorCode CheckRunawayEnergy(const RunawayInputs &inputs, RunawayEnergyMonitor &monitor, PetscInt step, double t,
                                  std::string *message);

} // namespace bapd
