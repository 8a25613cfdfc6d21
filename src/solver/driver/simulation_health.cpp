// The health checks that stop a run that diverged: NaN, inverted bonds, the Gent
// limit without failure, and runaway energy (divergence.hpp).
#include "bapd/solver/driver/simulation.hpp"

#include <cmath>
#include <cstdio>

#include "bapd/core/materials/law_registry.hpp"

namespace bapd {

// Stops every rank together on NaN, an inverted bond or the Gent limit without failure.
template <int D> PetscErrorCode SimulationD<D>::CheckHealth(PetscInt step, double t, PetscBool *diverged)
{
  const double *x;
  const PetscInt n = 2 * D * layout_.n_owned; // u and v

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X_, &x));
  PetscInt worst = -1;
  for (PetscInt k = 0; k < n; ++k)
    if (!std::isfinite(x[k])) {
      worst = (k % (D * layout_.n_owned)) / D;
      break;
    }
  PetscCall(VecRestoreArrayRead(X_, &x));
  // With failure enabled, a bond whose model fails (inverted or at the chain limit)
  // breaks (Failure::Break, failure.hpp); without it, the run cannot go on.
  const KernelStats &stats = force_.stats();
  int flags[3] = {worst >= 0, (int)stats.inverted, (int)stats.chain_limit};
  int global[3];
  PetscCallMPI(MPI_Allreduce(flags, global, 3, MPI_INT, MPI_SUM, comm_));
  // Where: the first bad owned point (NaN) or the first failed bond's point, reported
  // by the lowest rank that has one.
  double where[4] = {-1, 0, 0, 0}; // natural id, reference position
  const std::size_t bad = worst >= 0 ? (std::size_t)worst : stats.first_point;
  if (worst >= 0 || stats.first_point != KernelStats::none) {
    where[0] = (double)layout_.cloud.natural_id[bad];
    for (int c = 0; c < D; ++c) where[1 + c] = layout_.cloud.x[D * bad + c];
  }
  int have = where[0] >= 0 ? rank_ : size_, first = size_;
  PetscCallMPI(MPI_Allreduce(&have, &first, 1, MPI_INT, MPI_MIN, comm_));
  if (first < size_) PetscCallMPI(MPI_Bcast(where, 1 + D, MPI_DOUBLE, first, comm_));
  char at[160] = "";
  if (first < size_ && D == 2) std::snprintf(at, sizeof at, " First at point %.0f, reference position (%.6g, %.6g) m.", where[0], where[1], where[2]);
  else if (first < size_) std::snprintf(at, sizeof at, " First at point %.0f, reference position (%.6g, %.6g, %.6g) m.", where[0], where[1], where[2], where[3]);
  *diverged = PETSC_FALSE;
  if (global[0] || ((global[1] || global[2]) && !scene_.failure.enabled)) {
    *diverged = PETSC_TRUE;
    char msg[512];
    // What happened; the cause and its fix follow (DiagnoseDivergence).
    if (global[0])
      std::snprintf(msg, sizeof msg, "the solution became NaN/Inf at step %" PetscInt_FMT " (t = %.6e s, dt = %.4e s).", step, t, step_control_.current());
    else if (global[1])
      std::snprintf(msg, sizeof msg, "%d bond(s) inverted (det F <= 0) at step %" PetscInt_FMT " (t = %.6e s, dt = %.4e s): the run is unstable.", global[1], step, t, step_control_.current());
    else
      std::snprintf(msg, sizeof msg, "%d bond(s) reached the Gent chain-extension limit (I1bar - 3 >= Jm) at step %" PetscInt_FMT " (t = %.6e s), where the model has no finite energy.", global[2], step, t);
    stop_reason_      = std::string(msg) + at;
    stopped_on_error_ = true;
  }
  PetscFunctionReturn(0);
}

// The chain reach of a state (u: owned, c33: its warm starts): max over owned bonds of
// (I1bar - 3) / (I1bar_limit - 3) (Gent: / Jm), I1bar = tr(C) J^{-2/3} with
// C = diag(F~^T F~, C33) (C33 = 1 in plane strain; hyperelastic.hpp), and the largest
// principal stretch of that bond: reach = {reach, stretch}. `span`: I1bar_limit - 3 of a
// law with a limit. Once, when the run stops: the slow per-bond path. Collective.
template <int D> PetscErrorCode SimulationD<D>::ChainReach(const double *state_u, const std::vector<double> &state_c33, double span, double reach[2])
{
  const bool plane_strain = scene_.material.formulation == Formulation::plane_strain;

  PetscFunctionBegin;
  reach[0] = 0.0, reach[1] = 1.0;
  PetscCall(force_.UpdatePositions(state_u));
  const double *y = force_.positions();
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t q = 0; q < families_.size((std::size_t)i); ++q) {
      if (!bond_state_.is_intact((std::size_t)i, q) || !geometry_.is_usable((std::size_t)i, q)) continue;
      if constexpr (D == 2) {
        const Mat2   F   = bond_deformation_gradient(layout_.cloud, y, families_, geometry_, bond_state_, (std::size_t)i, q);
        const double C33 = plane_strain ? 1.0 : state_c33[families_.offsets[i] + q];
        const double J   = det(F) * std::sqrt(C33);
        if (!(J > 0) || !(C33 > 0)) continue;
        const double c11 = F[0] * F[0] + F[2] * F[2], c22 = F[1] * F[1] + F[3] * F[3], c12 = F[0] * F[1] + F[2] * F[3];
        const double I1bar = (c11 + c22 + C33) * std::pow(J, -2.0 / 3.0);
        const double r     = (I1bar - 3.0) / span;
        if (r > reach[0]) {
          const double mean = 0.5 * (c11 + c22), dev = std::sqrt(0.25 * (c11 - c22) * (c11 - c22) + c12 * c12);
          reach[0] = r, reach[1] = std::sqrt(mean + dev);
        }
      } else { // 3D: I1bar = tr(C) J^{-2/3}; the largest principal stretch by power iteration on C (once, at the stop)
        const nd::Mat<3> F = nd::bond_deformation_gradient<3>(layout_.cloud, y, families_, geometry_, bond_state_, (std::size_t)i, q);
        const double     J = nd::det<3>(F);
        if (!(J > 0)) continue;
        double C[9], trC = 0;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            C[3 * a + b] = F[a] * F[b] + F[3 + a] * F[3 + b] + F[6 + a] * F[6 + b];
            if (a == b) trC += C[3 * a + b];
          }
        const double r = (trC * std::pow(J, -2.0 / 3.0) - 3.0) / span;
        if (r > reach[0]) {
          double e[3] = {1, 1, 1}, largest = 0;
          for (int it = 0; it < 50; ++it) {
            double w[3];
            for (int a = 0; a < 3; ++a) w[a] = C[3 * a] * e[0] + C[3 * a + 1] * e[1] + C[3 * a + 2] * e[2];
            largest = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            for (int a = 0; a < 3; ++a) e[a] = w[a] / largest;
          }
          reach[0] = r, reach[1] = std::sqrt(largest);
        }
      }
    }
  struct {
    double value;
    int    rank;
  } mine = {reach[0], rank_}, best;
  PetscCallMPI(MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_));
  PetscCallMPI(MPI_Bcast(reach, 2, MPI_DOUBLE, best.rank, comm_));
  PetscFunctionReturn(0);
}

// The state 10 to 20 steps before the last good one, which a blow-up has often wrecked
// already (DivergenceFacts::stable_earlier, chain_reach_earlier): its stable step and its
// chain reach, into *f. c33_size: the warm starts' length. Collective.
template <int D> PetscErrorCode SimulationD<D>::DiagnoseEarlierState(std::size_t c33_size, double span, DivergenceFacts *f)
{
  const PetscInt n = D * layout_.n_owned;
  int            older = -1;

  PetscFunctionBegin;
  for (int k = 0; k < 2; ++k)
    if (output_.earlier_step[k] >= 0 && output_.earlier_step[k] + SimulationOutput::earlier_interval <= output_.good_step &&
        (older < 0 || output_.earlier_step[k] > output_.earlier_step[older]))
      older = k;
  if (older < 0) PetscFunctionReturn(0);
  const double *xe;
  PetscCall(VecGetArrayRead(output_.earlier_state[older], &xe));
  std::vector<double> ue(xe, xe + n);
  PetscCall(VecRestoreArrayRead(output_.earlier_state[older], &xe));
  f->earlier_steps = output_.good_step - output_.earlier_step[older];
  // Its C33, solved again from a cold start (the snapshot keeps no per-bond copy,
  // simulation_output.hpp): the same values to the solve's tolerance.
  std::vector<double> c33_earlier(c33_size, 0.0), unused(n);
  PetscCall(force_.EvaluateWithWarmStart(ue.data(), unused.data(), c33_earlier));
  PetscCall(step_control_.SharpEstimate(comm_, force_, ue.data(), c33_earlier, 40, &f->stable_earlier));
  if (!std::isfinite(f->stable_earlier) || f->stable_earlier <= 0) f->stable_earlier = 0;
  if (law_entry(scene_.material.model).limit) {
    double reach[2];
    PetscCall(ChainReach(ue.data(), c33_earlier, span, reach));
    f->chain_reach_earlier     = reach[0];
    f->bond_stretch_earlier    = reach[1];
    f->applied_stretch_earlier = loading_.stretch_at(output_.earlier_time[older]);
  }
  PetscFunctionReturn(0);
}

// What the solver sees at the last good state (the state saved before the step that
// failed; the current one without -checkpoint_on_error): the stable step of that
// state by a sharp power iteration, and how close its bonds came to the law's limit
// (Gent's chain limit, Arruda-Boyce's locking stretch). DivergenceAdvice
// (divergence.hpp) turns it into the cause and the fix.
// Once, when the run stops: the slow per-bond path is fine here. Collective.
template <int D> PetscErrorCode SimulationD<D>::DiagnoseDivergence()
{
  const bool     good = output_.good_step >= 0;
  const double  *x;
  const PetscInt n = D * layout_.n_owned;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(good ? output_.good_state : X_, &x));
  std::vector<double> u(x, x + n);
  PetscCall(VecRestoreArrayRead(good ? output_.good_state : X_, &x));
  // The last good state's C33, solved again from a cold start (it keeps no per-bond
  // copy, simulation_output.hpp): the same values to the solve's tolerance.
  std::vector<double> good_c33;
  if (good) {
    std::vector<double> unused(n);
    good_c33.assign(force_.warm_start().size(), 0.0);
    PetscCall(force_.EvaluateWithWarmStart(u.data(), unused.data(), good_c33));
  }
  const std::vector<double> &c33 = good ? good_c33 : force_.warm_start();
  PetscReal now;
  PetscCall(TSGetTime(ts_, &now));
  const double t = good ? output_.good_time : now;

  DivergenceFacts f;
  f.dt          = step_control_.current();
  f.base        = step_control_.base();
  f.stable_rest = step_control_.stable();
  f.step_given  = scene_.time_stepping.step > 0 || step_control_.base() != scene_.time_stepping.safety * step_control_.stable();
  f.safety      = scene_.time_stepping.safety;
  f.plane_strain = scene_.material.formulation == Formulation::plane_strain;
  f.bond_only    = scene_.material.force_form == ForceForm::bond_only;
  f.bulk_ratio   = 2.0 / (scene_.material.parameters.D * scene_.material.parameters.mu);
  f.damping      = scene_.time_stepping.damping;
  f.critical_stretch = scene_.failure.enabled ? scene_.failure.critical_stretch : 0.0;
  f.reestimating = step_control_.reestimating();
  f.horizon_factor = scene_.body.horizon_factor;
  f.stiffening     = step_control_.largest_lambda() / step_control_.lambda_rest();
  f.applied_stretch = loading_.stretch_at(t);
  // The chain reach only for a law with a limit (ChainReach).
  const LawEntry &law  = law_entry(scene_.material.model);
  const double    span = law.limit ? law.I1bar_limit(scene_.material.parameters) - 3.0 : 0.0;
  if (good) PetscCall(DiagnoseEarlierState(c33.size(), span, &f));
  PetscCall(step_control_.SharpEstimate(comm_, force_, u.data(), c33, 40, &f.stable));
  if (!std::isfinite(f.stable) || f.stable <= 0) f.stable = step_control_.stable_now();
  if (law.limit) {
    double reach[2];
    PetscCall(ChainReach(u.data(), c33, span, reach));
    f.chain_reach  = reach[0];
    f.bond_stretch = reach[1];
    f.limit        = law.limit;
    f.limit_option = law.limit_option;
    for (const LawOptionEntry &o : law.options)
      if (std::string(o.name) == law.limit_option) f.limit_value = scene_.material.parameters.values[o.index];
  }
  if (scene_.time_stepping.reestimate.monitor)
    PetscCall(PetscPrintf(comm_, "Diagnosis at the last good state: dt %.4e s, stable %.4e s (at rest %.4e s), chain reach %.4g (bond stretch %.4g), applied stretch %.4g; %" PetscInt_FMT " steps before: stable %.4e s, chain reach %.4g\n",
                          f.dt, f.stable, f.stable_rest, f.chain_reach, f.bond_stretch, f.applied_stretch, f.earlier_steps, f.stable_earlier, f.chain_reach_earlier));
  stop_reason_ += DivergenceAdvice(f);
  PetscFunctionReturn(0);
}

// The law's validity: Gent's chain limit is I1 - 3 < Jm (Arruda-Boyce's I1 < 3
// lambda_m^2). The compressible law puts it on the isochoric I1bar = J^{-2/3} I1, so near
// it a bond can stay inside the law's domain by a volume change alone: a plane-stress
// sheet thickens (J > 1) and I1bar stays below the limit at any stretch, the stress
// rising on the bulk modulus instead (plane_stress.hpp). For a nearly incompressible
// gel that state is not the material's: at stretch 20 the plate with a hole (Jm 162.6,
// K = 1000 mu) had J = 2.1 to 5.5 and ran to its end with exit 0. So a bond whose I1
// itself reaches the limit stops the run (without failure; with it, the failure
// criterion decides). Far from the limit J stays close to 1 (K = 1000 mu) and
// I1 and I1bar agree; near it the Gent stiffness carries the stress towards K and J
// departs from 1 (the plate: J = 1.28 where I1 reached the limit, I1bar - 3 = 0.85 Jm),
// which is why I1, the incompressible chain limit, is checked. A compressible gel with
// J > (limit / I1bar)^{3/2} meets it before its I1bar does.
// The trigger is free: the kernel's largest tr C of the dynamics' latest evaluation
// (KernelStats::largest_trC, with the bond's C33 warm start); once it fires, one loop
// over the owned bonds (with the C33 just solved) counts and locates them.
// A blow-up also swells bonds past the limit in I1 on its way to inverting them (the
// plate with Jm = 5 on a fixed step, stability.adaptive_step_diverge: 232 bonds at J =
// 1.6 one step before they inverted): that is the divergence checks' to diagnose (the
// time step), so the run stops here only once bonds have been past the limit for
// past_limit_steps consecutive steps; a state that crossed it under a load stays past it.
template <int D> PetscErrorCode SimulationD<D>::CheckLawValidity(PetscInt step, double t, std::string *message)
{
  PetscFunctionBegin;
  message->clear();
  const LawEntry &law = law_entry(scene_.material.model);
  if (scene_.failure.enabled || !law.limit) PetscFunctionReturn(0);
  const double limit = law.I1bar_limit(scene_.material.parameters);
  double       top   = force_.stats().largest_trC;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &top, 1, MPI_DOUBLE, MPI_MAX, comm_));
  if (!(top >= limit)) {
    past_limit_since_ = -1;
    PetscFunctionReturn(0);
  }

  const bool     plane_strain = scene_.material.formulation == Formulation::plane_strain;
  const double  *x;
  PetscCall(VecGetArrayRead(X_, &x)); // (u: the first D n_owned entries)
  PetscCall(force_.UpdatePositions(x));
  PetscCall(VecRestoreArrayRead(X_, &x));
  const double *y   = force_.positions();
  const double *c33 = force_.warm_start().empty() ? nullptr : force_.warm_start().data();
  long long     count   = 0;
  std::size_t   worst_i = 0;
  double        worst[3] = {0, 1, 0}; // I1, J, I1bar of the bond with the largest I1
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t q = 0; q < families_.size((std::size_t)i); ++q) {
      if (!bond_state_.is_intact((std::size_t)i, q) || !geometry_.is_usable((std::size_t)i, q)) continue;
      const nd::Mat<D> F = nd::bond_deformation_gradient<D>(layout_.cloud, y, families_, geometry_, bond_state_, (std::size_t)i, q);
      double trC = 0.0;
      for (int k = 0; k < D * D; ++k) trC += F[k] * F[k];
      double J = nd::det<D>(F);
      if (D == 2) {
        const double c = plane_strain || !c33 || !(c33[families_.offsets[i] + q] > 0) ? 1.0 : c33[families_.offsets[i] + q];
        trC += c;
        J *= std::sqrt(c);
      }
      // Past the limit in I1 and inside it in I1bar (so J > 1): the volume change the
      // law takes instead of its limit. A bond past it in I1bar too (or inverted) is a
      // state the model refused or a wreck: CheckHealth's and the divergence checks'.
      if (!(trC >= limit) || !(J > 0)) continue;
      const double I1bar = trC * std::pow(J, -2.0 / 3.0);
      if (!(I1bar < limit)) continue;
      ++count;
      if (trC > worst[0]) worst[0] = trC, worst[1] = J, worst[2] = I1bar, worst_i = (std::size_t)i;
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_LONG_LONG, MPI_SUM, comm_));
  if (count == 0) { // the trigger's C33 was the step before's: not yet
    past_limit_since_ = -1;
    PetscFunctionReturn(0);
  }
  if (past_limit_since_ < 0) past_limit_since_ = step, past_limit_stretch_ = loading_.stretch_at(t);
  if (step - past_limit_since_ + 1 < past_limit_steps) PetscFunctionReturn(0);
  struct {
    double value;
    int    rank;
  } mine = {worst[0], rank_}, best;
  PetscCallMPI(MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_));
  double where[7] = {worst[0], worst[1], worst[2], 0, 0, 0, 0}; // I1, J, I1bar, natural id, position
  if (best.rank == rank_) {
    where[3] = (double)layout_.cloud.natural_id[worst_i];
    for (int c = 0; c < D; ++c) where[4 + c] = layout_.cloud.x[D * worst_i + c];
  }
  PetscCallMPI(MPI_Bcast(where, 7, MPI_DOUBLE, best.rank, comm_));
  double option_value = 0;
  for (const LawOptionEntry &o : law.options)
    if (std::string(o.name) == law.limit_option) option_value = scene_.material.parameters.values[o.index];
  char at[128];
  if (D == 2) std::snprintf(at, sizeof at, "(%.6g, %.6g) m", where[4], where[5]);
  else std::snprintf(at, sizeof at, "(%.6g, %.6g, %.6g) m", where[4], where[5], where[6]);
  const double stretch = loading_.stretch_at(t);
  char         text[1600];
  std::snprintf(text, sizeof text,
                "%lld bond(s) past the law's chain limit in I1 = tr C at step %" PetscInt_FMT " (t = %.6e s, applied stretch %.4g; since "
                "step %" PetscInt_FMT ", stretch %.4g): "
                "the largest, at point %.0f, reference position %s, has I1 - 3 = %.4g >= %.4g (%s %g), and stays inside the law only "
                "because its volume ratio J = %.4g keeps I1bar = J^(-2/3) I1 at %.4g, a volume change a nearly incompressible gel "
                "(-material_bulk_ratio %g) does not make: past this point the stress is not the material's. Cause: %s. Raise %s "
                "(now %g), or end the load below stretch %.4g, or enable failure (-failure_critical_stretch) so that such bonds break.",
                count, step, t, stretch, past_limit_since_, past_limit_stretch_, where[3], at, where[0] - 3.0, limit - 3.0, law.limit_option, option_value, where[1], where[2],
                2.0 / (scene_.material.parameters.D * scene_.material.parameters.mu), law.limit, law.limit_option, option_value, past_limit_stretch_);
  *message = text;
  PetscFunctionReturn(0);
}

// Runaway energy (divergence.hpp), handed what it reads.
template <int D> PetscErrorCode SimulationD<D>::CheckRunaway(PetscInt step, double t, std::string *message)
{
  PetscReal dt;

  PetscFunctionBegin;
  PetscCall(TSGetTimeStep(ts_, &dt));
  RunawayInputs inputs;
  inputs.comm      = comm_;
  inputs.density          = scene_.material.density;
  inputs.dx               = scene_.body.dx();
  inputs.loads            = &scene_.loading.sets;
  inputs.reference_length = scene_.loading.reference_length;
  inputs.schedule         = &loading_.schedule();
  inputs.layout    = &layout_;
  inputs.state     = X_;
  inputs.dt        = dt;
  inputs.stable_dt = step_control_.stable();
  inputs.energies  = [this](double *kinetic, double *internal) { return Energies(kinetic, internal); };
  // The last good state is the previous step's while -checkpoint_on_error keeps it.
  inputs.energies_before = [this, step](double *kinetic, double *internal, bool *known) {
    PetscFunctionBegin;
    *known = output_.good_state && output_.good_step == step - 1;
    if (*known) PetscCall(Energies(kinetic, internal, output_.good_state));
    PetscFunctionReturn(0);
  };
  PetscCall(CheckRunawayEnergy(inputs, energy_monitor_, step, t, message));
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3 (main.cpp chooses one from the scene): the members defined
// here, one by one. simulation.cpp instantiates the class, which covers only what it
// defines; a class may be explicitly instantiated once in a program.
#define BAPD_SIMULATION_HEALTH(D) \
  template PetscErrorCode SimulationD<D>::CheckHealth(PetscInt step, double t, PetscBool *diverged); \
  template PetscErrorCode SimulationD<D>::ChainReach(const double *state_u, const std::vector<double> &state_c33, double span, double reach[2]); \
  template PetscErrorCode SimulationD<D>::DiagnoseEarlierState(std::size_t c33_size, double span, DivergenceFacts *f); \
  template PetscErrorCode SimulationD<D>::DiagnoseDivergence(); \
  template PetscErrorCode SimulationD<D>::CheckRunaway(PetscInt step, double t, std::string *message); \
  template PetscErrorCode SimulationD<D>::CheckLawValidity(PetscInt step, double t, std::string *message);
BAPD_SIMULATION_HEALTH(2)
BAPD_SIMULATION_HEALTH(3)
#undef BAPD_SIMULATION_HEALTH

} // namespace bapd
