// Resultant plasticity point law (theory.md §4), one return at a time: the section constants and sigma_eq
// closed forms (§4.1), consistency, normality and minimality of the closest-point return (§4.2-4.3), elastic
// trials and unloading, the reference trials of the Python check, extreme overstresses, and the law inside a
// Kokkos kernel. The references cited below are in the header comment of resultant_plasticity_test_cases.hpp.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "resultant_plasticity_test_cases.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"

using namespace shellfrac::materials;
using namespace shellfrac::materials::plasticity_test;

namespace {

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

}  // namespace
