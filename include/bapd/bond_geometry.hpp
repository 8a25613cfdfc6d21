#pragma once
// Bond-associated kinematics of one bond (paper eqs 8, 9, 11, 15, 23; METHOD.md 2-3).
//
// Per intact bond b = (i -> j), with B = the intact members of the BA family B_ij:
//   K_ij          = sum_{k in B} (x_k - x_i) (x) (x_k - x_i) V_k               (eq 8)
//   F_ij          = [ sum_{k in B} (y_k - y_i) (x) (x_k - x_i) V_k ] K_ij^{-1}  (eq 9)
//   phi_xi(i, j)  = V(B) / V(H_i)                                              (eq 15)
//   phi(i, j)     = V(H_i) / (V(H_i) + V(H_j))                                 (eq 11)
//   force_scale   = 1/2 phi_xi / phi,   g_ij = force_scale K_ij^{-1} (x_j - x_i),
//   t_ij          = gamma P(F_ij) g_ij                                         (eq 23)
// gamma (eq 7) is the intact bit of BondState.
//
// How it is computed. For a point i, every family member k gets two 4-vectors, formed
// once and reused by all of i's bonds (PointScratch):
//   deformation_k = (y_k - y_i) (x) (x_k - x_i) V_k        (xx, xy, yx, yy)
//   shape_k       = ((x_k - x_i) (x) (x_k - x_i) V_k, V_k)  (xx, xy, yy, V)
// A bond's two sums are one masked sum of both (BA mask AND intact mask) in family
// order: its N, K and V(B) together. K^{-1} and force_scale are therefore formed per
// bond per evaluation, not stored: storing them (32 bytes a bond) would cost 0.9 KB
// per point at delta = 3.015 dx against a memory target of 2 KB per point (2.1 KB
// stored, 1.2 KB formed), while forming them costs ~6 ns a bond (a second add per
// member in the loop that runs anyway, and one division; measured 12 -> 18 ns per
// bond for the kernel alone, 85 -> 94 ns with Gent plane stress, bench/). It also
// means that a broken bond changes K at once, with nothing to go stale. The kernel
// and the checks here use the same inline code, so they agree bit for bit.
//
// Usable K: K_ij is symmetric positive semi-definite; with eigenvalues l1 >= l2,
//   det K / (tr K)^2 = l1 l2 / (l1 + l2)^2 ~ l2 / l1 = 1 / cond(K).
// A bond is usable iff det K > shape_tensor_degeneracy (tr K)^2. On a lattice, K in
// units of V dx^2 has integer entries, so a non-degenerate K has det >= 1 while
// (tr K)^2 < 1e6 even for delta = 5 dx: its ratio is >= 1e-6. A degenerate one
// (collinear members, a lone member) has ratio 0 up to round-off, ~1e-16. The
// threshold 1e-8 sits between the two with two orders of margin on both sides, and
// a usable K loses at most cond(K) eps < 1e-8 relative accuracy in F. A bond that
// is not usable carries no force (the kernel writes t_ij = 0 and counts it).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/stress_correction.hpp"
#include "bapd/tensor.hpp"

namespace bapd {

inline constexpr double shape_tensor_degeneracy = 1e-8;


// Four doubles in one SIMD register (GCC/Clang vector extension), added with one
// instruction.
typedef double Double4 __attribute__((vector_size(32)));
struct alignas(32) Quad {
  Double4 v;
};

// Per-member data of one point i, formed once and reused by all of i's bonds.
struct PointScratch {
  std::vector<Quad>   deformation;   // (y_k - y_i) (x) (x_k - x_i) V_k, row-major
  std::vector<Quad>   shape;         // (x_k - x_i) (x) (x_k - x_i) V_k as xx, xy, yy; then V_k
  std::vector<double> offset;        // x_k - x_i, 2 per member
  std::vector<double> family_volume; // V(H_k)

  void reserve(std::size_t max_family_size)
  {
    if (deformation.size() >= max_family_size) return;
    deformation.resize(max_family_size);
    shape.resize(max_family_size);
    offset.resize(2 * max_family_size);
    family_volume.resize(max_family_size);
  }
};

// Per-point values that every bond of the point uses (kept in registers by the kernel).
struct PointTotals {
  Double4 deformation;                        // sum of deformation_k over the intact members, in order
  Double4 shape;                              // sum of shape_k over the intact members, in order
  double  family_volume;                      // V(H_i)
  double  half_inverse_family_volume_squared; // 1 / (2 V(H_i)^2)
};

// What one bond needs, from the masked sums.
struct BondKinematics {
  Mat2   F;                   // eq 9
  double shape_tensor_inv[3]; // K^{-1}: xx, xy, yy
  double volume;              // V(B): intact volume of the BA family
  bool   usable;              // K regular (if not, nothing else is set)
};

namespace detail {

// Fills the scratch for point i and returns its totals. Words: mask words known at
// compile time (1: up to 64 neighbours) or 0 (run-time count).
template <std::size_t Words>
inline PointTotals gather_point(const PointCloud &ref, const double *y, const Families &fam, std::size_t i,
                         const std::uint64_t *intact, PointScratch &s)
{
  const std::size_t   o = fam.offsets[i], m = fam.offsets[i + 1] - o;
  const double       *x = ref.x.data(), *vol = ref.volume.data(), *fv = ref.family_volume.data();
  const std::int32_t *nb  = fam.neighbour.data() + o;
  const double        xi0 = x[2 * i], xi1 = x[2 * i + 1], yi0 = y[2 * i], yi1 = y[2 * i + 1];
  Quad               *def = s.deformation.data(), *shp = s.shape.data();
  double             *off = s.offset.data(), *fvk = s.family_volume.data();
  Double4             dt = {0.0, 0.0, 0.0, 0.0}, st = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t p = 0; p < m; ++p) {
    const std::size_t k  = static_cast<std::size_t>(nb[p]);
    const double      v  = vol[k];
    const double      d0 = x[2 * k] - xi0, d1 = x[2 * k + 1] - xi1;
    const double      e0 = y[2 * k] - yi0, e1 = y[2 * k + 1] - yi1;
    const double      a0 = d0 * v, a1 = d1 * v;
    off[2 * p]           = d0;
    off[2 * p + 1]       = d1;
    fvk[p]               = fv[k];
    const Double4 dv     = {e0 * a0, e0 * a1, e1 * a0, e1 * a1};
    const Double4 sv     = {d0 * a0, d0 * a1, d1 * a1, v};
    def[p].v             = dv;
    shp[p].v             = sv;
    if ((intact[Words == 1 ? 0 : p / 64] >> (p % 64)) & 1u) {
      dt += dv;
      st += sv;
    }
  }
  return {dt, st, fv[i], 0.5 / (fv[i] * fv[i])};
}

// Sums of arrays[n][p] (n < N) over the set bits p of bits[0 .. words), in increasing
// p. Two accumulators per array, alternating: halves the add latency chain, and the
// order is still fixed by the family alone. N is 2 for a bond's kinematics
// (deformation and shape) and 1 for the energy-consistent kernel's stress sums
// (ba_force_energy.hpp): one loop, unrolled over N by the compiler.
template <std::size_t N>
inline void sum_selected(const std::uint64_t *bits, std::size_t words, const Quad *const *arrays, Double4 *sums)
{
  Double4 s0[N], s1[N];
  for (std::size_t n = 0; n < N; ++n) s0[n] = s1[n] = Double4{0.0, 0.0, 0.0, 0.0};
  for (std::size_t w = 0; w < words; ++w) {
    std::uint64_t     m    = bits[w];
    const std::size_t base = 64 * w;
    while (m) {
      std::size_t p = base + static_cast<std::size_t>(__builtin_ctzll(m));
      m &= m - 1;
      for (std::size_t n = 0; n < N; ++n) s0[n] += arrays[n][p].v;
      if (!m) break;
      p = base + static_cast<std::size_t>(__builtin_ctzll(m));
      m &= m - 1;
      for (std::size_t n = 0; n < N; ++n) s1[n] += arrays[n][p].v;
    }
  }
  for (std::size_t n = 0; n < N; ++n) sums[n] = s0[n] + s1[n];
}

// Sums of N per-member arrays over the members p that are in a BA family (bit p of
// ba) and in the set `members` (the intact members, or a subset of them); totals[n]
// is the sum of arrays[n] over all of `members`, in order. When the BA family holds
// more than half of the members, the sums are formed as the totals minus the others
// (11 instead of 15.6 terms on average at 3.015 dx). Which form a bond uses depends
// only on its masks, so the result is the same on every rank.
template <std::size_t Words, std::size_t N>
inline void masked_sums(const std::uint64_t *ba, const std::uint64_t *members, std::size_t W,
                        const Quad *const *arrays, const Double4 *totals, Double4 *sums)
{
  constexpr std::size_t cap   = Words ? Words : 16; // 16 words: up to 1024 neighbours
  const std::size_t     words = Words ? Words : W;
  if (Words == 0 && words > cap) { // (never on a lattice with delta < 18 dx) straight sum
    for (std::size_t n = 0; n < N; ++n) sums[n] = Double4{0.0, 0.0, 0.0, 0.0};
    for (std::size_t w = 0; w < words; ++w) {
      const std::uint64_t m = ba[w] & members[w];
      const Quad         *shifted[N];
      for (std::size_t n = 0; n < N; ++n) shifted[n] = arrays[n] + 64 * w;
      Double4 part[N];
      sum_selected<N>(&m, 1, shifted, part);
      for (std::size_t n = 0; n < N; ++n) sums[n] += part[n];
    }
    return;
  }
  std::uint64_t in[cap], out[cap];
  int           n_in = 0, n_out = 0;
  for (std::size_t w = 0; w < words; ++w) {
    in[w]  = ba[w] & members[w];
    out[w] = ~ba[w] & members[w];
    n_in += __builtin_popcountll(in[w]);
    n_out += __builtin_popcountll(out[w]);
  }
  if (n_in <= n_out) {
    sum_selected<N>(in, words, arrays, sums);
    return;
  }
  Double4 others[N];
  sum_selected<N>(out, words, arrays, others);
  for (std::size_t n = 0; n < N; ++n) sums[n] = totals[n] - others[n];
}

// N and (K, V(B)) of a bond: sums of deformation_k and shape_k over intact B_ij.
template <std::size_t Words>
inline void masked_sums(const std::uint64_t *ba, const std::uint64_t *intact, std::size_t W, const PointScratch &s,
                        const PointTotals &totals, Double4 &N, Double4 &R)
{
  const Quad   *arrays[2] = {s.deformation.data(), s.shape.data()};
  const Double4 total[2]  = {totals.deformation, totals.shape};
  Double4       sums[2];
  masked_sums<Words, 2>(ba, intact, W, arrays, total, sums);
  N = sums[0];
  R = sums[1];
}

// F, K^{-1} and V(B) of the bond at position q of the gathered point.
template <std::size_t Words>
inline BondKinematics bond_kinematics(const std::uint64_t *ba, const std::uint64_t *intact, std::size_t W,
                                      const PointScratch &s, const PointTotals &totals)
{
  Double4 N, R;
  masked_sums<Words>(ba, intact, W, s, totals, N, R);
  BondKinematics k;
  const double   det = R[0] * R[2] - R[1] * R[1], tr = R[0] + R[2];
  k.usable           = tr > 0.0 && det > shape_tensor_degeneracy * tr * tr;
  if (!k.usable) return k;
  const double inv      = 1.0 / det;
  const double k0       = R[2] * inv, k1 = -R[1] * inv, k2 = R[0] * inv;
  k.shape_tensor_inv[0] = k0;
  k.shape_tensor_inv[1] = k1;
  k.shape_tensor_inv[2] = k2;
  k.volume              = R[3];
  k.F = {N[0] * k0 + N[1] * k1, N[0] * k1 + N[1] * k2, N[2] * k0 + N[3] * k1, N[2] * k1 + N[3] * k2};
  return k;
}

// 1/2 phi_xi / phi = 1/2 (V(B) / V(H_i)) (V(H_i) + V(H_j)) / V(H_i)   (eqs 11, 15, 23)
inline double force_scale(const BondKinematics &k, const PointTotals &totals, double family_volume_j)
{
  return k.volume * (totals.family_volume + family_volume_j) * totals.half_inverse_family_volume_squared;
}

// g_ij = force_scale K^{-1} (x_j - x_i) of the bond at position q of the gathered point
// (eq 23; the kernel's BondOnlyForm::collect forms the same product in the same order).
inline Vec2 force_vector(const BondKinematics &k, const PointTotals &totals, const PointScratch &s, std::size_t q)
{
  const double  f  = force_scale(k, totals, s.family_volume[q]);
  const double *ki = k.shape_tensor_inv;
  const double  d0 = s.offset[2 * q], d1 = s.offset[2 * q + 1];
  return {f * (ki[0] * d0 + ki[1] * d1), f * (ki[1] * d0 + ki[2] * d1)};
}

} // namespace detail

// Which intact bonds have a usable K, per family point (for counts and reports; the
// kernel skips the bonds marked unusable here and repeats the test itself, so a
// geometry not recomputed after breaking cannot make it divide by a singular K).
struct BondGeometry {
  std::size_t                mask_words = 1;
  std::vector<std::uint64_t> usable;   // mask_words per family point; bit q: intact and K usable
  std::vector<std::uint64_t> singular; // mask_words per family point; bit q: intact, K not usable
  // Set before compute_bond_geometry (kept by it): with a correction other than none,
  // `correction` holds C_i (4 per family point, xx xy yx yy) that the bond-only kernel
  // applies to every force vector of i, g_ij -> C_i g_ij: M_i^{-1} (tensor) or I / m_i
  // (scalar), I where M_i is degenerate (no usable bond, or a rank-1 M_i). M_i is that
  // of the reference family (every bond of t = 0 intact): C_i is formed when the
  // geometry is sized and not changed by breaking (bond_geometry.cpp says why).
  StressCorrection           stress_correction = StressCorrection::none;
  std::vector<double>        correction;
  std::vector<std::uint64_t> reference_mask; // work space: every family bond set
  // Work space of compute_bond_geometry, sized with the geometry, so that a time step
  // in which bonds break allocates nothing (STYLE.md, "Data").
  PointScratch               scratch;
  std::vector<std::uint32_t> done_in_pass; // per family point: the last recomputation that did it
  std::uint32_t              pass = 0;

  bool is_usable(std::size_t i, std::size_t q) const { return (usable[i * mask_words + q / 64] >> (q % 64)) & 1u; }
  bool corrected() const { return stress_correction != StressCorrection::none; }
  // C_i of point i (identity without a correction).
  Mat2 correction_of(std::size_t i) const
  {
    if (!corrected()) return {1.0, 0.0, 0.0, 1.0};
    return {correction[4 * i], correction[4 * i + 1], correction[4 * i + 2], correction[4 * i + 3]};
  }
  // Intact bonds of points [0, n_points) that carry no force for want of a usable K.
  std::size_t count_unusable(std::size_t n_points) const
  {
    std::size_t n = 0;
    for (std::size_t w = 0; w < n_points * mask_words; ++w) n += static_cast<std::size_t>(__builtin_popcountll(singular[w]));
    return n;
  }
};

// Sizes the geometry and computes it for every family point (with C_i if
// geometry.stress_correction is set). Needs
// cloud.family_volume for every neighbour (ring-2 ghosts included). Returns the
// number of intact bonds whose K is not usable. Throws std::invalid_argument if a
// needed family volume is missing (NaN) or not positive.
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry);

// Recomputes the listed points only (after break_bond / break_bonds): their usable
// bits (the stress correction C_i is a reference quantity and stays). A geometry not
// yet sized for these families is sized first (the only allocation; C_i of every
// point is formed then). Duplicates in points are harmless (each point is done once).
// Returns the number of intact bonds of those points whose K is not usable.
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry, const std::vector<std::size_t> &points);

// The reference quantities of bond q of point i in the current state (slow path, for
// tests and output; the same arithmetic as the kernel).
struct BondShape {
  bool                  usable = false;
  std::array<double, 3> shape_tensor_inv{}; // K^{-1}: xx, xy, yy
  double                volume_fraction = 0; // phi_xi (eq 15)
  double                force_scale     = 0; // 1/2 phi_xi / phi
  Vec2                  force_vector{};      // g_ij = force_scale K^{-1} (x_j - x_i)
};
BondShape bond_shape(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i,
                     std::size_t q);

// M_i = sum_j g_ij (x) (x_j - x_i) V_j over the usable intact bonds of i in `state`,
// g_ij the uncorrected force vector (the virial tensor above; slow path, for tests
// and reports). C_i is formed from it with every bond of t = 0 intact.
Mat2 virial_tensor(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i);

} // namespace bapd
