// Region top, bottom, left, right (a 2D sheet's edges; a 3D body's faces y+, y-, x-,
// x+) and front, back (3D only: z+, z-): the point rows within `layers` rows of the
// edge. A 2D edge grip sits inside (the sheet's own edge rows, the paper's grips) or
// outside (rows added beyond the edge, Body<2>::grip_rows: the sheet is then the free
// region); a 3D face holds the body's own points, within `layers` rows of its extent.
#include <algorithm>
#include <cmath>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {
namespace {

// The axis an edge or face is normal to (0: x, 1: y, 2: z), and whether it is the upper one.
int EdgeAxis(LoadSet::Region r)
{
  return r == LoadSet::Region::left || r == LoadSet::Region::right ? 0 : r == LoadSet::Region::bottom || r == LoadSet::Region::top ? 1 : 2;
}
bool EdgeUpper(LoadSet::Region r) { return r == LoadSet::Region::right || r == LoadSet::Region::top || r == LoadSet::Region::front; }

// A grip shallower than a horizon: the points next to it see the grip's rows and then
// nothing where their family should go on, so the body there is softer (a surface
// effect at the grip) and the reaction is off: pure shear at dx = 0.5 mm with one row
// outside read a nominal stress 7.7 % off. Not an error (the paper's grips are one row
// inside): a warning that names the rows that reach a horizon, ceil(horizon / dx).
PetscErrorCode WarnShallowGrip(MPI_Comm comm, const LoadInput &li, int layers, double dx, double horizon)
{
  PetscFunctionBeginUser;
  if (!(layers * dx < horizon * (1.0 - 1e-9))) PetscFunctionReturn(0);
  const char *n      = li.name.c_str();
  const int   needed = static_cast<int>(std::ceil(horizon / dx - 1e-9));
  PetscCall(Warn(comm, Format("load set '%s' grips %d row(s), %g m deep, less than the horizon %g m: the points within a horizon of the "
                              "grip miss part of their family, the body there is softer and the reaction is off (pure shear at dx = "
                              "0.5 mm, one row: the nominal stress 7.7 %% off); give -load_%s_layers %d (ceil(horizon / dx)) or more%s",
                              n, layers, layers * dx, horizon, n, needed, li.depth_set ? Format(" (or a -load_%s_depth of %g m)", n, needed * dx).c_str() : "")));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckEdge2D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const Body<2>    &b  = r.body.sheet;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  const std::string placement = Lower(li.placement) == "auto" ? to_string(r.default_placement) : Lower(li.placement);
  if (placement == "outside") set->placement = GripPlacement::outside;
  else if (placement == "inside") set->placement = GripPlacement::inside;
  else SceneCheck(false, r.comm, "-load_%s_placement '%s' is not a choice: choose outside, inside or auto", n, li.placement.c_str());
  // A grip outside extrudes the edge row of the lattice; given points have no rows.
  SceneCheck(set->placement == GripPlacement::inside || !b.given_points, r.comm,
             "-load_%s_placement %s: a grip outside the specimen extrudes the lattice's edge rows, which given points (-body_cloud, "
             "-body_S_discretisation centroids) do not have: place it inside (-load_%s_placement inside, or -load_grip_placement "
             "inside for every grip)",
             n, Lower(li.placement) == "auto" ? "outside (the default)" : "outside", n);
  PetscCall(CheckLayersDepth(r, "grip", "row"));
  const bool outside = set->placement == GripPlacement::outside;
  if (li.depth_set) set->layers = GripRows(li.depth, b.dx);
  else if (li.layers_set || !outside) set->layers = static_cast<int>(li.layers);
  else set->layers = GripRows(2.0 * r.body.horizon(), b.dx);
  const bool   vertical = EdgeAxis(set->region) == 1;
  const double across   = vertical ? b.height : b.width;
  SceneCheck(outside || set->layers * b.dx < across, r.comm,
             "-load_%s_layers %d (placement inside) is %g m deep, the whole body %s (%g m): use fewer rows, or place the grip "
             "outside (-load_%s_placement outside)",
             n, set->layers, set->layers * b.dx, vertical ? "height" : "width", across, n);
  // Outside, ten times deeper than the body or its default grip (-load_top_depth 1e30):
  // rows without end, reported as a memory shortfall of -body_dx.
  const double deepest = 10.0 * std::max(across, 2.0 * r.body.horizon());
  SceneCheck(!outside || set->layers * b.dx <= deepest, r.comm,
             "-load_%s_%s is %d row(s), %g m deep, more than ten times the body's %s (%g m): a grip outside needs about two "
             "horizons (%g m, the default): give less", n, li.depth_set ? Format("depth %g m", li.depth).c_str() : "layers",
             set->layers, set->layers * b.dx, vertical ? "height" : "width", across, 2.0 * r.body.horizon());
  PetscCall(WarnShallowGrip(r.comm, li, set->layers, b.dx, r.body.horizon()));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckFace3D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const SolidSummary &b  = r.body.solid_summary; // (the extent)
  const double        dx = r.body.solid.dx;
  PetscFunctionBeginUser;
  PetscCall(CheckLayersDepth(r, "grip", "row"));
  set->layers         = li.depth_set ? GripRows(li.depth, dx) : static_cast<int>(li.layers);
  const int    axis   = EdgeAxis(set->region);
  const double across = b.hi[axis] - b.lo[axis];
  SceneCheck(set->layers * dx < across, r.comm, "-load_%s_layers %d is %g m deep, the whole body along %c (%g m): use fewer rows",
             li.name.c_str(), set->layers, set->layers * dx, "xyz"[axis], across);
  PetscCall(WarnShallowGrip(r.comm, li, set->layers, dx, r.body.horizon_factor * dx));
  PetscFunctionReturn(0);
}

// 2D: within `layers` rows of the edge, inside (between the edge and layers dx in; not
// the rows of other grips placed outside the sheet) or outside (beyond it). Layer
// boundaries fall half-way between lattice rows.
bool EdgeContains2D(const BodyExtent &b, const LoadSet &set, const double *p)
{
  const double depth = set.layers * b.dx;
  const int    axis  = EdgeAxis(set.region);
  const double q = p[axis], edge = EdgeUpper(set.region) ? b.hi[axis] : 0.0;
  if (set.placement == GripPlacement::outside) return EdgeUpper(set.region) ? q > edge && q < edge + depth : q < 0 && q > -depth;
  return EdgeUpper(set.region) ? q > edge - depth && q < edge : q < depth && q > 0;
}

// 3D: within `layers` rows of the body's extent (SolidSummary::lo, hi: lattice points sit
// (i + 1/2) dx inside it), as the 2D edges inside.
bool FaceContains3D(const BodyExtent &b, const LoadSet &set, const double *p)
{
  const double depth = set.layers * b.dx;
  const int    axis  = EdgeAxis(set.region);
  return EdgeUpper(set.region) ? p[axis] > b.hi[axis] - depth : p[axis] < b.lo[axis] + depth;
}

std::string EdgeText(const BodyExtent &s, const LoadSet &l)
{
  if (s.dimension != 3) return Format("%s edge, %d row(s) %s", to_string(l.region), l.layers, to_string(l.placement));
  const RegionType &r = region_type(l.region);
  return Format("%s face (%s), %d row(s) inside", r.alias, r.word, l.layers);
}

std::string EdgeEmpty(const BodyExtent &, const LoadSet &set)
{
  const char *n = set.name.c_str();
  return Format("-load_%s_region %s selects no material point for load set '%s' (its %d edge layer(s) hold none, e.g. cut away "
                "by a hole): raise -load_%s_layers or move the hole",
                n, to_string(set.region), n, set.layers, n);
}

} // namespace

RegionType edge_region(LoadSet::Region id, const char *word, const char *alias)
{
  const unsigned uses  = uses_layers | uses_depth;
  const bool     sheet = EdgeAxis(id) < 2; // (front and back, z: 3D only)
  return {id, word, alias, true, uses, uses, sheet ? CheckEdge2D : nullptr, CheckFace3D, sheet ? EdgeContains2D : nullptr,
          FaceContains3D, EdgeText, EdgeEmpty};
}

} // namespace bapd
