// Per-point stress, deformation and energy for output (point_quantities.hpp): an
// affine motion gives the model's P(A), A, lambda_3(A), sigma = P A^T / J and Psi(A)
// at every point; a rotation rotates them; a point without bonds gets zeros.
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/materials/gent.hpp"
#include "bapd/core/kernel/point_quantities.hpp"
#include "materials/deformations.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

constexpr double kPi = 3.141592653589793;

const MaterialParameters kGel = test::parameters(4.55e3, 162.6, 2.0 / (100 * 4.55e3)); // K = 100 mu, as the scenes
const Mat2               kStretch = {1.6, 0.3, -0.1, 0.8};            // large, sheared, not symmetric

Mat2 rotation(double deg)
{
  const double a = deg * kPi / 180.0;
  return {std::cos(a), -std::sin(a), std::sin(a), std::cos(a)};
}

Mat2 at(const std::vector<double> &v, std::size_t i) { return {v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]}; }

// Relative round-off bound: F_ij = A to about cond(K) eps ~ 1e-14 (bond_geometry.hpp),
// the plane-stress C33 solve stops at ~1e-13 of the stress scale, and the weighted
// mean of ~28 equal values adds ~28 eps.
constexpr double kRoundOff = 1e-11;

void expect_near(const Mat2 &a, const Mat2 &b, double scale, const char *what, std::size_t i)
{
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[c], b[c], kRoundOff * scale) << what << " component " << c << " at point " << i;
}

struct Expected {
  Mat2   P, F, sigma;
  double lambda_3, psi;
};

Expected model_at(Formulation formulation, const Mat2 &A)
{
  Expected e;
  double   c = 0.0, c_energy = 0.0;
  e.F        = A;
  if (formulation == Formulation::plane_stress) {
    const GentPlaneStress model{kGel};
    EXPECT_EQ(model.stress(A, c, e.P), StressStatus::ok);
    EXPECT_EQ(model.energy(A, c_energy, e.psi), StressStatus::ok);
  } else {
    const GentPlaneStrain model{kGel};
    EXPECT_EQ(model.stress(A, c, e.P), StressStatus::ok);
    EXPECT_EQ(model.energy(A, c_energy, e.psi), StressStatus::ok);
  }
  e.lambda_3 = std::sqrt(c);
  const double J = det(A) * e.lambda_3;
  e.sigma        = (1.0 / J) * (e.P * transpose(A));
  return e;
}

void check_affine(Formulation formulation, StressWeights weights, const Mat2 &A)
{
  const test::Discretisation d(test::plate(16, 12));
  const std::vector<double>  y = d.affine(A, 2e-3, -1e-3);
  PointQuantities            q;
  point_quantities(ModelKind::gent, formulation, kGel, d.cloud, y.data(), d.families, test::nd_geometry(d), d.state, nullptr,
                   d.size(), weights, q);
  const Expected e     = model_at(formulation, A);
  const double   scale = test::norm(e.P);
  ASSERT_GT(scale, kGel.mu); // a large deformation
  for (std::size_t i = 0; i < d.size(); ++i) { // boundary points too: F_ij = A for every usable bond
    expect_near(at(q.nominal_stress, i), e.P, scale, "P", i);
    expect_near(at(q.deformation_gradient, i), e.F, test::norm(A), "F", i);
    expect_near(at(q.cauchy_stress, i), e.sigma, test::norm(e.sigma), "sigma", i);
    EXPECT_NEAR(q.thickness_stretch[i], e.lambda_3, kRoundOff) << "lambda_3 at point " << i;
    EXPECT_NEAR(q.strain_energy_density[i], e.psi, kRoundOff * e.psi) << "W at point " << i;
  }
}

TEST(PointQuantities, AffineMotionGivesTheModelStressInPlaneStress)
{
  check_affine(Formulation::plane_stress, StressWeights::bond_force, kStretch);
  check_affine(Formulation::plane_stress, StressWeights::bond_energy, kStretch);
}

TEST(PointQuantities, AffineMotionGivesTheModelStressInPlaneStrain)
{
  check_affine(Formulation::plane_strain, StressWeights::bond_force, kStretch);
  const Expected e = model_at(Formulation::plane_strain, kStretch);
  EXPECT_EQ(e.lambda_3, 1.0);
}

TEST(PointQuantities, ThicknessStretchIsTheIncompressibleOneForAStiffGel)
{
  // K = 100 mu: J = det F~ lambda_3 stays within a few 1e-3 of 1.
  const Expected e = model_at(Formulation::plane_stress, kStretch);
  EXPECT_NEAR(e.lambda_3 * det(kStretch), 1.0, 1e-2);
  EXPECT_LT(e.lambda_3, 1.0);
}

// P(QA) = Q P(A), sigma(QA) = Q sigma(A) Q^T; lambda_3 and W do not change.
TEST(PointQuantities, RotationRotatesTheStress)
{
  const test::Discretisation d(test::plate(14, 14));
  const Mat2                 Q = rotation(35.0), QA = Q * kStretch;
  PointQuantities            a, b;
  const std::vector<double>  ya = d.affine(kStretch), yb = d.affine(QA);
  for (auto [y, out] : {std::pair{&ya, &a}, std::pair{&yb, &b}})
    point_quantities(ModelKind::gent, Formulation::plane_stress, kGel, d.cloud, y->data(), d.families, test::nd_geometry(d),
                     d.state, nullptr, d.size(), StressWeights::bond_force, *out);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const Mat2 P = at(a.nominal_stress, i), sigma = at(a.cauchy_stress, i);
    expect_near(at(b.nominal_stress, i), Q * P, test::norm(P), "rotated P", i);
    expect_near(at(b.cauchy_stress, i), Q * sigma * transpose(Q), test::norm(sigma), "rotated sigma", i);
    EXPECT_NEAR(b.thickness_stretch[i], a.thickness_stretch[i], kRoundOff);
    EXPECT_NEAR(b.strain_energy_density[i], a.strain_energy_density[i], kRoundOff * a.strain_energy_density[i]);
  }
}

// A point cut off from all its neighbours carries no stress: zeros, not NaN; its
// neighbours keep P(A) from their other bonds.
TEST(PointQuantities, PointWithoutBondsGetsZeros)
{
  test::Discretisation d(test::plate(12, 12));
  const std::size_t    lone = 6 * 12 + 6;
  std::vector<std::size_t> touched;
  while (true) {
    std::size_t q = 0;
    while (q < d.families.size(lone) && !d.state.is_intact(lone, q)) ++q;
    if (q == d.families.size(lone)) break;
    break_bond(d.families, d.state, lone, q, &touched);
  }
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  const std::vector<double> y = d.affine(kStretch);
  PointQuantities           q;
  point_quantities(ModelKind::gent, Formulation::plane_stress, kGel, d.cloud, y.data(), d.families, test::nd_geometry(d), d.state,
                   nullptr, d.size(), StressWeights::bond_force, q);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(q.nominal_stress[4 * lone + c], 0.0);
    EXPECT_EQ(q.cauchy_stress[4 * lone + c], 0.0);
    EXPECT_EQ(q.deformation_gradient[4 * lone + c], 0.0);
  }
  EXPECT_EQ(q.thickness_stretch[lone], 0.0);
  EXPECT_EQ(q.strain_energy_density[lone], 0.0);
  const Expected  e         = model_at(Formulation::plane_stress, kStretch);
  const std::size_t neighbour = lone + 1;
  expect_near(at(q.nominal_stress, neighbour), e.P, test::norm(e.P), "P next to the lone point", neighbour);
}

} // namespace
} // namespace bapd
