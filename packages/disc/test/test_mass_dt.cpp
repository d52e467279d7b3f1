// Element geometry at quadrature points, HRZ-lumped mass / rotary inertia and the element stable time step
// (theory.md §1.3-§1.4, §6, §8).
// References used below:
//  * affine triangle: G_1 = X2 - X1, G_2 = X3 - X1 are constant, j0 = |G_1 x G_2| = 2 Area (theory.md §1.4);
//  * cylinder of radius R: developable, dS = R dtheta dz, so the patch over a parametric (theta, z) triangle
//    of area A_p has exact area R A_p;
//  * HRZ for an affine P2 triangle: int N_vertex^2 = Area/30, int N_mid^2 = 8 Area/45, so
//    d_vertex / sum d = (1/30) / (3/30 + 3*8/45) = 1/19 and d_mid / sum d = 16/57 (theory.md §6);
//    P1: int L_a^2 = Area/6 each, so 1/3 each;
//  * stable time step: the closed-form formulas of theory.md §8, evaluated by hand below and in 40-digit
//    decimal arithmetic (Python `decimal`, prec = 40) for the fuselage numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "shellfrac/disc/element_geometry.hpp"
#include "shellfrac/disc/lumped_mass.hpp"
#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/disc/stable_time_step.hpp"
#include "shellfrac/core/triangle_basis.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;

namespace {

void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const double a[3]) { return std::sqrt(dot(a, a)); }

// Rotation matrix from an axis (normalized here) and an angle (Rodrigues).
void rotation(const double axis[3], double angle, double Q[3][3]) {
  const double n = norm(axis);
  const double k[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  const double K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Q[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * k[i] * k[j];
}

// Affine P2 element: 2-D vertices (x, y) rotated by Q and translated by t; mid-sides at edge midpoints.
void affine_element(const double v2d[3][2], const double Q[3][3], const double t[3], double X[6][3]) {
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) X[a][i] = Q[i][0] * v2d[a][0] + Q[i][1] * v2d[a][1] + t[i];
  const int mid[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < 3; ++i) X[3 + m][i] = 0.5 * (X[mid[m][0]][i] + X[mid[m][1]][i]);
}

// A generic affine element used by several tests (area of the 2-D triangle = 0.5 |0.9*0.8 - 0.3*(-0.2)|).
void generic_affine(double X[6][3], double& area) {
  const double v2d[3][2] = {{0.1, -0.2}, {1.0, 0.1}, {0.3, 0.6}};
  const double axis[3] = {0.3, -1.2, 0.7};
  double Q[3][3];
  rotation(axis, 1.1, Q);
  const double t[3] = {5.0, -3.0, 2.5};
  affine_element(v2d, Q, t, X);
  area = 0.5 * std::fabs((v2d[1][0] - v2d[0][0]) * (v2d[2][1] - v2d[0][1]) -
                         (v2d[2][0] - v2d[0][0]) * (v2d[1][1] - v2d[0][1]));
}

// P2 element with all 6 nodes on the cylinder x = R cos(theta0 + theta), y = R sin(theta0 + theta), z,
// over the parametric triangle (theta, z) = (0, 0), (dth, 0), (0.3 dth, R dth); mid-side nodes are the
// images of the parametric midpoints (on the arcs). Returns the exact patch area R * A_param.
double cylinder_element(double R, double dth, double X[6][3]) {
  const double L = R * dth, th0 = 0.3, z0 = 0.1;
  const double P[6][2] = {{0, 0},
                          {dth, 0},
                          {0.3 * dth, L},
                          {0.5 * dth, 0},
                          {0.65 * dth, 0.5 * L},
                          {0.15 * dth, 0.5 * L}};
  for (int A = 0; A < 6; ++A) {
    X[A][0] = R * std::cos(th0 + P[A][0]);
    X[A][1] = R * std::sin(th0 + P[A][0]);
    X[A][2] = z0 + P[A][1];
  }
  return R * 0.5 * dth * L;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// Geometry (theory.md §1.4)

TEST(ElementGeometry, AffineElementInRotatedTranslatedFrame) {
  double X[6][3], area;
  generic_affine(X, area);
  // Reference: for an affine element G_1 = X2 - X1, G_2 = X3 - X1, n0 = normalized G_1 x G_2, j0 = 2 Area.
  double G[2][3], c[3];
  for (int i = 0; i < 3; ++i) G[0][i] = X[1][i] - X[0][i], G[1][i] = X[2][i] - X[0][i];
  cross(G[0], G[1], c);
  const double j0_ref = norm(c);
  EXPECT_NEAR(j0_ref, 2 * area, 1e-14);

  // Every rule point plus a few arbitrary points (including a vertex and a mid-side node).
  double pts[10][3];
  int np = 0;
  for (int q = 0; q < tri6_rule.num_points; ++q)
    pts[np][0] = tri6_rule.xi[q][0], pts[np][1] = tri6_rule.xi[q][1], pts[np][2] = tri6_rule.w[q], ++np;
  const double extra[4][2] = {{0, 0}, {0.5, 0.5}, {0.2, 0.7}, {0.61, 0.13}};
  for (auto& e : extra) pts[np][0] = e[0], pts[np][1] = e[1], pts[np][2] = 0.37, ++np;

  for (int p = 0; p < np; ++p) {
    AreaPointGeometry g;
    area_point_geometry(X, pts[p][0], pts[p][1], pts[p][2], g);
    EXPECT_NEAR(g.wj0, pts[p][2] * 2 * area, 1e-14);
    // Orthonormal, right-handed basis.
    EXPECT_NEAR(dot(g.e1, g.e1), 1.0, 1e-14);
    EXPECT_NEAR(dot(g.e2, g.e2), 1.0, 1e-14);
    EXPECT_NEAR(dot(g.n0, g.n0), 1.0, 1e-14);
    EXPECT_NEAR(dot(g.e1, g.e2), 0.0, 1e-14);
    EXPECT_NEAR(dot(g.e1, g.n0), 0.0, 1e-14);
    EXPECT_NEAR(dot(g.e2, g.n0), 0.0, 1e-14);
    double e1xe2[3];
    cross(g.e1, g.e2, e1xe2);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(e1xe2[i], g.n0[i], 1e-14);
      EXPECT_NEAR(g.n0[i], c[i] / j0_ref, 1e-14);
      EXPECT_NEAR(g.e1[i], G[0][i] / norm(G[0]), 1e-14);
    }
    // J_{i alpha} = e_i . G_alpha (independent), det J = j0, J^{-1} J = I, and J upper triangular.
    const double* e[2] = {g.e1, g.e2};
    double J[2][2];
    for (int i = 0; i < 2; ++i)
      for (int al = 0; al < 2; ++al) J[i][al] = dot(e[i], G[al]);
    EXPECT_NEAR(J[1][0], 0.0, 1e-14);
    EXPECT_NEAR(J[0][0] * J[1][1] - J[0][1] * J[1][0], j0_ref, 1e-13);
    const double detJinv = g.Jinv[0][0] * g.Jinv[1][1] - g.Jinv[0][1] * g.Jinv[1][0];
    EXPECT_NEAR(detJinv * j0_ref, 1.0, 1e-13);
    for (int al = 0; al < 2; ++al)
      for (int be = 0; be < 2; ++be) {
        double s = 0;
        for (int i = 0; i < 2; ++i) s += g.Jinv[al][i] * J[i][be];
        EXPECT_NEAR(s, al == be ? 1.0 : 0.0, 1e-13) << "Jinv*J at " << al << be;
      }
  }
  // element_area: the rule weights sum to 1/2, so sum w j0 = 2 Area / 2.
  EXPECT_NEAR(element_area(X), area, 1e-14);
}

TEST(ElementGeometry, JinvMapsParametricToArcLengthDerivatives) {
  // Reference: for a linear field f(X) = a . X on an affine element, df/dx^i = a . e_i (theory.md §1.4).
  double X[6][3], area;
  generic_affine(X, area);
  const double a[3] = {0.7, -1.3, 2.1};
  const double xi1 = 0.23, xi2 = 0.41;
  double N[6], dN[6][2];
  p2_shape(xi1, xi2, N, dN);
  double df[2] = {0, 0};
  for (int A = 0; A < 6; ++A)
    for (int al = 0; al < 2; ++al) df[al] += dot(a, X[A]) * dN[A][al];
  AreaPointGeometry g;
  area_point_geometry(X, xi1, xi2, 1.0, g);
  for (int i = 0; i < 2; ++i) {
    const double dfdx = df[0] * g.Jinv[0][i] + df[1] * g.Jinv[1][i];
    EXPECT_NEAR(dfdx, dot(a, i == 0 ? g.e1 : g.e2), 1e-13);
  }
}

TEST(ElementGeometry, CurvedCylinderElementAreaConverges) {
  // Reference: exact cylindrical patch area R * A_param. The P2 interpolant of a circular arc of angle
  // dth deviates from it by O(R dth^3) in position and its tangent by O(dth^2) with an error that
  // integrates to O(dth^4) relative in area (fourth-order for the isoparametric P2 surface area). With
  // h/R = dth we require |rel. error| <= 1e-2 (h/R)^4 (measured constant ~6.5e-4: 1.65e-5 at h/R = 0.4,
  // 4.06e-9 at h/R = 0.05) and an observed rate >= 3.5 per halving (measured ~4.0).
  const double R = 2.0;
  double prev = -1;
  for (double dth : {0.4, 0.2, 0.1, 0.05}) {
    double X[6][3];
    const double exact = cylinder_element(R, dth, X);
    const double rel = std::fabs(element_area(X) - exact) / exact;
    EXPECT_LE(rel, 1e-2 * std::pow(dth, 4)) << "dth = " << dth;
    if (prev > 0 && rel > 1e-13) {
      EXPECT_GE(std::log2(prev / rel), 3.5) << "dth = " << dth;
    }
    std::printf("cylinder element: h/R = %.3f  area rel. error = %.3e\n", dth, rel);
    prev = rel;
    // Normals at the rule points point radially outward (for this node order) up to O(dth^2).
    for (int q = 0; q < tri6_rule.num_points; ++q) {
      AreaPointGeometry g;
      area_point_geometry(X, tri6_rule.xi[q][0], tri6_rule.xi[q][1], tri6_rule.w[q], g);
      double x[3] = {0, 0, 0}, N[6], dN[6][2];
      p2_shape(tri6_rule.xi[q][0], tri6_rule.xi[q][1], N, dN);
      for (int A = 0; A < 6; ++A)
        for (int i = 0; i < 3; ++i) x[i] += N[A] * X[A][i];
      const double r = std::hypot(x[0], x[1]);
      const double radial[3] = {x[0] / r, x[1] / r, 0};
      EXPECT_GE(dot(g.n0, radial), 1 - dth * dth);
    }
  }
}

TEST(ElementGeometry, CharacteristicLength) {
  // Reference: 3-4-5 right triangle, area 6, longest edge 5 -> l_E = 2*6/5 = 2.4 (smallest altitude);
  // invariant under rotation/translation; mid-side nodes are ignored.
  const double v2d[3][2] = {{0, 0}, {4, 0}, {0, 3}};
  const double axis[3] = {1, 2, 3};
  double Q[3][3], X[6][3];
  rotation(axis, 0.8, Q);
  const double t[3] = {-1, 7, 0.5};
  affine_element(v2d, Q, t, X);
  EXPECT_NEAR(characteristic_length(X), 2.4, 1e-14);
  X[4][2] += 0.3;  // bend a mid-side node: l_E unchanged
  EXPECT_NEAR(characteristic_length(X), 2.4, 1e-14);
  // Equilateral triangle of side a: l_E = sqrt(3)/2 a.
  const double a = 0.043;
  const double eq[3][2] = {{0, 0}, {a, 0}, {0.5 * a, std::sqrt(3.0) / 2 * a}};
  affine_element(eq, Q, t, X);
  EXPECT_NEAR(characteristic_length(X) / (std::sqrt(3.0) / 2 * a), 1.0, 1e-13);
}

// ---------------------------------------------------------------------------------------------------------
// HRZ lumping (theory.md §6)

TEST(LumpedMass, AffineP2GivesOneNineteenthAndSixteenFiftySevenths) {
  // Reference: d_vertex = Area/30, d_mid = 8 Area/45 (exact P2 mass-matrix diagonal), so 1/19 and 16/57.
  double X[6][3], area;
  generic_affine(X, area);
  const double rho = 2700, h = 1.5e-3, rho_h = rho * h;
  const double mE = rho_h * area;
  double m[6];
  hrz_lumped_mass(X, rho_h, m);
  double total = 0;
  for (int A = 0; A < 6; ++A) {
    const double expected = A < 3 ? mE / 19 : mE * 16 / 57;
    EXPECT_NEAR(m[A] / expected, 1.0, 1e-14) << "node " << A;
    total += m[A];
  }
  EXPECT_NEAR(total / mE, 1.0, 1e-14);

  // P1 rotary inertia: 1/3 each, total = s_I rho h^3/12 Area.
  for (double sI : {1.0, 4.0}) {
    const double Ibar = sI * rho * h * h * h / 12;
    double I[3];
    hrz_rotary_inertia(X, Ibar, I);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(I[a] / (Ibar * area / 3), 1.0, 1e-14) << "vertex " << a;
    EXPECT_NEAR((I[0] + I[1] + I[2]) / (Ibar * area), 1.0, 1e-14);
  }
}

TEST(LumpedMass, DistortedCurvedElementStaysPositive) {
  // Reference: HRZ scales the (positive) consistent diagonal, so every m_A > 0 whenever j0 > 0, and the
  // total is rho h * element area (theory.md §6). Element: scalene 3-D triangle, mid-side nodes moved off
  // the edge midpoints along the edge and out of plane (non-affine and curved).
  double X[6][3] = {{0.0, 0.0, 0.0}, {1.2, 0.1, 0.05}, {0.25, 0.9, -0.1}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const int mid[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  const double shift[3] = {0.12, -0.1, 0.08};   // along-edge shift (fraction of the edge)
  const double lift[3] = {0.09, -0.06, 0.11};   // out-of-plane offset
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) {
      const double a = X[mid[k][0]][i], b = X[mid[k][1]][i];
      X[3 + k][i] = 0.5 * (a + b) + shift[k] * (b - a) + (i == 2 ? lift[k] : 0.0);
    }
  // Non-affine: j0 varies over the element, and stays positive.
  double jmin = 1e300, jmax = 0;
  for (int q = 0; q < tri6_rule.num_points; ++q) {
    AreaPointGeometry g;
    area_point_geometry(X, tri6_rule.xi[q][0], tri6_rule.xi[q][1], 1.0, g);
    jmin = std::fmin(jmin, g.wj0), jmax = std::fmax(jmax, g.wj0);
  }
  ASSERT_GT(jmin, 0.0);
  EXPECT_GT(jmax / jmin, 1.05);

  const double rho_h = 7.3;
  double m[6], I[3], total = 0;
  hrz_lumped_mass(X, rho_h, m);
  for (int A = 0; A < 6; ++A) {
    EXPECT_GT(m[A], 0.0) << "node " << A;
    total += m[A];
  }
  const double area = element_area(X);
  EXPECT_NEAR(total / (rho_h * area), 1.0, 1e-14);
  hrz_rotary_inertia(X, 0.25, I);
  for (int a = 0; a < 3; ++a) EXPECT_GT(I[a], 0.0);
  EXPECT_NEAR((I[0] + I[1] + I[2]) / (0.25 * area), 1.0, 1e-14);
}

// ---------------------------------------------------------------------------------------------------------
// Stable time step (theory.md §8)

TEST(StableTimeStep, FuselageNumbersByHand) {
  // Aluminium fuselage skin (theory.md §8): E = 70 GPa, nu = 0.33, rho = 2700, h = 1.5 mm, l_E = 4.3 cm, c = 3.
  StableStepParams p;
  p.E = 70e9, p.nu = 0.33, p.rho = 2700, p.h = 1.5e-3;
  const double lE = 4.3e-2;
  // Hand evaluation of the formulas of theory.md §8.
  const double cL = std::sqrt(70e9 / (2700 * (1 - 0.33 * 0.33)));
  const double G = 70e9 / (2 * 1.33);
  const double cS = std::sqrt(G / 2700);
  const double w_mem = cL / lE * std::sqrt(40.0 + 20 * 3);
  const double w_rot = std::sqrt(12 * (5.0 / 6) * cS * cS / (1.5e-3 * 1.5e-3) + (cL / lE) * (cL / lE) * (40.0 + 60));
  // 40-digit decimal values (Python decimal): c_L = 5393.9127364861224, c_S = 3121.9527052723132,
  // omega_mem = 1254398.3108107261, omega_rot = 6700125.9014519672, 2/omega_mem = 1.5943899021255748e-6,
  // 2/omega_rot = 2.9850185346018425e-7.
  EXPECT_NEAR(cL / 5393.9127364861224, 1.0, 1e-14);
  EXPECT_NEAR(cS / 3121.9527052723132, 1.0, 1e-14);

  double wm, wr;
  element_max_frequency(p, lE, wm, wr);
  EXPECT_NEAR(wm / w_mem, 1.0, 1e-12);
  EXPECT_NEAR(wr / w_rot, 1.0, 1e-12);
  EXPECT_NEAR(wm / 1254398.3108107261, 1.0, 1e-12);
  EXPECT_NEAR(wr / 6700125.9014519672, 1.0, 1e-12);
  const double dt = element_stable_dt(p, lE);
  EXPECT_NEAR(dt / (2 / w_rot), 1.0, 1e-12);
  EXPECT_NEAR(dt / 2.9850185346018425e-7, 1.0, 1e-12);
  // The thin-shell approximation dt ~= 2h/(sqrt(12 kappa) c_S) ~= 0.63 h/c_S = 3.03e-7 s (theory.md §8),
  // within the size of the neglected bending/penalty term (~1.7 % here).
  EXPECT_NEAR(dt / (2 * p.h / (std::sqrt(12 * p.kappa) * cS)), 1.0, 0.02);
  EXPECT_NEAR(dt / (0.63 * p.h / cS), 1.0, 0.02);
  // Membrane-only step is ~2e-6 s, i.e. ~5x larger (theory.md §8).
  EXPECT_NEAR(2 / wm, 1.5943899021255748e-6, 1e-12 * 1.6e-6);
}

TEST(StableTimeStep, ShearDominatesThinMembraneThick) {
  // Reference: omega_rot^2 = A + B with A = 12 kappa c_S^2 / h^2 (rotary inertia vs transverse shear) and
  // B = (c_L/l_E)^2 (40 + 20 c_T); A/B = 12 kappa (1 - nu)/2 (l_E/h)^2 / (40 + 20 c_T), which exceeds 1
  // for l_E/h > ~5.5 (nu = 0.33, c = 3) (theory.md §8).
  StableStepParams p;
  p.E = 70e9, p.nu = 0.33, p.rho = 2700, p.h = 1e-3;
  const double cL2 = p.E / (p.rho * (1 - p.nu * p.nu)), cS2 = p.E / (2 * (1 + p.nu)) / p.rho;
  for (double ratio : {6.0, 10.0, 28.7, 100.0}) {
    const double lE = ratio * p.h;
    const double A = 12 * p.kappa * cS2 / (p.h * p.h), B = cL2 / (lE * lE) * (40 + 20 * p.cT);
    EXPECT_GT(A, B) << "l_E/h = " << ratio;
    double wm, wr;
    element_max_frequency(p, lE, wm, wr);
    EXPECT_GT(wr, 1.3 * wm) << "l_E/h = " << ratio;  // the director mode sets the step
    EXPECT_NEAR(element_stable_dt(p, lE) * wr, 2.0, 1e-14);
  }
  // Already at l_E/h = 5 the director estimate is ~36 % above the membrane one.
  {
    double wm, wr;
    element_max_frequency(p, 5 * p.h, wm, wr);
    EXPECT_GT(wr, 1.3 * wm);
  }
  // Thick shell (h = l_E): the wave (membrane/bending + penalty) term dominates omega_rot, which is then
  // within 2 % of omega_mem (equal penalties c_x = c_T), so dt ~= 2/omega_mem.
  {
    const double lE = p.h;
    const double A = 12 * p.kappa * cS2 / (p.h * p.h), B = cL2 / (lE * lE) * (40 + 20 * p.cT);
    EXPECT_LT(A, 0.05 * B);
    double wm, wr;
    element_max_frequency(p, lE, wm, wr);
    EXPECT_NEAR(wr / wm, 1.0, 0.02);
    EXPECT_NEAR(element_stable_dt(p, lE) * wm, 2.0, 0.04);
    // With a smaller director penalty (c_T = 0 < c_x = 3) the membrane frequency is the maximum, exactly.
    StableStepParams q = p;
    q.cT = 0;
    element_max_frequency(q, lE, wm, wr);
    EXPECT_GT(wm, wr);
    EXPECT_NEAR(element_stable_dt(q, lE) * wm, 2.0, 1e-14);
  }
}

TEST(StableTimeStep, RotaryInertiaScaleRaisesStep) {
  // Reference: with s_I = 4 the shear term A is divided by 4, so dt_rot(4)/dt_rot(1) = sqrt((A + B)/(A/4 + B)),
  // which tends to 2 when A >> B (theory.md §8).
  StableStepParams p;
  p.E = 70e9, p.nu = 0.33, p.rho = 2700, p.h = 1.5e-3;
  StableStepParams p4 = p;
  p4.rotary_scale = 4;
  // Fuselage: 40-digit decimal reference ratio 1.9024733167093499.
  const double lE = 4.3e-2;
  const double r = element_stable_dt(p4, lE) / element_stable_dt(p, lE);
  EXPECT_NEAR(r, 1.9024733167093499, 1e-12);
  EXPECT_GT(r, 1.85);
  EXPECT_LE(r, 2.0);
  // Very thin (l_E/h = 1000): within 0.1 % of 2.
  const double r_thin = element_stable_dt(p4, 1000 * p.h) / element_stable_dt(p, 1000 * p.h);
  EXPECT_NEAR(r_thin, 2.0, 2e-3);
  // Thick (l_E = h): s_I has almost no effect, and never lowers the step.
  const double r_thick = element_stable_dt(p4, p.h) / element_stable_dt(p, p.h);
  EXPECT_GE(r_thick, 1.0);
  EXPECT_LT(r_thick, 1.02);
}
