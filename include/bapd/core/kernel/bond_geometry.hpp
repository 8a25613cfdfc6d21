#pragma once
// Bond-associated kinematics in D = 2 or 3 dimensions (paper eqs 8, 9, 11, 15, 23;
// docs/method.md sections 2-3): the one kernel for 2D and 3D (D = 2 does the
// operations of the former 2D-only kernel in their order).
//
// Per intact bond b = (i -> j), with B = the intact members of the BA family B_ij:
//   K_ij          = sum_{k in B} (x_k - x_i) (x) (x_k - x_i) V_k               (eq 8)
//   F_ij          = [ sum_{k in B} (y_k - y_i) (x) (x_k - x_i) V_k ] K_ij^{-1}  (eq 9)
//   phi_xi(i, j)  = V(B) / V(H_i)                                              (eq 15)
//   phi(i, j)     = V(H_i) / (V(H_i) + V(H_j))                                 (eq 11)
//   force_scale   = 1/2 phi_xi / phi,   g_ij = force_scale C_i K_ij^{-1} (x_j - x_i)
// with C_i the stress correction of the point (stress_correction.hpp; I without one).
//
// How it is computed. Per point i, each family member k gets one record of
//   (y_k - y_i) (x) (x_k - x_i) V_k   (D x D, row-major),
//   (x_k - x_i) (x) (x_k - x_i) V_k   (its upper triangle, sym_index),   V_k,
// padded to whole vectors (2D: 8 doubles, 3D: 16), formed once and reused by
// all of i's bonds. A bond's N, K and V(B) are then one masked sum of the records (BA
// mask AND intact mask) in family order, or the point's total minus the others when
// the BA family holds more than half of the intact members. K^{-1} and force_scale
// are therefore formed per bond per evaluation, not stored: storing them (3 + 1
// doubles a bond in 2D) would cost 0.9 KB per point at delta = 3.015 dx against a
// memory target of 2 KB per point, while forming them costs ~6 ns a bond (measured on
// the 2D kernel, docs/notes/performance-kernel-1.md 1b). It also means that a broken bond changes K
// at once, with nothing to go stale. For D = 2 every operation is the earlier 2D
// kernel's, in its order (the same two alternating accumulators, the same K^{-1}
// formula), so 2D results are bit for bit that kernel's (scripts/compare_binaries.sh
// compares two binaries); ba_force_2d_reference_test.cpp holds D = 2 to the equations.
//
// Usable K: K is symmetric positive semi-definite; det K / (tr K)^D ~ 1 / cond(K)
// up to a constant. A bond is usable iff det K > shape_tensor_degeneracy (tr K)^D;
// one that is not carries no force (the kernel writes t_ij = 0 and counts it).
// 2D: K in units of V dx^2 has integer entries on a lattice, so a regular K has
// det >= 1 while (tr K)^2 < 1e6 even for delta = 5 dx: its ratio is >= 1e-6, and a
// degenerate one (collinear members, a lone member) has ratio ~1e-16; 1e-8 sits
// between them with two orders of margin on both sides, and a usable K loses at most
// cond(K) eps < 1e-8 relative accuracy in F.
// 3D: on a lattice K in units of V dx^2 has integer entries, so a
// regular K has det >= 1 while tr K is at most (members) x (delta/dx)^2: in 3D below
// 2200 at delta = 3.515 dx (178 x 12.4), so the ratio is >= 1 / 2200^3 ~ 1e-10, while
// a degenerate K (coplanar members) has det at round-off, ratio ~ 1e-16. The
// threshold 1e-12 sits between them with two orders of margin above and four below.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/tensor.hpp"
#include "bapd/core/kernel/stress_correction.hpp"

namespace bapd::nd {

template <int D> inline constexpr double shape_tensor_degeneracy = D == 2 ? 1e-8 : 1e-12;

// det > threshold (tr)^D, with tr > 0: K (or the virial M_i) regular. The product is
// formed as the 2D kernel forms it, (threshold tr) tr [tr].
template <int D> inline bool regular(double det, double tr)
{
  double bound = shape_tensor_degeneracy<D> * tr;
  for (int r = 1; r < D; ++r) bound = bound * tr;
  return tr > 0.0 && det > bound;
}

// The widest vector the target has: 8 doubles with AVX-512 (a 3D record, 16 doubles,
// is then two adds), else 4. Element-wise sums in the same order either way, so the
// width changes no bit of any result.
#if defined(__AVX512F__)
inline constexpr int vector_doubles = 8;
#else
inline constexpr int vector_doubles = 4;
#endif
typedef double Vector __attribute__((vector_size(8 * vector_doubles)));

// N doubles in whole vectors, summed one vector at a time.
template <int N> struct alignas(8 * vector_doubles) Packed {
  static constexpr int V = vector_doubles, vectors = (N + V - 1) / V;
  Vector               v[vectors];
  double               operator[](int k) const { return v[k / V][k % V]; }
  void                 set(int k, double a) { v[k / V][k % V] = a; }
  void                 zero()
  {
    for (int q = 0; q < vectors; ++q) v[q] = Vector{};
  }
  // From N doubles (a holds whole vectors: the rest is zero): each vector is built
  // from its scalars in registers ({a[0], a[1], ...}), not stored lane by lane and read
  // back as a vector (a store-forwarding stall per record: set() in gather_point cost
  // the D = 2 kernel 10-20 % against the retired 2D kernel: docs/notes/performance-kernel-2.md 1g).
  static Packed from(const double *a) { return from(a, std::make_index_sequence<V>{}); }
  template <std::size_t... I> static Packed from(const double *a, std::index_sequence<I...>)
  {
    Packed p;
    for (int q = 0; q < vectors; ++q) p.v[q] = Vector{a[q * V + static_cast<int>(I)]...};
    return p;
  }
  Packed &operator+=(const Packed &o)
  {
    for (int q = 0; q < vectors; ++q) v[q] += o.v[q];
    return *this;
  }
};
template <int N> inline Packed<N> operator+(Packed<N> a, const Packed<N> &b) { return a += b; }
// a where take, else b (bitwise, a blend and no branch).
template <int N> inline Packed<N> blend(bool take, const Packed<N> &a, const Packed<N> &b)
{
  typedef std::int64_t Bits __attribute__((vector_size(8 * vector_doubles)));
  const Bits keep = Bits{} - static_cast<std::int64_t>(take); // all ones or 0
  Packed<N>  r;
  for (int q = 0; q < Packed<N>::vectors; ++q) r.v[q] = (Vector)(((Bits)a.v[q] & keep) | ((Bits)b.v[q] & ~keep));
  return r;
}
template <int N> inline Packed<N> operator-(Packed<N> a, const Packed<N> &b)
{
  for (int q = 0; q < Packed<N>::vectors; ++q) a.v[q] -= b.v[q];
  return a;
}

// The per-member record: deformation (D x D), shape (upper triangle), V_k.
template <int D> struct Member {
  static constexpr int deformation = 0, shape = D * D, volume = D * D + sym_size<D>, size = volume + 1;
  using Record                     = Packed<size>;
};
template <int D> using MemberRecord = typename Member<D>::Record;
// V_q P(F_iq) K_iq^{-1} of a bond (the energy-consistent form, ba_force.hpp).
template <int D> using StressRecord = Packed<D * D>;

// The sum of records[p] over the set bits p of one mask word, in increasing p: two
// accumulators, alternating: half the add latency chain, and the order is still fixed
// by the family alone. always_inline (also masked_sum, bond_kinematics and
// nd::symmetric_inverse): GCC put these out of line in the energy-consistent kernel
// only, returning the sums through the stack (docs/notes/performance-kernel-3.md 1j: 3D 88 -> 76 ns a
// bond; the arithmetic, and so every bit, unchanged).
template <class R> [[gnu::always_inline]] inline R sum_selected(std::uint64_t m, const R *records)
{
  R s0, s1;
  s0.zero();
  s1.zero();
  while (m) {
    std::size_t p = static_cast<std::size_t>(__builtin_ctzll(m));
    m &= m - 1;
    s0 += records[p];
    if (!m) break;
    p = static_cast<std::size_t>(__builtin_ctzll(m));
    m &= m - 1;
    s1 += records[p];
  }
  return s0 + s1;
}

// masked_sum's sum over one mask word. Without a branch on the choice, which differs
// from bond to bond: the sum over the chosen set, then total - sum formed always and
// one of the two kept.
template <class R>
[[gnu::always_inline]] inline R word_sum(std::uint64_t ba, std::uint64_t members, const R *records, const R &total)
{
  const std::uint64_t in = ba & members, out = ~ba & members;
  const bool          direct = __builtin_popcountll(in) <= __builtin_popcountll(out);
  const R             sum    = sum_selected(direct ? in : out, records);
  return blend(direct, sum, total - sum);
}

// The sum of the records of the members in the BA family (ba) and in `members`, mask
// word by mask word (64 members each), the words' sums added in order. word_total[w] =
// the sum over all of `members` in word w, in order. Where the BA family holds more
// than half of a word's members: that word's total minus the others. Which form a
// word takes depends on the masks alone, so the result is the same on any rank.
// Deciding by word and not over the whole mask (the two are the same for 2D's one
// word) adds 38 records a sum in place of 47 on an interior 3D family at 3.015 dx:
// its members are sorted by natural id, z slowest, so a BA family (the lens of two
// balls) fills most of one word and little of the other (docs/notes/performance-kernel-3.md 1k).
// Words: the mask words if known at compile time (the kernels dispatch 1, 2 and 3; the
// masks then stay in registers), else 0 and `words` at run time.
template <std::size_t Words, class R>
[[gnu::always_inline]] inline R masked_sum(const std::uint64_t *ba, const std::uint64_t *members, std::size_t words,
                                           const R *records, const R *word_total)
{
  if constexpr (Words == 1) { // 2D: the same sum with a branch (kernel_bench energy_warm: 30.2-30.4 ns a bond, 31.9-32.3 with the blend)
    const std::uint64_t in = ba[0] & members[0], out = ~ba[0] & members[0];
    if (__builtin_popcountll(in) <= __builtin_popcountll(out)) return sum_selected(in, records);
    return word_total[0] - sum_selected(out, records);
  }
  if constexpr (Words > 0) words = Words;
  R s = word_sum(ba[0], members[0], records, word_total[0]);
  for (std::size_t w = 1; w < words; ++w) s += word_sum(ba[w], members[w], records + 64 * w, word_total[w]);
  return s;
}

// Per-member data of the point being processed, sized once for the largest family
// (nothing is allocated per evaluation).
template <int D> struct PointScratch {
  std::vector<MemberRecord<D>> member;        // records of the point's members
  std::vector<double>          offset;        // x_k - x_i, D per member
  std::vector<double>          family_volume; // V(H_k) per member
  std::vector<MemberRecord<D>> word_total;    // the sum of the intact members' records of each mask word

  void reserve(const Families &f)
  {
    if (member.size() < f.max_family_size) {
      member.resize(f.max_family_size);
      offset.resize(D * f.max_family_size);
      family_volume.resize(f.max_family_size);
    }
    if (word_total.size() < f.mask_words) word_total.resize(f.mask_words);
  }
};

// What one point's bonds share: the sums of its intact records (by mask word, in
// PointScratch::word_total) and V(H_i).
template <int D> struct PointTotals {
  const MemberRecord<D> *word_total;
  double                 family_volume;                      // V(H_i)
  double                 half_inverse_family_volume_squared; // 1 / (2 V(H_i)^2)
};

// What one bond needs, from the masked sums.
template <int D> struct BondKinematics {
  Mat<D> F;                                // eq 9
  double shape_tensor_inv[sym_size<D>];    // K^{-1}, upper triangle
  double volume;                           // V(B)
  bool   usable;                           // K regular (if not, nothing else is set)
  double kinv(int r, int c) const { return shape_tensor_inv[sym_index<D>(r, c)]; }
};

// Fills the records of point i (y: current positions, D per point; y = x gives the
// reference quantities) and returns its totals over the intact members.
template <int D>
inline PointTotals<D> gather_point(const PointCloud &ref, const double *y, const Families &fam, std::size_t i,
                                   const std::uint64_t *intact, PointScratch<D> &ws)
{
  using L                 = Member<D>;
  const std::size_t   o   = fam.offsets[i], m = fam.offsets[i + 1] - o;
  const double       *x   = ref.x.data(), *vol = ref.volume.data(), *fv = ref.family_volume.data();
  const std::int32_t *nb  = fam.neighbour.data() + o;
  MemberRecord<D>    *rec = ws.member.data(), *word_total = ws.word_total.data();
  double             *off = ws.offset.data(), *fvk = ws.family_volume.data();
  MemberRecord<D>     total; // of the current mask word
  // x_i and y_i in registers: the stores below could alias x and y for the compiler,
  // which would then load them again for every member.
  double xi[D], yi[D];
  for (int r = 0; r < D; ++r) {
    xi[r] = x[D * i + r];
    yi[r] = y[D * i + r];
  }
  for (std::size_t w = 0; w < fam.mask_words; ++w) {
    total.zero();
    for (std::size_t p = 64 * w; p < std::min(m, 64 * w + 64); ++p) {
      const std::size_t k = static_cast<std::size_t>(nb[p]);
      const double      v = vol[k];
      double            d[D], e[D], a[D];
      for (int r = 0; r < D; ++r) {
        d[r] = x[D * k + r] - xi[r];
        e[r] = y[D * k + r] - yi[r];
        a[r] = d[r] * v;
        off[D * p + r] = d[r];
      }
      fvk[p] = fv[k];
      double f[MemberRecord<D>::vectors * MemberRecord<D>::V] = {};
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) f[L::deformation + D * r + c] = e[r] * a[c];
      for (int r = 0; r < D; ++r)
        for (int c = r; c < D; ++c) f[L::shape + sym_index<D>(r, c)] = d[r] * a[c];
      f[L::volume]             = v;
      const MemberRecord<D> R = MemberRecord<D>::from(f);
      rec[p]                  = R;
      if ((intact[w] >> (p % 64)) & 1u) total += R;
    }
    word_total[w] = total;
  }
  return {word_total, fv[i], 0.5 / (fv[i] * fv[i])};
}

// F, K^{-1} and V(B) of a bond (ba: its BA mask) from the gathered point.
template <int D, std::size_t Words = 0>
[[gnu::always_inline]] inline BondKinematics<D> bond_kinematics(const std::uint64_t *ba, const std::uint64_t *intact, std::size_t W,
                                         PointScratch<D> &ws, const PointTotals<D> &totals)
{
  using L                 = Member<D>;
  const MemberRecord<D> S = masked_sum<Words>(ba, intact, W, ws.member.data(), totals.word_total);
  BondKinematics<D>     k;
  double                K[sym_size<D>];
  for (int s = 0; s < sym_size<D>; ++s) K[s] = S[L::shape + s];
  double tr = K[0] + K[sym_index<D>(1, 1)];
  if constexpr (D == 3) tr = tr + K[sym_index<D>(2, 2)];
  double det;
  if constexpr (D == 2) det = K[0] * K[2] - K[1] * K[1];
  else det = K[0] * (K[3] * K[5] - K[4] * K[4]) + K[1] * (K[2] * K[4] - K[1] * K[5]) + K[2] * (K[1] * K[4] - K[2] * K[3]);
  k.usable = regular<D>(det, tr);
  if (!k.usable) return k;
  symmetric_inverse<D>(K, k.shape_tensor_inv);
  k.volume = S[L::volume];
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) {
      double f = S[L::deformation + D * r] * k.kinv(0, c); // sums start at their first term (dot)
      for (int m = 1; m < D; ++m) f += S[L::deformation + D * r + m] * k.kinv(m, c);
      k.F[D * r + c] = f;
    }
  return k;
}

// 1/2 phi_xi / phi = V(B) (V(H_i) + V(H_j)) / (2 V(H_i)^2)   (eqs 11, 15, 23)
template <int D> inline double force_scale(const BondKinematics<D> &k, const PointTotals<D> &t, double family_volume_j)
{
  return k.volume * (t.family_volume + family_volume_j) * t.half_inverse_family_volume_squared;
}

// g = force_scale K^{-1} xi (uncorrected).
template <int D> inline void force_vector(const BondKinematics<D> &k, double scale, const double *xi, double *g)
{
  for (int r = 0; r < D; ++r) {
    double s = k.kinv(r, 0) * xi[0];
    for (int c = 1; c < D; ++c) s += k.kinv(r, c) * xi[c];
    g[r] = scale * s;
  }
}

// Which intact bonds have a usable K (per family point), and the stress correction
// C_i (D x D per family point) when one is set before compute_bond_geometry (for
// counts and reports; the kernel skips the bonds marked unusable here and repeats the
// test itself, so a geometry not recomputed after breaking cannot make it divide by a
// singular K).
template <int D> struct BondGeometry {
  std::size_t                mask_words = 1;
  std::vector<std::uint64_t> usable;   // bit q: intact and K usable
  std::vector<std::uint64_t> singular; // bit q: intact, K not usable
  StressCorrection           stress_correction = StressCorrection::none;
  std::vector<double>        correction; // C_i, D x D row-major per family point
  // Work space of compute_bond_geometry, sized with the geometry, so that a time step
  // in which bonds break allocates nothing.
  PointScratch<D>            scratch;
  std::vector<std::uint64_t> reference_mask;
  std::vector<std::uint32_t> done_in_pass; // per family point: the last recomputation that did it
  std::uint32_t              pass = 0;

  bool is_usable(std::size_t i, std::size_t q) const { return (usable[i * mask_words + q / 64] >> (q % 64)) & 1u; }
  bool corrected() const { return stress_correction != StressCorrection::none; }
  Mat<D> correction_of(std::size_t i) const
  {
    Mat<D> C = identity<D>();
    if (corrected())
      for (int k = 0; k < D * D; ++k) C[k] = correction[D * D * i + k];
    return C;
  }
  std::size_t count_unusable(std::size_t n_points) const
  {
    std::size_t n = 0;
    for (std::size_t w = 0; w < n_points * mask_words; ++w)
      n += static_cast<std::size_t>(__builtin_popcountll(singular[w]));
    return n;
  }
};

// Sizes the geometry and computes it for every family point, with C_i if
// geometry.stress_correction is set (from M_i of the reference family, every bond of
// t = 0 intact: bond_geometry.cpp says why). Needs cloud.family_volume of
// every neighbour. Returns the intact bonds whose K is not usable. Throws
// std::invalid_argument if a needed family volume is missing or not positive.
template <int D>
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry<D> &geometry);
// Recomputes the usable bits of the listed points only (after break_bond / break_bonds;
// the stress correction C_i is a reference quantity and stays). A geometry not yet
// sized for these families is sized first (the only allocation). Duplicates in
// points are harmless (each point is done once). Returns the intact bonds of those
// points whose K is not usable.
template <int D>
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry<D> &geometry, const std::vector<std::size_t> &points);

// The reference quantities of bond q of point i in the current state (slow path, for
// tests and output; the kernel's arithmetic).
template <int D> struct BondShape {
  bool   usable = false;
  double shape_tensor_inv[sym_size<D>]{}; // K^{-1}, upper triangle
  double volume_fraction = 0;             // phi_xi (eq 15)
  double force_scale     = 0;             // 1/2 phi_xi / phi
  Vec<D> force_vector{};                  // g_ij = force_scale K^{-1} (x_j - x_i), uncorrected
};
template <int D>
BondShape<D> bond_shape(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i,
                        std::size_t q);

// M_i = sum_j g_ij (x) xi_ij V_j over the usable intact bonds of i (g uncorrected):
// the virial tensor whose inverse the tensor correction is (slow path, tests).
template <int D>
Mat<D> virial_tensor(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i);

} // namespace bapd::nd
