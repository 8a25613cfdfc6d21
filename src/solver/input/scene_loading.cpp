// The loading section: the grips (-load_sets, each set's -load_NAME_region, box,
// layers and components) and the stretch schedule (-load_schedule,
// -load_reference_length) that moves them. Which points a set holds at run time:
// LoadSetSelect (scene_selection.cpp).
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

bool ParseComponent(const std::string &text, ComponentLoad *load)
{
  const std::string t = Lower(text);
  if (t == "free") *load = ComponentLoad::free;
  else if (t == "fixed") *load = ComponentLoad::fixed;
  else if (t == "stretch") *load = ComponentLoad::stretch;
  else return false;
  return true;
}

const char *const kRegionChoices   = "top, bottom, left, right, box, polygon, curve, group or block";
const char *const kRegionChoices3D =
    "a face (left or x-, right or x+, bottom or y-, top or y+, back or z-, front or z+), box, group (a Gmsh physical group) or block";

bool IsFace(LoadSet::Region r)
{
  return r == LoadSet::Region::top || r == LoadSet::Region::bottom || r == LoadSet::Region::left || r == LoadSet::Region::right ||
         r == LoadSet::Region::front || r == LoadSet::Region::back;
}

// Region group: the physical group -load_S_group of -load_S_file (default: the body's
// one Gmsh file) as the set's area (a physical surface) or segments (a curve or points).
PetscErrorCode ReadGroup(MPI_Comm comm, const LoadInput &li, const Body2D &body, LoadSet *set)
{
  const char *n = li.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(!li.group.empty(), comm, "-load_%s_group is required with -load_%s_region group: give the name of a physical group of the Gmsh file%s",
             n, n, MisspeltHint("-load_" + li.name + "_group").c_str());
  set->file = li.file;
  if (set->file.empty()) {
    const std::vector<std::string> files = BodyGmshFiles(body);
    SceneCheck(files.size() == 1, comm,
               "-load_%s_file is required for load set '%s': the body reads %zu Gmsh files (mesh shapes), so the file of group '%s' "
               "is not implied: give the .geo or .msh that names it",
               n, n, files.size(), li.group.c_str());
    set->file = files[0];
  }
  set->group = li.group;
  GmshGroup         group;
  const std::string problem = ReadGmshGroup(set->file, li.group, &group);
  SceneCheck(problem.empty(), comm, "-load_%s_group %s: %s", n, li.group.c_str(), problem.c_str());
  if (group.dim == 2) {
    SceneCheck(!li.layers_set && !li.depth_set, comm,
               "-load_%s_%s is set but group '%s' is a physical surface: the set holds the points inside its elements; remove it (a "
               "depth applies to a physical curve or point)",
               n, li.layers_set ? "layers" : "depth", li.group.c_str());
    set->area.kind      = Shape::Kind::mesh;
    set->area.file      = set->file;
    set->area.triangles = std::move(group.triangles);
  } else set->segments = std::move(group.segments);
  PetscFunctionReturn(0);
}

// Region group of a 3D body: the physical group -load_S_group of -load_S_file (default:
// the body's one Gmsh volume) as an nd::ElementRegion: a physical volume holds the points
// inside its tetrahedra; a physical surface, curve or point the points closer than
// -load_S_depth (default -load_S_layers x dx, one layer) to its elements.
PetscErrorCode ReadGroup3D(MPI_Comm comm, const LoadInput &li, const Body3D &body, LoadSet *set)
{
  const char *n = li.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(!li.group.empty(), comm,
             "-load_%s_group is required with -load_%s_region group: give the name of a physical group of the Gmsh file (a Physical "
             "Surface for a face)%s",
             n, n, MisspeltHint("-load_" + li.name + "_group").c_str());
  set->file = li.file;
  if (set->file.empty()) {
    const std::vector<std::string> files = BodyGmshFiles(body);
    SceneCheck(files.size() == 1, comm,
               "-load_%s_file is required for load set '%s': the body reads %zu Gmsh files (mesh solids), so the file of group '%s' is "
               "not implied: give the .geo or .msh that names it",
               n, n, files.size(), li.group.c_str());
    set->file = files[0];
  }
  set->group = li.group;
  SceneCheck(!(li.layers_set && li.depth_set), comm, "-load_%s_layers and -load_%s_depth both give the set's depth: keep one (rows, or metres)",
             n, n);
  SceneCheck(!li.depth_set || li.depth > 0, comm, "-load_%s_depth %g m: a depth must be > 0", n, li.depth);
  SceneCheck(li.layers >= 1, comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point layer", n, li.layers);
  set->depth                = li.depth_set ? li.depth : static_cast<double>(li.layers) * body.solid.dx;
  const std::string problem = ReadGmshGroup3D(set->file, li.group, set->depth, &set->elements);
  SceneCheck(problem.empty(), comm, "-load_%s_group %s: %s", n, li.group.c_str(), problem.c_str());
  SceneCheck(set->elements.dim < 3 || !(li.layers_set || li.depth_set), comm,
             "-load_%s_%s is set but group '%s' is a physical volume: the set holds the points inside its elements; remove it (a depth "
             "applies to a physical surface, curve or point)",
             n, li.layers_set ? "layers" : "depth", li.group.c_str());
  PetscFunctionReturn(0);
}

// Region block: the given points of block id -load_S_block (the cloud's block column;
// a 2D cloud's, or a 3D one's).
PetscErrorCode ReadBlock(MPI_Comm comm, const LoadInput &li, const Scene &scene, LoadSet *set)
{
  const char   *n     = li.name.c_str();
  const bool    three = scene.dimension == 3;
  const Body2D &b2    = scene.body;
  const Body3D &b3    = scene.body3d;
  PetscFunctionBeginUser;
  SceneCheck(li.block_set, comm, "-load_%s_block is required with -load_%s_region block: give a block id of the point cloud%s", n, n,
             MisspeltHint("-load_" + li.name + "_block").c_str());
  SceneCheck(three ? b3.given_points != nullptr : b2.given_points != nullptr, comm,
             "-load_%s_region block: block ids come with the points of a cloud (-body_cloud, column block_id), and this body is a "
             "lattice: choose %s",
             n, three ? "a face or a box" : "another region (box, polygon, curve, group)");
  set->block        = static_cast<int64_t>(li.block);
  set->block_points = three ? BlockPoints3D(b3.given_points->x, b3.given_block, set->block) : BlockPoints(b2, set->block);
  SceneCheck(!set->block_points.empty(), comm,
             "-load_%s_block %" PetscInt_FMT ": no point of '%s' has block id %" PetscInt_FMT " (its block ids: %s): give one of them", n,
             li.block, three ? b3.source.c_str() : b2.given_points->source.c_str(), li.block,
             (three ? BlockIdList(b3.given_block) : BlockIdList(b2)).c_str());
  PetscFunctionReturn(0);
}

// The region word (case-insensitive; the faces also as x-, x+, y-, y+, z-, z+).
bool ParseRegion(const std::string &text, LoadSet::Region *region)
{
  static const struct {
    const char     *word;
    LoadSet::Region region;
  } words[] = {{"top", LoadSet::Region::top},       {"y+", LoadSet::Region::top},         {"bottom", LoadSet::Region::bottom},
               {"y-", LoadSet::Region::bottom},     {"left", LoadSet::Region::left},      {"x-", LoadSet::Region::left},
               {"right", LoadSet::Region::right},   {"x+", LoadSet::Region::right},       {"front", LoadSet::Region::front},
               {"z+", LoadSet::Region::front},      {"back", LoadSet::Region::back},      {"z-", LoadSet::Region::back},
               {"box", LoadSet::Region::box},       {"polygon", LoadSet::Region::polygon}, {"curve", LoadSet::Region::curve},
               {"group", LoadSet::Region::group},   {"block", LoadSet::Region::block}};
  const std::string t = Lower(text);
  for (const auto &w : words)
    if (t == w.word) {
      *region = w.region;
      return true;
    }
  return false;
}

// One load set of a 3D body (Scene::dimension 3): a face of the body's extent (inside,
// `layers` rows deep), a box of six numbers, or a block id of a 3D cloud.
PetscErrorCode CheckLoadSet3D(MPI_Comm comm, const LoadInput &li, const SceneInput &in, const Scene &scene, LoadSet *set)
{
  const char   *n = li.name.c_str();
  const Body3D &b = scene.body3d;
  const double  dx = b.solid.dx;
  PetscFunctionBeginUser;
  SceneCheck(set->region != LoadSet::Region::polygon && set->region != LoadSet::Region::curve, comm,
             "-load_%s_region %s is a 2D region (a shape in the sheet's plane), and this body is 3D: choose %s", n, to_string(set->region),
             kRegionChoices3D);
  const bool face = IsFace(set->region), group = set->region == LoadSet::Region::group;
  for (const auto &[given, option, fits, which] :
       {std::tuple{li.box_set, "box", set->region == LoadSet::Region::box, "region box"},
        {li.points_set, "points", false, "the 2D regions polygon and curve"},
        {!li.group.empty(), "group", group, "region group"},
        {!li.file.empty(), "file", group, "region group"},
        {li.block_set, "block", set->region == LoadSet::Region::block, "region block"},
        {li.layers_set, "layers", face || group, "the faces and group"},
        {li.depth_set, "depth", face || group, "the faces and group"}})
    SceneCheck(!given || fits, comm, "-load_%s_%s is set but -load_%s_region is %s: it is used by %s only; remove it or change the region", n,
               option, n, to_string(set->region), which);
  // The faces of a 3D body hold its own points: there are no grip rows outside it.
  const std::string placement = Lower(li.placement);
  SceneCheck(placement == "auto" || placement == "inside", comm,
             "-load_%s_placement %s: a 3D body's load sets hold its own points (inside); grips outside the specimen are 2D only: "
             "remove it, or set it to inside",
             n, li.placement.c_str());
  SceneCheck(!in.grip_placement_set || Lower(in.grip_placement) == "inside", comm,
             "-load_grip_placement %s: a 3D body's load sets hold its own points (inside); grips outside the specimen are 2D only: "
             "remove it, or set it to inside",
             in.grip_placement.c_str());
  set->placement = GripPlacement::inside;
  if (set->region == LoadSet::Region::box) {
    SceneCheck(li.box_set, comm, "-load_%s_box is required with -load_%s_region box: give xmin,ymin,zmin,xmax,ymax,zmax in m%s", n, n,
               MisspeltHint("-load_" + li.name + "_box").c_str());
    SceneCheck(li.box.size() == 6, comm, "-load_%s_box holds %zu numbers: a 3D box takes exactly six, xmin,ymin,zmin,xmax,ymax,zmax in m", n,
               li.box.size());
    std::copy(li.box.begin(), li.box.end(), set->box);
    SceneCheck(set->box[0] < set->box[3] && set->box[1] < set->box[4] && set->box[2] < set->box[5], comm,
               "-load_%s_box %g,%g,%g,%g,%g,%g is empty: the order is xmin,ymin,zmin,xmax,ymax,zmax with each min < max", n, set->box[0],
               set->box[1], set->box[2], set->box[3], set->box[4], set->box[5]);
    bool meets = true;
    for (int r = 0; r < 3; ++r) meets = meets && set->box[3 + r] >= b.lo[r] && set->box[r] <= b.hi[r];
    SceneCheck(meets, comm,
               "-load_%s_box %g,%g,%g,%g,%g,%g lies outside the body [%g, %g] x [%g, %g] x [%g, %g] m: move it onto the body", n,
               set->box[0], set->box[1], set->box[2], set->box[3], set->box[4], set->box[5], b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2],
               b.hi[2]);
  } else if (set->region == LoadSet::Region::block) {
    PetscCall(ReadBlock(comm, li, scene, set));
  } else if (group) {
    PetscCall(ReadGroup3D(comm, li, b, set));
  } else {
    SceneCheck(!(li.layers_set && li.depth_set), comm,
               "-load_%s_layers and -load_%s_depth both give the grip's depth: keep one (rows, or metres)", n, n);
    SceneCheck(!li.depth_set || li.depth > 0, comm, "-load_%s_depth %g m: a grip's depth must be > 0", n, li.depth);
    SceneCheck(li.layers >= 1, comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point row", n, li.layers);
    set->layers = li.depth_set ? GripRows(li.depth, dx) : static_cast<int>(li.layers);
    const int    axis   = set->region == LoadSet::Region::left || set->region == LoadSet::Region::right    ? 0
                          : set->region == LoadSet::Region::bottom || set->region == LoadSet::Region::top ? 1
                                                                                                           : 2;
    const double across = b.hi[axis] - b.lo[axis];
    SceneCheck(set->layers * dx < across, comm,
               "-load_%s_layers %d is %g m deep, the whole body along %c (%g m): use fewer rows", n, set->layers, set->layers * dx,
               "xyz"[axis], across);
  }
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ReadLoading(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Loading: grips (load sets) following a stretch schedule", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.StringArray("-load_sets", "Names of the load sets name1,name2,... (each set S is configured by -load_S_...)", &in->load_names));
    PetscCall(r.RealArray("-load_schedule", "Stretch schedule t0,lambda0,t1,lambda1,... [s, -], piecewise linear (default: none)", &in->schedule,
                          &in->schedule_set));
    PetscCall(r.Real("-load_reference_length", "Length L in u = scale (lambda - 1) L [m] (default: body height)", &scene->reference_length,
                     &in->reference_length_set));
    PetscCall(r.String("-load_grip_placement",
                       "Where edge grips are, unless a set says: outside (clamps added beyond the specimen, which is the free "
                       "region) | inside (the specimen's edge rows: the paper's grips)",
                       &in->grip_placement, &in->grip_placement_set));
    PetscCall(r.String("-load_grip_field",
                       "y of the top and bottom grips' points (or of two region grips, the top one above): rigid (one u per grip) | affine (the continuation of the free "
                       "region's mean stretch into the grip; docs/stress_consistency.md) | auto (affine for a top and a bottom "
                       "grip outside, else rigid)",
                       &in->grip_field, &in->grip_field_set));
    return 0;
  }));
  PetscCall(CheckNames(comm, in->load_names, "-load_sets", "load set"));

  for (const std::string &name : in->load_names) {
    LoadInput         set;
    const std::string prefix = "load_" + name + "_";
    const std::string title  = "Load set " + name;
    set.name                 = name;
    PetscCall(ReadOptionBlock(comm, prefix.c_str(), title.c_str(), [&](OptionReader &r) -> PetscErrorCode {
      PetscCall(r.String("-region",
                         "Points held: top | bottom | left | right (edge layers; 3D: faces, with back | front, or x- | x+ | y- | y+ | z- | "
                         "z+) | box | polygon | curve (points near a polyline) | group (a Gmsh physical group) | block (a block id of "
                         "the point cloud) (required)",
                         &set.region, &set.region_set));
      PetscCall(r.RealArray("-box", "Region box xmin,ymin,xmax,ymax [m] (3D: xmin,ymin,zmin,xmax,ymax,zmax)", &set.box, &set.box_set));
      PetscCall(r.RealArray("-points", "Region polygon (closed) or curve (open polyline): vertices x0,y0,x1,y1,... [m]", &set.points,
                            &set.points_set));
      PetscCall(r.String("-group", "Region group: the name of a physical surface, curve or point of the Gmsh file (3D: also a volume)", &set.group));
      PetscCall(r.String("-file", "Region group: the Gmsh .geo or .msh file (default: the body's mesh shape's file; 3D: its mesh solid's)", &set.file));
      PetscCall(r.Int("-block", "Region block: the block id (-body_cloud's block_id column) whose points the set holds", &set.block, &set.block_set));
      PetscCall(r.String("-placement", "outside (beyond the specimen's edge) | inside (the specimen's edge rows) | auto (-load_grip_placement's); edge "
                         "regions (the others are inside)",
                         &set.placement));
      PetscCall(r.Int("-layers",
                      "Point rows the grip holds at its edge [-] (default: 2 horizons deep outside, 1 inside); curve and group "
                      "curve/point (3D: also surface): the points closer than layers x dx",
                      &set.layers, &set.layers_set));
      PetscCall(r.Real("-depth",
                       "Grip depth instead of -layers: the rows whose centres lie within it [m] (default outside: 2 horizons); curve "
                       "and group curve/point (3D: also surface): the points closer than it (default dx)",
                       &set.depth, &set.depth_set));
      PetscCall(r.String("-x", "x component: free | fixed (u = 0) | stretch (follows the schedule)", &set.x));
      PetscCall(r.String("-y", "y component: free | fixed (u = 0) | stretch (follows the schedule)", &set.y));
      PetscCall(r.String("-z", "z component (3D bodies): free | fixed (u = 0) | stretch (follows the schedule)", &set.z));
      PetscCall(r.Real("-x_scale", "Scale of a stretch x component: u = scale (lambda - 1) L [-]", &set.x_scale, &set.x_scale_set));
      PetscCall(r.Real("-y_scale", "Scale of a stretch y component: u = scale (lambda - 1) L [-]", &set.y_scale, &set.y_scale_set));
      PetscCall(r.Real("-z_scale", "Scale of a stretch z component (3D bodies): u = scale (lambda - 1) L [-]", &set.z_scale, &set.z_scale_set));
      return 0;
    }));
    in->loads.push_back(set);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckLoading(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  const Body2D &b = scene->body;
  Schedule     &schedule = scene->schedule;
  PetscFunctionBeginUser;
  // The schedule: pairs (t, lambda), times strictly increasing from t >= 0.
  schedule.time.clear();
  schedule.stretch.clear();
  if (in.schedule_set) {
    SceneCheck(!in.schedule.empty() && in.schedule.size() % 2 == 0, comm,
               "-load_schedule holds %zu numbers: give pairs time,stretch t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda from 1 "
               "to 2 over 10 s)",
               in.schedule.size());
    for (std::size_t k = 0; 2 * k < in.schedule.size(); ++k) {
      const double t = in.schedule[2 * k], lambda = in.schedule[2 * k + 1];
      SceneCheck(t >= 0, comm, "-load_schedule: knot %zu has time %g s: times count from the start of the run, t >= 0", k + 1, t);
      if (k > 0)
        SceneCheck(t > schedule.time.back(), comm,
                   "-load_schedule: times must increase strictly, but knot %zu has t = %g s after t = %g s: a hold is two knots with "
                   "the same stretch at different times",
                   k + 1, t, schedule.time.back());
      SceneCheck(lambda > 0, comm, "-load_schedule: knot %zu has stretch %g: a stretch (current / initial length) must be > 0",
                 k + 1, lambda);
      schedule.time.push_back(t);
      schedule.stretch.push_back(lambda);
    }
    if (std::fabs(schedule.stretch_at(0.0) - 1.0) > 1e-12)
      PetscCall(Warn(comm, Format("-load_schedule starts at stretch %g, not 1: the grips jump at t = 0", schedule.stretch_at(0.0))));
  }
  // The free length: the specimen's height between grips outside it; the whole
  // height (grip rows included) for the paper's grips inside it.
  if (in.reference_length_set)
    SceneCheck(scene->reference_length > 0, comm,
               "-load_reference_length %g: the length that turns stretch into displacement must be > 0 m (default: the body height)",
               scene->reference_length);
  else scene->reference_length = scene->dimension == 3 ? scene->body3d.hi[1] - scene->body3d.lo[1] : b.height; // (3D: the extent along y)

  GripPlacement     default_placement = GripPlacement::outside;
  const std::string placement_all     = Lower(in.grip_placement);
  if (placement_all == "inside") default_placement = GripPlacement::inside;
  else SceneCheck(placement_all == "outside", comm, "-load_grip_placement '%s' is not a choice: choose outside or inside",
                  in.grip_placement.c_str());
  scene->body.grip_rows = {};
  scene->loads.clear();
  for (const LoadInput &li : in.loads) {
    LoadSet     set;
    const char *n = li.name.c_str();
    set.name      = li.name;
    const bool  three = scene->dimension == 3;
    const char *choices = three ? kRegionChoices3D : kRegionChoices;
    SceneCheck(li.region_set, comm, "-load_%s_region is required for load set '%s': choose %s%s", n, n, choices,
               MisspeltHint("-load_" + li.name + "_region").c_str());
    if (!ParseRegion(li.region, &set.region))
      SETERRQ(comm, PETSC_ERR_USER, "%s", Format("-load_%s_region '%s' is not a region: choose %s", n, li.region.c_str(), choices).c_str());
    SceneCheck(three || (set.region != LoadSet::Region::front && set.region != LoadSet::Region::back), comm,
               "-load_%s_region %s is a face of a 3D body (z), and this body is a 2D sheet: choose %s (or make the body 3D, "
               "-body_dimension 3)",
               n, li.region.c_str(), kRegionChoices);
    if (three) PetscCall(CheckLoadSet3D(comm, li, in, *scene, &set));
    const bool edge = set.region == LoadSet::Region::top || set.region == LoadSet::Region::bottom ||
                      set.region == LoadSet::Region::left || set.region == LoadSet::Region::right;
    // Each option belongs to some regions; one given to another region is a mistake.
    if (!three) {
    const bool curve_like = set.region == LoadSet::Region::curve || set.region == LoadSet::Region::group; // (a group may be a curve)
    for (const auto &[given, option, fits, which] :
         {std::tuple{li.box_set, "box", set.region == LoadSet::Region::box, "region box"},
          {li.points_set, "points", set.region == LoadSet::Region::polygon || set.region == LoadSet::Region::curve, "regions polygon and curve"},
          {!li.group.empty(), "group", set.region == LoadSet::Region::group, "region group"},
          {!li.file.empty(), "file", set.region == LoadSet::Region::group, "region group"},
          {li.block_set, "block", set.region == LoadSet::Region::block, "region block"},
          {li.layers_set, "layers", edge || curve_like, "edge regions, curve and group"},
          {li.depth_set, "depth", edge || curve_like, "edge regions, curve and group"}})
      SceneCheck(!given || fits, comm, "-load_%s_%s is set but -load_%s_region is %s: it is used by %s only; remove it or change the region",
                 n, option, n, to_string(set.region), which);
    if (!edge) {
      // A box, polygon, curve or group holds the body's own points: there is nothing
      // beyond an edge to add for it.
      const std::string placement = Lower(li.placement);
      SceneCheck(placement == "auto" || placement == "inside", comm,
                 "-load_%s_placement %s: load set '%s' is a %s, which holds the body's own points (inside); only the edge regions "
                 "top, bottom, left and right add grip rows outside the body: remove it, or set it to inside",
                 n, li.placement.c_str(), n, to_string(set.region));
      SceneCheck(!(li.layers_set && li.depth_set), comm, "-load_%s_layers and -load_%s_depth both give the set's depth: keep one (rows, or metres)",
                 n, n);
      SceneCheck(!li.depth_set || li.depth > 0, comm, "-load_%s_depth %g m: a depth must be > 0", n, li.depth);
      SceneCheck(li.layers >= 1, comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point row", n, li.layers);
      set.depth = li.depth_set ? li.depth : static_cast<double>(li.layers) * b.dx;
    }
    if (set.region == LoadSet::Region::box) {
      SceneCheck(li.box_set, comm, "-load_%s_box is required with -load_%s_region box: give xmin,ymin,xmax,ymax in m%s", n, n,
                 MisspeltHint("-load_" + li.name + "_box").c_str());
      SceneCheck(li.box.size() == 4, comm, "-load_%s_box holds %zu numbers: give exactly four, xmin,ymin,xmax,ymax in m", n,
                 li.box.size());
      std::copy(li.box.begin(), li.box.end(), set.box);
      SceneCheck(set.box[0] < set.box[2] && set.box[1] < set.box[3], comm,
                 "-load_%s_box %g,%g,%g,%g is empty: the order is xmin,ymin,xmax,ymax with xmin < xmax and ymin < ymax", n, set.box[0],
                 set.box[1], set.box[2], set.box[3]);
      SceneCheck(set.box[2] >= 0 && set.box[0] <= b.width && set.box[3] >= 0 && set.box[1] <= b.height, comm,
                 "-load_%s_box %g,%g,%g,%g lies outside the body [0, %g] x [0, %g] m: move it onto the body", n, set.box[0], set.box[1],
                 set.box[2], set.box[3], b.width, b.height);
    } else if (set.region == LoadSet::Region::polygon || set.region == LoadSet::Region::curve) {
      const bool        polygon = set.region == LoadSet::Region::polygon;
      const std::size_t fewest  = polygon ? 3 : 2;
      SceneCheck(li.points_set, comm, "-load_%s_points is required with -load_%s_region %s: give the vertices x0,y0,x1,y1,... in m%s", n,
                 n, to_string(set.region), MisspeltHint("-load_" + li.name + "_points").c_str());
      SceneCheck(li.points.size() % 2 == 0 && li.points.size() >= 2 * fewest, comm,
                 "-load_%s_points holds %zu numbers: give x,y pairs, at least %zu vertices for a %s", n, li.points.size(), fewest,
                 to_string(set.region));
      if (polygon) {
        set.area.kind     = Shape::Kind::polygon;
        set.area.vertices = li.points;
        const std::string problem = polygon_problem(li.points);
        SceneCheck(problem.empty(), comm, "-load_%s_points (the polygon of load set '%s'): %s; give its vertices in order around it (it closes by itself)",
                   n, n, problem.c_str());
      } else
        for (std::size_t k = 0; k + 4 <= li.points.size(); k += 2) set.segments.insert(set.segments.end(), &li.points[k], &li.points[k + 4]);
      double lo[2] = {li.points[0], li.points[1]}, hi[2] = {li.points[0], li.points[1]};
      for (std::size_t k = 0; k < li.points.size(); ++k) lo[k % 2] = std::min(lo[k % 2], li.points[k]), hi[k % 2] = std::max(hi[k % 2], li.points[k]);
      const double grow = polygon ? 0.0 : set.depth;
      SceneCheck(hi[0] + grow >= 0 && lo[0] - grow <= b.width && hi[1] + grow >= 0 && lo[1] - grow <= b.height, comm,
                 "-load_%s_points: the %s of load set '%s' lies outside the body [0, %g] x [0, %g] m: move it onto the body", n,
                 to_string(set.region), n, b.width, b.height);
    } else if (set.region == LoadSet::Region::group) {
      PetscCall(ReadGroup(comm, li, b, &set));
    } else if (set.region == LoadSet::Region::block) {
      PetscCall(ReadBlock(comm, li, *scene, &set));
    } else {
      const std::string placement = Lower(li.placement) == "auto" ? to_string(default_placement) : Lower(li.placement);
      if (placement == "outside") set.placement = GripPlacement::outside;
      else if (placement == "inside") set.placement = GripPlacement::inside;
      else SceneCheck(false, comm, "-load_%s_placement '%s' is not a choice: choose outside, inside or auto", n, li.placement.c_str());
      // A grip outside extrudes the edge row of the lattice; given points have no rows.
      SceneCheck(set.placement == GripPlacement::inside || !b.given_points, comm,
                 "-load_%s_placement %s: a grip outside the specimen extrudes the lattice's edge rows, which given points (-body_cloud, "
                 "-body_S_discretisation centroids) do not have: place it inside (-load_%s_placement inside, or -load_grip_placement "
                 "inside for every grip)",
                 n, Lower(li.placement) == "auto" ? "outside (the default)" : "outside", n);
      SceneCheck(!(li.layers_set && li.depth_set), comm,
                 "-load_%s_layers and -load_%s_depth both give the grip's depth: keep one (rows, or metres)", n, n);
      SceneCheck(!li.depth_set || li.depth > 0, comm, "-load_%s_depth %g m: a grip's depth must be > 0", n, li.depth);
      SceneCheck(li.layers >= 1, comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point row", n, li.layers);
      const bool outside = set.placement == GripPlacement::outside;
      if (li.depth_set) set.layers = GripRows(li.depth, b.dx);
      else if (li.layers_set || !outside) set.layers = static_cast<int>(li.layers);
      else set.layers = GripRows(2.0 * scene->horizon(), b.dx);
      const bool   vertical = set.region == LoadSet::Region::top || set.region == LoadSet::Region::bottom;
      const double across   = vertical ? b.height : b.width;
      SceneCheck(outside || set.layers * b.dx < across, comm,
                 "-load_%s_layers %d (placement inside) is %g m deep, the whole body %s (%g m): use fewer rows, or place the grip "
                 "outside (-load_%s_placement outside)",
                 n, set.layers, set.layers * b.dx, vertical ? "height" : "width", across, n);
      if (outside) {
        int64_t &rows = set.region == LoadSet::Region::top      ? scene->body.grip_rows.top
                        : set.region == LoadSet::Region::bottom ? scene->body.grip_rows.bottom
                        : set.region == LoadSet::Region::left   ? scene->body.grip_rows.left
                                                                : scene->body.grip_rows.right;
        rows = std::max<int64_t>(rows, set.layers);
      }
    }
    } // (2D)
    if (!set.segments.empty()) SetCurveReach(&set);

    SceneCheck(ParseComponent(li.x, &set.x), comm, "-load_%s_x '%s' is not a choice: choose free, fixed or stretch", n, li.x.c_str());
    SceneCheck(ParseComponent(li.y, &set.y), comm, "-load_%s_y '%s' is not a choice: choose free, fixed or stretch", n, li.y.c_str());
    SceneCheck(ParseComponent(li.z, &set.z), comm, "-load_%s_z '%s' is not a choice: choose free, fixed or stretch", n, li.z.c_str());
    SceneCheck(three || (set.z == ComponentLoad::free && !li.z_scale_set), comm,
               "-load_%s_z%s is set, but this body is a 2D sheet (x, y): remove it, or make the body 3D (-body_dimension 3)", n,
               li.z_scale_set ? "_scale" : "");
    for (int c = 0; c < scene->dimension; ++c) {
      const char          axis  = "xyz"[c];
      const ComponentLoad load  = set.component(c);
      const bool          given = c == 0 ? li.x_scale_set : c == 1 ? li.y_scale_set : li.z_scale_set;
      const double        scale = c == 0 ? li.x_scale : c == 1 ? li.y_scale : li.z_scale;
      SceneCheck(load == ComponentLoad::stretch || !given, comm,
                 "-load_%s_%c_scale is set but -load_%s_%c is %s: the scale applies to a stretch component only; remove it or set "
                 "-load_%s_%c stretch",
                 n, axis, n, axis, to_string(load), n, axis);
      if (load != ComponentLoad::stretch) continue;
      SceneCheck(!schedule.time.empty(), comm,
                 "-load_%s_%c stretch needs a stretch schedule: give -load_schedule t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda "
                 "from 1 to 2 over 10 s)%s",
                 n, axis, MisspeltHint("-load_schedule").c_str());
      if (scale == 0.0)
        PetscCall(Warn(comm, Format("-load_%s_%c_scale is 0: the stretch component never moves (same as -load_%s_%c fixed)", n, axis, n, axis)));
      (c == 0 ? set.x_scale : c == 1 ? set.y_scale : set.z_scale) = scale;
    }
    if (three && set.x == ComponentLoad::free && set.y == ComponentLoad::free && set.z == ComponentLoad::free)
      PetscCall(Warn(comm, Format("load set '%s' holds no component (-load_%s_x, -load_%s_y and -load_%s_z are free): it does nothing; set "
                                  "one of them to fixed or stretch",
                                  n, n, n, n)));
    else if (!three && set.x == ComponentLoad::free && set.y == ComponentLoad::free)
      PetscCall(Warn(comm, Format("load set '%s' holds neither component (-load_%s_x and -load_%s_y are free): it does nothing; set "
                                  "one of them to fixed or stretch",
                                  n, n, n)));
    scene->loads.push_back(set);
  }
  int top = 0, bottom = 0, outside = 0, edges = 0, regions = 0; // the sets holding y at the top and bottom edges, and elsewhere
  for (const LoadSet &l : scene->loads) {
    if (l.y == ComponentLoad::free) continue;
    const bool is_edge = IsFace(l.region); // (an edge of a sheet, a face of a 3D body)
    edges += is_edge;
    regions += !is_edge;
    top += l.region == LoadSet::Region::top;
    bottom += l.region == LoadSet::Region::bottom;
    outside += (l.region == LoadSet::Region::top || l.region == LoadSet::Region::bottom) && l.placement == GripPlacement::outside;
  }
  const std::string field = Lower(in.grip_field);
  // The default: affine where it applies, to a top and a bottom grip outside (a 3D
  // body's grips are its own points: rigid unless asked, as region grips in 2D).
  if (field == "auto")
    scene->grip_field = top == 1 && bottom == 1 && outside == 2 ? GripField::affine : GripField::rigid;
  else if (field == "rigid") scene->grip_field = GripField::rigid;
  else if (field == "affine") scene->grip_field = GripField::affine;
  else SETERRQ(comm, PETSC_ERR_USER, "%s", Format("-load_grip_field '%s' is not a choice: choose rigid, affine or auto", in.grip_field.c_str()).c_str());
  if (scene->grip_field == GripField::affine) {
    // Edge grips: one top and one bottom. Region grips (any shape: the outside
    // treatment's equivalent, Loading::SetAffineLevers): exactly two sets hold y, and
    // no edge set does; which is the top one is found from their points at setup.
    SceneCheck((top == 1 && bottom == 1) || (edges == 0 && regions == 2), comm,
               "-load_grip_field affine continues the stretch between a top and a bottom grip, but the load sets hold y at %d top "
               "and %d bottom edge(s) (%d edges in all) and %d other region(s): give exactly one of each edge (-load_NAME_region top|bottom with "
               "-load_NAME_y fixed or stretch), or exactly two regions and no edge (a box, polygon, curve, group or block above "
               "the other), or use -load_grip_field rigid",
               top, bottom, edges, regions);
  }
  PetscFunctionReturn(0);
}

const char *to_string(LoadSet::Region region)
{
  switch (region) {
  case LoadSet::Region::top: return "top";
  case LoadSet::Region::bottom: return "bottom";
  case LoadSet::Region::left: return "left";
  case LoadSet::Region::right: return "right";
  case LoadSet::Region::box: return "box";
  case LoadSet::Region::polygon: return "polygon";
  case LoadSet::Region::curve: return "curve";
  case LoadSet::Region::group: return "group";
  case LoadSet::Region::block: return "block";
  case LoadSet::Region::front: return "front";
  case LoadSet::Region::back: return "back";
  }
  return "unknown";
}

int GripRows(double depth, double dx)
{
  // Row j's centre lies (j + 1/2) dx from the edge; 1e-9: a depth of whole rows given
  // in metres (6 x 0.5 mm) keeps its rows despite round-off.
  return std::max(1, static_cast<int>(std::ceil(depth / dx - 0.5 - 1e-9)));
}

const char *to_string(GripPlacement placement) { return placement == GripPlacement::outside ? "outside" : "inside"; }

const char *to_string(GripField field) { return field == GripField::affine ? "affine" : "rigid"; }

const char *to_string(ComponentLoad load)
{
  switch (load) {
  case ComponentLoad::free: return "free";
  case ComponentLoad::fixed: return "fixed";
  case ComponentLoad::stretch: return "stretch";
  }
  return "unknown";
}

std::vector<std::string> BodyGmshFiles(const Body2D &body)
{
  std::vector<std::string> files;
  for (const Shape &s : body.shapes)
    if (s.kind == Shape::Kind::mesh && std::find(files.begin(), files.end(), s.file) == files.end()) files.push_back(s.file);
  return files;
}

std::vector<std::string> BodyGmshFiles(const Body3D &body)
{
  std::vector<std::string> files;
  for (const nd::Solid &s : body.solid.solids)
    if (s.kind == nd::Solid::Kind::mesh && std::find(files.begin(), files.end(), s.mesh->file) == files.end()) files.push_back(s.mesh->file);
  return files;
}

} // namespace bapd
