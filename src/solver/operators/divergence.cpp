// Divergence by runaway energy (include/bapd/solver/operators/divergence.hpp explains the criterion).
#include "bapd/solver/operators/divergence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

RunawayEnergyMonitor::RunawayEnergyMonitor(RunawayCriterion criterion)
    : criterion_(criterion), kinetic_((std::size_t)std::max<PetscInt>(criterion.window, 1)), steps_(kinetic_.size())
{
}

void RunawayEnergyMonitor::Start(double floor, double tick)
{
  started_   = true;
  floor_     = floor;
  tick_      = tick;
  segment_   = -1;
  head_      = 0;
  count_     = 0;
  last_bin_  = -1;
  suspected_ = false;
}

RunawayEnergyMonitor::Verdict RunawayEnergyMonitor::Kinetic(PetscInt step, PetscInt segment, double kinetic, double t)
{
  // The tick of this step: the nearest whole number of full steps (on full steps t is
  // k tick up to round-off: one step a tick).
  bin_ = tick_ > 0 ? std::llround(t / tick_) : (long long)step;
  if (segment != segment_) { // the grip speed changed: growth from here on is measured anew
    segment_ = segment;
    head_ = count_ = 0; // the window holds slots [0, count_) until it is full
    last_bin_      = -1;
  }
  const std::size_t capacity = kinetic_.size();
  if (count_ > 0 && bin_ <= last_bin_) { // the same tick: its slot keeps the smallest KE
    const std::size_t newest = (head_ + capacity - 1) % capacity;
    if (kinetic < kinetic_[newest]) kinetic_[newest] = kinetic, steps_[newest] = step;
  } else {
    kinetic_[head_] = kinetic;
    steps_[head_]   = step;
    head_           = (head_ + 1) % capacity;
    count_          = std::min(count_ + 1, capacity);
    last_bin_       = bin_;
  }
  if (suspected_) {
    if (kinetic >= overflow) return Verdict::diverged;
    // Measured once a tick, and whenever KE doubled since the last measurement: a blow-up
    // on short steps is caught within a doubling of its energy, while a crack's KE,
    // which rises from round-off to a share of the stored energy, costs a few dozen.
    if (bin_ <= total_bin_ && kinetic < 2 * measured_kinetic_) return Verdict::fine;
    measured_kinetic_ = kinetic;
    return Verdict::measure_total;
  }
  if (!(kinetic > floor_)) return Verdict::fine;
  // The smallest KE of the window (the newest value included: never below itself).
  double   low      = kinetic;
  PetscInt low_step = step;
  for (std::size_t k = 0; k < count_; ++k)
    if (kinetic_[k] < low) low = kinetic_[k], low_step = steps_[k];
  if (!(kinetic >= criterion_.growth * low) && kinetic < overflow) return Verdict::fine;
  suspected_       = true;
  suspect_step_    = step;
  suspect_bin_     = bin_;
  total_bin_       = bin_ - 1;
  suspect_kinetic_ = kinetic;
  low_step_        = low_step;
  low_kinetic_     = low;
  first_total_     = -1;
  before_total_    = -1;
  total_step_      = step;
  measured_kinetic_ = kinetic;
  // Energies this large overflow the internal-energy sum: no need to confirm.
  return kinetic >= overflow ? Verdict::diverged : Verdict::measure_total;
}

RunawayEnergyMonitor::Verdict RunawayEnergyMonitor::Total(PetscInt step, double total, double before)
{
  if (!suspected_) return Verdict::fine;
  total_step_ = step;
  total_bin_  = bin_;
  total_      = total;
  if (first_total_ < 0) {
    first_total_ = max_total_ = total;
    // Energy created within one step, beyond the grips' work (which the floor bounds
    // from above: the whole body at grip speed): a blow-up that may not grow further.
    if (before >= 0 && (total >= criterion_.confirm_growth * (before + floor_) || !std::isfinite(total))) {
      before_total_ = before;
      return Verdict::diverged;
    }
    return Verdict::fine;
  }
  if (total >= criterion_.confirm_growth * first_total_ || !std::isfinite(total)) return Verdict::diverged;
  max_total_ = std::max(max_total_, total);
  if (bin_ - suspect_bin_ >= criterion_.confirm_steps) {
    // Energy moved between kinds but was not created (a crack, a vibration): clear the
    // suspicion. Kinetic energy cannot exceed the total one without new work, so the
    // next suspicion needs KE past the total measured here.
    suspected_ = false;
    floor_     = std::max(floor_, max_total_);
    head_ = count_ = 0;
    last_bin_      = -1;
  }
  return Verdict::fine;
}

std::string RunawayEnergyMonitor::Describe() const
{
  char text[512];
  int  length = std::snprintf(text, sizeof text, "the kinetic energy grew from %.3e J (step %" PetscInt_FMT ") to %.3e J (step %" PetscInt_FMT ")",
                              low_kinetic_, low_step_, suspect_kinetic_, suspect_step_);
  if (before_total_ >= 0 && length > 0 && (std::size_t)length < sizeof text)
    std::snprintf(text + length, sizeof text - (std::size_t)length,
                  " and the total (kinetic + internal) energy, which only the grips' work can raise, from %.3e J to %.3e J in one step",
                  before_total_, total_);
  else if (first_total_ >= 0 && length > 0 && (std::size_t)length < sizeof text)
    std::snprintf(text + length, sizeof text - (std::size_t)length,
                  " and the total (kinetic + internal) energy, which only the grips' work can raise, from %.3e J to %.3e J in %" PetscInt_FMT
                  " step(s)",
                  first_total_, total_, total_step_ - suspect_step_);
  return text;
}

namespace {

// Kinetic energy of the whole body moving at the fastest grip speed of the schedule,
// plus a round-off guard (every point moving a millionth of a spacing per step), so
// a body at rest, whose KE is zero or noise, never raises suspicion.
double KineticFloor(const RunawayInputs &in, const Schedule &s, double mass, double dt)
{
  double          max_rate = 0; // |d lambda / dt| over the schedule
  for (std::size_t k = 1; k < s.time.size(); ++k) max_rate = std::max(max_rate, std::fabs((s.stretch[k] - s.stretch[k - 1]) / (s.time[k] - s.time[k - 1])));
  double max_scale = 0;
  for (const LoadSet &set : *in.loads) {
    if (set.x == ComponentLoad::stretch) max_scale = std::max(max_scale, std::fabs(set.x_scale));
    if (set.y == ComponentLoad::stretch) max_scale = std::max(max_scale, std::fabs(set.y_scale));
    if (set.z == ComponentLoad::stretch) max_scale = std::max(max_scale, std::fabs(set.z_scale)); // (3D)
  }
  const double grip_speed = max_scale * max_rate * in.reference_length;
  const double guard      = 1e-6 * in.dx / dt;
  return 0.5 * mass * (grip_speed * grip_speed + guard * guard);
}

} // namespace

PetscErrorCode CheckRunawayEnergy(const RunawayInputs &inputs, RunawayEnergyMonitor &monitor, PetscInt step, double t, std::string *message)
{
  const Layout  &layout = *inputs.layout;
  const PetscInt n      = layout.n_owned;
  MPI_Comm       comm   = inputs.comm;
  const double  *x;
  const double   dt = inputs.dt;

  PetscFunctionBegin;
  message->clear();
  if (!monitor.started()) {
    double mass = 0;
    for (PetscInt i = 0; i < n; ++i) mass += inputs.density * layout.cloud.volume[i];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mass, 1, MPI_DOUBLE, MPI_SUM, comm));
    monitor.Start(KineticFloor(inputs, *inputs.schedule, mass, dt), dt); // a tick: the full step
  }
  // Kinetic energy and the fastest owned point (for the message), one pass. The sum is
  // reproducible: the same bits on every rank and on any number of ranks, so every
  // rank reaches the same verdict at the same step, whatever the layout.
  std::vector<double> &per_point = monitor.scratch();
  per_point.resize((std::size_t)n); // sized once: no allocation in later steps
  PetscCall(VecGetArrayRead(inputs.state, &x));
  const int     D       = layout.dimension; // dofs a point
  const double *v       = x + D * n;
  double        kinetic = 0, fastest = -1;
  PetscInt      fastest_i = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double *vi = v + D * i;
    double        vv = vi[0] * vi[0] + vi[1] * vi[1];
    if (D == 3) vv += vi[2] * vi[2];
    per_point[i] = std::min(0.5 * inputs.density * layout.cloud.volume[i] * vv, RunawayEnergyMonitor::overflow); // finite, whatever the speed
    if (per_point[i] > fastest) fastest = per_point[i], fastest_i = i;
  }
  PetscCall(VecRestoreArrayRead(inputs.state, &x));
  PetscCall(ReproducibleSum(comm, 1, n, per_point.data(), &kinetic));

  const Schedule &s       = *inputs.schedule;
  const PetscInt  segment = (PetscInt)(std::upper_bound(s.time.begin(), s.time.end(), t) - s.time.begin());
  RunawayEnergyMonitor::Verdict verdict = monitor.Kinetic(step, segment, kinetic, t);
  if (verdict == RunawayEnergyMonitor::Verdict::measure_total) {
    double kin, internal, before = -1;
    bool   known = false;
    PetscCall(inputs.energies(&kin, &internal));
    if (inputs.energies_before) {
      double kin_before, internal_before;
      PetscCall(inputs.energies_before(&kin_before, &internal_before, &known));
      if (known) before = kin_before + internal_before;
    }
    verdict = monitor.Total(step, kin + internal, before);
  }
  if (verdict != RunawayEnergyMonitor::Verdict::diverged) PetscFunctionReturn(0);

  // Where: the owned point with the largest kinetic energy, over all ranks.
  struct {
    double value;
    int    rank;
  } mine = {fastest, 0}, best;
  PetscCallMPI(MPI_Comm_rank(comm, &mine.rank));
  PetscCallMPI(MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  double where[4] = {-1, 0, 0, 0}; // natural id, then the D coordinates
  if (best.rank == mine.rank && fastest_i >= 0) {
    where[0] = (double)layout.cloud.natural_id[fastest_i];
    for (int c = 0; c < D; ++c) where[1 + c] = layout.cloud.x[D * fastest_i + c];
  }
  PetscCallMPI(MPI_Bcast(where, 4, MPI_DOUBLE, best.rank, comm));
  // The cause and its fix follow (DivergenceAdvice, from the last good state).
  char position[96];
  if (D == 3) std::snprintf(position, sizeof position, "(%.6g, %.6g, %.6g)", where[1], where[2], where[3]);
  else std::snprintf(position, sizeof position, "(%.6g, %.6g)", where[1], where[2]);
  char text[1024];
  std::snprintf(text, sizeof text, "the run diverged at step %" PetscInt_FMT " (t = %.6e s): %s. Fastest point: %.0f, reference position %s m.",
                step, t, monitor.Describe().c_str(), where[0], position);
  *message = text;
  PetscFunctionReturn(0);
}

namespace {

// A fixed step above this fraction of the stable step of the state 10 to 20 steps
// before the blow-up: the safety factor's margin is spent (the stable step includes
// the 10 % pad of the estimate, so this is 0.86 x the linear limit).
constexpr double      kFixedMargin = 0.9;
constexpr std::size_t kAdviceSize  = 1024; // the advice's text buffer

// The advice when the step was longer than the stable step `stable`; why: the cause's
// detail after "the time step".
void StepTooLong(const DivergenceFacts &f, const char *why, double stable, char *text)
{
  if (f.step_given)
    std::snprintf(text, kAdviceSize,
                  " Cause: the time step%s. dt = %.4e s is %.3g x the stable step %.4e s of the state %s (%.4e s at rest): "
                  "lower -time_step below %.3e s, or leave it to the solver (-time_step 0, -time_step_safety 0.8).",
                  why, f.dt, f.dt / stable, stable, stable == f.stable ? "reached" : "before the blow-up", f.stable_rest, 0.8 * std::min(stable, f.stable_rest));
  else
    std::snprintf(text, kAdviceSize,
                  " Cause: the time step%s. dt = %.4e s is %.3g x the stable step %.4e s of the state %s (%.4e s at rest): "
                  "lower -time_step_safety (now %g) to %.2g or less%s.",
                  why, f.dt, f.dt / stable, stable, stable == f.stable ? "reached" : "before the blow-up", f.stable_rest, f.safety,
                  std::min(0.8, 0.8 * f.safety * std::min(stable, f.stable_rest) / f.dt),
                  f.reestimating ? "" : ", or let the step follow the material (-time_step_reestimate 50)");
}

// The causes named by the step against the stable one before the blow-up, by the
// chain limit or by the bulk modulus; false if none of them applies.
bool StepOrMaterialCause(const DivergenceFacts &f, const char *break_first, char *text)
{
  // A base step above the stable step at rest: the blow-up starts at once (and may
  // shorten the re-estimated step on its way, so the step taken last says less).
  if (std::max(f.dt, f.base) > f.stable_rest)
    std::snprintf(text, kAdviceSize,
                  " Cause: the time step. The base step %.4e s is %.3g x the stable step at rest, %.4e s, so the explicit "
                  "scheme amplifies its fastest mode every step: %s.",
                  std::max(f.dt, f.base), std::max(f.dt, f.base) / f.stable_rest, f.stable_rest,
                  f.step_given ? "lower -time_step, or leave it to the solver (-time_step 0, -time_step_safety 0.8)"
                               : "lower -time_step_safety to 0.8 (the default) or less");
  // With the step fixed at rest, a step already above the stable one of the state 10
  // to 20 steps before the blow-up is a cause that letting the step follow cures, even
  // near the limit (the map's Jm = 3 plate, energy-consistent, slow: chain reach 0.82
  // there, and the re-estimated run goes to the end); where the limit itself is reached,
  // the re-estimated run then names it. So is a step within kFixedMargin of it: the
  // margin the safety factor left at rest is spent while the material goes on
  // stiffening (the map's plane strain K = 1e5 mu plate, energy-consistent: 0.96 x the
  // stable step 13 steps before the blow-up, which was called "a bulk modulus too stiff
  // ... whatever the step", yet safety 0.5 and the re-estimated step both run it).
  else if (!f.reestimating && f.stable_earlier > 0 && f.dt > kFixedMargin * f.stable_earlier) {
    char why[240];
    if (f.dt > f.stable_earlier)
      std::snprintf(why, sizeof why, " (the material stiffened; the step was fixed at rest; measured %" PetscInt_FMT " steps before the failure)",
                    f.earlier_steps);
    else
      std::snprintf(why, sizeof why,
                    " (the material stiffened; the step was fixed at rest and had spent the margin of the safety factor %" PetscInt_FMT
                    " steps before the failure, the stiffening still going on)",
                    f.earlier_steps);
    StepTooLong(f, why, f.stable_earlier, text);
  }
  // Wrecked, but near the limit 10 to 20 steps before: there the reach still had that
  // many steps to grow, a few hundredths a step at a fast ramp's rate (the Jm = 3 plate
  // on a 2 mm grid: 0.80 18 steps before the blow-up at stretch 1.90; on a 1 mm grid,
  // with the estimates sharp, its corner bonds reach the limit itself at 1.99), hence
  // 0.75 here against 0.8 for the state reached.
  else if (f.chain_reach > 1.05 && f.chain_reach_earlier >= 0.75 && f.chain_reach_earlier <= 1.05)
    std::snprintf(text, kAdviceSize,
                  " Cause: %s. %" PetscInt_FMT " steps before the failure bonds had reached I1bar - 3 = %.3g x its value at the limit "
                  "(largest bond stretch %.3g, applied stretch %.4g), where the material stiffens without bound and no time step "
                  "keeps up: raise %s (now %g), or end the load below stretch %.4g, %s.",
                  f.limit, f.earlier_steps, f.chain_reach_earlier, f.bond_stretch_earlier, f.applied_stretch_earlier, f.limit_option,
                  f.limit_value, f.applied_stretch_earlier, break_first);
  // Beyond 1.05: a state the blow-up already wrecked. Within, but less than half-way 10
  // to 20 steps before: wrecked too, within range by chance (the bond-only 2 dx plate
  // of the map reads 0.99 at stretch 1.17 once its last good state's C33 is solved
  // again from a cold start, where no stiffening preceded the blow-up).
  else if (f.chain_reach >= 0.8 && f.chain_reach <= 1.05 && !(f.stable_earlier > 0 && f.chain_reach_earlier < 0.5))
    std::snprintf(text, kAdviceSize,
                  " Cause: %s. Bonds reached I1bar - 3 = %.3g x its value at the limit (largest bond stretch %.3g, applied stretch %.4g), "
                  "where the material stiffens without bound (its stable step fell to %.3g x the one at rest) and no time step "
                  "keeps up: raise %s (now %g), or end the load below stretch %.4g, %s.",
                  f.limit, f.chain_reach, f.bond_stretch, f.applied_stretch, f.stable / f.stable_rest, f.limit_option,
                  f.limit_value, f.applied_stretch, break_first);
  else if (f.plane_strain && f.bulk_ratio >= 1000)
    std::snprintf(text, kAdviceSize,
                  " Cause: a bulk modulus too stiff for plane strain. The step (%.3g x the stable one) is not the problem: with "
                  "-material_bulk_ratio %g (K / mu) the %splane-strain body locks volumetrically and is unstable whatever the "
                  "step (docs/stability.md, section 1): lower -material_bulk_ratio to 100%s.",
                  f.dt / f.stable, f.bulk_ratio, f.bond_only ? "bond-only " : "", f.bond_only ? ", or use -force_form energy_consistent" : "");
  else if (f.chain_reach > 1.05 && f.limit_value > 0 && f.stiffening >= 4) // a wrecked state, but the run saw the stiffening
    std::snprintf(text, kAdviceSize,
                  " Cause: %s. The material stiffened to %.3g x its stiffness at rest as bonds neared the "
                  "limit (applied stretch %.4g), and the state broke down (bond stretch %.3g): raise %s (now %g), "
                  "or end the load below stretch %.4g, %s.",
                  f.limit, f.stiffening, f.applied_stretch, f.bond_stretch, f.limit_option, f.limit_value, f.applied_stretch, break_first);
  else return false;
  return true;
}

// The causes left when the step before the blow-up and the material look sound: the
// bond-only form, the stiffening outrunning the step, or none found.
void FormOrStepCause(const DivergenceFacts &f, char *text)
{
  // The bond-only form below 2.5 dx, with the step sound before the blow-up (the
  // branches above): at 2 dx scene 1's rest state has a real negative eigenvalue
  // (docs/stability.md section 1), at 1.5 dx it flutters; the map's 2 dx plate stops
  // at stretch 1.17 with the step fixed or re-estimated, at safety 0.2, and with
  // damping 200 or 1000 alike (it was called "the time step" and "flutter"), and the
  // energy-consistent form runs it. The wrecked state reached says nothing then.
  if (f.bond_only && f.horizon_factor < 2.5)
    std::snprintf(text, kAdviceSize,
                  " Cause: the bond-only force form at -horizon_factor %g (below 2.5). The step was below the stable one "
                  "%s, but with so few bonds per family the bond-only form's rest state can itself be unstable (a real "
                  "negative eigenvalue, docs/stability.md section 1), which no time step and no damping cures: use -force_form "
                  "energy_consistent, or -horizon_factor 2.5 to 4.",
                  f.horizon_factor, f.stable_earlier > 0 ? "10 to 20 steps before the failure" : "at rest");
  else if (!f.reestimating && f.dt > f.stable) StepTooLong(f, " (the material stiffened; the step was fixed at rest)", f.stable, text);
  else if (f.stable_earlier > 0 && f.dt > f.stable_earlier) {
    // The last good state is already a wreck (its sharp estimate finds the wreck's
    // negative eigenvalue, not the stiffening); the state before the blow-up shows it.
    char why[200];
    std::snprintf(why, sizeof why, " (the material stiffened; %s; measured %" PetscInt_FMT " steps before the failure)",
                  f.reestimating ? "faster than the re-estimate followed" : "the step was fixed at rest", f.earlier_steps);
    StepTooLong(f, why, f.stable_earlier, text);
  }
  // Flutter grows at free edges whatever the material does; a state that was half-way
  // to the chain limit before the blow-up (Gent stiffness over 4 x its value at rest)
  // points at the stiffening instead: the Jm = 3 plate (2 mm, fast route) was called
  // flutter at stretch 1.89 while its estimate lagged the hole's stiffening.
  else if (f.bond_only && f.damping < 100 && f.chain_reach_earlier < 0.5)
    std::snprintf(text, kAdviceSize,
                  " Cause: flutter of the bond-only force form. The step was below the stable one (dt = %.3g x the stable "
                  "step at rest), but the bond-only form's stiffness is not symmetric at free edges and its motion grows whatever the "
                  "step (docs/stability.md, section 1): raise -damping (now %g 1/s; 200 covers the pure shear sheet) or use "
                  "-force_form energy_consistent, which has no flutter%s.",
                  f.dt / f.stable_rest, f.damping,
                  f.reestimating ? "" : "; with the step fixed at rest, also let it follow the material (-time_step_reestimate 50)");
  // A re-estimated step above the stable step of the state reached, unless the state
  // 10 to 20 steps before still had the safety factor's margin: then the stiffness is
  // the blow-up's own (pure shear, bond-only, to 7: 0.8 x the stable step 13 steps
  // before the inversion at a free corner, the chain reach there 0.26 -> 0.45 within
  // those steps; the sharper Krylov estimate of the state reached read 1.44 x and
  // called it the time step, which the energy-consistent form, not a shorter step, cures).
  else if (f.dt > f.stable && !(f.reestimating && f.stable_earlier > 0 && f.dt <= kFixedMargin * f.stable_earlier))
    StepTooLong(f, " (the material stiffened faster than the re-estimate followed)", f.stable, text);
  else if (f.bond_only) // the step, the material and the damping are sound: what is left is the form itself
    std::snprintf(text, kAdviceSize,
                  " Cause: an instability of the bond-only force form. The step (%.3g x the stable one of the state reached), "
                  "the material (%.3g x its stiffness at rest) and the damping (%g 1/s) look sound, but the bond-only form's "
                  "stiffness is not symmetric, and at corners next to the grips its motion can grow whatever the step and the "
                  "damping (pure shear with the grips outside: stretch 4.7 to 6.6, docs/stability.md section 8): use "
                  "-force_form energy_consistent, which has no such mode.",
                  f.dt / f.stable, f.stiffening, f.damping);
  // A load that compresses (the tiny sheet to stretch 0.1 in 0.01 s, faster than its
  // shear waves cross it) inverts bonds at the grips with the step sound: lowering the
  // safety failed the same way. Points then pass through each other (no contact).
  else if (f.applied_stretch < 1)
    std::snprintf(text, kAdviceSize,
                  " Cause: the compression (applied stretch %.4g). With the step (%.3g x the stable one of the state reached) and "
                  "the material sound, the sheet squeezed this far or this fast folds near the grips and points pass through their "
                  "neighbours (bapd models no contact); a shorter step does not help: end the load above stretch %.4g, or apply it "
                  "more slowly (a later time in -load_schedule).",
                  f.applied_stretch, f.dt / f.stable, f.applied_stretch);
  else
    std::snprintf(text, kAdviceSize,
                  " Cause: not found. The step (%.3g x the stable one of the state reached) and the material look sound: lower "
                  "-time_step_safety (now %g), and see docs/stability.md.",
                  f.dt / f.stable, f.safety);
}

} // namespace

std::string DivergenceAdvice(const DivergenceFacts &f)
{
  char text[kAdviceSize];
  // The chain limit's third fix: bonds that break before they reach it. With failure
  // on, "enable failure" would send the user to an option already set.
  char break_first[160];
  if (f.critical_stretch > 0)
    std::snprintf(break_first, sizeof break_first, "or lower -failure_critical_stretch (now %g) so that such bonds break first", f.critical_stretch);
  else std::snprintf(break_first, sizeof break_first, "or enable failure (-failure_critical_stretch) so that such bonds break");
  if (!StepOrMaterialCause(f, break_first, text)) FormOrStepCause(f, text);
  return text;
}

} // namespace bapd
