#pragma once
// The affine patch test on irregular points (docs/method.md section 2:
// "the net internal force of an interior point is zero under an affine motion"),
// -force_patch_correction (docs/discretisations.md).
//
// Why it fails without a correction. An affine motion gives F_ij = A on every usable
// bond, so one P for every bond, and the bond-only force (eq 23, with the stress
// correction C_i of stress_correction.hpp) is t_ij = P g_ij, g_ij = C_i w_ij K_ij^{-1}
// xi_ij. The force density is then
//   f_i = sum_j (t_ij - t_ji) V_j = P d_i,   d_i = sum_j (g_ij - g_ji) V_j,
// the discrete divergence of a constant tensor. On a lattice d_i = 0 by symmetry at
// every point whose neighbourhood (two horizons: g_ji reads V(H_j)) is whole; on a
// jittered or graded cloud it is 3-20 % of sum_j (|g_ij| + |g_ji|) V_j and does not
// shrink with refinement (the family's rim takes points in and out irregularly).
//
// The correction. Every bond gets an added force vector along itself,
//   g_ij -> g_ij + h_ij,   h_ij = ((lambda_i - lambda_j) . xi_ij) xi_ij,
// from one vector lambda per point (D doubles: 16 bytes a point in 2D, 24 in 3D). h_ji = -h_ij
// (xi_ji = -xi_ij), so t_ij and t_ji stay an action-reaction pair and linear
// momentum is exact as before; the added force is central, like a bond-based
// spring's. lambda solves, at every interior point i,
//   d_i + sum_j 2 ((lambda_i - lambda_j) . xi_ij) xi_ij V_j = 0,
// which, times V_i, is A lambda = -V_i d_i with A_ii = sum_j 2 V_i V_j xi (x) xi and
// A_ij = -2 V_i V_j xi (x) xi: a graph Laplacian with positive semi-definite tensor
// weights, symmetric. At the boundary layer lambda = 0 (Dirichlet): there f_i = P d_i
// is the traction a free edge needs (the forces a grip holds), which must stay; the
// interior's corrections flow into it, and sum_i V_i f_i = 0 still holds. A is then
// positive definite, solved by conjugate gradients (block-Jacobi preconditioned) to
// round-off, once, on the whole cloud (rank 0 at setup): lambda is a reference
// quantity of the points, shipped with them like V(H), so every rank layout gets the
// same bits.
//
// Which points are interior: those more than one horizon from an edge. An edge point
// is one whose bonds leave an angular gap wider than a right angle (a point of the
// outer row of a straight edge has a gap of about 180 degrees; a notch's faces count,
// as no bond crosses it; in 3D an empty cone of half-angle 45 degrees, looked for among
// 500 directions: patch_correction.cpp, edge_points_3d); the boundary layer is the edge points and every point bonded
// to one, and every point with a bond whose K is not usable either way (its force
// vector is 0, not g). Why one horizon and not the two that d_i reaches:
// patch_correction.cpp (boundary_layer).
//
// What it does not do (-force_patch_correction on): the tensor correction's virial
// sum_j t_ij (x) xi_ij V_j = P is perturbed by sum_j h_ij (x) xi_ij V_j (0.3-1 % on
// average over a cloud, up to 14 % at a point; docs/discretisations.md;
// compute_virial_patch_correction below, -force_patch_correction virial, keeps both);
// the energy-consistent form is not corrected (its
// forces are a gradient: a correction would have to be an energy's). On the lattice the
// correction is off (its interior passes by symmetry), so lattice runs are bit for bit
// what they were.
#include <cstddef>
#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/stress_correction.hpp"

namespace bapd {

// h_ij added to g_ij: lambda_i, lambda_j (2 each), xi = (d0, d1). The kernel and the
// solve below use this one function, so they agree.
inline void add_patch_term(const double *lambda_i, const double *lambda_j, double d0, double d1, double &g0,
                           double &g1)
{
  const double s = (lambda_i[0] - lambda_j[0]) * d0 + (lambda_i[1] - lambda_j[1]) * d1;
  g0 += s * d0;
  g1 += s * d1;
}

struct PatchCorrectionReport {
  std::size_t interior   = 0; // points with d_i = 0 imposed
  std::size_t iterations = 0; // conjugate-gradient iterations
  double      before     = 0; // largest interior |d_i| / sum_j (|g_ij| + |g_ji|) V_j without the correction
  double      after      = 0; // the same with it (lambda, or c_ij of the virial-keeping solve)
  double      virial     = 0; // largest |sum_j h_ij (x) xi_ij V_j| / |sum_j g_ij (x) xi_ij V_j| over all points
  double      term       = 0; // largest |h_ij| / |g_ij| over the bonds that carry force
  double      residual   = 0; // the conjugate gradients' final ||r|| / ||b||
};

// The report as the run's set-up prints it (two lines; simulation.cpp BuildBody).
std::string describe_patch_correction(const PatchCorrectionReport &report, bool virial);

// lambda, D per point (0 in the boundary layer), for the bond-only force with the
// stress correction `stress_correction` (as compute_bond_geometry forms C_i) on a cloud
// of D = 2 or 3 dimensions (D coordinates a point). Needs families of every point of
// the cloud (n_family = cloud.size(), no ghosts) and cloud.family_volume. Throws
// std::invalid_argument if the families are not the whole cloud's, std::runtime_error
// if the solve does not reach round-off. One template for both D (instantiated for 2
// and 3 in patch_correction.cpp); D = 2 is the 2D solve of before, bit for bit.
template <int D>
std::vector<double> compute_patch_correction(const PointCloud &cloud, const Families &families,
                                             StressCorrection stress_correction, PatchCorrectionReport *report = nullptr);
inline std::vector<double> compute_patch_correction(const PointCloud &cloud, const Families &families,
                                                    StressCorrection stress_correction, PatchCorrectionReport *report = nullptr)
{
  return compute_patch_correction<2>(cloud, families, stress_correction, report);
}

// ---------------------------------------------------------------------------------
// The patch test AND the virial (docs/discretisations.md "Keeping the virial"):
// -force_patch_correction virial (the default for given points with the
// bond-only form). The setup solve is here; the kernel forms c_ij from the points'
// numbers (nd::add_patch_term with virial, ba_force.hpp; PointCloud::patch_virial),
// tested outside the kernel (tests/unit/geometry_test.cpp,
// NonUniformPatch.VirialPatchCorrection*) and through the driver
// (tests/mpi/patch_correction_driver_test.cpp).
//
// Unknown: one central term per usable bond, h_ij = c_ij xi_ij (8 bytes a bond if it
// were stored), c_ji independent of c_ij. Constraints, under an affine motion (one P):
//   patch, every interior point (D):  d_i + sum_j (c_ij + c_ji) xi_ij V_j = 0
//     (h_ij - h_ji = (c_ij + c_ji) xi_ij);
//   virial, every point (D(D+1)/2: 3, 6 in 3D; central terms have no skew part):
//     sum_j c_ij xi_ij (x) xi_ij V_j = 0,
//   so that sum_j t_ij (x) xi_ij V_j keeps its value (P with the tensor correction).
// The minimum of sum_ij V_i V_j c_ij^2 under these (a least-change solution) is, by
// the Lagrange conditions, in the span of the constraint rows:
//   c_ij = (mu_i - mu_j) . xi_ij + xi_ij . S_i xi_ij,
// with mu_i (2, 0 in the boundary layer) the patch multipliers and S_i (3, symmetric)
// the virial multipliers. So the per-bond correction needs 5 numbers a point (9 in 3D),
// not a number a bond (40 B a point against ~8 x 27 = 216 B; 3D 72 B against ~8 x 120),
// and the kernel forms one
// term per bond: s = c_ij; g_ij += s xi_ij, with y_j a ring-1 ghost's mu (shipped
// with the points at setup, as lambda: layout.cpp). (mu, S) solve A y = r,
// A = B W^-1 B^T (5 x 5 blocks on the bond graph, 3 x 3 in the layer; 9 x 9 and 6 x 6
// in 3D), symmetric
// positive definite when B has full row rank: an affine mu with S = sym grad mu makes
// every c_ij = 0 (the null space of B^T), and mu = 0 in the layer removes it.
inline constexpr std::size_t kVirialPatchStride = 5; // mu0, mu1, S00, S01, S11 (nd::patch_stride<2>(true))

inline double virial_patch_coefficient(const double *y_i, const double *y_j, double d0, double d1)
{
  return (y_i[0] - y_j[0]) * d0 + (y_i[1] - y_j[1]) * d1 + y_i[2] * d0 * d0 + 2.0 * y_i[3] * d0 * d1 + y_i[4] * d1 * d1;
}

// (mu, S), nd::patch_stride<D>(true) per point (5 in 2D, 9 in 3D: mu, then S's upper
// triangle by nd::sym_index), for the bond-only force with `stress_correction`; the
// same preconditions and errors as compute_patch_correction. report->after is the
// largest interior patch defect and report->virial the largest virial change, with c_ij.
template <int D>
std::vector<double> compute_virial_patch_correction(const PointCloud &cloud, const Families &families,
                                                    StressCorrection          stress_correction,
                                                    PatchCorrectionReport    *report = nullptr);
inline std::vector<double> compute_virial_patch_correction(const PointCloud &cloud, const Families &families,
                                                           StressCorrection       stress_correction,
                                                           PatchCorrectionReport *report = nullptr)
{
  return compute_virial_patch_correction<2>(cloud, families, stress_correction, report);
}

} // namespace bapd
