#pragma once
// Bond-associated NOSB bond forces in D = 2 or 3 dimensions, both force forms
// (paper eqs 9, 23; METHOD.md sections 2-3): the one kernel for 2D and 3D (issue 21;
// stage 3 retired the 2D-only ba_force.hpp and ba_force_energy.hpp, whose operations
// D = 2 does in their order).
//
// Bond-only (the paper's, eq 23), for every intact bond b = (i -> j) with a usable K:
//   t_ij = P(F_ij) g_ij,   g_ij = 1/2 phi_xi/phi C_i K_ij^{-1} (x_j - x_i)
// with C_i the stress correction (tensor: M_i^{-1}, so that a uniform P gives
// sum_j t_ij (x) xi_ij V_j = P at every point; bond_geometry.hpp,
// stress_correction.hpp) and, with -force_patch_correction (patch_correction.hpp),
// h_ij = ((lambda_i - lambda_j) . xi) xi added to g_ij.
//
// Energy-consistent (METHOD.md section 3; after Breitzman & Dayal 2018): the force
// density is minus the gradient of the stored energy
//   W = sum_i V_i omega_i sum_{b = (i -> j)} V_j Psi(F_ij),   omega_i = 1 / sum_b V_j,
// both sums over the bonds of i that carry energy (intact, usable K, model ok): the
// energy strain_energy() reports (W = Psi(A) x volume for an affine motion). The
// bond-only force is not the gradient of any energy: its tangent is not symmetric
// next to a free surface, which gives complex eigenvalues and undamped motions that
// grow whatever the time step (ba_force_energy_test.cpp). The derivation, for any D:
// F_ij = sum_{m in B} (y_m - y_i) (x) g_m, g_m = K_ij^{-1}(x_m - x_i) V_m (B = the
// intact members of B_ij, eq 9), so with M_b = omega_i V_j P(F_ij) K_ij^{-1}
//   dW/dy_m += V_i M_b (x_m - x_i) V_m   (m in B),
//   dW/dy_i -= V_i M_b sum_{m in B} (x_m - x_i) V_m.
// Collect, for a bond (i -> p), the stresses of the bonds of i whose BA family holds p:
//   S_ip = sum_{q : p in intact B_iq} V_q P(F_iq) K_iq^{-1},   t_ip = omega_i S_ip (x_p - x_i)
// (t_ip = 0 if the bond (i -> p) is broken). Then f_k = -(1/V_k) dW/dy_k becomes
// sum_j (t_kj - t_jk) V_j, the bond-only assembly (eq 1) with these t_ij: momentum is
// conserved pair by pair, nothing depends on the local numbering, and the halo is the
// same (t_ij needs i's family only). BA masks are symmetric within a family (p in B_iq
// iff q in B_ip: both are |x_p - x_q| <= delta, computed with the same bits either
// way; build_families), so the bonds q with p in B_iq are the set bits of bond
// (i -> p)'s own BA mask, and S_ip is one masked sum of the per-bond M_iq with the
// code (and the "word total minus the others" shortcut) of F_ij's sums. A bond that is
// broken, has no usable K or whose model fails has no energy; its end point p still
// counts in the other bonds' F_iq, so t_ip is generally not 0 unless (i -> p) is broken.
//
// Either way the force density of an owned point is
//   f_i = sum_j (t_ij - t_ji) V_j                                                 (eq 1)
// (assemble_force_density). Per point i the kernel runs one loop over its bonds (F_ij
// from the masked sums, then P: stress_pass), and the energy-consistent form a second
// (S_ip and t_ip); nothing per bond is stored beyond t_ij and c33.
//
// The model is a template parameter (inlined into the loop, nothing virtual per
// bond), with either of the two stress signatures of the existing laws:
//   StressStatus stress(const Mat<D> &F, Mat<D> &P) const             (Compressible3D)
//   StressStatus stress(const Mat<D> &F, double &c33, Mat<D> &P) const (2D PlaneStrain,
//        PlaneStress: c33 is the out-of-plane warm start, read from and written to
//        the optional c33 array, one per bond)
// and energy(F, psi) or energy(F, c33, psi) likewise. A model with has_lanes and
//   LaneMask stress_lanes(const std::array<Lanes, D*D> &F, Lanes &c33, std::array<Lanes, D*D> &P) const
// (PlaneStress in 2D, Compressible3DLanes in 3D: compressible_lanes.hpp) gets the
// point's bonds after the first loop, lane_count at a time (model_lanes; the last half
// register or less in HalfLanes where stress_lanes is a template over the register, as
// PlaneStress's is); a lane it does not finish goes through its scalar stress().
// Nothing is allocated per call (Workspace is sized once), except the list of failed
// bonds in the rare call where a model fails.
//
// Determinism: every sum runs in family order (families are sorted by natural id) and
// nothing depends on the local numbering, so a rank's owned points get bit for bit the
// bond forces and force densities of a one-rank run.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "bapd/core/kernel/force_form.hpp"
#include "bapd/core/kernel/kernel_stats.hpp"
#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {

// The kernels' work space: the point scratch, the energy-consistent form's per-bond
// stresses, and the failed bonds of the last call. Sized once (reserve).
template <int D> struct Workspace {
  PointScratch<D>              point;
  std::vector<StressRecord<D>> bond_stress;       // M_iq = V_q P(F_iq) K_iq^{-1} of the point's bonds
  std::vector<StressRecord<D>> bond_stress_total; // their sum by mask word (masked_sum's word_total)
  std::vector<std::uint64_t>   energetic;   // which of them carry energy
  std::vector<FailedBond>      failed;      // every failed bond of the last call
  bool                         keep_warm_start = false; // read c33, do not write it back
  // What a form keeps of a bond between its kinematics and its P, data_components of
  // them a slot, by component (component c of slot s at pending_data[c lane_stride + s],
  // so that a form reads lane_count slots' component as one vector): g of the bond-only
  // form, K^{-1} and V_q of the energy-consistent one. Models with a lane
  // path (has_lanes: PlaneStress in 2D, Compressible3DLanes in 3D) get the point's
  // bonds after the loop, lane_count at a time: F by component (D x D arrays of
  // lane_stride), the c33 warm start and the position q of each.
  static constexpr std::size_t data_components = sym_size<D> + 1;
  std::size_t                  lane_stride = 0; // max_family_size rounded up to lane_count
  std::vector<double>          pending_F, pending_c33, pending_data;
  std::vector<std::size_t>     pending_q;

  void reserve(const Families &f)
  {
    point.reserve(f);
    if (bond_stress.size() < f.max_family_size) bond_stress.resize(f.max_family_size);
    if (bond_stress_total.size() < f.mask_words) bond_stress_total.resize(f.mask_words);
    if (energetic.size() < f.mask_words) energetic.resize(f.mask_words);
    const std::size_t L = lane_count, stride = (std::max<std::size_t>(f.max_family_size, 1) + L - 1) / L * L;
    if (lane_stride < stride) {
      lane_stride = stride;
      pending_F.assign(D * D * stride, 0.0);
      pending_c33.assign(stride, 0.0);
      pending_data.assign(data_components * stride, 0.0);
      pending_q.assign(stride, 0);
    }
  }
};

// -force_patch_correction (patch_correction.hpp): h_ij = c_ij xi added to g_ij, from
// patch_stride<D>(virial) numbers a point. on: lambda (D), c_ij = (lambda_i - lambda_j) . xi;
// virial: (mu, S_i upper triangle by sym_index), c_ij = (mu_i - mu_j) . xi + xi . S_i xi.
// For D = 2 the operations of the 2D add_patch_term and virial_patch_coefficient in their order.
template <int D> constexpr std::size_t patch_stride(bool virial) { return virial ? D + sym_size<D> : D; }
template <int D>
inline void add_patch_term(const double *lambda_i, const double *lambda_j, const double *xi, double *g, bool virial = false)
{
  double s = (lambda_i[0] - lambda_j[0]) * xi[0];
  for (int r = 1; r < D; ++r) s = s + (lambda_i[r] - lambda_j[r]) * xi[r];
  if (virial)
    for (int r = 0; r < D; ++r)
      for (int c = r; c < D; ++c) s = s + (r == c ? 1.0 : 2.0) * lambda_i[D + sym_index<D>(r, c)] * xi[r] * xi[c];
  for (int r = 0; r < D; ++r) g[r] += s * xi[r];
}

namespace detail {

// The two stress and energy signatures (see the top of this file); int is preferred.
template <int D, class M>
inline auto stress_of(const M &m, const Mat<D> &F, double &c33, Mat<D> &P, int) -> decltype(m.stress(F, c33, P))
{
  return m.stress(F, c33, P);
}
template <int D, class M>
inline auto stress_of(const M &m, const Mat<D> &F, double &, Mat<D> &P, long) -> decltype(m.stress(F, P))
{
  return m.stress(F, P);
}
template <int D, class M>
inline auto energy_of(const M &m, const Mat<D> &F, double &c33, double &psi, int) -> decltype(m.energy(F, c33, psi))
{
  return m.energy(F, c33, psi);
}
template <int D, class M>
inline auto energy_of(const M &m, const Mat<D> &F, double &, double &psi, long) -> decltype(m.energy(F, psi))
{
  return m.energy(F, psi);
}

// Whether a model has a lane path (has_lanes = true and stress_lanes).
template <class M, class = void> struct HasLanes : std::false_type {};
template <class M> struct HasLanes<M, std::enable_if_t<M::has_lanes>> : std::true_type {};

template <class T> inline T load_lanes(const double *p)
{
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Whether a model's lane path also takes half a register (HalfLanes, lanes.hpp).
template <class M, int DD, class = void> struct HasHalfLanes : std::false_type {};
template <class M, int DD>
struct HasHalfLanes<M, DD,
                    std::void_t<decltype(std::declval<const M &>().stress_lanes(std::declval<const std::array<HalfLanes, DD> &>(),
                                                                               std::declval<HalfLanes &>(),
                                                                               std::declval<std::array<HalfLanes, DD> &>()))>>
    : std::true_type {};

[[gnu::noinline, gnu::cold]] inline void record_failure(KernelStats &stats, std::vector<FailedBond> &failed,
                                                        std::size_t i, std::size_t q, StressStatus status)
{
  stats.record(i, q, status);
  failed.push_back({i, q, status});
}

template <int D, class Model>
[[gnu::noinline, gnu::cold]] StressStatus model_lane_fallback(const Model &model, const Mat<D> &F, double &c33, Mat<D> &P)
{
  return stress_of<D>(model, F, c33, P, 0);
}

// One batch of model_lanes: the bonds collected in slots j .. j + width - 1 (T = Lanes,
// or HalfLanes for a point's last few), those from n on unused. top: tr C lane by lane.
template <int D, class T, class Model, class Form>
inline void model_batch(const Model &model, Workspace<D> &ws, std::size_t j, std::size_t n, std::size_t i,
                        std::size_t o, double *c33, Form &form, T &top, KernelStats &stats)
{
  constexpr int         DD = D * D;
  constexpr std::size_t L  = sizeof(T) / sizeof(double);
  const std::size_t     S  = ws.lane_stride;
  const double         *Fc = ws.pending_F.data(), *cw = ws.pending_c33.data();
  std::array<T, DD>     F, P;
  for (int k = 0; k < DD; ++k) F[k] = load_lanes<T>(Fc + k * S + j);
  T c   = load_lanes<T>(cw + j);
  T trC = D == 2 ? select(c > 0.0, c, T{} + 1.0) : T{};
  for (int k = 0; k < DD; ++k) trC = trC + F[k] * F[k];
  top                = select(trC > top, trC, top);
  const auto done    = model.stress_lanes(F, c, P);
  const auto product = form.product(j, P);
  for (std::size_t l = 0; l < L && j + l < n; ++l) {
    const std::size_t q = ws.pending_q[j + l];
    if (done[l]) {
      if (c33 && !ws.keep_warm_start) c33[o + q] = c[l];
      form.store(j + l, q, product, l);
      continue;
    }
    double cb = cw[j + l];
    Mat<D> Fb, Pb;
    for (int k = 0; k < DD; ++k) Fb[k] = F[k][l];
    const StressStatus status = model_lane_fallback<D>(model, Fb, cb, Pb);
    if (__builtin_expect(status != StressStatus::ok, 0)) {
      record_failure(stats, ws.failed, i, q, status);
      form.none(q);
      continue;
    }
    if (c33 && !ws.keep_warm_start) c33[o + q] = cb;
    form.stress(j + l, q, Pb);
  }
}

// The model over the n bonds of point i collected in ws.pending_*, lane_count at a
// time (Model::stress_lanes); the last half register or less of them in HalfLanes where
// the model takes them (the paper's horizon gives 28 bonds a point: 3.5 batches of 8,
// not 4). A lane it does not finish goes through the scalar stress(), which gives bit
// for bit what stress_lanes gives where that finishes (plane_stress.hpp), so a bond's
// result does not depend on its lane or on the width of its batch. The form's product
// with P is formed for all lanes at once (form.product, the operations of form.stress
// lane by lane, so the same bits) and kept by form.store for the lanes the model
// finished. Bonds are taken in family order, so failures are recorded and the form is
// told (store, stress) in loop order.
template <int D, class Model, class Form>
void model_lanes(const Model &model, Workspace<D> &ws, std::size_t n, std::size_t i, std::size_t o, double *c33,
                 Form &form, double &largest_trC, KernelStats &stats)
{
  constexpr int     DD   = D * D;
  constexpr bool    half = HasHalfLanes<Model, DD>::value;
  const std::size_t S    = ws.lane_stride, L = lane_count;
  double           *Fc = ws.pending_F.data(), *cw = ws.pending_c33.data();
  for (std::size_t l = n; l < (n + L - 1) / L * L; ++l) { // unused lanes: the rest state
    for (int k = 0; k < DD; ++k) Fc[k * S + l] = k % (D + 1) == 0 ? 1.0 : 0.0;
    cw[l] = 0.0;
  }
  Lanes       top = Lanes{}; // tr C of the bonds, lane by lane (stress_pass's scalar tr C; unused lanes hold the rest state, 3)
  std::size_t j   = 0;
  // whole registers, until what is left fits in half of one (if the model takes that)
  for (; j < n && !(half && n - j <= L / 2); j += L) model_batch<D>(model, ws, j, n, i, o, c33, form, top, stats);
  if constexpr (half) {
    HalfLanes top_half = HalfLanes{};
    if (j < n) model_batch<D>(model, ws, j, n, i, o, c33, form, top_half, stats);
    for (std::size_t l = 0; l < L / 2; ++l) largest_trC = std::max(largest_trC, top_half[l]);
  }
  for (std::size_t l = 0; l < L; ++l) largest_trC = std::max(largest_trC, top[l]);
}

// The first pass of both forms over the bonds of point i: F_iq (eq 9) and P(F_iq)
// from the model. The form is told, in family order:
//   form.none(q)               no stress: broken, K not usable, or the model failed;
//   form.collect(slot, q, k)   the kinematics, before the model (the form keeps what
//                              it needs in ws.pending_data, by component);
//   form.stress(slot, q, P)    P(F_iq) of the bond collected in slot;
//   form.product(j, P), form.store(slot, q, product, l)
//                              the same for P of lane_count slots from j (model_lanes).
// A model with stress_lanes (has_lanes) gets the bonds after the loop (model_lanes).
template <int D, std::size_t Words, class Model, class Form>
inline void stress_pass(const Model &model, const Families &fam, const BondGeometry<D> &geo, const BondState &state,
                        std::size_t i, const PointTotals<D> &totals, double *c33, Workspace<D> &ws, Form &form,
                        std::size_t &evaluated, std::size_t &unusable, double &largest_trC, KernelStats &stats)
{
  const std::size_t    W = fam.mask_words, o = fam.offsets[i], m = fam.size(i);
  const std::uint64_t *intact = state.intact_mask(i), *usable = geo.usable.data() + i * W;
  const std::uint64_t *ba     = fam.ba_mask.data() + o * W;
  std::size_t          pending = 0; // bonds collected for the lanes
  for (std::size_t q = 0; q < m; ++q) {
    const std::uint64_t bit   = std::uint64_t{1} << (q % 64);
    const bool          alive = intact[q / 64] & bit;
    if (!(alive && (usable[q / 64] & bit))) {
      unusable += alive;
      form.none(q);
      continue;
    }
    const BondKinematics<D> k = bond_kinematics<D, Words>(ba + q * W, intact, W, ws.point, totals);
    if (__builtin_expect(!k.usable, 0)) { // K went singular since the geometry was computed
      ++unusable;
      form.none(q);
      continue;
    }
    double c = c33 ? c33[o + q] : 0.0; // <= 0: no warm start
    ++evaluated;
    if constexpr (HasLanes<Model>::value) {
      const std::size_t S = ws.lane_stride;
      form.collect(pending, q, k);
      for (int comp = 0; comp < D * D; ++comp) ws.pending_F[comp * S + pending] = k.F[comp];
      ws.pending_c33[pending] = c;
      ws.pending_q[pending++] = q;
      continue;
    }
    // tr C of the bond (in 2D with the out-of-plane C33 of its warm start, 1 without
    // one): the time step's stiffening trigger (KernelStats::largest_trC; model_lanes
    // keeps it for the lane models, a vector at a time).
    double trC = D == 2 ? (c > 0.0 ? c : 1.0) : 0.0;
    for (int comp = 0; comp < D * D; ++comp) trC += k.F[comp] * k.F[comp];
    largest_trC = std::max(largest_trC, trC);
    form.collect(0, q, k);
    Mat<D>             P;
    const StressStatus status = stress_of<D>(model, k.F, c, P, 0);
    if (__builtin_expect(status != StressStatus::ok, 0)) {
      record_failure(stats, ws.failed, i, q, status);
      form.none(q);
      continue;
    }
    if (c33 && !ws.keep_warm_start) c33[o + q] = c;
    form.stress(0, q, P);
  }
  if constexpr (HasLanes<Model>::value) model_lanes<D>(model, ws, pending, i, o, c33, form, largest_trC, stats);
}

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

  void none(std::size_t q)
  {
    for (int r = 0; r < D; ++r) t[D * q + r] = 0.0;
  }
  // Out of line: inlined into stress_pass's loop it made that loop slower (3D lanes
  // bond-only 47.4 ns a bond inlined, 40.4 out of line; docs/performance.md 1k).
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
  }
  template <class T> void store(std::size_t, std::size_t q, const std::array<T, D> &f, std::size_t l)
  {
    for (int r = 0; r < D; ++r) t[D * q + r] = f[r][l];
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

  void none(std::size_t) {} // no energy: M_iq is not read (its bit stays clear)
  void collect(std::size_t slot, std::size_t q, const BondKinematics<D> &k)
  {
    for (int c = 0; c < sym_size<D>; ++c) data[c * S + slot] = k.shape_tensor_inv[c];
    data[volume_component * S + slot] = rec[q][Member<D>::volume];
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
  void keep(std::size_t slot, std::size_t q, const double *m_iq)
  {
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

template <int D, std::size_t Words, bool Corrected, class Model>
void bond_only_range(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                     const BondGeometry<D> &geo, const BondState &state, double *c33, double *bond_force,
                     Workspace<D> &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  const double     *lambda = ref.patch_correction.empty() ? nullptr : ref.patch_correction.data();
  const std::size_t stride = patch_stride<D>(ref.patch_virial);
  std::size_t       evaluated = 0, unusable = 0; // locals, not stats.*: no reload per bond (pending_q may alias)
  double            largest_trC = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    const PointTotals<D>    totals = gather_point<D>(ref, y, fam, i, state.intact_mask(i), ws.point);
    BondOnlyForm<D, Corrected> form{bond_force + D * fam.offsets[i],
                                    ws.pending_data.data(),
                                    ws.lane_stride,
                                    ws.point.offset.data(),
                                    ws.point.family_volume.data(),
                                    Corrected ? geo.correction.data() + D * D * i : nullptr,
                                    totals,
                                    lambda ? lambda + stride * i : nullptr,
                                    lambda,
                                    fam.neighbour.data() + fam.offsets[i],
                                    ref.patch_virial};
    stress_pass<D, Words>(model, fam, geo, state, i, totals, c33, ws, form, evaluated, unusable, largest_trC, stats);
  }
  stats.evaluated += evaluated;
  stats.unusable += unusable;
  stats.largest_trC = std::max(stats.largest_trC, largest_trC);
}

template <int D, std::size_t Words, class Model>
void energy_consistent_range(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                             const BondGeometry<D> &geo, const BondState &state, double *c33, double *bond_force,
                             Workspace<D> &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  const std::size_t W = fam.mask_words;
  std::size_t       evaluated = 0, unusable = 0; // as in bond_only_range
  double            largest_trC = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t    o = fam.offsets[i], m = fam.size(i);
    const std::uint64_t *intact = state.intact_mask(i), *ba = fam.ba_mask.data() + o * W;
    const PointTotals<D> totals = gather_point<D>(ref, y, fam, i, intact, ws.point);
    for (std::size_t w = 0; w < W; ++w) ws.energetic[w] = 0;
    for (std::size_t w = 0; w < W; ++w) ws.bond_stress_total[w].zero();
    EnergyConsistentForm<D> form{ws.bond_stress.data(),      ws.energetic.data(),
                                 ws.pending_data.data(),     ws.lane_stride,
                                 ws.point.member.data(),     ws.bond_stress_total.data(),
                                 0.0};
    stress_pass<D, Words>(model, fam, geo, state, i, totals, c33, ws, form, evaluated, unusable, largest_trC, stats);
    // Pass 2: t_ip = omega_i S_ip (x_p - x_i), S_ip = the sum of M_iq over q in B_ip
    // (BA masks are symmetric within a family: see the top of this file).
    double *t = bond_force + D * o;
    if (form.volume == 0.0) { // no bond of i carries energy
      for (std::size_t k = 0; k < D * m; ++k) t[k] = 0.0;
      continue;
    }
    const double  omega = 1.0 / form.volume;
    const double *off   = ws.point.offset.data();
    for (std::size_t p = 0; p < m; ++p) {
      if (!((intact[p / 64] >> (p % 64)) & 1u)) {
        for (int r = 0; r < D; ++r) t[D * p + r] = 0.0;
        continue;
      }
      const StressRecord<D> S =
          masked_sum<Words>(ba + p * W, ws.energetic.data(), W, ws.bond_stress.data(), ws.bond_stress_total.data());
      for (int r = 0; r < D; ++r) {
        double s = S[D * r] * off[D * p];
        for (int c = 1; c < D; ++c) s += S[D * r + c] * off[D * p + c];
        t[D * p + r] = omega * s;
      }
    }
  }
  stats.evaluated += evaluated;
  stats.unusable += unusable;
  stats.largest_trC = std::max(stats.largest_trC, largest_trC);
}

template <int D, std::size_t Words, class Model>
void forces_range(ForceForm form, const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                  const BondGeometry<D> &geo, const BondState &state, double *c33, double *bond_force,
                  Workspace<D> &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  if (form == ForceForm::energy_consistent)
    energy_consistent_range<D, Words>(model, ref, y, fam, geo, state, c33, bond_force, ws, begin, end, stats);
  else if (geo.corrected())
    bond_only_range<D, Words, true>(model, ref, y, fam, geo, state, c33, bond_force, ws, begin, end, stats);
  else bond_only_range<D, Words, false>(model, ref, y, fam, geo, state, c33, bond_force, ws, begin, end, stats);
}

} // namespace detail

// Bond forces t_ij (D per bond) of the family points [begin, end) in the given form.
// y: current positions of every local point (ring-2 ghosts included), D per point.
// c33: per-bond warm start of 2D models that have one (may be nullptr; ignored by
// models without). Broken bonds, bonds without a usable K and bonds whose model fails
// get t_ij = 0 (bond-only; the energy-consistent t_ij of a bond without energy is
// generally not 0). Failed bonds are counted and appended to ws.failed.
template <int D, class Model>
KernelStats compute_bond_forces(ForceForm form, const Model &model, const PointCloud &ref, const double *y,
                                const Families &families, const BondGeometry<D> &geometry, const BondState &state,
                                double *c33, double *bond_force, Workspace<D> &ws, std::size_t begin,
                                std::size_t end)
{
  KernelStats stats;
  ws.reserve(families);
  switch (families.mask_words) { // 1: 2D up to 64 members; 2, 3: 3D at delta <= 3.8 dx
  case 1: detail::forces_range<D, 1>(form, model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats); break;
  case 2: detail::forces_range<D, 2>(form, model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats); break;
  case 3: detail::forces_range<D, 3>(form, model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats); break;
  default: detail::forces_range<D, 0>(form, model, ref, y, families, geometry, state, c33, bond_force, ws, begin, end, stats);
  }
  return stats;
}

// All family points [0, n_family); clears ws.failed first.
template <int D, class Model>
KernelStats compute_bond_forces(ForceForm form, const Model &model, const PointCloud &ref, const double *y,
                                const Families &families, const BondGeometry<D> &geometry, const BondState &state,
                                double *c33, double *bond_force, Workspace<D> &ws)
{
  ws.failed.clear();
  return compute_bond_forces<D>(form, model, ref, y, families, geometry, state, c33, bond_force, ws, 0,
                                families.n_family);
}

// f_i = sum_j (t_ij - t_ji) V_j for the owned points [0, n_owned), in family order
// (eq 1 without body force). Throws std::logic_error if a neighbour of an owned point
// has no family here (t_ji unknown).
template <int D>
void assemble_force_density(const Families &families, const PointCloud &ref, const double *bond_force,
                            std::size_t n_owned, double *force_density);

// Strain energy W = sum_i V_i sum_j Psi(F_ij) V_j / sum_j V_j over the bonds of i that
// carry energy: the energy whose gradient the
// energy-consistent form is, Psi(A) x volume for an affine motion. c33 (may be
// nullptr) is read only. Writes E_i to point_energy[i] if given.
template <int D, class Model>
double strain_energy(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                     const BondGeometry<D> &geometry, const BondState &state, const double *c33,
                     std::size_t n_points, Workspace<D> &ws, KernelStats *stats = nullptr,
                     double *point_energy = nullptr)
{
  ws.reserve(families);
  const std::size_t W = families.mask_words;
  KernelStats       local;
  double            total = 0.0;
  for (std::size_t i = 0; i < n_points; ++i) {
    const std::size_t    o      = families.offsets[i], m = families.size(i);
    const std::uint64_t *intact = state.intact_mask(i);
    const PointTotals<D> totals = gather_point<D>(ref, y, families, i, intact, ws.point);
    double               num = 0.0, den = 0.0;
    for (std::size_t q = 0; q < m; ++q) {
      if (!state.is_intact(i, q)) continue;
      const BondKinematics<D> k = bond_kinematics<D>(families.ba(o + q), intact, W, ws.point, totals);
      if (!geometry.is_usable(i, q) || !k.usable) {
        ++local.unusable;
        continue;
      }
      double c = c33 ? c33[o + q] : 0.0, psi = 0.0;
      ++local.evaluated;
      const StressStatus status = detail::energy_of<D>(model, k.F, c, psi, 0);
      if (status != StressStatus::ok) {
        local.record(i, q, status);
        continue;
      }
      const double vj = ref.volume[static_cast<std::size_t>(families.neighbour[o + q])];
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

// F_ij of bond q of point i (slow path, tests and output): zero if the bond is broken
// or its K not usable.
template <int D>
Mat<D> bond_deformation_gradient(const PointCloud &ref, const double *y, const Families &families,
                                 const BondGeometry<D> &geometry, const BondState &state, std::size_t i,
                                 std::size_t q)
{
  if (!state.is_intact(i, q) || !geometry.is_usable(i, q)) return Mat<D>{};
  PointScratch<D> s;
  s.reserve(families);
  const PointTotals<D>    totals = gather_point<D>(ref, y, families, i, state.intact_mask(i), s);
  const BondKinematics<D> k      = bond_kinematics<D>(families.ba(families.offsets[i] + q), state.intact_mask(i),
                                                      families.mask_words, s, totals);
  return k.usable ? k.F : Mat<D>{};
}

} // namespace bapd::nd
