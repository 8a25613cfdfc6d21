#pragma once
// The tangent of the energy-consistent force (docs/method.md sections 3 and 8): the
// Hessian of one point's share of the stored energy with respect to the positions of the
// point and its family, the block the static solver adds into its stiffness matrix.
//
// W = sum_i W_i with (section 3)
//   W_i = V_i omega_i sum_q V_q Psi(F_iq),   omega_i = 1 / sum_q V_q,
// over the bonds of i that carry energy, and F_iq is linear in the positions (eq 9):
//   F_iq = sum_{p in B} (y_p - y_i) (x) g_p,   g_p = K_iq^{-1} (x_p - x_i) V_p,
// B the intact members of B_iq. With a_p = g_p for p in B and a_i = -sum_p g_p,
// dF_iq / dy_a = e_r (x) a_a, so
//   d^2 W_i / dy_a,r dy_b,s = V_i omega_i sum_q V_q sum_{m,n} A_q[r m][s n] a_a[m] a_b[n],
// A_q = dP/dF at F_iq (the law's tangent; plane stress: of the reduced law, C33 solved
// at every F, eq 33): the law's exact one where it has it (PlaneStress::tangent, a law of
// I1bar only: Gent, neo-Hookean), else central differences of the law's P
// (numerical_tangent.hpp's step, 1e-4 of max(1, |F|): about 1e-8 relative).
//
// The pair loop: per bond, the points of B_iq (and i) are listed once, T_a = V_q A a_a
// formed once for each, and only the blocks with b >= a summed (H is symmetric: the
// lower blocks are mirrored at the end).
//
// -material_volumetric point (section 8, volumetric.hpp): W_i's bond terms use P*_iq,
// which depends on F_iq and on Jbar_i = omega_i sum_q V_q J_iq. Differentiating the
// gradient V_i omega_i sum_q V_q P*_iq : dF_iq gives A_q = dP*/dF at fixed Jbar_i (the same
// central differences, of P*) plus, from dP*/dJbar = (U''(Jbar) - kappa) cof F_iq,
//   V_i (U''(Jbar_i) - kappa) v (x) v,   v = dJbar_i/dy = omega_i sum_q V_q cof F_iq : dF_iq/dy,
// one dense rank-one block per point. U''(J) = (1 + 1/J^2) / D.
//
// The energetic set (intact, K usable, law ok at F_iq) is held fixed: a bond whose law
// fails at F_iq carries no energy and no tangent, as in the force.
//
// Local numbering of the block: 0 = point i, 1 + p = the p-th member of i's family;
// D rows a point. H is (m + 1) D square, row-major, m = family size.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "bapd/core/kernel/ba_model_lanes.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/volumetric.hpp"

namespace bapd::nd {

// Scratch of point_tangent, sized once for the largest family.
template <int D> struct TangentWorkspace {
  PointScratch<D>     point;
  std::vector<double> H;        // (m + 1) D square
  std::vector<double> a;        // a_k, D per point of the current bond (k = 0: i)
  std::vector<double> T;        // V_q sum_m A[r m][s n] a_k[m], D^3 per point of the current bond
  std::vector<double> v;        // dJbar/dy, D per local point
  std::vector<int>    energetic; // per bond: 1 if it carries energy
  std::vector<double> dilatation; // J_iq per bond
  std::vector<Mat<D>> deformation; // F_iq per bond
  std::vector<double> kinv;     // K_iq^{-1} upper triangle per bond
  std::vector<double> c33;      // C33 solved at F_iq per bond (plane stress: the tangent's warm start)
  std::vector<double> law_A;    // the law's exact dP/dF per bond, D^4 (where it has one)
  std::vector<std::size_t> local; // the current bond's points: i (0), then the members of B_iq (1 + p)
  bool                law_tangent = true; // the law's exact dP/dF where it has one (false: central differences)
  Volumetric          volumetric = Volumetric::bond;
  double              kappa      = 0.0; // kappa [Pa] (-material_volumetric_stabilisation times mu)

  void reserve(const Families &f)
  {
    point.reserve(f);
    const std::size_t n = f.max_family_size + 1;
    if (H.size() < n * n * D * D) H.resize(n * n * D * D);
    if (a.size() < n * D) {
      a.resize(n * D);
      T.resize(n * D * D * D);
      v.resize(n * D);
    }
    if (energetic.size() < f.max_family_size) {
      energetic.resize(f.max_family_size);
      dilatation.resize(f.max_family_size);
      deformation.resize(f.max_family_size);
      kinv.resize(f.max_family_size * sym_size<D>);
      c33.resize(f.max_family_size);
      law_A.resize(f.max_family_size * D * D * D * D);
      local.resize(f.max_family_size + 1);
    }
  }
};

namespace detail {

// cof F = adj(F)^T = J F^{-T}.
template <int D> inline Mat<D> cofactor_of(const Mat<D> &F) { return transpose<D>(adjugate<D>(F)); }

// P (or P* of the point form at fixed Jbar) at F; c33 is the warm start (copied).
template <int D, class Model>
inline StressStatus tangent_stress(const Model &model, const Mat<D> &F, double c33, bool point, double Jbar,
                                   double compressibility, double kappa, Mat<D> &P)
{
  const StressStatus s = stress_of<D>(model, F, c33, P, 0);
  if (s != StressStatus::ok || !point) return s;
  const double J = det<D>(F);
  const double f = volumetric_slope(Jbar, compressibility) - volumetric_slope(J, compressibility) + stabilisation_slope(J, Jbar, kappa);
  const Mat<D> cof = cofactor_of<D>(F);
  for (int k = 0; k < D * D; ++k) P[k] += f * cof[k];
  return StressStatus::ok;
}

// Whether the model has an exact dP/dF (PlaneStress::tangent).
template <class Model, class = void> struct has_law_tangent : std::false_type {};
template <class Model> struct has_law_tangent<Model, std::enable_if_t<Model::has_tangent>> : std::true_type {};

// A[(D r + m) D^2 + (D s + n)] = dP_rm / dF_sn: the law's own (exact) where it has one and
// law_tangent is set, else by central differences (numerical_tangent.hpp's step).
template <int D, class Model>
inline StressStatus tangent_of(const Model &model, const Mat<D> &F, double c33, bool point, double Jbar,
                               double compressibility, double kappa, bool law_tangent, double *A)
{
  if constexpr (D == 2 && has_law_tangent<Model>::value) {
    if (law_tangent && !point) {
      std::array<double, 16> exact;
      const StressStatus     s = model.tangent(F, c33, exact);
      std::copy(exact.begin(), exact.end(), A);
      return s;
    }
  }
  double scale = 1.0;
  for (double f : F) scale = std::max(scale, std::abs(f));
  const double h = 1e-4 * scale;
  for (int kl = 0; kl < D * D; ++kl) {
    Mat<D> Fp = F, Fm = F, Pp, Pm;
    Fp[kl] += h;
    Fm[kl] -= h;
    StressStatus s = tangent_stress<D>(model, Fp, c33, point, Jbar, compressibility, kappa, Pp);
    if (s != StressStatus::ok) return s;
    if ((s = tangent_stress<D>(model, Fm, c33, point, Jbar, compressibility, kappa, Pm)) != StressStatus::ok) return s;
    const double step = Fp[kl] - Fm[kl];
    for (int ij = 0; ij < D * D; ++ij) A[D * D * ij + kl] = (Pp[ij] - Pm[ij]) / step;
  }
  return StressStatus::ok;
}

} // namespace detail

namespace detail {

// The sums of pass 1 over the bonds that carry energy: sum_q V_q (1 / omega_i) and
// sum_q V_q J_iq (Jbar_i / omega_i, point form only).
struct EnergeticSums {
  double volume = 0.0, dilatation = 0.0;
};

// Pass 1: which bonds of i carry energy (intact, K usable, law ok at F_iq), with their
// F, K^{-1}, C33, J (point form) and, for a law with an exact tangent (exact), its dP/dF.
template <int D, class Model>
EnergeticSums energetic_bonds(const Model &model, const Families &fam, const BondGeometry<D> &geo, const BondState &state,
                              const double *c33, std::size_t i, const PointTotals<D> &totals, bool exact, bool point,
                              TangentWorkspace<D> &ws)
{
  constexpr int        DD = D * D;
  const std::size_t    o = fam.offsets[i], m = fam.size(i), W = fam.mask_words;
  const std::uint64_t *intact = state.intact_mask(i);
  EnergeticSums        sums;
  for (std::size_t q = 0; q < m; ++q) {
    ws.energetic[q] = 0;
    if (!state.is_intact(i, q) || !geo.is_usable(i, q)) continue;
    const BondKinematics<D> k = bond_kinematics<D>(fam.ba(o + q), intact, W, ws.point, totals);
    if (!k.usable) continue;
    double c = c33 ? c33[o + q] : 0.0;
    if (exact) { // the law's tangent decides (its C33 solve is the stress's) and is kept
      if (tangent_of<D>(model, k.F, c, false, 1.0, 0.0, 0.0, true, &ws.law_A[DD * DD * q]) != StressStatus::ok) continue;
    } else {
      Mat<D> P;
      if (stress_of<D>(model, k.F, c, P, 0) != StressStatus::ok) continue;
    }
    ws.energetic[q]   = 1;
    ws.deformation[q] = k.F;
    ws.c33[q]         = c;
    for (int s = 0; s < sym_size<D>; ++s) ws.kinv[sym_size<D> * q + s] = k.shape_tensor_inv[s];
    const double vq = ws.point.member[q][Member<D>::volume];
    sums.volume += vq;
    if (point) {
      ws.dilatation[q] = det<D>(k.F);
      sums.dilatation += vq * ws.dilatation[q];
    }
  }
  return sums;
}

// The points of bond q: i (local 0), then the intact members p of B_iq (local 1 + p, by
// a sweep over the mask words, increasing), with a_p = K^{-1} (x_p - x_i) V_p and
// a_i = -sum_p a_p side by side in ws.a; returns their number.
template <int D>
std::size_t bond_points(const Families &fam, std::size_t i, std::size_t q, const std::uint64_t *intact, TangentWorkspace<D> &ws)
{
  const std::uint64_t *ba    = fam.ba(fam.offsets[i] + q);
  const double        *kinv  = &ws.kinv[sym_size<D> * q];
  std::size_t         *local = ws.local.data();
  double              *g     = ws.a.data();
  std::size_t          nb    = 1;
  double               ai[D] = {};
  local[0]                   = 0;
  for (std::size_t w = 0; w < fam.mask_words; ++w) {
    std::uint64_t bits = ba[w] & intact[w];
    while (bits) {
      const std::size_t p = 64 * w + static_cast<std::size_t>(__builtin_ctzll(bits));
      bits &= bits - 1;
      const double *d  = &ws.point.offset[D * p];
      const double  vp = ws.point.member[p][Member<D>::volume];
      for (int r = 0; r < D; ++r) {
        double t = 0.0;
        for (int c2 = 0; c2 < D; ++c2) t += kinv[sym_index<D>(r, c2)] * d[c2];
        g[D * nb + r] = t * vp;
        ai[r] -= t * vp;
      }
      local[nb++] = 1 + p;
    }
  }
  for (int r = 0; r < D; ++r) g[r] = ai[r];
  return nb;
}

// Bond q's blocks into the upper blocks of ws.H (N columns): T_k[r][s][n] = vq sum_m
// A[r m][s n] a_k[m], then H_ab[r][s] += sum_n T_a[r][s][n] a_b[n] over the pairs with
// b >= a (ws.local is increasing).
template <int D> void add_bond_blocks(const double *A, double vq, std::size_t nb, std::size_t N, TangentWorkspace<D> &ws)
{
  constexpr int      DD    = D * D;
  const std::size_t *local = ws.local.data();
  const double      *g     = ws.a.data();
  for (std::size_t k = 0; k < nb; ++k) {
    const double *gk = &g[D * k];
    double       *T  = &ws.T[DD * D * k];
    for (int r = 0; r < D; ++r)
      for (int s2 = 0; s2 < D; ++s2)
        for (int nn = 0; nn < D; ++nn) {
          double t = 0.0;
          for (int mm = 0; mm < D; ++mm) t += A[DD * (D * r + mm) + D * s2 + nn] * gk[mm];
          T[DD * r + D * s2 + nn] = vq * t;
        }
  }
  for (std::size_t k1 = 0; k1 < nb; ++k1) {
    double Tk[DD * D];
    for (int e = 0; e < DD * D; ++e) Tk[e] = ws.T[DD * D * k1 + e];
    double *row = &ws.H[D * local[k1] * N];
    for (std::size_t k2 = k1; k2 < nb; ++k2) {
      const double *gb  = &g[D * k2];
      double       *out = row + D * local[k2];
      for (int r = 0; r < D; ++r)
        for (int s2 = 0; s2 < D; ++s2) {
          double h = 0.0;
          for (int nn = 0; nn < D; ++nn) h += Tk[DD * r + D * s2 + nn] * gb[nn];
          out[r * N + s2] += h;
        }
    }
  }
}

// Point form: v += V_q cof F_iq : dF_iq/dy over the bond's points (omega_i applied later).
template <int D> void add_dilatation_gradient(const Mat<D> &F, double vq, std::size_t nb, TangentWorkspace<D> &ws)
{
  const Mat<D>  cof = cofactor_of<D>(F);
  const double *g   = ws.a.data();
  for (std::size_t k = 0; k < nb; ++k) {
    const double *gk = &g[D * k];
    for (int r = 0; r < D; ++r) {
      double t = 0.0;
      for (int nn = 0; nn < D; ++nn) t += cof[D * r + nn] * gk[nn];
      ws.v[D * ws.local[k] + r] += vq * t;
    }
  }
}

// H scaled by V_i omega_i, its lower blocks mirrored from the upper; the point form's
// rank-one block V_i (U''(Jbar_i) - kappa) v (x) v added (with v's omega_i).
template <int D>
void finish_tangent(double Vi, double omega, double Jbar, double compressibility, bool point, std::size_t N, TangentWorkspace<D> &ws)
{
  const double scale = Vi * omega;
  for (std::size_t r = 0; r < N; ++r) {
    for (std::size_t c = D * (r / D + 1); c < N; ++c) ws.H[c * N + r] = ws.H[r * N + c] *= scale; // lower blocks from the upper
    for (std::size_t c = D * (r / D); c < D * (r / D + 1); ++c) ws.H[r * N + c] *= scale;            // the diagonal block
  }
  if (!point) return;
  const double curvature = (1.0 + 1.0 / (Jbar * Jbar)) / compressibility - ws.kappa; // U''(Jbar) - kappa
  const double f         = Vi * curvature * omega * omega;
  for (std::size_t r = 0; r < N; ++r) {
    const double vr = f * ws.v[r];
    if (vr == 0.0) continue;
    for (std::size_t c = 0; c < N; ++c) ws.H[r * N + c] += vr * ws.v[c];
  }
}

} // namespace detail

// The Hessian of W_i (above) into ws.H, (m + 1) D square; returns the number of
// bonds whose law failed at a perturbed F (their tangent left out: the caller reports
// it). y: current positions of every local point; c33 the plane-stress warm starts (1
// per bond, may be nullptr), only read.
template <int D, class Model>
std::size_t point_tangent(const Model &model, const PointCloud &ref, const double *y, const Families &fam,
                          const BondGeometry<D> &geo, const BondState &state, const double *c33, std::size_t i,
                          TangentWorkspace<D> &ws)
{
  constexpr int        DD = D * D;
  const std::size_t    m = fam.size(i), N = (m + 1) * D;
  const std::uint64_t *intact = state.intact_mask(i);
  const PointTotals<D> totals = gather_point<D>(ref, y, fam, i, intact, ws.point);
  const bool           point  = ws.volumetric == Volumetric::point;
  // The law's exact tangent, formed in the first pass (one C33 solve a bond).
  const bool   exact = detail::has_law_tangent<Model>::value && D == 2 && ws.law_tangent && !point;
  const double Dc    = point ? detail::compressibility(model, 0) : 0.0;
  std::fill(ws.H.begin(), ws.H.begin() + N * N, 0.0);
  const detail::EnergeticSums sums = detail::energetic_bonds<D>(model, fam, geo, state, c33, i, totals, exact, point, ws);
  if (!(sums.volume > 0.0)) return 0;
  const double omega = 1.0 / sums.volume, Jbar = point ? sums.dilatation * omega : 1.0;
  if (point) std::fill(ws.v.begin(), ws.v.begin() + N, 0.0);
  std::size_t failed = 0;
  double      A[DD * DD];
  for (std::size_t q = 0; q < m; ++q) {
    if (!ws.energetic[q]) continue;
    if (exact) std::copy_n(&ws.law_A[DD * DD * q], DD * DD, A);
    else if (detail::tangent_of<D>(model, ws.deformation[q], ws.c33[q], point, Jbar, Dc, ws.kappa, ws.law_tangent, A) !=
             StressStatus::ok) {
      ++failed;
      continue;
    }
    const std::size_t nb = detail::bond_points<D>(fam, i, q, intact, ws);
    const double      vq = ws.point.member[q][Member<D>::volume];
    detail::add_bond_blocks<D>(A, vq, nb, N, ws);
    if (point) detail::add_dilatation_gradient<D>(ws.deformation[q], vq, nb, ws);
  }
  detail::finish_tangent<D>(ref.volume[i], omega, Jbar, Dc, point, N, ws);
  return failed;
}

} // namespace bapd::nd
