#pragma once
// The body and its material points (docs/method.md section 1).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bapd/core/geometry/shape.hpp"

namespace bapd {

// The body of dimension D: Body<2> the plane sheet (below), Body<3> the solid
// (shape3d.hpp). Each holds its own spacing dx.
template <int D> struct Body;

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

// Points given to the body instead of the uniform lattice (geometry.hpp): a point
// cloud file (-body_cloud) or the centroids of a Gmsh mesh's 2D elements
// (-body_S_discretisation centroids). Volumes are per point, so spacing and horizon
// are per point too (geometry.hpp says how).
struct GivenPoints {
  std::vector<double>  x;      // 2 per point [m]
  std::vector<double>  volume; // [m^3]
  std::vector<int64_t> block;  // block id per point (1 when the source has none)
  std::string          source; // the file, for messages
  std::size_t          size() const { return volume.size(); }
};

// A 2D plane sheet [0, width] x [0, height], cut by circular holes (which may reach
// outside it), then shaped by `shapes` in order (shape.hpp), and cut by pre-notches.
// The sheet is the specimen; `grip_rows` adds the material of the grips placed outside
// it (-load_NAME_placement outside; OutsideGripRows of the load sets, scene_loading.cpp):
// whole lattice rows beyond each edge, each the sheet's edge row extruded (a point
// there is material where the edge row's point at the same x, or the edge column's at
// the same y, is). Coordinates stay those of the sheet: a bottom grip's points have
// y < 0, a top grip's y > height.
template <> struct Body<2> {
  double width = 0, height = 0, thickness = 0, dx = 0;
  std::vector<Circle>  holes;
  std::vector<Shape>   shapes;  // subtract / add / intersect, in order
  std::vector<Segment> notches; // bonds that cross one are never created
  EdgeRows             grip_rows;
  // Not null: the body's points are these (clipped by the holes and shapes), not the
  // lattice; dx is then their smallest spacing (geometry.hpp). Shared: the scene is
  // copied, the points are not.
  std::shared_ptr<const GivenPoints> given_points;
};

// Material points in structure-of-arrays form. A point's natural id is its index in
// the order of the geometry stage that made the body (geometry.hpp: lattice order, or
// the order of the given points); it never depends on the partition, so every sum
// over a family runs in natural-id order on any rank layout.
struct PointCloud {
  std::vector<double>  x;             // reference positions, 2 per point
  std::vector<double>  volume;        // dx^2 * thickness on the lattice; per point for given points
  std::vector<double>  family_volume; // V(H_i): reference volume of the whole family
  std::vector<int64_t> natural_id;
  // delta_i, the point's own horizon [m] (geometry.hpp); empty: every point has the
  // one horizon passed to build_families (the uniform lattice).
  std::vector<double>  horizon;
  // -force_patch_correction (patch_correction.hpp): lambda_i, D per point (on), or with
  // patch_virial (mu_i, S_i), D + D(D+1)/2 per point (virial: 5 in 2D); empty: off.
  std::vector<double>  patch_correction;
  bool                 patch_virial = false;
  std::size_t          size() const { return volume.size(); }
};

} // namespace bapd
