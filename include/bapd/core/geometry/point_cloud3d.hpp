#pragma once
// A 3D body given as a point cloud text file (the 3D form of
// point_cloud_file.hpp's text format, PeriLab's CSV clouds and Peridigm's text
// discretisations): one point a row, its position x, y, z [m], its volume [m^3] and
// optionally its block id. The first line that is not blank names the columns (a
// leading '#' allowed: Peridigm's "# x y z block_id volume"); columns separated by commas
// and/or blanks, in any order; x, y, z and volume required, block_id (or block)
// optional, others ignored. Later lines starting with '#' are comments. Text only (the
// HDF5 form of point_cloud_file.hpp is 2D only).
#include <cstdint>
#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"

namespace bapd::nd {

// Reads `file` into `points` (x: 3 a point; volume; natural_id = the row's order among
// the points; horizon and family_volume left empty) and `block` (1 where the file has
// no block column). Returns "" or what is wrong, naming the line and the fix: the file
// is missing, the header lacks x, y, z or volume or names a column twice, a row is
// short or not a number, a volume is not > 0 or not finite, two points coincide (closer
// than 1e-9 of the cloud's extent), no point.
std::string read_point_cloud_3d(const std::string &file, PointCloud *points, std::vector<int64_t> *block);

} // namespace bapd::nd
