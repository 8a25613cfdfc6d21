#pragma once
// 3D bodies (docs/architecture.md "core/geometry", docs/options.md "3D bodies"): solids
// (boxes, cylinders, spheres, Gmsh volumes as tetrahedra) combined in order, the cell-centred lattice clipped to
// them, and planar polygon notches as a BondCut for nd::build_families<3>.
//
// A body starts empty; each solid, in the order listed, adds to it, subtracts from it or
// intersects it (the ops of the 2D shapes, shape.hpp, whose sheet is the start instead).
// The lattice is the global grid of cells of side dx anchored at `origin`: one point at
// every cell centre origin + (i + 0.5) dx (per axis, i any integer) that the solids keep,
// volume dx^3, x fastest, then y, then z (the order of nd::box_lattice<3>); natural id =
// that order. A box [origin, origin + n dx] holds exactly the points of box_lattice.
//
// Boundaries (as the 2D shapes and the hole rule of lattice.hpp): a point on a box's
// face, a cylinder's end cap or a mesh's boundary is inside; on a sphere or a
// cylinder's curved surface it is outside (a point on a hole's rim is material).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/shape.hpp"

namespace bapd::nd {

// Tetrahedra (12 numbers each: the four corners' x, y, z) with a bucket grid over their
// bounding box, so that a point finds the few that may hold it: the volume of a Gmsh 3D
// mesh (gmsh_volume3d.hpp reads it), the 3D form of shape.hpp's TriangleSet.
struct TetrahedronSet {
  std::vector<double>    corners;          // 12 per tetrahedron [m]
  std::array<double, 3>  lo{};             // the grid's lower corner [m]
  double                 cell = 1;         // bucket size [m]
  std::array<int64_t, 3> count{};          // buckets per axis
  std::vector<int64_t>   offsets, members; // CSR: tetrahedra overlapping each bucket
  std::string            file;             // the Gmsh file it came from, for messages
  std::size_t            size() const { return corners.size() / 12; }
};
// Builds the bucket grid of `set` (about one tetrahedron a bucket).
void index_tetrahedra(TetrahedronSet &set);
// Whether the point lies in one of the tetrahedra (faces inclusive, to 1e-12 of the
// tetrahedron's volume, as triangles_contain).
bool tetrahedra_contain(const TetrahedronSet &set, const double *p);

struct Solid {
  enum class Kind { box, cylinder, sphere, mesh };
  using Op = Shape::Op; // add, subtract, intersect (shape.hpp)
  Kind                  kind = Kind::box;
  Op                    op   = Op::add;
  std::array<double, 3> lo{}, hi{}; // box: opposite corners [m]
  std::array<double, 3> a{}, b{};   // cylinder: the axis's end points (cap centres); sphere: a = centre [m]
  double                radius = 0; // cylinder, sphere [m]
  std::shared_ptr<const TetrahedronSet> mesh; // mesh: its tetrahedra, indexed
};

// Convenience constructors.
Solid make_box(const std::array<double, 3> &lo, const std::array<double, 3> &hi, Solid::Op op = Solid::Op::add);
Solid make_cylinder(const std::array<double, 3> &a, const std::array<double, 3> &b, double radius,
                    Solid::Op op = Solid::Op::add);
Solid make_sphere(const std::array<double, 3> &centre, double radius, Solid::Op op = Solid::Op::add);
Solid make_mesh(std::shared_ptr<const TetrahedronSet> mesh, Solid::Op op = Solid::Op::add);

// A planar polygon: n >= 3 vertices in 3D (x0,y0,z0,x1,...), closed implicitly.
struct PlanarPolygon {
  std::vector<double> vertices;
};

} // namespace bapd::nd

namespace bapd {

// The 3D body (the 3D specialisation of Body<D>, body.hpp): solids applied in order to
// an empty start on the lattice above, cut by planar notches; or given points clipped
// by the solids: a 3D cloud (point_cloud3d.hpp) or the tetrahedron centroids of the
// first solid, a mesh (tetrahedron_centroids). make_solid_points, solid_lattice and the
// layers below are the lattice's (solid_lattice.cpp); the given points are already built.
template <> struct Body<3> {
  double                         dx = 0;   // lattice spacing [m] (given points: their smallest cbrt(V))
  std::array<double, 3>          origin{}; // the grid's anchor: points at origin + (i + 0.5) dx [m]
  std::vector<nd::Solid>         solids;   // applied in order to an empty start
  std::vector<nd::PlanarPolygon> notches;  // pre-notches (cut bonds; also split the connectivity check)
  // Not null: the body's points are these (x: 3 a point, clipped), not the lattice.
  // Shared: the scene is copied, the points are not.
  std::shared_ptr<const PointCloud> given_points;
  std::vector<int64_t>              given_block;       // block id of each given point
  bool                              centroids = false; // given_points are the tetrahedron centroids of the first solid
  std::string                       source;            // the file of the given points, for messages
};

} // namespace bapd

namespace bapd::nd {

// Whether the point lies inside the solid (boundary rule above).
bool solid_contains(const Solid &solid, const double *p);

// Whether the body keeps the point: the solids applied in order to an empty start.
bool body_contains(const std::vector<Solid> &solids, const double *p);

// The solid's volume [m^3] (analytic; a mesh: the sum of its tetrahedra's; for
// estimates and tests).
double solid_volume(const Solid &solid);

// "" for a usable solid, else what is wrong with it ("its radius must be > 0 (got -1)").
std::string solid_problem(const Solid &solid);

// "" for a polygon with at least 3 vertices, all in one plane (to 1e-9 of its size),
// whose edges do not cross (polygon_problem of shape.hpp on its projection) and whose
// area is not zero, else what is wrong with it.
std::string planar_polygon_problem(const PlanarPolygon &polygon);

// Whether the bond (a, b) crosses the polygon. The rule is open, like the 2D segment
// notch (segments_cross, family.hpp): cut iff a and b lie strictly on opposite sides of
// the polygon's plane AND the point where the segment meets the plane lies strictly
// inside the polygon. A bond lying in the plane, one with an end point on the plane, and
// one that meets the plane on the polygon's boundary (an edge or a vertex, to round-off
// 1e-12 of the polygon's size) are NOT cut: a notch is a crack of zero thickness, and
// a bond that only touches it does not pass through it. Symmetric in a and b.
// Place a notch on the lattice's cell faces (origin + i dx) and its edges off the cell
// centres' lines, so that no bond is a boundary case. Prepares the polygon on every call
// (for a single test); polygon_notches prepares once for many bonds.
bool polygon_cuts(const PlanarPolygon &polygon, const double *a, const double *b);

// The BondCut for nd::build_families<3>: a bond is cut by any of the polygons. Each
// polygon must be valid (planar_polygon_problem == ""); throws std::invalid_argument
// naming the first bad one. The polygons are copied (with their planes and 2D
// projections, computed once) into the returned function.
BondCut polygon_notches(const std::vector<PlanarPolygon> &polygons);

// Connected pieces of the body's lattice: points linked to their 6 face neighbours
// (the 3D form of lattice_pieces, lattice.hpp), minus the links a notch cuts. The
// smallest piece is the first of that size in the points' order (the natural order),
// smallest_at its first point.
struct SolidPieces {
  int64_t               count = 0;
  int64_t               smallest_points = 0;
  std::array<double, 3> smallest_at{}; // a point of the smallest piece [m]
};
// The pieces of built points (any order).
SolidPieces body_pieces(const Body<3> &body, const PointCloud &points);

// What the scene needs of a lattice body, found without holding its points: one pass
// over the lattice layer by layer (z) that keeps two layers of piece labels (the pieces
// by Hoshen-Kopelman labelling, the links as body_pieces's), so its memory goes as one
// layer of cells, not as the points.
struct SolidLattice {
  int64_t               points = 0;   // make_solid_points's count
  std::array<double, 3> lo{}, hi{};   // the extent of the points' cells (point +- dx / 2) [m]
  SolidPieces           pieces;       // as body_pieces on make_solid_points's points
};
// The summary; throws make_solid_points's messages (below) for a bad input, not for a
// body with no point or in pieces. checked_solid_lattice throws for those too.
SolidLattice solid_lattice(const Body<3> &body);
SolidLattice checked_solid_lattice(const Body<3> &body);

// The body's points (order and volumes above; horizon and family_volume left empty).
// Throws std::invalid_argument with a message that names the problem and the fix for:
// dx not > 0 or not finite; a bad solid (solid_problem) or notch
// (planar_polygon_problem); no solid that adds; a lattice of more than 2^31 cells
// around the added solids; a body that holds no lattice point; a body in more than
// one piece (checked_solid_lattice, the same pass).
PointCloud make_solid_points(const Body<3> &body);

// The lattice layer by layer (z cells), for a body built in slabs of layers (one a
// rank), with no check (checked_solid_lattice's are the scene's): solid_layers(body)
// layers (0 without a solid that adds), append_solid_layers appends the points of
// layers [layer_begin, layer_end) to *cloud in make_solid_points's order, natural_id =
// the point's index in *cloud, and each layer's count to layer_counts when given.
int64_t solid_layers(const Body<3> &body);
void    append_solid_layers(const Body<3> &body, int64_t layer_begin, int64_t layer_end, PointCloud *cloud,
                            std::vector<int64_t> *layer_counts);

const char *to_string(Solid::Kind kind);

// The element centroids of a 3D mesh as given points (the 3D form of geometry.hpp's
// element_centroids): one point a tetrahedron, at the mean of its four corners, volume =
// its volume |det(b - a, c - a, d - a)| / 6, in the mesh's order (natural id = index).
PointCloud tetrahedron_centroids(const TetrahedronSet &mesh);

// The elements of a named Gmsh physical group of a 3D body as a region of points (a load
// set or probe by group, gmsh_volume3d.hpp reads them): a physical volume holds the points
// inside its tetrahedra (faces inclusive, as a mesh solid); a physical surface, curve or
// point holds the points closer than `depth` to its triangles, line segments or nodes
// (the 3D distance to the element, boundary included; a node is a segment of length 0).
// On a face that lies on the lattice's cell faces, points sit (j + 1/2) dx from it, so a
// depth of n dx holds exactly the n layers of cells next to it, as a face grip of n rows
// (the rule of the 2D physical curve).
struct ElementRegion {
  int                                   dim = -1;   // 3, 2, 1 or 0
  std::shared_ptr<const TetrahedronSet> tetrahedra; // dim 3 (indexed)
  std::vector<double>                   triangles;  // dim 2: 9 numbers each [m]
  std::vector<double>                   segments;   // dim 1 and 0: x0,y0,z0,x1,y1,z1 each [m]
  double                                depth = 0;  // dim 2, 1, 0 [m]
  std::array<double, 3>                 lo{}, hi{}; // the elements' bounding box grown by depth (set_reach)
  std::size_t                           size() const
  {
    return dim == 3 ? (tetrahedra ? tetrahedra->size() : 0) : dim == 2 ? triangles.size() / 9 : segments.size() / 6;
  }
};
// Sets region.lo, hi from its elements and depth (call after changing either).
void set_reach(ElementRegion &region);
// Whether the point lies in the region (the rule above).
bool region_contains(const ElementRegion &region, const double *p);
// Squared distances from p to the triangle (a, b, c) (its closest point: a vertex, an
// edge or the inside; Ericson, Real-Time Collision Detection, 5.1.5) and to the segment
// (a, b) (a point when a = b).
double point_triangle_distance2(const double *p, const double *a, const double *b, const double *c);
double point_segment_distance2(const double *p, const double *a, const double *b);

} // namespace bapd::nd
