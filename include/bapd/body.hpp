#pragma once
// The body and its material points (METHOD.md section 1).
#include <cstdint>
#include <vector>

#include "bapd/shape.hpp"

namespace bapd {

struct Circle {
  double cx, cy, radius;
};
struct Segment {
  double x0, y0, x1, y1;
};

// Lattice rows (columns) added outside each edge of the sheet.
struct EdgeRows {
  int64_t left = 0, right = 0, bottom = 0, top = 0;
  bool    any() const { return left || right || bottom || top; }
};

// A 2D plane sheet [0, width] x [0, height], cut by circular holes (which may reach
// outside it), then shaped by `shapes` in order (shape.hpp), and cut by pre-notches.
// The sheet is the specimen; `grip_rows` adds the material of the grips placed outside
// it (-load_NAME_placement outside, set by the loading section, scene_loading.cpp):
// whole lattice rows beyond each edge, each the sheet's edge row extruded (a point
// there is material where the edge row's point at the same x, or the edge column's at
// the same y, is). Coordinates stay those of the sheet: a bottom grip's points have
// y < 0, a top grip's y > height.
struct Body2D {
  double width = 0, height = 0, thickness = 0, dx = 0;
  std::vector<Circle>  holes;
  std::vector<Shape>   shapes;  // subtract / add / intersect, in order
  std::vector<Segment> notches; // bonds that cross one are never created
  EdgeRows             grip_rows;
};

// Material points in structure-of-arrays form. A point's natural id is its index in
// the lattice order of the whole body; it never depends on the partition, so every
// sum over a family runs in natural-id order on any rank layout.
struct PointCloud {
  std::vector<double>  x;             // reference positions, 2 per point
  std::vector<double>  volume;        // dx^2 * thickness
  std::vector<double>  family_volume; // V(H_i): reference volume of the whole family
  std::vector<int64_t> natural_id;
  std::size_t          size() const { return volume.size(); }
};

} // namespace bapd
