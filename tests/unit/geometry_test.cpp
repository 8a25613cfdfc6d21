// The geometry stage and non-uniform points (geometry.hpp): the lattice producer, given
// points with their own volumes and horizons, element centroids, the "either horizon
// reaches" bond rule, and the kernel's checks of docs/method.md sections 2-3 on a jittered
// and on a graded cloud: exact F under affine motion, stress consistency of the tensor
// correction, phi (eq 11) and phi_xi with unequal volumes, linear momentum (both forms),
// and the affine patch test with -force_patch_correction (patch_correction.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/core/kernel/patch_correction.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

constexpr double kDx = 0.5e-3, kThickness = 3.0e-3, kFactor = 3.015;

// An n x n lattice of spacing kDx, each point moved by up to `jitter` x kDx in x and y
// and given a volume kDx^2 t (1 +- spread): unequal volumes, irregular positions.
Body<2> jittered_body(int n, double jitter, double spread = 0.3, unsigned seed = 7)
{
  Body<2>       body = test::plate(n, n, kDx, kThickness);
  GivenPoints  g;
  std::mt19937 rng(seed);
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix) {
      g.x.push_back((ix + 0.5 + test::random_between(rng, -jitter, jitter)) * kDx);
      g.x.push_back((iy + 0.5 + test::random_between(rng, -jitter, jitter)) * kDx);
      g.volume.push_back(kDx * kDx * kThickness * (1.0 + test::random_between(rng, -spread, spread)));
    }
  body.given_points = std::make_shared<GivenPoints>(g);
  return body;
}

// A graded grid: x = X(s), y = X(t) at the cell centres of a uniform n x n grid in (s, t)
// in [0, 1]^2, X(s) = L (s + a s^2) / (1 + a): the spacing grows (1 + 2a) / 1 = 3 times
// from one side to the other (a = 1). Volume = the cell's image, X'(s) X'(t) ds^2 t.
Body<2> graded_body(int n, double a = 1.0)
{
  const double L = n * kDx, ds = 1.0 / n;
  auto         X  = [&](double s) { return L * (s + a * s * s) / (1.0 + a); };
  auto         dX = [&](double s) { return L * (1.0 + 2.0 * a * s) / (1.0 + a); };
  Body<2>       body = test::plate(n, n, kDx, kThickness);
  GivenPoints  g;
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix) {
      const double s = (ix + 0.5) * ds, t = (iy + 0.5) * ds;
      g.x.push_back(X(s));
      g.x.push_back(X(t));
      g.volume.push_back(dX(s) * dX(t) * ds * ds * kThickness);
    }
  body.given_points = std::make_shared<GivenPoints>(g);
  return body;
}

// The bond forces t and force densities f of the affine motion y = A X (Saint
// Venant-Kirchhoff, bond-only), and the P of A: the one stress of every bond.
Mat2 affine_forces(test::Discretisation &d, const Mat2 &A, std::vector<double> &t, std::vector<double> &f)
{
  test::SaintVenantKirchhoff2D svk;
  double                       c33 = 0;
  Mat2                         P;
  EXPECT_EQ(svk.stress(A, c33, P), StressStatus::ok);
  d.forces(svk, d.affine(A), t, f);
  return P;
}

TEST(GeometryStage, LatticeProducerIsMakeLatticeBitForBit)
{
  Body<2> body = test::plate(17, 11, kDx, kThickness);
  body.holes.push_back({8.3 * kDx, 5.1 * kDx, 2.6 * kDx});
  const PointCloud a = make_points(body, kFactor), b = make_lattice(body);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.natural_id, b.natural_id);
  EXPECT_TRUE(a.horizon.empty()); // the one horizon of build_families
  EXPECT_EQ(body_point_count(body), static_cast<int64_t>(a.size()));
}

TEST(GeometryStage, GivenPointsKeepTheirOrderVolumesAndOwnHorizons)
{
  Body<2>      body = test::plate(10, 10, kDx, kThickness);
  GivenPoints g;
  g.x      = {1e-3, 1e-3, 2.5e-3, 2.5e-3, 4e-3, 1e-3, 2e-3, 4e-3};
  g.volume = {1e-9, 2e-9, 3e-9, 4e-9};
  body.holes.push_back({2.5e-3, 2.5e-3, 0.2e-3}); // removes the second point
  body.given_points        = std::make_shared<GivenPoints>(g);
  const PointCloud c       = make_points(body, kFactor);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(body_point_count(body), 3);
  const std::size_t kept[3] = {0, 2, 3};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(c.natural_id[k], static_cast<int64_t>(k)); // compact, in the given order
    EXPECT_EQ(c.x[2 * k], g.x[2 * kept[k]]);
    EXPECT_EQ(c.volume[k], g.volume[kept[k]]);
    EXPECT_EQ(c.horizon[k], kFactor * std::sqrt(g.volume[kept[k]] / kThickness)); // delta_i = factor sqrt(V_i / t)
  }
  EXPECT_EQ(smallest_spacing(g, kThickness), std::sqrt(1e-9 / kThickness));
}

TEST(ElementCentroids, QuadrangleIsOnePointAtItsAreaCentroid)
{
  // A trapezoid (0,0) (2,0) (1,1) (0,1) split as Gmsh's reader splits a quadrangle,
  // then a lone triangle: two elements.
  TriangleSet t;
  t.corners = {0, 0, 2, 0, 1, 1, /**/ 0, 0, 1, 1, 0, 1, /**/ 3, 0, 4, 0, 3, 1};
  t.element = {0, 0, 1};
  const GivenPoints g = element_centroids(t, 2.0);
  ASSERT_EQ(g.size(), 2u);
  // The unit square (area 1, centroid (1/2, 1/2)) plus the triangle (1,0) (2,0) (1,1)
  // (area 1/2, centroid (4/3, 1/3)): area 3/2, centroid (7/9, 4/9).
  EXPECT_NEAR(g.x[0], 7.0 / 9.0, 1e-15);
  EXPECT_NEAR(g.x[1], 4.0 / 9.0, 1e-15);
  EXPECT_DOUBLE_EQ(g.volume[0], 1.5 * 2.0); // area x thickness
  EXPECT_NEAR(g.x[2], 10.0 / 3.0, 1e-15);
  EXPECT_NEAR(g.x[3], 1.0 / 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(g.volume[1], 0.5 * 2.0);
}

TEST(NonUniformFamilies, BondWhereEitherHorizonReachesAndBaFamiliesAreTheOverlap)
{
  const Body<2>     body  = graded_body(16);
  const PointCloud cloud = make_points(body, kFactor);
  const Families   fam   = build_families(cloud, cloud.size(), 1.0, {});
  const std::size_t n    = cloud.size();
  auto d2 = [&](std::size_t a, std::size_t b) {
    const double e0 = cloud.x[2 * b] - cloud.x[2 * a], e1 = cloud.x[2 * b + 1] - cloud.x[2 * a + 1];
    return e0 * e0 + e1 * e1;
  };
  auto bonded = [&](std::size_t a, std::size_t b) {
    const double r = std::max(cloud.horizon[a], cloud.horizon[b]);
    return a != b && d2(a, b) <= r * r;
  };
  std::size_t beyond_own = 0; // bonds that only the neighbour's horizon reaches
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::size_t> expected;
    for (std::size_t j = 0; j < n; ++j)
      if (bonded(i, j)) expected.push_back(j), beyond_own += d2(i, j) > cloud.horizon[i] * cloud.horizon[i];
    ASSERT_EQ(fam.size(i), expected.size()) << "point " << i;
    for (std::size_t q = 0; q < fam.size(i); ++q) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + q]);
      ASSERT_EQ(j, expected[q]); // natural id = index here: sorted the same way
      for (std::size_t p = 0; p < fam.size(i); ++p) {
        const std::size_t k    = static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + p]);
        const bool        in_b = (fam.ba(fam.offsets[i] + q)[p / 64] >> (p % 64)) & 1u;
        ASSERT_EQ(in_b, k == j || bonded(j, k)) << "bond " << i << "-" << j << " member " << k; // B_ij = H_i ∩ H_j + j
      }
    }
  }
  EXPECT_GT(beyond_own, 100u); // the grading makes the rule matter
  EXPECT_EQ(fam.horizon, *std::max_element(cloud.horizon.begin(), cloud.horizon.end()));
}

class NonUniformCloud : public ::testing::TestWithParam<const char *> {
protected:
  Body<2> body() const { return std::string(GetParam()) == "jittered" ? jittered_body(20, 0.25) : graded_body(20); }
};

TEST_P(NonUniformCloud, AffineMotionGivesExactDeformationGradientOnEveryUsableBond)
{
  test::Discretisation d(make_points(body(), kFactor));
  const Mat2           A = test::rotation(30.0) * Mat2{2.0, 0.4, 0.0, 1.2};
  const std::vector<double> y = d.affine(A, 1e-3, -2e-3);
  std::size_t  usable = 0;
  const double worst  = test::worst_affine_gradient_error(d, y, A, &usable);
  EXPECT_EQ(usable, d.families.n_bonds()); // every K regular: each family holds its own horizon's disc
  // F = (A K) K^{-1}: round-off of the sums and of K^{-1}, times cond(K) (<~ 100 here).
  EXPECT_LT(worst, 1e-12);
}

TEST_P(NonUniformCloud, PhiAndPhiXiTakeTheUnequalVolumes)
{
  // eq 11 and eq 15 by hand: phi = V(H_i) / (V(H_i) + V(H_j)), phi_xi = V(B_ij) / V(H_i).
  test::Discretisation d(make_points(body(), kFactor));
  double               worst = 0, spread = 0;
  for (std::size_t i = 0; i < d.size(); i += 7)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const std::size_t b = d.families.offsets[i] + q, j = static_cast<std::size_t>(d.families.neighbour[b]);
      double            VH = 0, VB = 0;
      for (std::size_t p = 0; p < d.families.size(i); ++p) {
        const double v = d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + p])];
        VH += v;
        if ((d.families.ba(b)[p / 64] >> (p % 64)) & 1u) VB += v;
      }
      const double    phi = VH / (VH + d.cloud.family_volume[j]), phi_xi = VB / VH;
      const nd::BondShape<2> s   = nd::bond_shape<2>(d.cloud, d.families, d.state, i, q);
      ASSERT_TRUE(s.usable);
      worst  = std::max({worst, std::fabs(s.volume_fraction - phi_xi) / phi_xi, std::fabs(s.force_scale - 0.5 * phi_xi / phi) / s.force_scale});
      spread = std::max(spread, std::fabs(phi - 0.5));
    }
  EXPECT_LT(worst, 1e-13); // the same sums in another order
  EXPECT_GT(spread, 0.02); // unequal family volumes: phi is not 1/2
}

TEST_P(NonUniformCloud, TensorCorrectionGivesUniformStressAsTheVirialAtEveryPoint)
{
  // sum_j t_ij (x) xi_ij V_j = P C_i M_i = P at every point (C_i formed from the
  // reference families, bond_geometry.hpp), boundary points included.
  test::Discretisation d(make_points(body(), kFactor), StressCorrection::tensor);
  const Mat2           A = {1.2, 0.1, -0.05, 0.9};
  std::vector<double>  t, f;
  const Mat2           P = affine_forces(d, A, t, f);
  double               worst = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    worst = std::max(worst, test::norm(test::bond_force_virial(d, t, i) - P) / test::norm(P));
  }
  EXPECT_LT(worst, 1e-11); // round-off of ~30-60 terms times cond(K) and cond(M)
  // Without the correction the virial is P M_i, M_i != I on an irregular cloud.
  test::Discretisation plain(make_points(body(), kFactor));
  std::vector<double>  t0, f0;
  affine_forces(plain, A, t0, f0);
  double off = 0;
  for (std::size_t i = 0; i < plain.size(); ++i)
    off = std::max(off, test::norm(nd::virial_tensor<2>(plain.cloud, plain.families, plain.state, i) - Mat2{1, 0, 0, 1}));
  EXPECT_GT(off, 1e-2);
}

TEST_P(NonUniformCloud, BothForceFormsConserveLinearMomentum)
{
  test::Discretisation d(make_points(body(), kFactor), StressCorrection::tensor);
  test::Discretisation patched(make_points(body(), kFactor), StressCorrection::tensor); // -force_patch_correction
  patched.cloud.patch_correction = compute_patch_correction(patched.cloud, patched.families, StressCorrection::tensor);
  std::mt19937         rng(3);
  std::vector<double>  y = d.affine({1.3, 0.2, -0.1, 0.9});
  for (double &v : y) v += test::random_between(rng, -0.2, 0.2) * kDx;
  test::SaintVenantKirchhoff2D svk;
  for (int form = 0; form < 3; ++form) {
    std::vector<double> t, f;
    if (form == 0) d.forces(svk, y, t, f);
    else if (form == 1) d.energy_consistent_forces(svk, y, t, f);
    else patched.forces(svk, y, t, f);
    double sum0 = 0, sum1 = 0, scale = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      sum0 += f[2 * i] * d.cloud.volume[i];
      sum1 += f[2 * i + 1] * d.cloud.volume[i];
      scale += test::force_terms(d, t, i) * d.cloud.volume[i];
    }
    ASSERT_GT(scale, 0);
    // Each pair enters as +(t_ij - t_ji) V_i V_j and its negative: exact up to the
    // round-off of ~2e4 summands.
    EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale) << (form == 1 ? "energy-consistent" : form ? "patch-corrected" : "bond-only");
  }
}

INSTANTIATE_TEST_SUITE_P(Clouds, NonUniformCloud, ::testing::Values("jittered", "graded"),
                         [](const ::testing::TestParamInfo<const char *> &info) { return std::string(info.param); });

} // namespace
} // namespace bapd

namespace bapd {
namespace {

// The largest interior force density under the affine motion A (points more than three
// horizons from the sheet's edge: C_j of a neighbour j reads V(H_k) of j's neighbours), over the force a unit strain makes
// there (sum_j (|t_ij| + |t_ji|) V_j / |P|): 0 up to round-off where the discrete
// divergence of a constant stress vanishes.
double interior_affine_residual(const Body<2> &body, StressCorrection correction, bool energy_consistent,
                                bool patch = false, PatchCorrectionReport *report = nullptr)
{
  test::Discretisation d(make_points(body, kFactor), correction);
  if (patch) d.cloud.patch_correction = compute_patch_correction(d.cloud, d.families, correction, report);
  const Mat2           A = {1.1, 0.05, 0.02, 0.95};
  const std::vector<double>    y = d.affine(A);
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          t, f;
  if (energy_consistent) d.energy_consistent_forces(svk, y, t, f);
  else d.forces(svk, y, t, f);
  double worst = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double x0 = d.cloud.x[2 * i], x1 = d.cloud.x[2 * i + 1], reach = 3.0 * d.horizon;
    if (x0 < reach || x1 < reach || body.width - x0 < reach || body.height - x1 < reach) continue;
    worst = std::max(worst, std::hypot(f[2 * i], f[2 * i + 1]) / test::force_terms(d, t, i));
  }
  return worst;
}

TEST(NonUniformPatch, AffineMotionLeavesNoInteriorForceOnARegularCloudGivenAsPoints)
{
  // The lattice handed over as given points (own horizons, the either-reaches rule):
  // the affine patch test of docs/method.md section 2 holds, both forms, corrected or not.
  for (StressCorrection c : {StressCorrection::none, StressCorrection::tensor})
    for (bool ec : {false, true})
      EXPECT_LT(interior_affine_residual(jittered_body(30, 0.0, 0.0), c, ec), 1e-12) << (ec ? "energy-consistent" : "bond-only");
}

// The irregular clouds of the patch tests (docs/discretisations.md's tables).
struct NamedCloud {
  const char *name;
  Body<2>      body;
};
std::vector<NamedCloud> irregular_clouds()
{
  return {{"jittered 0.2 dx", jittered_body(30, 0.2, 0.0)}, {"volumes +-30 %", jittered_body(30, 0.0, 0.3)}, {"graded 1:3", graded_body(40)}};
}

TEST(NonUniformPatch, PatchCorrectionLeavesNoInteriorForceOnIrregularClouds)
{
  // -force_patch_correction (patch_correction.hpp): lambda solved so that the discrete
  // divergence of a constant stress vanishes at every interior point. Without it the
  // interior force is 3-14 % of its terms (docs/discretisations.md), with it round-off:
  // CG to 1e-14 of the right-hand side, then ~60 terms of size 1 each.
  for (StressCorrection c : {StressCorrection::none, StressCorrection::tensor})
    for (const NamedCloud &cloud : irregular_clouds()) {
      PatchCorrectionReport report;
      EXPECT_GT(interior_affine_residual(cloud.body, c, false), 0.02) << cloud.name; // the defect is there
      EXPECT_LT(interior_affine_residual(cloud.body, c, false, true, &report), 1e-12) << cloud.name << ", " << to_string(c);
      EXPECT_GT(report.interior, 100u) << cloud.name; // the boundary layer is one horizon, not the whole sheet
      EXPECT_LT(report.after, 1e-13) << cloud.name;   // at every interior point of the correction's own
    }
}

TEST(NonUniformPatch, PatchCorrectionIsRoundOffOnARegularCloudGivenAsPoints)
{
  // The lattice's interior already passes (d_i = 0 by symmetry): lambda only removes
  // the tail of the boundary force beyond the one-horizon layer (rows 4-8 from the
  // edge, <= 3 % there) and leaves the interior at round-off.
  PatchCorrectionReport report;
  EXPECT_LT(interior_affine_residual(jittered_body(30, 0.0, 0.0), StressCorrection::tensor, false, true, &report), 1e-12);
  EXPECT_LT(report.before, 0.035);
  EXPECT_LT(report.after, 1e-13);
}

// The virial-keeping correction (patch_correction.hpp, compute_virial_patch_correction)
// applied OUTSIDE the kernel: the uncorrected kernel's bond forces t_ij = P g_ij under an
// affine motion get P c_ij xi_ij on every force-carrying bond, c_ij from (mu, S) as the
// kernel hook would form it. Measured: the interior force (as interior_affine_residual),
// the virial sum_j t_ij (x) xi V_j against P at every point, and linear momentum.
struct VirialPatchFigures {
  double before = 0, after = 0;      // largest interior |f_i| / its terms, without / with
  double virial_lambda = 0;          // largest |virial - P| / |P| with the lambda correction (the kernel's)
  double virial_after = 0;           // the same with c_ij
  double momentum = 0;               // |sum_i f_i V_i| / sum_i terms_i V_i, with c_ij
  PatchCorrectionReport report;
};

VirialPatchFigures virial_patch_figures(const Body<2> &body, StressCorrection correction)
{
  VirialPatchFigures   out;
  test::Discretisation d(make_points(body, kFactor), correction);
  const std::vector<double> Y = compute_virial_patch_correction(d.cloud, d.families, correction, &out.report);
  const Mat2                A = {1.1, 0.05, 0.02, 0.95};
  std::vector<double>       t, f;
  const Mat2                P  = affine_forces(d, A, t, f);
  std::vector<double>       tc = t; // + P c_ij xi_ij where the kernel gives the bond a force
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t b = d.families.offsets[i]; b < d.families.offsets[i + 1]; ++b) {
      if (t[2 * b] == 0.0 && t[2 * b + 1] == 0.0) continue;
      const std::size_t j  = static_cast<std::size_t>(d.families.neighbour[b]);
      const double      x0 = d.cloud.x[2 * j] - d.cloud.x[2 * i], x1 = d.cloud.x[2 * j + 1] - d.cloud.x[2 * i + 1];
      const double      c  = virial_patch_coefficient(Y.data() + kVirialPatchStride * i, Y.data() + kVirialPatchStride * j, x0, x1);
      tc[2 * b] += c * (P[0] * x0 + P[1] * x1);
      tc[2 * b + 1] += c * (P[2] * x0 + P[3] * x1);
    }
  double m0 = 0, m1 = 0, mscale = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    double fc[2] = {0, 0};
    for (std::size_t b = d.families.offsets[i]; b < d.families.offsets[i + 1]; ++b) {
      const std::size_t r = static_cast<std::size_t>(d.families.reverse[b]);
      const double      v = d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[b])];
      fc[0] += (tc[2 * b] - tc[2 * r]) * v;
      fc[1] += (tc[2 * b + 1] - tc[2 * r + 1]) * v;
    }
    const double terms = test::force_terms(d, tc, i);
    m0 += fc[0] * d.cloud.volume[i];
    m1 += fc[1] * d.cloud.volume[i];
    mscale += terms * d.cloud.volume[i];
    out.virial_after = std::max(out.virial_after, test::norm(test::bond_force_virial(d, tc, i) - P) / test::norm(P));
    const double x0 = d.cloud.x[2 * i], x1 = d.cloud.x[2 * i + 1], reach = 3.0 * d.horizon;
    if (x0 < reach || x1 < reach || body.width - x0 < reach || body.height - x1 < reach) continue;
    out.before = std::max(out.before, std::hypot(f[2 * i], f[2 * i + 1]) / test::force_terms(d, t, i));
    out.after  = std::max(out.after, std::hypot(fc[0], fc[1]) / terms);
  }
  out.momentum = std::hypot(m0, m1) / mscale;
  // The lambda correction, through the kernel: its virial change.
  test::Discretisation l(make_points(body, kFactor), correction);
  l.cloud.patch_correction = compute_patch_correction(l.cloud, l.families, correction);
  std::vector<double> tl, fl;
  affine_forces(l, A, tl, fl);
  for (std::size_t i = 0; i < l.size(); ++i)
    out.virial_lambda = std::max(out.virial_lambda, test::norm(test::bond_force_virial(l, tl, i) - P) / test::norm(P));
  return out;
}

TEST(NonUniformPatch, VirialPatchCorrectionKeepsThePatchTestAndTheVirial)
{
  // The lambda correction passes the patch test but moves the virial
  // (7-14 % at a point); c_ij = (mu_i - mu_j) . xi + xi . S_i xi passes both, to
  // round-off, on every irregular cloud of the lambda test.
  std::vector<NamedCloud> clouds = irregular_clouds();
  clouds.insert(clouds.begin(), {"jittered 0.1 dx", jittered_body(30, 0.1, 0.0)});
  for (const NamedCloud &cloud : clouds) {
    const VirialPatchFigures v = virial_patch_figures(cloud.body, StressCorrection::tensor);
    std::printf("%-16s interior force %.3g -> %.3g, virial error lambda %.3g, c_ij %.3g, momentum %.2g, %zu CG iterations, "
                "largest |h_ij| / |g_ij| %.2g\n",
                cloud.name, v.before, v.after, v.virial_lambda, v.virial_after, v.momentum, v.report.iterations, v.report.term);
    EXPECT_GT(v.before, 0.02) << cloud.name;        // the defect is there
    EXPECT_GT(v.virial_lambda, 0.02) << cloud.name; // and the lambda correction moves the virial
    EXPECT_LT(v.after, 1e-12) << cloud.name;        // both hold with c_ij
    EXPECT_LT(v.virial_after, 1e-11) << cloud.name; // as TensorCorrectionGivesUniformStress... without any correction
    EXPECT_LT(v.momentum, 1e-13) << cloud.name;
    EXPECT_GT(v.report.interior, 100u) << cloud.name;
  }
}

} // namespace
} // namespace bapd
