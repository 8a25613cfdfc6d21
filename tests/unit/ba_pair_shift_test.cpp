// The pair symmetry of BA families (docs/notes/performance-kernel-3.md 1i): what one masked
// sum per pair would rest on, held to the code's family definition.
//
// For a bond (i -> j) the kernel sums over B_ij = the members k of H_i whose BA bit is
// set (|x_k - x_j| within reach: build_families), intact for i; j itself is one of them
// and i is not in H_i. So B_ij = (C + {j}) and B_ji = (C' + {i}) with C, C' the common
// members H_i and H_j intact for i, resp. for j, and the weights are V_k alone (eqs 8,
// 9). Where C = C', the sums of (j -> i) follow from those of (i -> j) by moving the
// origin from x_i to x_j with the zeroth and first moments over C (xi = x_j - x_i,
// eta = y_j - y_i, d_k = x_k - x_i, e_k = y_k - y_i):
//   K_ji = M2 - m1 xi^T - xi m1^T + (m0 + V_i) xi xi^T
//   N_ji = N  - n1 xi^T - eta m1^T + (m0 + V_i) eta xi^T
// exactly in exact arithmetic, to round-off in floating point (not bit for bit: why the
// kernel does not use it, docs/notes/performance-kernel-3.md 1i). Where bonds are broken, C != C' for
// some pairs and the shift is wrong: the test checks that too, so that it shows the
// condition is needed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "bapd/core/kernel/ba_force.hpp"
#include "unit/kernel_fixtures.hpp"

namespace bapd {
namespace {

struct Sums {
  double K[3] = {}; // xx, xy, yy
  double N[4] = {}; // row-major
  double m0 = 0, m1[2] = {}, n1[2] = {};
  std::vector<std::size_t> members; // in family (natural id) order
};

double rel_diff(const double *a, const double *b, int n)
{
  double d = 0, s = 0;
  for (int k = 0; k < n; ++k) {
    d = std::max(d, std::abs(a[k] - b[k]));
    s = std::max(s, std::abs(b[k]));
  }
  return d / s;
}

TEST(BaPairShift, ShiftedSumsOfTheReverseBondEqualTheDirectOnesWhereBothHoldTheSameMembers)
{
  test::CutPlate            plate(16, 0.2, 11);
  const test::Discretisation &d = plate.d;
  const Families            &fam = d.families;
  const double              *x = d.cloud.x.data(), *y = plate.y.data(), *V = d.cloud.volume.data();
  const std::size_t          W = fam.mask_words;
  auto member = [&](std::size_t i, std::size_t p) { return static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + p]); };
  auto ba_bit = [&](std::size_t i, std::size_t q, std::size_t p) {
    return (fam.ba_mask[(fam.offsets[i] + q) * W + p / 64] >> (p % 64)) & 1u;
  };
  // Direct sums of bond (i -> j = member q) over B_ij, origin x_i, and the moments over
  // the members other than j.
  auto direct = [&](std::size_t i, std::size_t q, Sums &all, Sums &common) {
    const std::size_t j = member(i, q);
    for (std::size_t p = 0; p < fam.size(i); ++p) {
      if (!ba_bit(i, q, p) || !d.state.is_intact(i, p)) continue;
      const std::size_t k = member(i, p);
      const double      dk[2] = {x[2 * k] - x[2 * i], x[2 * k + 1] - x[2 * i + 1]};
      const double      ek[2] = {y[2 * k] - y[2 * i], y[2 * k + 1] - y[2 * i + 1]};
      for (Sums *s : {&all, &common}) {
        if (s == &common && k == j) continue;
        s->K[0] += dk[0] * dk[0] * V[k];
        s->K[1] += dk[0] * dk[1] * V[k];
        s->K[2] += dk[1] * dk[1] * V[k];
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) s->N[2 * r + c] += ek[r] * dk[c] * V[k];
        s->m0 += V[k];
        s->members.push_back(k);
        for (int r = 0; r < 2; ++r) {
          s->m1[r] += dk[r] * V[k];
          s->n1[r] += ek[r] * V[k];
        }
      }
    }
  };
  std::size_t shared = 0, differing = 0;
  double      worst_shared = 0, best_differing = 1e300;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < fam.size(i); ++q) {
      const std::size_t b = fam.offsets[i] + q, j = member(i, q);
      if (j <= i || !d.state.is_intact(i, q)) continue;
      const std::size_t r = static_cast<std::size_t>(fam.reverse[b]) - fam.offsets[j];
      ASSERT_TRUE(d.state.is_intact(j, r)); // break_bond breaks both directions
      Sums ij, c_ij, ji, c_ji;
      direct(i, q, ij, c_ij);
      direct(j, r, ji, c_ji);
      // The kernel's F_ij is N_ij K_ij^{-1} of these sums: the test's B_ij is the code's.
      if (d.geometry.is_usable(i, q)) {
        const Mat2   F   = nd::bond_deformation_gradient<2>(d.cloud, y, fam, d.geometry, d.state, i, q);
        const double det = ij.K[0] * ij.K[2] - ij.K[1] * ij.K[1];
        const double Ki[3] = {ij.K[2] / det, -ij.K[1] / det, ij.K[0] / det};
        const double Fd[4] = {ij.N[0] * Ki[0] + ij.N[1] * Ki[1], ij.N[0] * Ki[1] + ij.N[1] * Ki[2],
                              ij.N[2] * Ki[0] + ij.N[3] * Ki[1], ij.N[2] * Ki[1] + ij.N[3] * Ki[2]};
        ASSERT_LT(rel_diff(F.data(), Fd, 4), 1e-12) << "bond " << i << " -> " << j;
      }
      // Shift i's common sums to j's origin: xi = x_j - x_i, and x_i - x_j = -xi.
      const double xi[2]  = {x[2 * j] - x[2 * i], x[2 * j + 1] - x[2 * i + 1]};
      const double eta[2] = {y[2 * j] - y[2 * i], y[2 * j + 1] - y[2 * i + 1]};
      const double w      = c_ij.m0 + V[i];
      const double K[3]   = {c_ij.K[0] - 2 * c_ij.m1[0] * xi[0] + w * xi[0] * xi[0],
                             c_ij.K[1] - c_ij.m1[0] * xi[1] - xi[0] * c_ij.m1[1] + w * xi[0] * xi[1],
                             c_ij.K[2] - 2 * c_ij.m1[1] * xi[1] + w * xi[1] * xi[1]};
      double N[4];
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c)
          N[2 * a + c] = c_ij.N[2 * a + c] - c_ij.n1[a] * xi[c] - eta[a] * c_ij.m1[c] + w * eta[a] * xi[c];
      // The same common members on both sides (i's intact bonds into C and j's)?
      const bool   same = c_ij.members == c_ji.members;
      const double diff = std::max(rel_diff(K, ji.K, 3), rel_diff(N, ji.N, 4));
      if (same) {
        ++shared;
        worst_shared = std::max(worst_shared, diff);
      } else {
        ++differing;
        best_differing = std::min(best_differing, diff);
      }
    }
  // The plate has broken bonds (every 5th of every 3rd point), a hole, a notch and
  // edges: both kinds of pair occur.
  EXPECT_GT(shared, 300u) << differing; // 376 on this 16 x 16 plate
  EXPECT_GT(differing, 10u);
  EXPECT_LT(worst_shared, 1e-13) << shared << " pairs with the same common members";
  // Where one side has lost a bond to a common member, the shift of its sums is wrong.
  EXPECT_GT(best_differing, 1e-3) << differing << " pairs whose common members differ";
}

} // namespace
} // namespace bapd
