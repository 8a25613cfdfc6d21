#pragma once
// Bond failure and damage (paper eqs 7 and 38; docs/method.md section 5), one code path
// for D = 2 and 3: breaking by critical stretch (nd::break_bonds<D>), by the fracture
// energy (break_bonds_by_energy, with crossing_density), where a model failed, and the
// damage field. All but the first work on families, masks and given energies alone.
#include <cstddef>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/kernel_stats.hpp"

namespace bapd {

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

// The fracture-energy criterion (-failure_fracture_energy; docs/method.md section 5.2).
// A straight crack through the bulk cuts, per unit area, the bonds (i, j) with i on one
// side and j on the other; with a critical pair energy w_c per unit V_i V_j the energy
// they held is w_c c_i, where c_i = 1/2 sum_j |xi_ij . n| V_j is the crossing density
// (m^4: bond length times volume). crossing_density gives c_i of a full family on the
// point's own lattice, of spacing h = (V / thickness)^(1/2) in 2D and V^(1/3) in 3D,
// for a crack along a lattice plane (n an axis) and |xi| <= horizon: the count the
// lattice really has (at delta = 3.015 h, 0.985 of the continuum 2 delta^3 / 3 in 2D and
// 1.079 of pi delta^4 / 4 in 3D), whatever the family lost to a notch or a surface.
// thickness: the 2D sheet's (ignored in 3D).
double crossing_density(int dimension, double volume, double horizon, double thickness);

// Breaks every intact bond (i, j) of the family points whose pair energy density
//   e_ij = Psi(F_ij) / V(H_i) + Psi(F_ji) / V(H_j)        (the pair's share of W / (V_i V_j))
// reaches the critical w_c = G_c / ((c_i + c_j) / 2), tested as e_ij (c_i + c_j) >= 2 G_c
// (critical_release G_c = kappa Gamma, docs/method.md (5.2)): both directed copies compute the same two sums (IEEE
// addition commutes), so they agree on any rank without communication. psi: Psi of
// every bond (bond_energies, -1: no energy, counts as 0); crossing: c_i per family
// point. A bond whose reverse copy has no family here (j a ring-2 ghost) is left to
// j's owner (Failure copies the owners' masks to the ring-1 ghosts). touched_points and
// the return value as break_bonds.
std::size_t break_bonds_by_energy(const PointCloud &cloud, const Families &families, const double *psi,
                                  const double *crossing, double critical_release, BondState &state,
                                  std::vector<std::size_t> &touched_points,
                                  std::size_t n_counted = static_cast<std::size_t>(-1));

// The crack the broken bonds of points [0, n_points) describe (history.csv; docs/method.md
// section 5.3): its area, the broken pairs counted back through the crossing density,
// A = sum over broken pairs of V_i V_j / ((c_i + c_j) / 2) (a plane of area A cuts pairs
// of weight A c, section 5.2; each pair is seen from both ends here, hence the halves),
// and its tip: of the broken bonds' reference midpoints m, the one furthest along the
// unit vector `direction` from `origin` (D components each), ties to the larger
// coordinates: tip = {(m - origin) . direction, m_x, m_y[, m_z]} ({-infinity, ...} if no
// bond is broken), so that the largest tip over the ranks, compared lexicographically,
// is the same on any layout. point_area[i]: point i's share of A (summed reproducibly by
// the caller). crossing: c_i per family point (every neighbour of the points counted has one).
void crack_extent(int dimension, const PointCloud &cloud, const Families &families, const BondState &state,
                  const double *crossing, std::size_t n_points, const double *origin, const double *direction,
                  double *point_area, double tip[4]);

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
