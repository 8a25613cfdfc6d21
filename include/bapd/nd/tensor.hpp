#pragma once
// Small D x D tensors for the dimension-generic core (D = 2 or 3): plain arrays,
// row-major, inline, so that the compiler keeps them in registers. Vec<2>, Mat<2> and
// Mat<3> are the very types of tensor.hpp (Vec2, Mat2, Mat3), so the 2D and 3D laws of
// hyperelastic.hpp take them as they are.
#include <array>
#include <cstddef>

#include "bapd/tensor.hpp"

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
// 2D: the same operations, in the same order, as bond_kinematics of the retired 2D
// kernel (issue 21 stage 3), so that the D = 2 instantiation rounds as it did.
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
