// Time-step control: the estimate of lambda_max (the power iteration and the Krylov
// search on the current tangent, the probes that feed them); when to run it and what
// the step does with it is time_step_control.cpp (time_step_control.hpp).
#include "bapd/solver/operators/time_step_control.hpp"

#include <algorithm>
#include <cmath>

#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

// The acceleration of the free dofs, M^{-1} f, with the held ones zero. The C33 warm
// starts are c33, only read (no per-bond copy, 8 B a bond), or, with advance
// (the set-up's iteration), read from and advanced in *advance.
PetscErrorCode TimeStepControl::ProbeAcceleration(ForceOperator &force, const std::vector<double> &c33, std::vector<double> *advance, double inv_rho,
                                                  const std::vector<char> &held, const double *u, double *a)
{
  PetscFunctionBegin;
  if (advance) PetscCall(force.EvaluateWithWarmStart(u, a, *advance));
  else PetscCall(force.EvaluateFrom(u, a, c33));
  for (std::size_t k = 0; k < held.size(); ++k) a[k] = held[k] ? 0.0 : a[k] * inv_rho;
  PetscFunctionReturn(0);
}

namespace {

// The largest eigenvalue of the symmetric m x m matrix S (row-major, leading dimension
// ld; m <= 16) and its unit eigenvector y, by cyclic Jacobi rotations: exact to
// round-off, deterministic (the same bits on every rank, which all hold the same S).
double LargestEigenpair(const double *S, PetscInt m, PetscInt ld, double *y)
{
  double a[16][16], q[16][16];
  for (PetscInt i = 0; i < m; ++i)
    for (PetscInt j = 0; j < m; ++j) a[i][j] = S[i * ld + j], q[i][j] = i == j;
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, diag = 0;
    for (PetscInt i = 0; i < m; ++i) {
      diag += a[i][i] * a[i][i];
      for (PetscInt j = i + 1; j < m; ++j) off += a[i][j] * a[i][j];
    }
    if (!(off > 1e-30 * diag)) break;
    for (PetscInt p = 0; p < m; ++p)
      for (PetscInt r = p + 1; r < m; ++r) {
        if (a[p][r] == 0) continue;
        const double theta = (a[r][r] - a[p][p]) / (2 * a[p][r]);
        const double t     = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), sn = t * c;
        for (PetscInt k = 0; k < m; ++k) { // A <- A J
          const double akp = a[k][p], akr = a[k][r];
          a[k][p] = c * akp - sn * akr, a[k][r] = sn * akp + c * akr;
        }
        for (PetscInt k = 0; k < m; ++k) { // A <- J^T A
          const double apk = a[p][k], ark = a[r][k];
          a[p][k] = c * apk - sn * ark, a[r][k] = sn * apk + c * ark;
        }
        for (PetscInt k = 0; k < m; ++k) { // Q <- Q J
          const double qkp = q[k][p], qkr = q[k][r];
          q[k][p] = c * qkp - sn * qkr, q[k][r] = sn * qkp + c * qkr;
        }
      }
  }
  PetscInt top = 0;
  for (PetscInt i = 1; i < m; ++i)
    if (a[i][i] > a[top][top]) top = i;
  for (PetscInt i = 0; i < m; ++i) y[i] = q[i][top];
  return a[top][top];
}

} // namespace
PetscErrorCode TimeStepControl::Dot(MPI_Comm comm, const double *x, const double *y, double *result)
{
  const PetscInt n = (PetscInt)v_.size();

  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; ++k) sq_[k] = x[k] * y[k];
  PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), result));
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::KrylovReserve(PetscInt vectors)
{
  PetscFunctionBegin;
  vectors = std::min(vectors, krylov_cap);
  if (vectors > krylov_size_) { // at set-up (or once, for a diagnosis): no allocation in a step
    basis_.assign((std::size_t)vectors * v_.size(), 0.0);
    krylov_size_ = vectors;
  }
  projected_.assign((std::size_t)(krylov_cap * krylov_cap), 0.0);
  ritz_.assign((std::size_t)krylov_cap, 0.0);
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::KrylovStart(MPI_Comm comm)
{
  const PetscInt n = (PetscInt)v_.size();
  double         norm2;

  PetscFunctionBegin;
  PetscCall(Dot(comm, v_.data(), v_.data(), &norm2));
  if (!std::isfinite(norm2)) { // a wrecked state's search left a NaN (a diagnosis): the start vector again
    std::copy(seed_.begin(), seed_.end(), v_.begin());
    PetscCall(Dot(comm, v_.data(), v_.data(), &norm2));
  }
  PetscCheck(norm2 > 0, comm, PETSC_ERR_USER, "Every degree of freedom is held by a load set: nothing moves");
  const double inv = 1.0 / std::sqrt(norm2);
  for (PetscInt k = 0; k < n; ++k) basis_[k] = v_[k] * inv;
  std::fill(projected_.begin(), projected_.end(), 0.0);
  PetscFunctionReturn(0);
}

// Arnoldi step j: w = A v_j (held dofs zero), then for i <= j in turn h_ij = v_i . w and
// w -= h_ij v_i (modified Gram-Schmidt: each h from the w already reduced), the whole
// pass twice (one pass loses orthogonality to round-off growth, two do not), v_{j+1} =
// w / |w| with h_{j+1,j} = |w|. H (upper Hessenberg) is the projection V^T A V; the
// Rayleigh quotient x^T A x of x = V y is y^T H y = y^T sym(H) y, so the largest
// eigenvalue of sym(H) is the largest quotient over the space. For the symmetric
// energy-consistent tangent this is Lanczos (H tridiagonal); for the bond-only form,
// whose tangent is not symmetric, it is what the power iteration's quotient measured.
PetscErrorCode TimeStepControl::KrylovStep(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, const double *u0, const double *a0, PetscInt j, double *lambda,
                                           bool *exhausted)
{
  const PetscInt n  = (PetscInt)v_.size();
  const PetscInt ld = krylov_cap;
  const double  *vj = basis_.data() + (std::size_t)j * n;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; ++k) u_probe_[k] = u0[k] + eps_ * vj[k];
  PetscCall(ProbeAcceleration(force, c33, nullptr, inv_rho_, held_, u_probe_.data(), a_probe_.data()));
  ++evaluations_;
  double *w = a_probe_.data();
  for (PetscInt k = 0; k < n; ++k) w[k] = held_[k] ? 0.0 : -(w[k] - a0[k]) / eps_;
  for (int pass = 0; pass < 2; ++pass)
    for (PetscInt i = 0; i <= j; ++i) {
      const double *vi = basis_.data() + (std::size_t)i * n;
      double        h;
      PetscCall(Dot(comm, vi, w, &h));
      projected_[i * ld + j] += h;
      for (PetscInt k = 0; k < n; ++k) w[k] -= h * vi[k];
    }
  double sym[krylov_cap * krylov_cap];
  for (PetscInt r = 0; r <= j; ++r)
    for (PetscInt c = 0; c <= j; ++c) sym[r * ld + c] = 0.5 * (projected_[r * ld + c] + projected_[c * ld + r]);
  *lambda = LargestEigenpair(sym, j + 1, ld, ritz_.data());
  double beta2;
  PetscCall(Dot(comm, w, w, &beta2));
  const double beta = std::sqrt(beta2);
  // The space is exhausted (an invariant subspace: the estimate is exact on it) or full.
  *exhausted = j + 1 >= krylov_size_ || !(beta > 1e-10 * std::fabs(*lambda)) || !std::isfinite(*lambda);
  if (!*exhausted) {
    double *next = basis_.data() + (std::size_t)(j + 1) * n;
    for (PetscInt k = 0; k < n; ++k) next[k] = w[k] / beta;
    projected_[(j + 1) * ld + j] = beta;
  }
  PetscFunctionReturn(0);
}

void TimeStepControl::KrylovFinish(PetscInt steps)
{
  const std::size_t n = v_.size();
  std::fill(v_.begin(), v_.end(), 0.0);
  for (PetscInt i = 0; i < steps; ++i) {
    const double *vi = basis_.data() + (std::size_t)i * n;
    for (std::size_t k = 0; k < n; ++k) v_[k] += ritz_[i] * vi[k];
  }
}

// One power iteration about (u0, a0 = M^{-1} f(u0)): v <- A v with A v = -(a(u0 + eps
// v/|v|) - a0) / eps, and the Rayleigh quotient of the unit vector v/|v|. The
// warm starts C33: c33 read only, or *advance (ProbeAcceleration).
PetscErrorCode TimeStepControl::PowerStep(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, std::vector<double> *advance,
                                          const double *u0, const double *a0, double shift, double *lambda)
{
  const PetscInt n = (PetscInt)v_.size();
  double         norm2;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; ++k) sq_[k] = v_[k] * v_[k];
  PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), &norm2));
  PetscCheck(norm2 > 0, comm, PETSC_ERR_USER, "Every degree of freedom is held by a load set: nothing moves");
  const double inv = 1.0 / std::sqrt(norm2);
  for (PetscInt k = 0; k < n; ++k) u_probe_[k] = u0[k] + eps_ * v_[k] * inv;
  PetscCall(ProbeAcceleration(force, c33, advance, inv_rho_, held_, u_probe_.data(), a_probe_.data()));
  ++evaluations_;
  for (PetscInt k = 0; k < n; ++k) a_probe_[k] = held_[k] ? 0.0 : -(a_probe_[k] - a0[k]) / eps_;
  for (PetscInt k = 0; k < n; ++k) sq_[k] = a_probe_[k] * v_[k] * inv;
  PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), lambda));
  if (shift > 0)
    for (PetscInt k = 0; k < n; ++k) a_probe_[k] -= shift * v_[k] * inv;
  std::swap(v_, a_probe_);
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::SharpEstimate(MPI_Comm comm, ForceOperator &force, const double *u, const std::vector<double> &c33,
                                             PetscInt iterations, double *stable)
{
  PetscFunctionBegin;
  std::copy(u, u + u_rec_.size(), u_rec_.begin());
  PetscCall(ProbeAcceleration(force, c33, nullptr, inv_rho_, held_, u_rec_.data(), a_rec_.data()));
  double lambda = lambda_, best = lambda_;
  if (options_.krylov) {
    double found;
    PetscCall(RestartedKrylov(comm, force, c33, iterations, &found));
    best = std::max(best, found);
  } else
    for (PetscInt it = 0; it < iterations; ++it) {
      PetscCall(PowerStep(comm, force, c33, nullptr, u_rec_.data(), a_rec_.data(), options_.shift * best, &lambda));
      if (std::isfinite(lambda) && lambda > best) best = lambda;
    }
  *stable = 2.0 / std::sqrt(1.1 * best);
  PetscFunctionReturn(0);
}

// The set-up's estimate (-time_step_estimate krylov). The space after k steps holds the
// power iterate of k - 1 steps from the same start, so the largest Ritz value is never
// below that iterate's quotient, and it converges much faster: on a spectrum that is
// dense up to lambda_max (every body here) the quotient of the power iteration gains on
// lambda_max about as 1/k, the Lanczos value about as 1/k^2 (the Chebyshev polynomial of
// degree k against x^k). The largest Ritz value only grows within a cycle (the space
// grows), so it stops once it moved by less than startup_tolerance (0.1 %) in two steps
// in a row (one such step can be a pause of the climb between two groups of modes: the
// 3D block's moved by 0.28, 0.18, 0.07, ... % a step), the first step of a cycle
// excepted: there the quotient of the last Ritz vector repeats the last value. The 10 % padding of the stable step (EstimateStable) is the power
// iteration's, kept: docs/stability.md section 3 gives both estimates against the full
// spectrum. At most startup_limit evaluations (the power iteration's 60), restarted every
// krylov_cap steps from the Ritz vector.
PetscErrorCode TimeStepControl::StartupKrylov(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, const double *u0, const double *a0,
                                              double *lambda)
{
  PetscFunctionBegin;
  *lambda          = 0;
  PetscInt done    = 0, quiet = 0; // quiet: steps in a row that moved it by less than the tolerance
  bool     settled = false;
  while (!settled && done < startup_limit) {
    PetscCall(KrylovStart(comm));
    PetscInt steps     = 0;
    bool     exhausted = false;
    double   previous  = 0, found = 0;
    while (!settled && !exhausted && steps < krylov_size_ && done < startup_limit) {
      PetscCall(KrylovStep(comm, force, c33, u0, a0, steps, &found, &exhausted));
      ++steps, ++done;
      PetscCheck(std::isfinite(found), comm, PETSC_ERR_USER,
                 "Could not estimate a stable time step (a force evaluation near the rest state gave %g): check -material_mu, "
                 "-material_D and -material_density",
                 found);
      if (options_.monitor)
        PetscCall(PetscPrintf(comm, "stable-step estimate, Krylov step %" PetscInt_FMT ": largest Ritz value %.9e 1/s^2\n", done, found));
      *lambda = std::max(*lambda, found);
      quiet   = steps >= 2 && std::fabs(found - previous) <= startup_tolerance * std::fabs(found) ? quiet + 1 : 0;
      settled = quiet >= 2;
      // An invariant subspace (a body of a few points): the value is exact on it.
      settled = settled || (exhausted && steps < krylov_size_);
      previous = found;
    }
    KrylovFinish(steps);
  }
  PetscFunctionReturn(0);
}

// Cycles of as many steps as the basis holds, each from the last one's Ritz vector, the
// first from the warm start with the seed mixed in (with the step fixed at rest the warm
// start is the rest state's mode, which has next to nothing of a mode that rose
// elsewhere).
PetscErrorCode TimeStepControl::RestartedKrylov(MPI_Comm comm, ForceOperator &force, const std::vector<double> &c33, PetscInt iterations, double *best)
{
  double lambda = 0;

  PetscFunctionBegin;
  *best = 0;
  PetscCall(KrylovReserve(options_.max_iterations + 1));
  PetscCall(MixSeed(comm));
  for (PetscInt done = 0; done < iterations && std::isfinite(lambda);) {
    PetscCall(KrylovStart(comm));
    PetscInt steps     = 0;
    bool     exhausted = false;
    while (steps < krylov_size_ && done < iterations && !exhausted) {
      PetscCall(KrylovStep(comm, force, c33, u_rec_.data(), a_rec_.data(), steps, &lambda, &exhausted));
      ++steps, ++done;
      if (!std::isfinite(lambda)) break;
      *best = std::max(*best, lambda);
    }
    if (std::isfinite(lambda)) KrylovFinish(steps);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::Reference(MPI_Comm comm, ForceOperator &force, PetscInt step)
{
  PetscFunctionBegin;
  const std::vector<double> v = v_; // a measurement: allocation is fine
  const PetscInt evaluations = evaluations_;
  const std::vector<double> &committed = force.warm_start();
  double reference;
  PetscCall(RestartedKrylov(comm, force, committed, options_.reference, &reference));
  v_           = v;
  evaluations_ = evaluations;
  double bond = 0;
  PetscCall(BondIndicator(comm, force, &bond));
  PetscCall(PetscPrintf(comm, "reference after step %" PetscInt_FMT ": lambda_max %.6e 1/s^2 (%.4g x at rest), estimate in use %.6e (ratio %.4f), stiffest bond's Gent factor %.4g\n",
                        step, reference, reference / lambda_rest_, lambda_, lambda_ / reference, bond));
  PetscFunctionReturn(0);
}

// v <- v / |v| + seed_weight seed / |seed| (reproducible sums: the same on any number
// of ranks).
PetscErrorCode TimeStepControl::MixSeed(MPI_Comm comm)
{
  const PetscInt n = (PetscInt)v_.size();
  double         norm2[2];

  PetscFunctionBegin;
  for (PetscInt k = 0; k < n; ++k) sq_[k] = v_[k] * v_[k];
  PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), &norm2[0]));
  for (PetscInt k = 0; k < n; ++k) sq_[k] = seed_[k] * seed_[k];
  PetscCall(ReproducibleSum(comm, 1, n, sq_.data(), &norm2[1]));
  if (!(norm2[0] > 0) || !std::isfinite(norm2[0]) || !(norm2[1] > 0)) PetscFunctionReturn(0);
  const double a = 1.0 / std::sqrt(norm2[0]), b = (options_.krylov ? krylov_seed_weight : seed_weight) / std::sqrt(norm2[1]);
  for (PetscInt k = 0; k < n; ++k) v_[k] = a * v_[k] + b * seed_[k];
  PetscFunctionReturn(0);
}

// The iterations of one re-estimate (Reestimate decides the plan): the power
// iteration or the Krylov search, at least plan.fewest steps, then until the quotient
// settles or, at the base step, cannot move the step.
PetscErrorCode TimeStepControl::Iterate(MPI_Comm comm, ForceOperator &force, const std::vector<double> &committed,
                                        const IterationPlan &plan, double *lambda_out, PetscInt *iterations)
{
  PetscFunctionBegin;
  const bool     rising = plan.rising, at_base = plan.at_base, search = plan.search, near = plan.near;
  const double   threshold = plan.threshold;
  const PetscInt fewest    = plan.fewest;
  double       lambda = 0, previous = lambda_;
  double       last_change = 0;
  PetscInt     it     = 0;
  bool         exhausted = false;
  if (options_.krylov) PetscCall(KrylovStart(comm));
  while (it < options_.max_iterations && !exhausted) {
    if (options_.krylov) PetscCall(KrylovStep(comm, force, committed, u_rec_.data(), a_rec_.data(), it, &lambda, &exhausted));
    else PetscCall(PowerStep(comm, force, committed, nullptr, u_rec_.data(), a_rec_.data(), options_.shift * lambda_, &lambda));
    ++it;
    if (!std::isfinite(lambda)) break;
    const double change   = std::fabs(lambda - previous);
    bool         settled  = change <= options_.tolerance * std::fabs(lambda);
    // Rising: also the rest of the climb, were it to go on geometrically at the ratio
    // of the last two increments (from the third iteration: the first increment holds
    // the state's own change since the last estimate), must be within the tolerance.
    if (rising && it >= 3 && last_change > 0) {
      const double r = std::min(change / last_change, 0.95);
      settled        = settled && change * r / (1.0 - r) <= options_.tolerance * std::fabs(lambda);
    }
    last_change = change;
    const bool   harmless = at_base && it >= 2 && lambda + 10.0 * change < threshold;
    // With the kernel's indicator and no search, the warm start is the last Ritz vector
    // of a state that moved little: a first quotient within half the dead band of the
    // last estimate cannot move the step, and the second Krylov step (the one the
    // tolerance asks for as the state moved) adds 0.1 to 1 % (Jm = 8 plate).
    if (options_.bonds && !search && !near && it == 1 && change <= 0.5 * options_.band * std::fabs(lambda)) settled = true;
    previous              = lambda;
    if (it >= fewest && (settled || harmless)) break;
  }
  if (options_.krylov && std::isfinite(lambda)) KrylovFinish(it);
  *lambda_out = lambda;
  *iterations = it;
  PetscFunctionReturn(0);
}

} // namespace bapd
