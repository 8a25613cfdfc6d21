// The 3D body of a scene (-body_dimension 3): the solids and planar
// notches of shape3d.hpp applied in order to an empty start, or a 3D point cloud (or
// a Gmsh volume's element centroids) clipped by them. Checked whole here: the lattice's
// count, extent (the faces of the load sets) and one piece from a pass over it that
// holds none of its points, so that no rank holds the whole body while the scene is
// read (-partition_type ptscotch then builds it in slabs); given points are read whole.
// scene_body.cpp reads the options and calls CheckBody3D.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/core/geometry/point_cloud3d.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

// A shape type of the 3D body (a 2D scene never names one).
bool IsShape3D(const std::string &type)
{
  const std::string t = Lower(type);
  return t == "box" || t == "cylinder" || t == "sphere" || t == "notch";
}

namespace {

// Three numbers as a point.
std::array<double, 3> Point3(const std::vector<double> &v, std::size_t k = 0) { return {v[k], v[k + 1], v[k + 2]}; }

// One shape of a 3D body: a solid (appended to body->solids) or a notch (to body->notches).
PetscErrorCode CheckShape3D(MPI_Comm comm, const ShapeInput &in, bool first_solid, BodySection *body)
{
  const char *n = in.name.c_str();
  PetscFunctionBeginUser;
  static const char *reserved[] = {"width", "height", "thickness", "dx", "holes", "notches", "shapes", "dimension", "cloud"};
  for (const char *word : reserved)
    SceneCheck(Lower(in.name) != word, comm, "-body_shapes: '%s' is the name of a body option (-body_%s): give the shape another name", n, word);
  SceneCheck(in.type_set, comm, "-body_%s_type is required for shape '%s' of a 3D body: box, cylinder, sphere, mesh or notch%s", n, n,
             MisspeltHint("-body_" + in.name + "_type").c_str());
  const std::string type = Lower(in.type);
  SceneCheck(type == "box" || type == "cylinder" || type == "sphere" || type == "mesh" || type == "notch", comm,
             "-body_%s_type '%s' is not a shape of a 3D body: give box, cylinder, sphere, mesh (a Gmsh volume) or notch (a planar "
             "polygon)%s",
             n, in.type.c_str(),
             type == "rectangle" || type == "circle" || type == "ellipse" || type == "polygon"
                 ? " (rectangle, circle, ellipse and polygon are the 2D sheet's shapes)"
                 : "");
  // Each type takes its own parameters and no other's (a stray one is a mistake).
  const struct {
    bool        given, wanted;
    const char *option;
  } parameters[] = {{!in.box.empty(), type == "box", "box"},
                    {!in.axis.empty(), type == "cylinder", "axis"},
                    {!in.centre.empty(), type == "sphere", "centre"},
                    {in.radius_set, type == "cylinder" || type == "sphere", "radius"},
                    {!in.radii.empty(), false, "radii"},
                    {in.angle != 0, false, "angle"},
                    {!in.points.empty(), type == "notch", "points"},
                    {!in.file.empty(), type == "mesh", "file"},
                    {Lower(in.discretisation) != "lattice", type == "mesh", "discretisation"},
                    {in.op_set, type != "notch", "op"}};
  for (const auto &p : parameters)
    SceneCheck(!p.given || p.wanted, comm, "-body_%s_%s is not a parameter of a 3D %s: remove it, or change -body_%s_type", n, p.option,
               type.c_str(), n);
  if (type == "notch") {
    SceneCheck(in.points.size() >= 9 && in.points.size() % 3 == 0, comm,
               "-body_%s_points holds %zu numbers: a notch of a 3D body is a planar polygon, at least three vertices "
               "x0,y0,z0,x1,y1,z1,... in m",
               n, in.points.size());
    const nd::PlanarPolygon notch{in.points};
    const std::string       problem = nd::planar_polygon_problem(notch);
    SceneCheck(problem.empty(), comm, "-body_%s_points (notch '%s'): %s; give the vertices in order around one plane polygon", n, n,
               problem.c_str());
    body->solid.notches.push_back(notch);
    body->solid_summary.notch_names.push_back(in.name);
    PetscFunctionReturn(0);
  }
  nd::Solid::Op op = first_solid ? nd::Solid::Op::add : nd::Solid::Op::subtract; // the defaults (-body_NAME_op's help)
  if (in.op_set) {
    const std::string o = Lower(in.op);
    if (o == "subtract") op = nd::Solid::Op::subtract;
    else if (o == "add") op = nd::Solid::Op::add;
    else if (o == "intersect") op = nd::Solid::Op::intersect;
    else SceneCheck(false, comm, "-body_%s_op '%s': give subtract, add or intersect", n, in.op.c_str());
  }
  nd::Solid solid;
  if (type == "box") {
    SceneCheck(in.box.size() == 6, comm, "-body_%s_box holds %zu numbers: a 3D box takes six, xmin,ymin,zmin,xmax,ymax,zmax in m", n,
               in.box.size());
    SceneCheck(in.box[3] > in.box[0] && in.box[4] > in.box[1] && in.box[5] > in.box[2], comm,
               "-body_%s_box %g,%g,%g,%g,%g,%g: give xmin,ymin,zmin,xmax,ymax,zmax with each max > min", n, in.box[0], in.box[1], in.box[2],
               in.box[3], in.box[4], in.box[5]);
    solid = nd::make_box(Point3(in.box), Point3(in.box, 3), op);
  } else if (type == "cylinder") {
    SceneCheck(in.axis.size() == 6, comm,
               "-body_%s_axis holds %zu numbers: give the cylinder's axis as its two end points x0,y0,z0,x1,y1,z1 in m", n, in.axis.size());
    SceneCheck(in.radius_set, comm, "-body_%s_radius: give the cylinder's radius in m, > 0", n);
    solid = nd::make_cylinder(Point3(in.axis), Point3(in.axis, 3), in.radius, op);
  } else if (type == "sphere") {
    SceneCheck(in.centre.size() == 3, comm, "-body_%s_centre holds %zu numbers: give the sphere's centre x,y,z in m", n, in.centre.size());
    SceneCheck(in.radius_set, comm, "-body_%s_radius: give the sphere's radius in m, > 0", n);
    solid = nd::make_sphere(Point3(in.centre), in.radius, op);
  } else { // mesh: a Gmsh volume
    SceneCheck(!in.file.empty(), comm, "-body_%s_file: give the Gmsh .geo (with a volume) or .msh (tetrahedra) of shape '%s'", n, n);
    auto              mesh    = std::make_shared<nd::TetrahedronSet>();
    const std::string problem = ReadGmshTetrahedra(in.file, mesh.get());
    SceneCheck(problem.empty(), comm, "-body_%s_file: %s", n, problem.c_str());
    solid = nd::make_mesh(mesh, op);
  }
  const std::string problem = nd::solid_problem(solid);
  SceneCheck(problem.empty(), comm, "-body_%s (%s): %s", n, type.c_str(), problem.c_str());
  body->solid.solids.push_back(solid);
  body->solid_summary.solid_names.push_back(in.name);
  PetscFunctionReturn(0);
}

// -body_width and the other options of the 2D sheet have no place in a 3D body.
PetscErrorCode CheckNoSheetOptions(MPI_Comm comm, const SceneInput &in)
{
  PetscFunctionBeginUser;
  const struct {
    bool        given;
    const char *option, *fix;
  } two_d[] = {{in.width_set, "-body_width", "the solids give its size"},
               {in.height_set, "-body_height", "the solids give its size"},
               {in.thickness_set, "-body_thickness", "the solids give its size (a slab is a box)"},
               {!in.holes.empty(), "-body_holes", "a hole is a shape: -body_NAME_type cylinder or sphere, -body_NAME_op subtract"},
               {!in.notches.empty(), "-body_notches", "a notch is a planar polygon shape: -body_NAME_type notch, -body_NAME_points "
                                                      "x0,y0,z0,x1,y1,z1,..."}};
  for (const auto &o : two_d)
    SceneCheck(!o.given, comm, "%s is an option of the 2D sheet, and this body is 3D (-body_dimension 3): remove it; %s", o.option, o.fix);
  PetscFunctionReturn(0);
}

// Given points instead of the lattice: a 3D cloud, or the element centroids of one mesh
// solid (-body_S_discretisation centroids, the first solid: the body is its tetrahedra).
// *centroid_solid_out: that solid's index, or the number of solids for none.
PetscErrorCode FindCentroidSolid(MPI_Comm comm, const SceneInput &in, const BodySection &b, std::size_t *centroid_solid_out)
{
  PetscFunctionBeginUser;
  std::size_t centroid_solid = b.solid.solids.size(); // none
  for (const ShapeInput &si : in.shapes) {
    const char *n = si.name.c_str();
    if (Lower(si.discretisation) == "lattice") continue;
    SceneCheck(Lower(si.discretisation) == "centroids", comm, "-body_%s_discretisation '%s' is not a choice: choose lattice or centroids", n,
               si.discretisation.c_str());
    SceneCheck(centroid_solid == b.solid.solids.size(), comm,
               "-body_%s_discretisation centroids: another mesh already gives the body's points as its centroids: keep one", n);
    SceneCheck(in.cloud.empty(), comm, "-body_%s_discretisation centroids and -body_cloud both give the body's points: keep one", n);
    const std::vector<std::string> &names = b.solid_summary.solid_names;
    centroid_solid                        = static_cast<std::size_t>(std::find(names.begin(), names.end(), si.name) - names.begin());
    SceneCheck(centroid_solid == 0, comm,
               "-body_%s_discretisation centroids: the mesh whose tetrahedra are the points must be the first solid of -body_shapes (the "
               "others may cut it): list '%s' first",
               n, n);
  }
  *centroid_solid_out = centroid_solid;
  PetscFunctionReturn(0);
}

// The given points (a 3D cloud, or the centroid solid's tetrahedra) clipped by the
// other solids: b->solid.given_points, their block ids and smallest spacing; *points a copy.
PetscErrorCode GivenPoints3D(MPI_Comm comm, const SceneInput &in, std::size_t centroid_solid, BodySection *body, PointCloud *points)
{
  BodySection &b        = *body;
  const bool centroids = centroid_solid < b.solid.solids.size();
  PetscFunctionBeginUser;
  const std::string source = centroids ? "-body_" + b.solid_summary.solid_names[centroid_solid] + "_discretisation centroids" : "-body_cloud";
  SceneCheck(!in.dx_set, comm, "-body_dx is the lattice spacing, but %s gives the body's points, each with its own volume: remove -body_dx",
             source.c_str());
  for (std::size_t k = 0; k < b.solid.solids.size(); ++k)
    SceneCheck(k == centroid_solid || b.solid.solids[k].op != nd::Solid::Op::add, comm,
               "-body_%s: the points of %s are the body, so a solid can only cut them: set -body_%s_op subtract or intersect",
               b.solid_summary.solid_names[k].c_str(), source.c_str(), b.solid_summary.solid_names[k].c_str());
  PointCloud           read;
  std::vector<int64_t> block;
  if (centroids) {
    const nd::TetrahedronSet &mesh = *b.solid.solids[centroid_solid].mesh;
    read                           = nd::tetrahedron_centroids(mesh);
    block.assign(read.size(), 0);
    for (std::size_t p = 0; p < read.size(); ++p)
      SceneCheck(read.volume[p] > 0, comm,
                 "%s: tetrahedron %zu of '%s' has zero volume, so its centroid point would have no volume: fix the mesh", source.c_str(),
                 p + 1, mesh.file.c_str());
  } else {
    const std::string problem = nd::read_point_cloud_3d(in.cloud, &read, &block);
    SceneCheck(problem.empty(), comm, "-body_cloud: %s", problem.c_str());
  }
  auto kept = std::make_shared<PointCloud>();
  for (std::size_t p = 0; p < read.size(); ++p) {
    bool keep = true; // the points, then each solid's cut in order (the centroids' own mesh holds them all)
    for (std::size_t k = 0; k < b.solid.solids.size(); ++k) {
      if (k == centroid_solid) continue;
      const nd::Solid &solid    = b.solid.solids[k];
      const bool       in_solid = nd::solid_contains(solid, &read.x[3 * p]);
      keep                      = solid.op == nd::Solid::Op::subtract ? keep && !in_solid : keep && in_solid;
    }
    if (!keep) continue;
    kept->x.insert(kept->x.end(), &read.x[3 * p], &read.x[3 * p + 3]);
    kept->volume.push_back(read.volume[p]);
    kept->natural_id.push_back(static_cast<int64_t>(kept->volume.size()) - 1);
    b.solid.given_block.push_back(block[p]);
  }
  SceneCheck(kept->size() > 0, comm, "%s '%s': the solids of -body_shapes cut away all %zu of its points: check each one's -op", source.c_str(),
             centroids ? b.solid.solids[centroid_solid].mesh->file.c_str() : in.cloud.c_str(), read.size());
  double smallest = std::numeric_limits<double>::max();
  for (double v : kept->volume) smallest = std::min(smallest, point_spacing(3, v, 0.0));
  // The smallest spacing cbrt(V) (2D: sqrt(V/t), geometry.hpp): the faces' row depth,
  // the stable-step and travel scale; each point's horizon is its own (BodyPoints).
  b.solid.dx     = smallest;
  b.solid.source       = centroids ? b.solid.solids[centroid_solid].mesh->file : in.cloud;
  b.solid.centroids    = centroids;
  b.solid.given_points = kept;
  *points        = *kept;
  PetscFunctionReturn(0);
}

// The solids on the lattice of spacing -body_dx: their checks, the count of the points
// and the extent of their cells (lattice point +- dx/2), from one pass over the lattice
// that holds none of its points (nd::checked_solid_lattice: the memory of one layer of cells).
PetscErrorCode LatticeBody3D(MPI_Comm comm, const SceneInput &in, BodySection *body)
{
  const double dx = in.dx;
  BodySection &b = *body;
  PetscFunctionBeginUser;
  SceneCheck(in.dx_set, comm, "-body_dx is required: give the lattice spacing of the 3D body in metres (YAML: body: {dx: 0.001})%s",
             MisspeltHint("-body_dx").c_str());
  SceneCheck(dx > 0, comm, "-body_dx %g: the lattice spacing must be > 0 m", dx);
  SceneCheck(!b.solid.solids.empty(), comm,
             "-body_dimension 3: a 3D body is made of solids: give -body_shapes with a shape of -body_NAME_type box, cylinder, sphere "
             "or mesh (a Gmsh volume), or a 3D point cloud by -body_cloud");
  b.solid.dx = dx;
  try {
    const nd::SolidLattice lattice = nd::checked_solid_lattice(b.solid);
    b.solid_summary.points         = lattice.points;
    b.solid_summary.lo             = lattice.lo;
    b.solid_summary.hi             = lattice.hi;
  } catch (const std::invalid_argument &e) {
    SceneCheck(false, comm, "-body_shapes: %s", e.what());
  }
  PetscFunctionReturn(0);
}

// The count of the given points and the extent of their cells (point +- its spacing / 2).
void SetExtent(const PointCloud &points, BodySection *body)
{
  SolidSummary &e = body->solid_summary;
  e.points        = static_cast<int64_t>(points.size());
  e.lo.fill(std::numeric_limits<double>::max());
  e.hi.fill(-std::numeric_limits<double>::max());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double h = 0.5 * point_spacing(3, points.volume[p], 0.0);
    for (int r = 0; r < 3; ++r) {
      e.lo[r] = std::min(e.lo[r], points.x[3 * p + r] - h);
      e.hi[r] = std::max(e.hi[r], points.x[3 * p + r] + h);
    }
  }
}

} // namespace

// The 3D body: its solids and notches on the lattice of spacing -body_dx, counted and
// checked (one piece) without building its points, or a 3D cloud clipped by its solids,
// whose points are built here (CheckBodyFits follows).
PetscErrorCode CheckBody3D(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  BodySection &b = scene->body;
  PetscFunctionBeginUser;
  PetscCall(CheckNoSheetOptions(comm, in));
  b.sheet         = Body<2>(); // (a 3D body has no sheet)
  b.solid         = Body<3>();
  b.solid_summary = SolidSummary();
  for (const ShapeInput &si : in.shapes) PetscCall(CheckShape3D(comm, si, b.solid.solids.empty(), &b));
  std::size_t centroid_solid = 0;
  PetscCall(FindCentroidSolid(comm, in, b, &centroid_solid));
  const bool centroids = centroid_solid < b.solid.solids.size();
  if (!in.cloud.empty() || centroids) {
    PointCloud points;
    PetscCall(GivenPoints3D(comm, in, centroid_solid, &b, &points));
    SetExtent(points, &b);
  } else PetscCall(LatticeBody3D(comm, in, &b));
  PetscCall(CheckHorizonFactor(comm, *scene));
  PetscFunctionReturn(0);
}
} // namespace bapd
