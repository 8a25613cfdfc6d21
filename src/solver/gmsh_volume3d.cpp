// A Gmsh 3D volume as tetrahedra (gmsh_volume3d.hpp).
#include "bapd/gmsh_volume3d.hpp"
#include "bapd/gmsh_session.hpp"

#include <gmsh.h>

#include <cstdio>
#include <unordered_map>
#include <vector>

namespace bapd {

namespace {

// Gmsh's tetrahedron element types (4-, 10-, 20-, 35-, 56-node); corner nodes come first.
bool IsTetrahedron(int type) { return type == 4 || type == 11 || type == 29 || type == 30 || type == 31; }

std::string ReadOpenModel(const std::string &file, nd::TetrahedronSet *set)
{
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3);
  if (types.empty()) {
    std::vector<std::pair<int, int>> volumes;
    gmsh::model::getEntities(volumes, 3);
    if (volumes.empty()) return "'" + file + "' holds no volume and no 3D element: give a .geo with a Volume, or a .msh of a 3D mesh";
    gmsh::model::mesh::generate(3);
    gmsh::model::mesh::getElements(types, tags, nodes, 3);
  }
  std::vector<std::size_t> node_tags;
  std::vector<double>      xyz, parametric;
  gmsh::model::mesh::getNodes(node_tags, xyz, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> where;
  for (std::size_t k = 0; k < node_tags.size(); ++k) where[node_tags[k]] = k;
  for (std::size_t t = 0; t < types.size(); ++t) {
    std::string         name;
    int                 dim, order, per, primary;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(types[t], name, dim, order, per, local, primary);
    if (!IsTetrahedron(types[t]))
      return "'" + file + "' holds 3D elements of a kind bapd does not read (" + name + "): mesh the volume with tetrahedra";
    for (std::size_t e = 0; e + static_cast<std::size_t>(per) <= nodes[t].size(); e += static_cast<std::size_t>(per))
      for (int c = 0; c < 4; ++c) {
        const std::size_t k = where.at(nodes[t][e + static_cast<std::size_t>(c)]);
        set->corners.insert(set->corners.end(), &xyz[3 * k], &xyz[3 * k] + 3);
      }
  }
  if (set->size() == 0) return "'" + file + "' holds no tetrahedron after meshing";
  nd::index_tetrahedra(*set);
  return "";
}

} // namespace

std::string ReadGmshTetrahedra(const std::string &file, nd::TetrahedronSet *tetrahedra)
{
  *tetrahedra      = nd::TetrahedronSet{};
  tetrahedra->file = file;
  return WithGmshFile(file, [&] { return ReadOpenModel(file, tetrahedra); });
}

} // namespace bapd
