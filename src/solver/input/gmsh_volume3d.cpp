// A Gmsh 3D volume as tetrahedra, and its named physical groups (gmsh_volume3d.hpp).
#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/solver/input/gmsh_node_table.hpp"
#include "bapd/solver/input/gmsh_session.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <unordered_map>
#include <vector>

namespace bapd {

namespace {

// Gmsh's tetrahedron element types (4-, 10-, 20-, 35-, 56-node); corner nodes come first.
bool IsTetrahedron(int type) { return type == 4 || type == 11 || type == 29 || type == 30 || type == 31; }

// Meshes the open model in 3D unless it holds 3D elements already; "" or what is missing.
std::string MeshIn3D(const std::string &file)
{
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3);
  if (!types.empty()) return "";
  std::vector<std::pair<int, int>> volumes;
  gmsh::model::getEntities(volumes, 3);
  if (volumes.empty()) return "'" + file + "' holds no volume and no 3D element: give a .geo with a Volume, or a .msh of a 3D mesh";
  GenerateOutlineMesh(3);
  return "";
}

// The model's node coordinates by tag (x, y, z).
class NodeTable3D {
public:
  void Append(std::size_t tag, std::vector<double> &out) const
  {
    const double *x = nodes_.at(tag);
    out.insert(out.end(), x, x + 3);
  }

private:
  GmshNodeTable nodes_;
};

// Appends the tetrahedra of entity `tag` (-1: every volume) to `corners`, 12 numbers each;
// "" or the element kind bapd does not read.
std::string AppendTetrahedra(const NodeTable3D &table, int tag, std::vector<double> &corners)
{
  return ForEachElementType(3, tag, [&](int type, const std::string &name, std::size_t per, const std::vector<std::size_t> &nodes) {
    if (!IsTetrahedron(type)) return "3D elements of a kind bapd does not read (" + name + "): mesh the volume with tetrahedra";
    for (std::size_t e = 0; e + per <= nodes.size(); e += per)
      for (std::size_t c = 0; c < 4; ++c) table.Append(nodes[e + c], corners);
    return std::string();
  });
}

// Appends the elements of dimension dim (2: triangles, a quadrangle as two; 1: line
// segments by their end nodes; 0: nodes, as segments of length 0) of entity `tag` to
// `out`; "" or the element kind bapd does not read.
std::string AppendBoundaryElements(const NodeTable3D &table, int dim, int tag, std::vector<double> &out)
{
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, dim, tag);
  for (std::size_t t = 0; t < types.size(); ++t) {
    const std::size_t per = nodes[t].size() / std::max<std::size_t>(1, tags[t].size());
    const int         corners = dim == 2 ? GmshCornerCount2D(types[t]) : 0;
    if (dim == 2 && corners == 0) return "2D elements of a kind bapd does not read: mesh the surface with triangles or quadrangles";
    for (std::size_t e = 0; per > 0 && e + per <= nodes[t].size(); e += per) {
      const std::size_t *n = &nodes[t][e];
      if (dim == 2) {
        for (int c : {0, 1, 2}) table.Append(n[c], out);
        if (corners == 4)
          for (int c : {0, 2, 3}) table.Append(n[c], out);
      } else {
        table.Append(n[0], out);
        table.Append(n[dim == 1 ? 1 : 0], out);
      }
    }
  }
  return "";
}

} // namespace

std::string ReadGmshTetrahedra(const std::string &file, nd::TetrahedronSet *tetrahedra)
{
  *tetrahedra      = nd::TetrahedronSet{};
  tetrahedra->file = file;
  return WithGmshFile(file, [&]() -> std::string {
    const std::string missing = MeshIn3D(file);
    if (!missing.empty()) return missing;
    const std::string kind = AppendTetrahedra(NodeTable3D(), -1, tetrahedra->corners);
    if (!kind.empty()) return "'" + file + "' holds " + kind;
    if (tetrahedra->size() == 0) return "'" + file + "' holds no tetrahedron after meshing";
    nd::index_tetrahedra(*tetrahedra);
    return "";
  });
}

std::string ReadGmshGroup3D(const std::string &file, const std::string &name, double depth, nd::ElementRegion *region)
{
  *region = nd::ElementRegion{};
  return WithGmshFile(file, [&]() -> std::string {
    const std::string missing = MeshIn3D(file);
    if (!missing.empty()) return missing;
    int               dim, tag;
    const std::string problem = FindPhysicalGroup(file, name,
                                                  "add one, e.g. Physical Surface(\"" + name + "\") = {1}; for a face, or Physical Volume(\"" +
                                                      name + "\") = {1};",
                                                  &dim, &tag);
    if (!problem.empty()) return problem;
    region->dim   = dim;
    region->depth = depth;
    const NodeTable3D table;
    std::vector<int>  entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    auto tetrahedra  = std::make_shared<nd::TetrahedronSet>();
    tetrahedra->file = file;
    for (int entity : entities) {
      const std::string kind = dim == 3 ? AppendTetrahedra(table, entity, tetrahedra->corners)
                                        : AppendBoundaryElements(table, dim, entity, dim == 2 ? region->triangles : region->segments);
      if (!kind.empty()) return "physical group '" + name + "' of '" + file + "' holds " + kind;
    }
    if (dim == 3 && tetrahedra->size() > 0) {
      nd::index_tetrahedra(*tetrahedra);
      region->tetrahedra = tetrahedra;
    }
    if (region->size() == 0) return "physical group '" + name + "' of '" + file + "' holds no mesh element: is it a group of meshed entities?";
    nd::set_reach(*region);
    return "";
  });
}

} // namespace bapd
