#pragma once
// Families and BA families in D = 2 or 3 dimensions (METHOD.md section 1, paper eq 8):
// the dimension-generic form of family.hpp's build_families, filling the same
// `Families` (CSR, natural-id order, BA bit masks of mask_words 64-bit words, reverse
// index), which has nothing 2D in it.
//
// The cloud is a PointCloud whose x holds D coordinates per point (2D: as
// make_lattice writes it; 3D: box_lattice below). For D = 2 build_families (family.hpp)
// is this with the notch segments as its bond filter (since issue 21 stage 2; the
// retired 2D builder's arithmetic and sort, so the families kept their bits).
//
// Sizes in 3D (interior point, every lattice point within delta): 80 members at
// delta = 2.515 dx (2 mask words), 122 at 3.015 dx (2 words), 178 at 3.515 dx (3 words).
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/family.hpp"

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
