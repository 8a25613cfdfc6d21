#pragma once
// A body's outline from Gmsh (-body_S_type mesh, -body_S_file F): a .msh file's 2D
// elements, or a .geo file meshed in 2D by Gmsh (Debian's libgmsh-dev, Gmsh's C++
// API), as the triangles of a Shape (shape.hpp). The lattice is then clipped to the
// meshed domain: the uniform lattice keeps the accuracy of BA on a regular grid.
// A file's named physical groups (Physical Surface("grip") = ...) are read the same
// way and become load sets (-load_S_region group, scene_loading.hpp).
#include <string>
#include <vector>

#include "bapd/core/geometry/shape.hpp"

namespace bapd {

// Reads `file` into `triangles` (quadrangles split in two, higher-order elements by
// their corner nodes; z ignored) and indexes them. Returns "" or what went wrong, in
// words a user can act on (the file is missing, Gmsh cannot read it, it holds no 2D
// element). Gmsh prints nothing.
std::string ReadGmshTriangles(const std::string &file, TriangleSet *triangles);

// A named physical group of a Gmsh file, as geometry: a physical surface is the
// triangles of its 2D elements; a physical curve the segments of its line elements
// (the curve as Gmsh meshed it: chords of an arc); a physical point its nodes, as
// segments of zero length.
struct GmshGroup {
  std::string         name;
  int                 dim = -1;  // 2, 1 or 0
  TriangleSet         triangles; // dim 2 (indexed)
  std::vector<double> segments;  // dim 1 and 0: x0,y0,x1,y1 per segment [m]
};

// Reads the physical group `name` of `file` (a .geo is meshed in 2D first, as for
// ReadGmshTriangles). Returns "" or what went wrong: the file is missing or Gmsh cannot
// read it, or it has no group of that name (the message lists the groups it has, with
// their dimensions, or says it has none and how to name one).
std::string ReadGmshGroup(const std::string &file, const std::string &name, GmshGroup *group);

} // namespace bapd
