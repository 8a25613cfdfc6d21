#include "bapd/lattice.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bapd {

int hole_containing(const Body2D &body, double x, double y)
{
  for (std::size_t h = 0; h < body.holes.size(); ++h)
    if (std::hypot(x - body.holes[h].cx, y - body.holes[h].cy) < body.holes[h].radius) return static_cast<int>(h);
  return -1;
}

LatticeCells lattice_cells(const Body2D &body)
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

int64_t lattice_point_count(const Body2D &body)
{
  const LatticeCells cells = lattice_cells(body);
  if (cells.nx < 1 || cells.ny < 1) return 0;
  if (body.holes.empty()) return cells.nx * cells.ny;
  int64_t count = 0;
  for (int64_t iy = 0; iy < cells.ny; ++iy) {
    const double py = cell_centre(iy, body.dx);
    for (int64_t ix = 0; ix < cells.nx; ++ix)
      if (hole_containing(body, cell_centre(ix, body.dx), py) < 0) ++count;
  }
  return count;
}

PointCloud make_lattice(const Body2D &body)
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

  const double cell_volume = body.dx * body.dx * body.thickness;
  PointCloud   cloud;
  cloud.x.reserve(2 * static_cast<std::size_t>(nx * ny));
  cloud.volume.reserve(static_cast<std::size_t>(nx * ny));
  cloud.natural_id.reserve(static_cast<std::size_t>(nx * ny));
  for (int64_t iy = 0; iy < ny; ++iy) {
    const double py = cell_centre(iy, body.dx);
    for (int64_t ix = 0; ix < nx; ++ix) {
      const double px = cell_centre(ix, body.dx);
      if (hole_containing(body, px, py) >= 0) continue;
      cloud.natural_id.push_back(static_cast<int64_t>(cloud.volume.size()));
      cloud.x.push_back(px);
      cloud.x.push_back(py);
      cloud.volume.push_back(cell_volume);
    }
  }
  return cloud;
}

} // namespace bapd
