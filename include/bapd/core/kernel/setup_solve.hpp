#pragma once
// The small dense linear algebra of the patch-correction setup solves
// (patch_correction.cpp): preconditioned conjugate gradients and the inverse of a
// symmetric positive-definite block. One thread, in index order: the same bits on
// every run.
#include <cmath>
#include <cstddef>
#include <vector>

namespace bapd::setup_solve {

inline double dot(const std::vector<double> &a, const std::vector<double> &b)
{
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// x (0 on entry) solving A x = b by preconditioned conjugate gradients to round-off,
// ||r|| <= 1e-14 ||b||, at most `most` iterations; one thread, in index order, so the
// same bits on every run. apply(p, q): q = A p; precondition(r, z): z = M^-1 r. Returns
// the iterations taken; *residual: ||r|| / ||b|| at the end (the recurrence's r).
template <class Apply, class Precondition>
std::size_t conjugate_gradients(const Apply &apply, const Precondition &precondition, const std::vector<double> &b,
                                std::vector<double> &x, std::size_t most, double *residual)
{
  std::vector<double> r = b, z(b.size()), p(b.size()), q(b.size());
  precondition(r, z);
  p                  = z;
  double       rz    = dot(r, z);
  const double bnorm = std::sqrt(dot(b, b));
  std::size_t  it    = 0;
  for (; it < most && std::sqrt(dot(r, r)) > 1e-14 * bnorm; ++it) {
    apply(p, q);
    const double pq = dot(p, q);
    if (!(pq > 0.0)) break; // (A is positive definite: only at round-off)
    const double alpha = rz / pq;
    for (std::size_t k = 0; k < b.size(); ++k) {
      x[k] += alpha * p[k];
      r[k] -= alpha * q[k];
    }
    precondition(r, z);
    const double rz_next = dot(r, z), beta = rz_next / rz;
    rz                   = rz_next;
    for (std::size_t k = 0; k < b.size(); ++k) p[k] = z[k] + beta * p[k];
  }
  *residual = bnorm > 0.0 ? std::sqrt(dot(r, r)) / bnorm : 0.0;
  return it;
}

// The largest block inverted below: the virial solve's (D + D(D+1)/2)^2 in 3D.
constexpr std::size_t kLargestBlock = 9;

// The inverse of the symmetric positive-definite m x m block a (m <= kLargestBlock),
// in place, by Gauss-Jordan (no pivoting needed: SPD).
inline bool invert_block(double *a, std::size_t m)
{
  double inv[kLargestBlock * kLargestBlock] = {};
  for (std::size_t k = 0; k < m; ++k) inv[k * m + k] = 1.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double piv = a[k * m + k];
    if (!(piv > 0.0)) return false;
    for (std::size_t l = 0; l < m; ++l) {
      a[k * m + l] /= piv;
      inv[k * m + l] /= piv;
    }
    for (std::size_t r = 0; r < m; ++r) {
      if (r == k) continue;
      const double f = a[r * m + k];
      for (std::size_t l = 0; l < m; ++l) {
        a[r * m + l] -= f * a[k * m + l];
        inv[r * m + l] -= f * inv[k * m + l];
      }
    }
  }
  for (std::size_t k = 0; k < m * m; ++k) a[k] = inv[k];
  return true;
}

} // namespace bapd::setup_solve
