// The BA bond-force kernel: patch tests, objectivity, momentum, zero-energy modes,
// energy, failure reporting, rank-layout independence (docs/method.md 2-3). The
// small-strain modulus and the stress correction: ba_force_modulus_test.cpp and
// ba_force_correction_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/damage.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/kernel/point_quantities.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

constexpr double kDx = 0.5e-3;
using test::boundary_distance;
using test::force_terms;
using test::kLargeAffine;
using test::rotation;

// sum_j (|g_ij| + |g_ji|) V_j times a modulus: the force density a unit strain makes.
double unit_strain_force(const test::Discretisation &d, std::size_t i, double modulus)
{
  double s = 0;
  for (std::size_t q = 0; q < d.families.size(i); ++q) {
    const std::size_t b = d.families.offsets[i] + q, j = static_cast<std::size_t>(d.families.neighbour[b]);
    const std::size_t r = static_cast<std::size_t>(d.families.reverse[b]) - d.families.offsets[j];
    const Vec2        g = nd::bond_shape<2>(d.cloud, d.families, d.state, i, q).force_vector;
    const Vec2        h = nd::bond_shape<2>(d.cloud, d.families, d.state, j, r).force_vector;
    s += (std::hypot(g[0], g[1]) + std::hypot(h[0], h[1])) * d.cloud.volume[j];
  }
  return modulus * s;
}

TEST(BaForce, AffineMotionGivesExactDeformationGradientOnEveryUsableBond)
{
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({10.3 * kDx, 9.6 * kDx, 3.4 * kDx});
  test::Discretisation d(body);
  const std::vector<double> y = d.affine(kLargeAffine, 3.7e-3, -1.2e-2);
  std::size_t               usable = 0;
  const double              worst  = test::worst_affine_gradient_error(d, y, kLargeAffine, &usable);
  EXPECT_EQ(usable, d.families.n_bonds()); // a lattice with a hole: every K is regular
  // F = (A K) K^{-1}: round-off of y_k - y_i (eps |y| / dx ~ 50 eps), of the sums and
  // of K^{-1}, times cond(K) (<= ~30 on this lattice).
  EXPECT_LT(worst, 1e-12);
}

template <class Model> void expect_zero_interior_force_under_affine_motion(const Model &model)
{
  test::Discretisation d(test::plate(20, 20, kDx));
  std::vector<double>  t, f;
  const KernelStats    s = d.forces(model, d.affine(kLargeAffine, 3.7e-3, -1.2e-2), t, f);
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.evaluated, d.families.n_bonds());
  const test::InteriorForce r = test::interior_force(d, t, f, 20 * kDx, 2 * d.horizon);
  EXPECT_EQ(r.interior, 64u);
  // 56 terms with relative round-off ~1e-15 each (F = A + O(1e-15), and the plane-
  // stress solve converges to 1e-12 of S33 but to the same C33 for equal F).
  EXPECT_LT(r.worst, 1e-13);
  EXPECT_GT(r.boundary_max, 1e-2); // not vacuous: the free surface is not in equilibrium
}

TEST(BaForce, AffineMotionGivesZeroNetForceTwoHorizonsFromTheBoundary)
{
  expect_zero_interior_force_under_affine_motion(test::SaintVenantKirchhoff2D{});
  MaterialParameters p; // the paper's hydrogel, K = 100 mu
  p.D = 2.0 / (100.0 * p.mu);
  expect_zero_interior_force_under_affine_motion(GentPlaneStress{p});
}

// t_ij straight from docs/method.md sections 2-3 (eqs 8, 9, 11, 15, 23): loops over the
// family, no masks, no reuse, no complement sums.
template <class Model>
Vec2 reference_bond_force(const test::Discretisation &d, const Model &model, const std::vector<double> &y,
                          std::size_t i, std::size_t q)
{
  const Families   &f = d.families;
  const PointCloud &c = d.cloud;
  const std::size_t j = static_cast<std::size_t>(f.neighbour[f.offsets[i] + q]);
  if (!d.state.is_intact(i, q)) return {0.0, 0.0};
  double K[4] = {0, 0, 0, 0}, N[4] = {0, 0, 0, 0}, VB = 0, VHi = 0, VHj = 0;
  for (std::size_t p = 0; p < f.size(i); ++p) VHi += c.volume[static_cast<std::size_t>(f.neighbour[f.offsets[i] + p])];
  for (std::size_t p = 0; p < f.size(j); ++p) VHj += c.volume[static_cast<std::size_t>(f.neighbour[f.offsets[j] + p])];
  for (std::size_t p = 0; p < f.size(i); ++p) {
    const std::size_t k = static_cast<std::size_t>(f.neighbour[f.offsets[i] + p]);
    if (!d.state.is_intact(i, p)) continue;                                                          // gamma = 0
    if (std::hypot(c.x[2 * k] - c.x[2 * j], c.x[2 * k + 1] - c.x[2 * j + 1]) > d.horizon) continue; // not in B_ij
    const double X[2] = {c.x[2 * k] - c.x[2 * i], c.x[2 * k + 1] - c.x[2 * i + 1]};
    const double Y[2] = {y[2 * k] - y[2 * i], y[2 * k + 1] - y[2 * i + 1]};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) K[2 * a + b] += X[a] * X[b] * c.volume[k], N[2 * a + b] += Y[a] * X[b] * c.volume[k];
    VB += c.volume[k];
  }
  const Mat2 Kinv = inverse(Mat2{K[0], K[1], K[2], K[3]});
  const Mat2 F    = Mat2{N[0], N[1], N[2], N[3]} * Kinv;
  double     c33  = 0;
  Mat2       P;
  model.stress(F, c33, P);
  const double phi_xi = VB / VHi, phi = VHi / (VHi + VHj);
  const Vec2   xi     = {c.x[2 * j] - c.x[2 * i], c.x[2 * j + 1] - c.x[2 * i + 1]};
  const Vec2   g      = Kinv * xi;
  const Vec2   t      = P * g;
  return {0.5 * phi_xi / phi * t[0], 0.5 * phi_xi / phi * t[1]};
}

TEST(BaForce, BondForcesMatchAStraightforwardImplementationOfEq23)
{
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({6.0 * kDx, 12.0 * kDx, 2.5 * kDx});
  body.notches.push_back({20 * kDx, 10.0 * kDx, 11.0 * kDx, 10.0 * kDx});
  test::Discretisation d(body);
  std::mt19937         rng(11);
  std::vector<double>  y = d.affine({1.3, 0.2, -0.1, 0.9});
  for (double &v : y) v += test::random_between(rng, -0.1, 0.1) * kDx;
  std::vector<std::size_t> touched;
  for (std::size_t i = 0; i < d.size(); i += 3)
    for (std::size_t q = 1; q < d.families.size(i); q += 5) break_bond(d.families, d.state, i, q, &touched);
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          t, f;
  EXPECT_TRUE(d.forces(svk, y, t, f).ok());
  double scale = 0;
  for (double v : t) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const std::size_t b = d.families.offsets[i] + q;
      const Vec2        r = reference_bond_force(d, svk, y, i, q);
      // Same mathematics, different summation orders and K^{-1} formulas: round-off,
      // amplified by cond(K) (<= ~100 next to the cuts).
      ASSERT_NEAR(t[2 * b], r[0], 1e-12 * scale) << i << " " << q;
      ASSERT_NEAR(t[2 * b + 1], r[1], 1e-12 * scale) << i << " " << q;
    }
}

TEST(BaForce, BondOnlyStiffnessIsSymmetricInTheInteriorButNotAtAFreeEdge)
{
  // The bond-only form of eq 23 is not the gradient of an energy: its tangent is
  // symmetric where the lattice symmetry makes it so (whole families), but not next to
  // a free surface. There a non-symmetric stiffness has complex eigenvalues, and
  // undamped explicit dynamics grows slowly whatever the time step (flutter): the
  // solver needs some damping, or the energy-consistent variant (docs/method.md 3).
  test::Discretisation         d(test::plate(20, 20, 1.0));
  test::SaintVenantKirchhoff2D svk;
  svk.lambda = svk.mu = 1.0;
  auto bond_only = [&](const std::vector<double> &y, std::vector<double> &f) {
    std::vector<double> t;
    d.forces(svk, y, t, f);
  };
  std::vector<std::size_t> interior, edge;
  for (int iy = 8; iy <= 11; ++iy)
    for (int ix = 8; ix <= 11; ++ix) interior.push_back(static_cast<std::size_t>(iy * 20 + ix));
  for (int iy = 0; iy <= 1; ++iy)
    for (int ix = 0; ix <= 5; ++ix) edge.push_back(static_cast<std::size_t>(iy * 20 + ix));
  EXPECT_LT(test::stiffness_asymmetry(d, interior, bond_only), 1e-6); // central differences: O(h^2) + round-off / h
  EXPECT_GT(test::stiffness_asymmetry(d, edge, bond_only), 1e-2);
}

TEST(BaForce, WideHorizonWithTwoMaskWordsPassesThePatchTest)
{
  // delta = 5.015 dx: 80 neighbours, two 64-bit mask words (the run-time-width path).
  test::Discretisation d(test::plate(24, 24, kDx), 5.015);
  ASSERT_EQ(d.families.mask_words, 2u);
  test::SaintVenantKirchhoff2D svk;
  const std::vector<double>    y = d.affine(kLargeAffine, 3.7e-3, -1.2e-2);
  double                       worst_F = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q)
      if (d.geometry.is_usable(i, q))
        worst_F = std::max(worst_F, test::norm(nd::bond_deformation_gradient<2>(d.cloud, y.data(), d.families, d.geometry,
                                                                         d.state, i, q) - kLargeAffine) / test::norm(kLargeAffine));
  EXPECT_LT(worst_F, 1e-12); // as in the 3.015 dx patch test
  std::vector<double> t, f;
  EXPECT_TRUE(d.forces(svk, y, t, f).ok());
  std::size_t interior = 0;
  double      sum0 = 0, sum1 = 0, scale = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    sum0 += f[2 * i] * d.cloud.volume[i];
    sum1 += f[2 * i + 1] * d.cloud.volume[i];
    scale += force_terms(d, t, i) * d.cloud.volume[i];
    if (boundary_distance(d, i, 24 * kDx, 24 * kDx) < 2 * d.horizon) continue;
    ++interior;
    EXPECT_LT(std::hypot(f[2 * i], f[2 * i + 1]), 1e-13 * force_terms(d, t, i)); // 160 terms of round-off
  }
  EXPECT_EQ(interior, 16u);
  EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale); // momentum, as above
}

TEST(BaForce, RigidRotationGivesZeroForceEverywhere)
{
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({10.3 * kDx, 9.6 * kDx, 3.4 * kDx});
  body.notches.push_back({20 * kDx, 4.0 * kDx, 14.0 * kDx, 4.0 * kDx});
  test::Discretisation        d(body);
  test::SaintVenantKirchhoff2D svk;
  for (double deg : {90.0, 40.0, 180.0}) {
    std::vector<double> t, f;
    d.forces(svk, d.affine(rotation(deg), 5.0e-3, -3.0e-3), t, f);
    for (std::size_t i = 0; i < d.size(); ++i)
      // F = R + O(eps |y| / dx) = R + O(1e-14) (translations ~ the body size), so P is
      // round-off times mu: compare with the force a unit strain would make.
      ASSERT_LT(std::hypot(f[2 * i], f[2 * i + 1]), 1e-13 * unit_strain_force(d, i, svk.young_modulus()))
          << "point " << i << " rotation " << deg;
  }
}

TEST(BaForce, ConservesLinearMomentumWithNotchHoleAndBrokenBonds)
{
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({6.0 * kDx, 12.0 * kDx, 2.5 * kDx});
  body.notches.push_back({20 * kDx, 10.0 * kDx, 11.0 * kDx, 10.0 * kDx});
  test::Discretisation d(body);
  std::mt19937         rng(42);
  std::vector<double>  y = d.affine({1.3, 0.2, -0.1, 0.9});
  for (double &v : y) v += test::random_between(rng, -0.2, 0.2) * kDx;
  // Break every 7th bond explicitly (both copies) and recompute the touched points.
  std::vector<std::size_t> touched;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); q += 7) break_bond(d.families, d.state, i, q, &touched);
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  ASSERT_GT(d.state.count_broken(d.families, d.size()), 1000u);

  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          t, f;
  d.forces(svk, y, t, f);
  double sum0 = 0, sum1 = 0, scale = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    sum0 += f[2 * i] * d.cloud.volume[i];
    sum1 += f[2 * i + 1] * d.cloud.volume[i];
    scale += force_terms(d, t, i) * d.cloud.volume[i];
  }
  ASSERT_GT(scale, 0);
  // Each pair enters as +(t_ij - t_ji) V_i V_j and -(...): exact cancellation up to the
  // round-off of ~2e4 summands (random-walk ~ sqrt(n) eps ~ 3e-14).
  EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale);
}

// Conventional point-associated NOSB force (paper eqs 2, 4, 5), for comparison only.
template <class Model>
std::vector<double> point_associated_force(const test::Discretisation &d, const Model &model, const std::vector<double> &y)
{
  const Families     &fam = d.families;
  const std::size_t   n   = d.size();
  std::vector<double> kinv(3 * n), P(4 * n), f(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double k00 = 0, k01 = 0, k11 = 0, n00 = 0, n01 = 0, n10 = 0, n11 = 0;
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const std::size_t k  = static_cast<std::size_t>(fam.neighbour[b]);
      const double      d0 = d.cloud.x[2 * k] - d.cloud.x[2 * i], d1 = d.cloud.x[2 * k + 1] - d.cloud.x[2 * i + 1];
      const double      e0 = y[2 * k] - y[2 * i], e1 = y[2 * k + 1] - y[2 * i + 1], v = d.cloud.volume[k];
      k00 += d0 * d0 * v, k01 += d0 * d1 * v, k11 += d1 * d1 * v;
      n00 += e0 * d0 * v, n01 += e0 * d1 * v, n10 += e1 * d0 * v, n11 += e1 * d1 * v;
    }
    const double det = k00 * k11 - k01 * k01;
    kinv[3 * i] = k11 / det, kinv[3 * i + 1] = -k01 / det, kinv[3 * i + 2] = k00 / det;
    const double *ki = &kinv[3 * i];
    const Mat2    F  = {n00 * ki[0] + n01 * ki[1], n00 * ki[1] + n01 * ki[2], n10 * ki[0] + n11 * ki[1], n10 * ki[1] + n11 * ki[2]};
    double        c  = 0;
    Mat2          Pi;
    model.stress(F, c, Pi);
    std::copy(Pi.begin(), Pi.end(), P.begin() + 4 * i);
  }
  auto t = [&](std::size_t i, std::size_t j) { // P_i K_i^{-1} (x_j - x_i)
    const double  d0 = d.cloud.x[2 * j] - d.cloud.x[2 * i], d1 = d.cloud.x[2 * j + 1] - d.cloud.x[2 * i + 1];
    const double *ki = &kinv[3 * i], *Pi = &P[4 * i];
    const double  g0 = ki[0] * d0 + ki[1] * d1, g1 = ki[1] * d0 + ki[2] * d1;
    return Vec2{Pi[0] * g0 + Pi[1] * g1, Pi[2] * g0 + Pi[3] * g1};
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
      const Vec2        a = t(i, j), c = t(j, i);
      f[2 * i] += (a[0] - c[0]) * d.cloud.volume[j];
      f[2 * i + 1] += (a[1] - c[1]) * d.cloud.volume[j];
    }
  return f;
}

TEST(BaForce, CheckerboardModeMeetsRestoringForceWherePointAssociatedFDoesNot)
{
  // u = eps (-1)^(ix+iy) e_x on the patch 4 <= ix, iy <= 25 of a 30 x 30 plate. The
  // point-associated F_i sees no strain from it (the odd neighbours' offsets sum to
  // zero): a zero-energy mode. B_ij is lopsided, so the BA F_ij does see it.
  test::Discretisation        d(test::plate(30, 30, kDx));
  test::SaintVenantKirchhoff2D svk;
  const double                eps = 1e-4 * kDx;
  std::vector<double>          y = d.cloud.x;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const int ix = d.ix(i, kDx), iy = d.iy(i, kDx);
    if (ix >= 4 && ix <= 25 && iy >= 4 && iy <= 25) y[2 * i] += ((ix + iy) % 2 ? -eps : eps);
  }
  std::vector<double>       t, f;
  d.forces(svk, y, t, f);
  const std::vector<double> f_pa = point_associated_force(d, svk, y);
  // Deep patch points: two horizons inside, so the point-associated F of the point and
  // of all its neighbours is exactly the identity (up to round-off).
  const double scale = svk.young_modulus() * eps / (kDx * kDx); // force density of E u / dx^2
  double       ba_min = std::numeric_limits<double>::max(), pa_max = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const int ix = d.ix(i, kDx), iy = d.iy(i, kDx);
    if (ix < 10 || ix > 19 || iy < 10 || iy > 19) continue;
    const double u = (ix + iy) % 2 ? -eps : eps;
    ba_min         = std::min(ba_min, -f[2 * i] * u / (eps * scale));
    pa_max         = std::max(pa_max, std::hypot(f_pa[2 * i], f_pa[2 * i + 1]) / scale);
    EXPECT_LT(std::abs(f[2 * i + 1]), 1e-9 * scale); // symmetric: no transverse force
  }
  // Every deep point is pushed back towards its place, with a stiffness of order E/dx^2
  // (a smooth mode of wavelength 20 dx would get ~E (2 pi / 20 dx)^2 = 0.1 E/dx^2).
  EXPECT_GT(ba_min, 0.3);
  // The point-associated force there is round-off: F_i = I + O(1e-16 / 1e-4).
  EXPECT_LT(pa_max, 1e-9);
}

TEST(BaForce, StrainEnergyOfAffineMotionIsTheContinuumEnergy)
{
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({10.3 * kDx, 9.6 * kDx, 3.4 * kDx});
  test::Discretisation        d(body);
  test::SaintVenantKirchhoff2D svk;
  nd::Workspace<2>          ws;
  KernelStats                  stats;
  const std::vector<double>    y = d.affine(kLargeAffine, 1.0e-2, 2.0e-2);
  const double                 W = nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr,
                                                 d.size(), ws, &stats);
  double c = 0, psi = 0, volume = 0;
  svk.energy(kLargeAffine, c, psi);
  for (double v : d.cloud.volume) volume += v;
  EXPECT_NEAR(W, psi * volume, 1e-12 * psi * volume); // Psi(F_ij) = Psi(A) + round-off
  EXPECT_EQ(stats.evaluated, d.families.n_bonds());
  nd::Workspace<2> fresh; // a second evaluation, in a workspace of its own: the same bits
  EXPECT_EQ(nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), fresh), W);
  std::vector<double> per_point(d.size());
  nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws, nullptr, per_point.data());
  double sum = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(per_point[i], psi * d.cloud.volume[i], 1e-12 * psi * d.cloud.volume[i]); // as above, per point
    sum += per_point[i];
  }
  EXPECT_EQ(sum, W); // same terms, same order
}

TEST(BaForce, ModelFailureIsCountedReportedAndCarriesNoForce)
{
  test::Discretisation d(test::plate(20, 20, kDx));
  test::LimitedModel   model; // chain_limit once F_xx > 1.5
  // y_x = x + x^2 / L: F_xx = 1 + 2 x / L grows from 1 to 3 across the plate.
  const double         L = 20 * kDx;
  std::vector<double>  y = d.cloud.x;
  for (std::size_t i = 0; i < d.size(); ++i) y[2 * i] += d.cloud.x[2 * i] * d.cloud.x[2 * i] / L;
  std::vector<double>      c33(d.families.n_bonds(), 7.0), t(2 * d.families.n_bonds(), 99.0);
  nd::Workspace<2>      ws;
  const KernelStats        s = nd::compute_bond_forces<2>(ForceForm::bond_only, model, d.cloud, y.data(), d.families, d.geometry, d.state,
                                                   c33.data(), t.data(), ws);
  std::set<std::size_t>    expected;
  std::size_t              first = KernelStats::none;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const std::size_t b = d.families.offsets[i] + q;
      if (nd::bond_deformation_gradient<2>(d.cloud, y.data(), d.families, d.geometry, d.state, i, q)[0] > 1.5) {
        expected.insert(b);
        if (first == KernelStats::none) first = i;
        EXPECT_EQ(t[2 * b], 0.0);
        EXPECT_EQ(t[2 * b + 1], 0.0);
        EXPECT_EQ(c33[b], 7.0); // the failed solve's state is not kept
      } else {
        EXPECT_EQ(c33[b], 0.5);
        EXPECT_NE(t[2 * b], 99.0);
      }
    }
  ASSERT_GT(expected.size(), 1000u);
  ASSERT_LT(expected.size(), d.families.n_bonds());
  EXPECT_EQ(s.chain_limit, expected.size());
  EXPECT_EQ(s.failed(), expected.size());
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.evaluated, d.families.n_bonds());
  EXPECT_EQ(s.first_point, first);
  EXPECT_EQ(s.first_status, StressStatus::chain_limit);
  ASSERT_EQ(ws.failed.size(), expected.size());
  for (const FailedBond &fb : ws.failed) EXPECT_EQ(expected.count(d.families.offsets[fb.point] + fb.position), 1u);

  // The solver breaks them (failure enabled): both copies, geometry recomputed.
  std::vector<std::size_t> touched;
  const std::size_t        broken = break_failed_bonds(d.families, d.state, ws.failed, touched);
  EXPECT_GT(broken, 0u);
  EXPECT_LE(broken, expected.size());
  for (const FailedBond &fb : ws.failed) {
    const std::size_t b = d.families.offsets[fb.point] + fb.position, j = static_cast<std::size_t>(d.families.neighbour[b]);
    EXPECT_FALSE(d.state.is_intact(fb.point, fb.position));
    EXPECT_FALSE(d.state.is_intact(j, static_cast<std::size_t>(d.families.reverse[b]) - d.families.offsets[j]));
    EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), j));
  }
}

// KernelStats::largest_trC, the time step's stiffening trigger (time_step_control.hpp):
// the largest tr(F^T F) + C33 (the warm start read, 1 without one) over the bonds handed
// to the model, failed ones included, in either force form; checked against every bond's
// F recomputed on the slow path, bit for bit.
TEST(BaForce, LargestTraceOfCIsThatOfTheStiffestBond)
{
  test::Discretisation d(test::plate(20, 20, kDx));
  test::LimitedModel   model; // chain_limit once F_xx > 1.5 (those bonds still count)
  const double         L = 20 * kDx;
  std::vector<double>  y = d.cloud.x;
  for (std::size_t i = 0; i < d.size(); ++i) y[2 * i] += d.cloud.x[2 * i] * d.cloud.x[2 * i] / L; // F_xx from 1 to 3
  double expected = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const Mat2 F   = nd::bond_deformation_gradient<2>(d.cloud, y.data(), d.families, d.geometry, d.state, i, q);
      double     trC = 7.0;
      for (int c = 0; c < 4; ++c) trC += F[c] * F[c];
      expected = std::max(expected, trC);
    }
  for (ForceForm form : {ForceForm::bond_only, ForceForm::energy_consistent}) {
    std::vector<double> c33(d.families.n_bonds(), 7.0), t(2 * d.families.n_bonds());
    nd::Workspace<2>    ws;
    const KernelStats   s = nd::compute_bond_forces<2>(form, model, d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(),
                                                       t.data(), ws);
    EXPECT_GT(s.chain_limit, 0u);
    EXPECT_NEAR(s.largest_trC, expected, 1e-14 * expected); // the lane path may contract a product into an fma
    EXPECT_GT(s.largest_trC, 7.0 + 9.0 * 0.9); // F_xx near 3 at the right edge
  }
  // An affine stretch, no warm starts: every bond's tr C is 1.2^2 + 0.9^2 + 1.
  const std::vector<double> ya = d.affine(Mat2{1.2, 0.0, 0.0, 0.9}, 0.0, 0.0);
  std::vector<double>       t, f;
  const KernelStats         s = d.forces(test::LimitedModel{}, ya, t, f);
  EXPECT_NEAR(s.largest_trC, 1.2 * 1.2 + 0.9 * 0.9 + 1.0, 1e-12);
}

TEST(BaForce, RankLocalCloudReproducesOneRankForcesBitForBit)
{
  const test::SaintVenantKirchhoff2D svk;
  test::expect_rank_local_views_reproduce_one_rank([&](const PointCloud &cloud, const double *y, const Families &f,
                                                       const nd::BondGeometry<2> &g, const BondState &s, double *c33,
                                                       double *t, nd::Workspace<2> &ws) {
    return nd::compute_bond_forces<2>(ForceForm::bond_only, svk, cloud, y, f, g, s, c33, t, ws);
  });
}

TEST(BaForce, AssemblyRejectsOwnedPointsWithoutGhostFamilies)
{
  test::Discretisation d(test::plate(10, 10, kDx));
  const Families       f = build_families(d.cloud, 50, d.horizon, {}); // points 50.. have no family
  std::vector<double>  t(2 * f.n_bonds(), 0.0), fd(2 * 50);
  EXPECT_THROW(nd::assemble_force_density<2>(f, d.cloud, t.data(), 50, fd.data()), std::logic_error);
}

} // namespace
} // namespace bapd
