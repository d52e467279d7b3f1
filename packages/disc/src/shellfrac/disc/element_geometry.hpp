#pragma once
/// \file element_geometry.hpp
/// Reference geometry of a P2 shell element at an area quadrature point (theory.md §1.4), the element
/// area (tri6 rule, §1.3) and the characteristic length l_E used by the stable time step (§8).
/// Pure per-element functions on plain arrays: no allocation, no exceptions, usable inside kernels.
#include <Kokkos_Macros.hpp>
#include <cmath>

#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/core/triangle_basis.hpp"

namespace shellfrac::disc {

/// Geometry stored per area quadrature point (theory.md §1.4):
///  * wj0 = w_q j0_q (rule weight times the reference area Jacobian |G_1 x G_2|),
///  * Jinv[alpha][i] = (J^{-1})_{alpha i}, where J_{i alpha} = e_i . G_alpha, so that
///    d(.)/dx^i = d(.)/dxi^alpha Jinv[alpha][i],
///  * the local orthonormal basis e1 = G_1/|G_1|, e2 = n0 x e1 and the unit normal n0.
struct AreaPointGeometry {
  double wj0;
  double Jinv[2][2];
  double e1[3], e2[3], n0[3];
};


/// Covariant tangent vectors G[alpha] = sum_A X_A dN^A/dxi^alpha of the P2 reference geometry at (xi1, xi2).
KOKKOS_INLINE_FUNCTION void covariant_tangents(const double X[6][3], double xi1, double xi2, double G[2][3]) {
  double N[6], dN[6][2];
  p2_shape(xi1, xi2, N, dN);
  for (int al = 0; al < 2; ++al)
    for (int k = 0; k < 3; ++k) {
      double s = 0.0;
      for (int A = 0; A < 6; ++A) s += X[A][k] * dN[A][al];
      G[al][k] = s;
    }
}

/// Reference geometry at the point (xi1, xi2) of the master triangle with rule weight w (theory.md §1.4).
/// X holds the 6 P2 node positions (vertices, then mid-sides, see triangle_basis.hpp). Requires a
/// non-degenerate element (|G_1| > 0 and j0 > 0); no check is made here.
KOKKOS_INLINE_FUNCTION void area_point_geometry(const double X[6][3], double xi1, double xi2, double w,
                                                AreaPointGeometry& g) {
  double G[2][3];
  covariant_tangents(X, xi1, xi2, G);
  double c[3];
  cross3(G[0], G[1], c);
  const double j0 = norm3(c);
  const double g1 = norm3(G[0]);
  for (int k = 0; k < 3; ++k) {
    g.n0[k] = c[k] / j0;
    g.e1[k] = G[0][k] / g1;
  }
  cross3(g.n0, g.e1, g.e2);
  // J = [[|G_1|, e1.G_2], [0, e2.G_2]], det J = |G_1| (e2.G_2) = j0.
  const double J01 = dot3(g.e1, G[1]);
  const double J11 = dot3(g.e2, G[1]);
  g.Jinv[0][0] = 1.0 / g1;
  g.Jinv[0][1] = -J01 / (g1 * J11);
  g.Jinv[1][0] = 0.0;
  g.Jinv[1][1] = 1.0 / J11;
  g.wj0 = w * j0;
}

/// Reference area Jacobian j0 = |G_1 x G_2| at (xi1, xi2).
KOKKOS_INLINE_FUNCTION double area_jacobian(const double X[6][3], double xi1, double xi2) {
  double G[2][3], c[3];
  covariant_tangents(X, xi1, xi2, G);
  cross3(G[0], G[1], c);
  return norm3(c);
}

/// Orientation of the P2 map at (xi1, xi2) relative to the vertex triangle: (G_1 x G_2) . n_v / (2 A_v), with
/// n_v the unit normal and A_v the area of the vertex triangle. 1 for straight-sided flat elements; <= 0 where
/// the element is folded over itself (a mid-side node far outside it), theory.md §1.4.
KOKKOS_INLINE_FUNCTION double orientation_ratio(const double X[6][3], double xi1, double xi2) {
  double G[2][3], c[3], e1[3], e2[3], nv[3];
  covariant_tangents(X, xi1, xi2, G);
  cross3(G[0], G[1], c);
  for (int k = 0; k < 3; ++k) e1[k] = X[1][k] - X[0][k], e2[k] = X[2][k] - X[0][k];
  cross3(e1, e2, nv);
  const double twice_area = norm3(nv);
  return dot3(c, nv) / (twice_area * twice_area);
}

/// Reference area of the P2 element, sum_q w_q j0_q with the 6-point rule (theory.md §1.3, §6).
KOKKOS_INLINE_FUNCTION double element_area(const double X[6][3]) {
  double a = 0.0;
  for (int q = 0; q < tri6_rule.num_points; ++q)
    a += tri6_rule.w[q] * area_jacobian(X, tri6_rule.xi[q][0], tri6_rule.xi[q][1]);
  return a;
}

/// Characteristic length l_E = 2 Area(vertex triangle) / longest vertex-to-vertex edge, i.e. the
/// smallest altitude of the vertex triangle (theory.md §8). Only the vertices X[0..2] are used.
KOKKOS_INLINE_FUNCTION double characteristic_length(const double X[6][3]) {
  double e[3][3];  // e[k] = edge vectors X1-X0, X2-X1, X0-X2
  for (int k = 0; k < 3; ++k) {
    e[0][k] = X[1][k] - X[0][k];
    e[1][k] = X[2][k] - X[1][k];
    e[2][k] = X[0][k] - X[2][k];
  }
  double c[3];
  cross3(e[0], e[2], c);  // |(X1-X0) x (X0-X2)| = 2 Area
  double lmax = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double l = norm3(e[k]);
    lmax = l > lmax ? l : lmax;
  }
  return norm3(c) / lmax;
}

}  // namespace shellfrac::disc
