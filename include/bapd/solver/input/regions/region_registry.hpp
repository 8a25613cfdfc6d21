#pragma once
// The registry of grip regions: every region a load set can name with
// -load_NAME_region, in one list. A region type is one file in src/solver/input/regions/
// that defines `RegionType <type>_region(LoadSet::Region id, const char *word, const
// char *alias)` (box.cpp is the smallest example): how it reads and checks its
// options, which points it holds, its summary text and the message when it holds
// none. A new region is that file plus one line X(id, alias, type) in
// BAPD_REGISTERED_REGIONS (region_list.hpp); LoadSet::Region, the region words, the selection
// (LoadSetContains), the summary (RegionText) and the empty-selection message are
// generated from that list, and so are the region choices quoted in messages
// (RegionChoices) and -load_NAME_region's help (RegionHelp), from the words and glosses.
#include <petscsys.h>

#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/solver/input/scene_loading.hpp"

namespace bapd {

struct BodySection;
struct LoadInput;
struct SceneInput;

// The region choices of the messages, from the registry: a 2D sheet's regions ("top,
// bottom, left, right, box, polygon, curve, group or block"), or a 3D body's ("a face
// (left or x-, right or x+, ...), box, group (a Gmsh physical group) or block (...)").
const char *RegionChoices(bool three);
// -load_NAME_region's help: every word with its gloss, the faces' aliases, "(required)".
const char *RegionHelp();

// The per-set options a region reads (RegionType::uses2d, uses3d); one given to a
// region that does not read it is refused by name.
enum RegionOption : unsigned {
  uses_box = 1u << 0, uses_points = 1u << 1, uses_group = 1u << 2, uses_file = 1u << 3, uses_block = 1u << 4,
  uses_layers = 1u << 5, uses_depth = 1u << 6
};

// What a region's check reads: the set's options, the whole input, the checked body
// section (its dimension, its sheet or solid, the horizon), and the placement of edge
// grips that no set overrides (-load_grip_placement).
struct RegionInput {
  MPI_Comm           comm;
  const LoadInput   &li;
  const SceneInput  &in;
  const BodySection &body;
  GripPlacement      default_placement;
};

struct RegionType {
  LoadSet::Region id;
  const char     *word;  // -load_NAME_region
  const char     *alias; // a second word (the faces' x-, x+, ...), or nullptr
  bool            edge;  // an edge of the sheet, a face of a 3D body (the grip-field counts)
  unsigned        uses2d = 0, uses3d = 0; // RegionOption bits
  // Reads and checks the set's options (set->region is id). nullptr check3d: a 2D
  // region, refused on a 3D body.
  PetscErrorCode (*check2d)(const RegionInput &, LoadSet *set) = nullptr;
  PetscErrorCode (*check3d)(const RegionInput &, LoadSet *set) = nullptr;
  // Whether the point at reference position p (2 or 3 coordinates) is held.
  bool (*contains2d)(const BodyExtent &, const LoadSet &, const double *p) = nullptr;
  bool (*contains3d)(const BodyExtent &, const LoadSet &, const double *p) = nullptr;
  // The summary's words for where the set is (SceneText), and the message when the set
  // holds no material point (Loading::Setup).
  std::string (*text)(const BodyExtent &, const LoadSet &)          = nullptr;
  std::string (*empty_message)(const BodyExtent &, const LoadSet &) = nullptr;
  // A few words after the word in -help and the 3D choices ("points near a polyline"), or
  // nullptr (the edges: their gloss is made from the list, RegionHelp).
  const char *gloss = nullptr;
};

#define BAPD_REGION_MAKER(id, alias, type) RegionType type##_region(LoadSet::Region, const char *, const char *);
BAPD_REGISTERED_REGIONS(BAPD_REGION_MAKER)
#undef BAPD_REGION_MAKER

// Every registered region, in registry order (entry k has id LoadSet::Region(k)).
const std::vector<RegionType> &registered_regions();
const RegionType              &region_type(LoadSet::Region id);
// The region of a word (case-insensitive; either word of a region); false: none.
bool ParseRegion(const std::string &text, LoadSet::Region *region);

// Shared by the regions' checks.
// A 2D region on the body's own points (all but the edges): -load_NAME_placement is
// inside or auto, and the set's depth (-load_NAME_layers rows, or -load_NAME_depth).
PetscErrorCode CheckOwnPoints2D(const RegionInput &r, LoadSet *set);
// -load_NAME_layers and -load_NAME_depth: not both, a depth > 0, at least one layer.
// `whose`: "grip" or "set"; `unit`: "row" or "layer".
PetscErrorCode CheckLayersDepth(const RegionInput &r, const char *whose, const char *unit);
// Region polygon and curve: -load_NAME_points, x,y pairs, at least `fewest` vertices;
// then (on body) their bounding box grown by `grow` meets the sheet.
PetscErrorCode CheckVertices2D(const RegionInput &r, const LoadSet &set, std::size_t fewest);
PetscErrorCode CheckVerticesOnBody2D(const RegionInput &r, const LoadSet &set, double grow);
// Their message when they hold no point, with the advice.
std::string VerticesEmpty2D(const BodyExtent &s, const LoadSet &set, const std::string &advice);
// Whether (px, py) lies closer than set.depth to one of set.segments (curve, group).
bool NearSegments(const LoadSet &set, double px, double py);

} // namespace bapd
