// Time-step control: the step at rest, when to re-estimate and what the
// step does with the estimate (the dead band, the rate limit, the back-off, the kink
// check, the travel limit), restarts. The options: the scene's, scene_time_stepping.cpp; the
// estimate itself: time_step_estimate.cpp.
#include "bapd/solver/operators/time_step_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "bapd/core/materials/law_registry.hpp"
#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

// Stable step of the linearised system at the reference state, from lambda_max of
// M^{-1} K (the bond kernel itself, so every model, horizon and formulation is
// covered) from a deterministic start: the Krylov search until its largest Ritz value
// settles (StartupKrylov), or 60 power iterations (-time_step_estimate power, the
// estimate before the search; it gives the same bits as then). Norms are reproducible
// sums: dt is the same on any number of ranks.
PetscErrorCode TimeStepControl::EstimateStable(MPI_Comm comm, const TimeSteppingSection &stepping, const MaterialSection &material,
                                               bool failure, double dx, const Layout &layout, const Loading &loading,
                                               ForceOperator &force)
{
  const int      D = loading.dimension(); // dofs a point (2 or 3)
  const PetscInt n = D * layout.n_owned;

  PetscFunctionBegin;
  dimension_ = D;
  options_ = stepping.reestimate;
  inv_rho_ = 1.0 / material.density;
  eps_     = 1e-7 * dx;
  // -time_step_travel: given, or chosen here. With failure on, bonds that snap fling
  // their points at many times the wave speed at rest (docs/stability.md, section 5):
  // 0.1 dx a step is what the torn sheets need (0.3 is not enough). A step that the
  // user set above the stable one is left alone, so that its blow-up is reported
  // instead of hidden by a step shortened while the points fly apart.
  // The floor of the stiffness step. With failure and no crack-tip search it stays
  // above half the base step: the search is what tells a stiff mode at the tip
  // from the forces of bonds that broke after the base point's evaluation (which once
  // read as 1e6 x lambda_rest on the notched sheet; Reestimate and Kink explain).
  const bool tip_search = failure && options_.tip > 0 && options_.interval > 0 && options_.krylov;
  floor_        = options_.floor > 0 ? options_.floor : (failure && !tip_search ? 0.5 : 0.1);
  const LawEntry &law = law_entry(material.model);
  span_         = law.limit ? law.I1bar_limit(material.parameters) - 3.0 : 0.0;
  plane_strain_ = material.formulation == Formulation::plane_strain;
  failure_      = failure;
  travel_auto_  = stepping.travel < 0;
  travel_given_ = (travel_auto_ ? (failure ? 0.1 : 0.0) : stepping.travel) * dx;
  held_.assign(n, 0);
  for (const ConstrainedDof &d : loading.constrained()) held_[d.dof] = 1;
  v_.assign(n, 0.0);
  u_rec_.assign(n, 0.0);
  a_rec_.assign(n, 0.0);
  u_probe_.assign(n, 0.0);
  a_probe_.assign(n, 0.0);
  sq_.assign(n, 0.0);
  // The re-estimates' basis; the start-up search's (krylov_cap vectors) is given back
  // to this size after it.
  const PetscInt run_vectors = options_.interval > 0 && options_.krylov ? std::min(std::max(options_.max_iterations, options_.tip) + 1, krylov_cap) : 0;
  if (run_vectors > 0) PetscCall(KrylovReserve(run_vectors));
  if (tip_search) v_kept_.assign(n, 0.0);
  SeedStart(layout);
  std::vector<double> u0(n, 0.0), a0(n); // set-up only
  // The warm starts are the operator's own, zero (no warm start) at set-up: the Krylov
  // search only reads them, as the re-estimates read the committed ones; the power
  // iteration advances them probe by probe and sets them back to zero after it, so
  // that the operator is left as it was without a per-bond copy.
  std::vector<double> &c33 = force.warm_start();
  PetscCheck(std::all_of(c33.begin(), c33.end(), [](double c) { return c == 0.0; }), comm, PETSC_ERR_PLIB,
             "EstimateStable: the operator has warm starts already (it must run before any evaluation)");
  double lambda = 0.0;
  if (options_.startup_krylov) {
    PetscCall(ProbeAcceleration(force, c33, nullptr, inv_rho_, held_, u0.data(), a0.data()));
    PetscCall(KrylovReserve(krylov_cap));
    PetscCall(StartupKrylov(comm, force, c33, u0.data(), a0.data(), &lambda));
    // The basis back to the re-estimates' size (set-up: the reallocation is allowed).
    basis_.resize((std::size_t)run_vectors * n);
    basis_.shrink_to_fit();
    krylov_size_ = run_vectors;
  } else {
    PetscCall(ProbeAcceleration(force, c33, &c33, inv_rho_, held_, u0.data(), a0.data()));
    for (PetscInt it = 0; it < startup_iterations; ++it) PetscCall(PowerStep(comm, force, c33, &c33, u0.data(), a0.data(), 0.0, &lambda));
    std::fill(c33.begin(), c33.end(), 0.0);
  }
  startup_evaluations_ = 1 + evaluations_; // the base point and the probes
  evaluations_         = 0;                // counts the re-estimates' cost only
  PetscCheck(std::isfinite(lambda) && lambda > 0, comm, PETSC_ERR_USER,
             "Could not estimate a stable time step (lambda_max = %g): check -material_mu, -material_D and -material_density", lambda);
  // The Rayleigh quotient approaches lambda_max from below: pad it by 10 %.
  lambda_rest_ = lambda_ = lambda_largest_ = lambda;
  stable_dt_ = stable_now_ = 2.0 / std::sqrt(1.1 * lambda);
  SetBaseStep(stepping.step > 0 ? stepping.step : stepping.safety * stable_dt_);
  next_estimate_    = options_.interval;
  interval_now_     = options_.interval;
  stretch_now_      = options_.stretch;
  estimate_stretch_ = loading.stretch_at(0.0);
  PetscCall(ReportStartup(comm, stepping.step > 0, lambda));
  PetscFunctionReturn(0);
}

// A deterministic start with energy in every wavelength: a hash of the natural id
// (held dofs zero), kept as the seed of later searches.
void TimeStepControl::SeedStart(const Layout &layout)
{
  const int D = dimension_;
  for (PetscInt i = 0; i < layout.n_owned; ++i)
    for (int c = 0; c < D; ++c) {
      uint64_t h = (uint64_t)layout.cloud.natural_id[i] * D + c + 0x9E3779B97F4A7C15ULL;
      h ^= h >> 33;
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 33;
      v_[D * i + c] = held_[D * i + c] ? 0.0 : (double)(h >> 11) / 9007199254740992.0 - 0.5;
    }
  seed_ = v_;
}

// The set-up's lines on the step: the estimate, the re-estimates, the travel limit, and
// a step given (-time_step) or taken above the stable one.
PetscErrorCode TimeStepControl::ReportStartup(MPI_Comm comm, bool step_given, double lambda) const
{
  PetscFunctionBegin;
  PetscCall(PetscPrintf(comm, "Stable time step %.4e s (%s, %" PetscInt_FMT " force evaluations, lambda_max = %.6e 1/s^2); using dt = %.4e s (%.3g x stable)\n",
                        stable_dt_, options_.startup_krylov ? "Krylov search" : "power iteration", startup_evaluations_, lambda, dt_, dt_ / stable_dt_));
  if (options_.interval > 0)
    PetscCall(PetscPrintf(comm, "Time step: re-estimated every %" PetscInt_FMT " steps (%" PetscInt_FMT " to %" PetscInt_FMT " %s about the current state), at most %.4e s%s\n",
                          options_.interval, options_.iterations, std::max(options_.iterations, options_.max_iterations), options_.krylov ? "Krylov steps" : "power iterations", dt_,
                          travel_ > 0 ? "; shorter while points with bonds fly" : ""));
  if (travel_ > 0 && travel_auto_)
    PetscCall(PetscPrintf(comm, "Time step: with failure on, no point with bonds moves more than 0.1 dx in one step (-time_step_travel 0 turns it off)\n"));
  if (step_given) PetscCall(CheckFixedStep(comm, "-time_step", dt_));
  else if (dt_ > stable_dt_)
    PetscCall(PetscPrintf(comm, "\n*** WARNING: dt = %.4e s is LARGER than the stable step %.4e s: expect the run to blow up.\n"
                                "*** Lower -time_step_safety below 1.\n\n",
                          dt_, stable_dt_));
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::CheckFixedStep(MPI_Comm comm, const char *option, double dt) const
{
  PetscFunctionBegin;
  if (!(dt > stable_dt_)) PetscFunctionReturn(0);
  char given[32], fix[32]; // (PETSc's %g would print "1.")
  std::snprintf(given, sizeof given, "%g", dt);
  std::snprintf(fix, sizeof fix, "%.3g", 0.8 * stable_dt_);
  const bool ts_dt = std::strcmp(option, "-ts_dt") == 0;
  PetscCheck(dt <= fixed_step_margin * stable_dt_ || options_.allow_unstable, comm, PETSC_ERR_USER,
             "%s %s s is %.3g x the stable time step %.4e s (estimated at rest; more than %g x it is refused): an explicit step that "
             "long amplifies the body's fastest mode every step, and the results would be meaningless. Give %s %s (0.8 x stable) or "
             "less, or %s (the solver then takes -time_step_safety x the stable step); -time_step_allow_unstable runs it anyway "
             "(to study the blow-up)",
             option, given, dt / stable_dt_, stable_dt_, fixed_step_margin, option, fix, ts_dt ? "remove -ts_dt" : "leave -time_step out");
  PetscCall(PetscPrintf(comm, "\n*** WARNING: %s %.4e s is LARGER than the stable step %.4e s (%.3g x): expect the run to blow up.\n\n", option,
                        dt, stable_dt_, dt / stable_dt_));
  PetscFunctionReturn(0);
}

void TimeStepControl::SetBaseStep(double dt)
{
  dt_ = base_dt_ = stiffness_dt_ = dt;
  travel_ = travel_auto_ && dt > stable_dt_ ? 0.0 : travel_given_;
}

void TimeStepControl::Record(const double *u, const double *a)
{
  if (options_.interval <= 0) return;
  std::memcpy(u_rec_.data(), u, sizeof(double) * u_rec_.size());
  std::memcpy(a_rec_.data(), a, sizeof(double) * a_rec_.size());
  recorded_ = true;
}

// A few power iterations about the latest evaluation of the dynamics, warm-started from
// the last eigenvector: the Rayleigh quotient follows lambda_max as the state changes.
// Every probe reads the operator's committed C33 warm starts (converged at that very
// state, 1e-7 dx from the probe) and writes none back, so the operator is left as it
// was and a restart (which restores them) repeats the estimate bit for bit. (Probes
// that advanced a copy of them, 8 B a bond, from probe to probe had the same start for
// the first probe, one at round-off distance for the later ones.)
PetscErrorCode TimeStepControl::Reestimate(MPI_Comm comm, ForceOperator &force, bool loading, double psi, bool broke, PetscInt *iterations)
{
  PetscFunctionBegin;
  const double               wall      = MPI_Wtime();
  const std::vector<double> &committed = force.warm_start();
  // At least `iterations` iterations, more (up to max_iterations) while the quotient
  // still moves by more than `tolerance`: in a steady state the warm start is already
  // converged and one iteration confirms it; when the fastest mode moves elsewhere
  // (stiffening at a hole, a crack tip) the quotient climbs and the iteration follows.
  // Except where the answer cannot matter: at the base step (which the stiffness step
  // never exceeds) only a lambda past lambda_rest / (1 - band)^2 would shorten it. The
  // quotient climbs towards lambda_max by increments that shrink about geometrically
  // (ratio r < 1, measured 0.57 to 0.85 on the plate's first ramp); while even ten
  // more increments of the last size (r = 0.9) stay below that threshold the step stays
  // at the base step, and the iteration stops (the plate's first ramp, where lambda_max
  // falls to 0.88 x its value at rest: 18 force evaluations became 10).
  // When the step's breaking pass broke bonds, the base point is evaluated again: the
  // recorded a(u) is the dynamics' evaluation, made before that pass, and the probes
  // see the bonds broken since, so the quotient read their forces over eps as a
  // stiffness (rank_invariance.fracture_corrected: 7.5e13 1/s^2, 1.2e6 x lambda_rest,
  // measured from both sides as +3.2e13 and -3.2e13, the signature of a base point off
  // the probes' force; the stiffness step then sat at the floor, 0.5 x, for the rest of
  // the run). Only then: with failure on at every estimate it doubled the short
  // notched sheet's cost (19 -> 38 evaluations in 1000 steps).
  if (broke) {
    PetscCall(ProbeAcceleration(force, committed, nullptr, inv_rho_, held_, u_rec_.data(), a_rec_.data()));
    ++evaluations_;
  }
  const bool   at_base   = stiffness_dt_ >= base_dt_ && Margin();
  const double threshold = ShorteningThreshold();
  // While the step is shortened by stiffness it rests on this estimate, so the warm
  // start keeps a part of every mode: a converged eigenvector has none of a mode that
  // rises elsewhere (the Jm = 3 plate: the hole's rim stiffened to 10 x lambda_rest
  // while a two-iteration estimate, warm-started from the old mode, still read 3 x and
  // the step blew up at stretch 1.8). The seed (white, |seed| = 1 after scaling) is
  // mixed in at seed_weight of the unit vector: it moves the power quotient by about
  // seed_weight^2 / 2 (0.1 %, inside the tolerance); the Krylov search, whose space
  // holds the warm start's mode whatever the mixture, takes krylov_seed_weight. Measured: without it the 2 mm
  // Jm = 3 plate still blew up at stretch 1.90 with the rising iterations below.
  //
  // With the stiffening indicator (-time_step_reestimate_indicator, StiffeningIndicator;
  // off by default) the search (the seed and the rising iterations below) runs only when
  // the indicator grew by search_growth since the last search, or none has run: the
  // rest of the time the warm start is the last Ritz vector and one or two Krylov steps
  // follow it. On the Jm = 8 plate (docs/stability.md section 8) it cut 50 evaluations
  // to 39 and still found the stretch-2 mode at step 513, but the indicator grows ten
  // times as much as lambda_max (psi 1.3 -> 18.5 while lambda_max goes 1.0 -> 2.0 x) and
  // where the search lands decides whether the mode is found: a proxy, not a bound.
  const bool shortened = stiffness_dt_ < base_dt_;
  const bool search    = shortened && (!(psi > 0) || !(psi_ > 0) || psi > options_.growth * psi_);
  // (Also taking the latest estimate at the base step as the reference saved 5 more
  // evaluations but put a search at step 501 of the Jm = 8 plate, just before the
  // stretch-2 mode took over, and no search after it: the run ended at 1.35 x lambda_rest
  // where lambda_max is 2.0 x.)
  if (search && psi > 0) psi_ = psi;
  // With the kernel's indicator: a bond within a quarter of its chain limit (Gent factor
  // near_limit or more) stiffens too fast for a warm-started estimate to follow between
  // searches (the 1 mm Jm = 3 plate blew up at stretch 1.82 with its estimates at 2.3 x
  // lambda_rest, the indicator swinging 5 -> 10.8 -> 8.5 as bonds reached the limit), so
  // every shortened estimate is seeded and rising again, as without the indicator.
  const bool near = options_.bonds && psi >= near_limit;
  if (shortened && (search || !(psi > 0) || near)) PetscCall(MixSeed(comm));
  // And while it is shortened and the load moves (or the last estimate shortened it,
  // lambda having risen past the band), at least rising_iterations: a quotient still
  // climbing by less than the tolerance per iteration is not settled then, as the
  // fastest mode localises at a stiffening spot (the Jm = 3 plate: with one to three
  // iterations the estimates read 2.9 x lambda_rest at stretch 1.8 to 1.9 and the run
  // blew up; with four and the tail check below they read up to 24 x (2 mm: the run
  // ends) and 43 x (1 mm: its corner bonds reach the limit itself at 1.993)). Both read from the state a checkpoint carries: a restart repeats it.
  // (From lambda = 1.5 x lambda_rest only, it saved the fast-route plate 7 of 30
  // evaluations but left the Jm = 8 plate at 1.3 x through its stretch-2 hold, where
  // lambda_max is 2.0 x: its step then sat at 0.99 x the stable one.)
  const bool     rising    = shortened && (psi > 0 && !near ? search : loading || stiffness_dt_ == StiffnessTarget());
  // With the kernel's indicator a search is rare (the stiffest bond grew by
  // options_.growth since the last), so it runs every Krylov step it may: on the Jm = 8
  // plate the mode near the hole shows only in the 6th to 8th step of a search (its
  // quotient settles at 1.3 x lambda_rest after four, then climbs to 1.9 x), and a search
  // stopped at four never found it.
  const PetscInt fewest = options_.bonds && search ? options_.max_iterations
                          : rising ? std::min(std::max(options_.iterations, rising_iterations), options_.max_iterations)
                                   : options_.iterations;
  double   lambda = 0;
  PetscInt it     = 0;
  PetscCall(Iterate(comm, force, committed, {rising, at_base, search, near, threshold, fewest}, &lambda, &it));
  // A jump is checked from both sides before it is believed (Kink).
  if (std::isfinite(lambda) && lambda > kink_jump * std::max(lambda_, lambda_rest_)) {
    bool kink = false;
    PetscCall(Kink(comm, force, committed, lambda, &kink));
    if (kink) lambda = lambda_, ++kinks_;
  }
  *iterations = it;
  ++estimates_;
  // A quotient that is not positive or not finite (a static instability, a NaN the
  // health check reports) says nothing about the fastest mode: keep the last one.
  if (std::isfinite(lambda) && lambda > 0) lambda_ = lambda;
  else if (!std::isfinite(lambda)) v_ = seed_; // a NaN must not stay in the vector: the start again (no allocation: same size)
  lambda_largest_ = std::max(lambda_largest_, lambda_);
  stable_now_     = 2.0 / std::sqrt(1.1 * lambda_);
  estimate_wall_ += MPI_Wtime() - wall;
  PetscFunctionReturn(0);
}

// After a step: the re-estimate when due, then the step. The stiffness step keeps the
// ratio of the base step to the stable one (the safety factor, or whatever -time_step
// or -ts_dt gave), bounded by the base step; it moves only outside the dead band.
// While lambda moves by more than the band between two estimates the next one comes
// a step later, so a fast stiffening is followed closely; a steady state costs
// iterations / interval force evaluations per step.
// The travel limit: bonds that snap at a large stretch fling their points at many
// times the wave speed at rest; a step that lets such a point travel a sizeable part
// of dx carries it past its neighbours, and the inverted bond-associated F that
// follows gives a huge stress and a blow-up within a step (docs/stability.md,
// section 5). So the step shrinks until no point that still has a bond moves more
// than the travel limit, and returns once they slow down. The maximum is exact
// (MPI_MAX of doubles), so the step is the same on any number of ranks.
PetscErrorCode TimeStepControl::AfterStep(MPI_Comm comm, PetscInt step, double stretch, const Layout &layout, const Families &families,
                                          const BondState &state, ForceOperator &force, const double *v, const std::vector<std::size_t> *touched,
                                          bool broke, TS ts)
{
  PetscFunctionBegin;
  // Due after `interval` steps, or sooner on a fast ramp: a ramp of the fast route
  // (0.05 s, 30 steps) stiffens a Jm = 3 gel past its step between two estimates
  // (docs/stability.md, section 8).
  const bool by_step = step >= next_estimate_;
  const bool due     = by_step || std::fabs(stretch - estimate_stretch_) > stretch_now_;
  // Bonds broke on any rank (the driver's reduction, which the breaking passes and the
  // released energy read too): the crack-tip search, and an estimate due now evaluates
  // its base point again (it is stale).
  if (options_.interval > 0 && recorded_ && due) {
    const double stretch_moved = std::fabs(stretch - estimate_stretch_);
    estimate_stretch_          = stretch;
    const double   before = lambda_, stiffness_before = stiffness_dt_;
    PetscInt       iterations         = 0;
    double psi = 0;
    if (options_.indicator) PetscCall(StiffeningIndicator(comm, layout, families, state, force, &psi));
    else if (options_.bonds) PetscCall(BondIndicator(comm, force, &psi));
    PetscCall(Reestimate(comm, force, stretch_moved > 0, psi, broke, &iterations));
    // Shrinks at once; grows back by at most 2 x band per estimate: a quotient that
    // drops is not trusted at once (the warm-started iteration can lose the fastest
    // mode for a while when it moves: a Jm = 3 plate at stretch 2 showed lambda_max
    // 17 x, then 0.6 x the value at rest 50 steps later, and blew up at the full step).
    const double target = StiffnessTarget();
    // With the kernel's indicator, the estimate that first shortens the step (it ran
    // until settled: the seed is for later ones) is where the indicator's growth is
    // counted from: the Jm = 8 plate's next estimate, 10 steps on, searched (6 Krylov
    // steps) only because no search had run yet.
    if (options_.bonds && psi > 0 && !(psi_ > 0) && stiffness_dt_ >= base_dt_ && target < (1.0 - options_.band) * stiffness_dt_) psi_ = psi;
    if (target < (1.0 - options_.band) * stiffness_dt_) stiffness_dt_ = target;
    else if (target > (1.0 + options_.band) * stiffness_dt_) stiffness_dt_ = std::min(target, (1.0 + 2.0 * options_.band) * stiffness_dt_);
    // Far from mattering: at the base step, lambda stays below the threshold that would
    // shorten it even if it went on moving as fast for two more intervals.
    const double moved     = std::fabs(lambda_ - before);
    const bool   far       = stiffness_dt_ >= base_dt_ && Margin() && lambda_ + 2.0 * moved < ShorteningThreshold();
    // Stiffening by more than the band (unless far from mattering), or a step still
    // growing back (beyond the band: inside it the step stays, and so would the
    // follow-ups, for good): the next estimate comes sooner (a fifth of the interval:
    // a tenth cost 6 % of the fast plate).
    const bool sooner = (lambda_ > (1.0 + options_.band) * before && !far) || target > (1.0 + options_.band) * stiffness_dt_;
    // Quiet: the step stayed, and lambda moved by less than half the band or is far
    // from mattering. Then the steps and the stretch increment to the next estimate
    // double, up to backoff x the options' (holds, and ramps of a soft gel, cost a
    // fourth); anything else brings them back at once.
    const bool quiet = !sooner && stiffness_dt_ == stiffness_before && Margin() && (moved <= 0.5 * options_.band * before || far);
    // The stretch increment backs off only on the evidence of a stretch that moved by
    // it: an estimate in a hold says nothing about the next ramp (the Jm = 3 plate
    // left its 1.5 hold with 0.2 and met the chain-limit stiffening at 1.6 unseen).
    // And the steps back off only in a hold: the load stops and the body goes on
    // moving (the Jm = 8 plate's stretch-2 mode took over 10 to 40 steps after its
    // ramp ended, lambda_max 1.3 -> 1.8 x rest, while a quiet estimate on the ramp
    // had put the next one 200 steps away).
    if (quiet) {
      interval_now_ = stretch_moved > 0 ? options_.interval : std::min(2 * interval_now_, options_.backoff * options_.interval);
      if (stretch_moved >= stretch_now_) stretch_now_ = std::min(2.0 * stretch_now_, (double)options_.backoff * options_.stretch);
    } else {
      interval_now_ = options_.interval;
      stretch_now_  = options_.stretch;
    }
    next_estimate_ = step + (sooner ? std::max<PetscInt>(1, options_.interval / 5) : interval_now_);
    if (options_.monitor)
      PetscCall(PetscPrintf(comm, "re-estimate %" PetscInt_FMT " after step %" PetscInt_FMT " (%s, %" PetscInt_FMT " iteration(s), indicator %.4g, at the last search %.4g): lambda_max %.6e 1/s^2 (%.4g x at rest), stable %.4e s, stiffness step %.4e s (%.4g x base), next in %" PetscInt_FMT " steps or %.3g in stretch, %" PetscInt_FMT " force evaluations, %.3f s so far\n",
                            estimates_, step, by_step ? "steps" : "stretch", iterations, psi, psi_, lambda_, lambda_ / lambda_rest_, stable_now_, stiffness_dt_,
                            stiffness_dt_ / base_dt_, next_estimate_ - step, stretch_now_, evaluations_, estimate_wall_));
  }
  if (broke && recorded_ && !v_kept_.empty()) PetscCall(FollowCrackTip(comm, force, *touched, layout.n_owned, step));
  if (options_.reference > 0 && recorded_ && step % 25 == 0) PetscCall(Reference(comm, force, step));
  double dt = stiffness_dt_;
  bool   flying = false;
  if (travel_ > 0) {
    double v2_max;
    PetscCall(FastestBondedSpeed2(comm, layout, families, state, v, &v2_max));
    if (v2_max * dt * dt > travel_ * travel_) dt = travel_ / std::sqrt(v2_max), flying = true;
  }
  // While the travel limit holds the step below the stiffness step, the re-estimates
  // wait: counted in steps, they would come ever more often in simulated time as the
  // step shrinks (a running crack at 0.04 x the base step spent 20 % of the run in
  // them), and the stiffness step does not set the step then anyway.
  if (flying && options_.interval > 0) ++next_estimate_;
  if (dt != dt_) {
    dt_ = dt;
    PetscCall(TSSetTimeStep(ts, dt_));
  }
  if (dt_ < base_dt_) {
    if (flying) ++by_travel_;
    else ++by_stiffness_;
    shortest_dt_ = shortest_dt_ > 0 ? std::min(shortest_dt_, dt_) : dt_;
  }
  PetscFunctionReturn(0);
}

// The largest |v|^2 over the points that still have a bond (a point with none is
// carried along and cannot pass a neighbour's bonds): an exact MPI maximum.
PetscErrorCode TimeStepControl::FastestBondedSpeed2(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state,
                                                    const double *v, double *v2_max) const
{
  const std::size_t W = families.mask_words;

  PetscFunctionBegin;
  *v2_max = 0.0;
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    const std::uint64_t *intact = state.intact_mask((std::size_t)i);
    std::uint64_t        any    = 0;
    for (std::size_t w = 0; w < W; ++w) any |= intact[w];
    if (!any) continue;
    const double *vi = v + dimension_ * i;
    double        v2 = vi[0] * vi[0] + vi[1] * vi[1];
    if (dimension_ == 3) v2 += vi[2] * vi[2];
    *v2_max = std::max(*v2_max, v2);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v2_max, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscFunctionReturn(0);
}

// The difference quotient A v = -(a(u + eps v) - a(u)) / eps assumes a force that is
// differentiable at u and a base point a(u) of the same bonds as the probes. A bond at
// the edge of the model's failure (inverted, at the chain limit, its C33 solve not
// converging) carries its force at u and none at the probe 1e-7 dx away (or the
// reverse), and the quotient reads that jump over eps as a stiffness (as it read the
// bonds broken after the base point's evaluation, Reestimate). So the
// Rayleigh quotient of the unit Ritz vector v is measured from both sides, q+ = -v .
// (a(u + eps v) - a(u)) / eps and q- = v . (a(u - eps v) - a(u)) / eps: for a smooth
// force they agree to O(eps) (a stiffening material's included: the Jm = 3 plate's
// 40 x is smooth at this scale); a switch between u and one of the probes moves only
// one of them. Two force evaluations, only for an estimate that jumped by kink_jump.
PetscErrorCode TimeStepControl::Kink(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, double lambda, bool *kink)
{
  const PetscInt n = (PetscInt)v_.size();
  double         q[2], norm2;

  PetscFunctionBegin;
  PetscCall(Dot(comm, v_.data(), v_.data(), &norm2));
  const double inv = 1.0 / std::sqrt(norm2);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    for (PetscInt k = 0; k < n; ++k) u_probe_[k] = u_rec_[k] + sign * eps_ * v_[k] * inv;
    PetscCall(ProbeAcceleration(force, c33, nullptr, inv_rho_, held_, u_probe_.data(), a_probe_.data()));
    ++evaluations_;
    for (PetscInt k = 0; k < n; ++k) sq_[k] = held_[k] ? 0.0 : -sign * (a_probe_[k] - a_rec_[k]) / eps_ * v_[k] * inv;
    PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), &q[side]));
  }
  *kink = !(std::fabs(q[0] - q[1]) <= kink_mismatch * std::max(std::fabs(q[0]), std::fabs(q[1])));
  if (options_.monitor)
    PetscCall(PetscPrintf(comm, "re-estimate: lambda_max %.6e 1/s^2 (%.4g x at rest) checked from both sides: %.6e and %.6e 1/s^2: %s\n", lambda,
                          lambda / lambda_rest_, q[0], q[1], *kink ? "a kink of the force (a bond at a switch), not a stiffness: the estimate is dropped" : "smooth"));
  if (*kink) v_ = seed_; // the Ritz vector sits on the switch: start again from the white vector
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::BondIndicator(MPI_Comm comm, const ForceOperator &force, double *psi) const
{
  PetscFunctionBegin;
  double trC = force.stats().largest_trC;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &trC, 1, MPI_DOUBLE, MPI_MAX, comm));
  trC = std::max(trC, 3.0);
  *psi = span_ > 0 ? 1.0 / std::max(1.0 - (trC - 3.0) / span_, 1e-3) : trC / 3.0;
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::StiffeningIndicator(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state,
                                                   ForceOperator &force, double *psi)
{
  PetscFunctionBegin;
  PetscCall(force.UpdatePositions(u_rec_.data()));
  const double *y = force.positions(), *x = layout.cloud.x.data(), *V = layout.cloud.volume.data();
  double        top = 1.0;
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    // N = sum V_j eta (x) xi and K = sum V_j xi (x) xi over the intact bonds: F = N K^-1.
    double n00 = 0, n01 = 0, n10 = 0, n11 = 0, k00 = 0, k01 = 0, k11 = 0;
    for (std::size_t q = 0; q < families.size((std::size_t)i); ++q) {
      if (!state.is_intact((std::size_t)i, q)) continue;
      const std::size_t j  = (std::size_t)families.neighbour[families.offsets[i] + q];
      const double      ex = x[2 * j] - x[2 * i], ey = x[2 * j + 1] - x[2 * i + 1];
      const double      hx = y[2 * j] - y[2 * i], hy = y[2 * j + 1] - y[2 * i + 1];
      const double      w  = V[j];
      n00 += w * hx * ex, n01 += w * hx * ey, n10 += w * hy * ex, n11 += w * hy * ey;
      k00 += w * ex * ex, k01 += w * ex * ey, k11 += w * ey * ey;
    }
    const double dk = k00 * k11 - k01 * k01;
    if (!(dk > 1e-8 * (k00 + k11) * (k00 + k11))) continue; // too few bonds left for a shape tensor
    const double i00 = k11 / dk, i01 = -k01 / dk, i11 = k00 / dk;
    const double f00 = n00 * i00 + n01 * i01, f01 = n00 * i01 + n01 * i11, f10 = n10 * i00 + n11 * i01, f11 = n10 * i01 + n11 * i11;
    const double J2d = f00 * f11 - f01 * f10;
    if (!(J2d > 0)) continue; // an inverted point: the health check's business
    const double trc   = f00 * f00 + f01 * f01 + f10 * f10 + f11 * f11;
    const double I1bar = plane_strain_ ? (trc + 1.0) * std::pow(J2d, -2.0 / 3.0) : trc + 1.0 / (J2d * J2d);
    double       g     = 1.0;
    if (span_ > 0) g = 1.0 / std::max(1.0 - (I1bar - 3.0) / span_, 1e-3);
    top = std::max(top, g * g * I1bar / 3.0);
  }
  PetscCallMPI(MPI_Allreduce(&top, psi, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscFunctionReturn(0);
}

TimeStepState TimeStepControl::state() const
{
  TimeStepState s;
  s.lambda        = lambda_;
  s.stiffness_dt  = stiffness_dt_;
  s.next_estimate = next_estimate_;
  s.stretch       = estimate_stretch_;
  s.by_stiffness  = by_stiffness_;
  s.by_travel     = by_travel_;
  s.shortest      = shortest_dt_;
  s.interval_now  = interval_now_;
  s.stretch_increment = stretch_now_;
  s.indicator     = psi_;
  return s;
}

// Restart: the step in use goes on as it was (a step shortened by stiffness or travel
// included), and so does the estimate; eigenvector() was filled from the checkpoint.
// A new, shorter base step (a smaller -time_step_safety) wins. state.lambda == 0: a
// checkpoint without the estimate (older format): start it again from the rest
// estimate's vector.
PetscErrorCode TimeStepControl::Restore(double dt, const TimeStepState &state, TS ts)
{
  PetscFunctionBegin;
  if (state.lambda > 0) {
    lambda_         = state.lambda;
    lambda_largest_ = std::max(lambda_largest_, lambda_);
    stable_now_     = 2.0 / std::sqrt(1.1 * lambda_);
    stiffness_dt_   = std::min(base_dt_, state.stiffness_dt);
    next_estimate_  = state.next_estimate;
    estimate_stretch_ = state.stretch;
    by_stiffness_   = state.by_stiffness;
    by_travel_      = state.by_travel;
    shortest_dt_    = state.shortest;
    if (state.interval_now > 0) { // format 4 on; older checkpoints start the back-off again
      interval_now_ = state.interval_now;
      stretch_now_  = state.stretch_increment;
    }
    psi_ = state.indicator; // format 5 on; 0 (older): the next estimate searches, as at the start
  }
  if (dt > 0 && dt < base_dt_ && (travel_ > 0 || options_.interval > 0)) {
    dt_ = dt;
    PetscCall(TSSetTimeStep(ts, dt_));
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
