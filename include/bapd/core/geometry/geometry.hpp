#pragma once
// The geometry stage (scene -> body -> families, docs/architecture.md): the one function that
// turns a body into the material points every later stage reads (families, scene
// checks, load sets, probes, output, checkpoints). Two producers:
//   - the uniform lattice (lattice.hpp): spacing dx, volume dx^2 t, one horizon
//     delta = horizon_factor dx for every point; natural id = lattice order;
//   - given points (Body<2>::given_points: a point cloud file, or the centroids of a
//     Gmsh mesh's 2D elements), kept where the body is material (holes, shapes);
//     natural id = their order in the source among the kept points.
//
// Non-uniform points (docs/method.md sections 1 and 3 with unequal volumes). A given
// point's spacing is h_i = sqrt(V_i / t), the spacing of the uniform lattice with the
// same point density (a lattice point gets h = dx; in 3D, h_i = cbrt(V_i)), and its
// horizon is delta_i = horizon_factor h_i (set_point_horizons, for both dimensions:
// a 3D cloud or a Gmsh volume's centroids get theirs the same way, in
// SimulationD<3>'s BodyPoints). A bond (i, j) exists where EITHER horizon reaches:
//   |x_j - x_i| <= delta_ij = max(delta_i, delta_j)                  (family.hpp)
// symmetric, so j in H_i iff i in H_j (t_ij and t_ji come in pairs: linear momentum),
// and every point's family holds at least the disc of its own horizon, so a fine
// point next to coarse ones keeps a shape tensor as regular as on a lattice of its own
// spacing (the rule "both reach", min, would leave a fine point beside points more
// than delta_i away with too few or collinear neighbours toward them). The BA family
// is B_ij = {k in H_i : k in H_j} (the discrete H_x ∩ H_x', docs/method.md section 1).
// phi (eq 11) and phi_xi (eq 15) take the volumes as they are (bond_geometry.hpp):
// V(H_i) is the sum of the family's volumes, V(B_ij) that of B_ij.
#include <cmath>
#include <cstdint>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/shape.hpp"

namespace bapd {

// h = sqrt(V / t): the spacing of a uniform lattice of the same point density [m].
inline double point_spacing(double volume, double thickness) { return std::sqrt(volume / thickness); }

// The same in `dimension` 2 or 3: sqrt(V / t) (2D), cbrt(V) (3D: the body has no
// thickness, so `thickness` is not read) [m].
inline double point_spacing(int dimension, double volume, double thickness)
{
  return dimension == 3 ? std::cbrt(volume) : point_spacing(volume, thickness);
}

// Gives every point of `cloud` its own horizon, delta_i = horizon_factor h_i with h_i
// = point_spacing(dimension, V_i, thickness): cloud->horizon, one a point, which
// build_families (2D) and nd::build_families<3> read as "a bond where either reaches".
void set_point_horizons(PointCloud *cloud, int dimension, double horizon_factor, double thickness);

// The smallest point_spacing of the given points: the body's characteristic spacing
// (Body<2>::dx), which the stable-step bound and the travel limit scale with.
double smallest_spacing(const GivenPoints &points, double thickness);

// The body's points: make_lattice(body) when there are no given points (horizon left
// empty: build_families' one horizon, horizon_factor x dx), else the given points
// that are material (is_material, lattice.hpp) with V_i and delta_i as above.
// family_volume is left empty (compute_family_volumes fills it).
PointCloud make_points(const Body<2> &body, double horizon_factor);

// One point per 2D element of a mesh (a Gmsh shape, -body_S_discretisation
// centroids): at the element's centroid (a quadrangle's from its two triangles,
// area-weighted), with volume = its area x thickness; in element order.
GivenPoints element_centroids(const TriangleSet &triangles, double thickness);

// How many points make_points keeps, without building them where it can
// (lattice_point_count for the lattice; given points are tested one by one).
int64_t body_point_count(const Body<2> &body);

} // namespace bapd
