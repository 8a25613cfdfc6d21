#pragma once
// The material points of a 2D body (METHOD.md section 1): a uniform grid of spacing
// dx, one point at the centre of each cell, points inside holes removed.
#include "bapd/body.hpp"

namespace bapd {

// Points at ((ix + 0.5) dx, (iy + 0.5) dx) for ix < nx = round(width / dx),
// iy < ny = round(height / dx), row by row (y outer, x inner). A point whose distance
// to a hole's centre is < radius is removed. natural_id is the compact index of the
// surviving points in that order; volume = dx^2 * thickness. family_volume is left
// empty (compute_family_volumes in family.hpp fills it).
// Throws std::invalid_argument for a non-positive dx, width, height or thickness.
PointCloud make_lattice(const Body2D &body);

} // namespace bapd
