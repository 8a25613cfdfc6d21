// Region group: a named physical group of a Gmsh file (-load_NAME_group, of
// -load_NAME_file; default: the body's one Gmsh file). 2D: a physical surface holds
// the points inside its elements (the set's area, a mesh shape); a physical curve or
// point, those closer than the set's depth to it (its segments). 3D: a physical volume
// holds the points inside its tetrahedra; a surface, curve or point those closer than
// -load_NAME_depth (default -load_NAME_layers x dx, one layer) to its elements.
#include <utility>

#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {
namespace {

PetscErrorCode CheckGroup2D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  PetscCall(CheckOwnPoints2D(r, set));
  SceneCheck(!li.group.empty(), r.comm, "-load_%s_group is required with -load_%s_region group: give the name of a physical group of the Gmsh file%s",
             n, n, MisspeltHint("-load_" + li.name + "_group").c_str());
  PetscCall(GroupGmshFile(r.comm, li.file, BodyGmshFiles(r.body.sheet), "load", "load set", li.name, "mesh shapes", li.group, &set->file));
  set->group = li.group;
  GmshGroup         group;
  const std::string problem = ReadGmshGroup(set->file, li.group, &group);
  SceneCheck(problem.empty(), r.comm, "-load_%s_group %s: %s", n, li.group.c_str(), problem.c_str());
  if (group.dim == 2) {
    SceneCheck(!li.layers_set && !li.depth_set, r.comm,
               "-load_%s_%s is set but group '%s' is a physical surface: the set holds the points inside its elements; remove it (a "
               "depth applies to a physical curve or point)",
               n, li.layers_set ? "layers" : "depth", li.group.c_str());
    set->area.kind      = Shape::Kind::mesh;
    set->area.file      = set->file;
    set->area.triangles = std::move(group.triangles);
  } else set->segments = std::move(group.segments);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckGroup3D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  const char      *n  = li.name.c_str();
  PetscFunctionBeginUser;
  SceneCheck(!li.group.empty(), r.comm,
             "-load_%s_group is required with -load_%s_region group: give the name of a physical group of the Gmsh file (a Physical "
             "Surface for a face)%s",
             n, n, MisspeltHint("-load_" + li.name + "_group").c_str());
  PetscCall(GroupGmshFile(r.comm, li.file, BodyGmshFiles(r.body.solid), "load", "load set", li.name, "mesh solids", li.group, &set->file));
  set->group = li.group;
  PetscCall(CheckLayersDepth(r, "set", "layer"));
  set->depth                = li.depth_set ? li.depth : static_cast<double>(li.layers) * r.body.solid.dx;
  const std::string problem = ReadGmshGroup3D(set->file, li.group, set->depth, &set->elements);
  SceneCheck(problem.empty(), r.comm, "-load_%s_group %s: %s", n, li.group.c_str(), problem.c_str());
  SceneCheck(set->elements.dim < 3 || !(li.layers_set || li.depth_set), r.comm,
             "-load_%s_%s is set but group '%s' is a physical volume: the set holds the points inside its elements; remove it (a depth "
             "applies to a physical surface, curve or point)",
             n, li.layers_set ? "layers" : "depth", li.group.c_str());
  PetscFunctionReturn(0);
}

bool GroupContains2D(const BodyExtent &, const LoadSet &set, const double *p)
{
  return set.segments.empty() ? shape_contains(set.area, p[0], p[1]) : NearSegments(set, p[0], p[1]);
}

bool GroupContains3D(const BodyExtent &, const LoadSet &set, const double *p) { return nd::region_contains(set.elements, p); }

std::string GroupText(const BodyExtent &s, const LoadSet &l)
{
  const char *g = l.group.c_str(), *f = l.file.c_str();
  if (s.dimension == 3)
    return l.elements.dim == 3 ? Format("physical volume '%s' of %s (%zu tetrahedra)", g, f, l.elements.size())
                               : Format("within %g m of physical %s '%s' of %s (%zu elements)", l.depth,
                                        l.elements.dim == 2 ? "surface" : l.elements.dim == 1 ? "curve" : "point", g, f, l.elements.size());
  return l.segments.empty() ? Format("physical surface '%s' of %s", g, f) : Format("within %g m of physical group '%s' of %s", l.depth, g, f);
}

std::string GroupEmpty(const BodyExtent &, const LoadSet &set)
{
  const char *n = set.name.c_str();
  return Format("-load_%s_group %s (of %s) selects no material point for load set '%s': %s", n, set.group.c_str(), set.file.c_str(), n,
                set.segments.empty() ? "no material point lies inside its elements (is it a surface of the body?)"
                                     : ("no point lies closer to it than -load_" + set.name + "_depth: raise the depth, or check that it lies on the body").c_str());
}

} // namespace

RegionType group_region(LoadSet::Region id, const char *word, const char *alias)
{
  const unsigned uses = uses_group | uses_file | uses_layers | uses_depth;
  return {id, word, alias, false, uses, uses, CheckGroup2D, CheckGroup3D, GroupContains2D, GroupContains3D, GroupText, GroupEmpty, "a Gmsh physical group"};
}

} // namespace bapd
