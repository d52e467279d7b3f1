#pragma once
/// \file cohesive_law_test_cases.hpp
/// Helpers shared by the cohesive law tests (test_cohesive_law_*.cpp): the paper's parameter sets, vector
/// helpers, random frames and random mixed-mode jumps. The references those tests cite as "the file header"
/// are the ones below.
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
#include <cmath>
#include <random>

#include "shellfrac/materials/cohesive_law.hpp"

namespace shellfrac::materials::cohesive_test {

// The paper's Table 3 (beam blast, Al 6061-T6) with a non-zero Gamma = 10 kJ/m^2 (the paper uses Gamma = 0 there).
inline CohesiveParams beam_blast(double Gamma = 10e3) { return make_cohesive_params(6.53e-3, 375e6, Gamma); }
// The paper's Table 2 (mode III tearing): h = 2 mm, sigma_c = 325 MPa, Gamma = 0.75 Y0 h with Y0 = 320 MPa.
inline CohesiveParams tearing(double a1 = 1, double a2 = 1, double a3 = 1) {
  return make_cohesive_params(2e-3, 325e6, 0.75 * 320e6 * 2e-3, a1, a2, a3);
}
// Table 2 with distinct eq. 20 weights, so that every alpha is visible in the results.
inline CohesiveParams weighted() { return tearing(0.7, 1.3, 0.5); }

inline double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm3(const double a[3]) { return std::sqrt(dot3(a, a)); }
inline double diff3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}
inline void cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
inline void normalize3(double a[3]) {
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
inline Frame random_frame(Rng& rng) {
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

/// Random mixed-mode jumps with effective opening exactly `delta` (all four modes active).
inline void random_jumps(Rng& rng, const CohesiveParams& p, const double nu[3], double delta, double jphi[3],
                         double jt[3]) {
  rng.vec(jphi, 1.0);
  rng.vec(jt, 1.0 / p.h);
  const double d = effective_opening(p, jphi, jt, nu);
  for (int i = 0; i < 3; ++i) {
    jphi[i] *= delta / d;
    jt[i] *= delta / d;
  }
}

}  // namespace shellfrac::materials::cohesive_test
