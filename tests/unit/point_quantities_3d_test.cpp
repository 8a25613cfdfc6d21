// Per-point stress, deformation and energy at D = 3 (point_quantities.hpp): an affine
// motion of a 3D box lattice gives, at every point, F_i = A, the 3D
// law's own P(A), sigma = P(A) A^T / det A and Psi(A), for both weights and with the
// tensor correction (virial weights); a rigid rotation of a deformed state with broken
// bonds rotates P and sigma; a point without bonds gets zeros.
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/kernel/point_quantities.hpp"
#include "unit/kernel_fixtures_3d.hpp"

namespace bapd {
namespace {

using test3d::Body3D;
using test3d::Mat3d;

// Large, sheared, not symmetric, det = 1.47: far from the identity.
const Mat3d kA = {1.4, 0.2, -0.1, 0.05, 0.9, 0.15, 0.1, -0.08, 1.2};

Mat3d at(const std::vector<double> &v, std::size_t i)
{
  Mat3d m;
  for (int k = 0; k < 9; ++k) m[k] = v[9 * i + k];
  return m;
}

// F_ij = A to about cond(K) eps (bond_geometry.hpp); the weighted means of ~122
// equal values add ~122 eps; the law adds a few eps of its own: 1e-11 leaves two
// orders of margin and catches any wrong weight, transpose or determinant.
constexpr double kRoundOff = 1e-11;

void expect_near(const Mat3d &a, const Mat3d &b, double scale, const char *what, std::size_t i)
{
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(a[k], b[k], kRoundOff * scale) << what << " component " << k << " at point " << i;
}

template <class Model> void check_affine(const Model &model, StressWeights weights, StressCorrection correction)
{
  Body3D b(7);
  if (correction != StressCorrection::none) b.set_correction(correction);
  const std::vector<double> y = b.affine(kA, {2e-3, -1e-3, 5e-4});
  PointQuantities           q;
  point_quantities<3>(model, b.cloud, y.data(), b.families, b.geometry, b.state, nullptr, b.size(), weights, q);
  // The law's own stress and energy at F = A, and the Cauchy stress formed here.
  Mat3d  P;
  double psi = 0;
  ASSERT_EQ(model.stress(kA, P), StressStatus::ok);
  ASSERT_EQ(model.energy(kA, psi), StressStatus::ok);
  const double J     = nd::det<3>(kA);
  Mat3d        sigma = nd::multiply<3>(P, nd::transpose<3>(kA));
  for (double &s : sigma) s /= J;
  ASSERT_GT(test3d::norm(P), test3d::gel().mu); // a large deformation
  EXPECT_EQ(q.dimension, 3);
  EXPECT_TRUE(q.thickness_stretch.empty()); // no C33 in 3D
  ASSERT_EQ(q.nominal_stress.size(), 9 * b.size());
  for (std::size_t i = 0; i < b.size(); ++i) { // boundary points too: F_ij = A for every usable bond
    expect_near(at(q.deformation_gradient, i), kA, test3d::norm(kA), "F", i);
    expect_near(at(q.nominal_stress, i), P, test3d::norm(P), "P", i);
    expect_near(at(q.cauchy_stress, i), sigma, test3d::norm(sigma), "sigma", i);
    EXPECT_NEAR(q.strain_energy_density[i], psi, kRoundOff * psi) << "W at point " << i;
  }
}

TEST(PointQuantities3D, AffineMotionGivesTheGentStressWithEnergyWeights)
{
  check_affine(test3d::gent(), StressWeights::bond_energy, StressCorrection::none);
}

TEST(PointQuantities3D, AffineMotionGivesTheGentStressWithForceWeights)
{
  check_affine(test3d::gent(), StressWeights::bond_force, StressCorrection::none);
}

TEST(PointQuantities3D, AffineMotionGivesTheNeoHookeanStressAsTheTensorCorrectedVirial)
{
  // With the tensor correction P_i is the virial sum_j P(F_ij) B_ij, sum_j B_ij = C_i M_i = I.
  check_affine(test3d::neo_hookean(), StressWeights::bond_force, StressCorrection::tensor);
}

TEST(PointQuantities3D, RotationRotatesTheStress)
{
  // Objectivity: y -> Q y gives F_i -> Q F_i, P_i -> Q P_i, sigma_i -> Q sigma_i Q^T,
  // W_i unchanged, at every point of a non-affine state with broken bonds.
  Body3D b(6);
  b.break_some(5);
  const std::vector<double> y = b.deformed({1.3, 0.1, 0.0, -0.05, 0.9, 0.1, 0.0, 0.08, 1.1}, 0.1, 3);
  const Mat3d               Q = test3d::rotation(71.0, 0.4, -1.0, 0.3);
  std::vector<double>       yq(y.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    const auto r = nd::multiply<3>(Q, nd::Vec<3>{y[3 * i], y[3 * i + 1], y[3 * i + 2]});
    for (int k = 0; k < 3; ++k) yq[3 * i + k] = r[k];
  }
  PointQuantities a, c;
  point_quantities<3>(test3d::gent(), b.cloud, y.data(), b.families, b.geometry, b.state, nullptr, b.size(),
                      StressWeights::bond_energy, a);
  point_quantities<3>(test3d::gent(), b.cloud, yq.data(), b.families, b.geometry, b.state, nullptr, b.size(),
                      StressWeights::bond_energy, c);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Mat3d P = at(a.nominal_stress, i), sigma = at(a.cauchy_stress, i);
    ASSERT_GT(test3d::norm(P), 0.0);
    expect_near(at(c.nominal_stress, i), nd::multiply<3>(Q, P), test3d::norm(P), "rotated P", i);
    expect_near(at(c.cauchy_stress, i), nd::multiply<3>(nd::multiply<3>(Q, sigma), nd::transpose<3>(Q)), test3d::norm(sigma),
                "rotated sigma", i);
    EXPECT_NEAR(c.strain_energy_density[i], a.strain_energy_density[i], kRoundOff * a.strain_energy_density[i]) << i;
  }
}

TEST(PointQuantities3D, PointWithoutBondsGetsZeros)
{
  Body3D                    b(5);
  const std::size_t         lone = 2 + 5 * 2 + 25 * 2; // the centre
  std::vector<std::size_t>  touched;
  for (std::size_t q = 0; q < b.families.size(lone); ++q) break_bond(b.families, b.state, lone, q, &touched);
  nd::compute_bond_geometry<3>(b.cloud, b.families, b.state, b.geometry, touched);
  const std::vector<double> y = b.affine(kA);
  PointQuantities           q;
  point_quantities<3>(test3d::gent(), b.cloud, y.data(), b.families, b.geometry, b.state, nullptr, b.size(),
                      StressWeights::bond_force, q);
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(q.nominal_stress[9 * lone + k], 0.0);
    EXPECT_EQ(q.cauchy_stress[9 * lone + k], 0.0);
    EXPECT_EQ(q.deformation_gradient[9 * lone + k], 0.0);
  }
  EXPECT_EQ(q.strain_energy_density[lone], 0.0);
  EXPECT_GT(std::fabs(q.nominal_stress[0]), 0.0); // the others still carry stress
}

} // namespace
} // namespace bapd
