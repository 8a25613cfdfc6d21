#pragma once
// Energy-consistent bond-associated forces (METHOD.md section 3; after Breitzman &
// Dayal 2018): the force density is minus the gradient of the stored energy
//   W = sum_i V_i omega_i sum_{b = (i -> j)} V_j Psi(F_ij),   omega_i = 1 / sum_b V_j,
// both sums over the bonds of i that carry energy (intact, usable K, model ok). This
// is the energy that strain_energy() (ba_force.hpp) reports: W_i is the volume-
// weighted mean of i's bond energy densities, so W = Psi(A) * volume for an affine
// motion. The paper's bond-only force (eq 23) is not the gradient of any energy: its
// tangent is not symmetric next to a free surface, which gives complex eigenvalues
// and undamped motions that grow whatever the time step (ba_force_energy_test.cpp).
//
// The derivation. F_ij = sum_{m in B} (y_m - y_i) (x) g_m, g_m = K_ij^{-1}(x_m - x_i) V_m
// (B = the intact members of B_ij, eq 9), so with M_b = omega_i V_j P(F_ij) K_ij^{-1}
//   dW/dy_m += V_i M_b (x_m - x_i) V_m   (m in B),
//   dW/dy_i -= V_i M_b sum_{m in B} (x_m - x_i) V_m.
// Collect, for a bond (i -> p), the stresses of the bonds of i whose BA family holds p:
//   S_ip = sum_{q : p in intact B_iq} M_iq,    t_ip = S_ip (x_p - x_i)
// (t_ip = 0 if the bond (i -> p) is broken). Then f_k = -(1/V_k) dW/dy_k becomes
//   f_k = sum_{p in H_k} V_p S_kp (x_p - x_k)  -  sum_{i in H_k} V_i S_ik (x_k - x_i)
//       = sum_j (t_kj - t_jk) V_j,
// the bond-only assembly (eq 1, assemble_force_density) with t_ij = S_ij (x_j - x_i).
// So this kernel writes t_ij in place of eq 23's and everything downstream is the
// same: momentum is conserved pair by pair, the result does not depend on the local
// numbering, and the halo is the same (t_ij needs i's family only).
//
// BA masks are symmetric within a family: p in B_iq iff q in B_ip (both are
// |x_p - x_q| <= delta, computed with the same bits either way; p = q is in both;
// build_families). So the bonds q with p in B_iq are the set bits of bond (i -> p)'s
// own BA mask, and S_ip is one masked sum of the per-member stresses M_iq with the
// same code (and the same "totals minus the others" shortcut) as F_ij's sums
// (bond_geometry.hpp). Per point i the kernel runs two loops over its bonds: the first
// forms F_ij and P (stress_pass, the code of compute_bond_forces, with the model four
// bonds at a time where it has stress_lanes) and M_iq, the second S_ip and t_ip. Nothing per bond is stored beyond t_ij (and c33); M lives in the
// workspace for one point at a time.
//
// A bond that is broken, has no usable K or whose model fails has M = 0 and no
// energy; its end point p still contributes to the other bonds' F_iq (p in B_iq), so
// t_ip is generally not 0 (unless the bond is broken). Failed bonds are counted and
// appended to ws.failed exactly as compute_bond_forces does.
#include <cstddef>
#include <cstdint>

#include "bapd/ba_force.hpp"

namespace bapd {

namespace detail {

// Pass 1 of the energy-consistent form (stress_pass, ba_force.hpp, gives F_iq and P):
// M_iq = V_q P(F_iq) K_iq^{-1} of every bond that carries energy, their sum in family
// order, sum_q V_q (omega_i = 1 / that) and the mask of those bonds.
struct EnergyConsistentForm {
  Quad          *M;         // ws.bond_stress
  std::uint64_t *energetic; // ws.energetic, cleared by the caller
  double        *data;      // ws.pending_data: K^{-1} (xx, xy, yy) per slot
  const Quad    *shp;       // the point's shape_k (V_k in the last entry)
  Double4        stress_total = {0.0, 0.0, 0.0, 0.0};
  double         volume       = 0.0;

  void none(std::size_t) {} // no energy: M_iq is not read (its bit stays clear)
  void collect(std::size_t slot, std::size_t, const BondKinematics &k)
  {
    for (int c = 0; c < 3; ++c) data[3 * slot + c] = k.shape_tensor_inv[c];
  }
  void stress(std::size_t slot, std::size_t q, const Mat2 &P)
  {
    const double *ki = data + 3 * slot;
    const double  v  = shp[q].v[3]; // V_q
    const Double4 mq = {v * (P[0] * ki[0] + P[1] * ki[1]), v * (P[0] * ki[1] + P[1] * ki[2]),
                        v * (P[2] * ki[0] + P[3] * ki[1]), v * (P[2] * ki[1] + P[3] * ki[2])};
    M[q].v           = mq;
    stress_total += mq;
    volume += v;
    energetic[q / 64] |= std::uint64_t{1} << (q % 64);
  }
};

template <std::size_t Words, class Model>
void energy_consistent_range(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                             const BondGeometry &geo, const BondState &state, double *c33, double *bond_force,
                             BondKernelWorkspace &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  Quad          *M         = ws.bond_stress.data();
  std::uint64_t *energetic = ws.energetic.data();
  std::size_t    evaluated = 0, unusable = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const KernelPoint pt = begin_point<Words>(ref, y, fam, geo, state, i, ws);
    const auto &[W, o, m, ba, intact, usable, s, totals] = pt;
    for (std::size_t w = 0; w < W; ++w) energetic[w] = 0;
    EnergyConsistentForm form{M, energetic, ws.pending_data.data(), s.shape.data()};
    stress_pass<Words>(model, pt, i, c33, ws, form, evaluated, unusable, stats);
    // Pass 2: t_ip = omega_i S_ip (x_p - x_i), S_ip = sum of M_iq over q in B_ip.
    const double *off = s.offset.data();
    double       *t   = bond_force + 2 * o;
    if (form.volume == 0.0) { // no bond of i carries energy
      for (std::size_t p = 0; p < 2 * m; ++p) t[p] = 0.0;
      continue;
    }
    const double      omega     = 1.0 / form.volume;
    const Quad *const arrays[1] = {M};
    for (std::size_t p = 0; p < m; ++p) {
      if (!((intact[p / 64] >> (p % 64)) & 1u)) {
        t[2 * p] = t[2 * p + 1] = 0.0;
        continue;
      }
      Double4 S;
      masked_sums<Words, 1>(ba + p * W, energetic, W, arrays, &form.stress_total, &S);
      const double d0 = off[2 * p], d1 = off[2 * p + 1];
      t[2 * p]        = omega * (S[0] * d0 + S[1] * d1);
      t[2 * p + 1]    = omega * (S[2] * d0 + S[3] * d1);
    }
  }
  stats.evaluated += evaluated;
  stats.unusable += unusable;
}

} // namespace detail

// Energy-consistent bond forces t_ij (2 per bond) of the family points [begin, end),
// to be assembled by assemble_force_density (ba_force.hpp) into
// f_i = -(1/V_i) dW/dy_i with W = strain_energy(). Arguments, c33 warm start, failure
// counting and ws.failed as compute_bond_forces (this overload does not clear
// ws.failed).
template <class Model>
KernelStats compute_energy_consistent_bond_forces(const Model &model, const PointCloud &ref, const double *y,
                                                  const Families &families, const BondGeometry &geometry,
                                                  const BondState &state, double *c33, double *bond_force,
                                                  BondKernelWorkspace &ws, std::size_t begin, std::size_t end)
{
  KernelStats stats;
  ws.reserve(families);
  if (families.mask_words == 1)
    detail::energy_consistent_range<1>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end,
                                       stats);
  else
    detail::energy_consistent_range<0>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end,
                                       stats);
  return stats;
}

// All family points [0, n_family); clears ws.failed first.
template <class Model>
KernelStats compute_energy_consistent_bond_forces(const Model &model, const PointCloud &ref, const double *y,
                                                  const Families &families, const BondGeometry &geometry,
                                                  const BondState &state, double *c33, double *bond_force,
                                                  BondKernelWorkspace &ws)
{
  ws.failed.clear();
  return compute_energy_consistent_bond_forces(model, ref, y, families, geometry, state, c33, bond_force, ws, 0,
                                               families.n_family);
}

} // namespace bapd
