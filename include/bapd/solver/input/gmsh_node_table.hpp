#pragma once
// The open Gmsh model's node coordinates by node tag, for the readers of its elements
// (gmsh_shape.cpp in 2D, gmsh_volume3d.cpp in 3D).
#include <gmsh.h>

#include <cstddef>
#include <unordered_map>
#include <vector>

namespace bapd {

class GmshNodeTable {
public:
  GmshNodeTable()
  {
    std::vector<std::size_t> node_tags;
    std::vector<double>      parametric;
    gmsh::model::mesh::getNodes(node_tags, xyz_, parametric, -1, -1, false, false);
    for (std::size_t k = 0; k < node_tags.size(); ++k) where_[node_tags[k]] = k;
  }
  // x, y, z of the node with this tag.
  const double *at(std::size_t tag) const { return &xyz_[3 * where_.at(tag)]; }

private:
  std::vector<double>                          xyz_;
  std::unordered_map<std::size_t, std::size_t> where_;
};

} // namespace bapd
