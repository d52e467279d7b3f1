// Shape functions and quadrature (theory.md §1.2, §1.3).
// References: exact monomial integrals over the master triangle, int_T xi1^p xi2^q = p! q! / (p + q + 2)!,
// and over [0, 1], int s^k = 1 / (k + 1); nodal (Kronecker) property and partition of unity by construction
// of Lagrange bases.
#include <gtest/gtest.h>

#include <cmath>

#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/core/triangle_basis.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;

namespace {
double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }
double exact_triangle_monomial(int p, int q) { return factorial(p) * factorial(q) / factorial(p + q + 2); }
double rule_triangle_monomial(const TriangleRule& r, int p, int q) {
  double s = 0;
  for (int i = 0; i < r.num_points; ++i) s += r.w[i] * std::pow(r.xi[i][0], p) * std::pow(r.xi[i][1], q);
  return s;
}
}  // namespace

TEST(Basis, KroneckerAndPartitionOfUnity) {
  for (int order : {1, 2}) {
    const int n = order == 2 ? 6 : 3;
    for (int node = 0; node < n; ++node) {
      double N[6], dN[6][2];
      shape(order, p2_node_xi[node][0], p2_node_xi[node][1], N, dN);
      for (int a = 0; a < n; ++a) EXPECT_NEAR(N[a], a == node ? 1.0 : 0.0, 1e-15) << "order " << order;
    }
    // Partition of unity and zero-sum derivatives at arbitrary interior points.
    for (double x : {0.1, 0.27, 0.6})
      for (double y : {0.05, 0.3}) {
        double N[6], dN[6][2], s = 0, d0 = 0, d1 = 0;
        shape(order, x, y, N, dN);
        for (int a = 0; a < n; ++a) s += N[a], d0 += dN[a][0], d1 += dN[a][1];
        EXPECT_NEAR(s, 1.0, 1e-14);
        EXPECT_NEAR(d0, 0.0, 1e-14);
        EXPECT_NEAR(d1, 0.0, 1e-14);
      }
  }
}

TEST(Basis, P2ReproducesQuadraticsAndItsDerivatives) {
  // f = 1 + 2x - 3y + 4x^2 + 5xy - 6y^2 is reproduced exactly by P2 interpolation.
  auto f = [](double x, double y) { return 1 + 2 * x - 3 * y + 4 * x * x + 5 * x * y - 6 * y * y; };
  const double x = 0.21, y = 0.33;
  double N[6], dN[6][2], v = 0, dx = 0, dy = 0;
  p2_shape(x, y, N, dN);
  for (int a = 0; a < 6; ++a) {
    const double fa = f(p2_node_xi[a][0], p2_node_xi[a][1]);
    v += N[a] * fa, dx += dN[a][0] * fa, dy += dN[a][1] * fa;
  }
  EXPECT_NEAR(v, f(x, y), 1e-14);
  EXPECT_NEAR(dx, 2 + 8 * x + 5 * y, 1e-13);
  EXPECT_NEAR(dy, -3 + 5 * x - 12 * y, 1e-13);
  // Derivatives against central finite differences (step 1e-6, tolerance 1e-8).
  const double h = 1e-6;
  double Np[6], Nm[6], tmp[6][2];
  for (int alpha = 0; alpha < 2; ++alpha) {
    p2_shape(x + (alpha == 0 ? h : 0), y + (alpha == 1 ? h : 0), Np, tmp);
    p2_shape(x - (alpha == 0 ? h : 0), y - (alpha == 1 ? h : 0), Nm, tmp);
    for (int a = 0; a < 6; ++a) EXPECT_NEAR(dN[a][alpha], (Np[a] - Nm[a]) / (2 * h), 1e-8);
  }
}

TEST(Quadrature, TriangleRulesExactToTheirDegree) {
  for (const auto& [rule, degree] : {std::pair{tri6_rule, 4}, std::pair{tri7_rule, 5}}) {
    for (int p = 0; p <= degree; ++p)
      for (int q = 0; p + q <= degree; ++q)
        EXPECT_NEAR(rule_triangle_monomial(rule, p, q), exact_triangle_monomial(p, q), 1e-14)
            << "degree " << degree << " rule, monomial x^" << p << " y^" << q;
    // The stated degree is sharp: some monomial of degree + 1 is not integrated exactly.
    double worst = 0;
    for (int p = 0; p <= degree + 1; ++p)
      worst = std::max(worst, std::abs(rule_triangle_monomial(rule, p, degree + 1 - p) -
                                        exact_triangle_monomial(p, degree + 1 - p)));
    EXPECT_GT(worst, 1e-6);
  }
}

TEST(Quadrature, EdgeRuleExactToDegreeFive) {
  for (int k = 0; k <= 5; ++k) {
    double s = 0;
    for (int g = 0; g < 3; ++g) s += edge3_rule.w[g] * std::pow(edge3_rule.s[g], k);
    EXPECT_NEAR(s, 1.0 / (k + 1), 1e-15) << "s^" << k;
  }
  double s6 = 0;
  for (int g = 0; g < 3; ++g) s6 += edge3_rule.w[g] * std::pow(edge3_rule.s[g], 6);
  EXPECT_GT(std::abs(s6 - 1.0 / 7), 1e-5);
}
