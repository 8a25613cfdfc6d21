// The BA bond-force kernel with a stress correction (-force_stress_correction, docs/method.md
// 2-3): the correction is that of the reference families after breaking, and keeps
// momentum, objectivity, the patch test and rank-layout independence; the corrected
// point stress is the virial of the force; without one the force is the paper's.
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

constexpr double kDx = test::kPlateDx;
using test::force_terms;
using test::kLargeAffine;
using test::max_abs_force;
using test::rotation;
using test::set_correction;

// A plate with a hole and a notch, the correction set, deformed non-affinely, with
// every 7th bond broken after the geometry was computed (the run's path: the touched
// points' geometry, their C_i included, recomputed).
struct CorrectedCutPlate {
  Body<2>               body;
  test::Discretisation d;
  std::vector<double>  y;
  explicit CorrectedCutPlate(StressCorrection c) : body(make_body()), d(body)
  {
    set_correction(d, c);
    std::mt19937 rng(42);
    y = d.affine({1.3, 0.2, -0.1, 0.9});
    for (double &v : y) v += test::random_between(rng, -0.2, 0.2) * kDx;
    std::vector<std::size_t> touched;
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t q = 0; q < d.families.size(i); q += 7) break_bond(d.families, d.state, i, q, &touched);
    nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  }
  static Body<2> make_body()
  {
    Body<2> b = test::plate(20, 20, kDx);
    b.holes.push_back({6.0 * kDx, 12.0 * kDx, 2.5 * kDx});
    b.notches.push_back({20 * kDx, 10.0 * kDx, 11.0 * kDx, 10.0 * kDx});
    return b;
  }
};

TEST(BaForce, StressCorrectionIsThatOfTheReferenceFamiliesAfterBreakingAndFromScratch)
{
  for (StressCorrection c : {StressCorrection::tensor, StressCorrection::scalar}) {
    CorrectedCutPlate p(c);
    ASSERT_GT(p.d.state.count_broken(p.d.families, p.d.size()), 1000u);
    nd::BondGeometry<2> fresh;
    fresh.stress_correction = c;
    nd::compute_bond_geometry<2>(p.d.cloud, p.d.families, p.d.state, fresh);
    ASSERT_EQ(fresh.correction.size(), 4 * p.d.size());
    EXPECT_EQ(p.d.geometry.correction, fresh.correction); // bit for bit
    EXPECT_EQ(p.d.geometry.usable, fresh.usable);
    // C_i is that of the reference families (breaking is damage, not a change of the
    // discretisation), so the unbroken plate has the same, while its usable bits differ.
    test::Discretisation whole(p.body);
    set_correction(whole, c);
    EXPECT_EQ(whole.geometry.correction, fresh.correction);
    EXPECT_NE(whole.geometry.usable, fresh.usable);
    std::size_t off_identity = 0; // not vacuous: C_i is not I
    for (std::size_t i = 0; i < p.d.size(); ++i) off_identity += fresh.correction[4 * i] != 1.0;
    EXPECT_EQ(off_identity, p.d.size());
  }
}

TEST(BaForce, StressCorrectionConservesLinearMomentumWithNotchHoleAndBrokenBonds)
{
  // C_i changes t_ij, not the pairing: f_i = sum_j (t_ij - t_ji) V_j still cancels
  // pair by pair.
  for (StressCorrection c : {StressCorrection::tensor, StressCorrection::scalar}) {
    CorrectedCutPlate            p(c);
    test::SaintVenantKirchhoff2D svk;
    std::vector<double>          t, f;
    p.d.forces(svk, p.y, t, f);
    double sum0 = 0, sum1 = 0, scale = 0;
    for (std::size_t i = 0; i < p.d.size(); ++i) {
      sum0 += f[2 * i] * p.d.cloud.volume[i];
      sum1 += f[2 * i + 1] * p.d.cloud.volume[i];
      scale += force_terms(p.d, t, i) * p.d.cloud.volume[i];
    }
    ASSERT_GT(scale, 0);
    EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale) << to_string(c); // as without it
  }
}

TEST(BaForce, StressCorrectionIsObjective)
{
  // C_i is a reference quantity and P(R F) = R P(F): rotating a deformed state
  // rotates every bond force, t_ij(R y + c) = R t_ij(y).
  for (StressCorrection c : {StressCorrection::tensor, StressCorrection::scalar}) {
    CorrectedCutPlate            p(c);
    test::SaintVenantKirchhoff2D svk;
    const Mat2                   R = rotation(37.0);
    std::vector<double>          yr(p.y.size());
    for (std::size_t i = 0; i < p.d.size(); ++i) {
      const Vec2 r     = R * Vec2{p.y[2 * i], p.y[2 * i + 1]};
      yr[2 * i]        = r[0] + 2.0e-3;
      yr[2 * i + 1]    = r[1] - 1.0e-3;
    }
    std::vector<double> t, f, tr, fr;
    p.d.forces(svk, p.y, t, f);
    p.d.forces(svk, yr, tr, fr);
    double worst = 0, size = max_abs_force(t);
    for (std::size_t b = 0; b < p.d.families.n_bonds(); ++b) {
      const Vec2 rt = R * Vec2{t[2 * b], t[2 * b + 1]};
      worst         = std::max(worst, std::hypot(tr[2 * b] - rt[0], tr[2 * b + 1] - rt[1]));
    }
    ASSERT_GT(size, 0);
    // F = R F0 + round-off of the translated positions (|y| / dx ~ 1e2 eps), times cond(K)
    EXPECT_LT(worst, 1e-11 * size) << to_string(c);
  }
}

template <class Model> void expect_zero_interior_force_with_correction(const Model &model, StressCorrection c)
{
  // C_j of every neighbour j of i must be the interior one, and C_j reads V(H) two
  // horizons from j: i three horizons from the boundary (a 26 x 26 plate: 64 points).
  test::Discretisation d(test::plate(26, 26, kDx));
  set_correction(d, c);
  std::vector<double> t, f;
  EXPECT_TRUE(d.forces(model, d.affine(kLargeAffine, 3.7e-3, -1.2e-2), t, f).ok());
  const test::InteriorForce r = test::interior_force(d, t, f, 26 * kDx, 3 * d.horizon);
  EXPECT_EQ(r.interior, 64u);
  EXPECT_LT(r.worst, 1e-13) << to_string(c); // as without a correction
  EXPECT_GT(r.boundary_max, 1e-2);           // not vacuous
}

TEST(BaForce, StressCorrectionPassesThePatchTestThreeHorizonsFromTheBoundary)
{
  for (StressCorrection c : {StressCorrection::tensor, StressCorrection::scalar}) {
    expect_zero_interior_force_with_correction(test::SaintVenantKirchhoff2D{}, c);
    expect_zero_interior_force_with_correction(test::hydrogel(), c);
  }
}

TEST(BaForce, StressCorrectedRankLocalCloudReproducesOneRankForcesBitForBit)
{
  const test::SaintVenantKirchhoff2D svk;
  for (StressCorrection c : {StressCorrection::tensor, StressCorrection::scalar})
    test::expect_rank_local_views_reproduce_one_rank(
        [&](const PointCloud &cloud, const double *y, const Families &f, const nd::BondGeometry<2> &g, const BondState &s,
            double *c33, double *t, nd::Workspace<2> &ws) { return nd::compute_bond_forces<2>(ForceForm::bond_only, svk, cloud, y, f, g, s, c33, t, ws); },
        c);
}

TEST(BaForce, TensorCorrectedPointStressIsTheVirialOfTheForce)
{
  // point_quantities with a correction: P_i = sum_j t_ij (x) xi_ij V_j, the virial of
  // the corrected force (docs/stress_consistency.md), formed from the kernel's t_ij
  // here; under an affine motion it is P(A) at every point, edges and hole included.
  Body<2> body = test::plate(20, 20, kDx);
  body.holes.push_back({10.3 * kDx, 9.6 * kDx, 3.4 * kDx});
  test::Discretisation d(body);
  set_correction(d, StressCorrection::tensor);
  const GentPlaneStress model = test::hydrogel();
  std::mt19937          rng(5);
  const std::vector<double> affine = d.affine({1.3, 0.1, -0.05, 0.9});
  std::vector<double>       noisy  = affine;
  for (double &v : noisy) v += test::random_between(rng, -0.05, 0.05) * kDx;
  for (const std::vector<double> *state : {&affine, static_cast<const std::vector<double> *>(&noisy)}) {
    PointQuantities out;
    point_quantities(model, d.cloud, state->data(), d.families, test::nd_geometry(d), d.state, nullptr, d.size(),
                     StressWeights::bond_force, out);
    std::vector<double> t, f;
    d.forces(model, *state, t, f);
    double worst = 0, size = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Mat2 V = test::bond_force_virial(d, t, i);
      const Mat2 P = {out.nominal_stress[4 * i], out.nominal_stress[4 * i + 1], out.nominal_stress[4 * i + 2],
                      out.nominal_stress[4 * i + 3]};
      worst = std::max(worst, test::norm(P - V));
      size  = std::max(size, test::norm(V));
    }
    // the same terms summed in another order (and the plane-stress solve converged to
    // 1e-12 of S33 from another warm start)
    EXPECT_LT(worst, 1e-10 * size);
    if (state == &affine) {
      double c33 = 0;
      Mat2   PA;
      ASSERT_EQ(model.stress({1.3, 0.1, -0.05, 0.9}, c33, PA), StressStatus::ok);
      for (std::size_t i = 0; i < d.size(); ++i)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(out.nominal_stress[4 * i + c], PA[c], 1e-9 * test::norm(PA));
    }
  }
}

TEST(BaForce, WithoutACorrectionTheGeometryHoldsNoneAndTheForceIsThePapers)
{
  // -force_stress_correction none: no C_i stored, and the kernel's t_ij is eq 23 (the
  // straightforward implementation in ba_force_test.cpp), so that default runs are unchanged.
  test::Discretisation d(test::plate(12, 12, kDx));
  EXPECT_FALSE(d.geometry.corrected());
  EXPECT_TRUE(d.geometry.correction.empty());
  const Mat2 I = d.geometry.correction_of(5);
  EXPECT_EQ(I, (Mat2{1.0, 0.0, 0.0, 1.0}));
}
} // namespace
} // namespace bapd
