// A 3D point cloud text file (point_cloud3d.hpp).
#include "bapd/core/geometry/point_cloud3d.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>

#include "bapd/core/geometry/text_table.hpp"

namespace bapd::nd {

namespace {

std::string format(const char *fmt, ...)
{
  char    text[400];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(text, sizeof text, fmt, args);
  va_end(args);
  return text;
}

// Two points at one position (to 1e-9 of the cloud's extent): sorted along x, a point
// can only coincide with the next few. "" or the message.
std::string coincident(const std::string &file, const PointCloud &c, const std::vector<long> &line_of)
{
  const std::size_t n = c.size();
  double            extent = std::cbrt(c.volume[0]);
  for (int r = 0; r < 3; ++r) {
    double lo = c.x[r], hi = lo;
    for (std::size_t p = 0; p < n; ++p) lo = std::min(lo, c.x[3 * p + r]), hi = std::max(hi, c.x[3 * p + r]);
    extent = std::max(extent, hi - lo);
  }
  const double             tol = 1e-9 * extent;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return c.x[3 * a] < c.x[3 * b] || (c.x[3 * a] == c.x[3 * b] && a < b);
  });
  for (std::size_t s = 0; s < n; ++s)
    for (std::size_t t = s + 1; t < n && c.x[3 * order[t]] - c.x[3 * order[s]] <= tol; ++t) {
      const std::size_t a = std::min(order[s], order[t]), b = std::max(order[s], order[t]);
      if (std::fabs(c.x[3 * a + 1] - c.x[3 * b + 1]) <= tol && std::fabs(c.x[3 * a + 2] - c.x[3 * b + 2]) <= tol)
        return format("'%s': lines %ld and %ld are the same point (%g, %g, %g) m: remove the duplicate (points closer "
                      "than %g m count as one)",
                      file.c_str(), line_of[a], line_of[b], c.x[3 * a], c.x[3 * a + 1], c.x[3 * a + 2], tol);
    }
  return "";
}

} // namespace

std::string read_point_cloud_3d(const std::string &file, PointCloud *points, std::vector<int64_t> *block)
{
  *points = PointCloud{};
  block->clear();
  std::ifstream in(file);
  if (!in) return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  std::string              trimmed;
  std::vector<std::string> header;
  std::vector<long>        line_of; // the file line of each point, for messages
  long                     at = 0;
  std::vector<int>         col; // the columns of x, y, z, volume, block
  const char              *names[5] = {"x", "y", "z", "volume", "block_id"};
  while (next_table_line(in, header.empty(), &at, &trimmed)) {
    if (header.empty()) {
      header = table_tokens(trimmed, true);
      const std::string problem = table_header(file, at, header, "", {"x", "y", "z", "volume", "block_id|block"}, 4, &col);
      if (!problem.empty()) return problem;
      continue;
    }
    const std::vector<std::string> row = table_tokens(trimmed, true);
    if (row.size() != header.size())
      return format("'%s', line %ld holds %zu values, the header names %zu columns: give one value per column",
                    file.c_str(), at, row.size(), header.size());
    double value[5] = {0, 0, 0, 0, 1};
    for (int k = 0; k < 5; ++k)
      if (col[k] >= 0 && !table_number(row[static_cast<std::size_t>(col[k])], &value[k]))
        return format("'%s', line %ld: '%s' (column %s) is not a number", file.c_str(), at,
                      row[static_cast<std::size_t>(col[k])].c_str(), names[k]);
    if (!std::isfinite(value[0]) || !std::isfinite(value[1]) || !std::isfinite(value[2]))
      return format("'%s', line %ld: the position is not a finite number", file.c_str(), at);
    if (!(value[3] > 0) || !std::isfinite(value[3]))
      return format("'%s', line %ld (at (%g, %g, %g) m): volume %g m^3; every point's volume must be > 0", file.c_str(), at,
                    value[0], value[1], value[2], value[3]);
    if (value[4] != std::floor(value[4]))
      return format("'%s', line %ld: block id %g is not a whole number", file.c_str(), at, value[4]);
    points->x.insert(points->x.end(), value, value + 3);
    points->volume.push_back(value[3]);
    points->natural_id.push_back(static_cast<int64_t>(line_of.size()));
    block->push_back(static_cast<int64_t>(value[4]));
    line_of.push_back(at);
  }
  if (points->size() == 0) return "'" + file + "' holds no point: give one row per point (x, y, z, volume)";
  return coincident(file, *points, line_of);
}

} // namespace bapd::nd
