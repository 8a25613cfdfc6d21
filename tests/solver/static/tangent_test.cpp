// The static solver's tangent (ba_tangent.hpp, tangent_operator.hpp) is the derivative
// of its nodal force: H v against central differences of -V f, at a deformed state, in
// plane stress, plane strain (with the point volumetric energy too) and 3D, two laws;
// and the plane-stress law's exact dP/dF (PlaneStress::tangent) against differences of P.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bapd/solver/driver/simulation.hpp"
#include "bapd/core/materials/models.hpp"
#include "bapd/core/materials/numerical_tangent.hpp"
#include "bapd/solver/driver/static_solver.hpp"
#include "mpi/test_scenes.hpp"

using namespace bapd;

namespace {

// A smooth, non-affine field of amplitude `a` (m) over a body of size ~`L` (m).
template <int D> void Field(const Layout &layout, double a, double L, int phase, Vec u)
{
  double *x;
  VecGetArray(u, &x);
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    const double *p = &layout.cloud.x[D * i];
    for (int c = 0; c < D; ++c) {
      double s = std::sin((3.0 + c + phase) * p[0] / L + 1.3 * c) * std::cos((2.0 + phase) * p[1] / L - 0.7 * c);
      if (D == 3) s *= std::cos((1.5 + c) * p[D - 1] / L);
      x[D * i + c] = a * s + (c == 1 ? 0.15 * p[1] : -0.05 * p[0]); // 15 % stretch along y, 5 % shortening along x
    }
  }
  VecRestoreArray(u, &x);
}

// |H v - (R(u + e v) - R(u - e v)) / 2e| / |H v| at a deformed state.
// exact: the law's own dP/dF where it has one (the default), else differences everywhere.
// broken: the bonds that meet the scene's failure criterion at u broken first
// (StaticSolver::BreakAt); *broken (if given) how many.
template <int D> double TangentError(const std::string &options, bool exact = true, PetscInt *broken = nullptr)
{
  EXPECT_EQ(bapd_test::SetOptions(options), 0);
  SimulationD<D> sim(PETSC_COMM_WORLD);
  EXPECT_EQ(sim.Setup(), 0);
  StaticSolver<D> solver(sim);
  EXPECT_EQ(solver.Setup(), 0);
  solver.set_law_tangent(exact);
  Vec u, v, up, um, fp, fm, Hv;
  Mat H;
  VecDuplicate(solver.displacement(), &u);
  VecDuplicate(u, &v);
  VecDuplicate(u, &up);
  VecDuplicate(u, &um);
  VecDuplicate(u, &fp);
  VecDuplicate(u, &fm);
  VecDuplicate(u, &Hv);
  const double L = 0.01;
  Field<D>(sim.layout(), 2e-4, L, 0, u);
  Field<D>(sim.layout(), 1e-4, L, 1, v);
  if (broken) {
    EXPECT_EQ(solver.BreakAt(u, broken), 0);
  }
  EXPECT_EQ(solver.CreateMatrix(&H), 0);
  EXPECT_EQ(solver.Tangent(u, H), 0);
  MatMult(H, v, Hv);
  // e v moves a point ~1e-9 m (1e-6 dx): truncation O(e^2) ~ 1e-12 relative, round-off of
  // the force (~1e-13 relative, and the plane-stress C33 solve ~1e-12) over e ~ 1e-7.
  const double e = 1e-5;
  VecWAXPY(up, e, v, u);
  VecWAXPY(um, -e, v, u);
  EXPECT_EQ(solver.NodalForce(up, fp), 0);
  EXPECT_EQ(solver.NodalForce(um, fm), 0);
  VecAXPY(fp, -1.0, fm);
  VecScale(fp, 1.0 / (2 * e));
  double norm;
  VecNorm(Hv, NORM_2, &norm);
  VecAXPY(fp, -1.0, Hv);
  double diff;
  VecNorm(fp, NORM_2, &diff);
  for (Vec *w : {&u, &v, &up, &um, &fp, &fm, &Hv}) VecDestroy(w);
  MatDestroy(&H);
  PetscPrintf(PETSC_COMM_WORLD, "tangent error |Hv - dR| / |Hv| = %.3e\n", diff / norm);
  return diff / norm;
}

std::string Sheet(const std::string &extra)
{
  return bapd_test::FreeSheetScene("static_tangent_output") + " " + extra;
}

std::string Box(const std::string &extra)
{
  return "-body_dimension 3 -body_dx 0.001 -body_shapes block -body_block_type box -body_block_box 0,0,0,0.008,0.006,0.004 "
         "-horizon_factor 2.015 -material_mu 4.55e3 -material_Jm 162.6 -material_density 1000 -end_time 1 "
         "-output_interval 1000000 -progress_interval 1000000 -output_dir " +
         bapd_test::OutputDirPerRankCount("static_tangent_output_3d") + " " + extra;
}

} // namespace

// The tangent uses central differences of P with step 1e-4 max(1, |F|): O(1e-8) relative
// (numerical_tangent.hpp); the force's differences add ~1e-9. 1e-6 leaves two orders.
constexpr double tolerance = 1e-6;

TEST(StaticTangent, PlaneStressMatchesForceDifferences)
{
  // gent and neo_hookean: the law's exact tangent, and differences of P; mooney_rivlin
  // (a law of I2bar): differences.
  for (const char *law : {"gent", "neo_hookean", "mooney_rivlin"})
    for (bool exact : {true, false}) {
      const double err = TangentError<2>(Sheet(std::string("-material_model ") + law + " -material_bulk_ratio 1000"), exact);
      EXPECT_LT(err, tolerance) << law << (exact ? " (the law's tangent)" : " (differences)");
    }
}

// PlaneStress::tangent against central differences of P (numerical_tangent.hpp): at rest, in tension, shear, compression, pure shear at stretch 5 and
// near the Gent chain limit (stretch 9 uniaxial, I1bar - 3 about 0.5 Jm).
template <class Model> void LawTangentMatchesDifferences(const Model &model, const char *name)
{
  const std::vector<Mat2> states = {{1, 0, 0, 1},      {1.5, 0, 0, 1},       {1, 0.4, 0, 1},   {0.7, 0.1, -0.05, 0.9},
                                    {5, 0, 0, 0.2},    {1.3, 0.7, -0.2, 2.1}, {9, 0, 0, 0.35}};
  for (const Mat2 &F : states) {
    Tangent2               coarse, fine;
    std::array<double, 16> exact;
    ASSERT_EQ(numerical_tangent(model, F, 0.0, coarse, 2e-4), StressStatus::ok);
    ASSERT_EQ(numerical_tangent(model, F, 0.0, fine, 1e-4), StressStatus::ok);
    ASSERT_EQ(model.tangent(F, 0.0, exact), StressStatus::ok);
    double worst = 0, size = 0;
    for (int e = 0; e < 16; ++e) {
      const double extrapolated = (4 * fine[e] - coarse[e]) / 3; // Richardson: O(h^4)
      worst                     = std::max(worst, std::abs(exact[e] - extrapolated));
      size                      = std::max(size, std::abs(exact[e]));
    }
    // The differences' step h = 1e-4 max|F| is up to 2.5e-3 of the smallest F component
    // here: O(h^4) truncation ~1e-10 after extrapolation, and the plane-stress solve's
    // 1e-12 noise over h ~1e-8 of |A|. An error in A shows at 1e-3 and above.
    EXPECT_LT(worst, 1e-7 * size) << name << " at F = " << F[0] << "," << F[1] << "," << F[2] << "," << F[3];
  }
}

TEST(StaticTangent, PlaneStressLawTangentMatchesDifferences)
{
  MaterialParameters p;
  p.mu              = 4.55e3;
  p["-material_Jm"] = 162.6;
  p.D               = 2.0 / (1000 * p.mu);
  LawTangentMatchesDifferences(GentPlaneStress{p}, "gent");
  LawTangentMatchesDifferences(NeoHookeanPlaneStress{p}, "neo_hookean");
  p.D = 2.0 / (10 * p.mu); // compressible
  LawTangentMatchesDifferences(GentPlaneStress{p}, "gent, K = 10 mu");
}

TEST(StaticTangent, PlaneStrainMatchesForceDifferences)
{
  for (const char *law : {"gent", "mooney_rivlin"}) {
    const double err = TangentError<2>(Sheet(std::string("-material_model ") + law + " -material_formulation plane_strain"));
    EXPECT_LT(err, tolerance) << law;
  }
}

TEST(StaticTangent, PointVolumetricMatchesForceDifferences)
{
  const double err = TangentError<2>(Sheet("-material_formulation plane_strain -material_bulk_ratio 1000 -material_volumetric point"));
  EXPECT_LT(err, tolerance);
  const double err3 = TangentError<3>(Box("-material_model gent -material_bulk_ratio 1000 -material_volumetric point"));
  EXPECT_LT(err3, tolerance);
}

TEST(StaticTangent, SolidMatchesForceDifferences)
{
  for (const char *law : {"gent", "yeoh"}) {
    const double err = TangentError<3>(Box(std::string("-material_model ") + law + " -material_bulk_ratio 100"));
    EXPECT_LT(err, tolerance) << law;
  }
}

// With bonds broken (here those stretched past 1.1 at u, some of every family near the
// stretched regions: the static solver's state after a breaking pass), the tangent is
// still the force's derivative: both drop the broken bonds from the BA families and
// recompute the points' shape tensors (bond_state.hpp).
TEST(StaticTangent, BrokenBondsMatchForceDifferences)
{
  PetscInt broken = 0;
  const double err = TangentError<2>(Sheet("-material_model gent -material_bulk_ratio 1000 -failure_critical_stretch 1.1"), true, &broken);
  EXPECT_LT(err, tolerance);
  EXPECT_GT(broken, 100) << "too few bonds broken for the test to see them";
  PetscInt broken3 = 0;
  const double err3 = TangentError<3>(Box("-material_model gent -material_bulk_ratio 100 -failure_critical_stretch 1.1"), true, &broken3);
  EXPECT_LT(err3, tolerance);
  EXPECT_GT(broken3, 100) << "too few bonds broken for the test to see them";
  PetscPrintf(PETSC_COMM_WORLD, "bonds broken: %d (2D), %d (3D)\n", (int)broken, (int)broken3);
}
