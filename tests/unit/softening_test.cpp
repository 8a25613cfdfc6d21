// Softening bonds (softening.hpp; docs/method.md section 5.4): the work to failure of a
// bond is Gamma, the damage never decreases and is the same for both copies, the time
// law fades a bond at dt / tau a step from its onset whatever its strain does, and the
// kernel scales a bond's force and energy by 1 - d.
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/softening.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

// Loaded monotonically, a bond whose energy is (1 - d) r (per unit V_i V_j / c) takes the
// work integral of (1 - d(r)) dr up to d = 1 (d held at each r: the force is dE/du at
// fixed d): r0 + (r_f - r0) / 2 = Gamma for the linear law, r0 + s (1 - cut) for the
// exponential one, whose cut leaves cut s unworked.
TEST(Softening, WorkToFailureIsTheFractureEnergy)
{
  const double gamma = 165.0, r0 = 0.43 * gamma;
  for (Softening law : {Softening::linear, Softening::exponential}) {
    const double end  = 1.01 * (law == Softening::linear ? 2 * gamma - r0 : r0 + (gamma - r0) * std::log(1 / exponential_cut));
    const int    n    = 1000000;
    double       work = 0.0, last = 0.0;
    for (int k = 0; k < n; ++k) {
      const double r = (k + 0.5) * end / n, d = softening_damage(law, r, r0, gamma);
      EXPECT_GE(d, last);
      last = d;
      if (d >= 1.0) break;
      work += (1.0 - d) * end / n;
    }
    EXPECT_EQ(last, 1.0) << to_string(law);
    const double expected = law == Softening::linear ? gamma : gamma - exponential_cut * (gamma - r0);
    EXPECT_NEAR(work, expected, 1e-4 * gamma) << to_string(law);
  }
  EXPECT_EQ(softening_damage(Softening::linear, 0.999 * r0, r0, gamma), 0.0);
  EXPECT_EQ(softening_damage(Softening::none, r0, r0, gamma), 1.0); // today's: at once
}

// One pair of a plate loaded up, unloaded half way and loaded again to failure: the
// energy soften_bonds reports (both copies) adds up to the pair's share of Gamma,
// V_i V_j Gamma / c (eq 5.1); d is the same for both copies and never decreases, and
// the bond breaks, from both ends, at d = 1.
TEST(Softening, APairDissipatesItsShareOfGammaAndNeverHeals)
{
  test::Discretisation d(test::plate(9, 9, 1.0));
  const std::size_t    p = 4 * 9 + 4, n = d.families.neighbour.size(), b = d.families.offsets[p];
  const std::size_t    j = static_cast<std::size_t>(d.families.neighbour[b]), back = static_cast<std::size_t>(d.families.reverse[b]);
  const double         c = 2.0, gamma = 10.0, r0 = 0.43 * gamma;
  std::vector<double>  crossing(d.size(), c), psi(n, -1.0), dissipated(d.size(), 0.0);
  for (std::size_t i : {p, j})
    for (std::size_t k = d.families.offsets[i]; k < d.families.offsets[i + 1]; ++k) psi[k] = 0.0; // energy-carrying bonds
  d.state.damage.assign(n, 0.0);
  // r = psi / V(H_p) c: up to 1.2 r_f, down to 0.5 r_f and up again, 3000 increments each way
  const double r_end = 2 * gamma - r0, scale = d.cloud.family_volume[p] / c;
  std::vector<double> path;
  for (int k = 0; k <= 3000; ++k) path.push_back(0.6 * r_end * k / 3000);
  for (int k = 0; k <= 3000; ++k) path.push_back(0.6 * r_end * (1.0 - 0.5 * k / 3000));
  for (int k = 0; k <= 6000; ++k) path.push_back(0.3 * r_end + 0.9 * r_end * k / 6000);
  std::vector<std::size_t> touched;
  double                   last = 0.0, at_peak = -1.0;
  std::size_t              broken = 0;
  for (std::size_t step = 0; step < path.size(); ++step) {
    if (!d.state.is_intact(p, 0)) break;
    psi[b] = path[step] * scale;
    broken += soften_bonds(Softening::linear, d.cloud, d.families, psi.data(), crossing.data(), r0, gamma, Fading{}, d.state,
                           touched, dissipated.data(), d.size());
    EXPECT_EQ(d.state.damage[b], d.state.damage[back]) << step;
    EXPECT_GE(d.state.damage[b], last) << step;
    last = d.state.damage[b];
    if (step == 3000) at_peak = last;
    if (step > 3000 && step < 6000) EXPECT_EQ(last, at_peak) << "unloading changed d at " << step;
  }
  EXPECT_GT(at_peak, 0.0);
  EXPECT_LT(at_peak, 1.0);
  EXPECT_FALSE(d.state.is_intact(p, 0));
  EXPECT_FALSE(d.state.is_intact(j, static_cast<std::size_t>(back - d.families.offsets[j])));
  EXPECT_EQ(broken, 2u);
  EXPECT_EQ(last, 1.0);
  const double expected = d.cloud.volume[p] * d.cloud.volume[j] * gamma / c;
  EXPECT_NEAR(dissipated[p] + dissipated[j], expected, 2e-3 * expected);
  for (std::size_t i = 0; i < d.size(); ++i)
    if (i != p) EXPECT_EQ(dissipated[i], 0.0) << i; // j's copy carries no energy here
}

// The time law: a pair that reaches r0 once fades by dt / tau in every step's first pass
// (not in the passes that follow at the same positions), also once it is unloaded below
// r0, and breaks from both ends after tau / dt steps; a pair just below r0 never starts.
// What a pass takes is V_p omega_p V_j Psi_pj (d_new - d_old) (the other bonds carry none).
TEST(Softening, TheTimeLawFadesAtItsRateWhateverTheStrain)
{
  EXPECT_EQ(fading_damage(0.0, 0.999, 1.0, Fading{0.1, 0.1}), 0.0);
  EXPECT_EQ(fading_damage(0.0, 1.0, 1.0, Fading{0.1, 0.0}), 0.1);  // starts in any pass
  EXPECT_EQ(fading_damage(0.3, 0.0, 1.0, Fading{0.1, 0.0}), 0.3);  // a later pass of the step
  EXPECT_EQ(fading_damage(0.95, 0.0, 1.0, Fading{0.1, 0.1}), 1.0); // capped: it breaks
  test::Discretisation d(test::plate(9, 9, 1.0));
  const std::size_t    p = 4 * 9 + 4, n = d.families.neighbour.size(), b = d.families.offsets[p];
  const std::size_t    j = static_cast<std::size_t>(d.families.neighbour[b]), back = static_cast<std::size_t>(d.families.reverse[b]);
  const double         c = 2.0, gamma = 10.0, r0 = 0.43 * gamma, dt = 1e-4, tau = 1e-3;
  std::vector<double>  crossing(d.size(), c), psi(n, -1.0), dissipated(d.size(), 0.0);
  for (std::size_t i : {p, j})
    for (std::size_t k = d.families.offsets[i]; k < d.families.offsets[i + 1]; ++k) psi[k] = 0.0;
  d.state.damage.assign(n, 0.0);
  const double scale = d.cloud.family_volume[p] / c; // psi[b] = r scale: the pair's release is r
  double       volume = 0.0;                         // 1 / omega_p: the family's bonds carry energy
  for (std::size_t k = d.families.offsets[p]; k < d.families.offsets[p + 1]; ++k)
    volume += d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[k])];
  std::vector<std::size_t> touched;
  std::size_t              broken = 0;
  auto pass = [&](double r, Fading fading) {
    psi[b] = r * scale;
    broken += soften_bonds(Softening::time, d.cloud, d.families, psi.data(), crossing.data(), r0, gamma, fading, d.state, touched,
                           dissipated.data(), d.size());
    EXPECT_EQ(d.state.damage[b], d.state.damage[back]);
  };
  const Fading first{dt / tau, dt / tau}, later{dt / tau, 0.0};
  pass(0.999 * r0, first);
  EXPECT_EQ(d.state.damage[b], 0.0);
  double expected = 0.0, last = 0.0;
  int    steps = 0;
  for (; steps < 100 && d.state.is_intact(p, 0); ++steps) {
    const double r = steps == 0 ? r0 : 0.5 * r0; // unloaded after the onset: it fades on
    pass(r, first);
    pass(r, later); // a cascade pass at the same positions: no further fading
    expected += d.cloud.volume[p] * d.cloud.volume[j] * r * scale * (d.state.damage[b] - last) / volume;
    EXPECT_GT(d.state.damage[b], last) << steps;
    last = d.state.damage[b];
  }
  EXPECT_NEAR(steps, tau / dt, 1.0); // (the sum of ten dt / tau in floating point may need an eleventh)
  EXPECT_EQ(last, 1.0);
  EXPECT_FALSE(d.state.is_intact(j, static_cast<std::size_t>(back - d.families.offsets[j])));
  EXPECT_EQ(broken, 2u);
  EXPECT_NEAR(dissipated[p], expected, 1e-12 * expected);
}

// The kernel: a uniform d scales every bond force (both forms) and the strain energy by
// 1 - d; an empty damage array is the kernel without softening.
TEST(Softening, TheKernelScalesForceAndEnergyByOneMinusD)
{
  test::Discretisation         d(test::plate(10, 10, 1.0));
  test::SaintVenantKirchhoff2D svk;
  const Mat2                   A = {1.2, 0.3, 0.1, 0.9};
  std::vector<double>          y = d.affine(A);
  const std::size_t            n = d.families.neighbour.size();
  for (ForceForm form : {ForceForm::bond_only, ForceForm::energy_consistent}) {
    nd::Workspace<2>    ws;
    std::vector<double> t0(2 * n), t1(2 * n);
    d.state.damage.clear();
    nd::compute_bond_forces<2>(form, svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, t0.data(), ws);
    const double e0 = nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws);
    d.state.damage.assign(n, 0.25);
    nd::compute_bond_forces<2>(form, svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, t1.data(), ws);
    const double e1 = nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws);
    double       largest = 0.0;
    for (double v : t0) largest = std::max(largest, std::abs(v));
    ASSERT_GT(largest, 0.0);
    for (std::size_t k = 0; k < 2 * n; ++k) EXPECT_NEAR(t1[k], 0.75 * t0[k], 1e-14 * largest) << to_string(form) << " " << k;
    EXPECT_NEAR(e1, 0.75 * e0, 1e-14 * e0);
  }
  d.state.damage.clear();
}

} // namespace
} // namespace bapd
