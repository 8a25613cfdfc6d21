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
// Why eight where the machine has AVX-512 (issue 20): the plane-stress model is a
// chain of dependent operations per bond; a wider register runs twice the bonds'
// chains per instruction (the Zen 5 core of docs/performance.md executes 512-bit
// operations at full width). Code that walks the lanes one by one uses lane_count.
#include <cmath>
#include <cstdint>
#include <cstring>
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

// The mask type of a comparison of two T.
template <class T> using MaskOf = decltype(T{} < T{});

inline double lane_abs(double x) { return std::abs(x); }
inline Lanes  lane_abs(Lanes x) { return (Lanes)((LaneBits)x & (LaneBits{} + 0x7fffffffffffffffull)); }
inline double lane_fma(double a, double b, double c) { return std::fma(a, b, c); }
inline Lanes  lane_fma(Lanes a, Lanes b, Lanes c)
{
#if defined(__AVX512F__)
  return (Lanes)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c); // one vfmadd231pd (zmm)
#elif defined(__FMA__)
  return (Lanes)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c); // one vfmadd231pd (ymm)
#else
  Lanes r;
  for (int l = 0; l < lane_count; ++l) r[l] = std::fma(a[l], b[l], c[l]); // the same (fma rounds once either way)
  return r;
#endif
}

// Half a register (four doubles with AVX-512, two with AVX2): a point's last bonds
// when they fill half a batch or less (nd/ba_force.hpp model_lanes: 28 bonds a point
// at the paper's horizon are 3 batches of 8 and 4 over). The same lane-by-lane
// arithmetic, so the same bits as Lanes and double.
inline constexpr int half_lane_count = lane_count / 2;
typedef double        HalfLanes __attribute__((vector_size(BAPD_LANE_BYTES / 2)));
typedef std::int64_t  HalfLaneMask __attribute__((vector_size(BAPD_LANE_BYTES / 2)));
typedef std::uint64_t HalfLaneBits __attribute__((vector_size(BAPD_LANE_BYTES / 2)));

inline HalfLanes lane_abs(HalfLanes x) { return (HalfLanes)((HalfLaneBits)x & (HalfLaneBits{} + 0x7fffffffffffffffull)); }
inline HalfLanes lane_fma(HalfLanes a, HalfLanes b, HalfLanes c)
{
#if defined(__AVX512F__)
  return (HalfLanes)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c); // one vfmadd231pd (ymm)
#elif defined(__FMA__)
  return (HalfLanes)_mm_fmadd_pd((__m128d)a, (__m128d)b, (__m128d)c); // one vfmadd231pd (xmm)
#else
  HalfLanes r;
  for (int l = 0; l < half_lane_count; ++l) r[l] = std::fma(a[l], b[l], c[l]);
  return r;
#endif
}
inline HalfLanes select(HalfLaneMask m, HalfLanes a, HalfLanes b) { return m ? a : b; }
inline bool      any(HalfLaneMask m)
{
  std::int64_t r = 0;
  for (int l = 0; l < half_lane_count; ++l) r |= m[l];
  return r != 0;
}
inline HalfLaneBits to_bits(HalfLanes x) { return (HalfLaneBits)x; }
inline HalfLanes    from_bits(HalfLaneBits b) { return (HalfLanes)b; }

inline double select(bool m, double a, double b) { return m ? a : b; }
inline Lanes  select(LaneMask m, Lanes a, Lanes b) { return m ? a : b; }
inline bool   any(bool m) { return m; }
inline bool   any(LaneMask m)
{
  std::int64_t r = 0;
  for (int l = 0; l < lane_count; ++l) r |= m[l];
  return r != 0;
}

// The bits of a double and back (the approximate cube root's seed).
inline std::uint64_t to_bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
inline LaneBits      to_bits(Lanes x) { return (LaneBits)x; }
inline double        from_bits(std::uint64_t b)
{
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}
inline Lanes from_bits(LaneBits b) { return (Lanes)b; }

} // namespace bapd
