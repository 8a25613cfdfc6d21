// Gmsh physical groups of a 3D body (gmsh_volume3d.hpp, nd::ElementRegion; load sets and
// probes by group, scene_loading.cpp, scene_probes.cpp): on a box meshed by Gmsh with its
// faces named, a grip on a named face holds exactly the points a box over the same layers
// holds (a face on the cell faces: points (j + 1/2) dx from it, depth n dx = n layers), a
// physical volume holds every point, a physical point places a probe; a missing group is
// refused naming it and the groups the file has.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene.hpp"

namespace bapd {
namespace {

constexpr double  kMm  = 1e-3;
const std::string kGeo = std::string(BAPD_TEST_SOURCE_DIR) + "/data/geometry/box_faces.geo";

TEST(GmshGroups3D, ReadsFacesVolumesCurvesAndPoints)
{
  nd::ElementRegion left, body, edge, corner;
  ASSERT_EQ(ReadGmshGroup3D(kGeo, "left", kMm, &left), "");
  EXPECT_EQ(left.dim, 2);
  ASSERT_GT(left.size(), 1u);
  for (std::size_t k = 0; k < left.triangles.size(); k += 3) EXPECT_EQ(left.triangles[k], 0.0); // every corner on x = 0
  ASSERT_EQ(ReadGmshGroup3D(kGeo, "body", 0, &body), "");
  EXPECT_EQ(body.dim, 3);
  EXPECT_NEAR(nd::solid_volume(nd::make_mesh(body.tetrahedra)), 72 * kMm * kMm * kMm, 1e-12 * 72 * kMm * kMm * kMm);
  ASSERT_EQ(ReadGmshGroup3D(kGeo, "edge", kMm, &edge), "");
  EXPECT_EQ(edge.dim, 1);
  ASSERT_EQ(ReadGmshGroup3D(kGeo, "corner", 0, &corner), "");
  ASSERT_EQ(corner.segments.size(), 6u);
  EXPECT_EQ(corner.segments[0], 6 * kMm);
  EXPECT_EQ(corner.segments[1], 4 * kMm);
  EXPECT_EQ(corner.segments[2], 0.0);

  // The distance rule itself, against points placed by hand: a face holds what is closer
  // than the depth (its edges and corners included), a segment likewise.
  const double p_in[3] = {0.9 * kMm, 2 * kMm, 1.5 * kMm}, p_out[3] = {1.1 * kMm, 2 * kMm, 1.5 * kMm};
  const double p_corner_in[3] = {-0.5 * kMm, -0.5 * kMm, -0.5 * kMm}, p_corner_out[3] = {-0.6 * kMm, -0.6 * kMm, -0.6 * kMm};
  EXPECT_TRUE(nd::region_contains(left, p_in));
  EXPECT_FALSE(nd::region_contains(left, p_out));
  EXPECT_TRUE(nd::region_contains(left, p_corner_in));   // sqrt(3) x 0.5 mm from the corner (0, 0, 0)
  EXPECT_FALSE(nd::region_contains(left, p_corner_out)); // sqrt(3) x 0.6 mm > 1 mm
  const double on_edge[3] = {0.5 * kMm, 2 * kMm, 0.5 * kMm}, off_edge[3] = {0.5 * kMm, 2 * kMm, 0.9 * kMm};
  EXPECT_TRUE(nd::region_contains(edge, on_edge));   // the edge x = 0, z = 0: 0.71 mm away
  EXPECT_FALSE(nd::region_contains(edge, off_edge)); // 1.03 mm away
  const double a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {0, 2, 0}, q[3] = {0.5, 0.5, 3}, r[3] = {3, 3, 0};
  EXPECT_DOUBLE_EQ(nd::point_triangle_distance2(q, a, b, c), 9.0); // above the inside
  EXPECT_DOUBLE_EQ(nd::point_triangle_distance2(r, a, b, c), 8.0); // beyond the edge bc: its point (1, 1, 0)
}

using Options = std::vector<std::pair<std::string, std::string>>;

class Groups3D : public ::testing::Test {
protected:
  void SetUp() override { ASSERT_EQ(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), 0); }
  void TearDown() override
  {
    PetscPopErrorHandler();
    PetscOptionsClear(nullptr);
  }
  PetscErrorCode Read(const Options &options, Scene *scene)
  {
    PetscOptionsClear(nullptr);
    std::string line;
    for (const auto &[name, value] : options) line += name + " " + value + " ";
    if (PetscOptionsInsertString(nullptr, line.c_str())) return PETSC_ERR_LIB;
    return SceneFromOptions(PETSC_COMM_WORLD, scene);
  }
  static std::string ErrorText()
  {
    const char *generic  = nullptr;
    char       *specific = nullptr;
    PetscErrorMessage(PETSC_ERR_USER, &generic, &specific);
    return specific ? specific : "";
  }
  // The box meshed by Gmsh, on a 1 mm lattice; sets by group and by box of the same layers.
  static Options Box(const Options &sets)
  {
    Options o = {{"-body_dimension", "3"}, {"-body_dx", "0.001"},     {"-body_shapes", "part"}, {"-body_part_type", "mesh"},
                 {"-body_part_file", kGeo}, {"-load_schedule", "0,1,1,1.1"}};
    o.insert(o.end(), sets.begin(), sets.end());
    return o;
  }
};

std::vector<PetscInt> Select(const Scene &scene, const LoadSet &set, const PointCloud &points)
{
  std::vector<PetscInt> selected;
  EXPECT_EQ(LoadSetSelect(BodyExtentOf(scene), set, points.x.data(), static_cast<PetscInt>(points.size()), &selected), 0);
  return selected;
}

TEST_F(Groups3D, AGripOnANamedFaceHoldsThePointsOfABoxOverTheSameLayers)
{
  Scene scene;
  ASSERT_EQ(Read(Box({{"-load_sets", "gl,bl,gt,ft,all,near_edge"},
                      {"-load_gl_region", "group"},   {"-load_gl_group", "left"},   {"-load_gl_layers", "2"}, {"-load_gl_x", "fixed"},
                      {"-load_bl_region", "box"},     {"-load_bl_box", "0,0,0,0.002,0.004,0.003"},            {"-load_bl_x", "fixed"},
                      {"-load_gt_region", "group"},   {"-load_gt_group", "top"},    {"-load_gt_depth", "0.001"}, {"-load_gt_y", "stretch"},
                      {"-load_ft_region", "y+"},      {"-load_ft_y", "stretch"},
                      {"-load_all_region", "group"},  {"-load_all_group", "body"},  {"-load_all_z", "fixed"},
                      {"-load_near_edge_region", "group"}, {"-load_near_edge_group", "edge"}, {"-load_near_edge_z", "fixed"},
                      {"-probes", "c"},               {"-probe_c_group", "corner"}}),
                 &scene),
            0)
      << ErrorText();
  const PointCloud points = nd::make_solid_points(scene.body.solid);
  ASSERT_EQ(points.size(), 72u); // 6 x 4 x 3 cells
  const auto gl = Select(scene, scene.loading.sets[0], points), bl = Select(scene, scene.loading.sets[1], points);
  EXPECT_EQ(gl.size(), 24u); // two layers of 4 x 3
  EXPECT_EQ(gl, bl);
  const auto gt = Select(scene, scene.loading.sets[2], points), ft = Select(scene, scene.loading.sets[3], points);
  EXPECT_EQ(gt.size(), 18u); // one layer of 6 x 3
  EXPECT_EQ(gt, ft);
  EXPECT_EQ(Select(scene, scene.loading.sets[4], points).size(), 72u); // the volume holds every point
  EXPECT_EQ(Select(scene, scene.loading.sets[5], points).size(), 4u);   // within 1 mm of the edge x = z = 0: (0.5, y, 0.5) mm
  EXPECT_EQ(scene.loading.probes[0].x, 6 * kMm);
  EXPECT_EQ(scene.loading.probes[0].y, 4 * kMm);
  EXPECT_EQ(scene.loading.probes[0].z, 0.0);
  const std::string text = SceneText(scene);
  EXPECT_NE(text.find("load set  gl: within 0.002 m of physical surface 'left' of " + kGeo), std::string::npos) << text;
  EXPECT_NE(text.find("load set  all: physical volume 'body' of " + kGeo), std::string::npos) << text;
}

TEST_F(Groups3D, AMissingGroupIsRefusedWithTheGroupsTheFileHas)
{
  Scene scene;
  EXPECT_EQ(Read(Box({{"-load_sets", "g"}, {"-load_g_region", "group"}, {"-load_g_group", "lefty"}, {"-load_g_x", "fixed"}}), &scene),
            PETSC_ERR_USER);
  const std::string message = ErrorText();
  for (const std::string &part : std::vector<std::string>{"-load_g_group lefty: '" + kGeo + "' has no physical group named 'lefty' (it has ", std::string("'left' (surface)"),
                                 std::string("'body' (volume)"), std::string("'edge' (curve)"), std::string("'corner' (point)")})
    EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in: " << message;
  // A depth for a volume, a probe on a face, a group on a body without a Gmsh file.
  EXPECT_EQ(Read(Box({{"-load_sets", "g"}, {"-load_g_region", "group"}, {"-load_g_group", "body"}, {"-load_g_layers", "2"}, {"-load_g_x", "fixed"}}),
                 &scene),
            PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("-load_g_layers is set but group 'body' is a physical volume"), std::string::npos) << ErrorText();
  EXPECT_EQ(Read(Box({{"-probes", "p"}, {"-probe_p_group", "left"}}), &scene), PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("a probe is one point, but group 'left' of '" + kGeo + "' is a physical surface"), std::string::npos) << ErrorText();
  EXPECT_EQ(Read({{"-body_dimension", "3"}, {"-body_dx", "0.001"}, {"-body_shapes", "b"}, {"-body_b_type", "box"},
                  {"-body_b_box", "0,0,0,0.006,0.004,0.003"}, {"-load_sets", "g"}, {"-load_g_region", "group"}, {"-load_g_group", "left"},
                  {"-load_g_x", "fixed"}},
                 &scene),
            PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("-load_g_file is required for load set 'g': the body reads 0 Gmsh files"), std::string::npos) << ErrorText();
}

// Element centroids of a 3D mesh (-body_S_discretisation centroids, nd::tetrahedron_centroids):
// one point a tetrahedron at the mean of its corners with its volume; by hand on a cube cut
// into Kuhn's six tetrahedra, and through the scene on the Gmsh box (the volumes fill it,
// a grip by group holds the centroids near its face, a solid cuts them).
TEST(TetrahedronCentroids, OnePointATetrahedronWithItsVolume)
{
  const double       v[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  const int          kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  nd::TetrahedronSet cube;
  for (const auto &t : kuhn)
    for (int c : t) cube.corners.insert(cube.corners.end(), v[c], v[c] + 3);
  const PointCloud points = nd::tetrahedron_centroids(cube);
  ASSERT_EQ(points.size(), 6u);
  for (std::size_t p = 0; p < 6; ++p) {
    EXPECT_NEAR(points.volume[p], 1.0 / 6.0, 1e-15);
    EXPECT_EQ(points.natural_id[p], static_cast<int64_t>(p));
    for (int r = 0; r < 3; ++r) {
      double mean = 0;
      for (int c : kuhn[p]) mean += v[c][r];
      EXPECT_DOUBLE_EQ(points.x[3 * p + r], mean / 4);
    }
  }
}

TEST_F(Groups3D, TheCentroidsOfTheGmshBoxAreItsPoints)
{
  Scene scene;
  const Options centroids = {{"-body_dimension", "3"},         {"-body_shapes", "part"},          {"-body_part_type", "mesh"},
                             {"-body_part_file", kGeo},        {"-body_part_discretisation", "centroids"},
                             {"-load_schedule", "0,1,1,1.1"},  {"-load_sets", "g"},               {"-load_g_region", "group"},
                             {"-load_g_group", "left"},        {"-load_g_depth", "0.001"},        {"-load_g_x", "fixed"}};
  ASSERT_EQ(Read(centroids, &scene), 0) << ErrorText();
  nd::TetrahedronSet mesh;
  ASSERT_EQ(ReadGmshTetrahedra(kGeo, &mesh), "");
  ASSERT_TRUE(scene.body.solid.given_points);
  const PointCloud &points = *scene.body.solid.given_points;
  EXPECT_TRUE(scene.body.solid.centroids);
  ASSERT_EQ(points.size(), mesh.size());
  EXPECT_EQ(scene.body.solid_summary.points, static_cast<int64_t>(mesh.size()));
  double volume = 0;
  for (double vp : points.volume) volume += vp;
  EXPECT_NEAR(volume, 72 * kMm * kMm * kMm, 1e-12 * 72 * kMm * kMm * kMm); // the tetrahedra fill the box
  // The grip holds the centroids closer than 1 mm to the face x = 0, and no other.
  const auto held = Select(scene, scene.loading.sets[0], points);
  std::size_t near = 0;
  for (std::size_t p = 0; p < points.size(); ++p) near += points.x[3 * p] < kMm;
  EXPECT_GT(held.size(), 0u);
  EXPECT_EQ(held.size(), near);
  const std::string text = SceneText(scene);
  EXPECT_NE(text.find(Format("  body      3D: %zu tetrahedron centroids of %s", mesh.size(), kGeo.c_str())), std::string::npos) << text;
  EXPECT_NE(text.find("0 solid(s) cutting them"), std::string::npos) << text;

  // A box cuts the centroids as it cuts a cloud; the mistakes.
  Options cut = centroids;
  cut.insert(cut.end(), {{"-body_shapes", "part,half"}, {"-body_half_type", "box"}, {"-body_half_box", "0.003,-1,-1,1,1,1"}});
  ASSERT_EQ(Read(cut, &scene), 0) << ErrorText();
  std::size_t left = 0;
  for (std::size_t p = 0; p < points.size(); ++p) left += !(points.x[3 * p] >= 3 * kMm);
  EXPECT_EQ(scene.body.solid_summary.points, static_cast<int64_t>(left));
  Options dx = centroids;
  dx.emplace_back("-body_dx", "0.001");
  EXPECT_EQ(Read(dx, &scene), PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("-body_dx is the lattice spacing, but -body_part_discretisation centroids gives the body's points"),
            std::string::npos)
      << ErrorText();
  Options second = cut;
  second.insert(second.end(), {{"-body_shapes", "half,part"}, {"-body_half_op", "add"}, {"-body_part_op", "intersect"}});
  EXPECT_EQ(Read(second, &scene), PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("must be the first solid of -body_shapes"), std::string::npos) << ErrorText();
  Options box = centroids;
  box.insert(box.end(), {{"-body_shapes", "part,b"}, {"-body_b_type", "box"}, {"-body_b_box", "0,0,0,1,1,1"}, {"-body_b_discretisation", "centroids"}});
  EXPECT_EQ(Read(box, &scene), PETSC_ERR_USER);
  EXPECT_NE(ErrorText().find("-body_b_discretisation is not a parameter of a 3D box"), std::string::npos) << ErrorText();
}

} // namespace
} // namespace bapd
