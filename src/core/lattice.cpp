#include "bapd/lattice.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bapd {

PointCloud make_lattice(const Body2D &body)
{
  if (!(body.dx > 0) || !(body.width > 0) || !(body.height > 0) || !(body.thickness > 0))
    throw std::invalid_argument("make_lattice: dx, width, height and thickness must be > 0 (got dx = " +
                                std::to_string(body.dx) + ", width = " + std::to_string(body.width) +
                                ", height = " + std::to_string(body.height) +
                                ", thickness = " + std::to_string(body.thickness) + ")");
  const long nx = std::lround(body.width / body.dx);
  const long ny = std::lround(body.height / body.dx);
  if (nx < 1 || ny < 1)
    throw std::invalid_argument("make_lattice: the body is narrower than one cell; reduce dx");

  const double cell_volume = body.dx * body.dx * body.thickness;
  PointCloud   cloud;
  cloud.x.reserve(2 * static_cast<std::size_t>(nx * ny));
  cloud.volume.reserve(static_cast<std::size_t>(nx * ny));
  cloud.natural_id.reserve(static_cast<std::size_t>(nx * ny));
  for (long iy = 0; iy < ny; ++iy) {
    const double py = (static_cast<double>(iy) + 0.5) * body.dx;
    for (long ix = 0; ix < nx; ++ix) {
      const double px     = (static_cast<double>(ix) + 0.5) * body.dx;
      bool         inside = false;
      for (const Circle &h : body.holes)
        if (std::hypot(px - h.cx, py - h.cy) < h.radius) inside = true;
      if (inside) continue;
      cloud.natural_id.push_back(static_cast<int64_t>(cloud.volume.size()));
      cloud.x.push_back(px);
      cloud.x.push_back(py);
      cloud.volume.push_back(cell_volume);
    }
  }
  return cloud;
}

} // namespace bapd
