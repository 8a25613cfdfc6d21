#pragma once
// A body given as a point cloud file (-body_cloud FILE, docs/options.md "Body"), the
// convention of Peridigm's text discretisations and PeriLab's CSV clouds: one point a
// row, its position x, y [m], its volume [m^3] and optionally its block id.
//   - Text (.csv, .txt, anything but .h5/.hdf5): the first line that is not blank
//     names the columns (a leading '#' is allowed: Peridigm's "# x y z block_id
//     volume"); columns separated by commas and/or blanks, in any order; x, y and
//     volume are required, block_id (or block) optional, others (z) ignored. Later
//     lines starting with '#' are comments.
//   - HDF5 (.h5, .hdf5): 1-D datasets /x, /y, /volume of one length, /block_id optional.
// Every rank reads the file (a cloud of 10^6 points is 24 MB).
#include <string>

#include "bapd/core/geometry/body.hpp"

namespace bapd {

// Reads `file` into `points`; "" or what is wrong, in words that name the line (text)
// or the point (HDF5) and the fix: the file is missing or unreadable, the header
// lacks x, y or volume, a row is short or not a number, a volume is zero, negative
// or not finite, two points coincide (closer than 1e-9 of the cloud's extent), no point.
std::string ReadPointCloud(const std::string &file, GivenPoints *points);

} // namespace bapd
