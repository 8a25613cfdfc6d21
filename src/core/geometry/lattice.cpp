#include "bapd/core/geometry/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bapd {

int hole_containing(const Body<2> &body, double x, double y)
{
  for (std::size_t h = 0; h < body.holes.size(); ++h)
    if (std::hypot(x - body.holes[h].cx, y - body.holes[h].cy) < body.holes[h].radius) return static_cast<int>(h);
  return -1;
}

bool is_material(const Body<2> &body, double x, double y)
{
  return hole_containing(body, x, y) < 0 && (body.shapes.empty() || shape_removing(body.shapes, x, y) < 0);
}

LatticeCells lattice_cells(const Body<2> &body)
{
  if (!(body.dx > 0) || !(body.width > 0) || !(body.height > 0)) return {};
  // llround of a ratio too large for int64 is unspecified: such a body is refused
  // long before by the memory estimate, so report it as empty rather than wrap.
  const double rx = body.width / body.dx, ry = body.height / body.dx;
  if (!(rx < 9.0e18) || !(ry < 9.0e18)) return {};
  return {std::llround(rx), std::llround(ry)};
}

// The centre of cell i along an axis: (i + 0.5) dx.
static double cell_centre(int64_t i, double dx) { return (static_cast<double>(i) + 0.5) * dx; }

// The cells of the whole lattice, the grips' rows outside the sheet included:
// ix in [x0, x1), iy in [y0, y1) (Body<2>::grip_rows; x0, y0 <= 0).
struct CellRange {
  int64_t x0, x1, y0, y1;
  int64_t nx() const { return x1 - x0; }
  int64_t ny() const { return y1 - y0; }
};
static CellRange cell_range(const Body<2> &body, const LatticeCells &cells)
{
  const EdgeRows &g = body.grip_rows;
  return {-g.left, cells.nx + g.right, -g.bottom, cells.ny + g.top};
}

// Whether cell (ix, iy) is material: a cell of a grip outside the sheet is its edge
// row's (column's) cell extruded, so the sheet's cell it is clamped onto decides.
static bool material_cell(const Body<2> &body, const LatticeCells &cells, int64_t ix, int64_t iy)
{
  const int64_t cx = std::clamp<int64_t>(ix, 0, cells.nx - 1), cy = std::clamp<int64_t>(iy, 0, cells.ny - 1);
  return is_material(body, cell_centre(cx, body.dx), cell_centre(cy, body.dx));
}

// The cells of one row (centre height py) inside hole h, as [lo, hi] (empty when
// lo > hi): the chord of the circle gives the range to within round-off, and the
// hole rule itself settles both ends, so the count agrees with make_lattice point
// for point. A disk's chord is one interval, so the cells between the ends are in.
static void hole_row_cells(const Body<2> &body, const Circle &h, int64_t nx, double py, int64_t *lo, int64_t *hi)
{
  const double dy    = py - h.cy;
  const double chord = std::sqrt(std::max(0.0, h.radius * h.radius - dy * dy));
  auto         in    = [&](int64_t ix) { return std::hypot(cell_centre(ix, body.dx) - h.cx, dy) < h.radius; };
  int64_t      a     = std::max<int64_t>(0, static_cast<int64_t>(std::ceil((h.cx - chord) / body.dx - 0.5)) - 2);
  int64_t      b     = std::min<int64_t>(nx - 1, static_cast<int64_t>(std::floor((h.cx + chord) / body.dx - 0.5)) + 2);
  while (a <= b && !in(a)) ++a;
  while (b >= a && !in(b)) --b;
  *lo = a;
  *hi = b;
}

// Bodies with shapes: every cell tested, or a regular sample of them scaled up.
static int64_t shaped_point_count(const Body<2> &body, const LatticeCells &cells)
{
  const CellRange r      = cell_range(body, cells);
  const double    total  = static_cast<double>(r.nx()) * static_cast<double>(r.ny());
  const int64_t   sx     = total > 2e7 ? std::max<int64_t>(1, r.nx() / 4000) : 1;
  const int64_t   sy     = total > 2e7 ? std::max<int64_t>(1, r.ny() / 4000) : 1;
  int64_t         kept = 0, tested = 0;
  for (int64_t iy = r.y0; iy < r.y1; iy += sy)
    for (int64_t ix = r.x0; ix < r.x1; ix += sx, ++tested) kept += material_cell(body, cells, ix, iy);
  if (sx == 1 && sy == 1) return kept;
  return static_cast<int64_t>(total * static_cast<double>(kept) / static_cast<double>(tested));
}

int64_t lattice_point_count(const Body<2> &body)
{
  const LatticeCells cells = lattice_cells(body);
  if (cells.nx < 1 || cells.ny < 1) return 0;
  if (!body.shapes.empty()) return shaped_point_count(body, cells);
  const CellRange r = cell_range(body, cells);
  if (body.holes.empty()) return r.nx() * r.ny();
  // Row by row, one chord per hole: O(ny x holes). A body of more rows than that can
  // afford has far more points than any machine holds: the hole areas estimate it.
  const double work = static_cast<double>(r.ny()) * static_cast<double>(body.holes.size());
  if (work > 1e8) {
    double removed = 0;
    for (const Circle &h : body.holes) removed += M_PI * h.radius * h.radius / (body.dx * body.dx);
    return std::max<int64_t>(0, r.nx() * r.ny() - static_cast<int64_t>(removed));
  }
  int64_t                                  count = 0;
  std::vector<std::pair<int64_t, int64_t>> runs; // cells inside some hole, this row
  for (int64_t iy = r.y0; iy < r.y1; ++iy) {
    // A grip row outside the sheet is its edge row extruded (material_cell).
    const double py = cell_centre(std::clamp<int64_t>(iy, 0, cells.ny - 1), body.dx);
    runs.clear();
    for (const Circle &h : body.holes) {
      if (std::fabs(py - h.cy) > h.radius) continue;
      int64_t lo, hi;
      hole_row_cells(body, h, cells.nx, py, &lo, &hi);
      if (lo <= hi) runs.emplace_back(lo, hi);
    }
    std::sort(runs.begin(), runs.end());
    int64_t removed = 0, end = -1; // cells [0, end] already counted as removed
    bool    first_in = false, last_in = false; // cells 0 and nx - 1 removed (the side grips extrude them)
    for (const auto &run : runs) {
      const int64_t from = std::max(run.first, end + 1);
      if (run.second >= from) removed += run.second - from + 1;
      end = std::max(end, run.second);
      first_in = first_in || run.first == 0;
      last_in  = last_in || run.second == cells.nx - 1;
    }
    count += cells.nx - removed + (first_in ? 0 : body.grip_rows.left) + (last_in ? 0 : body.grip_rows.right);
  }
  return count;
}

// Whether the link between the centres (ax, ay) and (bx, by) of two neighbouring
// cells crosses a notch (then no bond joins them either).
static bool notch_cuts(const Body<2> &body, double ax, double ay, double bx, double by)
{
  for (const Segment &g : body.notches) {
    auto side = [](double px, double py, double qx, double qy, double rx, double ry) {
      return (qx - px) * (ry - py) - (qy - py) * (rx - px);
    };
    const double d1 = side(g.x0, g.y0, g.x1, g.y1, ax, ay), d2 = side(g.x0, g.y0, g.x1, g.y1, bx, by);
    const double d3 = side(ax, ay, bx, by, g.x0, g.y0), d4 = side(ax, ay, bx, by, g.x1, g.y1);
    if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return true;
  }
  return false;
}

LatticePieces lattice_pieces(const Body<2> &body)
{
  LatticePieces      pieces;
  const LatticeCells cells = lattice_cells(body);
  if (cells.nx < 1 || cells.ny < 1) return pieces;
  const CellRange r = cell_range(body, cells);
  if (static_cast<double>(r.nx()) * static_cast<double>(r.ny()) > 2e7) return pieces;
  // Cell c is (ix, iy) = (x0 + c % nx, y0 + c / nx) of the whole lattice, grips included.
  const int64_t        nx = r.nx(), ny = r.ny(), n = nx * ny;
  auto                 centre_x = [&](int64_t c) { return cell_centre(r.x0 + c % nx, body.dx); };
  auto                 centre_y = [&](int64_t c) { return cell_centre(r.y0 + c / nx, body.dx); };
  std::vector<int8_t>  state(static_cast<std::size_t>(n), 0); // 0 void, 1 material, 2 reached
  for (int64_t c = 0; c < n; ++c) state[c] = material_cell(body, cells, r.x0 + c % nx, r.y0 + c / nx);
  std::vector<int64_t> stack;
  pieces.smallest_points = n + 1;
  for (int64_t seed = 0; seed < n; ++seed) {
    if (state[seed] != 1) continue;
    int64_t size = 0;
    state[seed]  = 2;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int64_t c = stack.back();
      stack.pop_back();
      ++size;
      const int64_t ix = c % nx, iy = c / nx;
      const double  x = centre_x(c), y = centre_y(c);
      const int64_t next[4][2] = {{ix - 1, iy}, {ix + 1, iy}, {ix, iy - 1}, {ix, iy + 1}};
      for (const auto &q : next) {
        if (q[0] < 0 || q[0] >= nx || q[1] < 0 || q[1] >= ny) continue;
        const int64_t k = q[1] * nx + q[0];
        if (state[k] != 1 || notch_cuts(body, x, y, centre_x(k), centre_y(k))) continue;
        state[k] = 2;
        stack.push_back(k);
      }
    }
    ++pieces.count;
    if (size < pieces.smallest_points) {
      pieces.smallest_points = size;
      pieces.smallest_x      = centre_x(seed);
      pieces.smallest_y      = centre_y(seed);
    }
  }
  if (pieces.count == 0) pieces.smallest_points = 0;
  return pieces;
}

int64_t lattice_rows(const Body<2> &body)
{
  const LatticeCells cells = lattice_cells(body);
  if (cells.nx < 1 || cells.ny < 1) return 0;
  return cell_range(body, cells).ny();
}

void append_lattice_rows(const Body<2> &body, int64_t row_begin, int64_t row_end, PointCloud *cloud, std::vector<int64_t> *row_counts)
{
  const LatticeCells cells = lattice_cells(body);
  if (cells.nx < 1 || cells.ny < 1) return;
  const CellRange r           = cell_range(body, cells);
  const double    cell_volume = body.dx * body.dx * body.thickness;
  row_begin                   = std::max<int64_t>(row_begin, 0);
  row_end                     = std::min<int64_t>(row_end, r.ny());
  if (row_end <= row_begin) return;
  const auto most = cloud->size() + static_cast<std::size_t>(r.nx() * (row_end - row_begin));
  cloud->x.reserve(2 * most);
  cloud->volume.reserve(most);
  cloud->natural_id.reserve(most);
  for (int64_t iy = r.y0 + row_begin; iy < r.y0 + row_end; ++iy) {
    const double      py    = cell_centre(iy, body.dx);
    const std::size_t first = cloud->size();
    for (int64_t ix = r.x0; ix < r.x1; ++ix) {
      const double px = cell_centre(ix, body.dx);
      if (!material_cell(body, cells, ix, iy)) continue;
      cloud->natural_id.push_back(static_cast<int64_t>(cloud->volume.size()));
      cloud->x.push_back(px);
      cloud->x.push_back(py);
      cloud->volume.push_back(cell_volume);
    }
    if (row_counts) row_counts->push_back(static_cast<int64_t>(cloud->size() - first));
  }
}

PointCloud make_lattice(const Body<2> &body)
{
  if (!(body.dx > 0) || !(body.width > 0) || !(body.height > 0) || !(body.thickness > 0))
    throw std::invalid_argument("make_lattice: dx, width, height and thickness must be > 0 (got dx = " +
                                std::to_string(body.dx) + ", width = " + std::to_string(body.width) +
                                ", height = " + std::to_string(body.height) +
                                ", thickness = " + std::to_string(body.thickness) + ")");
  const LatticeCells cells = lattice_cells(body);
  const int64_t      nx = cells.nx, ny = cells.ny;
  if (nx < 1 || ny < 1)
    throw std::invalid_argument("make_lattice: the body is narrower than one cell; reduce dx");

  PointCloud cloud;
  append_lattice_rows(body, 0, lattice_rows(body), &cloud, nullptr);
  return cloud;
}

} // namespace bapd
