// What the solver asks of a scene once points exist (scene.hpp): the stretch
// schedule and its rate, the points a load set holds, the point a probe reads, and
// the point count, on one rank and split over several.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/operators/loading.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"

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
  scene.loading.schedule         = RampHoldRamp();
  scene.loading.reference_length = 0.16;
  // u = scale (lambda - 1) L: the top grip of the plate (scale 1/2) at lambda = 1.25.
  EXPECT_DOUBLE_EQ(scene.loading.grip_displacement(0.5, 0.5), 0.5 * 0.25 * 0.16);
  EXPECT_DOUBLE_EQ(scene.loading.grip_velocity(-0.5, 0.5), -0.5 * 0.5 * 0.16);
  EXPECT_EQ(scene.loading.grip_displacement(1.0, 0.0), 0.0);
}

// The plate with a hole (docs/method.md section 7.1): 80 x 160 points, dx = 1 mm.
Scene Plate()
{
  Scene scene;
  scene.body.sheet.width     = 0.08;
  scene.body.sheet.height    = 0.16;
  scene.body.sheet.thickness = 0.001;
  scene.body.sheet.dx        = 0.001;
  scene.body.sheet.holes     = {{0.04, 0.08, 0.01}};
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
  EXPECT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), set, share.x.data(), share.n(), &selected), 0);
  PetscInt local = static_cast<PetscInt>(selected.size()), global = 0;
  MPI_Allreduce(&local, &global, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  return global;
}

// The region words quoted in messages and -help come from the registry: every region a
// sheet takes is among the 2D choices, every one a 3D body takes among the 3D choices
// (a face also by its alias), and all of them in -load_NAME_region's help.
TEST(RegionRegistry, ChoicesAndHelpNameEveryRegisteredRegion)
{
  const std::string sheet = bapd::RegionChoices(false), solid = bapd::RegionChoices(true), help = bapd::RegionHelp();
  auto word_in = [](const std::string &text, const std::string &word) { // a whole word: not "box" in "block"
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
      const bool start = at == 0 || std::string(" (,|").find(text[at - 1]) != std::string::npos;
      const bool end   = at + word.size() == text.size() || std::string(" ),|").find(text[at + word.size()]) != std::string::npos;
      if (start && end) return true;
    }
    return false;
  };
  for (const bapd::RegionType &r : bapd::registered_regions()) {
    EXPECT_TRUE(word_in(help, r.word)) << r.word << " missing from: " << help;
    EXPECT_EQ(word_in(sheet, r.word), r.check2d != nullptr) << r.word << " / " << sheet;
    EXPECT_EQ(word_in(solid, r.word), r.check3d != nullptr) << r.word << " / " << solid;
    if (r.alias && r.check3d) {
      EXPECT_TRUE(word_in(solid, std::string(r.word) + " or " + r.alias)) << r.word << " / " << solid;
    }
  }
  EXPECT_EQ(sheet.rfind("top, bottom, left, right, box, ", 0), 0u) << sheet; // the registry's order
}

TEST(LoadSetSelect, TakesWholePointLayersFromTheEdges)
{
  const Scene scene = Plate();
  const Share share = TakeShare(bapd::make_lattice(scene.body.sheet));
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
  const Share share = TakeShare(bapd::make_lattice(scene.body.sheet));
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

TEST(LoadSetSelect, PolygonTakesThePointsInsideItEdgesIncluded)
{
  const Scene scene = Plate();
  const Share share = TakeShare(bapd::make_lattice(scene.body.sheet));
  LoadSet     set;
  set.region         = LoadSet::Region::polygon;
  set.area.kind      = bapd::Shape::Kind::polygon;
  // The right triangle (0, 0), (10.2, 0), (0, 10.2) mm: the points ((i + 1/2), (j + 1/2))
  // mm with i + j + 1 <= 10.2, 10 + 9 + ... + 1 = 55 of them.
  set.area.vertices = {0, 0, 0.0102, 0, 0, 0.0102};
  EXPECT_EQ(GlobalCount(scene, set, share), 55);
  // The same square as the box test, as a polygon: the same 100 points.
  set.area.vertices = {0, 0, 0.01, 0, 0.01, 0.01, 0, 0.01};
  EXPECT_EQ(GlobalCount(scene, set, share), 100);
}

TEST(LoadSetSelect, CurveAlongAnEdgeTakesTheEdgeRowsOfItsDepth)
{
  const Scene            scene = Plate();
  const bapd::PointCloud cloud = bapd::make_lattice(scene.body.sheet);
  for (int layers : {1, 3}) {
    LoadSet edge;
    edge.region = LoadSet::Region::top, edge.layers = layers;
    LoadSet curve;
    curve.region   = LoadSet::Region::curve;
    curve.segments = {0.08, 0.16, 0.0, 0.16}; // the top edge, right to left
    curve.depth    = layers * scene.body.sheet.dx;
    bapd::SetCurveReach(&curve);
    std::vector<PetscInt> from_edge, from_curve;
    ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), edge, cloud.x.data(), (PetscInt)cloud.size(), &from_edge), 0);
    ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), curve, cloud.x.data(), (PetscInt)cloud.size(), &from_curve), 0);
    EXPECT_EQ(from_curve, from_edge) << layers << " layer(s)";
    EXPECT_EQ(from_curve.size(), 80u * layers);
  }
}

TEST(LoadSetSelect, CurveTakesThePointsCloserThanItsDepthToAnyOfItsSegments)
{
  const Scene            scene = Plate();
  const bapd::PointCloud cloud = bapd::make_lattice(scene.body.sheet);
  const Share            share = TakeShare(cloud);
  LoadSet                set;
  set.region = LoadSet::Region::curve;
  // An L-shaped polyline and a single point (a segment of length 0), 2.2 mm deep.
  set.segments = {0.02, 0.03, 0.05, 0.07, 0.05, 0.07, 0.06, 0.07, 0.07, 0.12, 0.07, 0.12};
  set.depth    = 0.0022;
  bapd::SetCurveReach(&set);
  auto distance = [](const double *s, double px, double py) { // the plain formula, point by point
    const double ex = s[2] - s[0], ey = s[3] - s[1], len2 = ex * ex + ey * ey;
    double       t  = len2 > 0 ? ((px - s[0]) * ex + (py - s[1]) * ey) / len2 : 0;
    t               = t < 0 ? 0 : t > 1 ? 1 : t;
    return std::hypot(px - s[0] - t * ex, py - s[1] - t * ey);
  };
  PetscInt expected = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    double d = 1e300;
    for (std::size_t k = 0; k < set.segments.size(); k += 4) d = std::min(d, distance(&set.segments[k], cloud.x[2 * i], cloud.x[2 * i + 1]));
    expected += d < set.depth;
  }
  EXPECT_GT(expected, 100); // the test means something
  EXPECT_EQ(GlobalCount(scene, set, share), expected);
}

TEST(LoadSetSelect, ReturnsIncreasingLocalIndices)
{
  const Scene           scene = Plate();
  const double          x[]   = {0.0005, 0.1595, 0.04, 0.08, 0.0795, 0.1595, 0.0005, 0.0005};
  LoadSet               set;
  std::vector<PetscInt> selected = {42}; // cleared first
  ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), set, x, 4, &selected), 0);
  EXPECT_EQ(selected, (std::vector<PetscInt>{0, 2}));
}

TEST(ProbeLocate, FindsTheSamePointOnAnyNumberOfRanks)
{
  const Scene               scene = Plate();
  const bapd::PointCloud    cloud = bapd::make_lattice(scene.body.sheet);
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
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)bapd::make_lattice(scene.body.sheet).size());
  scene.body.sheet.holes.push_back({0.02, 0.02, 0.0153});
  scene.body.sheet.width = 0.0804; // not a whole number of spacings
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)bapd::make_lattice(scene.body.sheet).size());
  scene.body.sheet.holes.clear();
  EXPECT_EQ(bapd::ScenePointEstimate(scene), 80 * 160);
}

// Grips outside the specimen (Body<2>::grip_rows): whole rows beyond each edge, each
// the edge row extruded, counted as built, held by the outside sets alone.
TEST(GripRows, ExtrudeTheEdgeRowsAndAreCountedAsBuilt)
{
  Scene scene = Plate();
  scene.body.sheet.holes.push_back({0.02, 0.16, 0.0052}); // cuts the top edge row: 10 of its points
  scene.body.sheet.grip_rows = {2, 3, 6, 6};              // left, right, bottom, top
  const bapd::PointCloud cloud = bapd::make_lattice(scene.body.sheet);
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)cloud.size());
  std::vector<double> top_edge, top_strip; // x of the sheet's top row, and of each row above it
  int                 strip_rows_seen = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double x = cloud.x[2 * i], y = cloud.x[2 * i + 1];
    if (std::fabs(y - 0.1595) < 1e-9 && x > 0 && x < 0.08) top_edge.push_back(x);
    if (std::fabs(y - 0.1655) < 1e-9 && x > 0 && x < 0.08) top_strip.push_back(x); // the 6th row above
    strip_rows_seen += std::fabs(y - 0.1665) < 1e-9;                                // a 7th: none
  }
  EXPECT_EQ(top_edge.size(), 70u);
  EXPECT_EQ(top_strip, top_edge);
  EXPECT_EQ(strip_rows_seen, 0);
  // Shapes: the same count rule.
  scene.body.sheet.holes.clear();
  bapd::Shape disc;
  disc.kind = bapd::Shape::Kind::circle, disc.op = bapd::Shape::Op::subtract, disc.cx = 0.08, disc.cy = 0.0, disc.a = disc.b = 0.0105;
  scene.body.sheet.shapes.push_back(disc);
  EXPECT_EQ(bapd::ScenePointEstimate(scene), (PetscInt)bapd::make_lattice(scene.body.sheet).size());

  // Selection: an outside top grip of 6 rows holds the 6 x 80 points above the sheet
  // (the sheet's x-extent: no side grips here); an inside one the sheet's own rows.
  Scene plate = Plate();
  plate.body.sheet.grip_rows.top = plate.body.sheet.grip_rows.bottom = 6;
  const Share share = TakeShare(bapd::make_lattice(plate.body.sheet));
  LoadSet     set;
  set.placement = bapd::GripPlacement::outside;
  set.layers    = 6;
  set.region    = LoadSet::Region::top;
  EXPECT_EQ(GlobalCount(plate, set, share), 6 * 80);
  set.layers = 4; // a shallower set on the same edge: the 4 rows next to the sheet
  EXPECT_EQ(GlobalCount(plate, set, share), 4 * 80);
  set.region = LoadSet::Region::bottom;
  EXPECT_EQ(GlobalCount(plate, set, share), 4 * 80);
  set.placement = bapd::GripPlacement::inside;
  set.layers    = 1;
  EXPECT_EQ(GlobalCount(plate, set, share), 80); // inside: 0 < y < dx, not the outside grip's rows
}

// -load_grip_field affine (the default outside): every held y of the top and bottom
// grips is the affine continuation of the free region's mean stretch, and x is what
// the set says. Pure shear (top scale 1, bottom fixed): u_y = (lambda - 1) y; the
// plate (scales +-1/2): u_y = (lambda - 1) (y - H/2). Tolerance: a few ulps of u.
TEST(GripField, AffineGripsContinueTheMeanStretch)
{
  for (const double bottom_scale : {0.0, -0.5}) {
    Scene scene = Plate();
    scene.body.sheet.grip_rows.top = scene.body.sheet.grip_rows.bottom = 6;
    scene.loading.reference_length = scene.body.sheet.height;
    scene.loading.schedule         = RampHoldRamp();
    scene.loading.grip_field       = bapd::GripField::affine;
    LoadSet top, bottom;
    top.name = "top", bottom.name = "bottom";
    top.region = LoadSet::Region::top, bottom.region = LoadSet::Region::bottom;
    top.placement = bottom.placement = bapd::GripPlacement::outside;
    top.layers = bottom.layers = 6;
    top.x = bottom.x = bapd::ComponentLoad::fixed;
    top.y = bapd::ComponentLoad::stretch, top.y_scale = 1.0 + bottom_scale;
    bottom.y = bottom_scale == 0 ? bapd::ComponentLoad::fixed : bapd::ComponentLoad::stretch, bottom.y_scale = bottom_scale;
    scene.loading.sets = {top, bottom};
    bapd::Layout layout;
    layout.cloud   = bapd::make_lattice(scene.body.sheet);
    layout.n_owned = static_cast<PetscInt>(layout.cloud.size());
    bapd::Loading loading;
    ASSERT_EQ(loading.Setup(PETSC_COMM_SELF, scene.loading, scene.time_stepping.end_time, bapd::BodyExtentOf(scene), layout), 0);
    const double        t = 2.5, lambda = scene.loading.schedule.stretch_at(t), y_centre = -bottom_scale * scene.body.sheet.height;
    std::vector<double> u(2 * layout.cloud.size(), 7.0), v(u.size(), 7.0);
    loading.Apply(t, u.data(), v.data());
    std::size_t held = 0;
    for (std::size_t i = 0; i < layout.cloud.size(); ++i) {
      const double y = layout.cloud.x[2 * i + 1];
      if (y > 0 && y < scene.body.sheet.height) { // free: untouched
        EXPECT_EQ(u[2 * i + 1], 7.0);
        continue;
      }
      ++held;
      EXPECT_EQ(u[2 * i], 0.0);
      EXPECT_NEAR(u[2 * i + 1], (lambda - 1) * (y - y_centre), 1e-15);
      EXPECT_NEAR(v[2 * i + 1], scene.loading.schedule.rate_at(t) * (y - y_centre), 1e-15);
    }
    EXPECT_EQ(held, 2u * 6 * 80);
  }
}

} // namespace
