#pragma once
/// \file triangle_basis.hpp
/// Shape functions on the master triangle T = {xi1 >= 0, xi2 >= 0, xi1 + xi2 <= 1} (theory.md §1.2), below both
/// the mesh (P2 geometry of new nodes) and the discretization.
/// Barycentrics lam1 = 1 - xi1 - xi2, lam2 = xi1, lam3 = xi2. Node order: vertices (0,0), (1,0), (0,1),
/// then mid-sides (1/2,0), (1/2,1/2), (0,1/2). Pure point functions, usable inside kernels.
#include <Kokkos_Macros.hpp>

namespace shellfrac {

/// Parametric coordinates of the 6 P2 nodes (the first 3 are the P1 nodes).
constexpr double p2_node_xi[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};

/// P1 shape functions L_a (a = 0..2) and their parametric derivatives dL[a][alpha].
KOKKOS_INLINE_FUNCTION void p1_shape(double xi1, double xi2, double L[3], double dL[3][2]) {
  L[0] = 1.0 - xi1 - xi2;
  L[1] = xi1;
  L[2] = xi2;
  dL[0][0] = -1.0, dL[0][1] = -1.0;
  dL[1][0] = 1.0, dL[1][1] = 0.0;
  dL[2][0] = 0.0, dL[2][1] = 1.0;
}

/// P2 shape functions N_A (A = 0..5) and their parametric derivatives dN[A][alpha] (theory.md §1.2).
KOKKOS_INLINE_FUNCTION void p2_shape(double xi1, double xi2, double N[6], double dN[6][2]) {
  const double l1 = 1.0 - xi1 - xi2, l2 = xi1, l3 = xi2;
  const double d1[2] = {-1.0, -1.0}, d2[2] = {1.0, 0.0}, d3[2] = {0.0, 1.0};
  N[0] = l1 * (2 * l1 - 1);
  N[1] = l2 * (2 * l2 - 1);
  N[2] = l3 * (2 * l3 - 1);
  N[3] = 4 * l1 * l2;
  N[4] = 4 * l2 * l3;
  N[5] = 4 * l3 * l1;
  for (int a = 0; a < 2; ++a) {
    dN[0][a] = (4 * l1 - 1) * d1[a];
    dN[1][a] = (4 * l2 - 1) * d2[a];
    dN[2][a] = (4 * l3 - 1) * d3[a];
    dN[3][a] = 4 * (l1 * d2[a] + l2 * d1[a]);
    dN[4][a] = 4 * (l2 * d3[a] + l3 * d2[a]);
    dN[5][a] = 4 * (l3 * d1[a] + l1 * d3[a]);
  }
}

/// Shape functions of order `order` (1: 3 functions, 2: 6 functions); N and dN sized for 6.
KOKKOS_INLINE_FUNCTION void shape(int order, double xi1, double xi2, double N[6], double dN[6][2]) {
  if (order == 2) {
    p2_shape(xi1, xi2, N, dN);
  } else {
    double L[3], dL[3][2];
    p1_shape(xi1, xi2, L, dL);
    for (int a = 0; a < 3; ++a) N[a] = L[a], dN[a][0] = dL[a][0], dN[a][1] = dL[a][1];
  }
}

}  // namespace shellfrac
