#pragma once
// A small Levenberg-Marquardt least-squares solver (Marquardt 1963, with Marquardt's
// diagonal scaling; Nocedal & Wright section 10.3): minimise 1/2 |r(p)|^2 over p.
// The Jacobian is by central differences (step 1e-6 of each parameter's scale). A trial
// point where the model is not defined (r returns false: a law locked at a data point,
// an inadmissible parameter) is treated as a rejected step. Dense normal equations: the
// laws have at most a handful of parameters.
//
// At the optimum the covariance of p is s^2 (J^T J)^{-1}, s^2 = |r|^2 / (m - n) (the
// residual variance; Bates & Watts, Nonlinear regression, section 2.3).
#include <functional>
#include <string>
#include <vector>

namespace bapd::fit {

using Residuals = std::function<bool(const std::vector<double> &p, std::vector<double> &r)>;

struct LeastSquaresResult {
  std::vector<double>              p;
  std::vector<std::vector<double>> covariance; // s^2 (J^T J)^{-1}
  std::vector<double>              standard_error;
  std::vector<double>              residuals;  // r at p
  double                           cost       = 0.0; // |r|^2
  int                              iterations = 0;
  bool                             converged  = false;
  bool                             singular   = false; // J^T J not invertible at p
  std::string                      why;                // when not converged
};

// m: the number of residuals; scale: each parameter's typical size (> 0).
LeastSquaresResult levenberg_marquardt(const Residuals &r, std::vector<double> p0, const std::vector<double> &scale,
                                       std::size_t m, int max_iterations = 500);

// Solves A x = b (n x n, Gaussian elimination with partial pivoting); false if singular.
bool solve_dense(std::vector<std::vector<double>> A, std::vector<double> b, std::vector<double> &x);

} // namespace bapd::fit
