#pragma once
// The material points of a 2D body (docs/method.md section 1): a uniform grid of spacing
// dx, one point at the centre of each cell, points inside holes removed.
#include <cstdint>
#include <vector>

#include "bapd/core/geometry/body.hpp"

namespace bapd {

// The hole rule, the one place it is written: a point at (x, y) lies inside hole h
// when its distance to the hole's centre is < radius (a point on the rim is
// material). Returns the first such hole's index, or -1 when the point is material.
// make_lattice, the scene's point estimate and its probe checks all call it.
int hole_containing(const Body<2> &body, double x, double y);

// The material rule of the whole body: (x, y) in the sheet is material unless a hole
// contains it (hole_containing) or the shapes remove it (shape_removing, shape.hpp).
bool is_material(const Body<2> &body, double x, double y);

// The body's pieces on the lattice: material cells joined to their four neighbours
// unless a notch crosses the link. `count` is 0 when the lattice was too large to
// look at (more than 2e7 cells); `smallest_x/y` is a point of the smallest piece.
struct LatticePieces {
  int64_t count = 0, smallest_points = 0;
  double  smallest_x = 0, smallest_y = 0;
};
LatticePieces lattice_pieces(const Body<2> &body);

// The sheet's cells (the grips' rows outside it not counted): nx = round(width / dx) x ny = round(height / dx); 0 x 0 when
// dx, width or height is not positive. 64-bit: a fine spacing can pass 2^31 cells.
struct LatticeCells {
  int64_t nx = 0, ny = 0;
};
LatticeCells lattice_cells(const Body<2> &body);

// How many points make_lattice keeps, grips outside the sheet included, counted
// without building them (cells less the centres inside holes), exactly, row by row (one chord per hole and row). Beyond
// 1e8 row-hole pairs (a body no machine holds) it estimates from the hole areas.
// With shapes, every cell is tested up to 2e7 cells (as lattice_pieces); beyond, a 4000 x 4000 sample of
// the cells estimates the fraction kept.
int64_t lattice_point_count(const Body<2> &body);

// Points at ((ix + 0.5) dx, (iy + 0.5) dx) for ix < nx = round(width / dx),
// iy < ny = round(height / dx), row by row (y outer, x inner); with grips outside the
// sheet (Body<2>::grip_rows) ix runs from -left to nx + right - 1 and iy from -bottom
// to ny + top - 1, a cell outside the sheet being material where the sheet's edge
// cell it extrudes is. A point that is not
// material (is_material: inside a hole, or removed by the shapes) is left out. natural_id is the compact index of the
// surviving points in that order; volume = dx^2 * thickness. family_volume is left
// empty (compute_family_volumes in family.hpp fills it).
// Throws std::invalid_argument for a non-positive dx, width, height or thickness.
PointCloud make_lattice(const Body<2> &body);

// The lattice row by row, for a body built in slabs of rows (one a rank): row 0 is
// the lowest (iy = -grip_rows.bottom), lattice_rows(body) of them (0 for a body
// narrower than a cell). append_lattice_rows appends the points of rows
// [row_begin, row_end) to *cloud in make_lattice's order, natural_id = the point's
// index in *cloud (a slab's caller renumbers them), and, when row_counts is given,
// each row's count of points to it. make_lattice is it over every row.
int64_t lattice_rows(const Body<2> &body);
void    append_lattice_rows(const Body<2> &body, int64_t row_begin, int64_t row_end, PointCloud *cloud,
                            std::vector<int64_t> *row_counts);

} // namespace bapd
