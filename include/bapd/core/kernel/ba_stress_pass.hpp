#pragma once
// The bond kernel's first pass over a point's bonds (ba_force.hpp): F_ij and P(F_ij).
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "bapd/core/kernel/ba_model_lanes.hpp"
#include "bapd/core/kernel/ba_workspace.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {
namespace detail {

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

} // namespace detail
} // namespace bapd::nd
