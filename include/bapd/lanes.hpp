#pragma once
// Four doubles in one AVX2 register (GCC vector extension), for code written once as a
// template over the lane type: T = double (one bond) or T = Lanes (four bonds). The
// arithmetic operators act lane by lane with the same IEEE rounding as the scalar
// code, so a lane gets bit for bit the result the scalar instantiation gets for the
// same input. That needs no FMA contraction, which GCC does by default for C++ (even
// with -std=c++17), and GCC 12's SLP vectorizer fuses a*b - c*d, e*f + g*h pairs even
// without it: the top-level CMakeLists.txt sets -ffp-contract=off and
// -fno-tree-slp-vectorize for the whole build (tests/unit/ba_force_lanes_test.cpp
// checks the result), and the code calls std::fma / lane_fma explicitly where it
// wants one.
#include <cmath>
#include <cstdint>
#include <cstring>
#ifdef __FMA__
#include <immintrin.h>
#endif

namespace bapd {

typedef double        Lanes __attribute__((vector_size(32)));
typedef std::int64_t  LaneMask __attribute__((vector_size(32))); // comparisons: all ones or 0
typedef std::uint64_t LaneBits __attribute__((vector_size(32)));

// The mask type of a comparison of two T.
template <class T> using MaskOf = decltype(T{} < T{});

inline double lane_abs(double x) { return std::abs(x); }
inline Lanes  lane_abs(Lanes x) { return (Lanes)((LaneBits)x & (LaneBits{} + 0x7fffffffffffffffull)); }
inline double lane_fma(double a, double b, double c) { return std::fma(a, b, c); }
inline Lanes  lane_fma(Lanes a, Lanes b, Lanes c)
{
#ifdef __FMA__
  return (Lanes)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c); // one vfmadd231pd
#else
  return Lanes{std::fma(a[0], b[0], c[0]), std::fma(a[1], b[1], c[1]), std::fma(a[2], b[2], c[2]),
               std::fma(a[3], b[3], c[3])}; // the same, lane by lane (fma rounds once either way)
#endif
}
inline double select(bool m, double a, double b) { return m ? a : b; }
inline Lanes  select(LaneMask m, Lanes a, Lanes b) { return m ? a : b; }
inline bool   any(bool m) { return m; }
inline bool   any(LaneMask m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }

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
