#pragma once
// Grips (load sets, -load_sets): which points a grip holds and how each component
// moves. Included by scene.hpp.
#include <petscsys.h>
#include <array>
#include <string>
#include <vector>

#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/core/geometry/shape.hpp"
#include "bapd/solver/input/regions/region_list.hpp"

namespace bapd {

// What the load regions read of the body once it is checked (BodyExtentOf, scene.hpp):
// its dimension, its extent, the spacing and the sheet's thickness.
struct BodyExtent {
  int                   dimension = 2;
  std::array<double, 3> lo{}, hi{};    // 2D: the sheet, [0, width] x [0, height]; 3D: the points' cells (SolidSummary::lo, hi) [m]
  double                dx        = 0; // the lattice spacing (given points: the smallest) [m]
  double                thickness = 0; // the sheet's [m]
};

enum class ComponentLoad { free, fixed, stretch };

// How a top or bottom grip moves the y component of its points (-load_grip_field;
// docs/stress_consistency.md): rigid, every point of the grip by the
// same u, or affine, the grip's points on the affine continuation of the free
// region's mean stretch, u = u_rigid + (lambda - 1) (L / L_free) (y - y_inner),
// y_inner the grip's inner boundary, L_free the distance between the two grips'
// inner boundaries. The free points next to a grip then see no kink of the
// displacement within their horizon. x is held as the set says (a clamp holds it).
// Default: affine for a top and a bottom grip placed outside the specimen, rigid
// otherwise.
enum class GripField { rigid, affine };

// Where an edge grip's points are (-load_grip_placement, -load_NAME_placement):
// outside, added beyond the specimen's edge (Body<2>::grip_rows), so the specimen is
// the free region; or inside, the specimen's own edge rows (the paper's grips).
enum class GripPlacement { outside, inside };

// A named set of points held by a grip. Per component: free, fixed (u = 0) or
// following the stretch schedule, u = scale * (lambda(t) - 1) * reference_length.
// Where its points are: the edge regions take rows at an edge of the sheet (inside,
// or added outside it); the other regions are predicates on a point's reference
// position, so they hold whatever points the body has there (a lattice's or a
// cloud's): a box, a closed polygon, the points closer than `depth` to an open
// polyline (curve), or a named physical group of a Gmsh file (group: a physical
// surface holds the points inside its elements; a physical curve or point, the
// points closer than `depth` to it).
// In 3D (BodySection::dimension 3) the edge regions are the faces of the
// body's extent (SolidSummary::lo, hi): left x-, right x+, bottom y-, top y+, back z-, front
// z+ (the words x-, x+, y-, y+, z-, z+ name them too), always inside; a box has six
// numbers; a group is a physical group of the body's Gmsh volume (a volume: the points
// inside it; a surface, curve or point: those closer than `depth` to it); a block is a
// block id of a 3D cloud; polygon and curve are 2D only.
struct LoadSet {
#define BAPD_REGION_ID(id, alias, type) id,
  enum class Region { BAPD_REGISTERED_REGIONS(BAPD_REGION_ID) }; // (regions/region_list.hpp)
#undef BAPD_REGION_ID
  std::string   name;
  Region        region    = Region::top;
  GripPlacement placement = GripPlacement::inside; // edge regions (the others are inside)
  // Region::box: the lower corner then the upper, D numbers each: 2D xmin, ymin, xmax,
  // ymax; 3D xmin, ymin, zmin, xmax, ymax, zmax.
  double        box[6] = {0, 0, 0, 0, 0, 0};
  int           layers = 1;            // point rows taken at the named edge
  ComponentLoad x = ComponentLoad::free, y = ComponentLoad::free, z = ComponentLoad::free; // z: 3D only
  double        x_scale = 0.0, y_scale = 0.0, z_scale = 0.0;
  // Component c (0: x, 1: y, 2: z) and its scale.
  ComponentLoad component(int c) const { return c == 0 ? x : c == 1 ? y : z; }
  double        scale(int c) const { return c == 0 ? x_scale : c == 1 ? y_scale : z_scale; }
  // polygon, and a group's physical surface: the points `area` contains (a polygon,
  // edges inclusive; or a mesh shape, the group's triangles).
  Shape               area;
  // curve, and a group's physical curve or points: the points closer than `depth` to
  // one of `segments` (x0,y0,x1,y1 each; a point is a segment of length 0).
  std::vector<double> segments;
  double              depth = 0.0;          // [m]
  double              reach[4] = {0, 0, 0, 0}; // the segments' bounding box grown by depth
  std::string         group, file;          // group: the physical group and its Gmsh file
  // group of a 3D body: the physical group's elements (a volume's tetrahedra; a surface's
  // triangles, a curve's segments or a point's nodes with `depth`), shape3d.hpp.
  nd::ElementRegion   elements;
  // block: the given points (-body_cloud) of block id `block`, found by position:
  // their (x, y) (3D: (x, y, z)), sorted, compared bit for bit (a point keeps the
  // coordinates read from the cloud, and two points never share a position: the cloud
  // check refuses it).
  int64_t             block = 0;
  std::vector<double> block_points;
};

// The (x, y) of the given points of block id `block`, sorted (LoadSet::block_points).
// Empty when there are no given points or no point has that id.
std::vector<double> BlockPoints(const Body<2> &body, int64_t block);
// The block ids the given points have, "1, 2, 5" (for messages; at most 20 shown).
std::string BlockIdList(const Body<2> &body);
// The same for the points of a 3D cloud (x: 3 a point, block: one id a point): the
// (x, y, z) of block `block`, sorted; the ids.
std::vector<double> BlockPoints3D(const std::vector<double> &x, const std::vector<int64_t> &block, int64_t id);
std::string         BlockIdList(const std::vector<int64_t> &block);

// Whether the point at reference position p (D coordinates; D = body.dimension)
// belongs to `set` (the predicate LoadSetSelect applies to every owned point).
template <int D> bool LoadSetContains(const BodyExtent &body, const LoadSet &set, const double *p);
inline bool LoadSetContains(const BodyExtent &body, const LoadSet &set, double px, double py)
{
  const double p[2] = {px, py};
  return LoadSetContains<2>(body, set, p);
}

// Sets set->reach from its segments and depth (call after changing either).
void SetCurveReach(LoadSet *set);

// The rows a grip of depth d holds: those whose centres lie within d of its edge,
// ceil(d / dx - 1/2) (at least 1). The default depth of a grip outside the specimen
// is two horizons, 2 delta (6 rows at delta = 3.015 dx): no free point then has a
// neighbour whose family reaches the grip's outer edge.
int GripRows(double depth, double dx);

// The local points (reference positions x, D = body.dimension per point, n points) that a load set
// holds: inside, within `layers` rows of its edge (top: y > height - layers*dx,
// bottom: y < layers*dx, left: x < layers*dx, right: x > width - layers*dx); outside,
// its `layers` rows beyond the edge (top: height < y < height + layers*dx, ...); or
// where LoadSetContains says for the other regions (a box: edges included). Indices into x, increasing. Pass owned points
// only; whether a set holds any point at all is for the caller to check over the
// communicator. 3D faces: within `layers` rows of the body's extent, inside (x-:
// x < lo_x + layers dx, ...).
PetscErrorCode LoadSetSelect(const BodyExtent &body, const LoadSet &set, const double *x, PetscInt n,
                             std::vector<PetscInt> *selected);

// The summary's words for where a load set is (SceneText), and the message when it
// holds no material point anywhere (Loading::Setup): its region type's (regions/).
std::string RegionText(const BodyExtent &body, const LoadSet &set);
std::string LoadSetEmptyMessage(const BodyExtent &body, const LoadSet &set);

const char *to_string(LoadSet::Region region);
const char *to_string(GripPlacement placement);
const char *to_string(GripField field);
const char *to_string(ComponentLoad load);

} // namespace bapd
