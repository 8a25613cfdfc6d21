// The bond kernel's four-bond path (ba_force.hpp: model_lanes, PlaneStress::stress_lanes)
// on a non-affine field with Gent: bit for bit the bond forces and C33 of the same
// kernel run one bond at a time, for both force forms, with cold and with warm starts;
// and the workspace's keep_warm_start, which evaluates without writing C33 back.
#include <gtest/gtest.h>

#include <cstdio>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "unit/kernel_fixtures.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

// Gent plane stress without stress_lanes: the kernel's one-bond-at-a-time path.
struct ScalarGent {
  GentPlaneStress gent;
  StressStatus    stress(const Mat2 &F, double &c33, Mat2 &P) const { return gent.stress(F, c33, P); }
};

// Gent plane stress that counts its scalar calls: with lanes, those are the bonds that
// stress_lanes did not finish (the fallback).
struct CountingGent : GentPlaneStress {
  mutable std::size_t scalar_calls = 0;
  StressStatus        stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    ++scalar_calls;
    return GentPlaneStress::stress(F, c33, P);
  }
};

bool same_bits(const std::vector<double> &a, const std::vector<double> &b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Bond forces of one kernel call (bond-only or energy-consistent) from the warm starts
// c33, which the call updates unless keep_warm_start.
template <class Model>
std::vector<double> bond_forces(const Model &model, const test::Discretisation &d, const std::vector<double> &y,
                                std::vector<double> &c33, bool keep_warm_start = false, bool energy_consistent = false)
{
  std::vector<double> t(2 * d.families.n_bonds(), 0.0);
  nd::Workspace<2> ws;
  ws.keep_warm_start = keep_warm_start;
  const KernelStats s =
      energy_consistent
          ? nd::compute_bond_forces<2>(ForceForm::energy_consistent, model, d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(),
                                                  t.data(), ws)
          : nd::compute_bond_forces<2>(ForceForm::bond_only, model, d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(), t.data(), ws);
  EXPECT_TRUE(s.ok());
  EXPECT_GT(s.evaluated, d.families.n_bonds() / 2); // most bonds are intact and usable
  return t;
}

// Both forms share the first pass (stress_pass): the energy-consistent one gets the
// same four-bond path, and must give bit for bit its one-bond-at-a-time result too.
void expect_lanes_match_the_scalar_kernel(bool energy_consistent)
{
  const test::CutPlate  c(20, 0.15, 17);
  const GentPlaneStress gent = test::hydrogel();
  CountingGent          counting{gent};
  const ScalarGent      scalar{gent};
  // Four "time steps": from cold (C33 = 0) at y; warm at y moved by up to 1e-4 dx (a
  // time step's motion); warm at y moved by up to 1e-2 dx (larger steps: a second
  // evaluation in the lanes); and from warm starts scrambled by a factor in [1/2, 2]
  // (far guesses: the scalar fallback, with its bisections).
  std::mt19937        rng(5);
  std::vector<double> y1 = c.y, y2 = c.y;
  for (double &v : y1) v += test::random_between(rng, -1e-4, 1e-4) * test::kPlateDx;
  for (double &v : y2) v += test::random_between(rng, -1e-2, 1e-2) * test::kPlateDx;
  const std::vector<double> *fields[4] = {&c.y, &y1, &y2, &c.y};
  std::vector<double>        c_lanes(c.d.families.n_bonds(), 0.0), c_scalar(c_lanes);
  std::size_t                fallbacks[4] = {0, 0, 0, 0};
  for (int step = 0; step < 4; ++step) {
    if (step == 3)
      for (std::size_t b = 0; b < c_lanes.size(); ++b) c_scalar[b] = c_lanes[b] *= std::exp2(test::random_between(rng, -1.0, 1.0));
    counting.scalar_calls         = 0;
    const std::vector<double> t   = bond_forces(counting, c.d, *fields[step], c_lanes, false, energy_consistent);
    const std::vector<double> ref = bond_forces(scalar, c.d, *fields[step], c_scalar, false, energy_consistent);
    fallbacks[step]               = counting.scalar_calls;
    EXPECT_TRUE(same_bits(t, ref)) << "step " << step;
    EXPECT_TRUE(same_bits(c_lanes, c_scalar)) << "step " << step;
  }
  const std::size_t bonds = c.d.families.n_bonds();
  std::printf("%s: scalar fallbacks of %zu bonds: cold %zu, warm 1e-4 dx %zu, warm 1e-2 dx %zu, scrambled %zu\n",
              energy_consistent ? "energy-consistent" : "bond-only", bonds, fallbacks[0], fallbacks[1], fallbacks[2],
              fallbacks[3]);
  // Not vacuous: the lanes finish the usual steps, and the far guesses reach the
  // fallback for a good share of the bonds, so both paths were compared.
  EXPECT_LT(fallbacks[1], bonds / 100);
  EXPECT_GT(fallbacks[3], bonds / 10);
}

TEST(BaForceLanes, NonAffineGentFieldGivesBitForBitTheScalarKernelColdAndWarm)
{
  expect_lanes_match_the_scalar_kernel(false);
}

TEST(BaForceLanes, EnergyConsistentFormOnTheLanesGivesBitForBitItsScalarKernel)
{
  expect_lanes_match_the_scalar_kernel(true);
}

TEST(BaForceLanes, KeepWarmStartLeavesC33AndGivesTheSameForces)
{
  const test::CutPlate  c(16, 0.1, 9);
  const GentPlaneStress gent = test::hydrogel();
  std::vector<double>   c33(c.d.families.n_bonds(), 0.0);
  bond_forces(gent, c.d, c.y, c33); // the converged C33 at y
  std::vector<double> y = c.y;
  std::mt19937        rng(2);
  for (double &v : y) v += test::random_between(rng, -1e-3, 1e-3) * test::kPlateDx;
  for (bool energy_consistent : {false, true}) {
    std::vector<double>       kept = c33, written = c33;
    const std::vector<double> t_kept    = bond_forces(gent, c.d, y, kept, true, energy_consistent);
    const std::vector<double> t_written = bond_forces(gent, c.d, y, written, false, energy_consistent);
    EXPECT_TRUE(same_bits(kept, c33)) << "keep_warm_start writes nothing back";
    EXPECT_FALSE(same_bits(written, c33)) << "not vacuous: without it the solved C33 is stored";
    EXPECT_TRUE(same_bits(t_kept, t_written)) << "the same warm starts give the same forces";
  }
}

// KernelStats::largest_trC from the lanes (model_lanes, a vector at a time) is the scalar
// path's (stress_pass, one bond at a time), both forms, from converged warm starts (their
// C33 is part of tr C): the time step's stiffening trigger reads it whichever path ran.
TEST(BaForceLanes, LargestTraceOfCIsTheScalarKernels)
{
  const test::CutPlate  c(16, 0.1, 9);
  const GentPlaneStress gent = test::hydrogel();
  const ScalarGent      scalar{gent};
  std::vector<double>   c33(c.d.families.n_bonds(), 0.0);
  bond_forces(gent, c.d, c.y, c33); // the converged C33 at y
  for (ForceForm form : {ForceForm::bond_only, ForceForm::energy_consistent}) {
    std::vector<double> t(2 * c.d.families.n_bonds());
    nd::Workspace<2>    ws;
    ws.keep_warm_start  = true;
    const KernelStats a = nd::compute_bond_forces<2>(form, gent, c.d.cloud, c.y.data(), c.d.families, c.d.geometry, c.d.state, c33.data(),
                                                     t.data(), ws);
    const KernelStats b = nd::compute_bond_forces<2>(form, scalar, c.d.cloud, c.y.data(), c.d.families, c.d.geometry, c.d.state,
                                                     c33.data(), t.data(), ws);
    EXPECT_GT(a.largest_trC, 3.1); // stretched by 1.2 and sheared: not the rest state's 3
    EXPECT_NEAR(a.largest_trC, b.largest_trC, 1e-14 * b.largest_trC); // the lanes may contract a product into an fma
  }
}

// model_lanes hands a point's last bonds to stress_lanes in HalfLanes when they fill
// half a register or less (plane_stress_fast_path_test checks that path against
// stress() model by model): the cut plate of the bit-for-bit tests above has such
// points, so those tests compare it in the kernel too.
TEST(BaForceLanes, TheCutPlateHasPointsWhoseLastBatchIsHalfARegister)
{
  const test::CutPlate c(20, 0.15, 17);
  std::size_t          tails = 0;
  for (std::size_t i = 0; i < c.d.cloud.size(); ++i) {
    const std::size_t r = c.d.families.size(i) % lane_count;
    tails += r > 0 && r <= static_cast<std::size_t>(half_lane_count);
  }
  EXPECT_GT(tails, c.d.cloud.size() / 10);
}

} // namespace
} // namespace bapd
