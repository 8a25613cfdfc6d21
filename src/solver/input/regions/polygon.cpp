// Region polygon (2D): the points inside a closed polygon, edges inclusive
// (-load_NAME_points, its vertices in order around it; it closes by itself).
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {
namespace {

PetscErrorCode CheckPolygon2D(const RegionInput &r, LoadSet *set)
{
  const std::vector<double> &vertices = r.li.points;
  PetscFunctionBeginUser;
  PetscCall(CheckOwnPoints2D(r, set));
  PetscCall(CheckVertices2D(r, *set, 3));
  set->area.kind            = Shape::Kind::polygon;
  set->area.vertices        = vertices;
  const std::string problem = polygon_problem(vertices);
  SceneCheck(problem.empty(), r.comm, "-load_%s_points (the polygon of load set '%s'): %s; give its vertices in order around it (it closes by itself)",
             set->name.c_str(), set->name.c_str(), problem.c_str());
  PetscCall(CheckVerticesOnBody2D(r, *set, 0.0));
  PetscFunctionReturn(0);
}

bool PolygonContains2D(const BodyExtent &, const LoadSet &set, const double *p) { return shape_contains(set.area, p[0], p[1]); }

std::string PolygonText(const BodyExtent &, const LoadSet &l) { return Format("polygon of %zu vertices", l.area.vertices.size() / 2); }

std::string PolygonEmpty(const BodyExtent &s, const LoadSet &set) { return VerticesEmpty2D(s, set, "enlarge it or move it onto the body"); }

} // namespace

RegionType polygon_region(LoadSet::Region id, const char *word, const char *alias)
{
  return {id, word, alias, false, uses_points, 0, CheckPolygon2D, nullptr, PolygonContains2D, nullptr, PolygonText, PolygonEmpty};
}

} // namespace bapd
