#pragma once
// One Gmsh read, shared by the 2D shapes and groups (gmsh_shape.cpp) and the 3D volumes
// (gmsh_volume3d.cpp): the file checked, a Gmsh session initialised and finalised on
// every path, the file opened, and any Gmsh failure turned into one sentence; and what
// both read of a model: the corners of 2D elements, a physical group by name.
// Include only from a .cpp that links Gmsh.
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/input/input_file.hpp"

namespace bapd {

// gmsh::initialize / finalize around one read, on every path.
struct GmshSession {
  GmshSession()
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
    // Without it Gmsh asks on stdin whether to go on with a mesh size it finds too small.
    gmsh::option::setNumber("General.ExpertMode", 1);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession &)            = delete;
  GmshSession &operator=(const GmshSession &) = delete;
};

// Opens `file` in a Gmsh session of its own and returns read() (what went wrong, or "")
// on the open model; a file that is missing or that Gmsh cannot read is reported.
template <class Read> std::string WithGmshFile(const std::string &file, Read read)
{
  if (std::string why = NotARegularFile(file); !why.empty()) return why;
  if (std::FILE *f = std::fopen(file.c_str(), "rb")) std::fclose(f);
  else return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  GmshSession session; // finalised on every return below
  try {
    gmsh::open(file);
    return read();
  } catch (...) {
    std::string last;
    try {
      gmsh::logger::getLastError(last);
    } catch (...) {
    }
    return "Gmsh cannot read '" + file + "'" + (last.empty() ? std::string(" (not a .geo or .msh file?)") : ": " + last);
  }
}

// Each element type of dimension dim in entity tag (-1: every entity) of the open model:
// visit(type, name, nodes per element, node tags of its elements); returns the first
// message a visit returns ("" when none does).
template <class Visit> std::string ForEachElementType(int dim, int tag, Visit visit)
{
  std::vector<int>                      types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, dim, tag);
  for (std::size_t t = 0; t < types.size(); ++t) {
    std::string         name;
    int                 type_dim, order, per, primary;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(types[t], name, type_dim, order, per, local, primary);
    if (std::string why = visit(types[t], name, static_cast<std::size_t>(per), nodes[t]); !why.empty()) return why;
  }
  return "";
}

// Meshes the open model in `dim` dimensions. The mesh only tells which lattice points
// lie inside the body, so a mesh far finer than any lattice costs time and nothing else:
// a .geo whose mesh size is 1e-9 m meshed for hours. Element sizes are held at or above
// 1/300 of the model's bounding-box diagonal in 2D (about 1e5 triangles at most;
// a chord strays from a circle of radius R by at most diagonal^2 / (7e5 R)) and 1/50
// in 3D (about 1e5 tetrahedra); a file's own larger Mesh.MeshSizeMin is kept. Gmsh
// applies Mesh.MeshSizeMax after the minimum, so a file's smaller maximum (1e-7 m:
// meshed for ever) is raised to the floor too.
inline void GenerateOutlineMesh(int dim)
{
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double diagonal = std::sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + (z1 - z0) * (z1 - z0));
  const double floor    = diagonal / (dim == 3 ? 50.0 : 300.0);
  double       size_min = 0, size_max = 0;
  gmsh::option::getNumber("Mesh.MeshSizeMin", size_min);
  gmsh::option::getNumber("Mesh.MeshSizeMax", size_max);
  gmsh::option::setNumber("Mesh.MeshSizeMin", std::max(size_min, floor));
  gmsh::option::setNumber("Mesh.MeshSizeMax", std::max(size_max, floor));
  gmsh::model::mesh::generate(dim);
}

// Gmsh's element types with a 2D cell, and how many of their first nodes are the
// corners (Gmsh numbers corner nodes first): 3-, 6-, 9-, 10-node triangles and 4-,
// 8-, 9-node quadrangles; 0 for any other type.
inline int GmshCornerCount2D(int type)
{
  switch (type) {
  case 2: case 9: case 20: case 21: return 3;
  case 3: case 10: case 16: return 4;
  default: return 0;
  }
}

// The word for a physical group of dimension dim (messages).
inline const char *GmshDimensionWord(int dim) { return dim == 2 ? "surface" : dim == 1 ? "curve" : dim == 0 ? "point" : "volume"; }

// Finds the physical group `name` of the open model: "" and its dimension and tag, or
// what is wrong: two groups of that name, or none (the message lists the groups the file
// has, with their dimensions; `how_to_name` says how to name one when it has none).
inline std::string FindPhysicalGroup(const std::string &file, const std::string &name, const std::string &how_to_name, int *dim, int *tag)
{
  std::vector<std::pair<int, int>> groups;
  gmsh::model::getPhysicalGroups(groups);
  std::string have;
  *dim = *tag = -1;
  for (const auto &[d, t] : groups) {
    std::string group_name;
    gmsh::model::getPhysicalName(d, t, group_name);
    if (group_name != name) {
      have += (have.empty() ? "" : ", ") + (group_name.empty() ? "(unnamed, tag " + std::to_string(t) + ")" : "'" + group_name + "'") + " (" +
              GmshDimensionWord(d) + ")";
      continue;
    }
    if (*dim >= 0) return "'" + file + "' has two physical groups named '" + name + "': give them different names";
    *dim = d, *tag = t;
  }
  if (*dim < 0)
    return "'" + file + "' has no physical group named '" + name + "' " + (have.empty() ? "(it names none: " + how_to_name + ")" : "(it has " + have + ")");
  return "";
}

} // namespace bapd
