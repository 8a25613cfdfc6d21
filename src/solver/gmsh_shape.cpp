// A Gmsh file as the triangles of a shape (gmsh_shape.hpp).
#include "bapd/gmsh_shape.hpp"

#include <gmsh.h>

#include <cstdio>
#include <unordered_map>
#include <vector>

namespace bapd {

namespace {

// Gmsh's element types with a 2D cell, and how many of their first nodes are the
// corners (Gmsh numbers corner nodes first): 3-, 6-, 9-, 10-node triangles and 4-,
// 8-, 9-node quadrangles.
int CornerCount(int type)
{
  switch (type) {
  case 2: case 9: case 20: case 21: return 3;
  case 3: case 10: case 16: return 4;
  default: return 0;
  }
}

// gmsh::initialize / finalize around one read, on every path.
struct GmshSession {
  GmshSession()
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
};

} // namespace

std::string ReadGmshTriangles(const std::string &file, TriangleSet *triangles)
{
  triangles->corners.clear();
  triangles->element.clear();
  if (std::FILE *f = std::fopen(file.c_str(), "rb")) std::fclose(f);
  else return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  GmshSession session; // finalised on every return below
  try {
    gmsh::open(file);
    std::vector<int>                      types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, 2);
    if (types.empty()) {
      std::vector<std::pair<int, int>> surfaces;
      gmsh::model::getEntities(surfaces, 2);
      if (surfaces.empty()) return "'" + file + "' holds no surface and no 2D element: give a .geo with a Plane Surface, or a .msh of a 2D mesh";
      gmsh::model::mesh::generate(2);
      gmsh::model::mesh::getElements(types, tags, nodes, 2);
    }
    std::vector<std::size_t> node_tags;
    std::vector<double>      xyz, parametric;
    gmsh::model::mesh::getNodes(node_tags, xyz, parametric, -1, -1, false, false);
    std::unordered_map<std::size_t, std::size_t> where;
    for (std::size_t k = 0; k < node_tags.size(); ++k) where[node_tags[k]] = k;
    auto corner = [&](std::size_t tag, std::vector<double> &out) {
      const std::size_t k = where.at(tag);
      out.push_back(xyz[3 * k]);
      out.push_back(xyz[3 * k + 1]);
    };
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string              name;
      int                      dim, order, per, primary;
      std::vector<double>      local;
      gmsh::model::mesh::getElementProperties(types[t], name, dim, order, per, local, primary);
      const int corners = CornerCount(types[t]);
      if (corners == 0) return "'" + file + "' has 2D elements of a kind bapd does not read (" + name + "): mesh with triangles or quadrangles";
      for (std::size_t e = 0; e + per <= nodes[t].size(); e += (std::size_t)per) {
        const std::size_t *n = &nodes[t][e];
        const std::size_t element = triangles->element.empty() ? 0 : triangles->element.back() + 1;
        corner(n[0], triangles->corners), corner(n[1], triangles->corners), corner(n[2], triangles->corners);
        triangles->element.push_back(element);
        if (corners == 4) {
          corner(n[0], triangles->corners), corner(n[2], triangles->corners), corner(n[3], triangles->corners);
          triangles->element.push_back(element);
        }
      }
    }
  } catch (...) {
    std::string last;
    try {
      gmsh::logger::getLastError(last);
    } catch (...) {
    }
    return "Gmsh cannot read '" + file + "'" + (last.empty() ? std::string(" (not a .geo or .msh file?)") : ": " + last);
  }
  if (triangles->corners.empty()) return "'" + file + "' holds no 2D element after meshing: check its surfaces";
  index_triangles(*triangles);
  return "";
}

} // namespace bapd
