#pragma once
// Where the volumetric energy U(J) of the law is evaluated (-material_volumetric;
// docs/method.md section 8): per bond, U(J_ij) with J_ij = det F_ij (the paper's, every
// bond a constraint J_ij = 1 on a nearly incompressible gel: it locks in plane strain and
// 3D), or once per point, U(Jbar_i) with Jbar_i the volume-weighted mean of the J_ij of
// the point's bonds (one constraint a point: it does not lock). The energy-consistent
// force form only (ba_force.hpp); plane stress has no volumetric constraint to relax.
//
//   W = sum_i V_i [ omega_i sum_q V_q (Psi(F_iq) - U(J_iq) + kappa/2 (J_iq - Jbar_i)^2) + U(Jbar_i) ],
//   Jbar_i = omega_i sum_q V_q J_iq,  omega_i = 1 / sum_q V_q,
// over the bonds of i that carry energy. dW/dF_iq = V_i omega_i V_q P*_iq with
//   P*_iq = P(F_iq) + (U'(Jbar_i) - U'(J_iq) + kappa (J_iq - Jbar_i)) cof F_iq,   cof F = J F^{-T},
// because dJ/dF = cof F, U is the same for every law (law.hpp),
//   U(J) = (1/D) ((J^2 - 1)/2 - ln J),  U'(J) = (1/D) (J - 1/J),
// and sum_q V_q (J_iq - Jbar_i) = 0 (so Jbar_i's own variation drops out of the kappa term).
// In plane strain F is the in-plane F~ (F33 = 1) and J = det F~.
// kappa (-material_volumetric_stabilisation, in mu) holds the bonds' J_iq near their mean
// with a modulus of the order of mu, not K: to second order the bond form is this one
// with kappa = K (its U(J_iq) is U(Jbar_i) plus K/2 times the spread of the J_iq), so a
// kappa of a few mu keeps the bond form's control of the odd-even mode (a mode whose
// mean dilatation is zero) without its locking.
#include <cstddef>
#include <type_traits>
#include <utility>

#include "bapd/core/kernel/volumetric_kind.hpp"
#include "bapd/core/materials/hyperelastic_numerics.hpp"

namespace bapd {

namespace nd::detail {

// The compressibility D of a model of the registry (its parameters p); 0 for a model
// without one (a test's own model), which the point form refuses.
template <class M> inline auto compressibility(const M &m, int) -> decltype(static_cast<double>(m.p.D)) { return m.p.D; }
template <class M> inline double compressibility(const M &, long) { return 0.0; }

// U'(J) = (J - 1/J) / D and U(J) = ((J^2 - 1)/2 - ln J) / D (hyperelastic.hpp's U).
inline double volumetric_slope(double J, double D) { return (J - 1.0 / J) / D; }
inline double volumetric_energy(double J, double D) { return volumetric_energy_times_D(J) / D; }
// The kappa term's factor of cof F_iq in P*_iq besides U'(Jbar_i) - U'(J_iq).
inline double stabilisation_slope(double J, double Jbar, double kappa) { return kappa * (J - Jbar); }

} // namespace nd::detail
} // namespace bapd
