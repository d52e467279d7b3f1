// Resultant plasticity point law (theory.md §4) with the transverse shear in the yield function (`Shear Yield`,
// §4.1). References: below, and for the work sum of the plastic returns the header comment of
// resultant_plasticity_test_cases.hpp (cited as the file header).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "resultant_plasticity_test_cases.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"

using namespace shellfrac::materials;
using namespace shellfrac::materials::plasticity_test;

namespace {

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
