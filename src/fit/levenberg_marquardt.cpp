// Levenberg-Marquardt (levenberg_marquardt.hpp).
#include "levenberg_marquardt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bapd::fit {

bool solve_dense(std::vector<std::vector<double>> A, std::vector<double> b, std::vector<double> &x)
{
  const std::size_t n = b.size();
  double            norm = 0.0;
  for (const auto &row : A)
    for (double v : row) norm = std::max(norm, std::abs(v));
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t piv = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[piv][k])) piv = i;
    if (!(std::abs(A[piv][k]) > 1e-14 * norm)) return false;
    std::swap(A[k], A[piv]);
    std::swap(b[k], b[piv]);
    for (std::size_t i = k + 1; i < n; ++i) {
      const double f = A[i][k] / A[k][k];
      for (std::size_t j = k; j < n; ++j) A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  x.assign(n, 0.0);
  for (std::size_t k = n; k-- > 0;) {
    double v = b[k];
    for (std::size_t j = k + 1; j < n; ++j) v -= A[k][j] * x[j];
    x[k] = v / A[k][k];
  }
  return true;
}

namespace {

double squared_norm(const std::vector<double> &r)
{
  double s = 0.0;
  for (double v : r) s += v * v;
  return s;
}

// J[i][j] = d r_i / d p_j by central differences, one-sided where one side is undefined.
bool jacobian(const Residuals &res, const std::vector<double> &p, const std::vector<double> &r0,
              const std::vector<double> &scale, std::vector<std::vector<double>> &J)
{
  const std::size_t n = p.size(), m = r0.size();
  J.assign(m, std::vector<double>(n, 0.0));
  std::vector<double> rp(m), rm(m);
  for (std::size_t j = 0; j < n; ++j) {
    const double h  = 1e-6 * std::max(std::abs(p[j]), scale[j]);
    auto         pp = p, pm = p;
    pp[j] += h;
    pm[j] -= h;
    const bool up = res(pp, rp), down = res(pm, rm);
    if (!up && !down) return false;
    for (std::size_t i = 0; i < m; ++i)
      J[i][j] = up && down ? (rp[i] - rm[i]) / (pp[j] - pm[j]) : up ? (rp[i] - r0[i]) / (pp[j] - p[j]) : (r0[i] - rm[i]) / (p[j] - pm[j]);
  }
  return true;
}

} // namespace

LeastSquaresResult levenberg_marquardt(const Residuals &res, std::vector<double> p, const std::vector<double> &scale,
                                       std::size_t m, int max_iterations)
{
  LeastSquaresResult out;
  const std::size_t  n = p.size();
  std::vector<double> r(m), r_trial(m);
  if (!res(p, r)) {
    out.why = "the model is not defined at the starting point";
    out.p   = p;
    return out;
  }
  double                           cost = squared_norm(r), damping = 1e-3;
  std::vector<std::vector<double>> J, A(n, std::vector<double>(n));
  std::vector<double>              g(n), step;
  int                              small_steps = 0;
  for (int it = 1; it <= max_iterations; ++it) {
    out.iterations = it;
    if (!jacobian(res, p, r, scale, J)) {
      out.why = "the model is undefined on both sides of the current point";
      break;
    }
    for (std::size_t a = 0; a < n; ++a) {
      g[a] = 0.0;
      for (std::size_t i = 0; i < m; ++i) g[a] += J[i][a] * r[i];
      for (std::size_t b = 0; b < n; ++b) {
        A[a][b] = 0.0;
        for (std::size_t i = 0; i < m; ++i) A[a][b] += J[i][a] * J[i][b];
      }
    }
    bool accepted = false;
    while (damping < 1e16) {
      auto M = A;
      for (std::size_t a = 0; a < n; ++a) M[a][a] += damping * std::max(A[a][a], 1e-30);
      std::vector<double> minus_g(n);
      for (std::size_t a = 0; a < n; ++a) minus_g[a] = -g[a];
      if (solve_dense(M, minus_g, step)) {
        auto trial = p;
        for (std::size_t a = 0; a < n; ++a) trial[a] += step[a];
        if (res(trial, r_trial)) {
          const double trial_cost = squared_norm(r_trial);
          if (trial_cost <= cost) {
            // converged when the step no longer moves any parameter (relative 1e-10 of
            // its size) or the cost stops falling (relative 1e-14), twice in a row
            bool small = cost - trial_cost <= 1e-14 * cost;
            bool tiny  = true;
            for (std::size_t a = 0; a < n; ++a) tiny &= std::abs(step[a]) <= 1e-10 * std::max(std::abs(p[a]), scale[a]);
            small_steps = (small || tiny) ? small_steps + 1 : 0;
            p           = trial;
            r           = r_trial;
            cost        = trial_cost;
            damping     = std::max(damping / 3.0, 1e-12);
            accepted    = true;
            break;
          }
        }
      }
      damping *= 4.0;
    }
    if (!accepted) {
      // no step lowers the cost at any damping: a minimum to round-off if the gradient
      // is negligible there (relative to |J| |r|)
      double gn = 0.0, jn = 0.0;
      for (std::size_t a = 0; a < n; ++a) gn += g[a] * g[a], jn += A[a][a];
      out.converged = gn <= 1e-16 * jn * cost + std::numeric_limits<double>::min();
      if (!out.converged) out.why = "no step lowers the misfit, yet the gradient is not zero";
      break;
    }
    if (small_steps >= 2) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged && out.why.empty()) out.why = "no convergence in " + std::to_string(max_iterations) + " iterations";
  out.p         = p;
  out.residuals = r;
  out.cost      = cost;
  // covariance at the optimum, with J there
  if (jacobian(res, p, r, scale, J)) {
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) {
        A[a][b] = 0.0;
        for (std::size_t i = 0; i < m; ++i) A[a][b] += J[i][a] * J[i][b];
      }
    const double s2 = m > n ? cost / static_cast<double>(m - n) : std::numeric_limits<double>::quiet_NaN();
    out.covariance.assign(n, std::vector<double>(n, 0.0));
    out.standard_error.assign(n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t b = 0; b < n; ++b) {
      std::vector<double> e(n, 0.0), col;
      e[b] = 1.0;
      if (!solve_dense(A, e, col)) {
        out.singular = true;
        break;
      }
      for (std::size_t a = 0; a < n; ++a) out.covariance[a][b] = s2 * col[a];
    }
    if (!out.singular)
      for (std::size_t a = 0; a < n; ++a) out.standard_error[a] = std::sqrt(std::max(out.covariance[a][a], 0.0));
  } else out.singular = true;
  return out;
}

} // namespace bapd::fit
