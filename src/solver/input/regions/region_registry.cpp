// The registry of grip regions (region_registry.hpp): the list made into region
// types, and what the rest of the solver asks of a load set's region, answered by its
// type: the word, the points it holds, its summary text, its empty-selection message.
#include "bapd/solver/input/regions/region_registry.hpp"

#include <algorithm>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

const std::vector<RegionType> &registered_regions()
{
#define BAPD_REGION_TYPE(id, alias, type) type##_region(LoadSet::Region::id, #id, alias),
  static const std::vector<RegionType> regions = {BAPD_REGISTERED_REGIONS(BAPD_REGION_TYPE)};
#undef BAPD_REGION_TYPE
  return regions;
}

const RegionType &region_type(LoadSet::Region id) { return registered_regions()[static_cast<std::size_t>(id)]; }

bool ParseRegion(const std::string &text, LoadSet::Region *region)
{
  const std::string t = Lower(text);
  for (const RegionType &r : registered_regions())
    if (t == r.word || (r.alias && t == r.alias)) {
      *region = r.id;
      return true;
    }
  return false;
}

const char *to_string(LoadSet::Region region) { return region_type(region).word; }

namespace {

// "a, b or c"
std::string ChoiceList(const std::vector<std::string> &items)
{
  std::string text;
  for (std::size_t k = 0; k < items.size(); ++k) text += (k == 0 ? "" : k + 1 == items.size() ? " or " : ", ") + items[k];
  return text;
}

// The faces of a 3D body by axis, the lower first (their aliases: x-, x+, y-, ...).
std::vector<const RegionType *> Faces()
{
  std::vector<const RegionType *> faces;
  for (const RegionType &r : registered_regions())
    if (r.edge && r.check3d && r.alias) faces.push_back(&r);
  std::sort(faces.begin(), faces.end(), [](const RegionType *a, const RegionType *b) {
    return a->alias[0] != b->alias[0] ? a->alias[0] < b->alias[0] : a->alias[1] == '-' && b->alias[1] == '+';
  });
  return faces;
}

std::string MakeRegionChoices(bool three)
{
  std::vector<std::string> items;
  if (three) {
    std::string faces;
    for (const RegionType *f : Faces()) faces += std::string(faces.empty() ? "" : ", ") + f->word + " or " + f->alias;
    items.push_back("a face (" + faces + ")");
  }
  for (const RegionType &r : registered_regions()) {
    if (three ? !r.check3d || r.edge : !r.check2d) continue;
    items.push_back(std::string(r.word) + (three && r.gloss ? std::string(" (") + r.gloss + ")" : ""));
  }
  return ChoiceList(items);
}

// "top | bottom | left | right (edge layers; 3D: faces, with back | front, or x- | x+ |
// ... ) | box | ... | block (a block id of the point cloud) (required)"
std::string MakeRegionHelp()
{
  std::string edges3d, aliases, text;
  for (const RegionType *f : Faces()) {
    if (!f->check2d) edges3d += std::string(edges3d.empty() ? "" : " | ") + f->word;
    aliases += std::string(aliases.empty() ? "" : " | ") + f->alias;
  }
  const std::vector<RegionType> &regions = registered_regions();
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const RegionType &r = regions[k];
    if (!r.check2d) continue;
    text += std::string(text.empty() ? "Points held: " : " | ") + r.word;
    const bool last_edge = r.edge && (k + 1 == regions.size() || !regions[k + 1].edge || !regions[k + 1].check2d);
    if (last_edge) text += " (edge layers; 3D: faces, with " + edges3d + ", or " + aliases + ")";
    else if (r.gloss) text += std::string(" (") + r.gloss + ")";
  }
  return text + " (required)";
}

} // namespace

const char *RegionChoices(bool three)
{
  static const std::string sheet = MakeRegionChoices(false), solid = MakeRegionChoices(true);
  return three ? solid.c_str() : sheet.c_str();
}

const char *RegionHelp()
{
  static const std::string help = MakeRegionHelp();
  return help.c_str();
}

template <int D> bool LoadSetContains(const BodyExtent &body, const LoadSet &set, const double *p)
{
  const RegionType &r        = region_type(set.region);
  const auto        contains = D == 3 ? r.contains3d : r.contains2d;
  return contains && contains(body, set, p); // (none: a region of the other dimension, refused by CheckLoading)
}
template bool LoadSetContains<2>(const BodyExtent &, const LoadSet &, const double *);
template bool LoadSetContains<3>(const BodyExtent &, const LoadSet &, const double *);

std::string RegionText(const BodyExtent &body, const LoadSet &set) { return region_type(set.region).text(body, set); }

std::string LoadSetEmptyMessage(const BodyExtent &body, const LoadSet &set) { return region_type(set.region).empty_message(body, set); }

PetscErrorCode CheckLayersDepth(const RegionInput &r, const char *whose, const char *unit)
{
  const LoadInput &li    = r.li;
  const char      *n     = li.name.c_str();
  const bool       grip  = std::string(whose) == "grip";
  PetscFunctionBeginUser;
  SceneCheck(!(li.layers_set && li.depth_set), r.comm, "-load_%s_layers and -load_%s_depth both give the %s's depth: keep one (rows, or metres)",
             n, n, whose);
  SceneCheck(!li.depth_set || li.depth > 0, r.comm, "-load_%s_depth %g m: %s must be > 0", n, li.depth, grip ? "a grip's depth" : "a depth");
  SceneCheck(li.layers >= 1, r.comm, "-load_%s_layers %" PetscInt_FMT ": take at least one point %s", n, li.layers, unit);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckOwnPoints2D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  // A box, polygon, curve or group holds the body's own points: there is nothing
  // beyond an edge to add for it.
  const std::string placement = Lower(li.placement);
  SceneCheck(placement == "auto" || placement == "inside", r.comm,
             "-load_%s_placement %s: load set '%s' is a %s, which holds the body's own points (inside); only the edge regions "
             "top, bottom, left and right add grip rows outside the body: remove it, or set it to inside",
             n, li.placement.c_str(), n, to_string(set->region));
  PetscCall(CheckLayersDepth(r, "set", "row"));
  set->depth = li.depth_set ? li.depth : static_cast<double>(li.layers) * r.body.dx();
  PetscFunctionReturn(0);
}

PetscErrorCode CheckVertices2D(const RegionInput &r, const LoadSet &set, std::size_t fewest)
{
  const LoadInput &li = r.li;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(li.points_set, r.comm, "-load_%s_points is required with -load_%s_region %s: give the vertices x0,y0,x1,y1,... in m%s", n, n,
             to_string(set.region), MisspeltHint("-load_" + li.name + "_points").c_str());
  SceneCheck(li.points.size() % 2 == 0 && li.points.size() >= 2 * fewest, r.comm,
             "-load_%s_points holds %zu numbers: give x,y pairs, at least %zu vertices for a %s", n, li.points.size(), fewest,
             to_string(set.region));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckVerticesOnBody2D(const RegionInput &r, const LoadSet &set, double grow)
{
  const LoadInput &li = r.li;
  const Body<2>    &b  = r.body.sheet;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  double lo[2] = {li.points[0], li.points[1]}, hi[2] = {li.points[0], li.points[1]};
  for (std::size_t k = 0; k < li.points.size(); ++k) lo[k % 2] = std::min(lo[k % 2], li.points[k]), hi[k % 2] = std::max(hi[k % 2], li.points[k]);
  SceneCheck(hi[0] + grow >= 0 && lo[0] - grow <= b.width && hi[1] + grow >= 0 && lo[1] - grow <= b.height, r.comm,
             "-load_%s_points: the %s of load set '%s' lies outside the body [0, %g] x [0, %g] m: move it onto the body", n,
             to_string(set.region), n, b.width, b.height);
  PetscFunctionReturn(0);
}

std::string VerticesEmpty2D(const BodyExtent &s, const LoadSet &set, const std::string &advice)
{
  const char *n = set.name.c_str();
  return Format("-load_%s_points: the %s selects no material point for load set '%s': %s (points sit at ((i + 1/2) dx, (j + "
                "1/2) dx), dx = %g m)",
                n, to_string(set.region), n, advice.c_str(), s.dx);
}

} // namespace bapd
