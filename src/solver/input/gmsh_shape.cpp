// A Gmsh file as the triangles of a shape, and its physical groups (gmsh_shape.hpp).
#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/solver/input/gmsh_node_table.hpp"
#include "bapd/solver/input/gmsh_session.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cstdio>
#include <unordered_map>
#include <utility>
#include <vector>

namespace bapd {

namespace {

// Opens `file` (WithGmshFile) and runs `read` on the model, meshed in 2D unless the
// file holds 2D elements already. Returns what went wrong or "".
template <class Read> std::string WithMeshedFile(const std::string &file, Read read)
{
  return WithGmshFile(file, [&]() -> std::string {
    std::vector<int>                      types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, 2);
    if (types.empty()) {
      std::vector<std::pair<int, int>> surfaces;
      gmsh::model::getEntities(surfaces, 2);
      if (surfaces.empty()) return "'" + file + "' holds no surface and no 2D element: give a .geo with a Plane Surface, or a .msh of a 2D mesh";
      GenerateOutlineMesh(2);
    }
    return read();
  });
}

// The model's node coordinates by tag (x, y; z ignored).
class NodeTable {
public:
  void Append(std::size_t tag, std::vector<double> &out) const
  {
    const double *x = nodes_.at(tag);
    out.push_back(x[0]);
    out.push_back(x[1]);
  }

private:
  GmshNodeTable nodes_;
};

// Appends the 2D elements of entity `tag` (-1: all) to `corners` as triangles, and to
// `element` (when given) the index of the element each triangle came from (a quadrangle
// gives two triangles); returns "" or the element kind bapd cannot read.
std::string AppendTriangles(const NodeTable &table, int tag, std::vector<double> &corners,
                            std::vector<std::size_t> *element = nullptr)
{
  return ForEachElementType(2, tag, [&](int type, const std::string &name, std::size_t per, const std::vector<std::size_t> &nodes) {
    const int n_corners = GmshCornerCount2D(type);
    if (n_corners == 0) return "2D elements of a kind bapd does not read (" + name + "): mesh with triangles or quadrangles";
    for (std::size_t e = 0; e + per <= nodes.size(); e += per) {
      const std::size_t *n     = &nodes[e];
      const std::size_t  index = element && !element->empty() ? element->back() + 1 : 0;
      table.Append(n[0], corners), table.Append(n[1], corners), table.Append(n[2], corners);
      if (element) element->push_back(index);
      if (n_corners == 4) {
        table.Append(n[0], corners), table.Append(n[2], corners), table.Append(n[3], corners);
        if (element) element->push_back(index);
      }
    }
    return std::string();
  });
}

// Appends the line elements (dim 1) or the point elements (dim 0) of entity `tag` to
// `segments`, x0,y0,x1,y1 each (a point as a segment of zero length). Line elements
// of any order: their first two nodes are the ends.
void AppendSegments(const NodeTable &table, int dim, int tag, std::vector<double> &segments)
{
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, dim, tag);
  for (std::size_t t = 0; t < types.size(); ++t) {
    const std::size_t per = nodes[t].size() / std::max<std::size_t>(1, tags[t].size());
    for (std::size_t e = 0; per > 0 && e + per <= nodes[t].size(); e += per) {
      table.Append(nodes[t][e], segments);
      table.Append(nodes[t][dim == 1 ? e + 1 : e], segments);
    }
  }
}

} // namespace

std::string ReadGmshTriangles(const std::string &file, TriangleSet *triangles)
{
  triangles->corners.clear();
  triangles->element.clear();
  const std::string problem = WithMeshedFile(file, [&]() -> std::string {
    const std::string kind = AppendTriangles(NodeTable(), -1, triangles->corners, &triangles->element);
    return kind.empty() ? "" : "'" + file + "' has " + kind;
  });
  if (!problem.empty()) return problem;
  if (triangles->corners.empty()) return "'" + file + "' holds no 2D element after meshing: check its surfaces";
  index_triangles(*triangles);
  return "";
}

std::string ReadGmshGroup(const std::string &file, const std::string &name, GmshGroup *group)
{
  *group = GmshGroup{};
  group->name = name;
  return WithMeshedFile(file, [&]() -> std::string {
    int               dim, tag;
    const std::string problem = FindPhysicalGroup(file, name,
                                                  "add one, e.g. Physical Surface(\"" + name + "\") = {1}; or Physical Curve(\"" + name +
                                                      "\") = {3};",
                                                  &dim, &tag);
    if (!problem.empty()) return problem;
    if (dim > 2) return "physical group '" + name + "' of '" + file + "' is a volume: bapd is 2D; name a surface, curve or point";
    group->dim = dim;
    const NodeTable  table;
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    for (int entity : entities) {
      if (dim == 2) {
        const std::string kind = AppendTriangles(table, entity, group->triangles.corners);
        if (!kind.empty()) return "physical group '" + name + "' of '" + file + "' has " + kind;
      } else AppendSegments(table, dim, entity, group->segments);
    }
    if (group->triangles.corners.empty() && group->segments.empty())
      return "physical group '" + name + "' of '" + file + "' holds no mesh element: is it a group of meshed entities?";
    if (dim == 2) index_triangles(group->triangles);
    return "";
  });
}

} // namespace bapd
