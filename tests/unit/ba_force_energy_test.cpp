// The energy-consistent BA force (ba_force.hpp): it is minus the gradient of
// nd::strain_energy<2>(), its tangent is symmetric, Verlet conserves its energy, it conserves
// angular momentum, and it keeps the bond-only form's linear momentum balance,
// objectivity, patch test, failure reporting and rank-layout independence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "bapd/core/kernel/damage.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/plane_stress_incompressible.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

constexpr double kDx = 0.5e-3;
constexpr double kPi = 3.141592653589793;

using test::CutPlate;
using test::force_terms;
using test::hydrogel;
using test::max_abs;
using test::rotation;
using test::stiffness_asymmetry;

TEST(BaForceEnergy, BaMasksAreSymmetricWithinAFamily)
{
  // The kernel's premise: p in B_iq iff q in B_ip, so the bonds whose BA family holds
  // p are the set bits of bond (i -> p)'s own mask.
  for (double factor : {3.015, 5.015}) {
    CutPlate                   c(20, 0.0, 1, factor);
    const Families            &f = c.d.families;
    std::size_t                checked = 0;
    for (std::size_t i = 0; i < c.d.size(); ++i)
      for (std::size_t p = 0; p < f.size(i); ++p)
        for (std::size_t q = 0; q < f.size(i); ++q) {
          const bool pq = (f.ba(f.offsets[i] + q)[p / 64] >> (p % 64)) & 1u;
          const bool qp = (f.ba(f.offsets[i] + p)[q / 64] >> (q % 64)) & 1u;
          ASSERT_EQ(pq, qp) << "point " << i << " members " << p << ", " << q;
          checked += pq;
        }
    EXPECT_GT(checked, 100000u);
  }
}

// f = -(1/V) dW/dy straight from the definition of W (ba_force.hpp): every
// bond's dPsi/dF scattered to the members of its BA family (found by distance, not by
// the masks) and to its origin. No symmetry of the masks, no complement sums.
template <class Model>
std::vector<double> reference_force(const test::Discretisation &d, const Model &model, const std::vector<double> &y)
{
  const Families     &fam = d.families;
  const PointCloud   &c   = d.cloud;
  std::vector<double> grad(2 * d.size(), 0.0);
  for (std::size_t i = 0; i < d.size(); ++i) {
    struct Term {
      std::size_t q;
      Mat2        P, Kinv;
    };
    std::vector<Term> terms;
    double            den = 0;
    for (std::size_t q = 0; q < fam.size(i); ++q) {
      const nd::BondShape<2> shape = nd::bond_shape<2>(c, fam, d.state, i, q);
      if (!d.state.is_intact(i, q) || !d.geometry.is_usable(i, q) || !shape.usable) continue;
      const Mat2 F = nd::bond_deformation_gradient<2>(c, y.data(), fam, d.geometry, d.state, i, q);
      double     c33 = 0;
      Mat2       P;
      if (model.stress(F, c33, P) != StressStatus::ok) continue;
      const auto &k = shape.shape_tensor_inv;
      terms.push_back({q, P, {k[0], k[1], k[1], k[2]}});
      den += c.volume[static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + q])];
    }
    for (const Term &t : terms) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + t.q]);
      const double      w = c.volume[i] * c.volume[j] / den;
      for (std::size_t p = 0; p < fam.size(i); ++p) {
        const std::size_t m = static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + p]);
        if (!d.state.is_intact(i, p)) continue;
        if (std::hypot(c.x[2 * m] - c.x[2 * j], c.x[2 * m + 1] - c.x[2 * j + 1]) > d.horizon) continue; // not in B_ij
        const Vec2 g  = t.Kinv * Vec2{(c.x[2 * m] - c.x[2 * i]) * c.volume[m], (c.x[2 * m + 1] - c.x[2 * i + 1]) * c.volume[m]};
        const Vec2 dW = t.P * g; // dPsi(F_ij)/dy_m
        for (int a = 0; a < 2; ++a) {
          grad[2 * m + a] += w * dW[a];
          grad[2 * i + a] -= w * dW[a];
        }
      }
    }
  }
  for (std::size_t k = 0; k < d.size(); ++k) grad[2 * k] /= -c.volume[k], grad[2 * k + 1] /= -c.volume[k];
  return grad;
}

TEST(BaForceEnergy, ForceMatchesAStraightforwardGradientOfTheEnergy)
{
  for (double factor : {3.015, 5.015}) { // one and two mask words
    CutPlate                     c(20, 0.1, 11, factor);
    test::SaintVenantKirchhoff2D svk;
    std::vector<double>          t, f;
    const KernelStats            s = c.d.energy_consistent_forces(svk, c.y, t, f);
    EXPECT_TRUE(s.ok());
    ASSERT_GT(c.d.state.count_broken(c.d.families, c.d.size()), 500u);
    const std::vector<double> r = reference_force(c.d, svk, c.y);
    const double              scale = max_abs(r);
    for (std::size_t k = 0; k < f.size(); ++k)
      // Same sums in other orders, K^{-1} by other formulas: round-off of ~30^2 terms,
      // amplified by cond(K) (<= ~100 next to the cuts).
      ASSERT_NEAR(f[k], r[k], 1e-12 * scale) << "dof " << k << ", delta = " << factor << " dx";
  }
}

// max_k |f_k + (1/V_k) dW/dy_k| / max |f| by central differences of nd::strain_energy<2>().
template <class Model> double finite_difference_error(const CutPlate &c, const Model &model, double h)
{
  const test::Discretisation &d = c.d;
  std::vector<double>         y = c.y, t(2 * d.families.n_bonds()), f(y.size()), c33(d.families.n_bonds(), 0.0);
  nd::Workspace<2>         ws;
  EXPECT_TRUE(nd::compute_bond_forces<2>(ForceForm::energy_consistent, model, d.cloud, y.data(), d.families, d.geometry, d.state,
                                                    c33.data(), t.data(), ws).ok());
  nd::assemble_force_density<2>(d.families, d.cloud, t.data(), d.size(), f.data());
  double worst = 0;
  for (std::size_t k = 0; k < y.size(); ++k) { // (c33: the plane-stress solve's warm start, read only)
    const double y0 = y[k];
    y[k]            = y0 + h;
    const double Wp = nd::strain_energy<2>(model, d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(), d.size(), ws);
    y[k]            = y0 - h;
    const double Wm = nd::strain_energy<2>(model, d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(), d.size(), ws);
    y[k]            = y0;
    const double fd = -(Wp - Wm) / (2 * h) / d.cloud.volume[k / 2];
    worst           = std::max(worst, std::abs(fd - f[k]));
  }
  return worst / max_abs(f);
}

TEST(BaForceEnergy, ForceIsMinusTheEnergyGradientBySvkFiniteDifferences)
{
  const CutPlate c(16, 0.1, 5);
  // h = 1e-4 dx: truncation (h/dx)^2 ~ 1e-8 of the force; round-off eps W / h over
  // 256 points ~ 1e-10 of it (measured 5e-9).
  EXPECT_LT(finite_difference_error(c, test::SaintVenantKirchhoff2D{}, 1e-4 * kDx), 1e-7);
}

TEST(BaForceEnergy, ForceIsMinusTheEnergyGradientByGentPlaneStressFiniteDifferences)
{
  const CutPlate c(16, 0.1, 6);
  // As for SVK, plus the C33 solve: its residual enters the reduced energy at second
  // order only (S33 = 0 is stationarity), far below eps Psi (measured 5e-9 again).
  EXPECT_LT(finite_difference_error(c, hydrogel(), 1e-4 * kDx), 1e-7);
}

// Incompressible plane stress (plane_stress_incompressible.hpp): the force is minus the
// gradient of the energy, it conserves linear and angular momentum, and it passes the
// patch test, as the compressible solve does.
TEST(BaForceEnergy, IncompressiblePlaneStressIsMinusTheEnergyGradientConservesMomentumAndPassesThePatchTest)
{
  const PlaneStressIncompressible<Gent> gel{MaterialParameters{}};
  const CutPlate                        c(16, 0.1, 6);
  // As for SVK: no solve, so truncation and round-off alone (measured as Gent's)
  EXPECT_LT(finite_difference_error(c, gel, 1e-4 * kDx), 1e-7);
  std::vector<double> t, f;
  EXPECT_TRUE(c.d.energy_consistent_forces(gel, c.y, t, f).ok());
  double sum0 = 0, sum1 = 0, scale = 0, torque = 0, torque_scale = 0;
  for (std::size_t i = 0; i < c.d.size(); ++i) {
    const double v = c.d.cloud.volume[i], y0 = c.y[2 * i] - 5 * kDx, y1 = c.y[2 * i + 1] - 5 * kDx;
    sum0 += f[2 * i] * v;
    sum1 += f[2 * i + 1] * v;
    scale += force_terms(c.d, t, i) * v;
    torque += (y0 * f[2 * i + 1] - y1 * f[2 * i]) * v;
    torque_scale += std::hypot(y0, y1) * force_terms(c.d, t, i) * v;
  }
  EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale); // pairwise cancellation: round-off
  EXPECT_LT(std::abs(torque), 1e-13 * torque_scale); // W objective: no moment
  test::Discretisation d(test::plate(20, 20, kDx));
  EXPECT_TRUE(d.energy_consistent_forces(gel, d.affine(rotation(40.0) * Mat2{1.8, 0.3, 0.0, 0.7}), t, f).ok());
  double worst = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double x = d.cloud.x[2 * i], y = d.cloud.x[2 * i + 1];
    if (std::min(std::min(x, 20 * kDx - x), std::min(y, 20 * kDx - y)) >= 2 * d.horizon)
      worst = std::max(worst, std::hypot(f[2 * i], f[2 * i + 1]) / force_terms(d, t, i));
  }
  EXPECT_LT(worst, 1e-13); // uniform P: the terms pair up by the lattice's symmetry
}

TEST(BaForceEnergy, ConservesLinearAndAngularMomentumWithNotchHoleAndBrokenBonds)
{
  const CutPlate c(20, 0.2, 42);
  for (int model = 0; model < 2; ++model) {
    std::vector<double> t, f, fb;
    if (model == 0) c.d.energy_consistent_forces(test::SaintVenantKirchhoff2D{}, c.y, t, f);
    else c.d.energy_consistent_forces(hydrogel(), c.y, t, f);
    double sum0 = 0, sum1 = 0, scale = 0, torque = 0, torque_scale = 0;
    for (std::size_t i = 0; i < c.d.size(); ++i) {
      const double v = c.d.cloud.volume[i], y0 = c.y[2 * i] - 5 * kDx, y1 = c.y[2 * i + 1] - 5 * kDx; // about a point in the body
      sum0 += f[2 * i] * v;
      sum1 += f[2 * i + 1] * v;
      scale += force_terms(c.d, t, i) * v;
      torque += (y0 * f[2 * i + 1] - y1 * f[2 * i]) * v;
      torque_scale += std::hypot(y0, y1) * force_terms(c.d, t, i) * v;
    }
    ASSERT_GT(scale, 0);
    // Pairwise cancellation as in the bond-only form: round-off of ~2e4 summands.
    EXPECT_LT(std::hypot(sum0, sum1), 1e-13 * scale);
    // W is objective (depends on y through F^T F), so its gradient has no moment:
    // sum_k y_k x f_k V_k = 0 exactly, here up to the round-off of the same sums.
    EXPECT_LT(std::abs(torque), 1e-13 * torque_scale);
    if (model == 1) {
      c.d.forces(hydrogel(), c.y, t, fb);
      double bond_only_torque = 0;
      for (std::size_t i = 0; i < c.d.size(); ++i)
        bond_only_torque += ((c.y[2 * i] - 5 * kDx) * fb[2 * i + 1] - (c.y[2 * i + 1] - 5 * kDx) * fb[2 * i]) * c.d.cloud.volume[i];
      // The contrast: the bond-only t_ij are not parallel to the bonds and not the
      // gradient of an objective energy; their net moment is ~2e-4 of the scale.
      EXPECT_GT(std::abs(bond_only_torque), 1e-6 * torque_scale);
    }
  }
}

TEST(BaForceEnergy, RigidRotationGivesZeroForceEverywhere)
{
  const CutPlate               c(20, 0.0, 1);
  test::SaintVenantKirchhoff2D svk;
  // The force a unit strain makes: that of a 1e-3 stretch, divided by 1e-3.
  std::vector<double> t, f_unit;
  c.d.energy_consistent_forces(svk, c.d.affine({1.001, 0.0, 0.0, 1.0}), t, f_unit);
  const double unit = max_abs(f_unit) / 1e-3;
  ASSERT_GT(unit, 0);
  for (double deg : {90.0, 40.0, 180.0}) {
    std::vector<double> f;
    c.d.energy_consistent_forces(svk, c.d.affine(rotation(deg), 5.0e-3, -3.0e-3), t, f);
    // F = R + O(eps |y| / dx) = R + O(1e-14): P is round-off times the modulus.
    EXPECT_LT(max_abs(f), 1e-12 * unit) << "rotation " << deg;
  }
}

TEST(BaForceEnergy, AffineMotionGivesZeroNetForceTwoHorizonsFromTheBoundary)
{
  const Mat2           A = rotation(40.0) * Mat2{3.0, 0.5, 0.0, 1.1};
  test::Discretisation d(test::plate(20, 20, kDx));
  for (int model = 0; model < 2; ++model) {
    std::vector<double> t, f;
    const KernelStats   s = model == 0 ? d.energy_consistent_forces(test::SaintVenantKirchhoff2D{}, d.affine(A, 3.7e-3, -1.2e-2), t, f)
                                       : d.energy_consistent_forces(hydrogel(), d.affine({1.3, 0.1, 0.0, 0.9}), t, f);
    EXPECT_TRUE(s.ok());
    EXPECT_EQ(s.evaluated, d.families.n_bonds());
    std::size_t interior = 0;
    double      worst = 0, boundary_max = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double x = d.cloud.x[2 * i], y = d.cloud.x[2 * i + 1];
      const double rel = std::hypot(f[2 * i], f[2 * i + 1]) / force_terms(d, t, i);
      if (std::min(std::min(x, 20 * kDx - x), std::min(y, 20 * kDx - y)) >= 2 * d.horizon) {
        ++interior;
        worst = std::max(worst, rel);
      } else boundary_max = std::max(boundary_max, rel);
    }
    EXPECT_EQ(interior, 64u);
    // Uniform P: the terms pair up by the lattice's point symmetry (t(xi) and t(-xi));
    // what is left is the round-off of the ~56 terms and of the masked sums.
    EXPECT_LT(worst, 1e-13);
    EXPECT_GT(boundary_max, 1e-2); // not vacuous: the free surface is not in equilibrium
  }
}

TEST(BaForceEnergy, StiffnessIsSymmetricAtFreeEdgesCornersAndNotchTipsWhereBondOnlyIsNot)
{
  Body<2> body = test::plate(20, 20, 1.0);
  body.notches.push_back({20.0, 10.0, 12.0, 10.0});
  test::Discretisation         d(body);
  test::SaintVenantKirchhoff2D svk;
  svk.lambda = svk.mu = 1.0;
  auto energy = [&](const std::vector<double> &y, std::vector<double> &f) {
    std::vector<double> t;
    d.energy_consistent_forces(svk, y, t, f);
  };
  auto bond_only = [&](const std::vector<double> &y, std::vector<double> &f) {
    std::vector<double> t;
    d.forces(svk, y, t, f);
  };
  auto index = [](int ix, int iy) { return static_cast<std::size_t>(iy * 20 + ix); };
  std::vector<std::size_t> interior, edge, notch_tip;
  for (int iy = 4; iy <= 7; ++iy)
    for (int ix = 8; ix <= 11; ++ix) interior.push_back(index(ix, iy));
  for (int iy = 0; iy <= 1; ++iy)
    for (int ix = 0; ix <= 5; ++ix) edge.push_back(index(ix, iy)); // the corner and the bottom edge
  for (int iy = 8; iy <= 11; ++iy)
    for (int ix = 10; ix <= 14; ++ix) notch_tip.push_back(index(ix, iy)); // both faces of the notch and its tip
  const double ec_interior = stiffness_asymmetry(d, interior, energy);
  const double ec_edge     = stiffness_asymmetry(d, edge, energy);
  const double ec_notch    = stiffness_asymmetry(d, notch_tip, energy);
  const double bo_edge     = stiffness_asymmetry(d, edge, bond_only);
  const double bo_notch    = stiffness_asymmetry(d, notch_tip, bond_only);
  std::printf("stiffness asymmetry: energy-consistent interior %.1e, edge %.1e, notch %.1e; bond-only edge %.1e, notch %.1e\n",
              ec_interior, ec_edge, ec_notch, bo_edge, bo_notch);
  // Central differences of a linear map at u = 0: O(h^2) truncation + round-off / h.
  EXPECT_LT(ec_interior, 1e-6);
  EXPECT_LT(ec_edge, 1e-6);
  EXPECT_LT(ec_notch, 1e-6);
  EXPECT_GT(bo_edge, 1e-2); // the contrast: the bond-only tangent is far from symmetric there
  EXPECT_GT(bo_notch, 1e-2);
}

// Velocity Verlet on a free 12 x 12 sheet (SVK, rho = 1000 kg/m^3), from a small
// sinusoidal displacement at rest, dt = dt_factor x the form's stable step (power
// iteration). The relative energy error |H_n - H_0| / H_0,
// H = kinetic + nd::strain_energy<2>(), is sampled every 10 steps.
struct VerletRun {
  double dt = 0, duration = 0;
  double early_max = 0;      // max relative error over steps 1 .. 1000
  double late_max  = 0;      // max relative error over steps 1001 .. end
  int    blow_up   = -1;     // first sampled step with an error above 1 (100 %), -1 if none
  double final_momentum = 0; // |sum m v| / sum m |v| at the end
  double max() const { return std::max(early_max, late_max); }
};

template <bool EnergyConsistent> VerletRun verlet(int steps, double dt_factor)
{
  test::Discretisation         d(test::plate(12, 12, kDx));
  test::SaintVenantKirchhoff2D svk;
  const double                 rho = 1000.0, L = 12 * kDx;
  const std::size_t            n   = d.size();
  auto acceleration = [&](const std::vector<double> &y, std::vector<double> &a) {
    std::vector<double> t;
    if (EnergyConsistent) d.energy_consistent_forces(svk, y, t, a);
    else d.forces(svk, y, t, a);
    for (double &v : a) v /= rho;
  };
  // Stable step 2 / sqrt(lambda_max(M^{-1} K)) of the form itself, by power iteration
  // as the solver does it, padded by 10 %.
  std::vector<double> v(2 * n), a, a0;
  std::mt19937        rng(7);
  for (double &c : v) c = test::random_between(rng, -0.5, 0.5);
  acceleration(d.cloud.x, a0);
  double lambda = 0;
  for (int it = 0; it < 200; ++it) {
    double norm = 0;
    for (double c : v) norm += c * c;
    norm = std::sqrt(norm);
    std::vector<double> y = d.cloud.x;
    const double        eps = 1e-7 * kDx;
    for (std::size_t k = 0; k < y.size(); ++k) y[k] += eps * v[k] / norm;
    acceleration(y, a);
    lambda = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      a[k] = -(a[k] - a0[k]) / eps;
      lambda += a[k] * v[k] / norm;
    }
    v = a;
  }
  VerletRun run;
  run.dt       = dt_factor * 2.0 / std::sqrt(1.1 * lambda);
  run.duration = steps * run.dt;
  // u = 0.01 dx (sin(pi x/L) cos(2 pi y/L), cos(3 pi x/L) sin(pi y/L)): strains ~ 3e-3.
  std::vector<double> y = d.cloud.x, vel(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double X = d.cloud.x[2 * i] / L, Y = d.cloud.x[2 * i + 1] / L;
    y[2 * i] += 0.01 * kDx * std::sin(kPi * X) * std::cos(2 * kPi * Y);
    y[2 * i + 1] += 0.01 * kDx * std::cos(3 * kPi * X) * std::sin(kPi * Y);
  }
  nd::Workspace<2> ws;
  auto energy = [&]() {
    double kinetic = 0;
    for (std::size_t i = 0; i < n; ++i)
      kinetic += 0.5 * rho * d.cloud.volume[i] * (vel[2 * i] * vel[2 * i] + vel[2 * i + 1] * vel[2 * i + 1]);
    return kinetic + nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, n, ws);
  };
  const double H0 = energy();
  acceleration(y, a);
  for (int step = 1; step <= steps; ++step) {
    for (std::size_t k = 0; k < y.size(); ++k) {
      vel[k] += 0.5 * run.dt * a[k];
      y[k] += run.dt * vel[k];
    }
    acceleration(y, a);
    for (std::size_t k = 0; k < y.size(); ++k) vel[k] += 0.5 * run.dt * a[k];
    if (step % 10 != 0) continue;
    const double error = std::abs(energy() - H0) / H0;
    double      &max   = step <= 1000 ? run.early_max : run.late_max;
    max                = std::isfinite(error) ? std::max(max, error) : HUGE_VAL;
    if (!(error <= 1.0)) {
      run.blow_up = step;
      break;
    }
  }
  double p0 = 0, p1 = 0, pabs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = rho * d.cloud.volume[i];
    p0 += m * vel[2 * i], p1 += m * vel[2 * i + 1], pabs += m * std::hypot(vel[2 * i], vel[2 * i + 1]);
  }
  run.final_momentum = std::hypot(p0, p1) / pabs;
  return run;
}

TEST(BaForceEnergy, VelocityVerletConservesTheEnergyOfAFreeSheetWhereBondOnlyFlutters)
{
  const VerletRun ec      = verlet<true>(10000, 0.5);
  const VerletRun ec_half = verlet<true>(4000, 0.25); // half the step (the error peaks within ~250 steps)
  const VerletRun bo      = verlet<false>(10000, 0.5);
  const VerletRun bo_half = verlet<false>(20000, 0.25);
  std::printf("free 12 x 12 sheet, Verlet at 0.5 x the stable step, 10000 steps:\n"
              "  energy-consistent (dt %.3e s, %.3f s): max |H - H0| / H0 = %.2e over steps 1-1000, %.2e over "
              "1001-10000; %.2e at dt / 2\n"
              "  bond-only (dt %.3e s): |H - H0| / H0 above 100 %% at t = %.2e s (step %d); at dt / 2: t = %.2e s\n",
              ec.dt, ec.duration, ec.early_max, ec.late_max, ec_half.max(), bo.dt, bo.blow_up * bo.dt, bo.blow_up,
              bo_half.blow_up * bo_half.dt);
  ASSERT_EQ(ec.blow_up, -1);
  // Verlet conserves a modified energy H + O(dt^2): |H - H0| / H0 is a bounded
  // oscillation, here ~5 % at 0.5 x the stable step (the free surfaces put part of the
  // energy into modes with omega dt ~ 1). Bounded: no larger after 10 000 steps than
  // over the first 1 000 (secular growth would multiply it).
  EXPECT_LT(ec.max(), 0.1);
  EXPECT_LT(ec.late_max, 1.5 * ec.early_max);
  // O(dt^2): halving dt divides it by 4 (3 .. 5 allows the sampling of the peaks).
  EXPECT_GT(ec.max() / ec_half.max(), 3.0);
  EXPECT_LT(ec.max() / ec_half.max(), 5.0);
  EXPECT_LT(ec.final_momentum, 1e-10); // sum f V = 0 to round-off every step
  // The contrast: the bond-only form's motion grows until the energy has doubled, at
  // the same time for both steps (measured 1.18e-2 s): flutter of the undamped
  // equations of motion (complex eigenvalues), not a time-step instability.
  ASSERT_GT(bo.blow_up, 0);
  ASSERT_GT(bo_half.blow_up, 0);
  EXPECT_NEAR(bo_half.blow_up * bo_half.dt / (bo.blow_up * bo.dt), 1.0, 0.2);
}

TEST(BaForceEnergy, RankLocalCloudReproducesOneRankForcesBitForBit)
{
  const GentPlaneStress gent = hydrogel();
  test::expect_rank_local_views_reproduce_one_rank([&](const PointCloud &cloud, const double *y, const Families &f,
                                                       const nd::BondGeometry<2> &g, const BondState &s, double *c33,
                                                       double *t, nd::Workspace<2> &ws) {
    return nd::compute_bond_forces<2>(ForceForm::energy_consistent, gent, cloud, y, f, g, s, c33, t, ws);
  });
}

TEST(BaForceEnergy, ModelFailuresAreReportedLikeTheBondOnlyKernelAndCarryNoEnergy)
{
  test::Discretisation d(test::plate(20, 20, kDx));
  test::LimitedModel   model; // chain_limit once F_xx > 1.5
  const double         L = 20 * kDx;
  std::vector<double>  y = d.cloud.x;
  for (std::size_t i = 0; i < d.size(); ++i) y[2 * i] += d.cloud.x[2 * i] * d.cloud.x[2 * i] / L; // F_xx = 1 + 2x/L
  std::vector<double>  c33_bo(d.families.n_bonds(), 7.0), c33_ec(c33_bo), t(2 * d.families.n_bonds());
  nd::Workspace<2>  ws_bo, ws_ec;
  const KernelStats    bo = nd::compute_bond_forces<2>(ForceForm::bond_only, model, d.cloud, y.data(), d.families, d.geometry, d.state,
                                                c33_bo.data(), t.data(), ws_bo);
  const KernelStats    ec = nd::compute_bond_forces<2>(ForceForm::energy_consistent, model, d.cloud, y.data(), d.families, d.geometry,
                                                                  d.state, c33_ec.data(), t.data(), ws_ec);
  ASSERT_GT(ec.chain_limit, 1000u);
  EXPECT_EQ(ec.chain_limit, bo.chain_limit);
  EXPECT_EQ(ec.evaluated, bo.evaluated);
  EXPECT_EQ(ec.unusable, bo.unusable);
  EXPECT_EQ(ec.first_point, bo.first_point);
  EXPECT_EQ(ec.first_position, bo.first_position);
  EXPECT_EQ(ec.first_status, StressStatus::chain_limit);
  ASSERT_EQ(ws_ec.failed.size(), ws_bo.failed.size());
  for (std::size_t k = 0; k < ws_ec.failed.size(); ++k) {
    EXPECT_EQ(ws_ec.failed[k].point, ws_bo.failed[k].point);
    EXPECT_EQ(ws_ec.failed[k].position, ws_bo.failed[k].position);
  }
  EXPECT_EQ(c33_ec, c33_bo); // failed solves keep the warm start; the others store 0.5

  // Carry no energy: the force is the reference gradient with the failed bonds left
  // out of W (their model's stress is absent from every sum and from omega).
  std::vector<double>       f(2 * d.size());
  nd::assemble_force_density<2>(d.families, d.cloud, t.data(), d.size(), f.data());
  const std::vector<double> r     = reference_force(d, model, y);
  const double              scale = max_abs(r);
  for (std::size_t k = 0; k < f.size(); ++k) ASSERT_NEAR(f[k], r[k], 1e-12 * scale) << "dof " << k; // round-off
}

} // namespace
} // namespace bapd
