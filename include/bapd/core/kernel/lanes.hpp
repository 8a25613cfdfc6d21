#pragma once
// lane_count doubles in one vector register (GCC vector extension): eight with AVX-512
// (zmm), four otherwise (AVX2 ymm), for code written once as a template over the lane
// type: T = double (one bond) or T = Lanes (lane_count bonds). The arithmetic
// operators act lane by lane with the same IEEE rounding as the scalar code, so a
// lane gets bit for bit the result the scalar instantiation gets for the same input,
// whatever the width (a bond's result does not depend on its lane or on the machine's
// vector width). That needs no FMA contraction, which GCC does by default for C++ (even
// with -std=c++17), and GCC 12's SLP vectorizer fuses a*b - c*d, e*f + g*h pairs even
// without it: the top-level CMakeLists.txt sets -ffp-contract=off and
// -fno-tree-slp-vectorize for the whole build (tests/unit/ba_force_lanes_test.cpp
// checks the result), and the code calls std::fma / lane_fma explicitly where it
// wants one.
//
// Why eight where the machine has AVX-512: the plane-stress model is a
// chain of dependent operations per bond; a wider register runs twice the bonds'
// chains per instruction (the Zen 5 core of docs/performance.md executes 512-bit
// operations at full width). Code that walks the lanes one by one uses lane_count.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__FMA__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace bapd {

#ifdef __AVX512F__
#define BAPD_LANE_BYTES 64
#else
#define BAPD_LANE_BYTES 32
#endif
inline constexpr int  lane_count = BAPD_LANE_BYTES / 8;
typedef double        Lanes __attribute__((vector_size(BAPD_LANE_BYTES)));
typedef std::int64_t  LaneMask __attribute__((vector_size(BAPD_LANE_BYTES))); // comparisons: all ones or 0
typedef std::uint64_t LaneBits __attribute__((vector_size(BAPD_LANE_BYTES)));

// Half a register (four doubles with AVX-512, two with AVX2): a point's last bonds
// when they fill half a batch or less (ba_force.hpp model_lanes: 28 bonds a point
// at the paper's horizon are 3 batches of 8 and 4 over). The same lane-by-lane
// arithmetic, so the same bits as Lanes and double.
inline constexpr int half_lane_count = lane_count / 2;
typedef double        HalfLanes __attribute__((vector_size(BAPD_LANE_BYTES / 2)));
typedef std::int64_t  HalfLaneMask __attribute__((vector_size(BAPD_LANE_BYTES / 2)));
typedef std::uint64_t HalfLaneBits __attribute__((vector_size(BAPD_LANE_BYTES / 2)));

// The mask type of a comparison of two T.
template <class T> using MaskOf = decltype(T{} < T{});

// The register types (Lanes, HalfLanes) with their bit patterns: the operations below
// are written once for both.
template <class V> struct LaneVector;
template <> struct LaneVector<Lanes> {
  using Bits = LaneBits;
};
template <> struct LaneVector<HalfLanes> {
  using Bits = HalfLaneBits;
};
template <class V> using BitsOf = typename LaneVector<V>::Bits;
template <class M>
inline constexpr bool is_lane_mask = std::is_same_v<M, LaneMask> || std::is_same_v<M, HalfLaneMask>;

inline double lane_abs(double x) { return std::abs(x); }
template <class V, class B = BitsOf<V>> inline V lane_abs(V x) { return (V)((B)x & (B{} + 0x7fffffffffffffffull)); }
inline double lane_fma(double a, double b, double c) { return std::fma(a, b, c); }
template <class V, class = BitsOf<V>> inline V lane_fma(V a, V b, V c)
{
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64) return (V)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c); // one vfmadd231pd (zmm)
#endif
#if defined(__FMA__) || defined(__AVX512F__)
  if constexpr (sizeof(V) == 32) return (V)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c); // (ymm)
  if constexpr (sizeof(V) == 16) return (V)_mm_fmadd_pd((__m128d)a, (__m128d)b, (__m128d)c);    // (xmm)
#endif
  V r; // without FMA instructions: the same (fma rounds once either way)
  for (int l = 0; l < static_cast<int>(sizeof(V) / sizeof(double)); ++l) r[l] = std::fma(a[l], b[l], c[l]);
  return r;
}
inline double                               select(bool m, double a, double b) { return m ? a : b; }
template <class V, class = BitsOf<V>> inline V select(MaskOf<V> m, V a, V b) { return m ? a : b; }
inline bool                                 any(bool m) { return m; }
template <class M, class = std::enable_if_t<is_lane_mask<M>>> inline bool any(M m)
{
  std::int64_t r = 0;
  for (int l = 0; l < static_cast<int>(sizeof(M) / sizeof(std::int64_t)); ++l) r |= m[l];
  return r != 0;
}

// The bits of a double and back (the approximate cube root's seed).
inline std::uint64_t to_bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
template <class V, class B = BitsOf<V>> inline B to_bits(V x) { return (B)x; }
inline double                                    from_bits(std::uint64_t b)
{
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}
inline Lanes     from_bits(LaneBits b) { return (Lanes)b; }
inline HalfLanes from_bits(HalfLaneBits b) { return (HalfLanes)b; }

} // namespace bapd
