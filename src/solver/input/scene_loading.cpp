// The loading section: the grips (-load_sets, each set's -load_NAME_region, box,
// layers and components) and the stretch schedule (-load_schedule,
// -load_reference_length) that moves them. Each region's own options, points and
// summary: its region type (regions/, region_registry.hpp). Which points a set holds
// at run time: LoadSetSelect (scene_selection.cpp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
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

// One load set's options (-load_NAME_...), in -help's order.
const OptionTable<LoadInput> kLoadSetOptions = {
    {"-region", RegionHelp(), &LoadInput::region, &LoadInput::region_set}, // (the words of the region registry)
    {"-box", "Region box xmin,ymin,xmax,ymax [m] (3D: xmin,ymin,zmin,xmax,ymax,zmax)", &LoadInput::box, &LoadInput::box_set},
    {"-points", "Region polygon (closed) or curve (open polyline): vertices x0,y0,x1,y1,... [m]", &LoadInput::points, &LoadInput::points_set},
    {"-group", "Region group: the name of a physical surface, curve or point of the Gmsh file (3D: also a volume)", &LoadInput::group},
    {"-file", "Region group: the Gmsh .geo or .msh file (default: the body's mesh shape's file; 3D: its mesh solid's)", &LoadInput::file},
    {"-block", "Region block: the block id (-body_cloud's block_id column) whose points the set holds", &LoadInput::block, &LoadInput::block_set},
    {"-placement",
     "outside (beyond the specimen's edge) | inside (the specimen's edge rows) | auto (-load_grip_placement's); edge "
     "regions (the others are inside)",
     &LoadInput::placement},
    {"-layers",
     "Point rows the grip holds at its edge [-] (default: 2 horizons deep outside, 1 inside); curve and group "
     "curve/point (3D: also surface): the points closer than layers x dx",
     &LoadInput::layers, &LoadInput::layers_set},
    {"-depth",
     "Grip depth instead of -layers: the rows whose centres lie within it [m] (default outside: 2 horizons); curve "
     "and group curve/point (3D: also surface): the points closer than it (default dx)",
     &LoadInput::depth, &LoadInput::depth_set},
    {"-x", "x component: free | fixed (u = 0) | stretch (follows the schedule)", &LoadInput::x},
    {"-y", "y component: free | fixed (u = 0) | stretch (follows the schedule)", &LoadInput::y},
    {"-z", "z component (3D bodies): free | fixed (u = 0) | stretch (follows the schedule)", &LoadInput::z},
    {"-x_scale", "Scale of a stretch x component: u = scale (lambda - 1) L [-]", &LoadInput::x_scale, &LoadInput::x_scale_set},
    {"-y_scale", "Scale of a stretch y component: u = scale (lambda - 1) L [-]", &LoadInput::y_scale, &LoadInput::y_scale_set},
    {"-z_scale", "Scale of a stretch z component (3D bodies): u = scale (lambda - 1) L [-]", &LoadInput::z_scale, &LoadInput::z_scale_set},
};

PetscErrorCode ReadLoadSet(MPI_Comm comm, const std::string &name, LoadInput *set)
{
  const std::string prefix = "load_" + name + "_";
  const std::string title  = "Load set " + name;
  PetscFunctionBeginUser;
  set->name = name;
  PetscCall(ReadOptionBlock(comm, prefix.c_str(), title.c_str(), [&](OptionReader &r) { return ReadOptionRows(r, kLoadSetOptions, set); }));
  PetscFunctionReturn(0);
}

// The schedule: pairs (t, lambda), times strictly increasing from t >= 0.
PetscErrorCode CheckSchedule(MPI_Comm comm, const SceneInput &in, Schedule *schedule)
{
  PetscFunctionBeginUser;
  schedule->time.clear();
  schedule->stretch.clear();
  if (!in.schedule_set) PetscFunctionReturn(0);
  SceneCheck(!in.schedule.empty() && in.schedule.size() % 2 == 0, comm,
             "-load_schedule holds %zu numbers: give pairs time,stretch t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda from 1 "
             "to 2 over 10 s)",
             in.schedule.size());
  for (std::size_t k = 0; 2 * k < in.schedule.size(); ++k) {
    const double t = in.schedule[2 * k], lambda = in.schedule[2 * k + 1];
    SceneCheck(t >= 0, comm, "-load_schedule: knot %zu has time %g s: times count from the start of the run, t >= 0", k + 1, t);
    if (k > 0)
      SceneCheck(t > schedule->time.back(), comm,
                 "-load_schedule: times must increase strictly, but knot %zu has t = %g s after t = %g s: a hold is two knots with "
                 "the same stretch at different times",
                 k + 1, t, schedule->time.back());
    SceneCheck(lambda > 0, comm, "-load_schedule: knot %zu has stretch %g: a stretch (current / initial length) must be > 0", k + 1,
               lambda);
    schedule->time.push_back(t);
    schedule->stretch.push_back(lambda);
  }
  if (std::fabs(schedule->stretch_at(0.0) - 1.0) > 1e-12)
    PetscCall(Warn(comm, Format("-load_schedule starts at stretch %g, not 1: the grips jump at t = 0", schedule->stretch_at(0.0))));
  PetscFunctionReturn(0);
}

// The regions that read a per-set option (RegionType::uses2d or uses3d has `bit`), for
// the message when another region is given it: "region box", "regions polygon and
// curve", "edge regions, curve and group" (3D: "the faces and group"); in 3D, when no
// region reads it there, the 2D ones ("the 2D regions polygon and curve").
std::string RegionsReading(unsigned bit, bool three)
{
  std::vector<std::string> names;
  bool                     edges = false;
  for (const RegionType &r : registered_regions()) {
    if (!((three ? r.uses3d : r.uses2d) & bit) || !(three ? r.check3d != nullptr : r.check2d != nullptr)) continue;
    if (r.edge) edges = true;
    else names.push_back(r.word);
  }
  if (three && !edges && names.empty()) return "the 2D " + RegionsReading(bit, false);
  std::string list;
  for (std::size_t k = 0; k < names.size(); ++k) list += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  if (edges) return (three ? "the faces" : "edge regions") + (list.empty() ? "" : (names.size() == 1 ? " and " : ", ") + list);
  return (names.size() == 1 ? "region " : "regions ") + list;
}

// Each per-set option belongs to some regions (RegionType::uses2d, uses3d); one given
// to another region is a mistake.
PetscErrorCode CheckOptionsFit(MPI_Comm comm, const LoadInput &li, const LoadSet &set, bool three)
{
  const RegionType &type = region_type(set.region);
  const unsigned    uses = three ? type.uses3d : type.uses2d;
  const char       *n    = li.name.c_str();
  const struct {
    bool        given;
    const char *option;
    unsigned    bit;
  } options[] = {{li.box_set, "box", uses_box},       {li.points_set, "points", uses_points}, {!li.group.empty(), "group", uses_group},
                 {!li.file.empty(), "file", uses_file}, {li.block_set, "block", uses_block},   {li.layers_set, "layers", uses_layers},
                 {li.depth_set, "depth", uses_depth}};
  PetscFunctionBeginUser;
  for (const auto &o : options)
    SceneCheck(!o.given || (uses & o.bit), comm, "-load_%s_%s is set but -load_%s_region is %s: it is used by %s only; remove it or change the region",
               n, o.option, n, to_string(set.region), RegionsReading(o.bit, three).c_str());
  PetscFunctionReturn(0);
}

// A 3D body's load sets hold its own points: there are no grip rows outside it.
PetscErrorCode CheckInside3D(MPI_Comm comm, const LoadInput &li, const SceneInput &in)
{
  PetscFunctionBeginUser;
  const std::string placement = Lower(li.placement);
  SceneCheck(placement == "auto" || placement == "inside", comm,
             "-load_%s_placement %s: a 3D body's load sets hold its own points (inside); grips outside the specimen are 2D only: "
             "remove it, or set it to inside",
             li.name.c_str(), li.placement.c_str());
  SceneCheck(!in.grip_placement_set || Lower(in.grip_placement) == "inside", comm,
             "-load_grip_placement %s: a 3D body's load sets hold its own points (inside); grips outside the specimen are 2D only: "
             "remove it, or set it to inside",
             in.grip_placement.c_str());
  PetscFunctionReturn(0);
}

// Where a load set is: its region word, then what its region type reads and checks
// (regions/).
PetscErrorCode CheckRegion(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li    = r.li;
  const char      *n     = li.name.c_str();
  const bool       three = r.body.dimension == 3;
  const char      *choices = RegionChoices(three);
  PetscFunctionBeginUser;
  SceneCheck(li.region_set, r.comm, "-load_%s_region is required for load set '%s': choose %s%s", n, n, choices,
             MisspeltHint("-load_" + li.name + "_region").c_str());
  if (!ParseRegion(li.region, &set->region))
    SETERRQ(r.comm, PETSC_ERR_USER, "%s", Format("-load_%s_region '%s' is not a region: choose %s", n, li.region.c_str(), choices).c_str());
  const RegionType &type = region_type(set->region);
  if (three) {
    SceneCheck(type.check3d != nullptr, r.comm, "-load_%s_region %s is a 2D region (a shape in the sheet's plane), and this body is 3D: choose %s",
               n, to_string(set->region), RegionChoices(true));
    PetscCall(CheckOptionsFit(r.comm, li, *set, true));
    PetscCall(CheckInside3D(r.comm, li, r.in));
    set->placement = GripPlacement::inside;
    PetscCall(type.check3d(r, set));
  } else {
    SceneCheck(type.check2d != nullptr, r.comm,
               "-load_%s_region %s is a face of a 3D body (z), and this body is a 2D sheet: choose %s (or make the body 3D, "
               "-body_dimension 3)",
               n, li.region.c_str(), RegionChoices(false));
    PetscCall(CheckOptionsFit(r.comm, li, *set, false));
    PetscCall(type.check2d(r, set));
  }
  if (!set->segments.empty()) SetCurveReach(set);
  PetscFunctionReturn(0);
}

// How the set moves each component (-load_NAME_x, _y, _z and their scales).
PetscErrorCode CheckComponents(MPI_Comm comm, const LoadInput &li, const Scene &scene, LoadSet *set)
{
  const char *n     = li.name.c_str();
  const bool  three = scene.body.dimension == 3;
  PetscFunctionBeginUser;
  SceneCheck(ParseComponent(li.x, &set->x), comm, "-load_%s_x '%s' is not a choice: choose free, fixed or stretch", n, li.x.c_str());
  SceneCheck(ParseComponent(li.y, &set->y), comm, "-load_%s_y '%s' is not a choice: choose free, fixed or stretch", n, li.y.c_str());
  SceneCheck(ParseComponent(li.z, &set->z), comm, "-load_%s_z '%s' is not a choice: choose free, fixed or stretch", n, li.z.c_str());
  SceneCheck(three || (set->z == ComponentLoad::free && !li.z_scale_set), comm,
             "-load_%s_z%s is set, but this body is a 2D sheet (x, y): remove it, or make the body 3D (-body_dimension 3)", n,
             li.z_scale_set ? "_scale" : "");
  for (int c = 0; c < scene.body.dimension; ++c) {
    const char          axis  = "xyz"[c];
    const ComponentLoad load  = set->component(c);
    const bool          given = c == 0 ? li.x_scale_set : c == 1 ? li.y_scale_set : li.z_scale_set;
    const double        scale = c == 0 ? li.x_scale : c == 1 ? li.y_scale : li.z_scale;
    SceneCheck(load == ComponentLoad::stretch || !given, comm,
               "-load_%s_%c_scale is set but -load_%s_%c is %s: the scale applies to a stretch component only; remove it or set "
               "-load_%s_%c stretch",
               n, axis, n, axis, to_string(load), n, axis);
    if (load != ComponentLoad::stretch) continue;
    SceneCheck(!scene.loading.schedule.time.empty(), comm,
               "-load_%s_%c stretch needs a stretch schedule: give -load_schedule t0,lambda0,t1,lambda1,... (e.g. 0,1,10,2 ramps lambda "
               "from 1 to 2 over 10 s)%s",
               n, axis, MisspeltHint("-load_schedule").c_str());
    if (scale == 0.0)
      PetscCall(Warn(comm, Format("-load_%s_%c_scale is 0: the stretch component never moves (same as -load_%s_%c fixed)", n, axis, n, axis)));
    (c == 0 ? set->x_scale : c == 1 ? set->y_scale : set->z_scale) = scale;
  }
  if (three && set->x == ComponentLoad::free && set->y == ComponentLoad::free && set->z == ComponentLoad::free)
    PetscCall(Warn(comm, Format("load set '%s' holds no component (-load_%s_x, -load_%s_y and -load_%s_z are free): it does nothing; set "
                                "one of them to fixed or stretch",
                                n, n, n, n)));
  else if (!three && set->x == ComponentLoad::free && set->y == ComponentLoad::free)
    PetscCall(Warn(comm, Format("load set '%s' holds neither component (-load_%s_x and -load_%s_y are free): it does nothing; set "
                                "one of them to fixed or stretch",
                                n, n, n)));
  PetscFunctionReturn(0);
}

// A stretch component moves by u = scale (lambda - 1) L; a negative scale moves it
// against lambda - 1 (the bottom grip of a symmetric pull: -0.5, with 0.5 at the top).
// Two grips on opposite edges (faces) that hold the same component then move apart by
// (s_upper - s_lower) (lambda - 1) L (a fixed one: scale 0), so lambda is their stretch.
// A negative difference pulls them together as lambda grows: the body is compressed
// while the schedule says stretched (and a long schedule makes them cross), so lambda no
// longer says what the grips do. Refused, naming both settings; a compression is a
// schedule with stretches below 1.
PetscErrorCode CheckGripsSeparate(MPI_Comm comm, const Scene &scene)
{
  using Region = LoadSet::Region;
  static const Region lower[] = {Region::left, Region::bottom, Region::back}, upper[] = {Region::right, Region::top, Region::front};
  auto scale = [](const LoadSet &l, int c) { return c == 0 ? l.x_scale : c == 1 ? l.y_scale : l.z_scale; };
  // "-load_top_y_scale -1" or "-load_bottom_y fixed"
  auto setting = [&](const LoadSet &l, int c) {
    const char axis = "xyz"[c];
    return l.component(c) == ComponentLoad::stretch ? Format("-load_%s_%c_scale %g", l.name.c_str(), axis, scale(l, c))
                                                    : Format("-load_%s_%c fixed", l.name.c_str(), axis);
  };
  PetscFunctionBeginUser;
  for (int c = 0; c < scene.body.dimension; ++c)
    for (const LoadSet &lo : scene.loading.sets) {
      if (lo.region != lower[c] || lo.component(c) == ComponentLoad::free) continue;
      for (const LoadSet &up : scene.loading.sets) {
        if (up.region != upper[c] || up.component(c) == ComponentLoad::free) continue;
        const double s_lo = lo.component(c) == ComponentLoad::stretch ? scale(lo, c) : 0.0;
        const double s_up = up.component(c) == ComponentLoad::stretch ? scale(up, c) : 0.0;
        const char   axis = "xyz"[c];
        SceneCheck(s_up - s_lo >= 0.0, comm,
                   "%s (a %s grip) and %s (a %s grip) move the two grips toward each other as the schedule's stretch grows: their "
                   "separation changes by (%g) (lambda - 1) L, so the body is compressed where -load_schedule says stretched. A negative "
                   "scale moves a grip against the stretch (the %s grip of a symmetric pull: -load_%s_%c_scale -0.5 with "
                   "-load_%s_%c_scale 0.5): fix the sign, or for a compression give -load_schedule stretches below 1 with positive scales",
                   setting(up, c).c_str(), to_string(up.region), setting(lo, c).c_str(), to_string(lo.region), s_up - s_lo,
                   to_string(lo.region), lo.name.c_str(), axis, up.name.c_str(), axis);
      }
    }
  PetscFunctionReturn(0);
}

// -load_grip_field: how the top and bottom grips move y (GripField), from the sets
// that hold y at the top and bottom edges, and elsewhere.
PetscErrorCode CheckGripField(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  int top = 0, bottom = 0, outside = 0, edges = 0, regions = 0;
  PetscFunctionBeginUser;
  for (const LoadSet &l : scene->loading.sets) {
    if (l.y == ComponentLoad::free) continue;
    const bool is_edge = region_type(l.region).edge; // (an edge of a sheet, a face of a 3D body)
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
    scene->loading.grip_field = top == 1 && bottom == 1 && outside == 2 ? GripField::affine : GripField::rigid;
  else if (field == "rigid") scene->loading.grip_field = GripField::rigid;
  else if (field == "affine") scene->loading.grip_field = GripField::affine;
  else SETERRQ(comm, PETSC_ERR_USER, "%s", Format("-load_grip_field '%s' is not a choice: choose rigid, affine or auto", in.grip_field.c_str()).c_str());
  if (scene->loading.grip_field == GripField::affine) {
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

} // namespace

SetFamily LoadSetFamily() { return {"-load_", "-load_sets", OptionRowSuffixes(kLoadSetOptions)}; }

PetscErrorCode ReadLoading(MPI_Comm comm, LoadingSection *loading, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Loading: grips (load sets) following a stretch schedule", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.StringArray("-load_sets", "Names of the load sets name1,name2,... (each set S is configured by -load_S_...)", &in->load_names));
    PetscCall(r.RealArray("-load_schedule", "Stretch schedule t0,lambda0,t1,lambda1,... [s, -], piecewise linear (default: none)", &in->schedule,
                          &in->schedule_set));
    PetscCall(r.Real("-load_reference_length", "Length L in u = scale (lambda - 1) L [m] (default: body height)", &loading->reference_length,
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
    LoadInput set;
    PetscCall(ReadLoadSet(comm, name, &set));
    in->loads.push_back(set);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckLoading(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSchedule(comm, in, &scene->loading.schedule));
  // The free length: the specimen's height between grips outside it; the whole
  // height (grip rows included) for the paper's grips inside it.
  if (in.reference_length_set)
    SceneCheck(scene->loading.reference_length > 0, comm,
               "-load_reference_length %g: the length that turns stretch into displacement must be > 0 m (default: the body height)",
               scene->loading.reference_length);
  else scene->loading.reference_length = scene->body.dimension == 3 ? scene->body.solid_summary.hi[1] - scene->body.solid_summary.lo[1] : scene->body.sheet.height; // (3D: the extent along y)

  GripPlacement     default_placement = GripPlacement::outside;
  const std::string placement_all     = Lower(in.grip_placement);
  if (placement_all == "inside") default_placement = GripPlacement::inside;
  else SceneCheck(placement_all == "outside", comm, "-load_grip_placement '%s' is not a choice: choose outside or inside",
                  in.grip_placement.c_str());
  scene->loading.sets.clear();
  for (const LoadInput &li : in.loads) {
    LoadSet set;
    set.name = li.name;
    PetscCall(CheckRegion({comm, li, in, scene->body, default_placement}, &set));
    PetscCall(CheckComponents(comm, li, *scene, &set));
    scene->loading.sets.push_back(set);
  }
  PetscCall(CheckGripsSeparate(comm, *scene));
  PetscCall(CheckGripField(comm, in, scene));
  PetscFunctionReturn(0);
}

std::string LoadingText(const Scene &s)
{
  const bool       three  = s.body.dimension == 3;
  const BodyExtent extent = BodyExtentOf(s);
  std::string      text;
  auto        component = [](ComponentLoad c, double scale) {
    return c == ComponentLoad::stretch ? Format("stretch (scale %g)", scale) : std::string(to_string(c));
  };
  for (const LoadSet &l : s.loading.sets)
    text += Format("  load set  %s: %s; x %s, y %s%s\n", l.name.c_str(), RegionText(extent, l).c_str(), component(l.x, l.x_scale).c_str(),
                   component(l.y, l.y_scale).c_str(), three ? (", z " + component(l.z, l.z_scale)).c_str() : "");
  if (s.loading.sets.empty()) text += "  load set  none\n";
  if (!s.loading.schedule.time.empty()) {
    text += "  schedule  (t, lambda):";
    for (std::size_t k = 0; k < s.loading.schedule.time.size(); ++k) text += Format(" (%g s, %g)", s.loading.schedule.time[k], s.loading.schedule.stretch[k]);
    text += Format("; u = scale (lambda - 1) %g m; grip field %s\n", s.loading.reference_length, to_string(s.loading.grip_field));
  }
  return text;
}

int GripRows(double depth, double dx)
{
  // Row j's centre lies (j + 1/2) dx from the edge; 1e-9: a depth of whole rows given
  // in metres (6 x 0.5 mm) keeps its rows despite round-off. Held below 1e9 rows: past
  // an int the cast wrapped, and -load_top_depth 1e30 ran as a grip of one row.
  return std::max(1, static_cast<int>(std::min(1e9, std::ceil(depth / dx - 0.5 - 1e-9))));
}

const char *to_string(GripPlacement placement) { return placement == GripPlacement::outside ? "outside" : "inside"; }

const char *to_string(GripField field) { return field == GripField::affine ? "affine" : "rigid"; }

const char *to_string(ComponentLoad load)
{
  static const char *const words[] = {"free", "fixed", "stretch"}; // (ComponentLoad's order)
  return words[static_cast<int>(load)];
}

EdgeRows OutsideGripRows(const LoadingSection &loading)
{
  EdgeRows rows;
  for (const LoadSet &set : loading.sets) {
    if (set.placement != GripPlacement::outside) continue; // (only a 2D edge grip is placed outside)
    int64_t &edge = set.region == LoadSet::Region::top      ? rows.top
                    : set.region == LoadSet::Region::bottom ? rows.bottom
                    : set.region == LoadSet::Region::left   ? rows.left
                                                            : rows.right;
    edge = std::max<int64_t>(edge, set.layers);
  }
  return rows;
}

std::vector<std::string> BodyGmshFiles(const Body<2> &body)
{
  std::vector<std::string> files;
  for (const Shape &s : body.shapes)
    if (s.kind == Shape::Kind::mesh && std::find(files.begin(), files.end(), s.file) == files.end()) files.push_back(s.file);
  return files;
}

std::vector<std::string> BodyGmshFiles(const Body<3> &body)
{
  std::vector<std::string> files;
  for (const nd::Solid &s : body.solids)
    if (s.kind == nd::Solid::Kind::mesh && std::find(files.begin(), files.end(), s.mesh->file) == files.end()) files.push_back(s.mesh->file);
  return files;
}

PetscErrorCode GroupGmshFile(MPI_Comm comm, const std::string &given, const std::vector<std::string> &files, const char *prefix,
                             const char *owner, const std::string &name, const char *kinds, const std::string &group, std::string *file)
{
  PetscFunctionBeginUser;
  *file = given;
  if (!file->empty()) PetscFunctionReturn(0);
  SceneCheck(files.size() == 1, comm,
             "-%s_%s_file is required for %s '%s': the body reads %zu Gmsh files (%s), so the file of group '%s' is not implied: give "
             "the .geo or .msh that names it",
             prefix, name.c_str(), owner, name.c_str(), files.size(), kinds, group.c_str());
  *file = files[0];
  PetscFunctionReturn(0);
}

} // namespace bapd
