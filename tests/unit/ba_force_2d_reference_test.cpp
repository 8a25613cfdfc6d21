// The kernel at D = 2 (ba_force.hpp, bond_geometry.hpp) against a reference
// written straight from the equations in this file: for every bond, K_ij and N_ij
// summed member by member over the intact BA family (eqs 8, 9), F = N K^{-1}, P from
// the model with no warm start, g = 1/2 phi_xi/phi C_i K^{-1} xi (eqs 11, 15, 23) plus
// the patch term, t = P g; the energy-consistent t_ip = omega_i S_ip xi_ip; the strain
// energy W_i. No masked sums, no "total minus the others", no lanes, no records: the
// reference shares only the families, the model and the bond state with the kernel.
//
// The comparison runs on a cut plate (hole, notch, broken bonds, a non-affine field)
// and covers both forms, the tensor and scalar corrections, two mask words, the
// plane-stress lane path and the patch correction. The families are checked by
// family_test.cpp (the cell search against a direct search, the BA masks, the notch).
// Bit-for-bit reproduction of the solver's results is compare_binaries.sh's job and the
// rank-invariance and restart tests'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bapd/core/materials/gent.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

using test::CutPlate;

// The reference quantities of bond q of point i (usable = false: no force).
struct ReferenceBond {
  bool   usable = false;
  Mat2   F{}, Kinv{};
  double volume = 0; // V(B)
};

// reference_family: as if every bond of t = 0 were intact (what C_i is formed from).
ReferenceBond reference_bond(const test::Discretisation &d, const std::vector<double> &y, std::size_t i,
                             std::size_t q, bool reference_family = false)
{
  const Families   &f      = d.families;
  const PointCloud &c      = d.cloud;
  auto              intact = [&](std::size_t p) { return reference_family || d.state.is_intact(i, p); };
  ReferenceBond     r;
  if (!intact(q)) return r;
  Mat2 K{}, N{};
  for (std::size_t p = 0; p < f.size(i); ++p) { // eqs 8, 9: the intact members of B_ij
    if (!((f.ba(f.offsets[i] + q)[p / 64] >> (p % 64)) & 1u) || !intact(p)) continue;
    const std::size_t k  = static_cast<std::size_t>(f.neighbour[f.offsets[i] + p]);
    const double      v  = c.volume[k];
    const double      x0 = c.x[2 * k] - c.x[2 * i], x1 = c.x[2 * k + 1] - c.x[2 * i + 1];
    const double      y0 = y[2 * k] - y[2 * i], y1 = y[2 * k + 1] - y[2 * i + 1];
    K = K + Mat2{x0 * x0 * v, x0 * x1 * v, x1 * x0 * v, x1 * x1 * v};
    N = N + Mat2{y0 * x0 * v, y0 * x1 * v, y1 * x0 * v, y1 * x1 * v};
    r.volume += v;
  }
  const double tr = K[0] + K[3];
  r.usable        = tr > 0 && det(K) > 1e-8 * tr * tr; // usable K (bond_geometry.hpp)
  if (!r.usable) return r;
  r.Kinv = inverse(K);
  r.F    = N * r.Kinv;
  return r;
}

// xi_ij = x_j - x_i of bond q of point i.
Vec2 bond_vector(const test::Discretisation &d, std::size_t i, std::size_t q)
{
  const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
  return {d.cloud.x[2 * j] - d.cloud.x[2 * i], d.cloud.x[2 * j + 1] - d.cloud.x[2 * i + 1]};
}

// g_ij = 1/2 phi_xi / phi K^{-1} xi (eq 23), uncorrected.
Vec2 reference_force_vector(const test::Discretisation &d, const ReferenceBond &r, std::size_t i, std::size_t q)
{
  const std::size_t j     = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
  const double      vh_i  = d.cloud.family_volume[i], vh_j = d.cloud.family_volume[j];
  const double      scale = 0.5 * (r.volume / vh_i) / (vh_i / (vh_i + vh_j)); // eqs 11, 15
  const Vec2        g     = r.Kinv * bond_vector(d, i, q);
  return {scale * g[0], scale * g[1]};
}

// C_i from M_i = sum_j g_ij (x) xi_ij V_j over the usable bonds of the reference family
// (every bond of t = 0 intact: breaking does not change C_i, bond_geometry.cpp).
Mat2 reference_correction(const test::Discretisation &d, std::size_t i, StressCorrection kind)
{
  Mat2 M{};
  for (std::size_t q = 0; q < d.families.size(i); ++q) {
    const ReferenceBond r = reference_bond(d, d.cloud.x, i, q, true);
    if (!r.usable) continue;
    const Vec2   g = reference_force_vector(d, r, i, q), xi = bond_vector(d, i, q);
    const double v = d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q])];
    M              = M + Mat2{g[0] * xi[0] * v, g[0] * xi[1] * v, g[1] * xi[0] * v, g[1] * xi[1] * v};
  }
  const double tr = M[0] + M[3];
  if (kind == StressCorrection::none || !(tr > 0) || !(det(M) > 1e-8 * tr * tr)) return identity2();
  if (kind == StressCorrection::scalar) return {2.0 / tr, 0.0, 0.0, 2.0 / tr};
  return inverse(M);
}

double max_abs_difference(const std::vector<double> &a, const std::vector<double> &b)
{
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// The reference bond forces (and c33) of every bond of the plate in the given form.
template <class Model>
void reference_forces(const test::Discretisation &d, const std::vector<double> &y, const Model &model, ForceForm form,
                      StressCorrection kind, std::vector<double> &t, std::vector<double> &c33)
{
  const Families &f = d.families;
  t.assign(2 * f.n_bonds(), 0.0);
  c33.assign(f.n_bonds(), 0.0);
  const std::vector<double> &lambda = d.cloud.patch_correction;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const std::size_t  o = f.offsets[i], m = f.size(i);
    const Mat2         C = reference_correction(d, i, kind);
    std::vector<Mat2>  stress(m, Mat2{}); // V_q P_q K_q^{-1} (energy-consistent)
    std::vector<bool>  energetic(m, false);
    double             volume = 0;
    for (std::size_t q = 0; q < m; ++q) {
      const ReferenceBond r = reference_bond(d, y, i, q);
      if (!r.usable) continue;
      double c = 0.0; // no warm start
      Mat2   P;
      ASSERT_EQ(model.stress(r.F, c, P), StressStatus::ok);
      c33[o + q] = c;
      const std::size_t j = static_cast<std::size_t>(f.neighbour[o + q]);
      if (form == ForceForm::bond_only) {
        Vec2 g = C * reference_force_vector(d, r, i, q);
        if (!lambda.empty()) { // h_ij = ((lambda_i - lambda_j) . xi) xi (patch_correction.hpp)
          const Vec2   xi = bond_vector(d, i, q);
          const double s  = (lambda[2 * i] - lambda[2 * j]) * xi[0] + (lambda[2 * i + 1] - lambda[2 * j + 1]) * xi[1];
          g               = {g[0] + s * xi[0], g[1] + s * xi[1]};
        }
        const Vec2 tb    = P * g;
        t[2 * (o + q)]     = tb[0];
        t[2 * (o + q) + 1] = tb[1];
      } else {
        const double vq = d.cloud.volume[j];
        const Mat2   M  = P * r.Kinv;
        stress[q]       = {vq * M[0], vq * M[1], vq * M[2], vq * M[3]};
        energetic[q]    = true;
        volume += vq;
      }
    }
    if (form == ForceForm::bond_only || volume == 0) continue;
    for (std::size_t p = 0; p < m; ++p) { // t_ip = omega_i S_ip xi_ip, S_ip over the q with p in B_iq
      if (!d.state.is_intact(i, p)) continue;
      Mat2 S{};
      for (std::size_t q = 0; q < m; ++q)
        if (energetic[q] && ((f.ba(o + p)[q / 64] >> (q % 64)) & 1u)) S = S + stress[q];
      const Vec2 tp      = S * bond_vector(d, i, p);
      t[2 * (o + p)]     = tp[0] / volume;
      t[2 * (o + p) + 1] = tp[1] / volume;
    }
  }
}

// The kernel's bond forces, c33, usable masks, C_i and strain energies against the
// reference. Tolerance: the two sum in different orders (the kernel may form a sum as
// the total minus the others), so they differ by round-off amplified by cond(K): bond
// forces measured at 2e-15 to 2e-14 of the largest (printed), asserted below 1e-12;
// C_i and energies, order-1 and sums of order-1 terms, below 1e-11. A wrong term, a
// correction or patch term left out, gives differences of order 1.
template <class Model>
void expect_reference_forces(CutPlate &c, const Model &model, ForceForm form, StressCorrection kind)
{
  test::Discretisation &d = c.d;
  d.geometry.stress_correction = kind;
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry);
  const std::size_t   nb = d.families.n_bonds(), n = d.size();
  std::vector<double> t(2 * nb, 7.0), c33(nb, 0.0), t_ref, c33_ref;
  nd::Workspace<2>    ws;
  const KernelStats   s = nd::compute_bond_forces<2>(form, model, d.cloud, c.y.data(), d.families, d.geometry, d.state,
                                                     c33.data(), t.data(), ws);
  ASSERT_TRUE(s.ok());
  EXPECT_GT(s.evaluated, 4000u); // not vacuous
  reference_forces(d, c.y, model, form, kind, t_ref, c33_ref);
  const double size = test::max_abs(t_ref);
  std::printf("%s, correction %s, %zu mask word(s): |t - t_ref| <= %.1e of max |t|, |c33 - c33_ref| <= %.1e\n",
              to_string(form), to_string(kind), d.families.mask_words, max_abs_difference(t, t_ref) / size,
              max_abs_difference(c33, c33_ref));
  EXPECT_LT(max_abs_difference(t, t_ref), 1e-12 * size) << to_string(form) << ", correction " << to_string(kind);
  EXPECT_LT(max_abs_difference(c33, c33_ref), 1e-11) << "c33 (order 1)";
  // usable bits: the reference's K test, bond by bond (margins of orders of magnitude)
  std::size_t usable = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const bool u = reference_bond(d, d.cloud.x, i, q).usable;
      ASSERT_EQ(d.geometry.is_usable(i, q), u) << "point " << i << " bond " << q;
      usable += u;
    }
  EXPECT_EQ(s.evaluated, usable); // the geometry is fresh: every usable bond evaluated
  // C_i (order 1): the same round-off argument
  for (std::size_t i = 0; i < n; ++i)
    EXPECT_LT(test::norm(d.geometry.correction_of(i) - reference_correction(d, i, kind)), 1e-11) << "point " << i;
  // strain energy per point: W_i = V_i sum_j Psi(F_ij) V_j / sum_j V_j
  std::vector<double> e(n);
  nd::strain_energy<2>(model, d.cloud, c.y.data(), d.families, d.geometry, d.state, nullptr, n, ws, nullptr, e.data());
  double worst = 0, largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double num = 0, den = 0;
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const ReferenceBond r = reference_bond(d, c.y, i, q);
      if (!r.usable) continue;
      double cq = 0.0, psi = 0.0;
      ASSERT_EQ(model.energy(r.F, cq, psi), StressStatus::ok);
      const double vj = d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q])];
      num += psi * vj;
      den += vj;
    }
    const double e_ref = den > 0 ? d.cloud.volume[i] * num / den : 0.0;
    worst              = std::max(worst, std::abs(e[i] - e_ref));
    largest            = std::max(largest, std::abs(e_ref));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(worst, 1e-11 * largest) << "strain energy";
}

MaterialParameters gel()
{
  MaterialParameters p; // the paper's hydrogel, K = 100 mu
  p.D = 2.0 / (100.0 * p.mu);
  return p;
}

TEST(Kernel2DReference, PlaneStrainGentBondOnlyForcesAreTheEquations)
{
  CutPlate c(20, 0.1, 11);
  ASSERT_GT(c.d.state.count_broken(c.d.families, c.d.size()), 500u);
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor, StressCorrection::scalar})
    expect_reference_forces(c, GentPlaneStrain{gel()}, ForceForm::bond_only, k);
}

TEST(Kernel2DReference, PlaneStrainGentEnergyConsistentForcesAreTheEquations)
{
  CutPlate c(20, 0.1, 12);
  expect_reference_forces(c, GentPlaneStrain{gel()}, ForceForm::energy_consistent, StressCorrection::none);
}

TEST(Kernel2DReference, TwoMaskWordsGiveTheEquations)
{
  // delta = 5.015 dx: 80 neighbours, two mask words (the kernel's Words = 2 path).
  CutPlate c(20, 0.1, 14, 5.015);
  ASSERT_EQ(c.d.families.mask_words, 2u);
  expect_reference_forces(c, GentPlaneStrain{gel()}, ForceForm::bond_only, StressCorrection::tensor);
  expect_reference_forces(c, GentPlaneStrain{gel()}, ForceForm::energy_consistent, StressCorrection::none);
}

TEST(Kernel2DReference, PlaneStressGentOnTheLanesGivesTheEquations)
{
  // The kernel runs PlaneStress lane_count bonds at a time (stress_lanes); the
  // reference calls the scalar stress() bond by bond.
  CutPlate c(16, 0.1, 13);
  expect_reference_forces(c, test::hydrogel(), ForceForm::bond_only, StressCorrection::tensor);
  expect_reference_forces(c, test::hydrogel(), ForceForm::energy_consistent, StressCorrection::none);
}

TEST(Kernel2DReference, PatchCorrectionAddsItsTermToTheForceVector)
{
  // -force_patch_correction: h_ij = ((lambda_i - lambda_j) . xi) xi added to g_ij
  // (patch_correction.hpp). The kernel only reads lambda, so any lambda exercises
  // its line; a field with both signs, sized so that h is of the order of g for an
  // interior bond (|g| ~ 1 / (m V dx), |h| ~ |lambda| dx^2, m ~ 28 members): it moves
  // the bond forces by about 1 % of the largest (an edge bond's).
  CutPlate            c(20, 0.1, 16);
  const std::size_t   n = c.d.size(), nb = c.d.families.n_bonds();
  const double        scale = 1.0 / (28.0 * std::pow(test::kPlateDx, 5));
  std::vector<double> t0(2 * nb), t1(2 * nb);
  nd::Workspace<2>    ws;
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor}) {
    c.d.geometry.stress_correction = k;
    nd::compute_bond_geometry<2>(c.d.cloud, c.d.families, c.d.state, c.d.geometry);
    c.d.cloud.patch_correction.clear();
    nd::compute_bond_forces<2>(ForceForm::bond_only, GentPlaneStrain{gel()}, c.d.cloud, c.y.data(), c.d.families,
                               c.d.geometry, c.d.state, nullptr, t0.data(), ws);
    c.d.cloud.patch_correction.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      c.d.cloud.patch_correction[2 * i]     = scale * std::sin(0.7 * static_cast<double>(i));
      c.d.cloud.patch_correction[2 * i + 1] = scale * std::cos(1.3 * static_cast<double>(i));
    }
    nd::compute_bond_forces<2>(ForceForm::bond_only, GentPlaneStrain{gel()}, c.d.cloud, c.y.data(), c.d.families,
                               c.d.geometry, c.d.state, nullptr, t1.data(), ws);
    EXPECT_GT(max_abs_difference(t1, t0), 1e-3 * test::max_abs(t0)) << "lambda changes the forces (not vacuous)";
    expect_reference_forces(c, GentPlaneStrain{gel()}, ForceForm::bond_only, k);
    expect_reference_forces(c, test::hydrogel(), ForceForm::bond_only, k); // the lane path
  }
}

} // namespace
} // namespace bapd
