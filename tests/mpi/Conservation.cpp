// Conservation laws of the explicit dynamics on a free body, on any rank layout.
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/reproducible_sum.hpp"
#include "bapd/simulation.hpp"
#include "mpi/test_scenes.hpp"

using namespace bapd;

namespace {

// Sets u, v of the owned points from functions of the reference position.
template <class U, class V> void SetState(Simulation &sim, U &&u_of, V &&v_of)
{
  const Layout  &layout = sim.layout();
  const PetscInt n      = layout.n_owned;
  double        *x;
  VecGetArray(sim.state(), &x);
  for (PetscInt i = 0; i < n; ++i) {
    const double px = layout.cloud.x[2 * i], py = layout.cloud.x[2 * i + 1];
    const auto   u = u_of(px, py), v = v_of(px, py);
    x[2 * i] = u[0], x[2 * i + 1] = u[1];
    x[2 * n + 2 * i] = v[0], x[2 * n + 2 * i + 1] = v[1];
  }
  VecRestoreArray(sim.state(), &x);
}

void Momentum(Simulation &sim, double p[2])
{
  const Layout  &layout = sim.layout();
  const PetscInt n      = layout.n_owned;
  const double  *x;
  std::vector<double> terms(2 * n);
  VecGetArrayRead(sim.state(), &x);
  for (PetscInt i = 0; i < n; ++i)
    for (int c = 0; c < 2; ++c) terms[2 * i + c] = sim.scene().density * layout.cloud.volume[i] * x[2 * n + 2 * i + c];
  VecRestoreArrayRead(sim.state(), &x);
  ReproducibleSum(PETSC_COMM_WORLD, 2, n, terms.data(), p);
}

} // namespace

// Internal forces sum to zero (paper eq 23 is antisymmetric in i, j), so a free body
// keeps its linear momentum whatever its deformation.
TEST(Conservation, FreeBodyKeepsItsLinearMomentum)
{
  ASSERT_EQ(bapd_test::SetOptions(bapd_test::FreeSheetScene("conservation_output") + " -end_time 100"), 0);
  Simulation sim(PETSC_COMM_WORLD);
  ASSERT_EQ(sim.Setup(), 0);
  // Drift plus a non-uniform, finite-amplitude velocity and displacement.
  SetState(
    sim, [](double x, double y) { return std::array<double, 2>{1e-4 * std::sin(400 * y), 2e-4 * std::cos(300 * x) * y / 0.02}; },
    [](double x, double y) { return std::array<double, 2>{0.03 + 0.01 * std::sin(500 * x * y / 0.02), -0.02 + 0.01 * std::cos(200 * y)}; });
  double p0[2], p1[2];
  Momentum(sim, p0);
  ASSERT_EQ(sim.Advance(500), 0);
  Momentum(sim, p1);
  const double scale = std::hypot(p0[0], p0[1]);
  // Each step adds dt * sum f_i V_i, zero up to round-off of ~10^4 terms per step.
  EXPECT_NEAR(p1[0], p0[0], 1e-10 * scale);
  EXPECT_NEAR(p1[1], p0[1], 1e-10 * scale);
}

// An undamped elastic vibration at the default time step (0.8 x the stable step):
// the total energy stays put. The bond-only force form of the paper (eq 23) is not
// the exact gradient of the stored energy, so the tolerance is a measured bound
// (docs/validation.md), not round-off.
TEST(Conservation, UndampedVibrationKeepsItsEnergy)
{
  ASSERT_EQ(bapd_test::SetOptions(bapd_test::FreeSheetScene("conservation_output") + " -end_time 100 " + std::string(getenv("EXTRA") ? getenv("EXTRA") : "")), 0);
  Simulation sim(PETSC_COMM_WORLD);
  ASSERT_EQ(sim.Setup(), 0);
  SetState(
    sim, [](double x, double y) { return std::array<double, 2>{2e-4 * std::sin(M_PI * x / 0.02) * std::cos(M_PI * y / 0.02), 1e-4 * std::sin(M_PI * y / 0.02)}; },
    [](double, double) { return std::array<double, 2>{0.0, 0.0}; });
  double k0, w0;
  ASSERT_EQ(sim.Energies(&k0, &w0), 0);
  const double e0 = k0 + w0;
  ASSERT_GT(w0, 0.0);
  double worst = 0, kmax = 0;
  for (int chunk = 0; chunk < 20; ++chunk) {
    ASSERT_EQ(sim.Advance(500), 0);
    double k, w;
    ASSERT_EQ(sim.Energies(&k, &w), 0);
    worst = std::max(worst, std::fabs(k + w - e0) / e0);
    kmax  = std::max(kmax, k);
  }
  PetscPrintf(PETSC_COMM_WORLD, "energy: E0 = %.6e J, max |E - E0|/E0 over 10000 steps = %.3e, max kinetic %.3e J\n", e0, worst, kmax);
  EXPECT_GT(kmax, 0.1 * e0); // it really vibrates
  EXPECT_LT(worst, 0.02);
}
