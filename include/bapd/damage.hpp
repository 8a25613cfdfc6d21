#pragma once
// Bond failure and damage (paper eqs 7 and 38; METHOD.md section 5).
#include <cstddef>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/kernel_stats.hpp"
#include "bapd/nd/damage.hpp"

namespace bapd {

// Breaking by critical stretch (eq 7) is nd::break_bonds<D> (nd/damage.hpp, included
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
