#pragma once
// Bond-associated NOSB bond forces in D = 2 or 3 dimensions, both force forms
// (paper eqs 9, 23; docs/method.md sections 2-3): the one kernel for 2D and 3D (D = 2 does
// the operations of the former 2D-only kernels in their order).
//
// The pieces: ba_workspace.hpp (the scratch, sized once), ba_patch_term.hpp (h_ij),
// ba_model_lanes.hpp (the model's signatures and its lane batches), ba_stress_pass.hpp
// (the first pass: F_ij and P), ba_forms.hpp (the two force forms); this file the loops
// over a range of points, the assembly (eq 1) and the strain energy.
//
// Bond-only (the paper's, eq 23), for every intact bond b = (i -> j) with a usable K:
//   t_ij = P(F_ij) g_ij,   g_ij = 1/2 phi_xi/phi C_i K_ij^{-1} (x_j - x_i)
// with C_i the stress correction (tensor: M_i^{-1}, so that a uniform P gives
// sum_j t_ij (x) xi_ij V_j = P at every point; bond_geometry.hpp,
// stress_correction.hpp) and, with -force_patch_correction (patch_correction.hpp),
// h_ij = ((lambda_i - lambda_j) . xi) xi added to g_ij.
//
// Energy-consistent (docs/method.md section 3; after Breitzman & Dayal 2018): the force
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
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "bapd/core/kernel/ba_forms.hpp"
#include "bapd/core/kernel/ba_model_lanes.hpp"
#include "bapd/core/kernel/ba_patch_term.hpp"
#include "bapd/core/kernel/ba_stress_pass.hpp"
#include "bapd/core/kernel/ba_workspace.hpp"
#include "bapd/core/kernel/force_form.hpp"
#include "bapd/core/kernel/kernel_stats.hpp"
#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {

namespace detail {

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
                                    ref.patch_virial,
                                    state.damage_from(fam.offsets[i])};
    stress_pass<D, Words>(model, fam, geo, state, i, totals, c33, ws, form, evaluated, unusable, largest_trC, stats);
  }
  stats.evaluated += evaluated;
  stats.unusable += unusable;
  stats.largest_trC = std::max(stats.largest_trC, largest_trC);
}

// -material_volumetric point (volumetric.hpp), after the first pass over the bonds of a
// point: Jbar_i = omega_i sum_q V_q J_iq over the bonds that carry energy, then
//   M_iq += (U'(Jbar_i) - U'(J_iq) + kappa (J_iq - Jbar_i)) V_q cof(F_iq) K_iq^{-1}
// (M_iq = V_q P*_iq K_iq^{-1}), and the word totals summed again, in family order.
template <int D>
inline void point_volumetric(Workspace<D> &ws, const MemberRecord<D> *rec, std::size_t m, double volume,
                             double compressibility, double kappa)
{
  const std::uint64_t *energetic = ws.energetic.data();
  double               sum       = 0.0;
  for (std::size_t q = 0; q < m; ++q)
    if ((energetic[q / 64] >> (q % 64)) & 1u) sum += rec[q][Member<D>::volume] * ws.bond_dilatation[q];
  const double Jbar = sum / volume, slope_bar = volumetric_slope(Jbar, compressibility);
  for (std::size_t w = 0; w < (m + 63) / 64; ++w) ws.bond_stress_total[w].zero();
  for (std::size_t q = 0; q < m; ++q) {
    if (!((energetic[q / 64] >> (q % 64)) & 1u)) continue;
    const double    J = ws.bond_dilatation[q];
    const double    a = slope_bar - volumetric_slope(J, compressibility) + stabilisation_slope(J, Jbar, kappa);
    StressRecord<D> n = ws.bond_cofactor[q];
    for (int v = 0; v < StressRecord<D>::vectors; ++v) n.v[v] *= a;
    ws.bond_stress[q] += n;
    ws.bond_stress_total[q / 64] += ws.bond_stress[q];
  }
}

template <int D, std::size_t Words, class Model>
void energy_consistent_range(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                             const BondGeometry<D> &geo, const BondState &state, double *c33, double *bond_force,
                             Workspace<D> &ws, std::size_t begin, std::size_t end, KernelStats &stats)
{
  const std::size_t W = fam.mask_words;
  const bool        point = ws.volumetric == Volumetric::point;
  const double      compressibility = point ? detail::compressibility(model, 0) : 0.0;
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
                                 0.0,
                                 point ? ws.bond_cofactor.data() : nullptr,
                                 point ? ws.bond_dilatation.data() : nullptr,
                                 state.damage_from(o)};
    stress_pass<D, Words>(model, fam, geo, state, i, totals, c33, ws, form, evaluated, unusable, largest_trC, stats);
    if (point && form.volume != 0.0) point_volumetric<D>(ws, ws.point.member.data(), m, form.volume, compressibility,
                                                         ws.volumetric_stabilisation);
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
  if (ws.volumetric == Volumetric::point && (form != ForceForm::energy_consistent || !(detail::compressibility(model, 0) > 0.0)))
    throw std::invalid_argument("nd::compute_bond_forces: the point volumetric energy needs the energy-consistent form and a "
                                "model of the registry (its compressibility D > 0)");
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

namespace detail {

// Psi(F_iq) of every bond of point i that carries energy (intact, usable K, model ok),
// in family order: visit(q, Psi). The one loop of strain_energy and bond_energies.
template <int D, class Model, class Visit>
void point_bond_energies(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                         const BondGeometry<D> &geometry, const BondState &state, const double *c33, std::size_t i,
                         Workspace<D> &ws, KernelStats &stats, Visit &&visit)
{
  const std::size_t    W = families.mask_words, o = families.offsets[i], m = families.size(i);
  const std::uint64_t *intact = state.intact_mask(i);
  const PointTotals<D> totals = gather_point<D>(ref, y, families, i, intact, ws.point);
  for (std::size_t q = 0; q < m; ++q) {
    if (!state.is_intact(i, q)) continue;
    const BondKinematics<D> k = bond_kinematics<D>(families.ba(o + q), intact, W, ws.point, totals);
    if (!geometry.is_usable(i, q) || !k.usable) {
      ++stats.unusable;
      continue;
    }
    double c = c33 ? c33[o + q] : 0.0, psi = 0.0;
    ++stats.evaluated;
    const StressStatus status = energy_of<D>(model, k.F, c, psi, 0);
    if (status != StressStatus::ok) {
      stats.record(i, q, status);
      continue;
    }
    visit(q, psi, k.F);
  }
}

// V_i W_i of point i: the mean of Psi over the bonds that carry energy, weighted by V_j;
// with -material_volumetric point the mean of Psi - U(J_iq) + kappa/2 (J_iq - Jbar_i)^2
// plus U(Jbar_i), Jbar_i the same mean of J_iq (volumetric.hpp; the J_iq kept in
// ws.bond_dilatation, 0 for a bond without energy, for the second sum).
template <int D, class Model>
double point_strain_energy(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                           const BondGeometry<D> &geometry, const BondState &state, const double *c33, std::size_t i,
                           Workspace<D> &ws, KernelStats &stats)
{
  const std::size_t o     = families.offsets[i];
  const bool        point = ws.volumetric == Volumetric::point;
  const double      Dc    = point ? compressibility(model, 0) : 0.0;
  const std::size_t m     = families.size(i);
  const double     *d     = state.damage_from(o); // softening: Psi scaled by 1 - d (softening.hpp)
  double            num = 0.0, den = 0.0, dilatation = 0.0;
  if (point) std::fill(ws.bond_dilatation.begin(), ws.bond_dilatation.begin() + m, 0.0);
  point_bond_energies<D>(model, ref, y, families, geometry, state, c33, i, ws, stats,
                         [&](std::size_t q, double psi, const Mat<D> &F) {
                           const double vj = ref.volume[static_cast<std::size_t>(families.neighbour[o + q])];
                           if (point) {
                             const double J = det<D>(F);
                             num += (psi - volumetric_energy(J, Dc)) * vj;
                             dilatation += J * vj;
                             ws.bond_dilatation[q] = J;
                           } else num += (d ? (1.0 - d[q]) * psi : psi) * vj;
                           den += vj;
                         });
  if (!(den > 0)) return 0.0;
  if (!point) return ref.volume[i] * (num / den);
  const double Jbar = dilatation / den, kappa = ws.volumetric_stabilisation;
  double       spread = 0.0;
  for (std::size_t q = 0; q < m; ++q)
    if (ws.bond_dilatation[q] > 0.0) {
      const double d = ws.bond_dilatation[q] - Jbar;
      spread += ref.volume[static_cast<std::size_t>(families.neighbour[o + q])] * d * d;
    }
  return ref.volume[i] * (num / den + 0.5 * kappa * spread / den + volumetric_energy(Jbar, Dc));
}

} // namespace detail

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
  KernelStats local;
  double      total = 0.0;
  for (std::size_t i = 0; i < n_points; ++i) {
    const double e = detail::point_strain_energy<D>(model, ref, y, families, geometry, state, c33, i, ws, local);
    if (point_energy) point_energy[i] = e;
    total += e;
  }
  if (stats) *stats = local;
  return total;
}

// strain_energy's V_i W_i of the listed points only (energy[k] of points[k]): W_i depends
// on the bonds of i alone (its intact mask and usable bits), so the energy a breaking pass
// releases is the change of these terms over the points whose bonds it changed.
template <int D, class Model>
void listed_strain_energies(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                            const BondGeometry<D> &geometry, const BondState &state, const double *c33,
                            const std::size_t *points, std::size_t count, Workspace<D> &ws, double *energy)
{
  ws.reserve(families);
  KernelStats local;
  for (std::size_t k = 0; k < count; ++k)
    energy[k] = detail::point_strain_energy<D>(model, ref, y, families, geometry, state, c33, points[k], ws, local);
}

// Psi(F_iq) of every bond of the points [0, n_points) into psi (one per bond, family
// order), -1 for a bond that carries no energy (broken, K not usable, model failed):
// what the fracture-energy criterion weighs (damage.hpp). c33 (may be nullptr) is read only.
template <int D, class Model>
void bond_energies(const Model &model, const PointCloud &ref, const double *y, const Families &families,
                   const BondGeometry<D> &geometry, const BondState &state, const double *c33, std::size_t n_points,
                   Workspace<D> &ws, double *psi)
{
  ws.reserve(families);
  KernelStats local;
  for (std::size_t i = 0; i < n_points; ++i) {
    const std::size_t o = families.offsets[i];
    for (std::size_t q = 0; q < families.size(i); ++q) psi[o + q] = -1.0;
    detail::point_bond_energies<D>(model, ref, y, families, geometry, state, c33, i, ws, local,
                                   [&](std::size_t q, double value, const Mat<D> &) { psi[o + q] = value; });
  }
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
