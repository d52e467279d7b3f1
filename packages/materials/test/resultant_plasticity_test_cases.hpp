#pragma once
/// \file resultant_plasticity_test_cases.hpp
/// Helpers shared by the resultant plasticity tests (test_resultant_plasticity_*.cpp): the sections, vector
/// helpers, random trial states and the assertions common to every plastic return. The references those tests
/// cite as "the header comment" or "the file header" are the ones below.
// Resultant plasticity point law (theory.md §4): equivalent stress (§4.1), associative flow and hardening
// (§4.2), closest-point return map (§4.3). References used below:
//  * closed forms of sigma_eq (theory.md §4.1): sigma_eq^2 = (N11^2 - N11 N22 + N22^2 + 3 N12^2)/h^2
//    + 16 (M11^2 - M11 M22 + M22^2 + 3 M12^2)/h^4 (a_n (2/3) = 1/h^2, a_m (2/3) = 16/h^4); uniaxial N = [s h,0,0]
//    gives s, a pure moment M = [M0,0,0] with M0 = Y0 h^2/4 gives Y0;
//  * uniaxial membrane stress (N22 = N12 = 0): the flow direction is P [1,0,0] ~ [2,-1,0], so d eps^p = d alpha
//    [1, -1/2, 0] and N11 = E h (eps11 - alpha); with sigma = Y0 + H alpha this is the 1D bilinear law,
//    exact for backward Euler at any increment size (monotone loading):
//    alpha = max(0, (E eps11 - Y0)/(E + H)), sigma = N11/h = E (eps11 - alpha), eps22 = -nu (eps11 - alpha) - alpha/2;
//  * uniaxial moment (M22 = M12 = 0): sigma_eq = 4 |M11|/h^2, d rho^p = (4/h) d alpha [1, -1/2, 0],
//    M11 = (E h^3/12)(rho11 - q), q = rho^p_11, and M11 = (h^2/4)(Y0 + H h q/4) once plastic. For H = 0 the
//    model's first-yield moment is already the Ilyushin limit M0 = Y0 h^2/4, so M11 = min(E h^3 rho11/12, M0);
//  * discrete energy identity of one backward-Euler step with a trapezoidal external work (exact algebra,
//    quadratic stored energy U, dW_p = N_{n+1}.d eps^p + M_{n+1}.d rho^p = dgam sigma_y(alpha_{n+1})):
//    1/2 (S_n + S_{n+1}).d e - (U_{n+1} - U_n) - dW_p = -1/2 (S_{n+1} - S_n).d e^p  (S = (N, M), e = (eps, rho)),
//    so sum dW_p = W_ext - U_final up to the sum of the right-hand sides (first order in the increment for H > 0,
//    second order for H = 0, see DissipationLoadUnloadCycle), and the identity itself holds to round-off;
//  * with alpha_{n+1} in dW_p: sum dW_p = h sum d alpha (Y0 + H alpha_{k+1})
//    = h (Y0 alpha + H alpha^2/2) + (h H/2) sum d alpha_k^2   (exact), i.e. first order in the increment;
//  * closest point (KKT of min 1/2|S - S_tr|^2_{C^-1} + 1/2 H h (alpha' - alpha_n)^2 s.t. sigma_eq(S) <= Y0 + H alpha',
//    the objective of an earlier, independent Python check): normality d eps^p = dgam a_n P N/sigma_eq,
//    d rho^p = dgam a_m P M/sigma_eq with dgam = h d alpha, and no feasible neighbour with a smaller objective;
//  * Python-check numbers: the five random trials of that Python check (numpy default_rng(0), E = 72e9,
//    nu = 0.343, h = 2e-3, Y0 = 320e6, H = 894e6); reference values recomputed in 50-digit arithmetic (mpmath,
//    dense 3x3 solves of (1 + z a D C0 P) S = S_tr, no spectral basis, root of g by findroot).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "shellfrac/materials/resultant_plasticity.hpp"

namespace shellfrac::materials::plasticity_test {

// Sections: the cylinder panel of paper §6.1 (psi, in) with H = 0 or H = 0.1 E, the mode III tearing data of
// paper §6.2 (SI), and a nu = 0 section.
inline PlasticSection panel(double H) { return make_plastic_section(10.5e6, 0.33, 0.125, 44e3, H); }
inline PlasticSection tearing() { return make_plastic_section(72e9, 0.343, 2e-3, 320e6, 894e6); }
inline PlasticSection tearing_perfect() { return make_plastic_section(72e9, 0.343, 2e-3, 320e6, 0.0); }
inline PlasticSection nu_zero() { return make_plastic_section(2.0e11, 0.0, 5e-3, 250e6, 2e9); }

inline double young(const PlasticSection& s) {  // E = D_n (1 - nu^2)/h
  return s.elastic.Dn * (1.0 - s.elastic.nu * s.elastic.nu) / s.h;
}
inline double sigma_y(const PlasticSection& s, double alpha) { return s.Y0 + s.H * alpha; }

inline double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm3(const double a[3]) { return std::sqrt(dot3(a, a)); }
inline double diff3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

/// Plane-stress von Mises matrix P of theory.md §4.1 applied to a Voigt resultant.
inline void apply_P(const double x[3], double y[3]) {
  y[0] = (2.0 * x[0] - x[1]) / 3.0;
  y[1] = (-x[0] + 2.0 * x[1]) / 3.0;
  y[2] = 2.0 * x[2];
}

/// sigma_eq written out component-wise (independent of the spectral form used by the header).
inline double sigma_eq_explicit(const PlasticSection& s, const double N[3], const double M[3]) {
  const double h = s.h;
  const double qn = N[0] * N[0] - N[0] * N[1] + N[1] * N[1] + 3.0 * N[2] * N[2];
  const double qm = M[0] * M[0] - M[0] * M[1] + M[1] * M[1] + 3.0 * M[2] * M[2];
  return std::sqrt(qn / (h * h) + 16.0 * qm / (h * h * h * h));
}

/// y = (D C0)^{-1} x, written out.
inline void c0_inverse(double D, double nu, const double x[3], double y[3]) {
  y[0] = (x[0] - nu * x[1]) / (D * (1.0 - nu * nu));
  y[1] = (x[1] - nu * x[0]) / (D * (1.0 - nu * nu));
  y[2] = 2.0 * x[2] / (D * (1.0 - nu));
}

inline PlasticState zero_state() { return PlasticState{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.0, {0.0, 0.0}}; }

struct Rng {
  std::mt19937_64 gen;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  explicit Rng(unsigned seed) : gen(seed) {}
  double operator()() { return u(gen); }
  double uniform01() { return 0.5 * (u(gen) + 1.0); }
  void vec(double x[3], double scale) {
    for (int k = 0; k < 3; ++k) x[k] = scale * (*this)();
  }
};

/// Yield strains of a section: membrane eps_y = Y0/E, uniaxial-moment curvature rho_y = 3 Y0/(E h).
inline double eps_y(const PlasticSection& s) { return s.Y0 / young(s); }
inline double rho_y(const PlasticSection& s) { return 3.0 * s.Y0 / (young(s) * s.h); }

/// Random internal state: plastic strains of the size of the yield strains, alpha in [0, 0.05).
inline PlasticState random_state(Rng& rng, const PlasticSection& s) {
  PlasticState st{};
  rng.vec(st.eps_p, eps_y(s));
  rng.vec(st.rho_p, rho_y(s));
  st.alpha = 0.05 * rng.uniform01();
  return st;
}

/// Iteration statistics of the plastic returns of one test (printed for the report).
struct IterStats {
  int max = 0;
  long sum = 0;
  int count = 0;
  void add(const ReturnMapResult& r) {
    if (!r.plastic) return;
    max = std::max(max, r.iterations);
    sum += r.iterations;
    ++count;
  }
  void print(const char* name) const {
    std::printf("[iterations] %-40s plastic returns %6d  mean %5.2f  max %3d\n", name, count,
                count ? double(sum) / count : 0.0, max);
  }
};

/// Strains eps, rho (elastic part added to the old plastic strains) such that the trial sigma_eq equals
/// factor * sigma_y(alpha_n); directions e_dir, r_dir of the elastic strains.
inline void trial_at_factor(const PlasticSection& s, const PlasticState& old, const double e_dir[3],
                            const double r_dir[3], double factor, double eps[3], double rho[3]) {
  double N[3], Q[2], M[3];
  const double g0[2] = {0.0, 0.0};
  elastic_resultants(s.elastic, e_dir, g0, r_dir, N, Q, M);
  const double t = factor * sigma_y(s, old.alpha) / equivalent_stress(s, N, M);
  for (int k = 0; k < 3; ++k) {
    eps[k] = old.eps_p[k] + t * e_dir[k];
    rho[k] = old.rho_p[k] + t * r_dir[k];
  }
}

/// Assertions common to every plastic return (theory.md §4.1-4.3):
///  * consistency sigma_eq(N, Q, M) = Y0 + H alpha_{n+1} to 1e-12 relative;
///  * N, M equal elastic_resultants with the new plastic strains to 1e-12 relative (norm-wise), plus the floor
///    set by storing eps^p = eps - (D_n C0)^{-1} N in double precision: one ulp of eps and eps^p per component,
///    i.e. 1e-15 (|D_n C0 eps| + |D_n C0 eps^p|) (only active for trial states >~ 1e3 x yield); Q = D_s gam
///    exactly when the shear is elastic (a_q = 0, gam^p stays 0), else Q = D_s (gam - gam^p_{n+1}) likewise;
///  * alpha_{n+1} >= alpha_n, plastic_work = dgam sigma_y(alpha_{n+1}) >= 0 with dgam = h (alpha_{n+1} - alpha_n)
///    to 1e-12 relative, plus the round-off of the test's own difference alpha_{n+1} - alpha_n
///    (4e-16 h alpha_{n+1} sigma_y);
///  * all outputs finite.
inline void expect_plastic_return_consistent(const PlasticSection& s, const double eps[3], const double gam[2],
                                             const double rho[3], const PlasticState& old, const PlasticState& next,
                                             const double N[3], const double Q[2], const double M[3],
                                             const ReturnMapResult& r) {
  ASSERT_TRUE(r.plastic);
  ASSERT_TRUE(r.converged);
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::isfinite(N[k]) && std::isfinite(M[k]));
    ASSERT_TRUE(std::isfinite(next.eps_p[k]) && std::isfinite(next.rho_p[k]));
  }
  ASSERT_TRUE(std::isfinite(next.alpha) && std::isfinite(r.plastic_work));
  const double sy = sigma_y(s, next.alpha);
  EXPECT_NEAR(equivalent_stress(s, N, Q, M), sy, 1e-12 * sy);
  double Nr[3], Qr[2], Mr[3], Nt[3], Qt[2], Mt[3], Np[3], Mp[3];
  elastic_resultants(s.elastic, eps, gam, rho, next.eps_p, next.gam_p, next.rho_p, Nr, Qr, Mr);
  elastic_resultants(s.elastic, eps, gam, rho, Nt, Qt, Mt);                // D C0 (total strains)
  elastic_resultants(s.elastic, next.eps_p, gam, next.rho_p, Np, Qt, Mp);  // D C0 (plastic strains)
  EXPECT_LE(diff3(N, Nr), 1e-12 * norm3(N) + 1e-15 * (norm3(Nt) + norm3(Np)));
  EXPECT_LE(diff3(M, Mr), 1e-12 * norm3(M) + 1e-15 * (norm3(Mt) + norm3(Mp)));
  if (s.a_q == 0.0) {
    EXPECT_EQ(Q[0], s.elastic.Ds * gam[0]);
    EXPECT_EQ(Q[1], s.elastic.Ds * gam[1]);
    EXPECT_EQ(next.gam_p[0], 0.0);
    EXPECT_EQ(next.gam_p[1], 0.0);
  } else {
    const double nq = std::hypot(Q[0], Q[1]), ng = s.elastic.Ds * std::hypot(gam[0], gam[1]);
    EXPECT_LE(std::hypot(Q[0] - Qr[0], Q[1] - Qr[1]), 1e-12 * nq + 1e-15 * 2.0 * ng);
  }
  EXPECT_GE(next.alpha, old.alpha);
  EXPECT_GE(r.plastic_work, 0.0);
  const double dgam = s.h * (next.alpha - old.alpha);
  EXPECT_NEAR(r.plastic_work, dgam * sy, 1e-12 * r.plastic_work + 4e-16 * s.h * next.alpha * sy);
}

/// Normality (theory.md §4.2) with one dgam = h d alpha for all plastic strains, to 1e-10 relative (norm-wise):
/// d eps^p = dgam a_n P N / sigma_eq, d rho^p = dgam a_m P M / sigma_eq, d gam^p = dgam a_q Q / sigma_eq (zero
/// when the shear is elastic, a_q = 0).
inline void expect_normality(const PlasticSection& s, const PlasticState& old, const PlasticState& next,
                             const double N[3], const double Q[2], const double M[3]) {
  const double seq = equivalent_stress(s, N, Q, M), dgam = s.h * (next.alpha - old.alpha);
  double PN[3], PM[3], dep[3], drp[3], dep_ref[3], drp_ref[3];
  apply_P(N, PN);
  apply_P(M, PM);
  for (int k = 0; k < 3; ++k) {
    dep[k] = next.eps_p[k] - old.eps_p[k];
    drp[k] = next.rho_p[k] - old.rho_p[k];
    dep_ref[k] = dgam * s.a_n * PN[k] / seq;
    drp_ref[k] = dgam * s.a_m * PM[k] / seq;
  }
  const double dgp[2] = {next.gam_p[0] - old.gam_p[0], next.gam_p[1] - old.gam_p[1]};
  const double dgp_ref[2] = {dgam * s.a_q * Q[0] / seq, dgam * s.a_q * Q[1] / seq};
  EXPECT_LE(diff3(dep, dep_ref), 1e-10 * norm3(dep_ref));
  EXPECT_LE(diff3(drp, drp_ref), 1e-10 * norm3(drp_ref));
  EXPECT_LE(std::hypot(dgp[0] - dgp_ref[0], dgp[1] - dgp_ref[1]), 1e-10 * std::hypot(dgp_ref[0], dgp_ref[1]));
}

}  // namespace shellfrac::materials::plasticity_test
