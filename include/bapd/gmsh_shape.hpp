#pragma once
// A body's outline from Gmsh (-body_S_type mesh, -body_S_file F): a .msh file's 2D
// elements, or a .geo file meshed in 2D by Gmsh (Debian's libgmsh-dev, Gmsh's C++
// API), as the triangles of a Shape (shape.hpp). The lattice is then clipped to the
// meshed domain: the uniform lattice keeps the accuracy of BA on a regular grid.
#include <string>

#include "bapd/shape.hpp"

namespace bapd {

// Reads `file` into `triangles` (quadrangles split in two, higher-order elements by
// their corner nodes; z ignored) and indexes them. Returns "" or what went wrong, in
// words a user can act on (the file is missing, Gmsh cannot read it, it holds no 2D
// element). Gmsh prints nothing.
std::string ReadGmshTriangles(const std::string &file, TriangleSet *triangles);

} // namespace bapd
