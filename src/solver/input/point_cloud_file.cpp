// A point cloud file (point_cloud_file.hpp).
#include "bapd/solver/input/point_cloud_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <vector>

#include "bapd/core/geometry/text_table.hpp"
#include "bapd/solver/io/hdf5_io.hpp"
#include "bapd/solver/input/input_file.hpp"
#include "bapd/solver/input/options_reader.hpp"

namespace bapd {

namespace {

bool EndsWith(const std::string &s, const char *tail)
{
  const std::string t = tail;
  return s.size() >= t.size() && Lower(s.substr(s.size() - t.size())) == t;
}

// The checks both formats share; `where(p)` names point p in the file ("line 7").
template <class Where>
std::string CheckPoints(const std::string &file, const GivenPoints &pts, Where where)
{
  const std::size_t n = pts.size();
  if (n == 0) return "'" + file + "' holds no point: give one row per point (x, y, volume)";
  for (std::size_t p = 0; p < n; ++p) {
    if (!std::isfinite(pts.x[2 * p]) || !std::isfinite(pts.x[2 * p + 1]))
      return Format("'%s', %s: the position is not a finite number", file.c_str(), where(p).c_str());
    if (!(pts.volume[p] > 0) || !std::isfinite(pts.volume[p]))
      return Format("'%s', %s (point %zu at (%g, %g) m): volume %g m^3; every point's volume must be > 0 (area x thickness)", file.c_str(),
                    where(p).c_str(), p + 1, pts.x[2 * p], pts.x[2 * p + 1], pts.volume[p]);
  }
  // Two points at one position (to round-off of the cloud's size): sorted along x, a
  // point can only coincide with the next few.
  double lo[2] = {pts.x[0], pts.x[1]}, hi[2] = {pts.x[0], pts.x[1]};
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 2; ++c) lo[c] = std::min(lo[c], pts.x[2 * p + c]), hi[c] = std::max(hi[c], pts.x[2 * p + c]);
  const double             tol = 1e-9 * std::max({hi[0] - lo[0], hi[1] - lo[1], std::sqrt(pts.volume[0])});
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pts.x[2 * a] < pts.x[2 * b] || (pts.x[2 * a] == pts.x[2 * b] && a < b); });
  for (std::size_t s = 0; s < n; ++s)
    for (std::size_t t = s + 1; t < n && pts.x[2 * order[t]] - pts.x[2 * order[s]] <= tol; ++t) {
      const std::size_t a = std::min(order[s], order[t]), b = std::max(order[s], order[t]);
      if (std::fabs(pts.x[2 * a + 1] - pts.x[2 * b + 1]) <= tol)
        return Format("'%s': %s and %s are the same point (%g, %g) m: remove the duplicate (points closer than %g m count as one)", file.c_str(),
                      where(a).c_str(), where(b).c_str(), pts.x[2 * a], pts.x[2 * a + 1], tol);
    }
  return "";
}

std::string ReadText(const std::string &file, GivenPoints *pts)
{
  std::ifstream in(file);
  if (!in) return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  std::string              trimmed;
  std::vector<std::string> header;
  std::vector<long>        line_of; // file line of each point, for messages
  long                     number = 0;
  int                      col_x = -1, col_y = -1, col_v = -1, col_b = -1;
  while (next_table_line(in, header.empty(), &number, &trimmed)) {
    if (header.empty()) {
      header = table_tokens(trimmed, false);
      std::vector<int>  col;
      const std::string problem = table_header(file, number, header, trimmed, {"x", "y", "volume", "block_id|block"}, 3, &col);
      if (!problem.empty()) return problem;
      col_x = col[0], col_y = col[1], col_v = col[2], col_b = col[3];
      continue;
    }
    const std::vector<std::string> row = table_tokens(trimmed, false);
    if (row.size() != header.size())
      return Format("'%s', line %ld holds %zu values, the header names %zu columns: give one value per column", file.c_str(), number,
                    row.size(), header.size());
    double values[4] = {0, 0, 0, 1};
    const int cols[4] = {col_x, col_y, col_v, col_b};
    for (int k = 0; k < 4; ++k) {
      if (cols[k] < 0) continue;
      if (!table_number(row[cols[k]], &values[k]))
        return Format("'%s', line %ld, column '%s': '%s' is not a number", file.c_str(), number, header[cols[k]].c_str(), row[cols[k]].c_str());
    }
    if (col_b >= 0 && values[3] != std::floor(values[3]))
      return Format("'%s', line %ld: block id '%s' is not a whole number", file.c_str(), number, row[col_b].c_str());
    pts->x.push_back(values[0]);
    pts->x.push_back(values[1]);
    pts->volume.push_back(values[2]);
    pts->block.push_back(static_cast<int64_t>(values[3]));
    line_of.push_back(number);
  }
  if (in.bad()) return "cannot read '" + file + "' (a read error)";
  if (header.empty()) return "'" + file + "' is empty: its first line must name the columns (x, y, volume), then one row a point";
  return CheckPoints(file, *pts, [&](std::size_t p) { return Format("line %ld", line_of[p]); });
}

std::string ReadHdf5(const std::string &file, GivenPoints *pts)
{
  if (std::FILE *f = std::fopen(file.c_str(), "rb")) std::fclose(f);
  else return "cannot open '" + file + "' (check the path; it is read relative to the directory bapd runs in)";
  H5Quiet     quiet;
  const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (h5 < 0) return "'" + file + "' is not an HDF5 file (a text cloud needs another ending, e.g. .csv)";
  std::vector<double> x, y, block;
  std::string         problem;
  const char         *names[3] = {"x", "y", "volume"};
  std::vector<double> *into[3] = {&x, &y, &pts->volume};
  for (int k = 0; k < 3 && problem.empty(); ++k) {
    const std::vector<hsize_t> shape = H5DatasetShape(h5, names[k]);
    if (shape.size() != 1 || !H5ReadDoubles(h5, names[k], into[k]))
      problem = Format("'%s' has no 1-D dataset '/%s': give datasets /x, /y, /volume (one entry a point) and optionally /block_id",
                       file.c_str(), names[k]);
  }
  const bool has_block = problem.empty() && !H5DatasetShape(h5, "block_id").empty();
  if (has_block && !H5ReadDoubles(h5, "block_id", &block)) problem = "'" + file + "': dataset /block_id cannot be read as numbers";
  H5Fclose(h5);
  if (!problem.empty()) return problem;
  if (y.size() != x.size() || pts->volume.size() != x.size() || (has_block && block.size() != x.size()))
    return Format("'%s': /x, /y, /volume%s differ in length (%zu, %zu, %zu): give one entry a point in each", file.c_str(),
                  has_block ? ", /block_id" : "", x.size(), y.size(), pts->volume.size());
  for (std::size_t p = 0; p < x.size(); ++p) {
    pts->x.push_back(x[p]);
    pts->x.push_back(y[p]);
    pts->block.push_back(has_block ? static_cast<int64_t>(block[p]) : 1);
  }
  return CheckPoints(file, *pts, [](std::size_t p) { return Format("entry %zu", p); });
}

} // namespace

std::string ReadPointCloud(const std::string &file, GivenPoints *points)
{
  *points        = GivenPoints{};
  points->source = file;
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    return "'" + file + "' is a directory, not a point cloud file: give the path of the .csv or .h5 file";
  if (std::string why = NotARegularFile(file); !why.empty()) return why;
  return EndsWith(file, ".h5") || EndsWith(file, ".hdf5") ? ReadHdf5(file, points) : ReadText(file, points);
}

} // namespace bapd
