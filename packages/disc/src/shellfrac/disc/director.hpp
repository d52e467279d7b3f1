#pragma once
/// \file director.hpp
/// Director kinematics on the unit sphere S^2 (theory.md §7.2, §7.3, §5.4, §10.1; paper Appendix A,
/// eqs. A.1-A.4 and Algorithm 1, after Simo et al.).
///
/// Each director node carries a unit director t and a rotation Lambda (double[3][3], row-major,
/// L[i][j] = row i, column j) with Lambda E3 = t. Lambda-bar = [Lambda E1, Lambda E2] (first two
/// columns, 3x2) maps the material 2-vector increments/velocities T in R^2 to spatial vectors tangent
/// to S^2 at t. Director forces g (3-vectors) are projected to the material 2-vector by Lambda-bar^T.
///
/// Pure point functions usable inside Kokkos kernels: plain arrays, no std containers, no exceptions,
/// no allocation. All functions that write outputs are alias-safe (an output may be the same array as
/// an input of the same shape).
#include <Kokkos_Macros.hpp>
#include <cmath>

#include "shellfrac/disc/small_tensor.hpp"

namespace shellfrac::disc {

/// Below this rotation angle update_director is the identity (Algorithm 1 step 2 early exit, theory.md §7.3).
constexpr double director_zero_angle = 1e-300;
/// Below this rotation angle the trigonometric ratios use their Taylor series (theory.md §7.3).
constexpr double director_series_angle = 1e-4;

/// Initial rotation Lambda^0 with Lambda^0 E3 = t0 (paper eq. A.1, theory.md §7.2): Rodrigues' formula
///   Lambda = (t0.E3) 1 + hat(E3 x t0) + (E3 x t0) (x) (E3 x t0) / (1 + t0.E3),
/// i.e. the rotation by the angle phi (cos phi = c = t0.E3, sin phi = |a|) about the axis a = E3 x t0.
/// t0 must be a unit vector.
///
/// Evaluated in the algebraically identical, singularity-free form
///   Lambda = c 1 + hat(a) + (1 - c) a_hat (x) a_hat,   a_hat = a / |a|,
/// using a (x) a / (1 + c) = (1 - c) a_hat (x) a_hat for unit t0 (|a|^2 = 1 - c^2); 1 - c is evaluated as
/// |a|^2 / (1 + c) when c >= 0 (no cancellation). Note a = (-t0_2, t0_1, 0) is exact in floating point,
/// so Lambda E3 = (t0_1, t0_2, c) = t0 holds exactly, even arbitrarily close to t0 = -E3.
/// Singular case (|a| = 0 up to underflow, i.e. t0 = +-E3): a_hat := E1. For t0 = -E3 this gives
/// diag(1, -1, -1), the rotation by pi about E1 (theory.md §7.2). (A threshold such as
/// t0.E3 < -1 + 1e-12 is not needed: the form above stays accurate up to t0 = -E3 itself, and using
/// diag(1,-1,-1) within the threshold would give |Lambda E3 - t0| up to ~1.4e-6.)
KOKKOS_INLINE_FUNCTION void initial_rotation(const double t0[3], double L[3][3]) {
  const double c = t0[2];
  const double a[3] = {-t0[1], t0[0], 0.0};  // E3 x t0
  const double a2 = a[0] * a[0] + a[1] * a[1];
  double ah[3] = {1.0, 0.0, 0.0};  // singular-case axis E1
  if (a2 > 1e-200) {
    const double na = std::sqrt(a2);
    ah[0] = a[0] / na, ah[1] = a[1] / na;
  }
  const double omc = (c >= 0.0) ? a2 / (1.0 + c) : 1.0 - c;  // 1 - c
  double A[3][3];
  skew33(a, A);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L[i][j] = (i == j ? c : 0.0) + A[i][j] + omc * ah[i] * ah[j];
}

/// out = Lambda-bar T = T_1 Lambda E1 + T_2 Lambda E2 (theory.md §5.4, §7.3 step 1; paper after eq. 38).
KOKKOS_INLINE_FUNCTION void lambda_bar_times(const double L[3][3], const double T[2], double out[3]) {
  const double T0 = T[0], T1 = T[1];
  for (int i = 0; i < 3; ++i) out[i] = L[i][0] * T0 + L[i][1] * T1;
}

/// out = Lambda-bar^T g = (g . Lambda E1, g . Lambda E2) (theory.md §5.4: f_T = Lambda-bar^T g;
/// §10.1: constraint vector d = Lambda-bar^T s).
KOKKOS_INLINE_FUNCTION void lambda_bar_transpose_times(const double L[3][3], const double g[3], double out[2]) {
  const double o0 = L[0][0] * g[0] + L[1][0] * g[1] + L[2][0] * g[2];
  const double o1 = L[0][1] * g[0] + L[1][1] * g[1] + L[2][1] * g[2];
  out[0] = o0, out[1] = o1;
}

/// Director update by the exponential map on S^2 (paper Algorithm 1, eqs. A.2-A.4; theory.md §7.3):
///   1. dt = Lambda-bar_n dT,  th = |dt|                      (spatial increment, tangent at t_n)
///   2. th < 1e-300: t_{n+1} = t_n, Lambda_{n+1} = Lambda_n  (early exit)
///      t_{n+1} = cos(th) t_n + (sin(th)/th) dt                                           (A.2)
///   3. k = t_n x dt,  dLambda = cos(th) 1 + (sin(th)/th) hat(k) + ((1-cos th)/th^2) k (x) k  (A.3)
///   4. Lambda_{n+1} = dLambda Lambda_n                                                    (A.4)
/// For th < 1e-4: sin(th)/th = 1 - th^2/6, (1-cos th)/th^2 = 1/2 - th^2/24 (series, theory.md §7.3).
/// For th >= 1e-4, (1-cos th)/th^2 is evaluated as 2 (sin(th/2)/th)^2 (no cancellation).
/// dLambda is the rotation by th about k/th: it maps t_n to t_{n+1} and parallel-transports tangent
/// vectors along the geodesic, so the material 2-vector Tdot needs no transformation.
/// Never add increments to t directly. Alias-safe: t_np1 may be t_n and L_np1 may be L_n.
KOKKOS_INLINE_FUNCTION void update_director(const double t_n[3], const double L_n[3][3], const double dT[2],
                                            double t_np1[3], double L_np1[3][3]) {
  double dt[3];
  lambda_bar_times(L_n, dT, dt);
  const double th = norm3(dt);
  if (th < director_zero_angle) {
    if (t_np1 != t_n) copy3(t_n, t_np1);
    if (L_np1 != L_n) copy33(L_n, L_np1);
    return;
  }
  const double c = std::cos(th);
  double s, c2;  // sin(th)/th, (1 - cos th)/th^2
  if (th < director_series_angle) {
    const double th2 = th * th;
    s = 1.0 - th2 / 6.0;
    c2 = 0.5 - th2 / 24.0;
  } else {
    s = std::sin(th) / th;
    const double h = std::sin(0.5 * th) / th;
    c2 = 2.0 * h * h;
  }
  double k[3];
  cross3(t_n, dt, k);
  // (A.3)
  double dL[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dL[i][j] = (i == j ? c : 0.0) + c2 * k[i] * k[j];
  dL[0][1] -= s * k[2], dL[0][2] += s * k[1];
  dL[1][0] += s * k[2], dL[1][2] -= s * k[0];
  dL[2][0] -= s * k[1], dL[2][1] += s * k[0];
  // (A.2)
  const double t0 = c * t_n[0] + s * dt[0];
  const double t1 = c * t_n[1] + s * dt[1];
  const double t2 = c * t_n[2] + s * dt[2];
  // (A.4)
  mat_mat(dL, L_n, L_np1);
  t_np1[0] = t0, t_np1[1] = t1, t_np1[2] = t2;
}

/// T <- T - (d . T) d / |d|^2 (no-op if |d| = 0): removes the component of the material 2-vector T along
/// d. Used for director constraints (theory.md §10.1): symmetry plane with unit normal s, d = Lambda-bar^T s;
/// hard simple support with edge tangent tau, d = Lambda-bar^T tau. Apply to Tdot, Tddot and dT.
KOKKOS_INLINE_FUNCTION void project_out(double T[2], const double d[2]) {
  const double dd = d[0] * d[0] + d[1] * d[1];
  if (!(dd > 0.0)) return;
  const double f = (d[0] * T[0] + d[1] * T[1]) / dd;
  T[0] -= f * d[0];
  T[1] -= f * d[1];
}

/// Optional hygiene for very long runs (theory.md §7.3; the solver does not need it): Gram-Schmidt on the
/// columns keeping the direction of column 3 (the director): e3 = c3/|c3|, e1 = normalize(c1 - (c1.e3) e3),
/// e2 = e3 x e1 (right-handed, det = +1). The caller may then set t = Lambda E3.
KOKKOS_INLINE_FUNCTION void reorthonormalize(double L[3][3]) {
  double e1[3], e2[3], e3[3];
  column33(L, 2, e3);
  normalize3(e3);
  column33(L, 0, e1);
  axpy3(-dot3(e1, e3), e3, e1);
  normalize3(e1);
  cross3(e3, e1, e2);
  set_column33(L, 0, e1);
  set_column33(L, 1, e2);
  set_column33(L, 2, e3);
}

}  // namespace shellfrac::disc
