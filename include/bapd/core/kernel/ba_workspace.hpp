#pragma once
// The work space of the bond kernel (ba_force.hpp), sized once per family set.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bapd/core/kernel/kernel_stats.hpp"
#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/volumetric.hpp"

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
  // -material_volumetric (volumetric.hpp): point evaluates U once per point, from Jbar_i;
  // then the energy-consistent form keeps, per bond, J_iq and V_q cof(F_iq) K_iq^{-1}.
  Volumetric                   volumetric = Volumetric::bond;
  double                       volumetric_stabilisation = 0.0; // kappa [Pa] (point only)
  std::vector<StressRecord<D>> bond_cofactor;   // V_q cof(F_iq) K_iq^{-1} (point only)
  std::vector<double>          bond_dilatation; // J_iq (point only)
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
    if (volumetric == Volumetric::point && bond_cofactor.size() < f.max_family_size) {
      bond_cofactor.resize(f.max_family_size);
      bond_dilatation.resize(f.max_family_size);
    }
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

} // namespace bapd::nd
