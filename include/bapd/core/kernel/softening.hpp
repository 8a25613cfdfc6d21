#pragma once
// Softening bonds (-failure_softening; docs/method.md section 5.4): with the
// fracture-energy criterion a bond fails gradually instead of at once. Its damage
// d_ij in [0, 1] scales the pair's force and energy by (1 - d_ij); d is a function of
// the pair's release r_ij = e_ij (c_i + c_j) / 2 [J/m^2] (e_ij its undamaged pair energy
// density, c_i the crossing density; (5.2)), taken at the largest r_ij it has reached, so
// it never decreases. Onset at r_0 = kappa Gamma (the criterion of breaking at once), and
// the law's work to d = 1, the integral of r dd, is Gamma: the pair dissipates
// Gamma / ((c_i + c_j) / 2) per unit V_i V_j, Gamma per unit crack area by (5.1). The
// time law instead grows d with time from the onset on (fading_damage).
#include <cstddef>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/kernel/softening_law.hpp"

namespace bapd {

// The damage the law gives at release r [J/m^2], onset r0 = kappa Gamma < Gamma:
//   linear       d = (r - r0) / (r_f - r0), r_f = 2 Gamma - r0 (work (r0 + r_f) / 2 = Gamma);
//   exponential  d = 1 - exp(-(r - r0) / s), s = Gamma - r0 (work r0 + s = Gamma), taken
//                as 1 (the bond breaks) once exp(...) < exponential_cut;
// 0 below r0, 1 from the end of the branch on; none: 1 from r0 on (the bond breaks at once).
// (time is not a function of r: fading_damage.)
inline constexpr double exponential_cut = 1e-3;
double softening_damage(Softening law, double r, double r0, double gamma);

// The time law (-failure_softening time; docs/method.md 5.4): a bond fades at a fixed
// rate from the pass in which r first reaches r0, whatever r does afterwards, and breaks
// after tau. Its damage after a pass, from d before it: a fading bond (d > 0) gains
// `advance` (dt / tau in the first pass of a step, 0 in the passes that follow at the
// same positions: a step fades a bond once), a bond at rest (d = 0) starts with `start`
// (dt / tau) once r >= r0; at most 1.
struct Fading {
  double start   = 0;
  double advance = 0;
};
double fading_damage(double d, double r, double r0, Fading fading);

// One softening pass of the family points at the bond energies psi (Psi(F_ij) undamaged,
// -1: no energy; ForceOperator::BondEnergies): every intact bond (i, j) whose reverse
// copy has a family here takes d_ij = max(d_ij, softening_damage(r_ij)) (both copies
// compute r_ij from the same two sums, as break_bonds_by_energy does), and breaks once
// d_ij reaches 1 (touched_points and the return value as break_bonds_by_energy).
// dissipated[i] (points [0, n_dissipated)) gains the energy the pass takes
// from the bonds of i, V_i omega_i sum_j V_j Psi(F_ij) (d_new - d_old), omega_i over the
// bonds that carry energy (the energy of strain_energy at the positions of psi): W with
// the old damage minus W with the new, both with the old intact bonds; what a bond that
// breaks (d = 1) then changes in its neighbours' F_ij and omega the caller measures
// (E before minus E after the break, at the new damage).
// With the time law the damage is fading_damage(d_ij, r_ij, ...) with `fading`, which the
// other laws do not read.
std::size_t soften_bonds(Softening law, const PointCloud &cloud, const Families &families, const double *psi,
                         const double *crossing, double onset_release, double fracture_energy, Fading fading,
                         BondState &state, std::vector<std::size_t> &touched_points, double *dissipated,
                         std::size_t n_dissipated);

} // namespace bapd
