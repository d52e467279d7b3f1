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

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "shellfrac/materials/resultant_plasticity.hpp"

using shellfrac::materials::elastic_energy;
using shellfrac::materials::elastic_resultants;
using shellfrac::materials::ElasticSection;
using shellfrac::materials::equivalent_stress;
using shellfrac::materials::make_elastic_section;
using shellfrac::materials::make_plastic_section;
using shellfrac::materials::PlasticSection;
using shellfrac::materials::PlasticState;
using shellfrac::materials::resultant_return_map;
using shellfrac::materials::ReturnMapResult;

namespace {

// Sections: the cylinder panel of paper §6.1 (psi, in) with H = 0 or H = 0.1 E, the mode III tearing data of
// paper §6.2 (SI), and a nu = 0 section.
PlasticSection panel(double H) { return make_plastic_section(10.5e6, 0.33, 0.125, 44e3, H); }
PlasticSection tearing() { return make_plastic_section(72e9, 0.343, 2e-3, 320e6, 894e6); }
PlasticSection tearing_perfect() { return make_plastic_section(72e9, 0.343, 2e-3, 320e6, 0.0); }
PlasticSection nu_zero() { return make_plastic_section(2.0e11, 0.0, 5e-3, 250e6, 2e9); }

double young(const PlasticSection& s) {  // E = D_n (1 - nu^2)/h
  return s.elastic.Dn * (1.0 - s.elastic.nu * s.elastic.nu) / s.h;
}
double sigma_y(const PlasticSection& s, double alpha) { return s.Y0 + s.H * alpha; }

double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm3(const double a[3]) { return std::sqrt(dot3(a, a)); }
double diff3(const double a[3], const double b[3]) {
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

/// Plane-stress von Mises matrix P of theory.md §4.1 applied to a Voigt resultant.
void apply_P(const double x[3], double y[3]) {
  y[0] = (2.0 * x[0] - x[1]) / 3.0;
  y[1] = (-x[0] + 2.0 * x[1]) / 3.0;
  y[2] = 2.0 * x[2];
}

/// sigma_eq written out component-wise (independent of the spectral form used by the header).
double sigma_eq_explicit(const PlasticSection& s, const double N[3], const double M[3]) {
  const double h = s.h;
  const double qn = N[0] * N[0] - N[0] * N[1] + N[1] * N[1] + 3.0 * N[2] * N[2];
  const double qm = M[0] * M[0] - M[0] * M[1] + M[1] * M[1] + 3.0 * M[2] * M[2];
  return std::sqrt(qn / (h * h) + 16.0 * qm / (h * h * h * h));
}

/// y = (D C0)^{-1} x, written out.
void c0_inverse(double D, double nu, const double x[3], double y[3]) {
  y[0] = (x[0] - nu * x[1]) / (D * (1.0 - nu * nu));
  y[1] = (x[1] - nu * x[0]) / (D * (1.0 - nu * nu));
  y[2] = 2.0 * x[2] / (D * (1.0 - nu));
}

PlasticState zero_state() { return PlasticState{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.0, {0.0, 0.0}}; }

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
double eps_y(const PlasticSection& s) { return s.Y0 / young(s); }
double rho_y(const PlasticSection& s) { return 3.0 * s.Y0 / (young(s) * s.h); }

/// Random internal state: plastic strains of the size of the yield strains, alpha in [0, 0.05).
PlasticState random_state(Rng& rng, const PlasticSection& s) {
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
void trial_at_factor(const PlasticSection& s, const PlasticState& old, const double e_dir[3], const double r_dir[3],
                     double factor, double eps[3], double rho[3]) {
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
void expect_plastic_return_consistent(const PlasticSection& s, const double eps[3], const double gam[2],
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
void expect_normality(const PlasticSection& s, const PlasticState& old, const PlasticState& next, const double N[3],
                      const double Q[2], const double M[3]) {
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

/// Root of a monotonically increasing scalar function f by bracketing and the Illinois (modified regula falsi)
/// method, |f| <= tol. Used to impose N22 = 0 or M22 = 0 through the lateral strain.
template <class Fun>
double solve_increasing(Fun f, double x0, double dx, double tol, bool& ok) {
  ok = true;
  double a = x0, fa = f(a);
  if (std::abs(fa) <= tol) return a;
  double step = fa > 0.0 ? -dx : dx;
  double b = a + step, fb = f(b);
  for (int k = 0; k < 200 && fa * fb > 0.0; ++k) {
    a = b;
    fa = fb;
    step *= 2.0;
    b = a + step;
    fb = f(b);
  }
  if (std::abs(fb) <= tol) return b;
  int side = 0;
  for (int k = 0; k < 300; ++k) {
    const double c = b - fb * (b - a) / (fb - fa);
    const double fc = f(c);
    if (std::abs(fc) <= tol) return c;
    if (fc * fb < 0.0) {
      a = b;
      fa = fb;
      side = 0;
    } else {
      if (side == 1) fa *= 0.5;
      side = 1;
    }
    b = c;
    fb = fc;
    if (std::abs(b - a) <= 1e-17 * std::abs(b)) return b;  // bracket exhausted at round-off level
  }
  ok = false;
  return b;
}

// ---------------------------------------------------------------------------------------------------------------

// Section constants and sigma_eq closed forms (theory.md §4.1). Tolerance 1e-14 relative (a handful of flops).
TEST(ResultantPlasticity, SectionAndEquivalentStress) {
  const double E = 10.5e6, nu = 0.33, h = 0.125, Y0 = 44e3, H = 1.05e6;
  const PlasticSection s = make_plastic_section(E, nu, h, Y0, H);
  const ElasticSection el = make_elastic_section(E, nu, h);
  EXPECT_EQ(s.elastic.Dn, el.Dn);
  EXPECT_EQ(s.elastic.Dm, el.Dm);
  EXPECT_EQ(s.elastic.Ds, el.Ds);
  EXPECT_EQ(s.elastic.nu, nu);
  EXPECT_EQ(s.h, h);
  EXPECT_EQ(s.Y0, Y0);
  EXPECT_EQ(s.H, H);
  EXPECT_NEAR(s.a_n, 96.0, 1e-14 * 96.0);        // 3/(2 h^2) = 3/(2/64)
  EXPECT_NEAR(s.a_m, 98304.0, 1e-14 * 98304.0);  // 24/h^4 = 24 * 4096

  const double z3[3] = {0.0, 0.0, 0.0};
  const double sig = 3.3e4;
  const double Nu[3] = {sig * h, 0.0, 0.0};
  EXPECT_NEAR(equivalent_stress(s, Nu, z3), sig, 1e-14 * sig);
  const double Nc[3] = {-sig * h, 0.0, 0.0};
  EXPECT_NEAR(equivalent_stress(s, Nc, z3), sig, 1e-14 * sig);
  const double Nbi[3] = {sig * h, sig * h, 0.0};  // equibiaxial: sigma_eq = sigma
  EXPECT_NEAR(equivalent_stress(s, Nbi, z3), sig, 1e-14 * sig);
  const double tau = 2.0e4, Ns[3] = {0.0, 0.0, tau * h};  // pure shear: sqrt(3) tau
  EXPECT_NEAR(equivalent_stress(s, Ns, z3), std::sqrt(3.0) * tau, 1e-14 * tau);
  const double M0 = Y0 * h * h / 4.0, Mu[3] = {M0, 0.0, 0.0};  // Ilyushin limit moment
  EXPECT_NEAR(equivalent_stress(s, z3, Mu), Y0, 1e-14 * Y0);

  Rng rng(1);
  for (int i = 0; i < 1000; ++i) {
    double N[3], M[3];
    rng.vec(N, Y0 * h);
    rng.vec(M, M0);
    const double ref = sigma_eq_explicit(s, N, M);
    EXPECT_NEAR(equivalent_stress(s, N, M), ref, 1e-14 * ref);
    // Homogeneous of degree 1 (theory.md §4.2): sigma_eq(t S) = |t| sigma_eq(S).
    const double Nt[3] = {-2.5 * N[0], -2.5 * N[1], -2.5 * N[2]}, Mt[3] = {-2.5 * M[0], -2.5 * M[1], -2.5 * M[2]};
    EXPECT_NEAR(equivalent_stress(s, Nt, Mt), 2.5 * ref, 1e-14 * ref);
  }
}

// (Test 1) After a plastic return: sigma_eq(N, M) = Y0 + H alpha to 1e-12 relative, N and M equal elastic_resultants
// with the new plastic strains to 1e-12 relative, plastic work = dgam sigma_y(alpha_{n+1}) (see
// expect_plastic_return_consistent). 4 sections x 500 random combined trial states with random old states and
// trial overstresses between 1.001 and 30.
TEST(ResultantPlasticity, ConsistencyAfterPlasticReturn) {
  const PlasticSection sections[4] = {panel(0.0), panel(0.1 * 10.5e6), tearing(), nu_zero()};
  const char* names[4] = {"consistency panel H=0", "consistency panel H=0.1E", "consistency tearing",
                          "consistency nu=0"};
  Rng rng(2);
  for (int is = 0; is < 4; ++is) {
    const PlasticSection& s = sections[is];
    IterStats stats;
    for (int i = 0; i < 500; ++i) {
      const PlasticState old = random_state(rng, s);
      double e_dir[3], r_dir[3], eps[3], rho[3];
      rng.vec(e_dir, 1.0);
      rng.vec(r_dir, rho_y(s) / eps_y(s) * rng.uniform01());
      const double factor = 1.001 + 29.0 * rng.uniform01();
      trial_at_factor(s, old, e_dir, r_dir, factor, eps, rho);
      const double gam[2] = {eps_y(s) * rng(), eps_y(s) * rng()};
      PlasticState next{};
      double N[3], Q[2], M[3];
      const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, old, next, N, Q, M);
      expect_plastic_return_consistent(s, eps, gam, rho, old, next, N, Q, M, r);
      stats.add(r);

      // `next` may alias `old`: identical results (bitwise).
      PlasticState inplace = old;
      double N2[3], Q2[2], M2[3];
      const ReturnMapResult r2 = resultant_return_map(s, eps, gam, rho, inplace, inplace, N2, Q2, M2);
      EXPECT_EQ(r2.iterations, r.iterations);
      EXPECT_EQ(r2.plastic_work, r.plastic_work);
      EXPECT_EQ(inplace.alpha, next.alpha);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(inplace.eps_p[k], next.eps_p[k]);
        EXPECT_EQ(inplace.rho_p[k], next.rho_p[k]);
        EXPECT_EQ(N2[k], N[k]);
        EXPECT_EQ(M2[k], M[k]);
      }
    }
    stats.print(names[is]);
  }
}

// (Test 2) Elastic trial states return unchanged: plastic false, iterations 0, plastic_work exactly 0, state
// bitwise unchanged, resultants bitwise equal to elastic_resultants with the old plastic strains. Elastic
// unloading after plastic loading (elastic strain scaled by 0.999 ... -0.999, so sigma_eq <= 0.999 sigma_y) leaves
// the state unchanged and N, M = factor * (N, M)_loaded to 1e-13 relative; factor -1.001 reverses yielding.
TEST(ResultantPlasticity, ElasticTrialAndUnloading) {
  Rng rng(3);
  const PlasticSection sections[3] = {panel(0.0), panel(0.1 * 10.5e6), tearing()};
  for (const PlasticSection& s : sections) {
    for (int i = 0; i < 300; ++i) {
      const PlasticState old = random_state(rng, s);
      double e_dir[3], r_dir[3], eps[3], rho[3];
      rng.vec(e_dir, 1.0);
      rng.vec(r_dir, rho_y(s) / eps_y(s));
      trial_at_factor(s, old, e_dir, r_dir, 0.999 * rng.uniform01(), eps, rho);
      const double gam[2] = {eps_y(s) * rng(), eps_y(s) * rng()};
      PlasticState next = random_state(rng, s);  // garbage that must be overwritten
      double N[3], Q[2], M[3], Ne[3], Qe[2], Me[3];
      const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, old, next, N, Q, M);
      elastic_resultants(s.elastic, eps, gam, rho, old.eps_p, old.gam_p, old.rho_p, Ne, Qe, Me);
      EXPECT_FALSE(r.plastic);
      EXPECT_TRUE(r.converged);
      EXPECT_EQ(r.iterations, 0);
      EXPECT_EQ(r.plastic_work, 0.0);
      EXPECT_EQ(next.alpha, old.alpha);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(next.eps_p[k], old.eps_p[k]);
        EXPECT_EQ(next.rho_p[k], old.rho_p[k]);
        EXPECT_EQ(N[k], Ne[k]);
        EXPECT_EQ(M[k], Me[k]);
      }
      EXPECT_EQ(Q[0], Qe[0]);
      EXPECT_EQ(Q[1], Qe[1]);
    }

    // Load plastically (trial 3x yield, combined), then unload elastically.
    for (int i = 0; i < 50; ++i) {
      const PlasticState s0 = random_state(rng, s);
      double e_dir[3], r_dir[3], eps1[3], rho1[3];
      rng.vec(e_dir, 1.0);
      rng.vec(r_dir, rho_y(s) / eps_y(s));
      trial_at_factor(s, s0, e_dir, r_dir, 3.0, eps1, rho1);
      const double gam[2] = {0.0, 0.0};
      PlasticState s1{};
      double N1[3], Q1[2], M1[3];
      const ReturnMapResult r1 = resultant_return_map(s, eps1, gam, rho1, s0, s1, N1, Q1, M1);
      ASSERT_TRUE(r1.plastic);
      for (double f : {0.999, 0.5, 0.0, -0.5, -0.999}) {
        double eps2[3], rho2[3];
        for (int k = 0; k < 3; ++k) {
          eps2[k] = s1.eps_p[k] + f * (eps1[k] - s1.eps_p[k]);
          rho2[k] = s1.rho_p[k] + f * (rho1[k] - s1.rho_p[k]);
        }
        PlasticState s2{};
        double N2[3], Q2[2], M2[3];
        const ReturnMapResult r2 = resultant_return_map(s, eps2, gam, rho2, s1, s2, N2, Q2, M2);
        EXPECT_FALSE(r2.plastic) << "f = " << f;
        EXPECT_EQ(r2.iterations, 0);
        EXPECT_EQ(r2.plastic_work, 0.0);
        EXPECT_EQ(s2.alpha, s1.alpha);
        for (int k = 0; k < 3; ++k) {
          EXPECT_EQ(s2.eps_p[k], s1.eps_p[k]);
          EXPECT_EQ(s2.rho_p[k], s1.rho_p[k]);
          EXPECT_NEAR(N2[k], f * N1[k], 1e-13 * norm3(N1));
          EXPECT_NEAR(M2[k], f * M1[k], 1e-13 * norm3(M1));
        }
      }
      // Beyond the opposite side of the (isotropically hardened) surface: reverse yielding.
      double eps3[3], rho3[3];
      for (int k = 0; k < 3; ++k) {
        eps3[k] = s1.eps_p[k] - 1.001 * (eps1[k] - s1.eps_p[k]);
        rho3[k] = s1.rho_p[k] - 1.001 * (rho1[k] - s1.rho_p[k]);
      }
      PlasticState s3{};
      double N3[3], Q3[2], M3[3];
      const ReturnMapResult r3 = resultant_return_map(s, eps3, gam, rho3, s1, s3, N3, Q3, M3);
      expect_plastic_return_consistent(s, eps3, gam, rho3, s1, s3, N3, Q3, M3, r3);
    }
  }
}

// (Test 3) Uniaxial membrane stress: eps11 driven monotonically from 0 to 20 eps_y in 400 increments, eps12 = 0,
// eps22 found every increment (Illinois root finding on the return map, |N22| <= 1e-13 Y0 h), so that
// N22 = N12 = 0. Compared with the exact 1D bilinear solution (header comment):
//   sigma = N11/h vs E (eps11 - alpha_ex): 1e-11 relative; alpha vs alpha_ex: 1e-11 eps_y;
//   eps22 vs -nu (eps11 - alpha) - alpha/2 (plastic lateral contraction 1/2): 1e-11 eps11;
//   hardening slope (sigma_{k+1} - sigma_k)/(alpha_{k+1} - alpha_k) = H on plastic increments to 1e-8 relative
//   (round-off 1e-16 sigma over d sigma ~ 5e-3 Y0, and the N22 tolerance); H = 0: N11 = Y0 h to 1e-12.
void run_uniaxial_membrane(const PlasticSection& s, const char* name) {
  const double E = young(s), nu = s.elastic.nu, ey = eps_y(s);
  const int n_inc = 400;
  const double eps_max = 20.0 * ey;
  PlasticState st = zero_state();
  double eps22 = 0.0, sigma_prev = 0.0, alpha_prev = 0.0;
  IterStats stats;
  int n_plastic = 0;
  for (int k = 1; k <= n_inc; ++k) {
    const double eps11 = eps_max * k / n_inc;
    const double gam[2] = {0.0, 0.0}, rho[3] = {0.0, 0.0, 0.0};
    auto N22_of = [&](double e22) {
      const double eps[3] = {eps11, e22, 0.0};
      PlasticState tmp{};
      double N[3], Q[2], M[3];
      resultant_return_map(s, eps, gam, rho, st, tmp, N, Q, M);
      return N[1];
    };
    bool ok = false;
    eps22 = solve_increasing(N22_of, eps22 - nu * eps_max / n_inc, 0.5 * eps_max / n_inc, 1e-13 * s.Y0 * s.h, ok);
    ASSERT_TRUE(ok) << name << " increment " << k;
    const double eps[3] = {eps11, eps22, 0.0};
    PlasticState next{};
    double N[3], Q[2], M[3];
    const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, st, next, N, Q, M);
    ASSERT_TRUE(r.converged);
    stats.add(r);
    EXPECT_EQ(N[2], 0.0);
    EXPECT_LE(std::abs(N[1]), 1e-13 * s.Y0 * s.h);
    const double alpha_ex = std::max(0.0, (E * eps11 - s.Y0) / (E + s.H));
    const double sigma_ex = E * (eps11 - alpha_ex);
    const double sigma = N[0] / s.h;
    EXPECT_NEAR(sigma, sigma_ex, 1e-11 * sigma_ex) << name << " increment " << k;
    EXPECT_NEAR(next.alpha, alpha_ex, 1e-11 * ey) << name << " increment " << k;
    EXPECT_NEAR(eps22, -nu * (eps11 - alpha_ex) - 0.5 * alpha_ex, 1e-11 * eps11) << name << " increment " << k;
    if (r.plastic) {
      ++n_plastic;
      expect_plastic_return_consistent(s, eps, gam, rho, st, next, N, Q, M, r);
      EXPECT_NEAR(sigma, s.Y0 + s.H * next.alpha, 1e-12 * sigma);
      if (s.H == 0.0) {
        EXPECT_NEAR(N[0], s.Y0 * s.h, 1e-12 * s.Y0 * s.h);
      }
      if (alpha_prev > 0.0 && s.H > 0.0) {
        const double slope = (sigma - sigma_prev) / (next.alpha - alpha_prev);
        EXPECT_NEAR(slope, s.H, 1e-8 * s.H) << name << " increment " << k;
      }
    }
    sigma_prev = sigma;
    alpha_prev = next.alpha;
    st = next;
  }
  EXPECT_EQ(n_plastic, n_inc - 20);  // first yield at eps11 = eps_y, i.e. after increment 20
  stats.print(name);
}

TEST(ResultantPlasticity, UniaxialMembraneHardeningAndSaturation) {
  run_uniaxial_membrane(panel(0.0), "uniaxial membrane panel H=0");
  run_uniaxial_membrane(panel(0.1 * 10.5e6), "uniaxial membrane panel H=0.1E");
  run_uniaxial_membrane(tearing(), "uniaxial membrane tearing");
  run_uniaxial_membrane(nu_zero(), "uniaxial membrane nu=0");
}

// (Test 4) Pure bending, uniaxial moment state: rho11 driven monotonically from 0 to 10 rho_y (rho_y = 3 Y0/(E h))
// in 400 increments, rho12 = 0, rho22 found every increment so that M22 = 0 (|M22| <= 1e-13 M0), eps = gam = 0.
// H = 0: M11 = E h^3 rho11/12 to 1e-12 relative while elastic, M11 = M0 = Y0 h^2/4 to 1e-10 relative once plastic
// (first yield = Ilyushin limit in this resultant model). H > 0: M11 = (h^2/4)(Y0 + H h q/4) with
// q = rho11 - 12 M11/(E h^3), to 1e-11 relative. Always: N = 0 exactly, rho22 = -nu (rho11 - q) - q/2 to 1e-11 rho11.
void run_pure_bending(const PlasticSection& s, const char* name) {
  const double E = young(s), nu = s.elastic.nu, h = s.h, ry = rho_y(s);
  const double M0 = s.Y0 * h * h / 4.0, Db = E * h * h * h / 12.0;
  const int n_inc = 400;
  const double rho_max = 10.0 * ry;
  PlasticState st = zero_state();
  double rho22 = 0.0;
  IterStats stats;
  int n_plastic = 0;
  for (int k = 1; k <= n_inc; ++k) {
    const double rho11 = rho_max * k / n_inc;
    const double gam[2] = {0.0, 0.0}, eps[3] = {0.0, 0.0, 0.0};
    auto M22_of = [&](double r22) {
      const double rho[3] = {rho11, r22, 0.0};
      PlasticState tmp{};
      double N[3], Q[2], M[3];
      resultant_return_map(s, eps, gam, rho, st, tmp, N, Q, M);
      return M[1];
    };
    bool ok = false;
    rho22 = solve_increasing(M22_of, rho22 - nu * rho_max / n_inc, 0.5 * rho_max / n_inc, 1e-13 * M0, ok);
    ASSERT_TRUE(ok) << name << " increment " << k;
    const double rho[3] = {rho11, rho22, 0.0};
    PlasticState next{};
    double N[3], Q[2], M[3];
    const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, st, next, N, Q, M);
    ASSERT_TRUE(r.converged);
    stats.add(r);
    EXPECT_EQ(N[0], 0.0);
    EXPECT_EQ(N[1], 0.0);
    EXPECT_EQ(N[2], 0.0);
    EXPECT_EQ(M[2], 0.0);
    EXPECT_LE(std::abs(M[1]), 1e-13 * M0);
    const double q = rho11 - M[0] / Db;  // rho^p_11
    EXPECT_NEAR(next.rho_p[0], q, 1e-11 * rho11);
    EXPECT_NEAR(rho22, -nu * (rho11 - q) - 0.5 * q, 1e-11 * rho11) << name << " increment " << k;
    if (!r.plastic) {
      EXPECT_NEAR(M[0], Db * rho11, 1e-12 * Db * rho11) << name << " increment " << k;
    } else {
      ++n_plastic;
      expect_plastic_return_consistent(s, eps, gam, rho, st, next, N, Q, M, r);
      if (s.H == 0.0) {
        EXPECT_NEAR(M[0], M0, 1e-10 * M0) << name << " increment " << k;
      } else {
        const double ref = h * h / 4.0 * (s.Y0 + s.H * h * q / 4.0);
        EXPECT_NEAR(M[0], ref, 1e-11 * ref) << name << " increment " << k;
        EXPECT_NEAR(next.alpha, h * q / 4.0, 1e-11 * h * q / 4.0);  // d alpha = (h/4) d rho^p_11
      }
    }
    st = next;
  }
  EXPECT_EQ(n_plastic, n_inc - 40);  // first yield at rho11 = rho_y, i.e. after increment 40
  stats.print(name);
}

TEST(ResultantPlasticity, PureBendingIlyushinLimit) {
  run_pure_bending(panel(0.0), "pure bending panel H=0");
  run_pure_bending(tearing_perfect(), "pure bending tearing H=0");
  run_pure_bending(tearing(), "pure bending tearing H=894e6");
}

// (Test 5) Dissipation over a load-unload cycle of combined membrane + bending + shear strains: legs
// 0 -> A -> -A -> -0.8 A (reverse yielding in the second leg; the last leg is elastic unloading), n increments per
// leg. Checks (references in the header comment):
//   * plastic_work >= 0 every increment, and = N_{n+1}.d eps^p + M_{n+1}.d rho^p (1e-9 of the largest increment);
//   * the exact discrete identity W_ext - U_final - sum W_p = -1/2 sum (dN.d eps^p + dM.d rho^p) to 1e-11 W_ext;
//   * |W_ext - U_final - sum W_p| <= 2/n * sum W_p (measured 0.15/n for H = 0.1 E, see the output). Order: with
//     H > 0 the error is first order (error ratio n vs 2n in [1.9, 2.1]): on the surface
//     dN.d eps^p + dM.d rho^p ~ d sigma_y dgam = h H d alpha^2 per increment. With H = 0 it is second order (ratio
//     in [3.6, 4.4]): dS.grad sigma_eq(S_{n+1}) = O(|dS|^2) for two points on the same convex surface, so an
//     increment on the surface contributes O(1/n^3) and the few increments where yielding starts O(1/n^2) each;
//   * H > 0: sum W_p = h (Y0 alpha + H alpha^2/2) + (h H/2) sum d alpha^2 to 1e-11 (exact), hence
//     |sum W_p - h (Y0 alpha + H alpha^2/2)| <= (h H/2) max(d alpha) alpha (first order in the increment);
//   * the same sum with the midpoint yield stress, sum dgam (Y0 + H (alpha_n + alpha_{n+1})/2) = sum W_p -
//     (h H/2) sum d alpha^2, balances W_ext - U_final far better (measured 1.6e-4 and 2.3e-3 times the error of
//     sum W_p, convergence ratio n vs 2n 2.5-2.8): asserted |error_mid| <= 1e-2 |error| (information for the
//     energy balance of theory.md §9.7).
struct CycleResult {
  double W_ext = 0.0, U = 0.0, W_p = 0.0, identity_rhs = 0.0, sum_dalpha2 = 0.0, max_dalpha = 0.0, alpha = 0.0;
  double max_pw = 0.0, max_pw_mismatch = 0.0;
  int last_leg_plastic = 0, n_plastic = 0, negative_pw = 0;
  IterStats stats;
};

CycleResult run_cycle(const PlasticSection& s, int n) {
  const double ey = eps_y(s), ry = rho_y(s);
  const double eA[3] = {2.0 * ey, -0.8 * ey, 1.2 * ey};
  const double rA[3] = {-0.6 * ry, 1.4 * ry, 0.4 * ry};
  const double gA[2] = {0.5 * ey, -1.0 * ey};
  const double legs[4] = {0.0, 1.0, -1.0, -0.8};  // path parameter at the leg ends
  CycleResult c;
  PlasticState st = zero_state();
  double Np[3] = {0, 0, 0}, Mp[3] = {0, 0, 0}, Qp[2] = {0, 0};
  double ep[3] = {0, 0, 0}, rp[3] = {0, 0, 0}, gp[2] = {0, 0};
  for (int leg = 0; leg < 3; ++leg) {
    for (int k = 1; k <= n; ++k) {
      const double t = legs[leg] + (legs[leg + 1] - legs[leg]) * double(k) / n;
      const double eps[3] = {t * eA[0], t * eA[1], t * eA[2]}, rho[3] = {t * rA[0], t * rA[1], t * rA[2]};
      const double gam[2] = {t * gA[0], t * gA[1]};
      PlasticState next{};
      double N[3], Q[2], M[3];
      const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, st, next, N, Q, M);
      c.stats.add(r);
      if (!r.converged) ADD_FAILURE() << "not converged";
      if (r.plastic_work < 0.0) ++c.negative_pw;
      if (r.plastic) ++c.n_plastic;
      if (leg == 2 && r.plastic) ++c.last_leg_plastic;
      double pp = 0.0, dd = 0.0;
      for (int i = 0; i < 3; ++i) {
        c.W_ext += 0.5 * (Np[i] + N[i]) * (eps[i] - ep[i]) + 0.5 * (Mp[i] + M[i]) * (rho[i] - rp[i]);
        const double dep = next.eps_p[i] - st.eps_p[i], drp = next.rho_p[i] - st.rho_p[i];
        pp += N[i] * dep + M[i] * drp;
        dd += (N[i] - Np[i]) * dep + (M[i] - Mp[i]) * drp;
      }
      for (int i = 0; i < 2; ++i) c.W_ext += 0.5 * (Qp[i] + Q[i]) * (gam[i] - gp[i]);
      c.W_p += r.plastic_work;
      c.identity_rhs += -0.5 * dd;
      c.max_pw = std::max(c.max_pw, r.plastic_work);
      c.max_pw_mismatch = std::max(c.max_pw_mismatch, std::abs(r.plastic_work - pp));
      const double da = next.alpha - st.alpha;
      c.sum_dalpha2 += da * da;
      c.max_dalpha = std::max(c.max_dalpha, da);
      for (int i = 0; i < 3; ++i) {
        Np[i] = N[i];
        Mp[i] = M[i];
        ep[i] = eps[i];
        rp[i] = rho[i];
      }
      for (int i = 0; i < 2; ++i) {
        Qp[i] = Q[i];
        gp[i] = gam[i];
      }
      st = next;
    }
  }
  c.U = elastic_energy(s.elastic, ep, gp, rp, st.eps_p, st.gam_p, st.rho_p);
  c.alpha = st.alpha;
  // Final state is inside the yield surface.
  if (!(equivalent_stress(s, Np, Mp) < sigma_y(s, st.alpha))) ADD_FAILURE() << "final state not elastic";
  return c;
}

void check_cycle(const PlasticSection& s, const char* name) {
  const int n = 10000;
  const CycleResult c = run_cycle(s, n), c2 = run_cycle(s, 2 * n);
  EXPECT_EQ(c.negative_pw, 0);
  EXPECT_EQ(c.last_leg_plastic, 0);
  EXPECT_GT(c.n_plastic, n / 2);
  EXPECT_LE(c.max_pw_mismatch, 1e-9 * c.max_pw);
  const double err = c.W_ext - c.U - c.W_p, err2 = c2.W_ext - c2.U - c2.W_p;
  EXPECT_NEAR(err, c.identity_rhs, 1e-11 * c.W_ext);
  EXPECT_NEAR(err2, c2.identity_rhs, 1e-11 * c2.W_ext);
  EXPECT_LE(std::abs(err), 2.0 / n * c.W_p);
  const double ratio = err / err2;
  if (s.H > 0.0) {
    EXPECT_GE(ratio, 1.9);
    EXPECT_LE(ratio, 2.1);
  } else {
    EXPECT_GE(ratio, 3.6);
    EXPECT_LE(ratio, 4.4);
  }
  std::printf("[cycle] %-24s n=%d W_ext=%.10e U=%.6e W_p=%.10e  (W_ext-U-W_p)/W_p=%.3e (2n: %.3e, ratio %.4f)\n", name,
              n, c.W_ext, c.U, c.W_p, err / c.W_p, err2 / c2.W_p, ratio);
  if (s.H > 0.0) {
    const double a = c.alpha, smooth = s.h * (s.Y0 * a + 0.5 * s.H * a * a);
    EXPECT_NEAR(c.W_p, smooth + 0.5 * s.h * s.H * c.sum_dalpha2, 1e-11 * c.W_p);
    EXPECT_LE(std::abs(c.W_p - smooth), 0.5 * s.h * s.H * c.max_dalpha * a * (1.0 + 1e-9));
    std::printf("[cycle] %-24s alpha=%.6e  (W_p - h(Y0 a + H a^2/2))/W_p = %.3e\n", name, a, (c.W_p - smooth) / c.W_p);
    const double mid = c.W_p - 0.5 * s.h * s.H * c.sum_dalpha2, mid2 = c2.W_p - 0.5 * s.h * s.H * c2.sum_dalpha2;
    const double emid = c.W_ext - c.U - mid, emid2 = c2.W_ext - c2.U - mid2;
    std::printf("[cycle] %-24s midpoint sigma_y: (W_ext-U-W_p,mid)/W_p = %.3e (2n: %.3e, ratio %.4f)\n", name,
                emid / c.W_p, emid2 / c2.W_p, emid / emid2);
    EXPECT_LE(std::abs(emid), 1e-2 * std::abs(err));
  }
  c.stats.print(name);
}

TEST(ResultantPlasticity, DissipationLoadUnloadCycle) {
  check_cycle(panel(0.0), "cycle panel H=0");
  check_cycle(panel(0.1 * 10.5e6), "cycle panel H=0.1E");
  check_cycle(tearing(), "cycle tearing");
}

// (Test 6a) Closest point: normality d eps^p = dgam a_n P N/sigma_eq and d rho^p = dgam a_m P M/sigma_eq with the same
// dgam = h d alpha, to 1e-10 relative (norm-wise), for random combined membrane + bending (+ shear) trials; and no
// feasible point near the returned one has a smaller complementary-energy distance
// J = 1/2 |N - N_tr|^2_{(Dn C0)^-1} + 1/2 |M - M_tr|^2_{(Dm C0)^-1} + 1/2 H h (alpha' - alpha_n)^2: neighbours at
// relative distances 1e-2 and 1e-4, scaled onto the surface sigma_eq = Y0 + H alpha', all have J >= J_rm (1 - 1e-13).
TEST(ResultantPlasticity, ClosestPointNormalityAndMinimality) {
  const PlasticSection sections[3] = {panel(0.0), tearing(), nu_zero()};
  Rng rng(6);
  for (const PlasticSection& s : sections) {
    for (int i = 0; i < 200; ++i) {
      const PlasticState old = random_state(rng, s);
      double e_dir[3], r_dir[3], eps[3], rho[3];
      rng.vec(e_dir, 1.0);
      rng.vec(r_dir, rho_y(s) / eps_y(s));
      trial_at_factor(s, old, e_dir, r_dir, 1.01 + 10.0 * rng.uniform01(), eps, rho);
      const double gam[2] = {eps_y(s) * rng(), eps_y(s) * rng()};
      PlasticState next{};
      double N[3], Q[2], M[3];
      const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, old, next, N, Q, M);
      expect_plastic_return_consistent(s, eps, gam, rho, old, next, N, Q, M, r);
      expect_normality(s, old, next, N, Q, M);

      // Complementary-energy distance (the objective of the independent Python check).
      double Ntr[3], Mtr[3], Qtr[2];
      elastic_resultants(s.elastic, eps, gam, rho, old.eps_p, old.gam_p, old.rho_p, Ntr, Qtr, Mtr);
      auto J = [&](const double Nx[3], const double Mx[3], double ax) {
        const double dn[3] = {Nx[0] - Ntr[0], Nx[1] - Ntr[1], Nx[2] - Ntr[2]};
        const double dm[3] = {Mx[0] - Mtr[0], Mx[1] - Mtr[1], Mx[2] - Mtr[2]};
        double cn[3], cm[3];
        c0_inverse(s.elastic.Dn, s.elastic.nu, dn, cn);
        c0_inverse(s.elastic.Dm, s.elastic.nu, dm, cm);
        return 0.5 * (dot3(dn, cn) + dot3(dm, cm)) + 0.5 * s.H * s.h * (ax - old.alpha) * (ax - old.alpha);
      };
      const double J_rm = J(N, M, next.alpha);
      for (double delta : {1e-2, 1e-4}) {
        for (int j = 0; j < 50; ++j) {
          double Nx[3], Mx[3];
          for (int k = 0; k < 3; ++k) {
            Nx[k] = N[k] + delta * norm3(N) * rng();
            Mx[k] = M[k] + delta * norm3(M) * rng();
          }
          const double ax = next.alpha + delta * (next.alpha - old.alpha) * rng();
          const double scale = sigma_y(s, ax) / equivalent_stress(s, Nx, Mx);
          for (int k = 0; k < 3; ++k) {
            Nx[k] *= scale;
            Mx[k] *= scale;
          }
          EXPECT_GE(J(Nx, Mx, ax), J_rm * (1.0 - 1e-13));
        }
      }
    }
  }
}

// (Test 6b) The five random trials of an earlier Python check (E = 72e9, nu = 0.343, h = 2e-3, Y0 = 320e6,
// H = 894e6, gam = 0; inputs eps, kap (= rho), alpha_n printed with repr() from numpy default_rng(0)). References:
// 50-digit mpmath solution of the return map (dense solves, no spectral basis), rounded to 17 digits. Tolerance
// 1e-12 relative (norm-wise N, M; alpha). The Python check itself printed the same values for trials 0-3 (to ~1e-15);
// for trial 4 it printed N = [-354763.03115988977, 30338.514014386077, -286763.17128976714] (3.6e-10 off, yield
// residual 4.08e-10): its Newton loop replaced an exact root g(z) = 0 by the bracket midpoint (a strict
// bracket test, theory.md §4.3), which this implementation avoids.
TEST(ResultantPlasticity, ReproducesReferenceTrials) {
  const PlasticSection s = tearing();
  struct Trial {
    double eps[3], kap[3], alpha_n;
    double N[3], M[3], alpha;
  };
  const Trial trials[5] = {
      {{0.001257302210933933, -0.0013210486329130189, 0.006404226504432821},
       {1.049001171530397, -5.356693731611109, 3.6159505490948476},
       0.006066357757671799,
       {102410.16025673189, -114167.07796972903, 268972.25655243169},
       {-42.128079403389593, -209.40659804787092, 47.213523317169052},
       0.007188658611211967},
      {{0.009470809631292421, -0.007037352358069926, -0.012654214710460526},
       {-6.232744625373522, 0.413259793472436, -23.250307746388344},
       0.0003358557530546436,
       {345622.25550815507, -151352.06241623092, -190476.07264371067},
       {-90.788821352594467, -36.993727913515029, -94.098077497328815},
       0.010837969505993104},
      {{-0.012459109472530651, -0.007322673547034517, -0.005442589828573099},
       {-3.1630015636915454, 4.116305363741328, 10.425133694426776},
       0.0002831967114546297,
       {-694711.43991884922, -573648.80636871576, -64139.246311788209},
       {-14.449876465565525, 30.936496472493115, 32.500278563692833},
       0.014998305897476254},
      {{0.013664634705496859, -0.0066519467348661356, 0.0035151007009301973},
       {9.034701816518085, 0.9401229776087456, -7.4349924935380844},
       0.0098083533877623,
       {597349.03908180711, -27130.455811566196, 54022.580439030108},
       {145.25082008489517, 78.247215120642912, -30.771909809227954},
       0.020270860601918791},
      {{-0.004577258256673392, 0.002201951234700494, -0.01009618183538736},
       {-2.0917557487171305, -1.5922500991447772, 5.408455846858077},
       0.005253543224757259,
       {-354763.03103211432, 30338.513989609574, -286763.17117617032},
       {-78.591294372169756, -70.414524681634059, 44.267465121817307},
       0.0088727363800069012},
  };
  IterStats stats;
  for (const Trial& t : trials) {
    const PlasticState old{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, t.alpha_n, {0.0, 0.0}};
    const double gam[2] = {0.0, 0.0};
    PlasticState next{};
    double N[3], Q[2], M[3];
    const ReturnMapResult r = resultant_return_map(s, t.eps, gam, t.kap, old, next, N, Q, M);
    expect_plastic_return_consistent(s, t.eps, gam, t.kap, old, next, N, Q, M, r);
    stats.add(r);
    EXPECT_LE(diff3(N, t.N), 1e-12 * norm3(t.N));
    EXPECT_LE(diff3(M, t.M), 1e-12 * norm3(t.M));
    EXPECT_NEAR(next.alpha, t.alpha, 1e-12 * t.alpha);
  }
  stats.print("reference trials");
}

// (Test 7) Robustness: trial overstress factors f = sigma_eq(trial)/sigma_y(alpha_n) = 1 + 1e-14, 1 + 1e-10, 1.5, 1e3,
// 1e6 x elastic-strain directions (mixed-sign membrane, mixed-sign bending, pure N12, pure M12, uniaxial, combined)
// x 4 sections (H = 0 and H > 0, nu = 0) x old states (virgin and random). Asserted: plastic, converged,
// iterations < 60 (required) and <= 8 (measured max 7 with the tight bracket of the header), finite outputs,
// consistency to 1e-12 (expect_plastic_return_consistent); for the small overshoots f = 1 + 1e-14, 1 + 1e-10:
// |S - S_tr| <= 2 (f - 1) |S_tr| + 1e-13 |S_tr| (S = N, M) and 0 <= alpha - alpha_n <= 2 (f - 1) sigma_y(alpha_n)/E
// (uniaxial: d alpha = (f - 1) sigma_y/(E + H); pure moment: 3/4 of that; pure N12: 2(1+nu)/3 of that), plus the
// round-off of the difference alpha - alpha_n (4e-16 alpha).
TEST(ResultantPlasticity, RobustnessExtremeTrials) {
  const PlasticSection sections[4] = {panel(0.0), panel(0.1 * 10.5e6), tearing(), nu_zero()};
  const double factors[5] = {1.0 + 1e-14, 1.0 + 1e-10, 1.5, 1e3, 1e6};
  const double dirs[6][6] = {
      {1.0, -0.7, 0.3, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, -0.2, 1.0, -0.9}, {0.0, 0.0, 1.0, 0.0, 0.0, 0.0},
      {0.0, 0.0, 0.0, 0.0, 0.0, -1.0}, {-1.0, 0.0, 0.0, 0.0, 0.0, 0.0},  {0.4, -1.0, -0.6, 0.9, 0.3, -0.5},
  };
  Rng rng(7);
  int max_it[5] = {0, 0, 0, 0, 0};
  for (const PlasticSection& s : sections) {
    for (int istate = 0; istate < 2; ++istate) {
      const PlasticState old = istate == 0 ? zero_state() : random_state(rng, s);
      for (const auto& d : dirs) {
        const double e_dir[3] = {d[0], d[1], d[2]};
        const double r_dir[3] = {d[3] * rho_y(s) / eps_y(s), d[4] * rho_y(s) / eps_y(s), d[5] * rho_y(s) / eps_y(s)};
        for (int f = 0; f < 5; ++f) {
          double eps[3], rho[3];
          trial_at_factor(s, old, e_dir, r_dir, factors[f], eps, rho);
          const double gam[2] = {-3.0 * eps_y(s), 2.0 * eps_y(s)};
          PlasticState next{};
          double N[3], Q[2], M[3];
          const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, old, next, N, Q, M);
          expect_plastic_return_consistent(s, eps, gam, rho, old, next, N, Q, M, r);
          EXPECT_LT(r.iterations, 60);
          EXPECT_LE(r.iterations, 8);
          max_it[f] = std::max(max_it[f], r.iterations);
          if (factors[f] < 1.0 + 1e-9) {
            const double fm1 = factors[f] - 1.0;
            double Ntr[3], Qtr[2], Mtr[3];
            elastic_resultants(s.elastic, eps, gam, rho, old.eps_p, old.gam_p, old.rho_p, Ntr, Qtr, Mtr);
            EXPECT_LE(diff3(N, Ntr), (2.0 * fm1 + 1e-13) * norm3(Ntr));
            EXPECT_LE(diff3(M, Mtr), (2.0 * fm1 + 1e-13) * norm3(Mtr));
            EXPECT_LE(next.alpha - old.alpha, 2.0 * fm1 * sigma_y(s, old.alpha) / young(s) + 4e-16 * next.alpha);
          }
        }
      }
    }
  }
  for (int f = 0; f < 5; ++f)
    std::printf("[iterations] robustness factor %-10.3g max %d\n", factors[f] - (f < 2 ? 1.0 : 0.0), max_it[f]);
}

// (Test 8) The return map runs inside a Kokkos kernel (host execution space, as for the other point laws) and
// gives bitwise the same results as a plain host loop (same code, same inputs).
TEST(ResultantPlasticity, UsableInKokkosKernel) {
  const PlasticSection s = tearing();
  const int n = 64;
  Kokkos::View<double*[3], Kokkos::HostSpace> eps("eps", n), rho("rho", n), N("N", n), M("M", n);
  Kokkos::View<double*[2], Kokkos::HostSpace> gam("gam", n), Q("Q", n);
  Kokkos::View<PlasticState*, Kokkos::HostSpace> state("state", n);
  Kokkos::View<double*, Kokkos::HostSpace> work("work", n);
  Kokkos::View<int*, Kokkos::HostSpace> iters("iters", n), ok("ok", n);
  Rng rng(8);
  std::vector<PlasticState> old(n);
  for (int i = 0; i < n; ++i) {
    old[i] = random_state(rng, s);
    state(i) = old[i];
    double e_dir[3], r_dir[3], e[3], r[3];
    rng.vec(e_dir, 1.0);
    rng.vec(r_dir, rho_y(s) / eps_y(s));
    trial_at_factor(s, old[i], e_dir, r_dir, i % 2 == 0 ? 0.5 : 5.0, e, r);  // half elastic, half plastic
    for (int k = 0; k < 3; ++k) {
      eps(i, k) = e[k];
      rho(i, k) = r[k];
    }
    gam(i, 0) = eps_y(s) * rng();
    gam(i, 1) = eps_y(s) * rng();
  }
  Kokkos::parallel_for(
      "resultant_return_map", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, n), KOKKOS_LAMBDA(const int i) {
        const double e[3] = {eps(i, 0), eps(i, 1), eps(i, 2)}, r[3] = {rho(i, 0), rho(i, 1), rho(i, 2)};
        const double g[2] = {gam(i, 0), gam(i, 1)};
        double Ni[3], Qi[2], Mi[3];
        const ReturnMapResult res = resultant_return_map(s, e, g, r, state(i), state(i), Ni, Qi, Mi);
        for (int k = 0; k < 3; ++k) {
          N(i, k) = Ni[k];
          M(i, k) = Mi[k];
        }
        Q(i, 0) = Qi[0];
        Q(i, 1) = Qi[1];
        work(i) = res.plastic_work;
        iters(i) = res.iterations;
        ok(i) = res.converged ? 1 : 0;
      });
  Kokkos::fence();
  for (int i = 0; i < n; ++i) {
    const double e[3] = {eps(i, 0), eps(i, 1), eps(i, 2)}, r[3] = {rho(i, 0), rho(i, 1), rho(i, 2)};
    const double g[2] = {gam(i, 0), gam(i, 1)};
    PlasticState next{};
    double Ni[3], Qi[2], Mi[3];
    const ReturnMapResult res = resultant_return_map(s, e, g, r, old[i], next, Ni, Qi, Mi);
    EXPECT_EQ(ok(i), 1);
    EXPECT_EQ(res.plastic, i % 2 == 1);
    EXPECT_EQ(iters(i), res.iterations);
    EXPECT_EQ(work(i), res.plastic_work);
    EXPECT_EQ(state(i).alpha, next.alpha);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(N(i, k), Ni[k]);
      EXPECT_EQ(M(i, k), Mi[k]);
      EXPECT_EQ(state(i).eps_p[k], next.eps_p[k]);
      EXPECT_EQ(state(i).rho_p[k], next.rho_p[k]);
    }
    EXPECT_EQ(Q(i, 0), Qi[0]);
    EXPECT_EQ(Q(i, 1), Qi[1]);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Transverse shear in the yield function (`Shear Yield`, theory.md §4.1): sigma_eq^2 += a_q |Q|^2 with a_q = 3/h^2 and
// flow d gam^p = dgam a_q Q / sigma_eq. References:
//  * pure shear: sigma_eq = sqrt(3) |Q| / h, so the yield force is Q0 = h sigma_y / sqrt(3) (a uniform shear stress
//    at von Mises' limit sigma_y / sqrt(3); FEniQS q0, theory.md §4.1);
//  * monotone pure shear gam = [g, 0] (N = M = 0): d gam^p = dgam a_q Q / (sqrt(3) Q / h) = sqrt(3) d alpha, so
//    Q = D_s (g - sqrt(3) alpha) and sqrt(3) Q / h = Y0 + H alpha give the exact bilinear law (backward Euler is
//    exact for it at any increment size):  alpha = max(0, (sqrt(3) D_s g / h - Y0) / (3 D_s / h + H)).

/// Sections with the shear in the yield function: the panel (H = 0 and 0.1 E), tearing and nu = 0 data.
PlasticSection with_shear(double E, double nu, double h, double Y0, double H) {
  return make_plastic_section(E, nu, h, Y0, H, true);
}

/// Trial strains with sigma_eq(trial) = factor sigma_y(alpha_n): elastic parts along e_dir, g_dir, r_dir
/// added to the old plastic strains.
void trial_with_shear(const PlasticSection& s, const PlasticState& old, const double e_dir[3], const double g_dir[2],
                      const double r_dir[3], double factor, double eps[3], double gam[2], double rho[3]) {
  double N[3], Q[2], M[3];
  elastic_resultants(s.elastic, e_dir, g_dir, r_dir, N, Q, M);
  const double t = factor * sigma_y(s, old.alpha) / equivalent_stress(s, N, Q, M);
  for (int k = 0; k < 3; ++k) {
    eps[k] = old.eps_p[k] + t * e_dir[k];
    rho[k] = old.rho_p[k] + t * r_dir[k];
  }
  for (int k = 0; k < 2; ++k) gam[k] = old.gam_p[k] + t * g_dir[k];
}

// Section constant a_q = 3/h^2, sigma_eq of pure shear, and the default (a_q = 0: shear not in sigma_eq).
TEST(ResultantPlasticityShearYield, SectionAndEquivalentStress) {
  const double h = 0.125, Y0 = 44e3;
  const PlasticSection s = with_shear(10.5e6, 0.33, h, Y0, 0.0);
  EXPECT_NEAR(s.a_q, 192.0, 1e-14 * 192.0);  // 3 / h^2 = 3 * 64
  EXPECT_EQ(panel(0.0).a_q, 0.0);
  const double z3[3] = {0.0, 0.0, 0.0}, Q0 = h * Y0 / std::sqrt(3.0);
  const double Qx[2] = {Q0, 0.0}, Qd[2] = {0.6 * Q0, -0.8 * Q0};
  EXPECT_NEAR(equivalent_stress(s, z3, Qx, z3), Y0, 1e-14 * Y0);
  EXPECT_NEAR(equivalent_stress(s, z3, Qd, z3), Y0, 1e-14 * Y0);
  EXPECT_EQ(equivalent_stress(panel(0.0), z3, Qx, z3), 0.0);
  Rng rng(11);
  for (int i = 0; i < 200; ++i) {  // sigma_eq^2 is the sum of the N, M part and 3 |Q|^2 / h^2
    double N[3], M[3];
    rng.vec(N, Y0 * h);
    rng.vec(M, Y0 * h * h / 4.0);
    const double Q[2] = {Q0 * rng(), Q0 * rng()};
    const double nm = sigma_eq_explicit(s, N, M), ref = std::sqrt(nm * nm + 3.0 * (Q[0] * Q[0] + Q[1] * Q[1]) / (h * h));
    EXPECT_NEAR(equivalent_stress(s, N, Q, M), ref, 1e-14 * ref);
  }
}

// Monotone pure transverse shear against the exact bilinear law (header comment): 300 increments to 20 x the
// yield strain gam_y = Q0 / D_s, and the same end state in ONE increment; Q, alpha, gam^p to 1e-12 relative; for
// H = 0 the force saturates at Q0 = h Y0 / sqrt(3). Plastic work = integral of Q d gam^p = sum dgam sigma_y.
TEST(ResultantPlasticityShearYield, PureShearBilinearLaw) {
  const double sq3 = std::sqrt(3.0);
  for (const double H : {0.0, 894e6}) {
    const PlasticSection s = with_shear(72e9, 0.343, 2e-3, 320e6, H);
    const double Ds = s.elastic.Ds, h = s.h, Q0 = h * s.Y0 / sq3, gy = Q0 / Ds;
    const double dir[2] = {0.6, -0.8};
    auto exact = [&](double g, double& Q, double& alpha) {
      alpha = std::max(0.0, (sq3 * Ds * g / h - s.Y0) / (3.0 * Ds / h + s.H));
      Q = Ds * (g - sq3 * alpha);
    };
    const double z3[3] = {0.0, 0.0, 0.0};
    PlasticState st = zero_state();
    double work = 0.0, sum_da2 = 0.0;
    const int n = 300;
    for (int i = 1; i <= n; ++i) {
      const double g = 20.0 * gy * i / n;
      const double gam[2] = {g * dir[0], g * dir[1]};
      double N[3], Q[2], M[3];
      const PlasticState old = st;
      const ReturnMapResult r = resultant_return_map(s, z3, gam, z3, old, st, N, Q, M);
      ASSERT_TRUE(r.converged);
      work += r.plastic_work;
      sum_da2 += (st.alpha - old.alpha) * (st.alpha - old.alpha);
      double Qref, aref;
      exact(g, Qref, aref);
      EXPECT_NEAR(std::hypot(Q[0], Q[1]), Qref, 1e-12 * Qref) << "increment " << i;
      EXPECT_NEAR(Q[0] * dir[1] - Q[1] * dir[0], 0.0, 1e-12 * Qref);  // Q stays along gam
      EXPECT_NEAR(st.alpha, aref, 1e-12 * aref + 1e-300);
      EXPECT_NEAR(std::hypot(st.gam_p[0], st.gam_p[1]), sq3 * aref, 1e-12 * sq3 * aref + 1e-300);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(N[k], 0.0);
        EXPECT_EQ(M[k], 0.0);
        EXPECT_EQ(st.eps_p[k], 0.0);
      }
      if (H == 0.0 && i > n / 10) {
        EXPECT_NEAR(std::hypot(Q[0], Q[1]), Q0, 1e-12 * Q0);
      }
    }
    // Work: sum dgam sigma_y(alpha_{k+1}) = h (Y0 alpha + H alpha^2/2) + (h H/2) sum d alpha^2 (file header).
    const double a = st.alpha;
    const double ref = h * (s.Y0 * a + 0.5 * s.H * a * a) + 0.5 * h * s.H * sum_da2;
    EXPECT_NEAR(work, ref, 1e-12 * ref);
    if (H == 0.0) {  // Q0 times the plastic slip
      EXPECT_NEAR(work, Q0 * std::hypot(st.gam_p[0], st.gam_p[1]), 1e-12 * work);
    }
    // One increment to the same end state: the same answer (backward Euler is exact for the bilinear law).
    const double gend[2] = {20.0 * gy * dir[0], 20.0 * gy * dir[1]};
    PlasticState one{};
    double N[3], Q[2], M[3];
    const ReturnMapResult r = resultant_return_map(s, z3, gend, z3, zero_state(), one, N, Q, M);
    ASSERT_TRUE(r.converged);
    double Qref, aref;
    exact(20.0 * gy, Qref, aref);
    EXPECT_NEAR(std::hypot(Q[0], Q[1]), Qref, 1e-12 * Qref);
    EXPECT_NEAR(one.alpha, aref, 1e-12 * aref);
  }
}

// Combined membrane + bending + shear trials (4 sections x 300, overstress 1.001..30, random old states with plastic
// shear): the consistency checks of expect_plastic_return_consistent, and normality of all three plastic strains
// with one dgam = h d alpha: d eps^p = dgam a_n P N / sigma_eq, d rho^p = dgam a_m P M / sigma_eq,
// d gam^p = dgam a_q Q / sigma_eq, to 1e-10 relative (as ClosestPointNormalityAndMinimality). Also: the
// complementary-energy distance (now with 1/2 |Q - Q_tr|^2 / D_s) is not decreased by feasible neighbours.
TEST(ResultantPlasticityShearYield, ConsistencyAndNormality) {
  const PlasticSection sections[4] = {with_shear(10.5e6, 0.33, 0.125, 44e3, 0.0),
                                      with_shear(10.5e6, 0.33, 0.125, 44e3, 1.05e6),
                                      with_shear(72e9, 0.343, 2e-3, 320e6, 894e6),
                                      with_shear(2.0e11, 0.0, 5e-3, 250e6, 2e9)};
  const char* names[4] = {"shear yield panel H=0", "shear yield panel H=0.1E", "shear yield tearing",
                          "shear yield nu=0"};
  Rng rng(12);
  for (int is = 0; is < 4; ++is) {
    const PlasticSection& s = sections[is];
    const double gy = s.h * s.Y0 / std::sqrt(3.0) / s.elastic.Ds;
    IterStats stats;
    for (int i = 0; i < 300; ++i) {
      PlasticState old = random_state(rng, s);
      old.gam_p[0] = gy * rng(), old.gam_p[1] = gy * rng();
      double e_dir[3], r_dir[3], eps[3], gam[2], rho[3];
      rng.vec(e_dir, eps_y(s) * rng.uniform01());
      rng.vec(r_dir, rho_y(s) * rng.uniform01());
      const double g_dir[2] = {gy * rng() * (i % 3 == 0 ? 3.0 : 1.0), gy * rng()};
      trial_with_shear(s, old, e_dir, g_dir, r_dir, 1.001 + 29.0 * rng.uniform01(), eps, gam, rho);
      PlasticState next{};
      double N[3], Q[2], M[3];
      const ReturnMapResult r = resultant_return_map(s, eps, gam, rho, old, next, N, Q, M);
      expect_plastic_return_consistent(s, eps, gam, rho, old, next, N, Q, M, r);
      stats.add(r);
      expect_normality(s, old, next, N, Q, M);

      double Ntr[3], Mtr[3], Qtr[2];
      elastic_resultants(s.elastic, eps, gam, rho, old.eps_p, old.gam_p, old.rho_p, Ntr, Qtr, Mtr);
      auto J = [&](const double Nx[3], const double Qx[2], const double Mx[3], double ax) {
        const double dn[3] = {Nx[0] - Ntr[0], Nx[1] - Ntr[1], Nx[2] - Ntr[2]};
        const double dm[3] = {Mx[0] - Mtr[0], Mx[1] - Mtr[1], Mx[2] - Mtr[2]};
        const double dq[2] = {Qx[0] - Qtr[0], Qx[1] - Qtr[1]};
        double cn[3], cm[3];
        c0_inverse(s.elastic.Dn, s.elastic.nu, dn, cn);
        c0_inverse(s.elastic.Dm, s.elastic.nu, dm, cm);
        return 0.5 * (dot3(dn, cn) + dot3(dm, cm) + (dq[0] * dq[0] + dq[1] * dq[1]) / s.elastic.Ds) +
               0.5 * s.H * s.h * (ax - old.alpha) * (ax - old.alpha);
      };
      const double J_rm = J(N, Q, M, next.alpha);
      const double nQ = std::hypot(Q[0], Q[1]);
      for (double delta : {1e-2, 1e-4}) {
        for (int j = 0; j < 20; ++j) {
          double Nx[3], Mx[3], Qx[2];
          for (int k = 0; k < 3; ++k) {
            Nx[k] = N[k] + delta * norm3(N) * rng();
            Mx[k] = M[k] + delta * norm3(M) * rng();
          }
          for (int k = 0; k < 2; ++k) Qx[k] = Q[k] + delta * nQ * rng();
          const double ax = next.alpha + delta * (next.alpha - old.alpha) * rng();
          const double scale = sigma_y(s, ax) / equivalent_stress(s, Nx, Qx, Mx);
          for (int k = 0; k < 3; ++k) Nx[k] *= scale, Mx[k] *= scale;
          for (int k = 0; k < 2; ++k) Qx[k] *= scale;
          EXPECT_GE(J(Nx, Qx, Mx, ax), J_rm * (1.0 - 1e-13));
        }
      }
    }
    stats.print(names[is]);
    EXPECT_LE(stats.max, 12);
  }
}

}  // namespace
