#include "bapd/core/geometry/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bapd/core/geometry/lattice.hpp"

namespace bapd {

double smallest_spacing(const GivenPoints &points, double thickness)
{
  double smallest = std::numeric_limits<double>::infinity();
  for (double v : points.volume) smallest = std::min(smallest, point_spacing(v, thickness));
  return smallest;
}

PointCloud make_points(const Body<2> &body, double horizon_factor)
{
  if (!body.given_points) return make_lattice(body);
  const GivenPoints &given = *body.given_points;
  PointCloud         cloud;
  for (std::size_t p = 0; p < given.size(); ++p) {
    const double x = given.x[2 * p], y = given.x[2 * p + 1];
    if (!is_material(body, x, y)) continue;
    cloud.natural_id.push_back(static_cast<int64_t>(cloud.volume.size()));
    cloud.x.push_back(x);
    cloud.x.push_back(y);
    cloud.volume.push_back(given.volume[p]);
  }
  set_point_horizons(&cloud, 2, horizon_factor, body.thickness);
  return cloud;
}

void set_point_horizons(PointCloud *cloud, int dimension, double horizon_factor, double thickness)
{
  cloud->horizon.resize(cloud->size());
  for (std::size_t p = 0; p < cloud->size(); ++p)
    cloud->horizon[p] = horizon_factor * point_spacing(dimension, cloud->volume[p], thickness);
}

GivenPoints element_centroids(const TriangleSet &triangles, double thickness)
{
  GivenPoints       out;
  const std::size_t n = triangles.size();
  for (std::size_t t = 0; t < n; ++t) {
    const double *c    = triangles.corners.data() + 6 * t;
    const double  area = 0.5 * std::fabs((c[2] - c[0]) * (c[5] - c[1]) - (c[4] - c[0]) * (c[3] - c[1]));
    const double  cx = (c[0] + c[2] + c[4]) / 3.0, cy = (c[1] + c[3] + c[5]) / 3.0;
    const bool    same = t > 0 && !triangles.element.empty() && triangles.element[t] == triangles.element[t - 1];
    if (!same) {
      out.x.push_back(cx * area);
      out.x.push_back(cy * area);
      out.volume.push_back(area);
      continue;
    }
    out.x[out.x.size() - 2] += cx * area; // the second triangle of a quadrangle
    out.x.back() += cy * area;
    out.volume.back() += area;
  }
  for (std::size_t p = 0; p < out.size(); ++p) {
    const double area = out.volume[p];
    out.x[2 * p] /= area;
    out.x[2 * p + 1] /= area;
    out.volume[p] = area * thickness;
  }
  out.block.assign(out.size(), 1);
  return out;
}

int64_t body_point_count(const Body<2> &body)
{
  if (!body.given_points) return lattice_point_count(body);
  const GivenPoints &given = *body.given_points;
  int64_t            kept  = 0;
  for (std::size_t p = 0; p < given.size(); ++p) kept += is_material(body, given.x[2 * p], given.x[2 * p + 1]);
  return kept;
}

} // namespace bapd
