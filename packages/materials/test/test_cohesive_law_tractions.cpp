// Extrinsic resultant cohesive law (theory.md §9.1-9.3, §9.5 step 2; Talamini & Radovitzky, the paper, §3,
// eqs. 19-31), the tractions at one opening: derived constants and the strength function, the tractions as the
// gradient of the free energy, single-mode loading through separation, consistency of the nucleation measure,
// degenerate cases, and the law inside a Kokkos kernel. The references cited below as the file header are in
// the header comment of cohesive_law_test_cases.hpp.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cohesive_law_test_cases.hpp"
#include "shellfrac/materials/cohesive_law.hpp"

using namespace shellfrac::materials;
using namespace shellfrac::materials::cohesive_test;

namespace {

/// phi(jumps; delta_max) = 1/2 S(delta_max) delta^2/delta_max at FIXED delta_max (eq. 24), written from
/// effective_opening and cohesive_strength.
double phi_fixed(const CohesiveParams& p, const double jphi[3], const double jt[3], const double nu[3], double dmax) {
  const double d = effective_opening(p, jphi, jt, nu);
  return 0.5 * cohesive_strength(p, dmax) * d * d / dmax;
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
