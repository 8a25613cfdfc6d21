#pragma once
// Small fixed-size tensors for the per-bond kernels: plain arrays, row-major,
// everything inline so that the compiler keeps them in registers.
#include <array>
#include <cmath>

namespace bapd {

using Vec2 = std::array<double, 2>;
using Mat2 = std::array<double, 4>; // [xx, xy, yx, yy]
using Mat3 = std::array<double, 9>; // row-major

inline constexpr Mat2 identity2() { return {1.0, 0.0, 0.0, 1.0}; }
inline constexpr Mat3 identity3() { return {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}; }

inline double det(const Mat2 &A) { return A[0] * A[3] - A[1] * A[2]; }
inline double trace(const Mat2 &A) { return A[0] + A[3]; }
inline Mat2 transpose(const Mat2 &A) { return {A[0], A[2], A[1], A[3]}; }

inline Mat2 operator*(const Mat2 &A, const Mat2 &B)
{
  return {A[0] * B[0] + A[1] * B[2], A[0] * B[1] + A[1] * B[3],
          A[2] * B[0] + A[3] * B[2], A[2] * B[1] + A[3] * B[3]};
}
inline Vec2 operator*(const Mat2 &A, const Vec2 &v) { return {A[0] * v[0] + A[1] * v[1], A[2] * v[0] + A[3] * v[1]}; }
inline Mat2 operator*(double s, const Mat2 &A) { return {s * A[0], s * A[1], s * A[2], s * A[3]}; }
inline Mat2 operator+(const Mat2 &A, const Mat2 &B) { return {A[0] + B[0], A[1] + B[1], A[2] + B[2], A[3] + B[3]}; }
inline Mat2 operator-(const Mat2 &A, const Mat2 &B) { return {A[0] - B[0], A[1] - B[1], A[2] - B[2], A[3] - B[3]}; }

// Inverse of a 2x2 matrix; the caller checks det != 0.
inline Mat2 inverse(const Mat2 &A)
{
  const double r = 1.0 / det(A);
  return {r * A[3], -r * A[1], -r * A[2], r * A[0]};
}
// F^{-T}, needed by every hyperelastic stress.
inline Mat2 inverse_transpose(const Mat2 &A)
{
  const double r = 1.0 / det(A);
  return {r * A[3], -r * A[2], -r * A[1], r * A[0]};
}
// C = F^T F
inline Mat2 right_cauchy_green(const Mat2 &F)
{
  return {F[0] * F[0] + F[2] * F[2], F[0] * F[1] + F[2] * F[3],
          F[0] * F[1] + F[2] * F[3], F[1] * F[1] + F[3] * F[3]};
}

inline double det(const Mat3 &A)
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}
inline Mat3 inverse_transpose(const Mat3 &A)
{
  const double r = 1.0 / det(A);
  // cofactor matrix / det
  return {r * (A[4] * A[8] - A[5] * A[7]), r * (A[5] * A[6] - A[3] * A[8]), r * (A[3] * A[7] - A[4] * A[6]),
          r * (A[2] * A[7] - A[1] * A[8]), r * (A[0] * A[8] - A[2] * A[6]), r * (A[1] * A[6] - A[0] * A[7]),
          r * (A[1] * A[5] - A[2] * A[4]), r * (A[2] * A[3] - A[0] * A[5]), r * (A[0] * A[4] - A[1] * A[3])};
}
inline double frobenius_squared(const Mat3 &A)
{
  double s = 0.0;
  for (double a : A) s += a * a;
  return s;
}
// Embeds an in-plane F~ into 3D with the given out-of-plane stretch F33.
inline Mat3 embed(const Mat2 &F, double F33) { return {F[0], F[1], 0.0, F[2], F[3], 0.0, 0.0, 0.0, F33}; }

} // namespace bapd
