#pragma once
// A 3D body's volume from Gmsh (the 3D form of gmsh_shape.hpp): a .msh file's
// tetrahedra, or a .geo file with a volume meshed in 3D by Gmsh (Gmsh's C++ API), as
// the TetrahedronSet of a mesh solid (shape3d.hpp). The lattice is then clipped to
// the meshed volume (nd::make_solid_points), as the 2D lattice is to a meshed surface.
// Its named physical groups become load sets and probes (scene_loading.cpp, scene_probes.cpp).
#include <string>

#include "bapd/core/geometry/shape3d.hpp"

namespace bapd {

// Reads `file` into `tetrahedra` (higher-order tetrahedra by their corner nodes) and
// indexes them. Returns "" or what went wrong, in words a user can act on: the file is
// missing, Gmsh cannot read it, it holds no volume and no 3D element, or 3D elements
// other than tetrahedra. Gmsh prints nothing.
std::string ReadGmshTetrahedra(const std::string &file, nd::TetrahedronSet *tetrahedra);

// Reads the physical group `name` of `file` (meshed in 3D first, as for
// ReadGmshTetrahedra) as a region of points (nd::ElementRegion): a physical volume's
// tetrahedra, or a physical surface's triangles (quadrangles split in two), a physical
// curve's line segments or a physical point's nodes, with `depth` (the distance within
// which those hold a point). Returns "" or what went wrong: the file is missing or Gmsh
// cannot read it, it holds no volume, it has no group of that name (the message lists
// the groups it has, with their dimensions), or two, or the group holds no element.
std::string ReadGmshGroup3D(const std::string &file, const std::string &name, double depth, nd::ElementRegion *region);

} // namespace bapd
