#pragma once
// Per-point stress, deformation and energy for output (fields.hpp): what Peridigm and
// PeriLab users look for at a material point, formed from the bond-associated
// quantities the force uses (METHOD.md sections 2-3; paper eqs 9, 23).
//
// The bond force is t_ij = w_ij P(F_ij) K_ij^{-1} (x_j - x_i), w_ij = 1/2 phi_xi/phi
// (eq 23), summed with V_j (eq 1): each bond's stress P(F_ij) enters point i's force
// with the weight w_ij V_j. The point's nominal stress is their weighted mean
//   P_i = sum_j a_ij P(F_ij) / sum_j a_ij,   a_ij = 1/2 phi_xi/phi V_j,
// over the bonds that carry force (intact, usable K, model ok), and F_i, lambda_3,i
// are the means of F_ij and sqrt(C33_ij) with the same weights. For the energy-
// consistent form (nd/ba_force.hpp) the weights are those of its energy,
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
//                      nd/ba_force.hpp: the internal energy of history.csv is sum V_i W_i)
// In-plane components only: the 2D models give P~ (P_33 = sigma_33 = 0 in plane
// stress; in plane strain sigma_33 is not formed). lambda_3 = sqrt(C33) is the
// thickness stretch of a plane-stress sheet (1 in plane strain). A point none of
// whose bonds carries force (damage 1, or every K singular) gets zeros everywhere.
//
// Output only, outside the time step: it uses the slow per-bond path
// (bond_shape, bond_deformation_gradient) and reads c33 as the warm start of the
// model's C33 solve without writing it.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/material.hpp"
#include "bapd/nd/ba_force.hpp"
#include "bapd/tensor.hpp"

namespace bapd {

// Which weights average the bond stresses at a point (see above).
enum class StressWeights {
  bond_force, // a_ij = 1/2 phi_xi/phi V_j: the paper's bond-only force (eq 23)
  bond_energy // a_ij = V_j: the energy-consistent force and strain_energy()
};

// Per point, in the order of the points; tensors as 4 numbers (xx, xy, yx, yy).
struct PointQuantities {
  std::vector<double> nominal_stress;        // P~_i [Pa]
  std::vector<double> cauchy_stress;         // sigma_i (in-plane) [Pa]
  std::vector<double> deformation_gradient;  // F~_i [-]
  std::vector<double> thickness_stretch;     // lambda_3,i [-]
  std::vector<double> strain_energy_density; // W_i [J/m^3]

  void resize(std::size_t n)
  {
    nominal_stress.assign(4 * n, 0.0);
    cauchy_stress.assign(4 * n, 0.0);
    deformation_gradient.assign(4 * n, 0.0);
    thickness_stretch.assign(n, 0.0);
    strain_energy_density.assign(n, 0.0);
  }
};

// sigma = P F^T / J, J = det F~ lambda_3: the in-plane Cauchy stress of a 2D state
// (F = diag(F~, lambda_3), so the in-plane block of P F^T is P~ F~^T). Zero if J <= 0.
inline Mat2 cauchy_stress(const Mat2 &P, const Mat2 &F, double lambda_3)
{
  const double J = det(F) * lambda_3;
  if (!(J > 0.0)) return {0.0, 0.0, 0.0, 0.0};
  return (1.0 / J) * (P * transpose(F));
}

// The quantities above for points [0, n_points) (every point needs its family:
// owned or ring-1); y: current positions of the local points, c33: the warm start
// (1 per bond, may be nullptr).
template <class Model>
void point_quantities(const Model &model, const PointCloud &cloud, const double *y, const Families &families,
                      const nd::BondGeometry<2> &geometry, const BondState &state, const double *c33,
                      std::size_t n_points, StressWeights weights, PointQuantities &out)
{
  out.resize(n_points);
  const bool virial = geometry.corrected() && weights == StressWeights::bond_force;
  for (std::size_t i = 0; i < n_points; ++i) {
    Mat2       P_sum = {0.0, 0.0, 0.0, 0.0}, F_sum = {0.0, 0.0, 0.0, 0.0};
    double     lambda_3_sum = 0.0, total = 0.0;
    const Mat2 C = geometry.correction_of(i);
    for (std::size_t q = 0; q < families.size(i); ++q) {
      if (!state.is_intact(i, q) || !geometry.is_usable(i, q)) continue;
      const nd::BondShape<2> shape = nd::bond_shape<2>(cloud, families, state, i, q);
      if (!shape.usable) continue;
      const std::size_t b = families.offsets[i] + q;
      const Mat2        F = nd::bond_deformation_gradient<2>(cloud, y, families, geometry, state, i, q);
      double            c = c33 ? c33[b] : 0.0;
      Mat2              P;
      if (model.stress(F, c, P) != StressStatus::ok) continue; // the kernel gives it t = 0
      const double v = cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
      const double a = weights == StressWeights::bond_force ? shape.force_scale * v : v;
      if (virial) { // P B_ij, B_ij = V_j (C_i g_ij) (x) xi_ij
        const std::size_t j  = static_cast<std::size_t>(families.neighbour[b]);
        Vec2              h  = C * shape.force_vector;
        const double      d0 = cloud.x[2 * j] - cloud.x[2 * i], d1 = cloud.x[2 * j + 1] - cloud.x[2 * i + 1];
        if (!cloud.patch_correction.empty()) { // h_ij of the kernel (patch_correction.hpp)
          const std::size_t S = nd::patch_stride<2>(cloud.patch_virial);
          nd::add_patch_term<2>(cloud.patch_correction.data() + S * i, cloud.patch_correction.data() + S * j,
                                std::array<double, 2>{d0, d1}.data(), h.data(), cloud.patch_virial);
        }
        P_sum                = P_sum + P * Mat2{v * h[0] * d0, v * h[0] * d1, v * h[1] * d0, v * h[1] * d1};
      } else P_sum = P_sum + a * P;
      F_sum          = F_sum + a * F;
      lambda_3_sum += a * std::sqrt(c);
      total += a;
    }
    if (!(total > 0.0)) continue; // no bond carries force: zeros
    const Mat2   P        = virial ? P_sum : (1.0 / total) * P_sum;
    const Mat2   F        = (1.0 / total) * F_sum;
    const double lambda_3 = lambda_3_sum / total;
    const Mat2   sigma    = cauchy_stress(P, F, lambda_3);
    for (int c = 0; c < 4; ++c) {
      out.nominal_stress[4 * i + c]       = P[c];
      out.deformation_gradient[4 * i + c] = F[c];
      out.cauchy_stress[4 * i + c]        = sigma[c];
    }
    out.thickness_stretch[i] = lambda_3;
  }
  nd::Workspace<2> ws;
  nd::strain_energy<2>(model, cloud, y, families, geometry, state, c33, n_points, ws, nullptr,
                       out.strain_energy_density.data());
  for (std::size_t i = 0; i < n_points; ++i) out.strain_energy_density[i] /= cloud.volume[i]; // V_i W_i -> W_i
}

// The same for the run-time model (with_model, models.hpp).
void point_quantities(ModelKind kind, Formulation formulation, const MaterialParameters &material,
                      const PointCloud &cloud, const double *y, const Families &families,
                      const nd::BondGeometry<2> &geometry,
                      const BondState &state, const double *c33, std::size_t n_points, StressWeights weights,
                      PointQuantities &out);

} // namespace bapd
