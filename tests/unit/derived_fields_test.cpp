// The fields derived for output (derived_fields.hpp): the von Mises stress and the
// principal stretches take their analytic values on stress states and deformation
// gradients of known principal values, in any frame, and on a homogeneous deformation
// of a lattice through point_quantities (2D plane stress and 3D), at every point.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "bapd/core/kernel/point_quantities.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/solver/io/derived_fields.hpp"
#include "materials/deformations.hpp"
#include "unit/kernel_fixtures_3d.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

using Mat3 = std::array<double, 9>;

constexpr double kPi = 3.141592653589793;

Mat2 rotation2(double deg)
{
  const double a = deg * kPi / 180.0;
  return {std::cos(a), -std::sin(a), std::sin(a), std::cos(a)};
}

// A rotation about the axis (1, 2, 2) / 3 (Rodrigues): every component non-zero.
Mat3 rotation3(double deg)
{
  const double a = deg * kPi / 180.0, c = std::cos(a), s = std::sin(a), n[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  Mat3 R;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) {
      const double cross = r == q ? 0.0 : ((q == (r + 1) % 3) ? -1.0 : 1.0) * n[3 - r - q];
      R[3 * r + q]       = (r == q ? c : 0.0) + (1 - c) * n[r] * n[q] + s * cross;
    }
  return R;
}

Mat3 multiply3(const Mat3 &a, const Mat3 &b)
{
  Mat3 m{};
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q)
      for (int k = 0; k < 3; ++k) m[3 * r + q] += a[3 * r + k] * b[3 * k + q];
  return m;
}

Mat3 transpose3(const Mat3 &a)
{
  Mat3 t;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) t[3 * q + r] = a[3 * r + q];
  return t;
}

Mat3 diagonal(double a, double b, double c) { return {a, 0, 0, 0, b, 0, 0, 0, c}; }

// Q diag R^T: principal values diag, in rotated frames on both sides.
Mat3 rotated(const Mat3 &d, double left, double right) { return multiply3(multiply3(rotation3(left), d), transpose3(rotation3(right))); }

// Round-off: a few products and sums of O(1) numbers, a square root, and the Jacobi
// rotations (each exact to a few eps): 1e-13 relative leaves two orders of margin.
constexpr double kRoundOff = 1e-13;

TEST(VonMisesStress, UniaxialShearAndEquibiaxialStatesIn2D)
{
  const double s = 3.7e4;
  const double uniaxial[4] = {s, 0, 0, 0}, shear[4] = {0, s, s, 0}, equibiaxial[4] = {s, 0, 0, s};
  EXPECT_NEAR(von_mises_stress<2>(uniaxial), s, kRoundOff * s);
  EXPECT_NEAR(von_mises_stress<2>(shear), std::sqrt(3.0) * s, kRoundOff * s);
  // sigma_33 = 0 (plane stress): equibiaxial in plane is uniaxial in the thickness.
  EXPECT_NEAR(von_mises_stress<2>(equibiaxial), s, kRoundOff * s);
}

TEST(VonMisesStress, InvariantAndZeroForAHydrostaticStateIn3D)
{
  const double s1 = 2.0e4, s2 = -0.5e4, s3 = 1.1e4;
  // sqrt(((s1 - s2)^2 + (s2 - s3)^2 + (s3 - s1)^2) / 2) in any frame.
  const double expected = std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  const Mat3   Q = rotation3(37), sigma = multiply3(multiply3(Q, diagonal(s1, s2, s3)), transpose3(Q));
  EXPECT_NEAR(von_mises_stress<3>(sigma.data()), expected, kRoundOff * expected);
  const Mat3 pressure = diagonal(-4e3, -4e3, -4e3);
  EXPECT_NEAR(von_mises_stress<3>(pressure.data()), 0.0, kRoundOff * 4e3);
  // Only the symmetric part counts: an antisymmetric part adds nothing.
  Mat3 skewed = sigma;
  skewed[1] += 900, skewed[3] -= 900;
  EXPECT_NEAR(von_mises_stress<3>(skewed.data()), expected, kRoundOff * expected);
}

TEST(PrincipalStretches, SingularValuesOfARotatedStretchIn2D)
{
  // F = Q diag(2, 0.5) R^T: stretches 2 and 0.5 (largest first), then lambda_3.
  const Mat2 F = rotation2(35) * Mat2{2.0, 0, 0, 0.5} * transpose(rotation2(-20));
  double     stretch[3];
  principal_stretches<2>(F.data(), 0.9, stretch);
  EXPECT_NEAR(stretch[0], 2.0, kRoundOff * 2);
  EXPECT_NEAR(stretch[1], 0.5, kRoundOff * 2);
  EXPECT_EQ(stretch[2], 0.9);
  // A rotation: all ones.
  const Mat2 R = rotation2(71);
  principal_stretches<2>(R.data(), 1.0, stretch);
  for (double s : stretch) EXPECT_NEAR(s, 1.0, kRoundOff);
}

TEST(PrincipalStretches, EigenvaluesOfURotatedIn3DIncludingARepeatedOne)
{
  double stretch[3];
  principal_stretches<3>(rotated(diagonal(0.6, 1.3, 1.1), 40, -65).data(), 0, stretch);
  EXPECT_NEAR(stretch[0], 1.3, kRoundOff * 1.3);
  EXPECT_NEAR(stretch[1], 1.1, kRoundOff * 1.3);
  EXPECT_NEAR(stretch[2], 0.6, kRoundOff * 1.3);
  // Uniaxial with a repeated transverse stretch: 1.8, 1/sqrt(1.8) twice.
  const double t = 1.0 / std::sqrt(1.8);
  principal_stretches<3>(rotated(diagonal(t, 1.8, t), 15, 110).data(), 0, stretch);
  EXPECT_NEAR(stretch[0], 1.8, kRoundOff * 1.8);
  EXPECT_NEAR(stretch[1], t, kRoundOff * 1.8);
  EXPECT_NEAR(stretch[2], t, kRoundOff * 1.8);
}

// A homogeneous deformation F = Q diag(1.5, 0.8) R^T of a plate in plane stress
// (Gent, K = 100 mu): at every point the principal stretches 1.5, 0.8 and the law's
// lambda_3, and the von Mises stress of its principal Cauchy stresses,
// sqrt(s1^2 + s2^2 - s1 s2) (sigma_33 = 0), whatever Q and R (isotropy).
TEST(DerivedFields, HomogeneousDeformationOfAPlateInPlaneStress)
{
  const MaterialParameters   gel = test::parameters(4.55e3, 162.6, 2.0 / (100 * 4.55e3));
  const Mat2                 principal = {1.5, 0, 0, 0.8};
  const Mat2                 A = rotation2(30) * principal * transpose(rotation2(-20));
  const test::Discretisation d(test::plate(16, 12));
  const std::vector<double>  y = d.affine(A, 2e-3, -1e-3);
  PointQuantities            q;
  point_quantities(ModelKind::gent, Formulation::plane_stress, gel, d.cloud, y.data(), d.families, test::nd_geometry(d), d.state,
                   nullptr, d.size(), StressWeights::bond_energy, q);
  std::vector<double> von_mises(d.size()), stretch(3 * d.size());
  derived_fields<2>(d.size(), q.cauchy_stress.data(), q.deformation_gradient.data(), q.thickness_stretch.data(), von_mises.data(),
                    stretch.data());
  // The law at the principal stretches: sigma = diag(s1, s2) = P diag^T / J.
  const GentPlaneStress model{gel};
  double                c = 0;
  Mat2                  P;
  ASSERT_EQ(model.stress(principal, c, P), StressStatus::ok);
  const double lambda_3 = std::sqrt(c), J = 1.5 * 0.8 * lambda_3;
  const double s1 = P[0] * 1.5 / J, s2 = P[3] * 0.8 / J;
  const double expected = std::sqrt(s1 * s1 + s2 * s2 - s1 * s2);
  ASSERT_GT(expected, gel.mu); // a large deformation
  EXPECT_NEAR(lambda_3 * 1.5 * 0.8, 1.0, 1e-2); // nearly incompressible (K = 100 mu)
  // F_i = A and sigma_i to 1e-11 relative (point_quantities_test.cpp): the derived
  // values to the same bound.
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(von_mises[i], expected, 1e-11 * expected) << "von Mises at point " << i;
    EXPECT_NEAR(stretch[3 * i], 1.5, 1e-11) << "lambda_1 at point " << i;
    EXPECT_NEAR(stretch[3 * i + 1], 0.8, 1e-11) << "lambda_2 at point " << i;
    EXPECT_NEAR(stretch[3 * i + 2], lambda_3, 1e-11) << "lambda_3 at point " << i;
  }
}

// The same in 3D: F = Q diag(1.4, 0.9, 0.8) R^T of a box (Gent 3D): the three
// stretches, and the von Mises stress of the law's Cauchy stress at diag (isotropy).
TEST(DerivedFields, HomogeneousDeformationOfABoxIn3D)
{
  const Mat3         principal = diagonal(0.9, 1.4, 0.8);
  const Mat3         A         = rotated(principal, 25, -50);
  test3d::Body3D     b(7);
  test3d::Mat3d      A3;
  for (int k = 0; k < 9; ++k) A3[k] = A[k];
  const std::vector<double> y = b.affine(A3, {2e-3, -1e-3, 5e-4});
  PointQuantities           q;
  const auto                model = test3d::gent();
  point_quantities<3>(model, b.cloud, y.data(), b.families, b.geometry, b.state, nullptr, b.size(), StressWeights::bond_energy, q);
  std::vector<double> von_mises(b.size()), stretch(3 * b.size());
  derived_fields<3>(b.size(), q.cauchy_stress.data(), q.deformation_gradient.data(), nullptr, von_mises.data(), stretch.data());
  test3d::Mat3d D, P;
  for (int k = 0; k < 9; ++k) D[k] = principal[k];
  ASSERT_EQ(model.stress(D, P), StressStatus::ok);
  const double J = 0.9 * 1.4 * 0.8, s1 = P[0] * 0.9 / J, s2 = P[4] * 1.4 / J, s3 = P[8] * 0.8 / J;
  const double expected = std::sqrt(0.5 * ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)));
  ASSERT_GT(expected, test3d::gel().mu);
  for (std::size_t i = 0; i < b.size(); ++i) {
    EXPECT_NEAR(von_mises[i], expected, 1e-11 * expected) << "von Mises at point " << i;
    EXPECT_NEAR(stretch[3 * i], 1.4, 1e-11) << "lambda_1 at point " << i;
    EXPECT_NEAR(stretch[3 * i + 1], 0.9, 1e-11) << "lambda_2 at point " << i;
    EXPECT_NEAR(stretch[3 * i + 2], 0.8, 1e-11) << "lambda_3 at point " << i;
  }
}

} // namespace
} // namespace bapd
