// What the solver asks of a scene once points exist (scene.hpp): the stretch
// schedule and its rate, the points a load set holds, the point a probe reads, and
// the point count, on one rank and split over several.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "bapd/lattice.hpp"
#include "bapd/scene.hpp"

namespace {

using bapd::LoadSet;
using bapd::Schedule;
using bapd::Scene;

// Ramp 1 -> 1.5 over 1 s, hold 1 s, ramp to 2 over 1 s.
Schedule RampHoldRamp() { return Schedule{{0, 1, 2, 3}, {1, 1.5, 1.5, 2}}; }

// The schedule values below are exact in binary floating point (halves and
// quarters), so the interpolation must reproduce them to the last bit.
TEST(Schedule, InterpolatesLinearlyBetweenKnots)
{
  const Schedule s = RampHoldRamp();
  EXPECT_EQ(s.stretch_at(0.0), 1.0);
  EXPECT_EQ(s.stretch_at(0.5), 1.25);
  EXPECT_EQ(s.stretch_at(1.0), 1.5);
  EXPECT_EQ(s.stretch_at(1.5), 1.5);
  EXPECT_EQ(s.stretch_at(2.5), 1.75);
  EXPECT_EQ(s.stretch_at(3.0), 2.0);
  EXPECT_EQ(s.end_time(), 3.0);
}

TEST(Schedule, HoldsTheEndValuesOutsideTheKnots)
{
  const Schedule s = RampHoldRamp();
  EXPECT_EQ(s.stretch_at(-1.0), 1.0);
  EXPECT_EQ(s.stretch_at(10.0), 2.0);
  const Schedule late{{1, 2}, {1.25, 1.5}}; // starts at t = 1 with lambda = 1.25
  EXPECT_EQ(late.stretch_at(0.0), 1.25);
  EXPECT_EQ(late.rate_at(0.0), 0.0);
}

TEST(Schedule, RateIsTheRightDerivative)
{
  const Schedule s = RampHoldRamp();
  EXPECT_EQ(s.rate_at(-1.0), 0.0);
  EXPECT_EQ(s.rate_at(0.0), 0.5);
  EXPECT_EQ(s.rate_at(0.75), 0.5);
  EXPECT_EQ(s.rate_at(1.0), 0.0); // the hold starts at t = 1
  EXPECT_EQ(s.rate_at(1.999), 0.0);
  EXPECT_EQ(s.rate_at(2.0), 0.5);
  EXPECT_EQ(s.rate_at(3.0), 0.0); // after the last knot lambda stays put
  EXPECT_EQ(s.rate_at(10.0), 0.0);
}

TEST(Schedule, RateIntegratesToTheStretch)
{
  // Midpoint rule on a piecewise-constant rate whose breaks fall on step ends: exact
  // up to round-off in the sum of 3000 terms (about 3000 ulps of 2).
  const Schedule s  = RampHoldRamp();
  const int      n  = 3000;
  const double   dt = 3.0 / n;
  double         lambda = s.stretch_at(0.0);
  for (int k = 0; k < n; ++k) lambda += s.rate_at((k + 0.5) * dt) * dt;
  EXPECT_NEAR(lambda, s.stretch_at(3.0), 1e-12);
}

TEST(Schedule, EmptyMeansNoStretch)
{
  const Schedule s;
  EXPECT_EQ(s.stretch_at(5.0), 1.0);
  EXPECT_EQ(s.rate_at(5.0), 0.0);
  EXPECT_EQ(s.end_time(), 0.0);
}

TEST(Scene, GripDisplacementFollowsTheSchedule)
{
  Scene scene;
  scene.schedule         = RampHoldRamp();
  scene.reference_length = 0.16;
  // u = scale (lambda - 1) L: the top grip of the plate (scale 1/2) at lambda = 1.25.
  EXPECT_DOUBLE_EQ(scene.grip_displacement(0.5, 0.5), 0.5 * 0.25 * 0.16);
  EXPECT_DOUBLE_EQ(scene.grip_velocity(-0.5, 0.5), -0.5 * 0.5 * 0.16);
  EXPECT_EQ(scene.grip_displacement(1.0, 0.0), 0.0);
}

// The plate with a hole (METHOD.md section 7.1): 80 x 160 points, dx = 1 mm.
Scene Plate()
{
  Scene scene;
  scene.body.width     = 0.08;
  scene.body.height    = 0.16;
  scene.body.thickness = 0.001;
  scene.body.dx        = 0.001;
  scene.body.holes     = {{0.04, 0.08, 0.01}};
  return scene;
}

// This rank's share of the points: every size-th one, so that both ranks hold
// points of every edge.
struct Share {
  std::vector<double>  x;
  std::vector<int64_t> id;
  PetscInt             n() const { return static_cast<PetscInt>(id.size()); }
};
Share TakeShare(const bapd::PointCloud &cloud)
{
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  Share share;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (static_cast<PetscMPIInt>(i % size) == rank) {
      share.x.push_back(cloud.x[2 * i]);
      share.x.push_back(cloud.x[2 * i + 1]);
      share.id.push_back(cloud.natural_id[i]);
    }
  return share;
}

PetscInt GlobalCount(const Scene &scene, const LoadSet &set, const Share &share)
{
  std::vector<PetscInt> selected;
  EXPECT_EQ(bapd::LoadSetSelect(scene, set, share.x.data(), share.n(), &selected), 0);
  PetscInt local = static_cast<PetscInt>(selected.size()), global = 0;
  MPI_Allreduce(&local, &global, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  return global;
}

TEST(LoadSetSelect, TakesWholePointLayersFromTheEdges)
{
  const Scene scene = Plate();
  const Share share = TakeShare(bapd::make_lattice(scene.body));
  LoadSet     set;
  for (int layers : {1, 3}) {
    set.layers = layers;
    set.region = LoadSet::Region::top;
    EXPECT_EQ(GlobalCount(scene, set, share), 80 * layers);
    set.region = LoadSet::Region::bottom;
    EXPECT_EQ(GlobalCount(scene, set, share), 80 * layers);
    set.region = LoadSet::Region::left;
    EXPECT_EQ(GlobalCount(scene, set, share), 160 * layers);
    set.region = LoadSet::Region::right;
    EXPECT_EQ(GlobalCount(scene, set, share), 160 * layers);
  }
}

TEST(LoadSetSelect, TakesThePointsInsideABox)
{
  const Scene scene = Plate();
  const Share share = TakeShare(bapd::make_lattice(scene.body));
  LoadSet     set;
  set.region = LoadSet::Region::box;
  // Points at 0.5, 1.5, ..., 9.5 mm in x and y: 10 x 10 of them.
  set.box[0] = 0;
  set.box[1] = 0;
  set.box[2] = 0.01;
  set.box[3] = 0.01;
  EXPECT_EQ(GlobalCount(scene, set, share), 100);
  // A box between two lattice rows holds nothing: the solver must catch this.
  set.box[1] = 0.0101;
  set.box[3] = 0.0104;
  EXPECT_EQ(GlobalCount(scene, set, share), 0);
}

TEST(LoadSetSelect, ReturnsIncreasingLocalIndices)
{
  const Scene           scene = Plate();
  const double          x[]   = {0.0005, 0.1595, 0.04, 0.08, 0.0795, 0.1595, 0.0005, 0.0005};
  LoadSet               set;
  std::vector<PetscInt> selected = {42}; // cleared first
  ASSERT_EQ(bapd::LoadSetSelect(scene, set, x, 4, &selected), 0);
  EXPECT_EQ(selected, (std::vector<PetscInt>{0, 2}));
}

TEST(ProbeLocate, FindsTheSamePointOnAnyNumberOfRanks)
{
  const Scene               scene = Plate();
  const bapd::PointCloud    cloud = bapd::make_lattice(scene.body);
  const Share               share = TakeShare(cloud);
  PetscMPIInt               rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (const bapd::Probe &probe : {bapd::Probe{"left_mid", 0.0, 0.08}, bapd::Probe{"corner", 0.08, 0.16}, bapd::Probe{"hole_edge", 0.03, 0.08}}) {
    // Serial answer over the whole cloud: the nearest point, ties to the lowest id.
    double  best_d2 = 1e300;
    int64_t best_id = -1;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const double dx = cloud.x[2 * i] - probe.x, dy = cloud.x[2 * i + 1] - probe.y, d2 = dx * dx + dy * dy;
      if (d2 < best_d2 || (d2 == best_d2 && cloud.natural_id[i] < best_id)) {
        best_d2 = d2;
        best_id = cloud.natural_id[i];
      }
    }
    bapd::ProbeLocation at;
    ASSERT_EQ(bapd::ProbeLocate(PETSC_COMM_WORLD, probe, share.x.data(), share.id.data(), share.n(), &at), 0);
    EXPECT_EQ(at.natural_id, best_id) << probe.name;
    EXPECT_EQ(at.distance, std::sqrt(best_d2)) << probe.name;
    if (at.owner == rank) {
      ASSERT_GE(at.local_index, 0);
      EXPECT_EQ(share.id[at.local_index], best_id);
    } else EXPECT_EQ(at.local_index, -1);
  }
}

TEST(ProbeLocate, BreaksExactTiesByLowestNaturalId)
{
  // Two points exactly 1 m from the probe: ids 7 at (0, 1) and 3 at (0, -1). On two
  // ranks id 7 lives on rank 0 and id 3 on rank 1.
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  std::vector<double>  x;
  std::vector<int64_t> id;
  if (rank == 0) {
    x.insert(x.end(), {0.0, 1.0});
    id.push_back(7);
  }
  if (rank == size - 1) {
    x.insert(x.end(), {0.0, -1.0});
    id.push_back(3);
  }
  bapd::ProbeLocation at;
  ASSERT_EQ(bapd::ProbeLocate(PETSC_COMM_WORLD, bapd::Probe{"tie", 0.0, 0.0}, x.data(), id.data(), (PetscInt)id.size(), &at), 0);
  EXPECT_EQ(at.natural_id, 3);
  EXPECT_EQ(at.owner, size - 1);
  EXPECT_EQ(at.distance, 1.0);
}

TEST(ScenePointEstimate, CountsWhatTheLatticeBuilds)
{
  Scene scene = Plate();
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)bapd::make_lattice(scene.body).size());
  scene.body.holes.push_back({0.02, 0.02, 0.0153});
  scene.body.width = 0.0804; // not a whole number of spacings
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)bapd::make_lattice(scene.body).size());
  scene.body.holes.clear();
  EXPECT_EQ(bapd::ScenePointEstimate(scene), 80 * 160);
}

} // namespace
