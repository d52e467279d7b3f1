// Director kinematics (director.hpp, small_tensor.hpp): theory.md §7.2, §7.3, §5.4, §10.1; paper
// Appendix A, eqs. A.1-A.4 (Algorithm 1).
// References used below:
//  * SO(3): Lambda^T Lambda = 1, det Lambda = +1; Lambda E3 = t (definition of the director frame, §7.2).
//  * Exponential map on S^2 along a great circle: exp_t(s v) is the geodesic, so n steps of angle th along
//    the parallel-transported material direction equal one step of angle n th (closed-form A.2/A.3).
//  * Long-double evaluation of A.2-A.4 (direct trigonometric formulas) as the reference near the
//    series switch th = 1e-4.
//  * Parallel transport: dLambda maps tangent vectors at t_n to tangent vectors at t_{n+1}, and the
//    transported increment equals the geodesic velocity d/ds exp(s dt)|_{s=1} = -th sin(th) t_n + cos(th) dt.
//  * Orthogonal projection in R^2: (T - (d.T) d/|d|^2) . d = 0, P^2 = P.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/small_tensor.hpp"

using namespace shellfrac::disc;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Rng {
  std::mt19937_64 gen;
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uni{0.0, 1.0};
  explicit Rng(unsigned long long seed) : gen(seed) {}
  void unit3(double v[3]) {
    do {
      for (int i = 0; i < 3; ++i) v[i] = normal(gen);
    } while (norm3(v) < 1e-3);
    normalize3(v);
  }
  void unit2(double v[2]) {
    double n = 0;
    do {
      v[0] = normal(gen), v[1] = normal(gen);
      n = std::sqrt(v[0] * v[0] + v[1] * v[1]);
    } while (n < 1e-3);
    v[0] /= n, v[1] /= n;
  }
  double u() { return uni(gen); }
};

// max_ij |(L^T L - 1)_ij|
double orthonormality_error(const double L[3][3]) {
  double LtL[3][3];
  mat_t_mat(L, L, LtL);
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e = std::max(e, std::abs(LtL[i][j] - (i == j ? 1.0 : 0.0)));
  return e;
}

// max_i |(L E3)_i - t_i|
double director_error(const double L[3][3], const double t[3]) {
  double e = 0;
  for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(L[i][2] - t[i]));
  return e;
}

double max_diff3(const double a[3], const double b[3]) {
  double e = 0;
  for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

double max_diff33(const double A[3][3], const double B[3][3]) {
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e = std::max(e, std::abs(A[i][j] - B[i][j]));
  return e;
}

// Paper eq. A.1 evaluated literally (reference away from t0 = -E3).
void initial_rotation_literal(const double t0[3], double L[3][3]) {
  const double E3[3] = {0, 0, 1};
  double a[3], A[3][3];
  cross3(E3, t0, a);
  skew33(a, A);
  const double c = dot3(t0, E3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L[i][j] = (i == j ? c : 0.0) + A[i][j] + a[i] * a[j] / (1.0 + c);
}

// Paper A.2-A.4 in long double with the direct trigonometric ratios ((1-cos)/th^2 = 2 sin^2(th/2)/th^2).
void update_director_ld(const double t_n[3], const double L_n[3][3], const double dT[2], long double t[3],
                        long double L[3][3]) {
  long double dt[3], k[3];
  for (int i = 0; i < 3; ++i) dt[i] = (long double)L_n[i][0] * dT[0] + (long double)L_n[i][1] * dT[1];
  const long double th = std::sqrt(dt[0] * dt[0] + dt[1] * dt[1] + dt[2] * dt[2]);
  const long double c = std::cos(th), s = std::sin(th) / th, h = std::sin(th / 2) / th, c2 = 2 * h * h;
  k[0] = t_n[1] * dt[2] - t_n[2] * dt[1];
  k[1] = t_n[2] * dt[0] - t_n[0] * dt[2];
  k[2] = t_n[0] * dt[1] - t_n[1] * dt[0];
  long double dL[3][3] = {{c, -s * k[2], s * k[1]}, {s * k[2], c, -s * k[0]}, {-s * k[1], s * k[0], c}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dL[i][j] += c2 * k[i] * k[j];
  for (int i = 0; i < 3; ++i) t[i] = c * t_n[i] + s * dt[i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      L[i][j] = 0;
      for (int m = 0; m < 3; ++m) L[i][j] += dL[i][m] * L_n[m][j];
    }
}

}  // namespace

// ------------------------------------------------------------------ small_tensor sanity

TEST(SmallTensor, BasicIdentities) {
  // Reference: a x b . a = 0, |a x b|^2 + (a.b)^2 = |a|^2 |b|^2, hat(w) x = w x x, (AB)^T = B^T A^T.
  Rng rng(7);
  for (int n = 0; n < 100; ++n) {
    double a[3], b[3], c[3], W[3][3], Wb[3], A[3][3], B[3][3], AB[3][3], ABt[3][3], BtAt[3][3], At[3][3],
        Bt[3][3];
    for (int i = 0; i < 3; ++i) a[i] = rng.normal(rng.gen), b[i] = rng.normal(rng.gen);
    cross3(a, b, c);
    EXPECT_NEAR(dot3(c, a), 0.0, 1e-14);
    EXPECT_NEAR(norm3_sq(c) + dot3(a, b) * dot3(a, b), norm3_sq(a) * norm3_sq(b), 1e-12);
    skew33(a, W);
    mat_vec(W, b, Wb);
    EXPECT_LT(max_diff3(Wb, c), 1e-14);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A[i][j] = rng.normal(rng.gen), B[i][j] = rng.normal(rng.gen);
    mat_mat(A, B, AB);
    transpose33(AB, ABt);
    transpose33(A, At);
    transpose33(B, Bt);
    mat_mat(Bt, At, BtAt);
    EXPECT_LT(max_diff33(ABt, BtAt), 1e-13);
    // mat_t_vec(A, x) = mat_vec(A^T, x); outer: (a (x) b) c = a (b.c)
    double y1[3], y2[3], O[3][3], Oc[3];
    mat_t_vec(A, a, y1);
    mat_vec(At, a, y2);
    EXPECT_LT(max_diff3(y1, y2), 1e-14);
    outer33(a, b, O);
    mat_vec(O, c, Oc);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(Oc[i], a[i] * dot3(b, c), 1e-13);
    // Alias safety: mat_mat(A, B, A)
    double A2[3][3];
    copy33(A, A2);
    mat_mat(A2, B, A2);
    EXPECT_LT(max_diff33(A2, AB), 1e-15);
  }
  double I[3][3];
  identity33(I);
  EXPECT_EQ(det33(I), 1.0);
}

// ------------------------------------------------------------------ initial rotation (A.1, theory.md §7.2)

TEST(Director, InitialRotationIsRotationMappingE3ToT0) {
  // Reference: SO(3) membership and Lambda E3 = t0 (theory.md §7.2, tolerance 1e-14).
  Rng rng(12345);
  auto check = [](const double t0[3]) {
    double L[3][3];
    initial_rotation(t0, L);
    EXPECT_LT(orthonormality_error(L), 1e-14) << t0[0] << " " << t0[1] << " " << t0[2];
    EXPECT_NEAR(det33(L), 1.0, 1e-14);
    EXPECT_LT(director_error(L, t0), 1e-14);
  };
  for (int n = 0; n < 10000; ++n) {
    double t0[3];
    rng.unit3(t0);
    check(t0);
    // Literal A.1 as reference where it is well conditioned (1 + t0.E3 not small).
    if (t0[2] > -0.5) {
      double L[3][3], Lref[3][3];
      initial_rotation(t0, L);
      initial_rotation_literal(t0, Lref);
      EXPECT_LT(max_diff33(L, Lref), 1e-14);
    }
  }
  const double E3[3] = {0, 0, 1}, mE3[3] = {0, 0, -1};
  check(E3);
  check(mE3);
  {
    // t0 = E3 -> identity; t0 = -E3 -> diag(1, -1, -1) (theory.md §7.2).
    double L[3][3], I[3][3];
    initial_rotation(E3, L);
    identity33(I);
    EXPECT_EQ(max_diff33(L, I), 0.0);
    initial_rotation(mE3, L);
    const double D[3][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    EXPECT_EQ(max_diff33(L, D), 0.0);
  }
  // t0 within 1e-13 (and other tiny distances) of -E3 and of +E3, in random directions.
  for (double eps : {1e-13, 3e-14, 1e-16, 1e-100, 1e-9, 1e-7}) {
    for (int n = 0; n < 200; ++n) {
      double p[2];
      rng.unit2(p);
      for (double sgn : {-1.0, 1.0}) {
        double t0[3] = {eps * p[0], eps * p[1], sgn};
        normalize3(t0);
        check(t0);
      }
    }
  }
}

// ------------------------------------------------------------------ update (Algorithm 1, A.2-A.4)

TEST(Director, LongRandomSequenceStaysOnSphereAndInSO3) {
  // Reference: |t| = 1, Lambda in SO(3), Lambda E3 = t after 1e5 large random increments (|dT| up to pi),
  // without re-orthonormalization (theory.md §7.3).
  Rng rng(2024);
  double t[3], L[3][3];
  rng.unit3(t);
  initial_rotation(t, L);
  double max_norm_err = 0, max_orth = 0, max_dir = 0;
  for (int n = 0; n < 100000; ++n) {
    double dT[2];
    rng.unit2(dT);
    const double mag = kPi * rng.u();
    dT[0] *= mag, dT[1] *= mag;
    update_director(t, L, dT, t, L);  // in place (alias-safe)
    if (n % 1000 == 999 || n == 99999) {
      max_norm_err = std::max(max_norm_err, std::abs(norm3(t) - 1.0));
      max_orth = std::max(max_orth, orthonormality_error(L));
      max_dir = std::max(max_dir, director_error(L, t));
    }
  }
  EXPECT_LT(max_norm_err, 1e-12);
  EXPECT_LT(max_orth, 1e-11);
  EXPECT_LT(max_dir, 1e-11);
  EXPECT_NEAR(det33(L), 1.0, 1e-11);
  std::printf("after 1e5 steps: ||t|-1| = %.2e, |L^T L - 1| = %.2e, |L E3 - t| = %.2e\n", max_norm_err, max_orth,
              max_dir);
}

TEST(Director, ZeroIncrementIsIdentity) {
  // Reference: Algorithm 1 step 2 early exit (th < 1e-300).
  Rng rng(3);
  double t[3], L[3][3], t1[3], L1[3][3];
  rng.unit3(t);
  initial_rotation(t, L);
  const double z[2] = {0.0, 0.0};
  update_director(t, L, z, t1, L1);
  EXPECT_EQ(max_diff3(t, t1), 0.0);
  EXPECT_EQ(max_diff33(L, L1), 0.0);
  const double tiny[2] = {1e-310, 0.0};
  update_director(t, L, tiny, t1, L1);
  EXPECT_EQ(max_diff3(t, t1), 0.0);
  EXPECT_EQ(max_diff33(L, L1), 0.0);
}

TEST(Director, GeodesicExactness) {
  // Reference: exponential-map property along a great circle: n updates by the fixed material increment
  // dT (|dT| = th) equal one update by n dT (angle n th), because the material direction is parallel-
  // transported along the geodesic it generates (theory.md §7.3).
  Rng rng(99);
  const int ns[] = {2, 10, 100, 7};
  const double ths[] = {0.9, 0.3, 0.05, 1.2};  // 7 * 1.2 > 2 pi: wraps around the great circle
  for (int trial = 0; trial < 50; ++trial)
    for (int c = 0; c < 4; ++c) {
      const int n = ns[c];
      const double th = ths[c];
      double t0[3], L0[3][3], dir[2];
      rng.unit3(t0);
      initial_rotation(t0, L0);
      rng.unit2(dir);
      const double dT[2] = {th * dir[0], th * dir[1]}, dTn[2] = {n * th * dir[0], n * th * dir[1]};
      double t[3], L[3][3], t1[3], L1[3][3];
      copy3(t0, t);
      copy33(L0, L);
      for (int k = 0; k < n; ++k) update_director(t, L, dT, t, L);
      update_director(t0, L0, dTn, t1, L1);
      EXPECT_LT(max_diff3(t, t1), 1e-12) << "n " << n << " th " << th;
      EXPECT_LT(max_diff33(L, L1), 1e-12) << "n " << n << " th " << th;
    }
}

TEST(Director, SmallAngleBranchContinuity) {
  // Reference: long-double evaluation of A.2-A.4 with direct trigonometric ratios. Results just below
  // (series branch) and just above (trigonometric branch) th = 1e-4 must both agree with it to 1e-15
  // relative (the entries of t and Lambda are O(1): |t| = 1, columns of Lambda are unit vectors).
  Rng rng(4242);
  const double ths[] = {1e-4 * (1 - 1e-12), 1e-4 * (1 + 1e-12), 0.999e-4, 1.001e-4, 0.5e-4, 2e-4, 1e-6, 1e-3};
  double worst = 0;
  for (int trial = 0; trial < 2000; ++trial)
    for (double th : ths) {
      double t0[3], L0[3][3], dir[2];
      rng.unit3(t0);
      initial_rotation(t0, L0);
      rng.unit2(dir);
      const double dT[2] = {th * dir[0], th * dir[1]};
      double t[3], L[3][3];
      long double tr[3], Lr[3][3];
      update_director(t0, L0, dT, t, L);
      update_director_ld(t0, L0, dT, tr, Lr);
      double e = 0;
      for (int i = 0; i < 3; ++i) {
        e = std::max(e, (double)std::abs((long double)t[i] - tr[i]));
        for (int j = 0; j < 3; ++j) e = std::max(e, (double)std::abs((long double)L[i][j] - Lr[i][j]));
      }
      worst = std::max(worst, e);
      EXPECT_LT(e, 1e-15) << "th = " << th;
    }
  // The two branches, applied to the same state with angles 1e-4 (1 -+ 1e-12), must agree to 1e-15
  // (the exact results differ by ~1e-16).
  for (int trial = 0; trial < 1000; ++trial) {
    double t0[3], L0[3][3], dir[2];
    rng.unit3(t0);
    initial_rotation(t0, L0);
    rng.unit2(dir);
    const double a = 1e-4 * (1 - 1e-12), b = 1e-4 * (1 + 1e-12);
    const double dTa[2] = {a * dir[0], a * dir[1]}, dTb[2] = {b * dir[0], b * dir[1]};
    double ta[3], La[3][3], tb[3], Lb[3][3];
    update_director(t0, L0, dTa, ta, La);
    update_director(t0, L0, dTb, tb, Lb);
    EXPECT_LT(max_diff3(ta, tb), 1e-15);
    EXPECT_LT(max_diff33(La, Lb), 1e-15);
  }
  std::printf("small-angle branch: worst deviation from long double = %.2e\n", worst);
}

TEST(Director, ParallelTransportKeepsMaterialBasisTangent) {
  // Reference: t_{n+1} . (Lambda-bar_{n+1} T) = 0 for every T (Lambda-bar spans the tangent plane), and the
  // transported increment Lambda-bar_{n+1} dT equals the geodesic velocity -th sin(th) t_n + cos(th) dt_n
  // (so Tdot needs no transformation, theory.md §7.3).
  Rng rng(777);
  double t[3], L[3][3];
  rng.unit3(t);
  initial_rotation(t, L);
  for (int n = 0; n < 5000; ++n) {
    double dT[2];
    rng.unit2(dT);
    const double th = (n % 3 == 0 ? 1e-5 : kPi) * rng.u();
    dT[0] *= th, dT[1] *= th;
    double dt[3], tn[3];
    copy3(t, tn);
    lambda_bar_times(L, dT, dt);
    update_director(t, L, dT, t, L);
    for (int k = 0; k < 3; ++k) {
      double T[2], v[3];
      rng.unit2(T);
      lambda_bar_times(L, T, v);
      EXPECT_NEAR(dot3(t, v), 0.0, 1e-13);
      EXPECT_NEAR(norm3(v), 1.0, 1e-13);
    }
    double v[3], vel[3];
    lambda_bar_times(L, dT, v);
    for (int i = 0; i < 3; ++i) vel[i] = -th * std::sin(th) * tn[i] + std::cos(th) * dt[i];
    EXPECT_LT(max_diff3(v, vel), 1e-13 * (1.0 + th));  // |v| = th <= pi
  }
}

TEST(Director, LambdaBarTransposeIsAdjoint) {
  // Reference: g . (Lambda-bar T) = (Lambda-bar^T g) . T (theory.md §5.4 force projection is the adjoint
  // of the velocity map); Lambda-bar^T t = 0 (drilling/normal component is powerless).
  Rng rng(5);
  for (int n = 0; n < 1000; ++n) {
    double t[3], L[3][3], g[3], T[2], v[3], f[2];
    rng.unit3(t);
    initial_rotation(t, L);
    for (int i = 0; i < 3; ++i) g[i] = rng.normal(rng.gen);
    T[0] = rng.normal(rng.gen), T[1] = rng.normal(rng.gen);
    lambda_bar_times(L, T, v);
    lambda_bar_transpose_times(L, g, f);
    EXPECT_NEAR(dot3(g, v), f[0] * T[0] + f[1] * T[1], 1e-13);
    lambda_bar_transpose_times(L, t, f);
    EXPECT_NEAR(f[0], 0.0, 1e-15);
    EXPECT_NEAR(f[1], 0.0, 1e-15);
  }
}

// ------------------------------------------------------------------ constraints (theory.md §10.1)

TEST(Director, ProjectOutIsOrthogonalIdempotentProjection) {
  // Reference: P T = T - (d.T) d/|d|^2 is the orthogonal projector onto d-perp: (P T).d = 0, P P = P,
  // and P = identity for d = 0.
  Rng rng(31);
  for (int n = 0; n < 10000; ++n) {
    double T[2] = {rng.normal(rng.gen), rng.normal(rng.gen)};
    const double scale = std::pow(10.0, 6 * rng.u() - 3);
    const double d[2] = {scale * rng.normal(rng.gen), scale * rng.normal(rng.gen)};
    const double nT = std::sqrt(T[0] * T[0] + T[1] * T[1]), nd = std::sqrt(d[0] * d[0] + d[1] * d[1]);
    project_out(T, d);
    EXPECT_NEAR((T[0] * d[0] + T[1] * d[1]) / (nT * nd), 0.0, 1e-15);
    const double P1[2] = {T[0], T[1]};
    project_out(T, d);
    EXPECT_NEAR(T[0], P1[0], 1e-15 * nT);
    EXPECT_NEAR(T[1], P1[1], 1e-15 * nT);
  }
  double T[2] = {1.5, -2.0};
  const double z[2] = {0.0, 0.0};
  project_out(T, z);
  EXPECT_EQ(T[0], 1.5);
  EXPECT_EQ(T[1], -2.0);
}

TEST(Director, SymmetryPlaneConstraintKeepsDirectorInPlane) {
  // Reference: theory.md §10.1 symmetry plane with normal s: with t0.s = 0 and d = Lambda-bar^T s projected
  // out of dT, the exponential map keeps t.s = 0 (t_{n+1} combines t_n and dt_s, both perpendicular to s).
  Rng rng(8);
  const double s[3] = {0.0, 1.0, 0.0};
  double t[3] = {0.3, 0.0, 0.8};
  normalize3(t);
  double L[3][3];
  initial_rotation(t, L);
  double worst = 0;
  for (int n = 0; n < 10000; ++n) {
    double dT[2], d[2];
    rng.unit2(dT);
    const double th = 2.0 * rng.u();
    dT[0] *= th, dT[1] *= th;
    lambda_bar_transpose_times(L, s, d);
    project_out(dT, d);
    update_director(t, L, dT, t, L);
    worst = std::max(worst, std::abs(dot3(t, s)));
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(Director, ReorthonormalizeRestoresSO3AndKeepsDirector) {
  // Reference: Gram-Schmidt with column 3 first yields SO(3) with column 3 parallel to the input column 3.
  Rng rng(55);
  for (int n = 0; n < 1000; ++n) {
    double t[3], L[3][3];
    rng.unit3(t);
    initial_rotation(t, L);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) L[i][j] += 1e-6 * rng.normal(rng.gen);
    double c3[3];
    column33(L, 2, c3);
    normalize3(c3);
    reorthonormalize(L);
    EXPECT_LT(orthonormality_error(L), 1e-15 * 4);
    EXPECT_NEAR(det33(L), 1.0, 1e-14);
    EXPECT_LT(director_error(L, c3), 1e-15);
  }
}
