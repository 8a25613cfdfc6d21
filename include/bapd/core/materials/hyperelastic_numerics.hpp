#pragma once
// Scalar numerics shared by the hyperelastic formulations (hyperelastic.hpp,
// plane_stress.hpp): the volumetric energy without cancellation near J = 1, and a
// cube root for starting points. T = double or Lanes (lanes.hpp) where templated.
#include <cmath>
#include <cstdint>

#include "bapd/core/kernel/lanes.hpp"

namespace bapd {

// (J^2 - 1)/2 - ln J = D U(J). Near J = 1 both terms are O(J - 1) and cancel to
// O((J - 1)^2), so there it is summed as e^2/2 + (e - ln(1 + e)), e = J - 1, with
// e - ln(1 + e) = e^2/(2 + e) - 2 sum_{n>=1} u^{2n+1}/(2n+1), u = e/(2 + e)
// (ln(1 + e) = 2 atanh u): every term positive order, no cancellation.
inline double volumetric_energy_times_D(double J)
{
  const double e = J - 1.0;
  if (std::abs(e) > 0.1) return 0.5 * (J * J - 1.0) - std::log(J);
  const double u = e / (2.0 + e), u2 = u * u;
  double       odd = u * u2, series = 0.0; // u^3/3 + u^5/5 + ... ; u^17 < 1e-22 here
  for (int n = 3; n <= 17; n += 2, odd *= u2) series += odd / n;
  return 0.5 * e * e + e * e / (2.0 + e) - 2.0 * series;
}

// x^(1/3) for a normal x > 0 to a relative error below 4e-7, without a division or a
// call: x^(-1/3) from the exponent bits (the bit pattern is ~ 2^52 log2 x, so
// C - bits/3 is ~ x^(-1/3) to 3.5 %; bits/3 from the high word, exact in 64-bit
// integer arithmetic, so that AVX2 does it lane by lane), one step of
// r <- r (1 - e)^(-1/3) with e = 1 - x r^3 and the series of (1 - e)^(-1/3) to e^5
// (error ~ 0.11 e^6 < 2e-7 for |e| < 0.1), then x^(1/3) = x r^2. About 12 dependent
// operations where libm's cbrt is ~95 cycles; the plane-stress solve uses it for a
// starting point only, where any value near the root does. T = double or Lanes.
template <class T> inline T approximate_cbrt(T x)
{
  const auto high = to_bits(x) >> 32;
  T          r    = from_bits(0x553ef10000000000ull - (((high * 0xaaaaaaabull) >> 33) << 32));
  const T    e = lane_fma(-x * r, r * r, T{} + 1.0), e2 = e * e;
  const T    series = 1.0 + e * (1.0 / 3.0) + e2 * ((2.0 / 9.0) + e * (14.0 / 81.0)) +
                   e2 * e2 * ((35.0 / 243.0) + e * (91.0 / 729.0));
  r = r * series;
  return x * r * r;
}

} // namespace bapd
