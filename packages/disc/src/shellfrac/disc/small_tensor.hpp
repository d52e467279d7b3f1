#pragma once
/// \file small_tensor.hpp
/// Minimal fixed-size R^3 algebra on plain arrays (`double[3]` vectors, `double[3][3]` matrices, row-major:
/// A[i][j] = row i, column j). Pure point functions usable inside Kokkos kernels on any backend: no
/// std containers, no exceptions, no allocation.
///
/// Aliasing: functions writing to `out` accept `out` aliasing an input only where stated ("alias-safe");
/// mat_mat, cross3, mat_vec, mat_t_vec compute into a temporary first, so they are alias-safe too.
#include <Kokkos_Macros.hpp>
#include <cmath>

namespace shellfrac::disc {

// ---------------------------------------------------------------- vectors

/// a . b (T: double, or Batch for elements in lock-step, lanes.hpp)
template <class T>
KOKKOS_INLINE_FUNCTION T dot3(const T a[3], const T b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// |a|^2
KOKKOS_INLINE_FUNCTION double norm3_sq(const double a[3]) { return dot3(a, a); }

/// |a| (Euclidean norm)
KOKKOS_INLINE_FUNCTION double norm3(const double a[3]) { return std::sqrt(dot3(a, a)); }

/// out = a x b (alias-safe)
KOKKOS_INLINE_FUNCTION void cross3(const double a[3], const double b[3], double out[3]) {
  const double c0 = a[1] * b[2] - a[2] * b[1];
  const double c1 = a[2] * b[0] - a[0] * b[2];
  const double c2 = a[0] * b[1] - a[1] * b[0];
  out[0] = c0, out[1] = c1, out[2] = c2;
}

/// y <- y + alpha x
KOKKOS_INLINE_FUNCTION void axpy3(double alpha, const double x[3], double y[3]) {
  y[0] += alpha * x[0], y[1] += alpha * x[1], y[2] += alpha * x[2];
}

/// x <- alpha x
KOKKOS_INLINE_FUNCTION void scale3(double alpha, double x[3]) { x[0] *= alpha, x[1] *= alpha, x[2] *= alpha; }

/// out = a (copy)
KOKKOS_INLINE_FUNCTION void copy3(const double a[3], double out[3]) { out[0] = a[0], out[1] = a[1], out[2] = a[2]; }

/// out = a + b (alias-safe)
KOKKOS_INLINE_FUNCTION void add3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[0] + b[0], out[1] = a[1] + b[1], out[2] = a[2] + b[2];
}

/// out = a - b (alias-safe)
KOKKOS_INLINE_FUNCTION void sub3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[0] - b[0], out[1] = a[1] - b[1], out[2] = a[2] - b[2];
}

/// a <- a / |a|; returns the original norm (a untouched when |a| = 0).
KOKKOS_INLINE_FUNCTION double normalize3(double a[3]) {
  const double n = norm3(a);
  if (n > 0.0) scale3(1.0 / n, a);
  return n;
}

// ---------------------------------------------------------------- matrices

/// A = 1
KOKKOS_INLINE_FUNCTION void identity33(double A[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A[i][j] = (i == j) ? 1.0 : 0.0;
}

/// B = A (copy)
KOKKOS_INLINE_FUNCTION void copy33(const double A[3][3], double B[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) B[i][j] = A[i][j];
}

/// B = A^T (alias-safe)
KOKKOS_INLINE_FUNCTION void transpose33(const double A[3][3], double B[3][3]) {
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T[i][j] = A[j][i];
  copy33(T, B);
}

/// out = A x (alias-safe)
KOKKOS_INLINE_FUNCTION void mat_vec(const double A[3][3], const double x[3], double out[3]) {
  const double y0 = A[0][0] * x[0] + A[0][1] * x[1] + A[0][2] * x[2];
  const double y1 = A[1][0] * x[0] + A[1][1] * x[1] + A[1][2] * x[2];
  const double y2 = A[2][0] * x[0] + A[2][1] * x[1] + A[2][2] * x[2];
  out[0] = y0, out[1] = y1, out[2] = y2;
}

/// out = A^T x (alias-safe)
KOKKOS_INLINE_FUNCTION void mat_t_vec(const double A[3][3], const double x[3], double out[3]) {
  const double y0 = A[0][0] * x[0] + A[1][0] * x[1] + A[2][0] * x[2];
  const double y1 = A[0][1] * x[0] + A[1][1] * x[1] + A[2][1] * x[2];
  const double y2 = A[0][2] * x[0] + A[1][2] * x[1] + A[2][2] * x[2];
  out[0] = y0, out[1] = y1, out[2] = y2;
}

/// C = A B (alias-safe)
KOKKOS_INLINE_FUNCTION void mat_mat(const double A[3][3], const double B[3][3], double C[3][3]) {
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  copy33(T, C);
}

/// C = A^T B (alias-safe)
KOKKOS_INLINE_FUNCTION void mat_t_mat(const double A[3][3], const double B[3][3], double C[3][3]) {
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T[i][j] = A[0][i] * B[0][j] + A[1][i] * B[1][j] + A[2][i] * B[2][j];
  copy33(T, C);
}

/// W = hat(w), the skew matrix with W x = w x x.
KOKKOS_INLINE_FUNCTION void skew33(const double w[3], double W[3][3]) {
  W[0][0] = 0.0, W[0][1] = -w[2], W[0][2] = w[1];
  W[1][0] = w[2], W[1][1] = 0.0, W[1][2] = -w[0];
  W[2][0] = -w[1], W[2][1] = w[0], W[2][2] = 0.0;
}

/// Rotation by the angle theta about the unit axis a (Euler-Rodrigues):
/// R = cos(theta) I + sin(theta) hat(a) + (1 - cos(theta)) a (x) a.
KOKKOS_INLINE_FUNCTION void axis_angle_rotation(const double a[3], double theta, double R[3][3]) {
  const double c = std::cos(theta), s = std::sin(theta);
  double W[3][3];
  skew33(a, W);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + s * W[i][j] + (1.0 - c) * a[i] * a[j];
}

/// A = a (x) b, i.e. A[i][j] = a[i] b[j].
KOKKOS_INLINE_FUNCTION void outer33(const double a[3], const double b[3], double A[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A[i][j] = a[i] * b[j];
}

/// det A
KOKKOS_INLINE_FUNCTION double det33(const double A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

/// out = column j of A
KOKKOS_INLINE_FUNCTION void column33(const double A[3][3], int j, double out[3]) {
  out[0] = A[0][j], out[1] = A[1][j], out[2] = A[2][j];
}

/// column j of A = c
KOKKOS_INLINE_FUNCTION void set_column33(double A[3][3], int j, const double c[3]) {
  A[0][j] = c[0], A[1][j] = c[1], A[2][j] = c[2];
}

}  // namespace shellfrac::disc
