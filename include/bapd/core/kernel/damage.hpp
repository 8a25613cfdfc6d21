#pragma once
// Bond failure and damage (paper eqs 7 and 38; METHOD.md section 5), one code path
// for D = 2 and 3: breaking by critical stretch (nd::break_bonds<D>), breaking where a
// model failed, and the damage field. The last two work on families and masks alone.
#include <cstddef>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/kernel_stats.hpp"

namespace bapd {

// Breaking by critical stretch (eq 7) is nd::break_bonds<D> (damage.hpp, included
// here), one code path for 2D and 3D.

// Breaks the bonds whose model failed in the last kernel call (ws.failed), both
// directed copies where present; appends their end points to touched_points (then
// sorted, unique). Returns the number of bonds newly broken (a pair counts once if
// both copies failed). A failure is a property of one directed copy: a rank that
// holds i only as a ring-1 ghost next to a ring-2 j never evaluates (j, i), so the
// solver must copy the owners' intact masks to the ring-1 ghosts after this.
std::size_t break_failed_bonds(const Families &families, BondState &state, const std::vector<FailedBond> &failed,
                               std::vector<std::size_t> &touched_points);

// Damage of points [0, n_points) (eq 38): 1 - (intact family volume) / V(H_i),
// 0 for a point without a family. V(H_i) never changes (bonds cut by a notch were
// never created, so they are not damage).
void point_damage(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t n_points,
                  double *damage);

} // namespace bapd

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
