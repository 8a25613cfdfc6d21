#pragma once
// Bond-associated NOSB bond forces (paper eqs 9, 23; METHOD.md sections 2-3).
//
// For every intact bond b = (i -> j) with a usable K_ij:
//   F_ij = [ sum_{k in intact B_ij} (y_k - y_i) (x) (x_k - x_i) V_k ] K_ij^{-1}      (eq 9)
//   t_ij = P(F_ij) g_ij,   g_ij = 1/2 phi_xi/phi K_ij^{-1} (x_j - x_i)                (eq 23)
// and the force density of an owned point is
//   f_i = sum_j (t_ij - t_ji) V_j                                                   (eq 1)
// With -force_stress_correction (stress_correction.hpp, docs/stress_consistency.md)
// g_ij becomes C_i g_ij, C_i = M_i^{-1} or I / m_i from BondGeometry, so that a
// uniform P gives sum_j t_ij (x) xi_ij V_j = P (P M_i without it); the pairing of
// eq 1, and so linear momentum, is untouched. With -force_patch_correction
// (patch_correction.hpp: given points) g_ij gets h_ij = ((lambda_i - lambda_j) . xi) xi
// added, so that an affine motion leaves no interior force on an irregular cloud.
//
// The loop is written once here and templated on the constitutive model (any type
// with `StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const`), so the
// model's stress is inlined into it. Per point i, the outer products
// (y_k - y_i) (x) (x_k - x_i) V_k and (x_k - x_i) (x) (x_k - x_i) V_k are formed once
// per family member; each bond's F and K are then one masked sum of them (BA mask AND
// intact mask), in family order (bond_geometry.hpp). A model with stress_lanes
// (has_lanes, material.hpp: PlaneStress, plane_stress.hpp) is run lane_count (4 or 8) bonds at a time: the point's
// bonds are collected first (F, warm start, what the force form keeps), then model_lanes hands
// them to it in family order. That first pass (stress_pass) is shared with the
// energy-consistent form (ba_force_energy.hpp): the forms differ only in what they do
// with a bond's kinematics and P (BondOnlyForm here, EnergyConsistentForm there). Nothing is allocated per call
// (the workspace is sized once), except the list of failed bonds in the rare call
// where a model fails.
//
// Determinism: every sum runs in family order (families are sorted by natural id) and
// nothing depends on the local numbering, so a rank's owned points get bit-for-bit
// the same bond forces and force densities as a one-rank run.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_geometry.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/kernel_stats.hpp"
#include "bapd/lanes.hpp"
#include "bapd/patch_correction.hpp"
#include "bapd/stress_status.hpp"
#include "bapd/tensor.hpp"

namespace bapd {

// Scratch space of the kernels, sized once for the largest family.
struct BondKernelWorkspace {
  PointScratch            point;  // per-member data of the point being processed
  // Read c33 as the warm start but do not write it back: an evaluation that only looks
  // at the state (output, reactions) then leaves the dynamics untouched, without a
  // copy of c33 (8 bytes a bond, ~0.2 KB a point at delta = 3.015 dx).
  bool                    keep_warm_start = false;
  std::vector<FailedBond> failed; // every failed bond of the last compute_bond_forces call
  // Energy-consistent kernel only (ba_force_energy.hpp): V_j P(F_ij) K_ij^{-1} of the
  // point's bonds, and which of them carry energy (mask_words words).
  std::vector<Quad>          bond_stress;
  std::vector<std::uint64_t> energetic;
  // The point's bonds waiting for the model, in family order (models with stress_lanes,
  // has_lanes, e.g. PlaneStress, take them lane_count at a time; the others one at a time
  // through slot 0): F by component (4 arrays of `lane_stride`), the warm start, what
  // the force form needs once P is known (pending_data, 3 per bond: the force vector g
  // of the bond-only form, K^{-1} of the energy-consistent one) and the position q.
  std::size_t              lane_stride = 0; // max_family_size rounded up to lane_count
  std::vector<double>      pending_F, pending_c33, pending_data;
  std::vector<std::size_t> pending_q;

  void reserve(const Families &families)
  {
    point.reserve(families.max_family_size);
    if (bond_stress.size() < families.max_family_size) bond_stress.resize(families.max_family_size);
    if (energetic.size() < families.mask_words) energetic.resize(families.mask_words);
    const std::size_t L = lane_count, stride = (families.max_family_size + L - 1) / L * L;
    if (lane_stride < stride) {
      lane_stride = stride;
      pending_F.assign(4 * stride, 0.0);
      pending_c33.assign(stride, 0.0);
      pending_data.assign(3 * stride, 0.0);
      pending_q.assign(stride, 0);
    }
  }
};

namespace detail {

// Out of the hot loop: keeps the loop's registers free of the rare path.
[[gnu::noinline, gnu::cold]] inline void record_failure(KernelStats &stats, BondKernelWorkspace &ws, std::size_t i,
                                                        std::size_t q, StressStatus status)
{
  stats.record(i, q, status);
  ws.failed.push_back({i, q, status});
}

template <class M, class = void> struct HasLanes : std::false_type {};
template <class M> struct HasLanes<M, std::enable_if_t<M::has_lanes>> : std::true_type {};

// A bond that stress_lanes did not finish: the scalar solve (rare, out of the loop's
// registers; bench/callgrind_calls.py counts its calls).
template <class Model>
[[gnu::noinline, gnu::cold]] StressStatus model_lane_fallback(const Model &model, const Mat2 &F, double &c33, Mat2 &P)
{
  return model.stress(F, c33, P);
}

inline Lanes load_lanes(const double *p)
{
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// The model over the n bonds of point i collected in ws.pending_*, lane_count (lanes.hpp) at a time
// (Model::stress_lanes); a lane that its first evaluation does not finish goes through
// the scalar stress(), which gives bit for bit what stress_lanes gives where that
// finishes (plane_stress.hpp), so a bond's result does not depend on its lane. Bonds
// are taken in family order, so failures are recorded, and the form's stress() is
// called, in loop order (the energy-consistent form sums in that order).
template <class Model, class Form>
void model_lanes(const Model &model, BondKernelWorkspace &ws, std::size_t n, std::size_t i, std::size_t o,
                 double *c33, Form &form, KernelStats &stats)
{
  const std::size_t S = ws.lane_stride, L = lane_count;
  double           *Fc = ws.pending_F.data(), *cw = ws.pending_c33.data();
  for (std::size_t l = n; l < (n + L - 1) / L * L; ++l) { // unused lanes: the rest state
    Fc[l] = Fc[3 * S + l] = 1.0;
    Fc[S + l] = Fc[2 * S + l] = cw[l] = 0.0;
  }
  for (std::size_t j = 0; j < n; j += L) {
    const std::array<Lanes, 4> F = {load_lanes(Fc + j), load_lanes(Fc + S + j), load_lanes(Fc + 2 * S + j),
                                    load_lanes(Fc + 3 * S + j)};
    Lanes                      c = load_lanes(cw + j);
    std::array<Lanes, 4>       P;
    const LaneMask             done = model.stress_lanes(F, c, P);
    for (std::size_t l = 0; l < L && j + l < n; ++l) {
      const std::size_t q = ws.pending_q[j + l];
      double            cb;
      Mat2              Pb;
      if (done[l]) {
        cb = c[l];
        Pb = {P[0][l], P[1][l], P[2][l], P[3][l]};
      } else {
        cb                        = cw[j + l];
        const StressStatus status = model_lane_fallback(model, {F[0][l], F[1][l], F[2][l], F[3][l]}, cb, Pb);
        if (__builtin_expect(status != StressStatus::ok, 0)) {
          record_failure(stats, ws, i, q, status);
          form.none(q);
          continue;
        }
      }
      if (c33 && !ws.keep_warm_start) c33[o + q] = cb;
      form.stress(j + l, q, Pb);
    }
  }
}

// What both kernels (this and energy_consistent_range) set up for point i before
// its bonds: the mask words, where its bonds start and how many, its BA, intact and
// usable masks, and the scratch and totals of gather_point.
struct KernelPoint {
  std::size_t          W, offset, size;
  const std::uint64_t *ba, *intact, *usable; // ba: of the point's first bond
  PointScratch        &s;
  PointTotals          totals;
};
template <std::size_t Words>
inline KernelPoint begin_point(const PointCloud &ref, const double *y, const Families &fam, const BondGeometry &geo,
                               const BondState &state, std::size_t i, BondKernelWorkspace &ws)
{
  const std::size_t    W = Words ? Words : fam.mask_words, o = fam.offsets[i];
  const std::uint64_t *intact = state.intact.data() + i * W;
  return {W,      o,        fam.offsets[i + 1] - o,
          fam.ba_mask.data() + o * W, intact, geo.usable.data() + i * W,
          ws.point, gather_point<Words>(ref, y, fam, i, intact, ws.point)};
}

// The first pass of both force forms over the bonds of point i (begun by begin_point):
// F_iq from the masked sums (eq 9) and P(F_iq) from the model, one bond at a time or,
// for a model with stress_lanes, lane_count at a time after the loop (model_lanes). The
// form (BondOnlyForm below, EnergyConsistentForm in ba_force_energy.hpp) is told, in
// family order:
//   form.none(q)                 bond q carries no stress: broken, K not usable, or
//                                its model failed (then after its collect());
//   form.collect(slot, q, k)     its kinematics k, before the model: the form keeps
//                                what it needs in ws.pending_data[3 slot .. 3 slot + 3);
//   form.stress(slot, q, P)      P(F_iq) of the bond collected in slot.
// The c33 warm starts are read, and written back unless ws.keep_warm_start; failures
// are recorded (stats, ws.failed) in loop order.
template <std::size_t Words, class Model, class Form>
void stress_pass(const Model &model, const KernelPoint &pt, std::size_t i, double *c33, BondKernelWorkspace &ws,
                 Form &form, std::size_t &evaluated, std::size_t &unusable, KernelStats &stats)
{
  const auto &[W, o, m, ba, intact, usable, s, totals] = pt;
  std::size_t pending = 0; // bonds collected for the model (HasLanes)
  for (std::size_t q = 0; q < m; ++q) {
    const std::size_t   b     = o + q;
    const std::uint64_t bit   = std::uint64_t{1} << (q % 64);
    const bool          alive = intact[q / 64] & bit;
    if (!(alive && (usable[q / 64] & bit))) {
      unusable += alive;
      form.none(q);
      continue;
    }
    const BondKinematics k = bond_kinematics<Words>(ba + q * W, intact, W, s, totals);
    if (__builtin_expect(!k.usable, 0)) { // K went singular since the geometry was computed
      ++unusable;
      form.none(q);
      continue;
    }
    double c = c33 ? c33[b] : 0.0; // <= 0: no warm start
    ++evaluated;
    if constexpr (HasLanes<Model>::value) { // the model for lane_count bonds at a time after the loop
      const std::size_t S = ws.lane_stride;
      form.collect(pending, q, k);
      for (int comp = 0; comp < 4; ++comp) ws.pending_F[comp * S + pending] = k.F[comp];
      ws.pending_c33[pending] = c;
      ws.pending_q[pending++] = q;
      continue;
    }
    form.collect(0, q, k);
    Mat2               P;
    const StressStatus status = model.stress(k.F, c, P);
    if (__builtin_expect(status != StressStatus::ok, 0)) {
      record_failure(stats, ws, i, q, status);
      form.none(q);
      continue;
    }
    if (c33 && !ws.keep_warm_start) c33[b] = c;
    form.stress(0, q, P);
  }
  if constexpr (HasLanes<Model>::value) model_lanes(model, ws, pending, i, o, c33, form, stats);
}

// g_ij -> C_i g_ij, C_i the point's stress correction (BondGeometry::correction,
// -force_stress_correction); compiled out without one, so that the paper's force is
// bit for bit what it was.
template <bool Corrected> inline void correct(const double *C, double &g0, double &g1)
{
  if constexpr (Corrected) {
    const double h0 = C[0] * g0 + C[1] * g1, h1 = C[2] * g0 + C[3] * g1;
    g0 = h0;
    g1 = h1;
  }
}

// The paper's bond-only force of the bonds of one point (eq 23):
//   g_ij = force_scale K^{-1} (x_j - x_i) (C_i g_ij corrected),   t_ij = P(F_ij) g_ij,
// and t_ij = 0 for a bond without stress.
template <bool Corrected> struct BondOnlyForm {
  double            *t;    // the point's bond forces, 2 per bond (bond_force + 2 offset)
  double            *data; // ws.pending_data: g_ij, 2 of 3 per slot
  const double      *off, *fvk, *C;
  const PointTotals &totals;
  // -force_patch_correction (patch_correction.hpp): lambda of the point and of every
  // local point, and the point's neighbours; lambda_i nullptr: off (the lattice).
  const double       *lambda_i, *lambda;
  const std::int32_t *nb;

  void none(std::size_t q) { t[2 * q] = t[2 * q + 1] = 0.0; }
  void collect(std::size_t slot, std::size_t q, const BondKinematics &k)
  {
    const double  f  = force_scale(k, totals, fvk[q]);
    const double *ki = k.shape_tensor_inv;
    const double  d0 = off[2 * q], d1 = off[2 * q + 1];
    double        g0 = f * (ki[0] * d0 + ki[1] * d1), g1 = f * (ki[1] * d0 + ki[2] * d1);
    correct<Corrected>(C, g0, g1);
    if (lambda_i) add_patch_term(lambda_i, lambda + 2 * nb[q], d0, d1, g0, g1); // h_ij
    data[3 * slot]     = g0;
    data[3 * slot + 1] = g1;
  }
  void stress(std::size_t slot, std::size_t q, const Mat2 &P)
  {
    const double g0 = data[3 * slot], g1 = data[3 * slot + 1];
    t[2 * q]        = P[0] * g0 + P[1] * g1;
    t[2 * q + 1]    = P[2] * g0 + P[3] * g1;
  }
};

template <std::size_t Words, bool Corrected, class Model>
void bond_forces_range(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                       const BondGeometry &geo, const BondState &state, double *c33, double *bond_force,
                       BondKernelWorkspace &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  std::size_t   evaluated = 0, unusable = 0;
  const double *lambda = ref.patch_correction.empty() ? nullptr : ref.patch_correction.data();
  for (std::size_t i = begin; i < end; ++i) {
    const KernelPoint       pt = begin_point<Words>(ref, y, fam, geo, state, i, ws);
    BondOnlyForm<Corrected> form{bond_force + 2 * pt.offset, ws.pending_data.data(), pt.s.offset.data(),
                                 pt.s.family_volume.data(), Corrected ? geo.correction.data() + 4 * i : nullptr,
                                 pt.totals, lambda ? lambda + 2 * i : nullptr, lambda, fam.neighbour.data() + pt.offset};
    stress_pass<Words>(model, pt, i, c33, ws, form, evaluated, unusable, stats);
  }
  stats.evaluated += evaluated;
  stats.unusable += unusable;
}

} // namespace detail

// Bond forces t_ij (2 per bond) of the family points [begin, end), eq 23. y holds the
// current positions of every local point (ring-2 ghosts included), 2 per point. c33
// (1 per bond) is the model's out-of-plane warm start, read and written back (read
// only with ws.keep_warm_start); it may be nullptr (no warm start, nothing stored). Bonds that are broken, have no usable K
// or whose model fails get t_ij = 0 and keep their c33. Failed bonds are counted in
// the result and appended to ws.failed (this overload does not clear it).
template <class Model>
KernelStats compute_bond_forces(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                                const BondGeometry &geometry, const BondState &state, double *c33,
                                double *bond_force, BondKernelWorkspace &ws, std::size_t begin, std::size_t end)
{
  KernelStats stats;
  ws.reserve(families);
  const bool one_word = families.mask_words == 1;
  if (geometry.corrected() && one_word)
    detail::bond_forces_range<1, true>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats);
  else if (geometry.corrected())
    detail::bond_forces_range<0, true>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats);
  else if (one_word)
    detail::bond_forces_range<1, false>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats);
  else
    detail::bond_forces_range<0, false>(model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats);
  return stats;
}

// All family points [0, n_family); clears ws.failed first.
template <class Model>
KernelStats compute_bond_forces(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                                const BondGeometry &geometry, const BondState &state, double *c33,
                                double *bond_force, BondKernelWorkspace &ws)
{
  ws.failed.clear();
  return compute_bond_forces(model, ref, y, families, geometry, state, c33, bond_force, ws, 0, families.n_family);
}

// Same with a per-thread workspace kept between calls (allocates on the first call only).
template <class Model>
KernelStats compute_bond_forces(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                                const BondGeometry &geometry, const BondState &state, double *c33,
                                double *bond_force)
{
  thread_local BondKernelWorkspace ws;
  return compute_bond_forces(model, ref, y, families, geometry, state, c33, bond_force, ws);
}

// f_i = sum_j (t_ij - t_ji) V_j for the owned points [0, n_owned), in family order
// (eq 1 without body force). Every neighbour of an owned point must have a family
// here (it is owned or ring-1), so that t_ji is known; throws std::logic_error if not.
void assemble_force_density(const Families &families, const PointCloud &ref, const double *bond_force,
                            std::size_t n_owned, double *force_density);

// F_ij of one bond (slow path, for tests and output): zero if the bond is broken or
// its K is not usable.
Mat2 bond_deformation_gradient(const PointCloud &ref, const double *y, const Families &families,
                               const BondGeometry &geometry, const BondState &state, std::size_t i,
                               std::size_t q);

// Strain energy (for energy reports), per point and in total over points [0, n_points):
//   E_i = V_i W_i,   W_i = sum_j Psi(F_ij) V_j / sum_j V_j,   W = sum_i E_i,
// both sums over the intact bonds of i with a usable K whose model energy succeeds
// (W_i = 0 if there is none). W_i is the volume-weighted mean of the bond energy
// densities of i, so for an affine motion (F_ij = A) W = Psi(A) * (volume of the
// points with a usable bond): the continuum energy. The bond-only forces here are not
// its derivative (the paper's form, METHOD.md section 3); the energy-consistent ones
// (ba_force_energy.hpp) are: f_i = -(1/V_i) dW/dy_i.
// c33 (may be nullptr) is read as a warm start, never written. Writes E_i to
// point_energy[i] if given (for a reproducible sum over ranks) and returns W summed
// in local order. Failed energies are counted in *stats if given, their bonds skipped.
template <class Model>
double strain_energy(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                     const BondGeometry &geometry, const BondState &state, const double *c33, std::size_t n_points,
                     BondKernelWorkspace &ws, KernelStats *stats = nullptr, double *point_energy = nullptr)
{
  ws.reserve(families);
  const std::size_t W = families.mask_words;
  PointScratch     &s = ws.point;
  KernelStats       local;
  double            total = 0.0;
  for (std::size_t i = 0; i < n_points; ++i) {
    const std::size_t    o      = families.offsets[i], m = families.offsets[i + 1] - o;
    const std::uint64_t *intact = state.intact_mask(i);
    const PointTotals totals = W == 1 ? detail::gather_point<1>(ref, y, families, i, intact, s)
                                      : detail::gather_point<0>(ref, y, families, i, intact, s);
    double            num = 0.0, den = 0.0;
    for (std::size_t q = 0; q < m; ++q) {
      if (!state.is_intact(i, q)) continue;
      const std::size_t    b = o + q;
      // the kernel's arithmetic, bit for bit
      const BondKinematics k = W == 1 ? detail::bond_kinematics<1>(families.ba(b), intact, 1, s, totals)
                                      : detail::bond_kinematics<0>(families.ba(b), intact, W, s, totals);
      if (!geometry.is_usable(i, q) || !k.usable) {
        ++local.unusable;
        continue;
      }
      double c = c33 ? c33[b] : 0.0, psi = 0.0;
      ++local.evaluated;
      const StressStatus status = model.energy(k.F, c, psi);
      if (status != StressStatus::ok) {
        local.record(i, q, status);
        continue;
      }
      const double vj = ref.volume[static_cast<std::size_t>(families.neighbour[b])];
      num += psi * vj;
      den += vj;
    }
    const double e = den > 0 ? ref.volume[i] * (num / den) : 0.0;
    if (point_energy) point_energy[i] = e;
    total += e;
  }
  if (stats) *stats = local;
  return total;
}

// Same without warm start, with a per-thread workspace.
template <class Model>
double strain_energy(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                     const BondGeometry &geometry, const BondState &state, std::size_t n_points)
{
  thread_local BondKernelWorkspace ws;
  return strain_energy(model, ref, y, families, geometry, state, nullptr, n_points, ws);
}

} // namespace bapd
