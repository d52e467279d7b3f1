// Extrinsic resultant cohesive law (theory.md §9.1-9.3, §9.5 step 2, §9.7; Talamini & Radovitzky, the paper,
// §3, eqs. 19-31). References used below (derived by hand from the paper's equations):
//  * derived constants (paper §3.1): S0 = h sigma_c, k = h sigma_c^2/(2 Gamma), delta_f = S0/k = 2 Gamma/sigma_c;
//    for the beam-blast material of paper Table 3 with Gamma = 10e3 (h = 6.53e-3, sigma_c = 375e6):
//    S0 = 2.44875e6, k = 4.59140625e10, delta_f = 5.3333...e-5 (exact decimal arithmetic);
//  * gradient (eq. 17 with eq. 24): phi = 1/2 S(delta_max) delta^2/delta_max is a quadratic form in the jumps at
//    fixed delta_max, so a central difference of phi is exact up to round-off (~eps phi/step);
//  * single-mode loading (eq. 20, 22, 23; delta = delta_max on monotone loading, s = S(delta)/delta):
//      [[phi]] = d nu           : delta = |d|,          n_c = sign(d) S(delta) nu
//      [[phi]] = d e (e _|_ nu) : delta = alpha1 d,     n_c = alpha1 S(delta) e          (in-plane or transverse)
//      [[t]]   = th nu          : delta = alpha2 h th,  m_c = alpha2 h S(delta) nu       (bending)
//      [[t]]   = th e (e _|_ nu): delta = alpha3 h th,  m_c = alpha3 h S(delta) e        (twist / transverse)
//    and the other traction is 0; complete separation at delta = delta_f in each mode;
//  * unloading at fixed delta_max: tractions linear in the jumps, phi quadratic, D = 1/2 S0 delta_max constant;
//  * work identity (eq. 13 with equality, eq. 18, 26): d(phi + D) = n_c.d[[phi]] + m_c.d[[t]] along any path,
//    D = 1/2 S0 min(delta_max, delta_f), = Gamma h at separation. With the trapezoidal work sum, the first
//    increment from the rigid state (traction 0 at delta_max = 0, S(delta_1) after it) misses exactly
//    1/2 S0 delta_1 (trapezoid 1/2 S(delta_1) delta_1 vs phi + D = 1/2 S(delta_1) delta_1 + 1/2 S0 delta_1);
//    radial loading (S linear in delta, delta linear in the path parameter) and unloading (tractions linear in
//    the jumps) are integrated exactly by the trapezoid; the remaining defect is O(increment^2);
//  * consistency (eq. 29 vs eqs. 22-23): equivalent_traction(n_c, m_c) = s delta = S(delta_max) delta/delta_max;
//    pure membrane tension n = sigma h nu gives n_eq = sigma h (theory.md §9.5).
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "shellfrac/materials/cohesive_law.hpp"

using shellfrac::materials::cohesive_strength;
using shellfrac::materials::cohesive_tractions;
using shellfrac::materials::CohesiveParams;
using shellfrac::materials::CohesiveResult;
using shellfrac::materials::effective_opening;
using shellfrac::materials::equivalent_traction;
using shellfrac::materials::make_cohesive_params;
using shellfrac::materials::starting_energy_released;
using shellfrac::materials::crack_face_contact;

namespace {

// The paper's Table 3 (beam blast, Al 6061-T6) with a non-zero Gamma = 10 kJ/m^2 (the paper uses Gamma = 0 there).
CohesiveParams beam_blast(double Gamma = 10e3) { return make_cohesive_params(6.53e-3, 375e6, Gamma); }
// The paper's Table 2 (mode III tearing): h = 2 mm, sigma_c = 325 MPa, Gamma = 0.75 Y0 h with Y0 = 320 MPa.
CohesiveParams tearing(double a1 = 1, double a2 = 1, double a3 = 1) {
  return make_cohesive_params(2e-3, 325e6, 0.75 * 320e6 * 2e-3, a1, a2, a3);
}
// Table 2 with distinct eq. 20 weights, so that every alpha is visible in the results.
CohesiveParams weighted() { return tearing(0.7, 1.3, 0.5); }

double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm3(const double a[3]) { return std::sqrt(dot3(a, a)); }
double diff3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}
void cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
void normalize3(double a[3]) {
  const double l = norm3(a);
  for (int i = 0; i < 3; ++i) a[i] /= l;
}

struct Rng {
  std::mt19937_64 gen;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  explicit Rng(unsigned seed) : gen(seed) {}
  double operator()() { return u(gen); }
  double uniform(double a, double b) { return a + 0.5 * (u(gen) + 1.0) * (b - a); }
  void vec(double x[3], double scale) {
    for (int k = 0; k < 3; ++k) x[k] = scale * (*this)();
  }
};

/// Random orthonormal frame: nu (co-normal), e1 (in-plane tangent), e2 (transverse, nu ^ e1).
struct Frame {
  double nu[3], e1[3], e2[3];
};
Frame random_frame(Rng& rng) {
  Frame f{};
  double r[3];
  do {
    rng.vec(f.nu, 1.0);
  } while (norm3(f.nu) < 0.1);
  normalize3(f.nu);
  do {
    rng.vec(r, 1.0);
    cross3(f.nu, r, f.e1);
  } while (norm3(f.e1) < 0.1);
  normalize3(f.e1);
  cross3(f.nu, f.e1, f.e2);
  return f;
}

/// phi(jumps; delta_max) = 1/2 S(delta_max) delta^2/delta_max at FIXED delta_max (eq. 24), written from
/// effective_opening and cohesive_strength.
double phi_fixed(const CohesiveParams& p, const double jphi[3], const double jt[3], const double nu[3], double dmax) {
  const double d = effective_opening(p, jphi, jt, nu);
  return 0.5 * cohesive_strength(p, dmax) * d * d / dmax;
}

/// Random mixed-mode jumps with effective opening exactly `delta` (all four modes active).
void random_jumps(Rng& rng, const CohesiveParams& p, const double nu[3], double delta, double jphi[3], double jt[3]) {
  rng.vec(jphi, 1.0);
  rng.vec(jt, 1.0 / p.h);
  const double d = effective_opening(p, jphi, jt, nu);
  for (int i = 0; i < 3; ++i) {
    jphi[i] *= delta / d;
    jt[i] *= delta / d;
  }
}

/// One cohesive evaluation on a copy of delta_max (returns the copy through dmax_out).
CohesiveResult eval(const CohesiveParams& p, const double jphi[3], const double jt[3], const double nu[3],
                    double dmax_in, double n_c[3], double m_c[3], double* dmax_out = nullptr) {
  double dmax = dmax_in;
  const CohesiveResult r = cohesive_tractions(p, jphi, jt, nu, dmax, n_c, m_c);
  if (dmax_out) *dmax_out = dmax;
  return r;
}

// (Test 1) Derived constants and the strength function S(delta_max) = max(S0 - k delta_max, 0) (eq. 24/25).
// References: hand values of Table 3 (Gamma = 10e3) to 1e-15 relative; S0/k = delta_f to 1e-15; S(0) = S0 and
// S(delta_f) = 0 exactly; S(delta_f/2) = S0/2 and linearity on random points to 1e-13 S0; S = 0 beyond delta_f.
// Also eq. 20 written component-wise in an orthonormal frame (nu, e1, e2) to 1e-14 relative.
TEST(CohesiveLaw, DerivedConstantsAndStrength) {
  {
    const CohesiveParams p = beam_blast();
    EXPECT_NEAR(p.S0, 2.44875e6, 1e-15 * 2.44875e6);
    EXPECT_NEAR(p.k, 4.59140625e10, 1e-15 * 4.59140625e10);
    EXPECT_NEAR(p.delta_f, 2e4 / 375e6, 1e-15 * p.delta_f);
    EXPECT_NEAR(p.delta_f, 5.333333333333333e-5, 1e-15 * p.delta_f);
    EXPECT_EQ(p.h, 6.53e-3);
    EXPECT_EQ(p.sigma_c, 375e6);
    EXPECT_EQ(p.Gamma, 10e3);
    EXPECT_EQ(p.alpha1, 1.0);
    EXPECT_EQ(p.alpha2, 1.0);
    EXPECT_EQ(p.alpha3, 1.0);
  }
  Rng rng(1);
  for (const CohesiveParams& p : {beam_blast(), tearing(), weighted()}) {
    EXPECT_NEAR(p.S0, p.h * p.sigma_c, 1e-15 * p.S0);
    EXPECT_NEAR(p.k, p.h * p.sigma_c * p.sigma_c / (2.0 * p.Gamma), 1e-15 * p.k);
    EXPECT_NEAR(p.delta_f, 2.0 * p.Gamma / p.sigma_c, 1e-15 * p.delta_f);
    EXPECT_NEAR(p.S0 / p.k, p.delta_f, 1e-15 * p.delta_f);
    EXPECT_NEAR(0.5 * p.S0 * p.delta_f, p.Gamma * p.h, 1e-15 * p.Gamma * p.h);  // area under S = Gamma h
    EXPECT_EQ(cohesive_strength(p, 0.0), p.S0);
    EXPECT_EQ(cohesive_strength(p, p.delta_f), 0.0);
    EXPECT_EQ(cohesive_strength(p, 1.5 * p.delta_f), 0.0);
    EXPECT_EQ(cohesive_strength(p, 1e6 * p.delta_f), 0.0);
    EXPECT_NEAR(cohesive_strength(p, 0.5 * p.delta_f), 0.5 * p.S0, 1e-13 * p.S0);
    EXPECT_GE(cohesive_strength(p, p.delta_f * (1.0 - 1e-15)), 0.0);
    for (int t = 0; t < 20; ++t) {
      const double x = rng.uniform(0.0, 1.0) * p.delta_f, y = rng.uniform(0.0, 1.0) * p.delta_f, a = rng.uniform(0, 1);
      EXPECT_NEAR(cohesive_strength(p, a * x + (1 - a) * y),
                  a * cohesive_strength(p, x) + (1 - a) * cohesive_strength(p, y), 1e-13 * p.S0);
      EXPECT_NEAR(cohesive_strength(p, x), p.S0 * (1.0 - x / p.delta_f), 1e-13 * p.S0);
    }
    // eq. 20 in a frame: [[phi]] = a nu + b e1 + c e2, [[t]] = d nu + e e1 + f e2.
    for (int t = 0; t < 20; ++t) {
      const Frame fr = random_frame(rng);
      const double a = rng(), b = rng(), c = rng(), d = rng() / p.h, e = rng() / p.h, f = rng() / p.h;
      double jphi[3], jt[3];
      for (int i = 0; i < 3; ++i) {
        jphi[i] = a * fr.nu[i] + b * fr.e1[i] + c * fr.e2[i];
        jt[i] = d * fr.nu[i] + e * fr.e1[i] + f * fr.e2[i];
      }
      const double h = p.h, a1 = p.alpha1, a2 = p.alpha2, a3 = p.alpha3;
      const double ref = std::sqrt(a * a + a1 * a1 * (b * b + c * c) + a2 * a2 * h * h * d * d +
                                   a3 * a3 * h * h * (e * e + f * f));
      EXPECT_NEAR(effective_opening(p, jphi, jt, fr.nu), ref, 1e-14 * ref);
      // flipping nu (the other side's co-normal) leaves delta unchanged
      const double mnu[3] = {-fr.nu[0], -fr.nu[1], -fr.nu[2]};
      EXPECT_NEAR(effective_opening(p, jphi, jt, mnu), ref, 1e-14 * ref);
    }
  }
}

// (Test 2) The tractions are the gradient of the free energy at fixed delta_max (eq. 17 + eq. 24):
// n_c_i = d phi/d [[phi]]_i, m_c_i = d phi/d [[t]]_i. Central differences of phi_fixed (step 1e-4 of the
// natural scale: delta_max for [[phi]], delta_max/h for [[t]]) on random mixed-mode jumps, random unit nu, in
// unloading states (delta < delta_max) and loading states (delta = delta_max after the in-place update).
// Reference: exact gradient of a quadratic form (central difference exact up to round-off ~1e-12);
// tolerance 1e-7 of the traction magnitude |n_c| (resp. |m_c|) per component. The returned stored energy
// equals phi_fixed to 1e-13 relative.
TEST(CohesiveLaw, TractionsAreGradientOfFreeEnergy) {
  Rng rng(2);
  double worst = 0.0;
  for (const CohesiveParams& p : {beam_blast(), weighted()}) {
    for (int t = 0; t < 40; ++t) {
      const Frame fr = random_frame(rng);
      const bool loading = t % 2 == 1;
      const double dmax0 = rng.uniform(0.05, 0.95) * p.delta_f;
      const double delta = loading ? dmax0 : rng.uniform(0.1, 0.95) * dmax0;
      double jphi[3], jt[3], n_c[3], m_c[3], dmax;
      random_jumps(rng, p, fr.nu, delta, jphi, jt);
      const CohesiveResult r = eval(p, jphi, jt, fr.nu, loading ? 0.0 : dmax0, n_c, m_c, &dmax);
      EXPECT_NEAR(dmax, dmax0, 1e-14 * dmax0);
      EXPECT_FALSE(r.separated);
      EXPECT_NEAR(r.stored, phi_fixed(p, jphi, jt, fr.nu, dmax), 1e-13 * r.stored);
      const double nmag = norm3(n_c), mmag = norm3(m_c);
      for (int which = 0; which < 2; ++which) {
        const double step = 1e-4 * dmax * (which == 0 ? 1.0 : 1.0 / p.h);
        for (int i = 0; i < 3; ++i) {
          double a[3] = {jphi[0], jphi[1], jphi[2]}, b[3] = {jt[0], jt[1], jt[2]};
          double* x = which == 0 ? a : b;
          x[i] += step;
          const double fp = phi_fixed(p, a, b, fr.nu, dmax);
          x[i] -= 2.0 * step;
          const double fm = phi_fixed(p, a, b, fr.nu, dmax);
          const double fd = (fp - fm) / (2.0 * step);
          const double exact = which == 0 ? n_c[i] : m_c[i];
          const double scale = which == 0 ? nmag : mmag;
          EXPECT_NEAR(fd, exact, 1e-7 * scale) << "loading " << loading << " which " << which << " i " << i;
          worst = std::max(worst, std::fabs(fd - exact) / scale);
        }
      }
    }
  }
  std::printf("[gradient] max |FD - traction| / |traction| = %.3g\n", worst);
}

// (Test 3) Monotone single-mode loading through complete separation, for the weighted Table 2 law
// (alpha = 0.7, 1.3, 0.5), in a random frame (nu, e1 in-plane tangent, e2 transverse). Reference: the
// closed forms of the file header (delta = |d|, alpha1 d, alpha2 h th, alpha3 h th; |traction| = S(delta),
// alpha1 S(delta), alpha2 h S(delta), alpha3 h S(delta)); tolerance 1e-12 of S0 (resp. h S0) per vector,
// delta_max to 1e-14 relative; separated exactly when delta >= delta_f (points within 1e-9 delta_f of
// delta_f are not checked for the flag); the other traction is exactly 0.
TEST(CohesiveLaw, SingleModeLoadingPaths) {
  const CohesiveParams p = weighted();
  Rng rng(3);
  const Frame fr = random_frame(rng);
  struct Mode {
    const char* name;
    bool director;     // the jump is in [[t]] (else in [[phi]])
    const double* e;   // direction of the jump
    double weight;     // delta = weight * d
    double sign;       // sign of d
  };
  const double h = p.h;
  const Mode modes[] = {{"opening (mode I)", false, fr.nu, 1.0, 1.0},
                        {"closing (compression)", false, fr.nu, 1.0, -1.0},
                        {"in-plane sliding", false, fr.e1, p.alpha1, 1.0},
                        {"transverse sliding (shear-off)", false, fr.e2, p.alpha1, -1.0},
                        {"bending theta_N", true, fr.nu, p.alpha2 * h, 1.0},
                        {"twist theta_S in-plane", true, fr.e1, p.alpha3 * h, -1.0},
                        {"theta_S transverse", true, fr.e2, p.alpha3 * h, 1.0}};
  const int nsteps = 500;
  for (const Mode& md : modes) {
    double dmax = 0.0;
    const double d_end = 1.25 * p.delta_f / md.weight;
    double D_prev = 0.0;
    for (int j = 1; j <= nsteps; ++j) {
      const double d = md.sign * d_end * j / nsteps;
      double jphi[3] = {0, 0, 0}, jt[3] = {0, 0, 0}, n_c[3], m_c[3];
      for (int i = 0; i < 3; ++i) (md.director ? jt : jphi)[i] = d * md.e[i];
      const CohesiveResult r = cohesive_tractions(p, jphi, jt, fr.nu, dmax, n_c, m_c);
      const double delta = md.weight * std::fabs(d);
      const double S = std::max(p.S0 * (1.0 - delta / p.delta_f), 0.0);
      EXPECT_NEAR(dmax, delta, 1e-14 * delta) << md.name;
      // expected traction: sign(d) * weight * S * e (n_c for [[phi]] modes, m_c for [[t]] modes)
      double ref[3];
      for (int i = 0; i < 3; ++i) ref[i] = md.sign * md.weight * S * md.e[i];
      const double* got = md.director ? m_c : n_c;
      const double* other = md.director ? n_c : m_c;
      EXPECT_LE(diff3(got, ref), 1e-12 * p.S0 * (md.director ? h : 1.0)) << md.name << " step " << j;
      EXPECT_EQ(norm3(other), 0.0) << md.name;
      EXPECT_NEAR(equivalent_traction(p, n_c, m_c, fr.nu), S, 1e-12 * p.S0) << md.name;
      if (std::fabs(delta - p.delta_f) > 1e-9 * p.delta_f) {
        EXPECT_EQ(r.separated, delta >= p.delta_f) << md.name;
      }
      EXPECT_GE(r.dissipated, D_prev);
      D_prev = r.dissipated;
      EXPECT_NEAR(r.dissipated, 0.5 * p.S0 * std::min(delta, p.delta_f), 1e-14 * p.S0 * p.delta_f);
      EXPECT_NEAR(r.stored, 0.5 * S * delta, 1e-13 * p.S0 * p.delta_f);  // loading: phi = 1/2 S delta
    }
    EXPECT_NEAR(dmax, 1.25 * p.delta_f, 1e-14 * p.delta_f);
  }
  std::printf("[modes] delta_f = %.6g m; separation at d = %.6g (N/S), %.6g (theta_N), %.6g (theta_S)\n", p.delta_f,
              p.delta_f / p.alpha1, p.delta_f / (p.alpha2 * h), p.delta_f / (p.alpha3 * h));
}

// (Test 4) Unloading to the origin and reloading (mixed mode, weighted Table 2 and Table 3). Reference: linear
// unloading at fixed delta_max, n_c(lam) = (lam/lam1) n_c(lam1) and phi = (lam/lam1)^2 phi_1 to 1e-13
// relative; stored energy and tractions exactly 0 at the origin; delta_max and D unchanged (bitwise) while
// delta < delta_max, including a non-radial excursion, after which the state at lam1 is recovered to 1e-13
// (reversible); reloading past delta_max: delta_max = delta, equivalent traction = S(delta) (softening,
// strictly decreasing) to 1e-12 S0, D = 1/2 S0 delta to 1e-14.
TEST(CohesiveLaw, UnloadingReloadingToOrigin) {
  Rng rng(4);
  for (const CohesiveParams& p : {weighted(), beam_blast()}) {
    for (int t = 0; t < 5; ++t) {
      const Frame fr = random_frame(rng);
      double J[3], Jt[3];
      random_jumps(rng, p, fr.nu, 1.0, J, Jt);  // delta(lam J) = lam
      const double lam1 = 0.4 * p.delta_f;
      const int N = 200;
      double dmax = 0.0, n1[3], m1[3];
      CohesiveResult r1{};
      auto at = [&](double lam, double n_c[3], double m_c[3]) {
        const double a[3] = {lam * J[0], lam * J[1], lam * J[2]}, b[3] = {lam * Jt[0], lam * Jt[1], lam * Jt[2]};
        return cohesive_tractions(p, a, b, fr.nu, dmax, n_c, m_c);
      };
      for (int j = 1; j <= N; ++j) r1 = at(lam1 * j / N, n1, m1);  // loading
      const double dmax1 = dmax, D1 = r1.dissipated, phi1 = r1.stored;
      EXPECT_NEAR(dmax1, lam1, 1e-14 * lam1);
      EXPECT_NEAR(phi1, 0.5 * cohesive_strength(p, lam1) * lam1, 1e-13 * phi1);
      EXPECT_NEAR(D1, 0.5 * p.S0 * lam1, 1e-14 * D1);
      const double n1m = norm3(n1), m1m = norm3(m1);
      // unloading (radial) to the origin, then reloading to lam1
      for (int pass = 0; pass < 2; ++pass) {
        for (int j = 0; j <= N; ++j) {
          const double lam = pass == 0 ? lam1 * (N - j) / N : lam1 * j / N;
          double n_c[3], m_c[3];
          const CohesiveResult r = at(lam, n_c, m_c);
          EXPECT_EQ(dmax, dmax1);
          EXPECT_EQ(r.dissipated, D1);
          EXPECT_FALSE(r.separated);
          const double q = lam / lam1;
          double nr[3], mr[3];
          for (int i = 0; i < 3; ++i) {
            nr[i] = q * n1[i];
            mr[i] = q * m1[i];
          }
          EXPECT_LE(diff3(n_c, nr), 1e-13 * n1m);
          EXPECT_LE(diff3(m_c, mr), 1e-13 * m1m);
          EXPECT_NEAR(r.stored, q * q * phi1, 1e-13 * phi1);
          EXPECT_NEAR(equivalent_traction(p, n_c, m_c, fr.nu), q * cohesive_strength(p, dmax1), 1e-12 * p.S0);
          if (lam == 0.0) {
            EXPECT_EQ(r.stored, 0.0);
            EXPECT_EQ(norm3(n_c), 0.0);
            EXPECT_EQ(norm3(m_c), 0.0);
          }
        }
      }
      // non-radial excursion inside delta < delta_max, back to lam1 J: same state (reversible)
      {
        double P[3], Pt[3], n_c[3], m_c[3];
        random_jumps(rng, p, fr.nu, 0.3 * lam1, P, Pt);
        for (int j = 1; j <= N; ++j) {  // lam1 J -> P -> lam1 J along straight segments
          const double a = double(j) / N;
          const double w = j <= N / 2 ? 2.0 * a : 2.0 * (1.0 - a);
          const double x[3] = {(1 - w) * lam1 * J[0] + w * P[0], (1 - w) * lam1 * J[1] + w * P[1],
                               (1 - w) * lam1 * J[2] + w * P[2]};
          const double y[3] = {(1 - w) * lam1 * Jt[0] + w * Pt[0], (1 - w) * lam1 * Jt[1] + w * Pt[1],
                               (1 - w) * lam1 * Jt[2] + w * Pt[2]};
          const CohesiveResult r = cohesive_tractions(p, x, y, fr.nu, dmax, n_c, m_c);
          EXPECT_EQ(dmax, dmax1);
          EXPECT_EQ(r.dissipated, D1);
        }
        const CohesiveResult r = at(lam1, n_c, m_c);
        EXPECT_NEAR(r.stored, phi1, 1e-13 * phi1);
        EXPECT_LE(diff3(n_c, n1), 1e-13 * n1m);
        EXPECT_LE(diff3(m_c, m1), 1e-13 * m1m);
      }
      // reloading past delta_max resumes softening
      double S_prev = cohesive_strength(p, dmax1);
      for (int j = 1; j <= N; ++j) {
        const double lam = lam1 * (1.0 + double(j) / N);  // up to 0.8 delta_f
        double n_c[3], m_c[3];
        const CohesiveResult r = at(lam, n_c, m_c);
        EXPECT_NEAR(dmax, lam, 1e-14 * lam);
        const double neff = equivalent_traction(p, n_c, m_c, fr.nu);
        EXPECT_NEAR(neff, cohesive_strength(p, lam), 1e-12 * p.S0);
        EXPECT_LT(neff, S_prev);
        S_prev = neff;
        EXPECT_NEAR(r.dissipated, 0.5 * p.S0 * lam, 1e-14 * p.S0 * p.delta_f);
      }
    }
  }
}

// Work of the tractions along a piecewise-linear path in jump space through the given waypoints, each segment
// split into n increments (trapezoidal sum of n_c.d[[phi]] + m_c.d[[t]]). Returns the maximum over all points
// of |W + 1/2 S0 delta_1 - (phi + D)| / (Gamma h), where delta_1 is the effective opening after the first
// increment (the exact trapezoid defect of the rigid first increment, see the file header), and checks the
// invariants at every point. Outputs the final result and the corrected work.
double path_work_defect(const CohesiveParams& p, const double nu[3], const std::vector<std::vector<double>>& wp,
                        int n, CohesiveResult& last, double& W_corrected, double& first_defect) {
  double dmax = 0.0, W = 0.0, correction = 0.0, worst = 0.0;
  double q_prev[6] = {0, 0, 0, 0, 0, 0}, F_prev[6] = {0, 0, 0, 0, 0, 0};
  bool first = true;
  for (std::size_t s = 1; s < wp.size(); ++s) {
    for (int j = 1; j <= n; ++j) {
      const double a = double(j) / n;
      double q[6], F[6];
      for (int i = 0; i < 6; ++i) q[i] = (1 - a) * wp[s - 1][i] + a * wp[s][i];
      const double dmax_old = dmax;
      const double D_old = 0.5 * p.S0 * std::min(dmax_old, p.delta_f);
      const CohesiveResult r = cohesive_tractions(p, q, q + 3, nu, dmax, F, F + 3);
      const double delta = effective_opening(p, q, q + 3, nu);
      for (int i = 0; i < 6; ++i) W += 0.5 * (F_prev[i] + F[i]) * (q[i] - q_prev[i]);
      if (first) {
        correction = 0.5 * p.S0 * delta;
        first_defect = std::fabs(W - (r.stored + r.dissipated)) / (p.Gamma * p.h);
        first = false;
      }
      // invariants: delta_max monotone, D = 1/2 S0 min(delta_max, delta_f), D unchanged while delta < delta_max
      EXPECT_EQ(dmax, std::max(dmax_old, delta));
      EXPECT_NEAR(r.dissipated, 0.5 * p.S0 * std::min(dmax, p.delta_f), 1e-14 * p.Gamma * p.h);
      if (delta <= dmax_old) {
        EXPECT_NEAR(r.dissipated, D_old, 1e-15 * p.Gamma * p.h);
      }
      worst = std::max(worst, std::fabs(W + correction - (r.stored + r.dissipated)) / (p.Gamma * p.h));
      for (int i = 0; i < 6; ++i) {
        q_prev[i] = q[i];
        F_prev[i] = F[i];
      }
      last = r;
    }
  }
  W_corrected = W + correction;
  return worst;
}

// (Test 5) Dissipation and the work identity W = phi + D along a load - unload (non-radial) - unload to the
// origin - reload past delta_max in another direction - partial unload - load to complete separation path,
// mixed mode, for the weighted Table 2 law and Table 3 (Gamma = 10e3).
// References: D = 1/2 S0 min(delta_max, delta_f) to 1e-14 Gamma h at every point and D constant while
// delta < delta_max; trapezoidal work + the exact first-increment defect 1/2 S0 delta_1 = phi + D at every point
// with a second-order quadrature error (kinks where the path switches between unloading and loading or crosses
// delta_f inside an increment, curvature of delta along non-radial loading segments): tolerance 2/n^2 Gamma h
// for n = 2000 and n = 4000 increments per segment (measured ~0.4/n^2 and ~0.6/n^2); the uncorrected first-increment
// defect equals delta_1/delta_f Gamma h (reported). At complete separation: D = Gamma h to 1e-12 relative,
// phi = 0, separated.
TEST(CohesiveLaw, DissipationAndWorkIdentity) {
  Rng rng(5);
  for (const CohesiveParams& p : {weighted(), beam_blast()}) {
    const Frame fr = random_frame(rng);
    const double df = p.delta_f;
    auto point = [&](double delta) {
      double a[3], b[3];
      random_jumps(rng, p, fr.nu, delta, a, b);
      return std::vector<double>{a[0], a[1], a[2], b[0], b[1], b[2]};
    };
    const std::vector<double> zero(6, 0.0), A = point(0.3 * df), B = point(0.15 * df), C = point(0.6 * df);
    std::vector<double> C_half(6), E(6);
    for (int i = 0; i < 6; ++i) {
      C_half[i] = 0.5 * C[i];
      E[i] = A[i] * (1.3 / 0.3);  // direction of A, delta = 1.3 delta_f: complete separation
    }
    const std::vector<std::vector<double>> wp = {zero, A, B, zero, C, C_half, E};
    CohesiveResult last{}, last2{};
    double W = 0.0, W2 = 0.0, first = 0.0, first2 = 0.0;
    const int n = 2000;
    const double defect = path_work_defect(p, fr.nu, wp, n, last, W, first);
    const double defect2 = path_work_defect(p, fr.nu, wp, 2 * n, last2, W2, first2);
    std::printf("[work] Gamma h = %.6g: max |W - (phi + D)|/(Gamma h) = %.3g (n = %d), %.3g (n = %d); "
                "uncorrected first-increment defect %.3g, %.3g\n",
                p.Gamma * p.h, defect, n, defect2, 2 * n, first, first2);
    EXPECT_LE(defect, 2.0 / (double(n) * n));
    EXPECT_LE(defect2, 2.0 / (4.0 * n * n));
    for (const CohesiveResult& r : {last, last2}) {
      EXPECT_TRUE(r.separated);
      EXPECT_EQ(r.stored, 0.0);
      EXPECT_NEAR(r.dissipated, p.Gamma * p.h, 1e-12 * p.Gamma * p.h);
    }
    EXPECT_NEAR(W, p.Gamma * p.h, 2.0 / (double(n) * n) * p.Gamma * p.h);
    // the uncorrected first increment misses 1/2 S0 delta_1 = (delta_1/delta_f) Gamma h, delta_1 = 0.3 df/n
    EXPECT_NEAR(first, 0.3 / n, 1e-9);
  }
}

// (Test 5b) The law that starts at the activation opening delta0 = 0.05 delta_f (theory.md §9.2, §9.6-9.7): from
// a starting state Q0 on the loading surface (delta(Q0) = delta0 = delta_max, traction S0), along load - unload -
// reload in another direction - load to complete separation, mixed mode, weighted Table 2 law.
// References (derived in theory.md §9.7): S(delta0) = S0 and S(delta0 + delta_f) = 0 exactly; the trapezoidal work
// from Q0 = Delta(phi + D) at every point with the second-order quadrature error of test 5 (2/n^2 Gamma h, no
// first-increment defect: the law starts carrying its traction); at separation D = Gamma h + S0 delta0 / 2 and
// the released starting energy is S0 delta0 / 2, so D less it is Gamma h, to 1e-12 relative; the total work from
// Q0 is Gamma h (the area under S from delta0 to delta0 + delta_f), whatever delta0.
TEST(CohesiveLaw, LawStartingAtTheActivationOpening) {
  Rng rng(7);
  const CohesiveParams rigid = weighted();
  const CohesiveParams p = make_cohesive_params(rigid.h, rigid.sigma_c, rigid.Gamma, rigid.alpha1, rigid.alpha2,
                                                rigid.alpha3, 0.05);
  const double df = p.delta_f, d0 = p.delta0, Gh = p.Gamma * p.h;
  EXPECT_NEAR(d0, 0.05 * df, 1e-15 * df);
  EXPECT_EQ(cohesive_strength(p, 0.0), p.S0);
  EXPECT_EQ(cohesive_strength(p, d0), p.S0);
  EXPECT_NEAR(cohesive_strength(p, d0 + 0.5 * df), 0.5 * p.S0, 1e-13 * p.S0);
  EXPECT_EQ(cohesive_strength(p, d0 + df), 0.0);
  const Frame fr = random_frame(rng);
  auto point = [&](double delta) {
    double a[3], b[3];
    random_jumps(rng, p, fr.nu, delta, a, b);
    return std::vector<double>{a[0], a[1], a[2], b[0], b[1], b[2]};
  };
  const std::vector<double> Q0 = point(d0), A = point(d0 + 0.3 * df), B = point(0.5 * d0);
  std::vector<double> E(6);
  for (int i = 0; i < 6; ++i) E[i] = A[i] * (1.2 * (d0 + df) / (d0 + 0.3 * df));  // beyond separation
  const std::vector<std::vector<double>> wp = {Q0, A, B, E};
  const int n = 2000;
  double dmax = d0, W = 0, worst = 0, F[6], q[6];
  CohesiveResult start = cohesive_tractions(p, Q0.data(), Q0.data() + 3, fr.nu, dmax, F, F + 3), r = start;
  EXPECT_NEAR(start.stored, 0.5 * p.S0 * d0, 1e-12 * Gh);
  EXPECT_EQ(start.dissipated, 0.0);
  double q_prev[6], F_prev[6];
  for (int i = 0; i < 6; ++i) q_prev[i] = Q0[i], F_prev[i] = F[i];
  for (std::size_t s = 1; s < wp.size(); ++s)
    for (int j = 1; j <= n; ++j) {
      const double a = double(j) / n;
      for (int i = 0; i < 6; ++i) q[i] = (1 - a) * wp[s - 1][i] + a * wp[s][i];
      r = cohesive_tractions(p, q, q + 3, fr.nu, dmax, F, F + 3);
      for (int i = 0; i < 6; ++i) W += 0.5 * (F_prev[i] + F[i]) * (q[i] - q_prev[i]), q_prev[i] = q[i], F_prev[i] = F[i];
      worst = std::max(worst, std::fabs(W - (r.stored + r.dissipated - start.stored)) / Gh);
    }
  std::printf("[delta0] max |W - Delta(phi + D)|/(Gamma h) = %.3g (n = %d)\n", worst, n);
  EXPECT_LE(worst, 2.0 / (double(n) * n));
  EXPECT_TRUE(r.separated);
  EXPECT_EQ(r.stored, 0.0);
  EXPECT_NEAR(r.dissipated, Gh + 0.5 * p.S0 * d0, 1e-12 * Gh);
  EXPECT_NEAR(starting_energy_released(p, dmax), 0.5 * p.S0 * d0, 1e-12 * Gh);
  EXPECT_NEAR(r.dissipated - starting_energy_released(p, dmax), Gh, 1e-12 * Gh);
  EXPECT_NEAR(W, Gh, 2.0 / (double(n) * n) * Gh);
  EXPECT_EQ(starting_energy_released(rigid, 2 * df), 0.0);
}

// (Test 6) Consistency of the nucleation measure (eqs. 29-31) with the traction law (eqs. 22-23), random mixed
// modes, random unit nu, random weights alpha_i in [0.5, 2], Table 2 and Table 3 data. Reference:
// equivalent_traction(n_c, m_c) = S(delta_max) on loading states and S(delta_max) delta/delta_max on unloading
// states, to 1e-12 relative; the same with -nu (other side). Closed forms: n = sigma h nu -> sigma h,
// n = tau h e -> tau h/alpha1, m = M nu -> M/(alpha2 h), m = M e -> M/(alpha3 h), to 1e-15 relative; at
// sigma = sigma_c, n_eq = S0 (f = 0 of eq. 30).
TEST(CohesiveLaw, EquivalentTractionConsistency) {
  Rng rng(6);
  double worst = 0.0;
  for (int t = 0; t < 200; ++t) {
    const double a1 = rng.uniform(0.5, 2.0), a2 = rng.uniform(0.5, 2.0), a3 = rng.uniform(0.5, 2.0);
    const CohesiveParams p = t % 2 == 0 ? tearing(a1, a2, a3) : make_cohesive_params(6.53e-3, 375e6, 10e3, a1, a2, a3);
    const Frame fr = random_frame(rng);
    const double mnu[3] = {-fr.nu[0], -fr.nu[1], -fr.nu[2]};
    double jphi[3], jt[3], n_c[3], m_c[3], dmax = 0.0;
    const double delta = rng.uniform(0.0, 1.0) * p.delta_f;
    random_jumps(rng, p, fr.nu, delta, jphi, jt);
    const bool unloading = t % 4 >= 2;
    if (unloading) dmax = std::min(delta / rng.uniform(0.2, 0.99), 0.999 * p.delta_f);
    cohesive_tractions(p, jphi, jt, fr.nu, dmax, n_c, m_c);
    const double ref = cohesive_strength(p, dmax) * delta / dmax;
    const double neq = equivalent_traction(p, n_c, m_c, fr.nu);
    EXPECT_NEAR(neq, ref, 1e-12 * ref) << "unloading " << unloading;
    EXPECT_NEAR(equivalent_traction(p, n_c, m_c, mnu), ref, 1e-12 * ref);
    if (!unloading) {
      EXPECT_NEAR(neq, cohesive_strength(p, dmax), 1e-12 * ref);
    }
    worst = std::max(worst, std::fabs(neq - ref) / ref);
  }
  std::printf("[consistency] max |n_eq(n_c, m_c) - S delta/delta_max| / S = %.3g\n", worst);

  const CohesiveParams p = weighted();
  const Frame fr = random_frame(rng);
  const double zero[3] = {0, 0, 0};
  double n[3], m[3];
  const double sigma = 200e6, tau = 150e6, M = 2.5e3;
  for (int i = 0; i < 3; ++i) n[i] = sigma * p.h * fr.nu[i];
  EXPECT_NEAR(equivalent_traction(p, n, zero, fr.nu), sigma * p.h, 1e-15 * sigma * p.h);
  for (int i = 0; i < 3; ++i) n[i] = p.sigma_c * p.h * fr.nu[i];
  EXPECT_NEAR(equivalent_traction(p, n, zero, fr.nu) / p.S0 - 1.0, 0.0, 1e-15);  // nucleation threshold
  for (int i = 0; i < 3; ++i) n[i] = tau * p.h * fr.e1[i];
  EXPECT_NEAR(equivalent_traction(p, n, zero, fr.nu), tau * p.h / p.alpha1, 1e-15 * tau * p.h / p.alpha1);
  for (int i = 0; i < 3; ++i) n[i] = tau * p.h * fr.e2[i];
  EXPECT_NEAR(equivalent_traction(p, n, zero, fr.nu), tau * p.h / p.alpha1, 1e-15 * tau * p.h / p.alpha1);
  for (int i = 0; i < 3; ++i) m[i] = M * fr.nu[i];
  EXPECT_NEAR(equivalent_traction(p, zero, m, fr.nu), M / (p.alpha2 * p.h), 1e-15 * M / (p.alpha2 * p.h));
  for (int i = 0; i < 3; ++i) m[i] = M * fr.e1[i];
  EXPECT_NEAR(equivalent_traction(p, zero, m, fr.nu), M / (p.alpha3 * p.h), 1e-15 * M / (p.alpha3 * p.h));
}

// (Test 7) Degenerate cases. Gamma = 0 (paper Table 3 as printed): k = +inf, delta_f = 0 stored, S = 0 for all
// delta_max >= 0, every evaluation (zero or non-zero jumps) returns exactly zero, finite tractions, separated,
// stored = dissipated = 0; the nucleation measure still uses S0 = h sigma_c. delta_max = 0 with Gamma > 0 and
// zero jumps: zero tractions, stored 0, dissipated 0, not separated, delta_max stays 0. All exact.
TEST(CohesiveLaw, ZeroGammaAndZeroOpening) {
  Rng rng(7);
  const CohesiveParams p0 = beam_blast(0.0);
  EXPECT_TRUE(std::isinf(p0.k) && p0.k > 0);
  EXPECT_EQ(p0.delta_f, 0.0);
  EXPECT_EQ(p0.S0, 6.53e-3 * 375e6);
  EXPECT_EQ(cohesive_strength(p0, 0.0), 0.0);
  EXPECT_EQ(cohesive_strength(p0, 1e-3), 0.0);
  const double nan = std::nan("");
  for (int t = 0; t < 10; ++t) {
    const Frame fr = random_frame(rng);
    double jphi[3] = {0, 0, 0}, jt[3] = {0, 0, 0};
    if (t > 0) random_jumps(rng, p0, fr.nu, 1e-6 * t, jphi, jt);
    double n_c[3] = {nan, nan, nan}, m_c[3] = {nan, nan, nan}, dmax = 0.0;
    const CohesiveResult r = cohesive_tractions(p0, jphi, jt, fr.nu, dmax, n_c, m_c);
    EXPECT_TRUE(r.separated);
    EXPECT_EQ(r.stored, 0.0);
    EXPECT_EQ(r.dissipated, 0.0);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(n_c[i], 0.0);
      EXPECT_EQ(m_c[i], 0.0);
    }
    EXPECT_EQ(dmax, t > 0 ? effective_opening(p0, jphi, jt, fr.nu) : 0.0);
    double n[3];
    for (int i = 0; i < 3; ++i) n[i] = 2.0 * p0.S0 * fr.nu[i];
    EXPECT_NEAR(equivalent_traction(p0, n, m_c, fr.nu), 2.0 * p0.S0, 1e-15 * p0.S0);  // m_c = 0 here
  }
  for (const CohesiveParams& p : {beam_blast(), weighted()}) {
    const Frame fr = random_frame(rng);
    const double z[3] = {0, 0, 0};
    double n_c[3] = {nan, nan, nan}, m_c[3] = {nan, nan, nan}, dmax = 0.0;
    const CohesiveResult r = cohesive_tractions(p, z, z, fr.nu, dmax, n_c, m_c);
    EXPECT_FALSE(r.separated);
    EXPECT_EQ(dmax, 0.0);
    EXPECT_EQ(r.stored, 0.0);
    EXPECT_EQ(r.dissipated, 0.0);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(n_c[i], 0.0);
      EXPECT_EQ(m_c[i], 0.0);
    }
    EXPECT_EQ(effective_opening(p, z, z, fr.nu), 0.0);
    EXPECT_EQ(equivalent_traction(p, z, z, fr.nu), 0.0);
    // tiny first opening: traction already at full strength (initially rigid law), bounded by S0
    double jphi[3], jt[3];
    random_jumps(rng, p, fr.nu, 1e-12 * p.delta_f, jphi, jt);
    cohesive_tractions(p, jphi, jt, fr.nu, dmax, n_c, m_c);
    EXPECT_NEAR(equivalent_traction(p, n_c, m_c, fr.nu), p.S0, 1e-11 * p.S0);
  }
}

// (Test 8) The law runs inside a Kokkos kernel (host execution space, as for the other point laws) and gives
// bitwise the same results as a plain host loop (same code, same inputs), with delta_max updated in place in
// a View. Half of the points start from delta_max = 0 (loading), half from a larger delta_max (unloading),
// a few beyond delta_f (separated).
TEST(CohesiveLaw, UsableInKokkosKernel) {
  const CohesiveParams p = weighted();
  const int n = 64;
  Kokkos::View<double*[3], Kokkos::HostSpace> jphi("jphi", n), jt("jt", n), nu("nu", n), nc("nc", n), mc("mc", n);
  Kokkos::View<double*, Kokkos::HostSpace> dmax("dmax", n), stored("stored", n), diss("diss", n), neq("neq", n);
  Kokkos::View<int*, Kokkos::HostSpace> sep("sep", n);
  Rng rng(8);
  std::vector<double> dmax0(n);
  for (int i = 0; i < n; ++i) {
    const Frame fr = random_frame(rng);
    double a[3], b[3];
    random_jumps(rng, p, fr.nu, rng.uniform(0.0, 1.2) * p.delta_f, a, b);
    for (int k = 0; k < 3; ++k) {
      jphi(i, k) = a[k];
      jt(i, k) = b[k];
      nu(i, k) = fr.nu[k];
    }
    dmax0[i] = i % 2 == 0 ? 0.0 : rng.uniform(0.0, 1.2) * p.delta_f;
    dmax(i) = dmax0[i];
  }
  Kokkos::parallel_for(
      "cohesive_tractions", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, n), KOKKOS_LAMBDA(const int i) {
        const double a[3] = {jphi(i, 0), jphi(i, 1), jphi(i, 2)}, b[3] = {jt(i, 0), jt(i, 1), jt(i, 2)};
        const double v[3] = {nu(i, 0), nu(i, 1), nu(i, 2)};
        double n_c[3], m_c[3];
        const CohesiveResult r = cohesive_tractions(p, a, b, v, dmax(i), n_c, m_c);
        for (int k = 0; k < 3; ++k) {
          nc(i, k) = n_c[k];
          mc(i, k) = m_c[k];
        }
        stored(i) = r.stored;
        diss(i) = r.dissipated;
        sep(i) = r.separated ? 1 : 0;
        neq(i) = equivalent_traction(p, n_c, m_c, v);
      });
  Kokkos::fence();
  int nsep = 0;
  for (int i = 0; i < n; ++i) {
    const double a[3] = {jphi(i, 0), jphi(i, 1), jphi(i, 2)}, b[3] = {jt(i, 0), jt(i, 1), jt(i, 2)};
    const double v[3] = {nu(i, 0), nu(i, 1), nu(i, 2)};
    double n_c[3], m_c[3], d = dmax0[i];
    const CohesiveResult r = cohesive_tractions(p, a, b, v, d, n_c, m_c);
    EXPECT_EQ(dmax(i), d);
    EXPECT_EQ(stored(i), r.stored);
    EXPECT_EQ(diss(i), r.dissipated);
    EXPECT_EQ(sep(i), r.separated ? 1 : 0);
    EXPECT_EQ(neq(i), equivalent_traction(p, n_c, m_c, v));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(nc(i, k), n_c[k]);
      EXPECT_EQ(mc(i, k), m_c[k]);
    }
    nsep += r.separated ? 1 : 0;
  }
  EXPECT_GT(nsep, 0);
  EXPECT_LT(nsep, n);
}

}  // namespace

// With crack-face contact (Fracture->Crack Face Contact, theory.md §9.9) closing is not opening, and the crack
// faces resist interpenetration. References:
// the contact energy of a penalty k_c/h per unit thickness on the gap g(z) = d + z t over the part of
// z in [-h/2, h/2] where g < 0, integrated by hand: closed over the whole thickness
// U = 1/2 k_c (d^2 + h^2 t^2 / 12); touching at one face only (g(-h/2) < 0 < g(h/2), t > 0), with
// z0 = -d/t: U = k_c/(2h) (-(d - t h/2)^3 / (3 t)) (the integral of g^2 = (g^3/(3t)) from -h/2 to z0).
TEST(CrackFaceContact, ClosedFacesStoreThePenaltyEnergyAndPushApart) {
  const double kc = 3 * 70e9 * 2e-3 / 1e-3, h = 2e-3;  // beta_x / h_e with c_x = 3, E = 70 GPa, h_e = 1 mm
  double f, m;
  // Closed everywhere, no rotation.
  EXPECT_NEAR(crack_face_contact(kc, h, -1e-6, 0.0, f, m), 0.5 * kc * 1e-12, 1e-15 * 0.5 * kc * 1e-12 * 4);
  EXPECT_NEAR(f, -kc * 1e-6, 1e-14 * kc * 1e-6);
  EXPECT_EQ(m, 0.0);
  // Closed everywhere, with a director jump: U = 1/2 kc (d^2 + h^2 t^2/12), f = kc d, m = kc h^2 t/12.
  const double d = -2e-6, t = 1e-4;  // |t| h/2 = 1e-7 < |d|
  EXPECT_NEAR(crack_face_contact(kc, h, d, t, f, m), 0.5 * kc * (d * d + h * h * t * t / 12), 1e-12 * kc * d * d);
  EXPECT_NEAR(f, kc * d, 1e-12 * kc * std::abs(d));
  EXPECT_NEAR(m, kc * h * h * t / 12, 1e-9 * kc * h * h * t / 12);
  // Apart: no energy, no force.
  EXPECT_EQ(crack_face_contact(kc, h, 1e-6, 1e-4, f, m), 0.0);
  EXPECT_EQ(f, 0.0);
  EXPECT_EQ(m, 0.0);
  EXPECT_EQ(crack_face_contact(kc, h, 0.0, 0.0, f, m), 0.0);
  // Touching at one face: the closed form above.
  const double d1 = 2e-7, t1 = 4e-4;  // g(-h/2) = 2e-7 - 4e-7 < 0 < g(h/2)
  const double lo = d1 - t1 * h / 2;
  EXPECT_NEAR(crack_face_contact(kc, h, d1, t1, f, m), kc / (2 * h) * (-lo * lo * lo / (3 * t1)),
              1e-9 * kc / (2 * h) * (-lo * lo * lo / (3 * t1)));
}

TEST(CrackFaceContact, ForcesAreTheGradientOfTheEnergy) {
  const double kc = 4.2e11, h = 2e-3;
  for (const auto& [d, t] : {std::pair{-1e-6, 0.0}, {-1e-6, 3e-3}, {2e-7, 4e-4}, {2e-7, -4e-4}, {-3e-6, -1e-2}}) {
    double f, m, f1, m1;
    crack_face_contact(kc, h, d, t, f, m);
    const double ed = 1e-6 * std::max(std::abs(d), 1e-9), et = 1e-6 * std::max(std::abs(t), 1e-6);
    const double dUdd = (crack_face_contact(kc, h, d + ed, t, f1, m1) - crack_face_contact(kc, h, d - ed, t, f1, m1)) / (2 * ed);
    const double dUdt = (crack_face_contact(kc, h, d, t + et, f1, m1) - crack_face_contact(kc, h, d, t - et, f1, m1)) / (2 * et);
    EXPECT_NEAR(f, dUdd, 1e-6 * std::abs(f) + 1e-12) << d << " " << t;
    EXPECT_NEAR(m, dUdt, 1e-6 * std::abs(m) + 1e-12) << d << " " << t;
  }
}

TEST(CrackFaceContact, ClosingNeitherOpensNorDamages) {
  CohesiveParams p = beam_blast();
  p.contact = true;
  const double nu[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  // Open to a quarter of delta_f, then press the faces through each other: delta_max stays.
  double dmax = 0, n_c[3], m_c[3];
  const double open[3] = {0.25 * p.delta_f, 0, 0};
  cohesive_tractions(p, open, zero, nu, dmax, n_c, m_c);
  EXPECT_EQ(dmax, 0.25 * p.delta_f);
  const double closed[3] = {-0.5 * p.delta_f, 0, 0};
  const CohesiveResult r = cohesive_tractions(p, closed, zero, nu, dmax, n_c, m_c);
  EXPECT_EQ(dmax, 0.25 * p.delta_f);
  EXPECT_EQ(effective_opening(p, closed, zero, nu), 0.0);
  EXPECT_EQ(n_c[0], 0.0);  // the law carries no compression; the contact does
  EXPECT_EQ(r.stored, 0.0);
  // A compressive edge force does not count towards nucleation; shear under compression does.
  const double press[3] = {-2 * p.S0, 0, 0}, shear_press[3] = {-2 * p.S0, 0.5 * p.S0, 0};
  EXPECT_EQ(equivalent_traction(p, press, zero, nu), 0.0);
  EXPECT_NEAR(equivalent_traction(p, shear_press, zero, nu), 0.5 * p.S0, 1e-9 * p.S0);
  // Without contact (the default, the paper's law) a closing jump counts as opening.
  p.contact = false;
  double dmax2 = 0;
  cohesive_tractions(p, closed, zero, nu, dmax2, n_c, m_c);
  EXPECT_EQ(dmax2, 0.5 * p.delta_f);
  EXPECT_EQ(equivalent_traction(p, press, zero, nu), 2 * p.S0);
}
