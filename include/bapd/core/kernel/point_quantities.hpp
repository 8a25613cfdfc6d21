#pragma once
// Per-point stress, deformation and energy for output (fields.hpp): what Peridigm and
// PeriLab users look for at a material point, formed from the bond-associated
// quantities the force uses (docs/method.md sections 2-3; paper eqs 9, 23).
//
// The bond force is t_ij = w_ij P(F_ij) K_ij^{-1} (x_j - x_i), w_ij = 1/2 phi_xi/phi
// (eq 23), summed with V_j (eq 1): each bond's stress P(F_ij) enters point i's force
// with the weight w_ij V_j. The point's nominal stress is their weighted mean
//   P_i = sum_j a_ij P(F_ij) / sum_j a_ij,   a_ij = 1/2 phi_xi/phi V_j,
// over the bonds that carry force (intact, usable K, model ok), and F_i, lambda_3,i
// are the means of F_ij and sqrt(C33_ij) with the same weights. For the energy-
// consistent form (ba_force.hpp) the weights are those of its energy,
// a_ij = V_j (omega_i V_j). Either way an affine motion (F_ij = A for every bond)
// gives P_i = P(A), F_i = A up to round-off, at the boundary too.
// With a stress correction of the bond-only force (-force_stress_correction,
// stress_correction.hpp; geometry.corrected()) P_i is instead the point's virial
// stress, the quantity the correction is built to make equal P:
//   P_i = sum_j t_ij (x) xi_ij V_j = sum_j P(F_ij) B_ij,   B_ij = V_j (C_i g_ij) (x) xi_ij,
// with g_ij = w_ij K_ij^{-1} xi_ij; sum_j B_ij = C_i M_i = I for the tensor correction,
// so an affine motion again gives P_i = P(A) at every point (and the interior figure
// for the scalar one). With -force_patch_correction C_i g_ij gets the kernel's h_ij
// added (patch_correction.hpp), and sum_j B_ij = I + sum_j h_ij (x) xi_ij V_j: I + a
// few percent at a point with lambda (on), I again with virial (its S_i is solved so
// that sum_j h_ij (x) xi_ij V_j = 0).
// F_i and lambda_3,i keep the scalar weights a_ij.
//   Cauchy stress      sigma_i = P_i F_i^T / J_i,  J_i = det F~_i lambda_3,i
//   energy density     W_i = sum_j Psi(F_ij) V_j / sum_j V_j (strain_energy(),
//                      ba_force.hpp: the internal energy of history.csv is sum V_i W_i)
// D = 2, in-plane components only: the 2D models give P~ (P_33 = sigma_33 = 0 in plane
// stress; in plane strain sigma_33 is not formed). lambda_3 = sqrt(C33) is the
// thickness stretch of a plane-stress sheet (1 in plane strain).
// D = 3: the full 3 x 3 tensors of the 3D law (Compressible3D and
// every other 3D law of the registry: stress(F, P)), sigma_i = P_i F_i^T / det F_i, and
// no thickness stretch (thickness_stretch is left empty: there is no C33 to solve).
// A point none of whose bonds carries force (damage 1, or every K singular) gets zeros
// everywhere.
// With -material_volumetric point (volumetric.hpp; energy-consistent weights) each bond's
// P(F_ij) is the P*_ij the force uses, P + (U'(Jbar_i) - U'(J_ij) + kappa (J_ij - Jbar_i))
// cof F_ij, Jbar_i the mean of J_ij with the same weights, kappa the stabilisation [Pa],
// and W_i that of the point form's energy.
//
// Output only, outside the time step: it uses the slow per-bond path
// (bond_shape, bond_deformation_gradient) and reads c33 as the warm start of the
// model's C33 solve without writing it.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd {

// Which weights average the bond stresses at a point (see above).
enum class StressWeights {
  bond_force, // a_ij = 1/2 phi_xi/phi V_j: the paper's bond-only force (eq 23)
  bond_energy // a_ij = V_j: the energy-consistent force and strain_energy()
};

// Per point, in the order of the points; tensors as D x D numbers, row-major (2D: xx,
// xy, yx, yy; 3D: xx, xy, xz, yx, ..., zz).
struct PointQuantities {
  int                 dimension = 2;         // D of the tensors below
  std::vector<double> nominal_stress;        // P~_i (2D), P_i (3D) [Pa]
  std::vector<double> cauchy_stress;         // sigma_i (2D: in-plane) [Pa]
  std::vector<double> deformation_gradient;  // F~_i (2D), F_i (3D) [-]
  std::vector<double> thickness_stretch;     // lambda_3,i [-] (2D only; empty in 3D)
  std::vector<double> strain_energy_density; // W_i [J/m^3]

  void resize(std::size_t n, int D = 2)
  {
    const std::size_t tensor = static_cast<std::size_t>(D * D);
    dimension                = D;
    nominal_stress.assign(tensor * n, 0.0);
    cauchy_stress.assign(tensor * n, 0.0);
    deformation_gradient.assign(tensor * n, 0.0);
    thickness_stretch.assign(D == 2 ? n : 0, 0.0);
    strain_energy_density.assign(n, 0.0);
  }
};

namespace detail {
// A B with each entry summed from its first term, k = 0, 1 (, 2) in order: for D = 2
// the operations of tensor.hpp's Mat2 product, so the 2D quantities keep their bits.
template <int D> inline nd::Mat<D> product(const nd::Mat<D> &A, const nd::Mat<D> &B)
{
  nd::Mat<D> C;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) {
      double s = A[D * r] * B[c];
      for (int k = 1; k < D; ++k) s = s + A[D * r + k] * B[D * k + c];
      C[D * r + c] = s;
    }
  return C;
}
template <int D> inline nd::Vec<D> product_vector(const nd::Mat<D> &A, const nd::Vec<D> &v)
{
  nd::Vec<D> w;
  for (int r = 0; r < D; ++r) {
    double s = A[D * r] * v[0];
    for (int c = 1; c < D; ++c) s = s + A[D * r + c] * v[c];
    w[r] = s;
  }
  return w;
}
} // namespace detail

// sigma = P F^T / J. D = 2: the in-plane Cauchy stress of a 2D state, J = det F~
// lambda_3 (F = diag(F~, lambda_3), so the in-plane block of P F^T is P~ F~^T); D = 3:
// J = det F (lambda_3 unused). Zero if J <= 0.
template <int D> inline nd::Mat<D> cauchy_stress(const nd::Mat<D> &P, const nd::Mat<D> &F, double lambda_3 = 1.0)
{
  const double J = D == 2 ? nd::det<D>(F) * lambda_3 : nd::det<D>(F);
  if (!(J > 0.0)) return nd::Mat<D>{};
  const nd::Mat<D> PFt = detail::product<D>(P, nd::transpose<D>(F));
  nd::Mat<D>       sigma;
  const double     r = 1.0 / J;
  for (int k = 0; k < D * D; ++k) sigma[k] = r * PFt[k];
  return sigma;
}
inline Mat2 cauchy_stress(const Mat2 &P, const Mat2 &F, double lambda_3) { return cauchy_stress<2>(P, F, lambda_3); }

// The quantities above for points [0, n_points) (every point needs its family:
// owned or ring-1); y: current positions of the local points (D a point), c33: the
// 2D warm start (1 per bond, may be nullptr; 3D models have none and ignore it).
// The model: a 2D formulation (stress(F, c33, P)) at D = 2, a 3D law (stress(F, P)) at
// D = 3 (ba_force.hpp's two signatures).
template <int D, class Model>
void point_quantities(const Model &model, const PointCloud &cloud, const double *y, const Families &families,
                      const nd::BondGeometry<D> &geometry, const BondState &state, const double *c33,
                      std::size_t n_points, StressWeights weights, PointQuantities &out,
                      Volumetric volumetric = Volumetric::bond, double stabilisation = 0.0)
{
  using Mat = nd::Mat<D>;
  out.resize(n_points, D);
  const bool   virial = geometry.corrected() && weights == StressWeights::bond_force;
  const bool   point  = volumetric == Volumetric::point;
  const double Dc     = point ? nd::detail::compressibility(model, 0) : 0.0;
  for (std::size_t i = 0; i < n_points; ++i) {
    Mat       P_sum{}, F_sum{};
    double    lambda_3_sum = 0.0, total = 0.0, slope_bar = 0.0, Jbar = 1.0;
    const Mat C = geometry.correction_of(i);
    if (point) { // U'(Jbar_i), Jbar_i over the bonds that carry force, weights V_j
      double num = 0.0, den = 0.0;
      for (std::size_t q = 0; q < families.size(i); ++q) {
        if (!state.is_intact(i, q) || !geometry.is_usable(i, q)) continue;
        if (!nd::bond_shape<D>(cloud, families, state, i, q).usable) continue;
        const std::size_t b = families.offsets[i] + q;
        const Mat         F = nd::bond_deformation_gradient<D>(cloud, y, families, geometry, state, i, q);
        double            c = c33 ? c33[b] : 0.0;
        Mat               P;
        if (nd::detail::stress_of<D>(model, F, c, P, 0) != StressStatus::ok) continue;
        const double v = cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
        num += v * nd::det<D>(F);
        den += v;
      }
      if (den > 0.0) {
        Jbar      = num / den;
        slope_bar = nd::detail::volumetric_slope(Jbar, Dc);
      }
    }
    for (std::size_t q = 0; q < families.size(i); ++q) {
      if (!state.is_intact(i, q) || !geometry.is_usable(i, q)) continue;
      const nd::BondShape<D> shape = nd::bond_shape<D>(cloud, families, state, i, q);
      if (!shape.usable) continue;
      const std::size_t b = families.offsets[i] + q;
      const Mat         F = nd::bond_deformation_gradient<D>(cloud, y, families, geometry, state, i, q);
      double            c = c33 ? c33[b] : 0.0;
      Mat               P;
      if (nd::detail::stress_of<D>(model, F, c, P, 0) != StressStatus::ok) continue; // the kernel gives it t = 0
      if (point) { // P -> P*
        const Mat    adj = nd::adjugate<D>(F);
        const double J   = nd::det<D>(F);
        const double a   = slope_bar - nd::detail::volumetric_slope(J, Dc) + nd::detail::stabilisation_slope(J, Jbar, stabilisation);
        for (int r = 0; r < D; ++r)
          for (int s = 0; s < D; ++s) P[D * r + s] += a * adj[D * s + r]; // cof F = adj(F)^T
      }
      const double v = cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
      const double a = weights == StressWeights::bond_force ? shape.force_scale * v : v;
      if (virial) { // P B_ij, B_ij = V_j (C_i g_ij) (x) xi_ij
        const std::size_t j = static_cast<std::size_t>(families.neighbour[b]);
        nd::Vec<D>        h = detail::product_vector<D>(C, shape.force_vector);
        nd::Vec<D>        d;
        for (int r = 0; r < D; ++r) d[r] = cloud.x[D * j + r] - cloud.x[D * i + r];
        if (!cloud.patch_correction.empty()) { // h_ij of the kernel (patch_correction.hpp)
          const std::size_t S = nd::patch_stride<D>(cloud.patch_virial);
          nd::add_patch_term<D>(cloud.patch_correction.data() + S * i, cloud.patch_correction.data() + S * j, d.data(),
                                h.data(), cloud.patch_virial);
        }
        Mat B;
        for (int r = 0; r < D; ++r)
          for (int s = 0; s < D; ++s) B[D * r + s] = v * h[r] * d[s];
        const Mat PB = detail::product<D>(P, B);
        for (int k = 0; k < D * D; ++k) P_sum[k] = P_sum[k] + PB[k];
      } else
        for (int k = 0; k < D * D; ++k) P_sum[k] = P_sum[k] + a * P[k];
      for (int k = 0; k < D * D; ++k) F_sum[k] = F_sum[k] + a * F[k];
      if constexpr (D == 2) lambda_3_sum += a * std::sqrt(c);
      total += a;
    }
    if (!(total > 0.0)) continue; // no bond carries force: zeros
    const double r = 1.0 / total;
    Mat          P, F;
    for (int k = 0; k < D * D; ++k) {
      P[k] = virial ? P_sum[k] : r * P_sum[k];
      F[k] = r * F_sum[k];
    }
    const double lambda_3 = D == 2 ? lambda_3_sum / total : 1.0;
    const Mat    sigma    = cauchy_stress<D>(P, F, lambda_3);
    for (int k = 0; k < D * D; ++k) {
      out.nominal_stress[D * D * i + k]       = P[k];
      out.deformation_gradient[D * D * i + k] = F[k];
      out.cauchy_stress[D * D * i + k]        = sigma[k];
    }
    if constexpr (D == 2) out.thickness_stretch[i] = lambda_3;
  }
  nd::Workspace<D> ws;
  ws.volumetric               = volumetric;
  ws.volumetric_stabilisation = stabilisation;
  nd::strain_energy<D>(model, cloud, y, families, geometry, state, c33, n_points, ws, nullptr,
                       out.strain_energy_density.data());
  for (std::size_t i = 0; i < n_points; ++i) out.strain_energy_density[i] /= cloud.volume[i]; // V_i W_i -> W_i
}

// The same for the run-time model: in 2D the law in its formulation (with_model), in 3D
// the law's 3D form (with_model_3d; the formulation is not used). models.hpp.
template <int D>
void point_quantities(ModelKind kind, Formulation formulation, const MaterialParameters &material, const PointCloud &cloud,
                      const double *y, const Families &families, const nd::BondGeometry<D> &geometry, const BondState &state,
                      const double *c33, std::size_t n_points, StressWeights weights, PointQuantities &out,
                      Volumetric volumetric = Volumetric::bond, double stabilisation = 0.0);

} // namespace bapd
