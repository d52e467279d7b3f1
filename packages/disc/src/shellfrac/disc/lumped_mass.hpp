#pragma once
/// \file lumped_mass.hpp
/// HRZ (Hinton-Rock-Zienkiewicz) lumped translational mass of the 6 P2 position nodes and lumped rotary
/// inertia of the 3 P1 director nodes of one element (theory.md §6):
///   m_E = rho-bar0 sum_q w_q j0_q,  d_A = sum_q w_q j0_q N^A(xi_q)^2,  m_A = m_E d_A / sum_B d_B,
///   I_a = Ibar0 (sum_q w_q j0_q) c_a / sum_b c_b,  c_a = sum_q w_q j0_q L^a(xi_q)^2,
/// with the 6-point rule of §1.3. Never row-sum P2 (vertex row sums vanish for affine elements).
/// Pure per-element functions, usable inside kernels.
#include <Kokkos_Macros.hpp>

#include "shellfrac/disc/element_geometry.hpp"
#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/core/triangle_basis.hpp"

namespace shellfrac::disc {

/// HRZ-lumped masses m[A] (A = 0..5) of the P2 position nodes; rho_h = rho-bar0 = rho0 h.
/// sum_A m[A] = rho_h * element_area(X). Affine element: 1/19 per vertex, 16/57 per mid-side node.
KOKKOS_INLINE_FUNCTION void hrz_lumped_mass(const double X[6][3], double rho_h, double m[6]) {
  double d[6] = {0, 0, 0, 0, 0, 0};
  double area = 0.0;
  for (int q = 0; q < tri6_rule.num_points; ++q) {
    const double xi1 = tri6_rule.xi[q][0], xi2 = tri6_rule.xi[q][1];
    const double wj0 = tri6_rule.w[q] * area_jacobian(X, xi1, xi2);
    double N[6], dN[6][2];
    p2_shape(xi1, xi2, N, dN);
    area += wj0;
    for (int A = 0; A < 6; ++A) d[A] += wj0 * N[A] * N[A];
  }
  double dsum = 0.0;
  for (int A = 0; A < 6; ++A) dsum += d[A];
  const double scale = rho_h * area / dsum;
  for (int A = 0; A < 6; ++A) m[A] = scale * d[A];
}

/// HRZ-lumped rotary inertias I[a] (a = 0..2) of the P1 director nodes;
/// rho_h3_over_12_scaled = Ibar0 = s_I rho0 h^3 / 12 (s_I >= 1 optional rotary-inertia scale, §8).
/// sum_a I[a] = Ibar0 * element_area(X). Affine element: 1/3 each.
KOKKOS_INLINE_FUNCTION void hrz_rotary_inertia(const double X[6][3], double rho_h3_over_12_scaled, double I[3]) {
  double c[3] = {0, 0, 0};
  double area = 0.0;
  for (int q = 0; q < tri6_rule.num_points; ++q) {
    const double xi1 = tri6_rule.xi[q][0], xi2 = tri6_rule.xi[q][1];
    const double wj0 = tri6_rule.w[q] * area_jacobian(X, xi1, xi2);
    double L[3], dL[3][2];
    p1_shape(xi1, xi2, L, dL);
    area += wj0;
    for (int a = 0; a < 3; ++a) c[a] += wj0 * L[a] * L[a];
  }
  const double scale = rho_h3_over_12_scaled * area / (c[0] + c[1] + c[2]);
  for (int a = 0; a < 3; ++a) I[a] = scale * c[a];
}

}  // namespace shellfrac::disc
