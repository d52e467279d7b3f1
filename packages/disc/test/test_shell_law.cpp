// Shell strain measures (theory.md §2), elastic resultant law (theory.md §3.1) and stress-power vectors
// (theory.md §3.2) as point functions. References used below:
//  * reference state: eps_ij = 1/2 (a0_i.a0_j - delta_ij) = 0 for an orthonormal a0_i; gam and rho vanish by
//    construction of gam0 = a0_i.t0 and rho0 = sym(a0_i.d0_j) (theory.md §2), for any t0 (also off-normal) and
//    any d0 (curved reference);
//  * objectivity: all strains are built from dot products of a_i, d_i, t, hence invariant under
//    x -> R x; n^i, m^i, l are linear in a_i, d_i, t with invariant coefficients, hence rotate with R;
//  * gradient: dW = N^{ij} d eps_ij + M^{ij} d rho_ij + Q^i d gam_i gives n^i = dW/da_i, m^i = dW/dd_i,
//    l = dW/dt (theory.md §3.2 derivation), checked by central finite differences;
//  * closed forms: a_1 = (1+s) e_1 gives eps_11 = ((1+s)^2 - 1)/2 = s + s^2/2, N = D_n C0 eps_v gives
//    N_11 = D_n eps_11, N_22 = nu D_n eps_11; d_1 = k e_1 gives rho_11 = k, M_11 = D_m k, M_22 = nu D_m k;
//    a_1.t = g gives gam_1 = g, Q_1 = (5/6) G h g with G = E/(2(1+nu));
//  * section values for E = 2.1e6, nu = 0.3, h = 0.1 in 40-digit decimal arithmetic (Python `decimal`):
//    D_n = 230769.2307692307692307692, D_m = 192.3076923076923076923, D_s = 67307.69230769230769230769.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <cmath>
#include <random>

#include "shellfrac/disc/shell_strains.hpp"
#include "shellfrac/disc/stress_power.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"

using namespace shellfrac::disc;
using shellfrac::materials::elastic_energy;
using shellfrac::materials::elastic_resultants;
using shellfrac::materials::ElasticSection;
using shellfrac::materials::make_elastic_section;

namespace {

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const double a[3]) { return std::sqrt(dot(a, a)); }

// Rotation matrix from an axis (normalized here) and an angle (Rodrigues).
void rotation(const double axis[3], double angle, double R[3][3]) {
  const double n = norm(axis);
  const double k[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * k[i] * k[j];
}

void rotate(const double R[3][3], const double x[3], double y[3]) {
  for (int i = 0; i < 3; ++i) y[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2];
}

struct Rng {
  std::mt19937 gen;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  explicit Rng(unsigned seed) : gen(seed) {}
  double operator()() { return u(gen); }
  void vec(double x[3], double scale = 1.0) {
    for (int k = 0; k < 3; ++k) x[k] = scale * (*this)();
  }
  void random_rotation(double R[3][3]) {
    double axis[3];
    vec(axis);
    axis[0] += 1.5;  // keep it away from zero
    rotation(axis, 3.0 * (*this)(), R);
  }
};

ShellKinematics rotated(const double R[3][3], const ShellKinematics& k) {
  ShellKinematics r{};
  for (int i = 0; i < 2; ++i) rotate(R, k.a[i], r.a[i]), rotate(R, k.d[i], r.d[i]);
  rotate(R, k.t, r.t);
  return r;
}

// Curved reference: orthonormal a0_i = R e_i, off-normal unnormalized t0, arbitrary d0_i.
ShellKinematics random_reference(Rng& rng) {
  double R[3][3];
  rng.random_rotation(R);
  ShellKinematics k0{};
  const double e1[3] = {1, 0, 0}, e2[3] = {0, 1, 0};
  rotate(R, e1, k0.a[0]);
  rotate(R, e2, k0.a[1]);
  const double tloc[3] = {0.2 * rng(), 0.2 * rng(), 1.0 + 0.1 * rng()};
  rotate(R, tloc, k0.t);
  rng.vec(k0.d[0], 0.5);
  rng.vec(k0.d[1], 0.5);
  return k0;
}

// Random current kinematics near the reference (finite strains, not small); dscale sets the size of the
// director-gradient perturbation, i.e. of the bending strains.
ShellKinematics random_current(Rng& rng, const ShellKinematics& k0, double dscale = 0.5) {
  ShellKinematics k = k0;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 2; ++i) k.a[i][c] += 0.3 * rng(), k.d[i][c] += dscale * rng();
    k.t[c] += 0.3 * rng();
  }
  return k;
}

ShellKinematics flat_unit() {
  ShellKinematics k{};
  k.a[0][0] = 1.0;
  k.a[1][1] = 1.0;
  k.t[2] = 1.0;
  return k;
}

struct Law {
  ElasticSection sec;
  ShellReference ref;
  double eps_p[3], rho_p[3], gam_p[2];
  double energy(const ShellKinematics& k) const {
    double eps[3], gam[2], rho[3];
    compute_strains(k, ref, eps, gam, rho);
    return elastic_energy(sec, eps, gam, rho, eps_p, gam_p, rho_p);
  }
  void vectors(const ShellKinematics& k, double n[2][3], double m[2][3], double l[3]) const {
    double eps[3], gam[2], rho[3], N[3], Q[2], M[3];
    compute_strains(k, ref, eps, gam, rho);
    elastic_resultants(sec, eps, gam, rho, eps_p, gam_p, rho_p, N, Q, M);
    stress_power_vectors(k, N, Q, M, n, m, l);
  }
};

// Central finite difference of W with respect to the 3-vector x (a member of k, restored on exit),
// relative step 1e-6.
void fd_gradient(const Law& law, ShellKinematics& k, double* x, double g[3]) {
  const double h = 1e-6 * std::fmax(norm(x), 1e-3);
  for (int c = 0; c < 3; ++c) {
    const double x0 = x[c];
    x[c] = x0 + h;
    const double wp = law.energy(k);
    x[c] = x0 - h;
    const double wm = law.energy(k);
    x[c] = x0;
    g[c] = (wp - wm) / (2 * h);
  }
}

void expect_vec_near(const double got[3], const double want[3], double rel, const char* what) {
  const double scale = std::fmax(norm(want), 1e-300);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], rel * scale) << what << " component " << c;
}

}  // namespace

TEST(ShellLaw, SectionValues) {
  const ElasticSection s = make_elastic_section(2.1e6, 0.3, 0.1);
  EXPECT_NEAR(s.Dn, 230769.2307692307692307692, 1e-14 * 230769.23);
  EXPECT_NEAR(s.Dm, 192.3076923076923076923, 1e-14 * 192.31);
  EXPECT_NEAR(s.Ds, 67307.69230769230769230769, 1e-14 * 67307.69);
  EXPECT_EQ(s.nu, 0.3);
  // kappa is a parameter: kappa = 1 gives G h = 807692.307... * 0.1.
  EXPECT_NEAR(make_elastic_section(2.1e6, 0.3, 0.1, 1.0).Ds, 80769.23076923076923076923, 1e-14 * 80769.23);
}

TEST(ShellLaw, ReferenceStateFlat) {
  const ShellKinematics k0 = flat_unit();
  const ShellReference ref = make_shell_reference(k0);
  for (int c = 0; c < 2; ++c) EXPECT_EQ(ref.gam0[c], 0.0);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(ref.rho0[c], 0.0);
  double eps[3], gam[2], rho[3], N[3], Q[2], M[3];
  compute_strains(k0, ref, eps, gam, rho);
  const ElasticSection s = make_elastic_section(2.1e6, 0.3, 0.1);
  elastic_resultants(s, eps, gam, rho, N, Q, M);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(eps[c], 0.0);
    EXPECT_EQ(rho[c], 0.0);
    EXPECT_EQ(N[c], 0.0);
    EXPECT_EQ(M[c], 0.0);
  }
  for (int c = 0; c < 2; ++c) {
    EXPECT_EQ(gam[c], 0.0);
    EXPECT_EQ(Q[c], 0.0);
  }
  EXPECT_EQ(elastic_energy(s, eps, gam, rho), 0.0);
}

TEST(ShellLaw, ReferenceStateCurvedRandomFrame) {
  Rng rng(12345);
  const ElasticSection s = make_elastic_section(2.1e6, 0.3, 0.1);
  for (int trial = 0; trial < 20; ++trial) {
    const ShellKinematics k0 = random_reference(rng);
    const ShellReference ref = make_shell_reference(k0);
    // The reference is genuinely curved and t0 is off-normal, so the offsets are non-trivial.
    EXPECT_GT(std::fabs(ref.gam0[0]) + std::fabs(ref.gam0[1]), 1e-6);
    EXPECT_GT(std::fabs(ref.rho0[0]) + std::fabs(ref.rho0[1]) + std::fabs(ref.rho0[2]), 1e-6);
    double eps[3], gam[2], rho[3], N[3], Q[2], M[3], n[2][3], m[2][3], l[3];
    compute_strains(k0, ref, eps, gam, rho);
    elastic_resultants(s, eps, gam, rho, N, Q, M);
    stress_power_vectors(k0, N, Q, M, n, m, l);
    // eps: orthonormal a0_i up to the rounding of the rotation matrix; gam, rho: same expressions cancel.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(eps[c], 0.0, 1e-15);
      EXPECT_EQ(rho[c], 0.0);
      EXPECT_NEAR(N[c], 0.0, 1e-15 * s.Dn);
      EXPECT_EQ(M[c], 0.0);
      EXPECT_NEAR(l[c], 0.0, 1e-15 * s.Dn);
      for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(n[i][c], 0.0, 1e-14 * s.Dn);
        EXPECT_EQ(m[i][c], 0.0);
      }
    }
    for (int c = 0; c < 2; ++c) {
      EXPECT_EQ(gam[c], 0.0);
      EXPECT_EQ(Q[c], 0.0);
    }
    EXPECT_NEAR(elastic_energy(s, eps, gam, rho), 0.0, 1e-25 * s.Dn);
  }
}

TEST(ShellLaw, Objectivity) {
  Rng rng(777);
  for (int trial = 0; trial < 20; ++trial) {
    const ShellKinematics k0 = random_reference(rng);
    Law law{make_elastic_section(1.0e3, 0.25, 0.4), make_shell_reference(k0), {0.01, -0.02, 0.015}, {0.03, 0.01, -0.02},
            {0.004, -0.006}};
    const ShellKinematics k = random_current(rng, k0);
    double R[3][3];
    rng.random_rotation(R);
    const ShellKinematics kr = rotated(R, k);

    double eps[3], gam[2], rho[3], epsr[3], gamr[2], rhor[3];
    compute_strains(k, law.ref, eps, gam, rho);
    compute_strains(kr, law.ref, epsr, gamr, rhor);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(epsr[c], eps[c], 1e-14);
      EXPECT_NEAR(rhor[c], rho[c], 1e-14);
    }
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(gamr[c], gam[c], 1e-14);

    double n[2][3], m[2][3], l[3], nr[2][3], mr[2][3], lr[3], Rn[3];
    law.vectors(k, n, m, l);
    law.vectors(kr, nr, mr, lr);
    for (int i = 0; i < 2; ++i) {
      rotate(R, n[i], Rn);
      expect_vec_near(nr[i], Rn, 1e-13, "n^i");
      rotate(R, m[i], Rn);
      expect_vec_near(mr[i], Rn, 1e-13, "m^i");
    }
    rotate(R, l, Rn);
    expect_vec_near(lr, Rn, 1e-13, "l");
  }
}

TEST(ShellLaw, StressPowerIsGradientOfEnergy) {
  Rng rng(2024);
  // Two sections: a thin one (h = 0.1) and a thick one (h = 1). The bending strains are taken of the order
  // membrane strain / h, so that membrane and bending energies are comparable (D_m rho^2 ~ D_n eps^2):
  // otherwise the central difference of W w.r.t. d_i (whose gradient m^i is ~D_m/D_n = h^2/12 smaller)
  // is dominated by the rounding of the membrane energy, eps_mach W / step ~ 1e-6 relative for h = 0.1.
  // With this scaling the observed worst error over 400 samples is ~1e-7 (thin) and ~1e-8 (thick).
  const double thickness[2] = {0.1, 1.0};
  const ElasticSection sections[2] = {make_elastic_section(2.1e6, 0.3, thickness[0]),
                                      make_elastic_section(1.0e3, 0.2, thickness[1])};
  for (int is = 0; is < 2; ++is) {
    const ElasticSection& sec = sections[is];
    for (int trial = 0; trial < 20; ++trial) {
      const ShellKinematics k0 = (trial % 4 == 0) ? flat_unit() : random_reference(rng);
      Law law{sec, make_shell_reference(k0), {0, 0, 0}, {0, 0, 0}, {0, 0}};
      if (trial % 2 == 1) {  // plastic strains enter as eps - eps_p, rho - rho_p
        for (int c = 0; c < 3; ++c) law.eps_p[c] = 0.05 * rng(), law.rho_p[c] = 0.1 * rng();
      }
      ShellKinematics k = random_current(rng, k0, 0.5 / thickness[is]);
      double n[2][3], m[2][3], l[3], g[3];
      law.vectors(k, n, m, l);
      for (int i = 0; i < 2; ++i) {
        fd_gradient(law, k, k.a[i], g);
        expect_vec_near(g, n[i], 1e-6, "dW/da_i vs n^i");
        fd_gradient(law, k, k.d[i], g);
        expect_vec_near(g, m[i], 1e-6, "dW/dd_i vs m^i");
      }
      fd_gradient(law, k, k.t, g);
      expect_vec_near(g, l, 1e-6, "dW/dt vs l");
    }
  }
}

TEST(ShellLaw, UniaxialMembraneStretch) {
  const double E = 2.1e6, nu = 0.3, h = 0.1;
  const ElasticSection s = make_elastic_section(E, nu, h);
  const ShellReference ref = make_shell_reference(flat_unit());
  // Dyadic stretches: (1+s)^2 - 1 and s + s^2/2 are exact in binary, so eps_11 must match bit for bit.
  // Small stretches: eps_11 = 1/2 (a_1.a_1 - 1) cancels, so it is exact only up to the rounding of
  // |a_1|^2 ~ 1, i.e. an absolute error of a few 2^-53 (a property of the formula, theory.md §2).
  for (double st : {0.25, -0.125, 0.5, 0.01, 1e-3, 1e-6}) {
    const bool dyadic = (st == 0.25 || st == -0.125 || st == 0.5);
    ShellKinematics k = flat_unit();
    k.a[0][0] = 1.0 + st;
    double eps[3], gam[2], rho[3], N[3], Q[2], M[3];
    compute_strains(k, ref, eps, gam, rho);
    if (dyadic) {
      EXPECT_EQ(eps[0], st + 0.5 * st * st);
    } else {
      EXPECT_NEAR(eps[0], st + 0.5 * st * st, 4.0 * 1.1102230246251565e-16);
    }
    EXPECT_EQ(eps[1], 0.0);
    EXPECT_EQ(eps[2], 0.0);
    elastic_resultants(s, eps, gam, rho, N, Q, M);
    EXPECT_DOUBLE_EQ(N[0], s.Dn * eps[0]);
    EXPECT_DOUBLE_EQ(N[1], nu * s.Dn * eps[0]);
    EXPECT_EQ(N[2], 0.0);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(M[c], 0.0);
    for (int c = 0; c < 2; ++c) EXPECT_EQ(Q[c], 0.0);
    // n^1 = N11 a_1 along e_1, n^2 = N22 a_2 along e_2.
    double n[2][3], m[2][3], l[3];
    stress_power_vectors(k, N, Q, M, n, m, l);
    EXPECT_DOUBLE_EQ(n[0][0], N[0] * (1.0 + st));
    EXPECT_DOUBLE_EQ(n[1][1], N[1]);
    // W = 1/2 D_n eps_11^2.
    EXPECT_DOUBLE_EQ(elastic_energy(s, eps, gam, rho), 0.5 * s.Dn * eps[0] * eps[0]);
  }
}

TEST(ShellLaw, PureBending) {
  const double E = 2.1e6, nu = 0.3, h = 0.1;
  const ElasticSection s = make_elastic_section(E, nu, h);
  const ShellReference ref = make_shell_reference(flat_unit());
  for (double kap : {0.5, -2.0, 1e-3}) {
    ShellKinematics k = flat_unit();
    k.d[0][0] = kap;
    double eps[3], gam[2], rho[3], N[3], Q[2], M[3];
    compute_strains(k, ref, eps, gam, rho);
    EXPECT_EQ(rho[0], kap);
    EXPECT_EQ(rho[1], 0.0);
    EXPECT_EQ(rho[2], 0.0);
    elastic_resultants(s, eps, gam, rho, N, Q, M);
    EXPECT_DOUBLE_EQ(M[0], s.Dm * kap);
    EXPECT_DOUBLE_EQ(M[1], nu * s.Dm * kap);
    EXPECT_EQ(M[2], 0.0);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(N[c], 0.0);
    // D_m = E h^3 / (12 (1 - nu^2)).
    EXPECT_NEAR(M[0], E * h * h * h / (12 * (1 - nu * nu)) * kap, 1e-14 * std::fabs(M[0]));
    // m^1 = M11 a_1 + M12 a_2 = M11 e_1, m^2 = M22 e_2; n^1 picks up M11 d_1.
    double n[2][3], m[2][3], l[3];
    stress_power_vectors(k, N, Q, M, n, m, l);
    EXPECT_EQ(m[0][0], M[0]);
    EXPECT_EQ(m[1][1], M[1]);
    EXPECT_EQ(n[0][0], M[0] * kap);
  }
}

TEST(ShellLaw, PureTransverseShear) {
  const double E = 2.1e6, nu = 0.3, h = 0.1;
  const double G = E / (2 * (1 + nu));
  const ElasticSection s = make_elastic_section(E, nu, h);
  const ShellReference ref = make_shell_reference(flat_unit());
  for (double g : {0.125, -0.01}) {
    ShellKinematics k = flat_unit();
    k.t[0] = g;  // a_1 . t = g, t not normalized (theory.md §2)
    double eps[3], gam[2], rho[3], N[3], Q[2], M[3];
    compute_strains(k, ref, eps, gam, rho);
    EXPECT_EQ(gam[0], g);
    EXPECT_EQ(gam[1], 0.0);
    elastic_resultants(s, eps, gam, rho, N, Q, M);
    EXPECT_NEAR(Q[0], 5.0 / 6.0 * G * h * g, 1e-14 * std::fabs(Q[0]));
    EXPECT_EQ(Q[1], 0.0);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(N[c], 0.0);
      EXPECT_EQ(M[c], 0.0);
    }
    // l = Q^1 a_1 = Q1 e_1; n^1 = Q1 t.
    double n[2][3], m[2][3], l[3];
    stress_power_vectors(k, N, Q, M, n, m, l);
    EXPECT_EQ(l[0], Q[0]);
    EXPECT_EQ(n[0][0], Q[0] * g);
    EXPECT_EQ(n[0][2], Q[0]);
  }
}

// The point functions are usable inside a Kokkos kernel (host execution space here).
TEST(ShellLaw, UsableInKokkosKernel) {
  Rng rng(99);
  const ShellKinematics k0 = random_reference(rng);
  const ShellKinematics k = random_current(rng, k0);
  const ShellReference ref = make_shell_reference(k0);
  const ElasticSection sec = make_elastic_section(2.1e6, 0.3, 0.1);
  double w_host = 0;
  {
    double eps[3], gam[2], rho[3];
    compute_strains(k, ref, eps, gam, rho);
    w_host = elastic_energy(sec, eps, gam, rho);
  }
  double w_dev = 0;
  Kokkos::parallel_reduce(
      "shell_law_energy", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, 4),
      KOKKOS_LAMBDA(const int, double& acc) {
        double eps[3], gam[2], rho[3], N[3], Q[2], M[3], n[2][3], m[2][3], l[3];
        compute_strains(k, ref, eps, gam, rho);
        elastic_resultants(sec, eps, gam, rho, N, Q, M);
        stress_power_vectors(k, N, Q, M, n, m, l);
        acc += elastic_energy(sec, eps, gam, rho);
      },
      w_dev);
  EXPECT_NEAR(w_dev, 4 * w_host, 1e-12 * std::fabs(w_host));
}
