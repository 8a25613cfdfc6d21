// The dimension-generic core (include/bapd/nd) instantiated for D = 2 against the 2D
// kernel (ba_force.hpp, ba_force_energy.hpp, bond_geometry.hpp, family.hpp): same
// lattice, same displacement field, same broken bonds, both force forms, with and
// without the stress correction. The generic core does the 2D kernel's operations in
// its order (nd/bond_geometry.hpp), so the tolerance is 0: bit for bit. That is what
// makes moving the 2D driver onto the generic core safe (docs/architecture.md, "3D
// (stage 1)"): the rank-invariance, restart and baseline tests keep their bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "bapd/gent.hpp"
#include "bapd/damage.hpp"
#include "bapd/nd/ba_force.hpp"
#include "bapd/nd/damage.hpp"
#include "bapd/nd/family.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

using test::CutPlate;

// The 2D plate (hole, notch, broken bonds, non-affine y) on the generic core.
struct GenericPlate {
  nd::BondGeometry<2> geometry;
  explicit GenericPlate(const CutPlate &c, StressCorrection correction)
  {
    geometry.stress_correction = correction;
    nd::compute_bond_geometry<2>(c.d.cloud, c.d.families, c.d.state, geometry);
  }
};

void set_correction(test::Discretisation &d, StressCorrection c)
{
  d.geometry.stress_correction = c;
  compute_bond_geometry(d.cloud, d.families, d.state, d.geometry);
}

TEST(GenericCore2D, BuildsTheFamiliesOf2DBitForBit)
{
  for (double factor : {3.015, 5.015}) { // one and two mask words
    const CutPlate c(20, 0.0, 1, factor);
    const Body2D  &body = c.body;
    const Families f    = nd::build_families<2>(c.d.cloud, c.d.size(), factor * test::kPlateDx,
                                                [&](const double *a, const double *b) {
                                               for (const Segment &s : body.notches)
                                                 if (segments_cross(a[0], a[1], b[0], b[1], s)) return true;
                                               return false;
                                             });
    const Families &g = c.d.families;
    EXPECT_EQ(f.offsets, g.offsets);
    EXPECT_EQ(f.neighbour, g.neighbour);
    EXPECT_EQ(f.reverse, g.reverse);
    EXPECT_EQ(f.ba_mask, g.ba_mask);
    EXPECT_EQ(f.mask_words, g.mask_words);
    EXPECT_EQ(f.max_family_size, g.max_family_size);
    EXPECT_GT(g.n_bonds(), 8000u); // not vacuous
  }
}

TEST(GenericCore2D, GivesThe2DBondGeometryAndCorrectionBitForBit)
{
  CutPlate c(20, 0.1, 3);
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor, StressCorrection::scalar}) {
    set_correction(c.d, k);
    const GenericPlate g(c, k);
    EXPECT_EQ(g.geometry.usable, c.d.geometry.usable);
    EXPECT_EQ(g.geometry.singular, c.d.geometry.singular);
    EXPECT_EQ(g.geometry.correction, c.d.geometry.correction) << to_string(k);
  }
}

// Bond forces, c33 and force densities of both cores for one model and form.
template <class Model>
void expect_same_forces(CutPlate &c, const Model &model, nd::ForceForm form, StressCorrection k)
{
  set_correction(c.d, k);
  const GenericPlate  g(c, k);
  const std::size_t   nb = c.d.families.n_bonds(), n = c.d.size();
  std::vector<double> t2(2 * nb, 7.0), tn(2 * nb, -7.0), c2(nb, 0.0), cn(nb, 0.0), f2(2 * n), fn(2 * n);
  BondKernelWorkspace ws2;
  nd::Workspace<2>    wsn;
  const KernelStats   s2 =
      form == nd::ForceForm::bond_only
            ? compute_bond_forces(model, c.d.cloud, c.y.data(), c.d.families, c.d.geometry, c.d.state, c2.data(), t2.data(), ws2)
            : compute_energy_consistent_bond_forces(model, c.d.cloud, c.y.data(), c.d.families, c.d.geometry, c.d.state,
                                                    c2.data(), t2.data(), ws2);
  const KernelStats sn =
      nd::compute_bond_forces<2>(form, model, c.d.cloud, c.y.data(), c.d.families, g.geometry, c.d.state, cn.data(), tn.data(), wsn);
  ASSERT_TRUE(s2.ok());
  EXPECT_EQ(sn.evaluated, s2.evaluated);
  EXPECT_EQ(sn.unusable, s2.unusable);
  EXPECT_GT(s2.evaluated, 4000u); // not vacuous
  // Tolerance 0: the same floating-point operations in the same order (see the top).
  for (std::size_t k2 = 0; k2 < 2 * nb; ++k2) ASSERT_EQ(tn[k2], t2[k2]) << "bond " << k2 / 2;
  for (std::size_t b = 0; b < nb; ++b) ASSERT_EQ(cn[b], c2[b]) << "bond " << b;
  assemble_force_density(c.d.families, c.d.cloud, t2.data(), n, f2.data());
  nd::assemble_force_density<2>(c.d.families, c.d.cloud, tn.data(), n, fn.data());
  EXPECT_EQ(fn, f2);
  // and the strain energy, point by point
  std::vector<double> e2(n), en(n);
  strain_energy(model, c.d.cloud, c.y.data(), c.d.families, c.d.geometry, c.d.state, c2.data(), n, ws2, nullptr, e2.data());
  nd::strain_energy<2>(model, c.d.cloud, c.y.data(), c.d.families, g.geometry, c.d.state, cn.data(), n, wsn, nullptr,
                       en.data());
  EXPECT_EQ(en, e2);
}

MaterialParameters gel()
{
  MaterialParameters p; // the paper's hydrogel, K = 100 mu
  p.D = 2.0 / (100.0 * p.mu);
  return p;
}

TEST(GenericCore2D, PlaneStrainGentBondOnlyForcesAreThe2DKernelsBitForBit)
{
  CutPlate c(20, 0.1, 11);
  ASSERT_GT(c.d.state.count_broken(c.d.families, c.d.size()), 500u);
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor})
    expect_same_forces(c, GentPlaneStrain{gel()}, nd::ForceForm::bond_only, k);
}

TEST(GenericCore2D, PlaneStrainGentEnergyConsistentForcesAreThe2DKernelsBitForBit)
{
  CutPlate c(20, 0.1, 12);
  expect_same_forces(c, GentPlaneStrain{gel()}, nd::ForceForm::energy_consistent, StressCorrection::none);
}

TEST(GenericCore2D, TwoMaskWordsGiveThe2DKernelsForcesBitForBit)
{
  // delta = 5.015 dx: 80 neighbours, two mask words (the 2D kernel's run-time-width
  // path, the generic core's Words = 2).
  CutPlate c(20, 0.1, 14, 5.015);
  ASSERT_EQ(c.d.families.mask_words, 2u);
  expect_same_forces(c, GentPlaneStrain{gel()}, nd::ForceForm::bond_only, StressCorrection::tensor);
  expect_same_forces(c, GentPlaneStrain{gel()}, nd::ForceForm::energy_consistent, StressCorrection::none);
}

TEST(GenericCore2D, PlaneStressGentWithWarmStartsIsThe2DKernelsBitForBit)
{
  // Both cores run PlaneStress in lanes (stress_lanes, lane_count bonds at a time,
  // the failed lanes through the scalar solve): the same bits, c33 included.
  CutPlate c(16, 0.1, 13);
  expect_same_forces(c, test::hydrogel(), nd::ForceForm::bond_only, StressCorrection::tensor);
  expect_same_forces(c, test::hydrogel(), nd::ForceForm::energy_consistent, StressCorrection::none);
}

TEST(GenericCore2D, PatchCorrectionIsThe2DKernelsBitForBit)
{
  // -force_patch_correction: h_ij = ((lambda_i - lambda_j) . xi) xi added to g_ij
  // (patch_correction.hpp). The kernel only reads lambda, so any lambda exercises
  // its line; a field with both signs, sized so that h is of the order of g for an
  // interior bond (|g| ~ 1 / (m V dx), |h| ~ |lambda| dx^2, m ~ 28 members): it moves
  // the bond forces by about 1 % of the largest (an edge bond's).
  CutPlate            c(20, 0.1, 16);
  const std::size_t   n = c.d.size(), nb = c.d.families.n_bonds();
  const double        scale = 1.0 / (28.0 * std::pow(test::kPlateDx, 5));
  std::vector<double> t0(2 * nb), t1(2 * nb);
  nd::Workspace<2>    ws;
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor}) {
    set_correction(c.d, k);
    const GenericPlate g(c, k);
    c.d.cloud.patch_correction.clear();
    nd::compute_bond_forces<2>(nd::ForceForm::bond_only, GentPlaneStrain{gel()}, c.d.cloud, c.y.data(), c.d.families,
                               g.geometry, c.d.state, nullptr, t0.data(), ws);
    c.d.cloud.patch_correction.resize(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      c.d.cloud.patch_correction[2 * i]     = scale * std::sin(0.7 * static_cast<double>(i));
      c.d.cloud.patch_correction[2 * i + 1] = scale * std::cos(1.3 * static_cast<double>(i));
    }
    nd::compute_bond_forces<2>(nd::ForceForm::bond_only, GentPlaneStrain{gel()}, c.d.cloud, c.y.data(), c.d.families,
                               g.geometry, c.d.state, nullptr, t1.data(), ws);
    double change = 0.0, size = 0.0;
    for (std::size_t k2 = 0; k2 < 2 * nb; ++k2) {
      change = std::max(change, std::abs(t1[k2] - t0[k2]));
      size   = std::max(size, std::abs(t0[k2]));
    }
    EXPECT_GT(change, 1e-3 * size) << "lambda changes the forces (not vacuous)";
    expect_same_forces(c, GentPlaneStrain{gel()}, nd::ForceForm::bond_only, k);
    expect_same_forces(c, test::hydrogel(), nd::ForceForm::bond_only, k); // the lane path
  }
}

} // namespace
} // namespace bapd
