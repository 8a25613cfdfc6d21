#pragma once
#include <string>

// -force_stress_correction (docs/stress_consistency.md): how the bond-only force of
// eq 23 is corrected so that a uniform P gives sum_j t_ij (x) xi_ij V_j = P at a point.
// Without a correction that sum is P M_i, with the point's virial tensor
//   M_i = sum_j w_ij K_ij^{-1} xi_ij (x) xi_ij V_j,   w_ij = 1/2 phi_xi/phi   (eq 23)
// over its bonds of t = 0 (M_i = 0.958 I in the interior at delta = 3.015 dx).
//   none:   the paper's force, t_ij = w_ij P(F_ij) K_ij^{-1} xi_ij
//   tensor: t_ij = w_ij P(F_ij) M_i^{-1} K_ij^{-1} xi_ij            (sum = P exactly)
//   scalar: t_ij = w_ij P(F_ij) K_ij^{-1} xi_ij / m_i, m_i = tr M_i / 2  (sum = P where
//           M_i is isotropic: the interior of a square lattice; a normalisation of the
//           influence function)
// The energy-consistent form (ba_force.hpp) needs none: its sum is the mean of
// its bond stresses, P for a uniform P, at every point.

namespace bapd {

enum class StressCorrection { none, tensor, scalar };
const char *to_string(StressCorrection c);
// "none", "tensor", "scalar" (as to_string writes them); false for anything else.
bool parse(const std::string &name, StressCorrection &c);

} // namespace bapd
