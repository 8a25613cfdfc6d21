#pragma once
// The two force forms of the bond kernel (ba_force.hpp): what each keeps of a bond
// and what it makes of P(F_ij).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "bapd/core/kernel/ba_patch_term.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {
namespace detail {

// Bond-only (eq 23): t_iq = P g_iq, g_iq = force_scale C_i K^{-1} xi_iq (+ h_iq with
// the patch correction).
template <int D, bool Corrected> struct BondOnlyForm {
  double                      *t;    // the point's bond forces, D per bond
  double                      *data; // ws.pending_data: g_iq, component r of slot s at data[r S + s]
  std::size_t                  S;    // ws.lane_stride
  const double                *off, *fvk, *C;
  const PointTotals<D>        &totals;
  // -force_patch_correction: lambda of the point and of every local point
  // (patch_stride<D>(virial) each), the point's neighbours; lambda_i nullptr: off (the
  // lattice, the energy-consistent form).
  const double                *lambda_i = nullptr, *lambda = nullptr;
  const std::int32_t          *nb       = nullptr;
  bool                         virial   = false;
  const double                *damage   = nullptr; // d of the point's bonds (softening.hpp): t scaled by 1 - d; nullptr: none

  void none(std::size_t q)
  {
    for (int r = 0; r < D; ++r) t[D * q + r] = 0.0;
  }
  // Out of line: inlined into stress_pass's loop it made that loop slower (3D lanes
  // bond-only 47.4 ns a bond inlined, 40.4 out of line; docs/notes/performance-kernel-3.md 1k).
  [[gnu::noinline]] void collect(std::size_t slot, std::size_t q, const BondKinematics<D> &k)
  {
    double g[D];
    force_vector<D>(k, force_scale<D>(k, totals, fvk[q]), off + D * q, g);
    if constexpr (Corrected) { // g -> C_i g (compiled out without a correction)
      double h[D];
      for (int r = 0; r < D; ++r) {
        double s = C[D * r] * g[0];
        for (int c = 1; c < D; ++c) s += C[D * r + c] * g[c];
        h[r] = s;
      }
      for (int r = 0; r < D; ++r) g[r] = h[r];
    }
    if (lambda_i) add_patch_term<D>(lambda_i, lambda + patch_stride<D>(virial) * nb[q], off + D * q, g, virial); // h_iq
    for (int r = 0; r < D; ++r) data[r * S + slot] = g[r];
  }
  // t = P g, in one bond's doubles or in lanes (slot = the first of the register's).
  template <class T> std::array<T, D> product(std::size_t slot, const std::array<T, D * D> &P) const
  {
    std::array<T, D> g, t;
    for (int r = 0; r < D; ++r) std::memcpy(&g[r], data + r * S + slot, sizeof(T));
    for (int r = 0; r < D; ++r) {
      T s = P[D * r] * g[0];
      for (int c = 1; c < D; ++c) s += P[D * r + c] * g[c];
      t[r] = s;
    }
    return t;
  }
  void stress(std::size_t slot, std::size_t q, const Mat<D> &P)
  {
    const std::array<double, D> f = product(slot, P);
    for (int r = 0; r < D; ++r) t[D * q + r] = f[r];
    if (damage) soften(q);
  }
  template <class T> void store(std::size_t, std::size_t q, const std::array<T, D> &f, std::size_t l)
  {
    for (int r = 0; r < D; ++r) t[D * q + r] = f[r][l];
    if (damage) soften(q);
  }
  void soften(std::size_t q)
  {
    const double g = 1.0 - damage[q];
    for (int r = 0; r < D; ++r) t[D * q + r] *= g;
  }
};

// Energy-consistent, pass 1: M_iq = V_q P(F_iq) K_iq^{-1}, their sum by mask word in
// family order, sum_q V_q and the mask of the bonds that carry energy.
template <int D> struct EnergyConsistentForm {
  static constexpr int         volume_component = sym_size<D>;
  StressRecord<D>             *M;
  std::uint64_t               *energetic;
  double                      *data; // ws.pending_data: K^{-1} (upper triangle) and V_q, component c of slot s at data[c S + s]
  std::size_t                  S;    // ws.lane_stride
  const MemberRecord<D>       *rec;
  StressRecord<D>             *stress_total; // by mask word, zeroed by the caller
  double                       volume = 0.0;
  // -material_volumetric point (volumetric.hpp): per bond V_q cof(F_iq) K_iq^{-1} and
  // J_iq (ws.bond_cofactor, ws.bond_dilatation); nullptr: bond (nothing kept).
  StressRecord<D>             *cofactor   = nullptr;
  double                      *dilatation = nullptr;
  // Softening (softening.hpp): d of the point's bonds, M_iq scaled by 1 - d (the energy
  // is sum V_q (1 - d_iq) Psi(F_iq), omega_i unchanged); nullptr: none.
  const double                *damage = nullptr;

  void none(std::size_t) {} // no energy: M_iq is not read (its bit stays clear)
  void collect(std::size_t slot, std::size_t q, const BondKinematics<D> &k)
  {
    for (int c = 0; c < sym_size<D>; ++c) data[c * S + slot] = k.shape_tensor_inv[c];
    data[volume_component * S + slot] = rec[q][Member<D>::volume];
    if (cofactor) keep_cofactor(q, k);
  }
  // cof F = adj(F)^T = J F^{-T}; kept before the model runs (a bond whose model fails
  // keeps it too, unread: its energetic bit stays clear).
  [[gnu::noinline]] void keep_cofactor(std::size_t q, const BondKinematics<D> &k)
  {
    const Mat<D> adj = adjugate<D>(k.F);
    const double v   = rec[q][Member<D>::volume];
    double       n[StressRecord<D>::vectors * StressRecord<D>::V] = {};
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) {
        double s = adj[r] * k.kinv(0, c); // cof(F)_{r0} = adj(F)_{0r}
        for (int j = 1; j < D; ++j) s += adj[D * j + r] * k.kinv(j, c);
        n[D * r + c] = v * s;
      }
    cofactor[q]   = StressRecord<D>::from(n);
    dilatation[q] = det<D>(k.F);
  }
  // M = V_q P K^{-1}, in one bond's doubles or in lanes (slot = the first of the register's).
  template <class T> std::array<T, D * D> product(std::size_t slot, const std::array<T, D * D> &P) const
  {
    T ki[sym_size<D>], v;
    for (int c = 0; c < sym_size<D>; ++c) std::memcpy(&ki[c], data + c * S + slot, sizeof(T));
    std::memcpy(&v, data + volume_component * S + slot, sizeof(T));
    std::array<T, D * D> m;
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) {
        T s = P[D * r] * ki[sym_index<D>(0, c)];
        for (int k = 1; k < D; ++k) s += P[D * r + k] * ki[sym_index<D>(k, c)];
        m[D * r + c] = v * s;
      }
    return m;
  }
  void keep(std::size_t slot, std::size_t q, double *m_iq)
  {
    if (damage)
      for (int k = 0; k < D * D; ++k) m_iq[k] *= 1.0 - damage[q];
    const StressRecord<D> mq = StressRecord<D>::from(m_iq); // in registers (Packed::from)
    M[q]                     = mq;
    stress_total[q / 64] += mq;
    volume += data[volume_component * S + slot];
    energetic[q / 64] |= std::uint64_t{1} << (q % 64);
  }
  void stress(std::size_t slot, std::size_t q, const Mat<D> &P)
  {
    const Mat<D> m = product(slot, P);
    double       m_iq[StressRecord<D>::vectors * StressRecord<D>::V] = {};
    for (int k = 0; k < D * D; ++k) m_iq[k] = m[k];
    keep(slot, q, m_iq);
  }
  template <class T> void store(std::size_t slot, std::size_t q, const std::array<T, D * D> &m, std::size_t l)
  {
    double m_iq[StressRecord<D>::vectors * StressRecord<D>::V] = {};
    for (int k = 0; k < D * D; ++k) m_iq[k] = m[k][l];
    keep(slot, q, m_iq);
  }
};

} // namespace detail
} // namespace bapd::nd
