#pragma once
// Families and bond-associated (BA) families (docs/method.md section 1, paper eq 8), in
// D = 2 or 3 dimensions.
//
// Works on LOCAL data: the point cloud of one rank, [owned, ring-1 ghosts, ring-2
// ghosts]. Points [0, n_family) (owned + ring-1) get a family; ring-2 points only
// supply positions and reference volumes. Every family is sorted by natural_id, so
// every sum over a family runs in the same order on any rank layout.
//
// Bond b = (i -> j) is the q-th member of i's family: b = offsets[i] + q,
// j = neighbour[b]. Bits of a per-point mask (BondState::intact,
// BondGeometry::usable) and of a BA mask are indexed by that position q.
//
// One builder for every D (nd::build_families<D>, a cell list over a cloud whose x
// holds D coordinates a point); the 2D entry point build_families is it with the
// notch segments as its bond filter. Sizes in 3D (interior point, every lattice point
// within delta): 80 members at delta = 2.515 dx (2 mask words), 122 at 3.015 dx
// (2 words), 178 at 3.515 dx (3 words).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "bapd/core/geometry/body.hpp"

namespace bapd {

struct Families {
  std::size_t n_family        = 0; // points [0, n_family) have a family
  std::size_t max_family_size = 0;
  std::size_t mask_words      = 1; // 64-bit words per mask = max(1, ceil(max_family_size / 64))
  double      horizon         = 0;

  std::vector<std::size_t>   offsets;   // n_family + 1 (CSR)
  std::vector<std::int32_t>  neighbour; // local index of j, per bond
  std::vector<std::int32_t>  reverse;   // bond (j -> i) of bond (i -> j), -1 if j >= n_family
  // B_ij = {k in family(i) : |x_k - x_j| <= horizon} (contains j; the bond rule of
  // build_families between j and k with per-point horizons): bit p of the
  // mask_words words of bond b is set iff the p-th member of i's family is in B_ij.
  std::vector<std::uint64_t> ba_mask;

  std::size_t          n_bonds() const { return neighbour.size(); }
  std::size_t          size(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  const std::uint64_t *ba(std::size_t bond) const { return ba_mask.data() + bond * mask_words; }
};

// Families of points [0, n_family): every j != i of the cloud (all points, ghosts
// included) with |x_j - x_i| <= horizon (max(delta_i, delta_j) when cloud.horizon
// gives each point its own, geometry.hpp; Families::horizon is then the largest
// delta), found with a cell list, minus the bonds whose
// segment properly crosses a notch segment (such bonds never exist; a bond that only
// touches a notch end point is kept), sorted by natural_id; then the BA masks and the
// reverse index. Throws std::invalid_argument for a bad horizon or n_family, and
// std::runtime_error if the bond count does not fit the 32-bit index or a family is
// not symmetric (j in family(i) but i not in family(j) with both < n_family).
Families build_families(const PointCloud &cloud, std::size_t n_family, double horizon,
                        const std::vector<Segment> &notches);

// True iff segment (a, b) properly crosses segment (c, d): each one's end points lie
// strictly on opposite sides of the other's line. Symmetric in the bond's end points
// because build_families always passes the lower natural id first.
bool segments_cross(double ax, double ay, double bx, double by, const Segment &s);

// V(H_i) = sum of the reference volumes of i's family, in family order, for
// i < n_family (docs/method.md section 3). It never changes: broken bonds do not reduce it.
// family_volume is resized to cloud.size() if needed; entries it adds for points
// without a family (ring-2 ghosts) are NaN: the solver ships their values.
void compute_family_volumes(PointCloud &cloud, const Families &families);

} // namespace bapd

namespace bapd::nd {

// Bonds that must never exist (cut by a pre-notch): called with the two end points'
// coordinates (D each), lower natural id first, so that (i, j) and (j, i) get the same
// answer. Empty: every bond within the horizon exists. Called at set-up only.
using BondCut = std::function<bool(const double *a, const double *b)>;

// Families of points [0, n_family) of a cloud with D coordinates per point: every
// j != i with |x_j - x_i| <= horizon (max(delta_i, delta_j) with per-point horizons,
// cloud.horizon), found with a cell list of cells one reach wide (a 3^D block of cells
// holds a family), minus the cut bonds; sorted by natural id; then the BA masks
// (bit p of bond (i -> j) iff the p-th member k of i's family has |x_k - x_j| within
// the reach of (j, k)) and the reverse index. Throws as build_families does.
template <int D>
Families build_families(const PointCloud &cloud, std::size_t n_family, double horizon, const BondCut &cut = {});

// A box of n[0] x ... x n[D-1] cells of side dx, one point at each cell centre
// ((i + 0.5) dx along each axis), x fastest, then y, then z; natural_id = index;
// volume dx^D (2D: dx^2 thickness, as make_lattice). family_volume left empty.
template <int D>
PointCloud box_lattice(const std::array<int, D> &cells, double dx, double thickness = 1.0);

} // namespace bapd::nd
