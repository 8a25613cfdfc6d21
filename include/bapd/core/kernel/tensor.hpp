#pragma once
// Small tensors for the per-bond kernels: plain arrays, row-major, inline, so that
// the compiler keeps them in registers. The fixed 2 x 2 and 3 x 3 forms (Vec2, Mat2,
// Mat3) and the dimension-generic ones (nd::Vec<D>, nd::Mat<D>, D = 2 or 3) are the
// same std::array types, so the 2D and 3D laws of hyperelastic.hpp take either.
#include <array>
#include <cmath>
#include <cstddef>

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

namespace bapd::nd {

template <int D> using Vec = std::array<double, D>;
template <int D> using Mat = std::array<double, D * D>; // row-major: A[D r + c]

// Symmetric D x D as its upper triangle, row by row: 2D (xx, xy, yy), 3D (xx, xy, xz,
// yy, yz, zz). K_ij (paper eq 8) is stored and summed this way.
template <int D> inline constexpr int sym_size = D * (D + 1) / 2;
template <int D> inline constexpr int sym_index(int r, int c)
{
  const int a = r < c ? r : c, b = r < c ? c : r; // a <= b
  return a * D - a * (a - 1) / 2 + (b - a);
}

template <int D> inline Mat<D> identity()
{
  Mat<D> I{};
  for (int r = 0; r < D; ++r) I[D * r + r] = 1.0;
  return I;
}

template <int D> inline double det(const Mat<D> &A)
{
  if constexpr (D == 2) return A[0] * A[3] - A[1] * A[2];
  else
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
           A[2] * (A[3] * A[7] - A[4] * A[6]);
}

template <int D> inline double trace(const Mat<D> &A)
{
  double t = 0.0;
  for (int r = 0; r < D; ++r) t += A[D * r + r];
  return t;
}

template <int D> inline Mat<D> transpose(const Mat<D> &A)
{
  Mat<D> T;
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) T[D * c + r] = A[D * r + c];
  return T;
}

// Adjugate (transposed cofactor matrix): A adj(A) = det(A) I.
template <int D> inline Mat<D> adjugate(const Mat<D> &A)
{
  if constexpr (D == 2) return {A[3], -A[1], -A[2], A[0]};
  else
    return {A[4] * A[8] - A[5] * A[7], A[2] * A[7] - A[1] * A[8], A[1] * A[5] - A[2] * A[4],
            A[5] * A[6] - A[3] * A[8], A[0] * A[8] - A[2] * A[6], A[2] * A[3] - A[0] * A[5],
            A[3] * A[7] - A[4] * A[6], A[1] * A[6] - A[0] * A[7], A[0] * A[4] - A[1] * A[3]};
}

// A^{-1}; the caller checks det A != 0.
template <int D> inline Mat<D> inverse(const Mat<D> &A)
{
  const double r   = 1.0 / det<D>(A);
  Mat<D>       inv = adjugate<D>(A);
  for (double &a : inv) a *= r;
  return inv;
}

template <int D> inline Mat<D> multiply(const Mat<D> &A, const Mat<D> &B)
{
  Mat<D> C{};
  for (int r = 0; r < D; ++r)
    for (int k = 0; k < D; ++k)
      for (int c = 0; c < D; ++c) C[D * r + c] += A[D * r + k] * B[D * k + c];
  return C;
}

template <int D> inline Vec<D> multiply(const Mat<D> &A, const Vec<D> &v)
{
  Vec<D> w{};
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) w[r] += A[D * r + c] * v[c];
  return w;
}

// The inverse of a symmetric matrix given as its upper triangle (sym_index), as an
// upper triangle, and its determinant (det <= 0: not inverted, inv untouched).
// 2D: the same operations, in the same order, as bond_kinematics of the earlier 2D
// kernel, so that the D = 2 instantiation rounds as that kernel did.
template <int D> [[gnu::always_inline]] inline double symmetric_inverse(const double *S, double *inv)
{
  if constexpr (D == 2) {
    const double d = S[0] * S[2] - S[1] * S[1];
    if (!(d > 0.0)) return d;
    const double r = 1.0 / d;
    inv[0]         = S[2] * r;
    inv[1]         = -S[1] * r;
    inv[2]         = S[0] * r;
    return d;
  } else {
    // (xx, xy, xz, yy, yz, zz) = S[0..5]; cofactors of a symmetric matrix
    const double c00 = S[3] * S[5] - S[4] * S[4], c01 = S[2] * S[4] - S[1] * S[5], c02 = S[1] * S[4] - S[2] * S[3];
    const double d = S[0] * c00 + S[1] * c01 + S[2] * c02;
    if (!(d > 0.0)) return d;
    const double r = 1.0 / d;
    inv[0]         = c00 * r;
    inv[1]         = c01 * r;
    inv[2]         = c02 * r;
    inv[3]         = (S[0] * S[5] - S[2] * S[2]) * r;
    inv[4]         = (S[1] * S[2] - S[0] * S[4]) * r;
    inv[5]         = (S[0] * S[3] - S[1] * S[1]) * r;
    return d;
  }
}

} // namespace bapd::nd
