#pragma once
// Fields derived for output from a point's Cauchy stress and deformation gradient
// (point_quantities.hpp forms both): what a user looks for first in ParaView.
//   von Mises stress     sigma_vm = sqrt(3/2 s : s), s the deviator of sym(sigma)
//                        (sigma_i = P_i F_i^T / J_i is symmetric only up to the
//                        averaging of the bond stresses, so its symmetric part is
//                        taken). D = 2: sigma_33 = 0, exact in plane stress; in plane
//                        strain sigma_33 is not formed, and the value is that of the
//                        in-plane components alone.
//   principal stretches  the eigenvalues of U = sqrt(F^T F) (the singular values of F),
//                        three a point. D = 2: the two in-plane ones of F~, largest
//                        first, then the thickness stretch lambda_3 (sqrt(C33); 1 in
//                        plane strain). D = 3: all three, largest first.
// Plain arithmetic, no allocation; header-only, so that the unit tests check it alone.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>

namespace bapd {

// sigma: D x D, row-major.
template <int D> double von_mises_stress(const double *sigma)
{
  double s[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; // sym(sigma), 0 out of plane in 2D
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) s[r][c] = 0.5 * (sigma[D * r + c] + sigma[D * c + r]);
  const double mean = (s[0][0] + s[1][1] + s[2][2]) / 3.0;
  for (int k = 0; k < 3; ++k) s[k][k] -= mean;
  double contraction = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) contraction += s[r][c] * s[r][c];
  return std::sqrt(1.5 * contraction);
}

// F: D x D, row-major; lambda_3: the thickness stretch (D = 2 only). stretch[3] gets
// the principal stretches as described above.
template <int D> void principal_stretches(const double *F, double lambda_3, double stretch[3])
{
  // C = F^T F, symmetric.
  double C[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c)
      for (int k = 0; k < D; ++k) C[r][c] += F[D * k + r] * F[D * k + c];
  double eigen[3] = {0, 0, 0};
  if constexpr (D == 2) {
    // Closed form of a symmetric 2 x 2: mean +- radius, radius by hypot (no cancellation
    // inside the root).
    const double mean = 0.5 * (C[0][0] + C[1][1]), radius = std::hypot(0.5 * (C[0][0] - C[1][1]), C[0][1]);
    eigen[0] = mean + radius;
    eigen[1] = std::max(0.0, mean - radius);
  } else {
    // Cyclic Jacobi rotations: each zeroes one off-diagonal term; quadratic
    // convergence, to round-off within a handful of sweeps.
    for (int sweep = 0; sweep < 50; ++sweep) {
      const double off = C[0][1] * C[0][1] + C[0][2] * C[0][2] + C[1][2] * C[1][2];
      const double diagonal = C[0][0] * C[0][0] + C[1][1] * C[1][1] + C[2][2] * C[2][2];
      if (!(off > 1e-36 * diagonal)) break; // (NaN stops too)
      for (int p = 0; p < 2; ++p)
        for (int q = p + 1; q < 3; ++q) {
          if (C[p][q] == 0.0) continue;
          const double theta = (C[q][q] - C[p][p]) / (2.0 * C[p][q]);
          const double t     = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
          const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
          for (int k = 0; k < 3; ++k) { // C <- C J (columns p, q)
            const double kp = C[k][p], kq = C[k][q];
            C[k][p] = c * kp - s * kq;
            C[k][q] = s * kp + c * kq;
          }
          for (int k = 0; k < 3; ++k) { // C <- J^T C (rows p, q)
            const double pk = C[p][k], qk = C[q][k];
            C[p][k] = c * pk - s * qk;
            C[q][k] = s * pk + c * qk;
          }
        }
    }
    for (int k = 0; k < 3; ++k) eigen[k] = std::max(0.0, C[k][k]);
    std::sort(eigen, eigen + 3, std::greater<double>());
  }
  for (int k = 0; k < D; ++k) stretch[k] = std::sqrt(eigen[k]);
  if constexpr (D == 2) stretch[2] = lambda_3;
}

// Both fields for points [0, n): cauchy and F D x D each a point, lambda_3 one a point
// (D = 2; nullptr: 1); von_mises one, stretch three a point.
template <int D>
void derived_fields(std::size_t n, const double *cauchy, const double *F, const double *lambda_3, double *von_mises, double *stretch)
{
  for (std::size_t i = 0; i < n; ++i) {
    von_mises[i] = von_mises_stress<D>(cauchy + D * D * i);
    principal_stretches<D>(F + D * D * i, D == 2 && lambda_3 ? lambda_3[i] : 1.0, stretch + 3 * i);
  }
}

} // namespace bapd
