#pragma once
// The material points of a 2D body (METHOD.md section 1): a uniform grid of spacing
// dx, one point at the centre of each cell, points inside holes removed.
#include <cstdint>

#include "bapd/body.hpp"

namespace bapd {

// The hole rule, the one place it is written: a point at (x, y) lies inside hole h
// when its distance to the hole's centre is < radius (a point on the rim is
// material). Returns the first such hole's index, or -1 when the point is material.
// make_lattice, the scene's point estimate and its probe checks all call it.
int hole_containing(const Body2D &body, double x, double y);

// The lattice's cells: nx = round(width / dx) x ny = round(height / dx); 0 x 0 when
// dx, width or height is not positive. 64-bit: a fine spacing can pass 2^31 cells.
struct LatticeCells {
  int64_t nx = 0, ny = 0;
};
LatticeCells lattice_cells(const Body2D &body);

// How many points make_lattice keeps, counted without building them (cells less the
// centres inside holes). Cost: one test per cell, only when the body has holes.
int64_t lattice_point_count(const Body2D &body);

// Points at ((ix + 0.5) dx, (iy + 0.5) dx) for ix < nx = round(width / dx),
// iy < ny = round(height / dx), row by row (y outer, x inner). A point inside a hole
// (hole_containing) is removed. natural_id is the compact index of the
// surviving points in that order; volume = dx^2 * thickness. family_volume is left
// empty (compute_family_volumes in family.hpp fills it).
// Throws std::invalid_argument for a non-positive dx, width, height or thickness.
PointCloud make_lattice(const Body2D &body);

} // namespace bapd
