// Bond failure, damage and the geometry of broken bonds (paper eqs 7, 38; docs/method.md 2, 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/damage.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

std::size_t position_of(const Families &f, std::size_t i, std::size_t j)
{
  for (std::size_t q = 0; q < f.size(i); ++q)
    if (static_cast<std::size_t>(f.neighbour[f.offsets[i] + q]) == j) return q;
  ADD_FAILURE() << j << " is not in the family of " << i;
  return 0;
}

TEST(Damage, StretchedBondBreaksForBothCopiesAndStaysBrokenAfterUnloading)
{
  test::Discretisation d(test::plate(9, 9, 1.0));
  const double         s_c = 1.3;
  const std::size_t    p   = 4 * 9 + 4; // centre
  std::vector<double>  y   = d.cloud.x;
  y[2 * p] += 0.8; // pull the centre point to the right by 0.8 dx
  std::vector<std::size_t> touched;
  const std::size_t        broken = nd::break_bonds<2>(d.cloud, y.data(), d.families, s_c, d.state, touched);
  // Expected: exactly the bonds of p whose stretch exceeds s_c, seen from both ends.
  std::size_t expected = 0;
  for (std::size_t q = 0; q < d.families.size(p); ++q) {
    const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[p] + q]);
    const double      s = std::hypot(y[2 * j] - y[2 * p], y[2 * j + 1] - y[2 * p + 1]) /
                     std::hypot(d.cloud.x[2 * j] - d.cloud.x[2 * p], d.cloud.x[2 * j + 1] - d.cloud.x[2 * p + 1]);
    const std::size_t r = position_of(d.families, j, p);
    EXPECT_EQ(d.state.is_intact(p, q), s <= s_c);
    EXPECT_EQ(d.state.is_intact(j, r), s <= s_c); // symmetric decision
    if (s > s_c) {
      ++expected;
      EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), j));
    }
  }
  ASSERT_GT(expected, 0u);
  ASSERT_LT(expected, d.families.size(p));
  EXPECT_EQ(broken, 2 * expected); // directed copies
  EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), p));
  EXPECT_TRUE(std::is_sorted(touched.begin(), touched.end()));
  EXPECT_EQ(d.state.count_broken(d.families, d.size()), 2 * expected);
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  // Nothing more breaks under the same load.
  EXPECT_EQ(nd::break_bonds<2>(d.cloud, y.data(), d.families, s_c, d.state, touched), 0u);

  // Unload: nothing heals, nothing new breaks, and the body is force free again.
  EXPECT_EQ(nd::break_bonds<2>(d.cloud, d.cloud.x.data(), d.families, s_c, d.state, touched), 0u);
  EXPECT_TRUE(touched.empty());
  EXPECT_EQ(d.state.count_broken(d.families, d.size()), 2 * expected);
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          t, f;
  d.forces(svk, d.cloud.x, t, f);
  // y = x: F = K K^{-1} = I + O(eps), so f is round-off: ~1e-16 of a unit-strain force
  // (E / dx = 2.7e4 here, summed over ~56 terms).
  for (double v : f) EXPECT_LT(std::abs(v), 1e-13 * svk.young_modulus() / 1.0);
  // Reloading: the broken bonds carry nothing, their intact neighbours do.
  d.forces(svk, y, t, f);
  for (std::size_t q = 0; q < d.families.size(p); ++q) {
    const std::size_t b = d.families.offsets[p] + q;
    if (!d.state.is_intact(p, q)) EXPECT_EQ(std::hypot(t[2 * b], t[2 * b + 1]), 0.0);
    else EXPECT_GT(std::hypot(t[2 * b], t[2 * b + 1]), 0.0);
  }
}

// A step in which every bond fails (a sheet past the chain limit at once): 2 end points
// a bond, n * family size of them, far more than the n + 2 n entries the solver reserves
// (failure.cpp) for the points touched. The list stays in its reserve (no allocation in
// a time step) and ends as every point once, sorted; an unreserved one grows as needed.
TEST(Damage, EveryBondFailingInOneStepStaysInTheTouchedListsReserve)
{
  for (const bool reserved : {true, false}) {
    test::Discretisation    d(test::plate(12, 12, 1.0));
    std::vector<FailedBond> failed;
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t q = 0; q < d.families.size(i); ++q) failed.push_back({i, q, StressStatus::chain_limit});
    ASSERT_GT(failed.size(), 3 * d.size()); // 2 entries a pair: more than the reserve holds unmerged
    std::vector<std::size_t> touched;
    if (reserved) touched.reserve(3 * d.size());
    const std::size_t *const storage = touched.data();
    const std::size_t        broken  = break_failed_bonds(d.families, d.state, failed, touched);
    EXPECT_EQ(2 * broken, d.families.n_bonds()) << "reserved " << reserved; // a pair counts once
    if (reserved) {
      EXPECT_EQ(touched.data(), storage) << "the touched list outgrew its reserve";
    }
    ASSERT_EQ(touched.size(), d.size()) << "reserved " << reserved;
    for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(touched[i], i);
    EXPECT_EQ(d.state.count_broken(d.families, d.size()), d.families.n_bonds());
  }
}

TEST(Damage, PointDamageIsTheBrokenFractionOfTheFamilyVolume)
{
  test::Discretisation d(test::plate(7, 7, 0.5e-3)); // the centre has the whole 28-point family
  const std::size_t    c = 3 * 7 + 3;
  ASSERT_EQ(d.families.size(c), 28u);
  std::vector<std::size_t> touched;
  for (std::size_t q : {0u, 5u, 17u}) ASSERT_TRUE(break_bond(d.families, d.state, c, q, &touched));
  EXPECT_FALSE(break_bond(d.families, d.state, c, 5, &touched)); // already broken
  std::vector<double> damage(d.size());
  point_damage(d.cloud, d.families, d.state, d.size(), damage.data());
  // eq 38 with equal volumes: 3 of 28 (one rounding in the sum and one in the ratio).
  EXPECT_NEAR(damage[c], 3.0 / 28.0, 4e-16);
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (i == c) continue;
    const bool partner = std::count(touched.begin(), touched.end(), i) > 0;
    if (partner) EXPECT_NEAR(damage[i], 1.0 / static_cast<double>(d.families.size(i)), 4e-16);
    else EXPECT_EQ(damage[i], 0.0); // same sum in the same order as V(H): exactly 1 - 1
  }
  EXPECT_EQ(d.state.count_broken(d.families, d.size()), 6u);
}

TEST(Damage, BreakingABondChangesTheShapeTensorsOfItsEndPointsOnly)
{
  test::Discretisation d(test::plate(20, 20, 1.0));
  const std::size_t    i = 10 * 20 + 10, k = 11 * 20 + 12; // offset (2, 1)
  const std::size_t    qk = position_of(d.families, i, k);
  std::vector<nd::BondShape<2>> before(d.families.n_bonds());
  for (std::size_t p = 0; p < d.size(); ++p)
    for (std::size_t q = 0; q < d.families.size(p); ++q)
      before[d.families.offsets[p] + q] = nd::bond_shape<2>(d.cloud, d.families, d.state, p, q);
  std::vector<std::size_t> touched;
  break_bond(d.families, d.state, i, qk, &touched);
  ASSERT_EQ(touched.size(), 2u);
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  std::size_t changed = 0;
  for (std::size_t q = 0; q < d.families.size(i); ++q) {
    const std::size_t b     = d.families.offsets[i] + q;
    const nd::BondShape<2>   after = nd::bond_shape<2>(d.cloud, d.families, d.state, i, q);
    ASSERT_TRUE(d.families.ba(b)[q / 64] >> (q % 64) & 1u); // j in B_ij, always
    const bool k_in = d.families.ba(b)[qk / 64] >> (qk % 64) & 1u;
    if (q == qk) {
      EXPECT_FALSE(d.geometry.is_usable(i, q)); // the broken bond itself
      EXPECT_FALSE(after.usable);
      continue;
    }
    double change = 0; // relative change of K^{-1}
    for (int c = 0; c < 3; ++c)
      change = std::max(change, std::abs(after.shape_tensor_inv[c] - before[b].shape_tensor_inv[c]) /
                                    std::abs(before[b].shape_tensor_inv[0]));
    // K_ij changes iff k was in B_ij: by O(1/|B_ij|) if so, else by round-off only
    // (the sums may be formed as total minus complement, and the total lost k).
    const bool diff = change > 1e-6;
    EXPECT_EQ(diff, k_in) << "bond " << q;
    if (!diff) {
      EXPECT_LT(change, 1e-13);
    }
    EXPECT_EQ(after.volume_fraction < before[b].volume_fraction - 1e-6, k_in); // and so does phi_xi
    changed += diff;
    // Interior point: phi = 1/2, so the force scale is phi_xi.
    EXPECT_DOUBLE_EQ(after.force_scale, after.volume_fraction);
  }
  EXPECT_GT(changed, 5u);
  // Every other point keeps its geometry bit for bit.
  for (std::size_t p = 0; p < d.size(); ++p) {
    if (p == i || p == k) continue;
    for (std::size_t q = 0; q < d.families.size(p); ++q) {
      const nd::BondShape<2> after = nd::bond_shape<2>(d.cloud, d.families, d.state, p, q);
      for (int c = 0; c < 3; ++c) // K^{-1}'s upper triangle (a C array: element by element)
        ASSERT_EQ(after.shape_tensor_inv[c], before[d.families.offsets[p] + q].shape_tensor_inv[c]);
      ASSERT_EQ(after.force_scale, before[d.families.offsets[p] + q].force_scale);
    }
  }
  // Recomputing the touched points equals recomputing everything.
  nd::BondGeometry<2> full;
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, full);
  EXPECT_EQ(full.usable, d.geometry.usable);
  EXPECT_EQ(full.singular, d.geometry.singular);
}

TEST(Damage, BondWithSingularShapeTensorCarriesNoForceAndIsCounted)
{
  test::Discretisation d(test::plate(20, 20, 1.0));
  const std::size_t    i = 10 * 20 + 10;
  // Keep only the bonds of i along its row: every remaining B_ij is collinear with i.
  std::vector<std::size_t> touched;
  for (std::size_t q = 0; q < d.families.size(i); ++q) {
    const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
    if (d.cloud.x[2 * j + 1] != d.cloud.x[2 * i + 1]) break_bond(d.families, d.state, i, q, &touched);
  }
  touched.push_back(i);
  const std::size_t not_usable = nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  EXPECT_EQ(not_usable, 6u); // (+-1, 0), (+-2, 0), (+-3, 0)
  EXPECT_EQ(d.geometry.count_unusable(d.size()), 6u);
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          y = d.affine({1.2, 0.3, 0.1, 0.9});
  std::vector<double>          t, f;
  const KernelStats            s = d.forces(svk, y, t, f);
  EXPECT_EQ(s.unusable, 6u);
  EXPECT_TRUE(s.ok());
  for (std::size_t b = d.families.offsets[i]; b < d.families.offsets[i + 1]; ++b) {
    EXPECT_EQ(t[2 * b], 0.0);
    EXPECT_EQ(t[2 * b + 1], 0.0);
  }
  // Recomputing every point's geometry finds the same six: the count is of the state.
  EXPECT_EQ(nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry), 6u);
}

TEST(Damage, NotchBondsAreNotDamage)
{
  Body<2> body = test::plate(20, 20, 1.0);
  body.notches.push_back({20.0, 10.0, 10.0, 10.0});
  test::Discretisation d(body);
  std::vector<double>  damage(d.size());
  point_damage(d.cloud, d.families, d.state, d.size(), damage.data());
  for (double v : damage) EXPECT_EQ(v, 0.0);
}

// The crossing density c = 1/2 sum_j |xi . n| V_j is what a straight crack along a
// lattice row cuts per unit area: counted here pair by pair on a real lattice, across
// the line between two rows, over the columns far from the plate's sides.
TEST(FractureEnergy, CrossingDensityIsWhatACrackBetweenTwoRowsCuts)
{
  for (const double factor : {2.515, 3.015, 3.515}) {
    const double         dx = 0.5e-3, t = 3.0e-3;
    test::Discretisation d(test::plate(30, 12, dx, t), factor);
    const double         line = 6 * dx; // between rows 5 and 6 (cell centres at (k + 1/2) dx)
    double               cut  = 0.0;    // sum of V_i V_j over crossing pairs with i below, x_i in the middle 10 columns
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double xi = d.cloud.x[2 * i], yi = d.cloud.x[2 * i + 1];
      if (yi > line || xi < 10 * dx || xi > 20 * dx) continue;
      for (std::size_t q = 0; q < d.families.size(i); ++q) {
        const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
        if (d.cloud.x[2 * j + 1] > line) cut += d.cloud.volume[i] * d.cloud.volume[j];
      }
    }
    const double per_area = cut / (10 * dx * t); // sum of V_i V_j a unit crack area: c_i (Gamma = w_c c_i)
    EXPECT_NEAR(crossing_density(2, dx * dx * t, factor * dx, t) / per_area, 1.0, 1e-12) << factor;
  }
}

// Far from the lattice scale the count is the continuum's: 2 t delta^3 / 3 in 2D,
// pi delta^4 / 4 in 3D (docs/method.md section 5.2).
TEST(FractureEnergy, CrossingDensityTendsToTheContinuumOne)
{
  const double h = 1e-3, t = 2e-3;
  for (const double m : {20.0, 40.0}) {
    const double delta = m * h;
    const double c2 = crossing_density(2, h * h * t, delta, t), c3 = crossing_density(3, h * h * h, delta, 0.0);
    EXPECT_NEAR(c2 / (2.0 * delta * delta * delta / 3.0 * t), 1.0, 1.5 / m) << m;
    EXPECT_NEAR(c3 / (M_PI * std::pow(delta, 4) / 4.0), 1.0, 1.5 / m) << m;
  }
  // The paper's lattice (delta = 3.015 dx): 0.985 of the continuum in 2D, 1.079 in 3D.
  EXPECT_NEAR(crossing_density(2, h * h * t, 3.015 * h, t) / (2.0 * std::pow(3.015 * h, 3) / 3.0 * t), 0.9851, 1e-4);
  EXPECT_NEAR(crossing_density(3, h * h * h, 3.015 * h, 0.0) / (M_PI * std::pow(3.015 * h, 4) / 4.0), 1.0786, 1e-4);
}

// A bond breaks once Psi_ij / V(H_i) + Psi_ji / V(H_j) reaches 2 Gamma / (c_i + c_j),
// both copies together; a bond without energy (-1) counts as 0.
TEST(FractureEnergy, PairEnergyBreaksBothCopiesAtTheCriticalOne)
{
  test::Discretisation d(test::plate(9, 9, 1.0));
  const std::size_t    p = 4 * 9 + 4, n = d.families.neighbour.size();
  std::vector<double>  crossing(d.size(), 2.0), psi(n, -1.0);
  // Every bond of p carries q + 1 (its position), every reverse copy 0: the pair
  // energy of p's bond q is (q + 1) / V(H_p); Gamma at the level of q = 9.5 breaks
  // the bonds q >= 9 of p, from both ends.
  for (std::size_t q = 0; q < d.families.size(p); ++q) {
    psi[d.families.offsets[p] + q]                                                 = double(q + 1);
    psi[static_cast<std::size_t>(d.families.reverse[d.families.offsets[p] + q])] = 0.0;
  }
  const double             gamma = 10.5 / d.cloud.family_volume[p] * 2.0; // e (c_i + c_j) / 2 at q + 1 = 10.5
  std::vector<std::size_t> touched;
  const std::size_t        broken = break_bonds_by_energy(d.cloud, d.families, psi.data(), crossing.data(), gamma, d.state, touched);
  std::size_t              expected = 0;
  for (std::size_t q = 0; q < d.families.size(p); ++q) {
    const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[p] + q]);
    EXPECT_EQ(d.state.is_intact(p, q), q + 1 < 11) << q;
    EXPECT_EQ(d.state.is_intact(j, position_of(d.families, j, p)), q + 1 < 11) << q;
    if (q + 1 >= 11) {
      ++expected;
      EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), j));
    }
  }
  ASSERT_GT(expected, 0u);
  EXPECT_EQ(broken, 2 * expected);
  EXPECT_TRUE(std::is_sorted(touched.begin(), touched.end()));
  EXPECT_EQ(break_bonds_by_energy(d.cloud, d.families, psi.data(), crossing.data(), gamma, d.state, touched), 0u);
}

// bond_energies: under an affine motion every interior bond carries Psi(A), and the
// strain energy is their volume average (the two share one loop).
TEST(FractureEnergy, BondEnergiesOfAnAffineMotionArePsiOfIt)
{
  test::Discretisation         d(test::plate(12, 12, 1.0));
  test::SaintVenantKirchhoff2D svk;
  const Mat2                   A = {1.2, 0.3, 0.1, 0.9};
  std::vector<double>          y = d.affine(A), psi(d.families.neighbour.size());
  nd::Workspace<2>             ws;
  nd::bond_energies<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws, psi.data());
  double c = 0.0, expected = 0.0;
  ASSERT_EQ(svk.energy(A, c, expected), StressStatus::ok);
  ASSERT_GT(expected, 0.0);
  const std::size_t centre = 6 * 12 + 6;
  for (std::size_t b = d.families.offsets[centre]; b < d.families.offsets[centre + 1]; ++b)
    EXPECT_NEAR(psi[b], expected, 1e-12 * expected);
  for (double v : psi) EXPECT_TRUE(v == -1.0 || v >= 0.0);
}

// crack_extent counts the broken pairs back through the crossing density: a cut of length
// L along a lattice row, made of exactly the pairs the crossing density counts (i below the
// line with x_i in L's columns, j above), has area L t to round-off; its tip is the broken
// midpoint furthest along the axis, here from the right side towards -x (the notch of
// examples/notched_pure_shear.yaml runs that way).
TEST(CrackExtent, AStraightCutHasItsLengthTimesTheThicknessAndItsTip)
{
  const double         dx = 0.5e-3, t = 3.0e-3, width = 30 * dx;
  test::Discretisation d(test::plate(30, 12, dx, t));
  const double         line = 6 * dx;
  std::vector<std::size_t> touched;
  double                   nearest = width; // smallest midpoint x of the pairs cut (the tip towards -x)
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double xi = d.cloud.x[2 * i], yi = d.cloud.x[2 * i + 1];
    if (yi > line || xi < 10 * dx || xi > 20 * dx) continue;
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
      if (d.cloud.x[2 * j + 1] < line) continue;
      ASSERT_TRUE(break_bond(d.families, d.state, i, q, &touched));
      nearest = std::min(nearest, 0.5 * (xi + d.cloud.x[2 * j]));
    }
  }
  const std::vector<double> crossing(d.size(), crossing_density(2, dx * dx * t, 3.015 * dx, t));
  std::vector<double>       area(d.size());
  const double              origin[2] = {width, line}, direction[2] = {-1.0, 0.0};
  double                    tip[4];
  crack_extent(2, d.cloud, d.families, d.state, crossing.data(), d.size(), origin, direction, area.data(), tip);
  double total = 0;
  for (double a : area) total += a;
  EXPECT_NEAR(total / (10 * dx * t), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(tip[0], width - nearest);
  EXPECT_DOUBLE_EQ(tip[1], nearest);
  EXPECT_NEAR(tip[2], line, 3.015 * dx); // a midpoint within a horizon of the line
  // No broken bond, no tip.
  BondState intact(d.families);
  crack_extent(2, d.cloud, d.families, intact, crossing.data(), d.size(), origin, direction, area.data(), tip);
  EXPECT_TRUE(std::isinf(tip[0]) && tip[0] < 0);
  EXPECT_EQ(*std::max_element(area.begin(), area.end()), 0.0);
}

// The energy a breaking pass releases, taken over the points whose bonds it changed only
// (listed_strain_energies; the fracture dissipation of history.csv), is the change of the
// whole body's strain energy: W_i depends on the bonds of i alone.
TEST(CrackExtent, TheReleasedEnergyIsThatOfThePointsWhoseBondsBroke)
{
  test::Discretisation         d(test::plate(14, 14, 1.0));
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          y = d.affine({1.3, 0.2, -0.1, 0.8});
  for (std::size_t i = 0; i < d.size(); ++i) y[2 * i + 1] += 0.05 * std::sin(1.7 * d.cloud.x[2 * i]); // not affine
  nd::Workspace<2> ws;
  const double     before = nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws);
  // Break three bonds of the centre and one near the edge, as a pass would.
  std::vector<std::size_t> touched;
  const std::size_t        centre = 7 * 14 + 7, edge = 1 * 14 + 2;
  for (std::size_t q : {0, 5, 11}) ASSERT_TRUE(break_bond(d.families, d.state, centre, q, &touched));
  ASSERT_TRUE(break_bond(d.families, d.state, edge, 3, &touched));
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<double> listed_after(touched.size()), listed_before(touched.size());
  // The listed energies before the pass: the same points with the bonds intact.
  BondState           intact(d.families);
  nd::BondGeometry<2> geometry_before;
  nd::compute_bond_geometry<2>(d.cloud, d.families, intact, geometry_before);
  nd::listed_strain_energies<2>(svk, d.cloud, y.data(), d.families, geometry_before, intact, nullptr, touched.data(), touched.size(), ws,
                                listed_before.data());
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  const double after = nd::strain_energy<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, d.size(), ws);
  nd::listed_strain_energies<2>(svk, d.cloud, y.data(), d.families, d.geometry, d.state, nullptr, touched.data(), touched.size(), ws,
                                listed_after.data());
  double released = 0;
  for (std::size_t k = 0; k < touched.size(); ++k) released += listed_before[k] - listed_after[k];
  ASSERT_NE(before, after);
  EXPECT_NEAR(released, before - after, 1e-12 * before);
}

} // namespace
} // namespace bapd
