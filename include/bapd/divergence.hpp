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
//     KE >= 1000 x its smallest value over the last 50 steps of the current loading
//     segment (a schedule knot changes the grip speed, and so KE: the window restarts
//     there), and KE above a floor: the kinetic energy of the whole body moving at
//     the fastest grip speed of the schedule, or the highest KE already cleared.
//  2. Confirmation, only while suspected (one internal-energy evaluation per step):
//     the total energy grows tenfold within the next 10 steps. Otherwise the
//     suspicion is cleared, and the largest total energy measured becomes the floor:
//     KE cannot exceed it unless the grips do more work (or the run blows up).
#include <petscvec.h>

#include <functional>
#include <string>
#include <vector>

#include "bapd/layout.hpp"
#include "bapd/scene.hpp"

namespace bapd {

struct RunawayCriterion {
  PetscInt window         = 50;  // steps over which the growth of KE is measured
  double   growth         = 1e3; // KE growth over the window that raises suspicion
  PetscInt confirm_steps  = 10;  // steps within which the total energy must grow...
  double   confirm_growth = 10;  // ...by this factor to confirm the divergence
};

// The decision, plain numbers in and out (no MPI: every rank feeds it the same
// reduced values, so every rank reaches the same verdict at the same step).
class RunawayEnergyMonitor {
public:
  enum class Verdict { fine, measure_total, diverged };
  static constexpr double overflow = 1e250; // [J] a kinetic energy past any physics: diverged

  explicit RunawayEnergyMonitor(RunawayCriterion criterion = {});
  // floor: the kinetic energy of the whole body moving at the fastest grip speed [J].
  void Start(double floor);
  bool started() const { return started_; }
  // The kinetic energy after `step`; `segment` numbers the loading segment (schedule
  // knots passed). measure_total: call Total with the total energy of this step.
  Verdict Kinetic(PetscInt step, PetscInt segment, double kinetic);
  Verdict Total(PetscInt step, double total);
  // What was seen, for the message: "the kinetic energy grew from ... to ...".
  std::string Describe() const;
  // Room for one value per owned point, kept between steps (CheckRunawayEnergy).
  std::vector<double> &scratch() { return scratch_; }

private:
  RunawayCriterion    criterion_;
  bool                started_ = false;
  double              floor_   = 0;
  PetscInt            segment_ = -1;
  std::vector<double> kinetic_; // ring buffer of the last `window` values
  std::vector<PetscInt> steps_;
  std::size_t         head_ = 0, count_ = 0;
  // The suspicion being confirmed.
  bool     suspected_ = false;
  PetscInt suspect_step_ = 0, low_step_ = 0, total_step_ = 0;
  double   suspect_kinetic_ = 0, low_kinetic_ = 0, first_total_ = -1, total_ = 0, max_total_ = 0;
  std::vector<double> scratch_;
};

// What the post-step check reads, handed to it by the driver.
struct RunawayInputs {
  MPI_Comm        comm     = MPI_COMM_NULL;
  const Scene    *scene    = nullptr; // density, loads, failure options
  const Schedule *schedule = nullptr; // as it stands (static holds move it: loading.hpp)
  const Layout   *layout   = nullptr;
  Vec             state    = nullptr; // [u, v] of the owned points
  double          dt = 0, stable_dt = 0;
  // Kinetic and internal energy of the state, reproducible sums (collective).
  std::function<PetscErrorCode(double *kinetic, double *internal)> energies;
};

// The post-step check: sums KE over the owned points (a reproducible sum: the same
// bits on every rank and any rank count), feeds the monitor, measures the total
// energy while suspected (inputs.energies) and, on divergence, fills *message with
// the step, the time, the energies, the point moving fastest and the fix. Collective.
PetscErrorCode CheckRunawayEnergy(const RunawayInputs &inputs, RunawayEnergyMonitor &monitor, PetscInt step, double t,
                                  std::string *message);

} // namespace bapd
