#pragma once
// A 3D body's volume from Gmsh (issue 21, the 3D form of gmsh_shape.hpp): a .msh file's
// tetrahedra, or a .geo file with a volume meshed in 3D by Gmsh (Gmsh's C++ API), as
// the TetrahedronSet of a mesh solid (nd/shape3d.hpp). The lattice is then clipped to
// the meshed volume (nd::make_solid_points), as the 2D lattice is to a meshed surface.
#include <string>

#include "bapd/nd/shape3d.hpp"

namespace bapd {

// Reads `file` into `tetrahedra` (higher-order tetrahedra by their corner nodes) and
// indexes them. Returns "" or what went wrong, in words a user can act on: the file is
// missing, Gmsh cannot read it, it holds no volume and no 3D element, or 3D elements
// other than tetrahedra. Gmsh prints nothing.
std::string ReadGmshTetrahedra(const std::string &file, nd::TetrahedronSet *tetrahedra);

} // namespace bapd
