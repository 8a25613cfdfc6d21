#pragma once
// The constitutive model inside the bond kernel (ba_force.hpp): its two stress and
// energy signatures, and its lane path, the point's bonds lane_count at a time.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <vector>

#include "bapd/core/kernel/ba_workspace.hpp"
#include "bapd/core/kernel/kernel_stats.hpp"
#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {
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

} // namespace detail
} // namespace bapd::nd
