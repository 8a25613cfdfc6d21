// 3D scenes (scene_body.cpp, scene_loading.cpp, scene_probes.cpp,
// scene_selection.cpp, loading.cpp, relaxation.cpp at D = 3): a 3D body given by options
// is read and checked (its points counted, its extent found, none of them held); its
// load sets, grips and probes pick exactly the points a brute-force count over the lattice indices says; the
// grips hold D = 3 dofs a point and their reactions sum 3 components; each bad 3D option
// is refused with its own message; the material section in 3D (the law's 3D form, the
// 2D-only options refused, the bond-only form's default correction); the relaxation's damping and the kinetic energy run over 3 dofs a point.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/operators/loading.hpp"
#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/operators/relaxation.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/parallel/distributed_body.hpp"
#include "scene_reading.hpp"

namespace {

using bapd::LoadSet;
using bapd::Scene;
using Options = std::vector<std::pair<std::string, std::string>>;

constexpr double kDx = 1e-3;
// The valid scene: a 10 x 8 x 6 mm box (10 x 8 x 6 cells of 1 mm) less a sphere of
// radius 1.6 mm at (5, 4, 3) mm, a planar notch, grips on the x- and x+ faces.
constexpr double kCentre[3] = {5e-3, 4e-3, 3e-3}, kRadius = 1.6e-3;

Options Block()
{
  return {{"-body_dimension", "3"},
          {"-body_dx", "0.001"},
          {"-body_shapes", "block,hole,crack"},
          {"-body_block_type", "box"},
          {"-body_block_box", "0,0,0,0.01,0.008,0.006"},
          {"-body_hole_type", "sphere"},
          {"-body_hole_centre", "0.005,0.004,0.003"},
          {"-body_hole_radius", "0.0016"},
          {"-body_crack_type", "notch"},
          {"-body_crack_points", "0.001,0.004,-0.001,0.0026,0.004,-0.001,0.0026,0.004,0.007,0.001,0.004,0.007"},
          {"-load_sets", "left,right"},
          {"-load_left_region", "left"},
          {"-load_left_x", "fixed"},
          {"-load_left_y", "fixed"},
          {"-load_left_z", "fixed"},
          {"-load_right_region", "x+"},
          {"-load_right_layers", "2"},
          {"-load_right_x", "stretch"},
          {"-load_right_z", "fixed"},
          {"-load_schedule", "0,1,1,1.1"},
          {"-probes", "p"},
          {"-probe_p_at", "0.0091,0.0013,0.0049"}};
}

Options With(Options o, const Options &changes)
{
  for (const auto &[name, value] : changes) {
    bool found = false;
    for (auto &[n, v] : o)
      if (n == name) v = value, found = true;
    if (!found) o.emplace_back(name, value);
  }
  return o;
}
Options Without(Options o, const std::string &name)
{
  Options out;
  for (const auto &e : o)
    if (e.first != name) out.push_back(e);
  return out;
}

class Scene3D : public bapd::test::SceneReading<Options> {};

// Whether lattice cell (i, j, k) of the valid scene is material, from the indices alone.
bool Material(int i, int j, int k)
{
  const double x[3] = {(i + 0.5) * kDx, (j + 0.5) * kDx, (k + 0.5) * kDx};
  double       r2   = 0;
  for (int a = 0; a < 3; ++a) r2 += (x[a] - kCentre[a]) * (x[a] - kCentre[a]);
  return r2 >= kRadius * kRadius; // (a sphere's surface is outside it: material)
}

TEST_F(Scene3D, ReadsTheBodyItsExtentAndItsPointCount)
{
  Scene scene;
  ASSERT_EQ(Read(Block(), &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.body.dimension, 3);
  int64_t count = 0;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 10; ++i) count += Material(i, j, k);
  EXPECT_LT(count, 480); // the sphere removed some
  EXPECT_EQ(scene.body.solid_summary.points, count);
  const double hi[3] = {0.01, 0.008, 0.006};
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(scene.body.solid_summary.lo[r], 0.0, 1e-15);
    EXPECT_NEAR(scene.body.solid_summary.hi[r], hi[r], 1e-15);
  }
  ASSERT_EQ(scene.body.solid.solids.size(), 2u);
  EXPECT_EQ(scene.body.solid.solids[0].op, bapd::nd::Solid::Op::add);      // the first solid starts the body
  EXPECT_EQ(scene.body.solid.solids[1].op, bapd::nd::Solid::Op::subtract); // the next cuts it
  EXPECT_EQ(scene.body.solid.notches.size(), 1u);
  EXPECT_DOUBLE_EQ(scene.loading.reference_length, 0.008); // the extent along y
  ASSERT_EQ(scene.loading.sets.size(), 2u);
  EXPECT_EQ(scene.loading.sets[0].region, LoadSet::Region::left);
  EXPECT_EQ(scene.loading.sets[1].region, LoadSet::Region::right);
  EXPECT_EQ(scene.loading.sets[1].z, bapd::ComponentLoad::fixed);
  // The driver's D (main.cpp builds SimulationD<3> for it); a scene without 3D options is 2D.
  EXPECT_EQ(scene.body.dimension, 3);
  Scene flat;
  EXPECT_EQ(flat.body.dimension, 2);
}

// Sets the peak resident memory (VmHWM) to the current one (/proc/self/clear_refs 5,
// Linux 4.0 and later); false where it cannot.
bool ResetPeak()
{
  std::FILE *f  = std::fopen("/proc/self/clear_refs", "w");
  const bool ok = f && std::fputs("5", f) >= 0;
  return f && std::fclose(f) == 0 && ok;
}

// Reading a lattice body holds none of its points, so that with -partition_type ptscotch
// no rank ever holds the whole body: the valid scene at dx = 0.05 mm (3.8e6 points, 150
// MB as points and more for their pieces) is read, refused by the memory check or not,
// with the peak memory grown by less than 16 MB (the pass over it holds two layers of
// 200 x 160 cells: 0.5 MB).
TEST_F(Scene3D, ReadingALatticeHoldsNoPoints)
{
  ASSERT_TRUE(ResetPeak()) << "/proc/self/clear_refs could not reset the peak memory (VmHWM) that this test measures";
  const double before = bapd::PeakResidentBytes();
  Scene        scene;
  Read(With(Block(), {{"-body_dx", "0.00005"}, {"-load_left_layers", "4"}, {"-load_right_layers", "4"}}), &scene);
  const double grown = bapd::PeakResidentBytes() - before;
  EXPECT_LT(grown, 16e6) << "the peak grew by " << grown / 1e6 << " MB";
}

// The scene's view of a 3D body (SceneText): the lattice, point count and extent, each
// solid and notch by name and type, the faces by axis with their z components, probes
// at (x, y, z); of a 3D cloud: its file and spacing, a block and a box of six numbers.
TEST_F(Scene3D, ViewNamesTheSolidsNotchesFacesAndProbes)
{
  Scene scene;
  ASSERT_EQ(Read(With(Block(), {{"-load_right_x_scale", "0.5"}}), &scene), 0) << bapd::test::UserErrorText();
  const std::string text = bapd::SceneText(scene);
  const std::string expected[] = {
    bapd::Format("  body      3D, dx 0.001 m: %lld points, cells in [0, 0.01] x [0, 0.008] x [0, 0.006] m, 2 solid(s), 1 notch(es)\n",
                 static_cast<long long>(scene.body.solid_summary.points)),
    "            solid block: add a box, [0, 0.01] x [0, 0.008] x [0, 0.006] m\n",
    "            solid hole: subtract a sphere, centre (0.005, 0.004, 0.003) m, radius 0.0016 m\n",
    "            notch crack: a planar polygon of 4 vertices, (0.001, 0.004, -0.001) (0.0026, 0.004, -0.001) (0.0026, 0.004, 0.007) "
    "(0.001, 0.004, 0.007) m\n",
    "  horizon   delta = 3.015 dx = 0.003015 m\n",
    "  material  gent, 3D: mu ",
    "  load set  left: x- face (left), 1 row(s) inside; x fixed, y fixed, z fixed\n",
    "  load set  right: x+ face (right), 2 row(s) inside; x stretch (scale 0.5), y free, z fixed\n",
    "; u = scale (lambda - 1) 0.008 m; grip field rigid\n",
    "  probe     p at (0.0091, 0.0013, 0.0049) m\n",
  };
  for (const std::string &line : expected) EXPECT_NE(text.find(line), std::string::npos) << "expected '" << line << "' in:\n" << text;
  EXPECT_EQ(text.find("plane_stress"), std::string::npos) << text; // (a 2D formulation means nothing in 3D)

  Scene box;
  ASSERT_EQ(Read(With(Without(Block(), "-body_hole_centre"), {{"-load_left_region", "box"}, {"-load_left_box", "0,0,0,0.002,0.008,0.006"},
                                                              {"-body_hole_type", "cylinder"}, {"-body_hole_axis", "0.005,0.004,0,0.005,0.004,0.006"}}),
                 &box),
            0)
      << bapd::test::UserErrorText();
  const std::string box_text = bapd::SceneText(box);
  for (const std::string &line : std::vector<std::string>{"  load set  left: box [0, 0.002] x [0, 0.008] x [0, 0.006] m; x fixed, y fixed, z fixed\n",
                                 "            solid hole: subtract a cylinder, axis (0.005, 0.004, 0)-(0.005, 0.004, 0.006) m, radius 0.0016 m\n"})
    EXPECT_NE(box_text.find(line), std::string::npos) << "expected '" << line << "' in:\n" << box_text;
}

// Every load set region of a 3D body against a count over the lattice indices.
TEST_F(Scene3D, LoadSetsPickExactlyTheBruteForcePoints)
{
  Scene scene;
  ASSERT_EQ(Read(Block(), &scene), 0) << bapd::test::UserErrorText();
  const bapd::PointCloud points = bapd::nd::make_solid_points(scene.body.solid);
  ASSERT_EQ(static_cast<int64_t>(points.size()), scene.body.solid_summary.points);
  // Index (i, j, k) of each point, from its position.
  std::vector<std::array<int, 3>> index(points.size());
  for (std::size_t p = 0; p < points.size(); ++p)
    for (int r = 0; r < 3; ++r) index[p][r] = static_cast<int>(std::lround(points.x[3 * p + r] / kDx - 0.5));
  struct Case {
    const char *name;
    LoadSet::Region region;
    int             layers;
    std::vector<double> box;
    bool (*expected)(const std::array<int, 3> &);
  };
  const Case cases[] = {
    {"x-", LoadSet::Region::left, 1, {}, [](const std::array<int, 3> &c) { return c[0] == 0; }},
    {"x+", LoadSet::Region::right, 2, {}, [](const std::array<int, 3> &c) { return c[0] >= 8; }},
    {"y-", LoadSet::Region::bottom, 3, {}, [](const std::array<int, 3> &c) { return c[1] <= 2; }},
    {"y+", LoadSet::Region::top, 1, {}, [](const std::array<int, 3> &c) { return c[1] == 7; }},
    {"z-", LoadSet::Region::back, 2, {}, [](const std::array<int, 3> &c) { return c[2] <= 1; }},
    {"z+", LoadSet::Region::front, 1, {}, [](const std::array<int, 3> &c) { return c[2] == 5; }},
    // centres 2.5..5.5 mm in x, 1.5..3.5 in y, 3.5..5.5 in z: i 2..5, j 1..3, k 3..5
    {"box", LoadSet::Region::box, 1, {0.0024, 0.0011, 0.0031, 0.0058, 0.0039, 0.0061},
     [](const std::array<int, 3> &c) { return c[0] >= 2 && c[0] <= 5 && c[1] >= 1 && c[1] <= 3 && c[2] >= 3; }},
  };
  for (const Case &c : cases) {
    LoadSet set;
    set.region = c.region;
    set.layers = c.layers;
    std::copy(c.box.begin(), c.box.end(), set.box);
    std::vector<PetscInt> selected;
    ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), set, points.x.data(), (PetscInt)points.size(), &selected), 0);
    std::vector<PetscInt> expected;
    for (std::size_t p = 0; p < points.size(); ++p)
      if (c.expected(index[p])) expected.push_back((PetscInt)p);
    EXPECT_GT(expected.size(), 0u) << c.name;
    EXPECT_EQ(selected, expected) << c.name;
  }
}

// A probe reads the point nearest to (x, y, z) (ties to the lowest natural id), on any
// number of ranks: each rank passes every size-th point.
TEST_F(Scene3D, ProbeFindsTheNearestPointInThreeDimensions)
{
  Scene scene;
  ASSERT_EQ(Read(Block(), &scene), 0) << bapd::test::UserErrorText();
  const bapd::PointCloud points = bapd::nd::make_solid_points(scene.body.solid);
  PetscMPIInt            rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  std::vector<double>  x;
  std::vector<int64_t> id;
  for (std::size_t p = rank; p < points.size(); p += size) {
    x.insert(x.end(), &points.x[3 * p], &points.x[3 * p + 3]);
    id.push_back(points.natural_id[p]);
  }
  const bapd::Probe &probe = scene.loading.probes.at(0);
  EXPECT_DOUBLE_EQ(probe.z, 0.0049);
  // By brute force: (9.1, 1.3, 4.9) mm is nearest to the centre (9.5, 1.5, 4.5) mm.
  int64_t best = -1;
  double  best_d2 = 1e300;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double at[3] = {probe.x, probe.y, probe.z};
    double       d2    = 0;
    for (int r = 0; r < 3; ++r) d2 += (points.x[3 * p + r] - at[r]) * (points.x[3 * p + r] - at[r]);
    if (d2 < best_d2) best_d2 = d2, best = points.natural_id[p];
  }
  bapd::ProbeLocation at;
  ASSERT_EQ(bapd::ProbeLocate<3>(PETSC_COMM_WORLD, probe, x.data(), id.data(), (PetscInt)id.size(), &at), 0);
  EXPECT_EQ(at.natural_id, best);
  EXPECT_NEAR(at.distance, std::sqrt(0.4 * 0.4 + 0.2 * 0.2 + 0.4 * 0.4) * 1e-3, 1e-15);
  EXPECT_NEAR(points.x[3 * static_cast<std::size_t>(best) + 2], 4.5e-3, 1e-15); // (z decides: the 2D distance would tie over z)
}

// Loading at D = 3: the held dofs are 3 p + c, and a set's reaction sums 3 components.
TEST_F(Scene3D, GripsHoldThreeDofsAPointAndReactInThree)
{
  Scene scene;
  ASSERT_EQ(Read(Block(), &scene), 0) << bapd::test::UserErrorText();
  // Every rank holds the whole body here, so the loading works on PETSC_COMM_SELF.
  bapd::Layout layout;
  layout.cloud   = bapd::nd::make_solid_points(scene.body.solid);
  layout.n_owned = (PetscInt)layout.cloud.size();
  bapd::Loading loading;
  ASSERT_EQ(loading.Setup(PETSC_COMM_SELF, scene.loading, scene.time_stepping.end_time, bapd::BodyExtentOf(scene), layout), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(loading.dimension(), 3);
  // left: x, y, z of the 6 x 8 = 48 points of i = 0 (no cell of i = 0 is in the sphere);
  // right: x and z of the 2 x 48 points of i = 8, 9.
  std::vector<PetscInt> expected;
  for (std::size_t p = 0; p < layout.cloud.size(); ++p) {
    const int i = static_cast<int>(std::lround(layout.cloud.x[3 * p] / kDx - 0.5));
    if (i == 0)
      for (int c = 0; c < 3; ++c) expected.push_back(3 * (PetscInt)p + c);
    if (i >= 8)
      for (int c : {0, 2}) expected.push_back(3 * (PetscInt)p + c);
  }
  std::vector<PetscInt> held = loading.held_dofs();
  std::sort(held.begin(), held.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(expected.size(), 48u * 3 + 96u * 2);
  EXPECT_EQ(held, expected);
  // u at stretch 1.1 (t = 1): the right grip's x moves by 0.1 L, its z stays.
  std::vector<double> u(3 * layout.cloud.size(), -1.0);
  loading.Apply(1.0, u.data(), nullptr);
  for (const bapd::ConstrainedDof &d : loading.constrained())
    EXPECT_NEAR(u[d.dof], d.dof % 3 == 0 && d.kind == bapd::ComponentLoad::stretch ? 0.1 * 0.008 : 0.0, 1e-18) << d.dof;
  // Reactions: -sum f V per component, with f = (1, 2, 3) N/m^3 at every point.
  std::vector<double> f(3 * layout.cloud.size());
  for (std::size_t p = 0; p < layout.cloud.size(); ++p)
    for (int c = 0; c < 3; ++c) f[3 * p + c] = c + 1.0;
  std::vector<double> reaction(3 * scene.loading.sets.size(), 0.0);
  ASSERT_EQ(loading.Reactions(f.data(), reaction.data()), 0);
  const double V = kDx * kDx * kDx;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(reaction[c], -(c + 1.0) * 48 * V, 1e-12 * 48 * V) << "left, component " << c;
    EXPECT_NEAR(reaction[3 + c], -(c + 1.0) * 96 * V, 1e-12 * 96 * V) << "right, component " << c;
  }
}

// -load_grip_field affine on a 3D body (Loading::SetAffineLevers): the y dofs of the
// grips on the faces y- and y+ (`layers` rows inside) move on the affine continuation
// of the free region's mean stretch, u_y = u_rigid + (lambda - 1) (L / L_free)
// (y - y_inner) with y_inner = lo + layers dx and hi - layers dx; x and z keep what the
// sets say. Two box grips get their grip lines half a spacing (cbrt V / 2) beyond their
// innermost points. `auto` leaves a 3D body's grips rigid (they are its own points).
TEST_F(Scene3D, AffineGripFieldContinuesTheStretchIntoFaceAndBoxGrips)
{
  Options pulled_in_y;
  for (const auto &e : Block())
    if (e.first.rfind("-load_left", 0) != 0 && e.first.rfind("-load_right", 0) != 0) pulled_in_y.push_back(e);
  pulled_in_y = With(pulled_in_y, {{"-load_sets", "bottom,top"},
                                   {"-load_bottom_region", "y-"},
                                   {"-load_bottom_layers", "2"},
                                   {"-load_bottom_x", "fixed"},
                                   {"-load_bottom_y", "fixed"},
                                   {"-load_bottom_z", "fixed"},
                                   {"-load_top_region", "y+"},
                                   {"-load_top_layers", "3"},
                                   {"-load_top_x", "fixed"},
                                   {"-load_top_y", "stretch"},
                                   {"-load_top_z", "fixed"}});
  const Options boxes = With(pulled_in_y, {{"-load_bottom_region", "box"},
                                           {"-load_bottom_box", "0,0,0,0.01,0.002,0.006"},
                                           {"-load_top_region", "box"},
                                           {"-load_top_box", "0,0.005,0,0.01,0.008,0.006"}});
  const double L = 8e-3, y_bottom = 2e-3, y_top = 5e-3, gradient = L / (y_top - y_bottom); // (the same lines for both)
  const Options box_grips = Without(Without(boxes, "-load_bottom_layers"), "-load_top_layers"); // (a box has no layers)
  for (const auto &[options, field] : {std::pair{pulled_in_y, "affine"}, {pulled_in_y, "auto"}, {box_grips, "affine"}}) {
    Scene scene;
    ASSERT_EQ(Read(With(options, {{"-load_grip_field", field}}), &scene), 0) << bapd::test::UserErrorText();
    const bool affine = std::string(field) == "affine";
    EXPECT_EQ(scene.loading.grip_field, affine ? bapd::GripField::affine : bapd::GripField::rigid) << field;
    bapd::Layout layout;
    layout.cloud   = bapd::nd::make_solid_points(scene.body.solid);
    layout.n_owned = (PetscInt)layout.cloud.size();
    bapd::Loading loading;
    ASSERT_EQ(loading.Setup(PETSC_COMM_SELF, scene.loading, scene.time_stepping.end_time, bapd::BodyExtentOf(scene), layout), 0) << bapd::test::UserErrorText();
    std::vector<double> u(3 * layout.cloud.size(), -1.0);
    loading.Apply(1.0, u.data(), nullptr); // stretch 1.1
    std::size_t top = 0, bottom = 0;
    for (const bapd::ConstrainedDof &d : loading.constrained()) {
      const double y = layout.cloud.x[3 * (d.dof / 3) + 1];
      double       expected = 0.0;
      if (d.dof % 3 == 1) {
        const bool is_top = y > y_top;
        top += is_top, bottom += !is_top;
        expected = (is_top ? 0.1 * L : 0.0) + (affine ? 0.1 * gradient * (y - (is_top ? y_top : y_bottom)) : 0.0);
      }
      EXPECT_NEAR(u[d.dof], expected, 1e-15) << field << ", dof " << d.dof << " at y = " << y;
    }
    std::size_t material_top = 0, material_bottom = 0; // the lattice cells j = 5..7 and 0..1 outside the sphere
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 8; ++j)
        for (int k = 0; k < 6; ++k) {
          if (!Material(i, j, k)) continue;
          material_top += j >= 5;
          material_bottom += j <= 1;
        }
    EXPECT_EQ(top, material_top) << field << ": the top grip's points";
    EXPECT_EQ(bottom, material_bottom) << field << ": the bottom grip's points";
  }
}

// Each mistake in a 3D scene is refused with its own message (option and fix).
TEST_F(Scene3D, EachBadOptionGetsItsMessage)
{
  const std::vector<std::pair<Options, std::string>> cases = {
    {With(Block(), {{"-body_dimension", "4"}}), "-body_dimension 4: give 2 (a plane sheet) or 3"},
    {With(Block(), {{"-body_dimension", "2"}}), "-body_block_type box is a shape of a 3D body, but -body_dimension is 2"},
    {With(Block(), {{"-body_width", "0.01"}}), "-body_width is an option of the 2D sheet, and this body is 3D"},
    {With(Block(), {{"-body_holes", "0.005,0.004,0.001"}}), "-body_holes is an option of the 2D sheet"},
    {With(Block(), {{"-body_notches", "0,0,0.001,0.001"}}), "a notch is a planar polygon shape: -body_NAME_type notch"},
    {Without(Block(), "-body_dx"), "-body_dx is required: give the lattice spacing of the 3D body"},
    {With(Block(), {{"-body_block_box", "0,0,0.01,0.008"}}), "-body_block_box holds 4 numbers: a 3D box takes six"},
    {With(Block(), {{"-body_block_box", "0,0,0,0.01,0.008,0"}}), "give xmin,ymin,zmin,xmax,ymax,zmax with each max > min"},
    {With(Block(), {{"-body_hole_radius", "-0.001"}}), "-body_hole (sphere): "},
    {With(Block(), {{"-body_hole_type", "cylinder"}}), "-body_hole_centre is not a parameter of a 3D cylinder"},
    {With(Without(Block(), "-body_hole_centre"), {{"-body_hole_type", "cylinder"}}), "-body_hole_axis holds 0 numbers"},
    {With(Block(), {{"-body_hole_type", "circle"}}), "(rectangle, circle, ellipse and polygon are the 2D sheet's shapes)"},
    {With(Block(), {{"-body_crack_op", "subtract"}}), "-body_crack_op is not a parameter of a 3D notch"},
    {With(Block(), {{"-body_crack_points", "0.001,0.004,0,0.002,0.004,0,0.002,0.005,0.001,0.001,0.004,0.003"}}),
     "-body_crack_points (notch 'crack'): "},
    {With(Block(), {{"-body_crack_points", "0.001,0.004,0,0.002,0.004"}}), "at least three vertices x0,y0,z0"},
    {With(Block(), {{"-body_shapes", "block,far"}, {"-body_far_type", "box"}, {"-body_far_op", "add"}, {"-body_far_box", "0.02,0,0,0.03,0.008,0.006"}}),
     "piece"},
    {With(Block(), {{"-body_m_type", "mesh"}, {"-body_shapes", "block,m"}, {"-body_m_file", "no_such_volume.msh"}}), "-body_m_file: "},
    {With(Block(), {{"-load_left_region", "polygon"}}), "-load_left_region polygon is a 2D region"},
    {With(Block(), {{"-load_left_region", "box"}, {"-load_left_box", "0,0,0.001,0.001"}}), "a 3D box takes exactly six"},
    {With(Block(), {{"-load_left_placement", "outside"}}), "grips outside the specimen are 2D only"},
    {With(Block(), {{"-load_grip_placement", "outside"}}), "-load_grip_placement outside: a 3D body's load sets hold its own points"},
    {With(Block(), {{"-load_grip_field", "affine"}}), "-load_grip_field affine continues the stretch between a top and a bottom grip"},
    {With(Block(), {{"-load_right_layers", "10"}}), "-load_right_layers 10 is 0.01 m deep, the whole body along x"},
    {With(Block(), {{"-load_left_region", "block"}, {"-load_left_block", "1"}}), "this body is a lattice: choose a face or a box"},
    {With(Block(), {{"-probe_p_at", "0.001,0.002"}}), "-probe_p_at holds 2 numbers: a probe of a 3D body takes exactly three"},
    {With(Block(), {{"-probe_p_at", "0.005,0.004,0.003"}}), "lies where the body's solids leave no material"},
    {With(Block(), {{"-probe_p_at", "0.005,0.004,0.009"}}), "lies outside the body [0, 0.01] x [0, 0.008] x [0, 0.006] m"},
  };
  for (const auto &[options, text] : cases) {
    const std::string message = Rejection(options);
    EXPECT_NE(message.find(text), std::string::npos) << "expected '" << text << "' in: " << message;
  }
}

// The material section of a 3D body (scene_material.cpp): the 2D
// reductions are refused, the patch correction is allowed for the bond-only form only
// (auto: off on the lattice, as in 2D; a cloud's auto below), every law of the registry has a
// 3D form (Ogden its own, Ogden3D), and the bond-only form is tensor-corrected by default (uncorrected it is
// 15 % soft in 3D, docs/architecture.md "The source tree").
TEST_F(Scene3D, MaterialOptionsOfASolidBody)
{
  Scene scene;
  ASSERT_EQ(Read(Block(), &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.force_form, bapd::ForceForm::energy_consistent);
  EXPECT_EQ(scene.material.stress_correction, bapd::StressCorrection::none);
  EXPECT_EQ(scene.material.patch_correction, bapd::PatchCorrection::off);
  Scene bond_only;
  ASSERT_EQ(Read(With(Block(), {{"-force_form", "bond_only"}}), &bond_only), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(bond_only.material.stress_correction, bapd::StressCorrection::tensor);
  EXPECT_EQ(bond_only.material.patch_correction, bapd::PatchCorrection::off); // (auto: off on the lattice, which passes as it is)
  for (const char *patch : {"on", "virial"}) { // given, it runs in 3D (patch_correction.hpp at D = 3)
    Scene corrected;
    ASSERT_EQ(Read(With(Block(), {{"-force_form", "bond_only"}, {"-force_patch_correction", patch}}), &corrected), 0)
        << patch << ": " << bapd::test::UserErrorText();
    EXPECT_EQ(corrected.material.patch_correction, patch[0] == 'o' ? bapd::PatchCorrection::lambda : bapd::PatchCorrection::virial);
  }
  Scene paper;
  ASSERT_EQ(Read(With(Block(), {{"-force_form", "bond_only"}, {"-force_stress_correction", "none"}}), &paper), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(paper.material.stress_correction, bapd::StressCorrection::none); // the paper's force stays reachable
  for (const char *law : {"neo_hookean", "mooney_rivlin", "yeoh", "arruda_boyce", "ogden"}) {
    Scene other;
    EXPECT_EQ(Read(With(Block(), {{"-material_model", law}}), &other), 0) << law << ": " << bapd::test::UserErrorText();
  }
  const std::vector<std::pair<Options, std::string>> cases = {
    {With(Block(), {{"-material_formulation", "plane_strain"}}), "-material_formulation plane_strain is a 2D reduction"},
    {With(Block(), {{"-material_formulation", "plane_stress"}}), "-material_formulation plane_stress is a 2D reduction"},
    {With(Block(), {{"-force_patch_correction", "virial"}}), "-force_patch_correction virial corrects the bond-only force only"},
  };
  for (const auto &[options, text] : cases) {
    const std::string message = Rejection(options);
    EXPECT_NE(message.find(text), std::string::npos) << "expected '" << text << "' in: " << message;
  }
}

TEST_F(Scene3D, TwoDimensionalSheetsRefuseTheThirdComponentAndTheZFaces)
{
  const Options sheet = {{"-body_width", "0.01"}, {"-body_height", "0.01"}, {"-body_thickness", "0.001"}, {"-body_dx", "0.0005"},
                         {"-load_sets", "top"},   {"-load_top_region", "top"}, {"-load_top_y", "fixed"},
                         {"-end_time", "1"}};
  EXPECT_NE(Rejection(With(sheet, {{"-load_top_z", "fixed"}})).find("-load_top_z is set, but this body is a 2D sheet"), std::string::npos)
      << bapd::test::UserErrorText();
  EXPECT_NE(Rejection(With(sheet, {{"-load_top_region", "front"}})).find("is a face of a 3D body (z), and this body is a 2D sheet"),
            std::string::npos)
      << bapd::test::UserErrorText();
  Scene scene;
  ASSERT_EQ(Read(sheet, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.body.dimension, 2);
}

// A 3D cloud (text, x y z volume block_id): solids cut it; block ids make load sets and probes.
TEST_F(Scene3D, ACloudIsClippedByItsSolidsAndItsBlocksAreLoadSets)
{
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  char name[] = "/tmp/bapd_scene3d_cloud_XXXXXX";
  if (rank == 0) {
    const int fd = mkstemp(name);
    ASSERT_GE(fd, 0);
    FILE *f = fdopen(fd, "w");
    std::fprintf(f, "x y z volume block_id\n");
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          std::fprintf(f, "%.17g %.17g %.17g 1e-9 %d\n", (i + 0.5) * kDx, (j + 0.5) * kDx, (k + 0.5) * kDx,
                       i == 3 && j == 3 && k == 3 ? 7 : i == 0 ? 2 : 1);
    std::fclose(f);
  }
  MPI_Bcast(name, sizeof name, MPI_CHAR, 0, PETSC_COMM_WORLD);
  const Options cloud = {{"-body_dimension", "3"},       {"-body_cloud", name},           {"-body_shapes", "cut"},
                         {"-body_cut_type", "box"},      {"-body_cut_op", "subtract"},    {"-body_cut_box", "0.002,0.002,0,0.004,0.004,0.001"},
                         {"-load_sets", "b"},            {"-load_b_region", "block"},     {"-load_b_block", "2"},
                         {"-load_b_x", "fixed"},         {"-probes", "corner"},           {"-probe_corner_block", "7"},
                         {"-end_time", "1"}};
  Scene scene;
  ASSERT_EQ(Read(cloud, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.body.solid_summary.points, 64 - 4); // the cut took i, j in {2, 3}, k = 0
  EXPECT_EQ(scene.loading.sets[0].block_points.size(), 3u * 16);
  EXPECT_NEAR(scene.loading.probes[0].z, 3.5e-3, 1e-18);
  EXPECT_EQ(scene.material.patch_correction, bapd::PatchCorrection::off); // auto: the energy-consistent form is not corrected
  Scene bond_only;
  ASSERT_EQ(Read(With(cloud, {{"-force_form", "bond_only"}}), &bond_only), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(bond_only.material.patch_correction, bapd::PatchCorrection::virial); // auto: virial for given points, as in 2D
  const std::string text = bapd::SceneText(scene);
  // (the cells' extent: x -+ cbrt(1e-9) / 2, to round-off)
  for (const std::string &line : std::vector<std::string>{
         "  body      3D: 60 points of " + std::string(name) + " (spacing cbrt(V), the smallest 0.001 m), cells in [",
         "0.004] m, 1 solid(s) cutting them, 0 notch(es)\n", std::string("            solid cut: subtract a box, [0.002, 0.004] x [0.002, 0.004] x [0, 0.001] m\n"),
        std::string("  horizon   delta_i = 3.015 h_i, h_i = cbrt(V_i) (at least 0.003015 m); a bond where either reaches\n"),
        std::string("  load set  b: block 2 of the cloud (16 points); x fixed, y free, z free\n"),
        std::string("  probe     corner at (0.0035, 0.0035, 0.0035) m\n")})
    EXPECT_NE(text.find(line), std::string::npos) << "expected '" << line << "' in:\n" << text;
  EXPECT_NE(Rejection(With(cloud, {{"-body_cut_op", "add"}})).find("can only cut them"), std::string::npos) << bapd::test::UserErrorText();
  EXPECT_NE(Rejection(With(cloud, {{"-body_dx", "0.001"}})).find("-body_dx is the lattice spacing, but -body_cloud"), std::string::npos);
  if (rank == 0) std::remove(name);
}

// Adaptive relaxation at D = 3: omega^2 = -sum V du.da / sum V |du|^2 over the three free
// dofs of each point (held ones left out), and the kinetic energy 1/2 m v.v.
TEST(Relaxation3D, DampingAndKineticEnergyRunOverThreeDofsAPoint)
{
  const std::size_t   n = 4;
  const double        volume[n] = {1.0, 2.0, 0.5, 1.5};
  std::vector<double> u0(3 * n), u1(3 * n), a0(3 * n), a1(3 * n);
  for (std::size_t k = 0; k < 3 * n; ++k) {
    u0[k] = 0.01 * static_cast<double>(k % 5) - 0.02;
    u1[k] = u0[k] + 1e-3 * (1.0 + static_cast<double>(k % 3)); // every component moves, z most
    a0[k] = 0.3 * static_cast<double>(k % 7);
    a1[k] = a0[k] - (k % 3 == 2 ? 900.0 : 100.0) * (u1[k] - u0[k]); // z is stiffer
  }
  const std::vector<PetscInt> held = {3 * 1 + 2}; // point 1's z
  bapd::AdaptiveRelaxation<3> relax;
  relax.Setup(bapd::RelaxationKind::adaptive, n, volume, held, 0.0, 1e-6);
  relax.Record(u0.data(), a0.data());
  relax.Record(u1.data(), a1.data());
  double c = 0;
  ASSERT_EQ(relax.Damping(PETSC_COMM_SELF, &c), 0);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * i + d;
      if (k == 3 * 1 + 2) continue;
      num -= volume[i] * (u1[k] - u0[k]) * (a1[k] - a0[k]);
      den += volume[i] * (u1[k] - u0[k]) * (u1[k] - u0[k]);
    }
  EXPECT_NEAR(c, 2.0 * std::sqrt(num / den), 1e-12 * c);
  EXPECT_GT(c, 2.0 * std::sqrt(100.0) * 1.05); // the stiff z dofs count
  // Kinetic energy: 1/2 m v.v with all three components.
  const double v[3] = {0.3, -0.4, 1.2}, m = 2.5;
  EXPECT_NEAR(bapd::PointKineticEnergy<3>(m, v), 0.5 * 2.5 * (0.09 + 0.16 + 1.44), 1e-15);
  EXPECT_EQ(bapd::PointKineticEnergy<2>(m, v), 0.5 * m * (v[0] * v[0] + v[1] * v[1])); // the history's 2D arithmetic, bit for bit
}

} // namespace
