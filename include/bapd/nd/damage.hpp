#pragma once
// Bond failure by critical stretch (paper eq 7; METHOD.md section 5) in D = 2 or 3
// dimensions: the one breaking pass of the solver (failure.cpp) for every D.
// break_failed_bonds and point_damage of damage.hpp work on families and masks alone
// and serve every D as they are.
#include <cstddef>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"

namespace bapd::nd {

// Breaks, for good, every intact bond of the family points whose stretch
// s = |y_j - y_i| / |x_j - x_i| exceeds critical_stretch, tested as
// |y_j - y_i|^2 > s_c^2 |x_j - x_i|^2 (x and y: D per point). Both directed copies of a
// bond see the same bits (differences are negated exactly), so (i, j) and (j, i) always
// agree, on any rank, without communication. touched_points (cleared, sorted, unique):
// the points whose geometry must be recomputed (compute_bond_geometry(..., points)).
// Returns the directed bonds broken at points [0, n_counted) (default: every family
// point; n_owned gives a count that sums over ranks without ghost copies).
template <int D>
std::size_t break_bonds(const PointCloud &cloud, const double *y, const Families &families, double critical_stretch,
                        BondState &state, std::vector<std::size_t> &touched_points,
                        std::size_t n_counted = static_cast<std::size_t>(-1));

} // namespace bapd::nd
