#pragma once
/// \file dg_element.hpp
/// The DG shell operator on one element and on one interface (theory.md §5; paper §4.2, eqs. 41-44).
///  * DgElementRef: reference data of an element, constant in time (area-point geometry, reference strain
///    offsets, edge-point data, the inverse lifting mass matrix). What follows from it or is the same for every
///    element is evaluated in the kernel, not stored: the reference triangle's shape data (AreaPointShapes), the
///    lifting weights W (LiftingWeights) and the P1 projection matrix (projection_matrix).
///  * dg_kinematics: the DG derivatives by lifting (theory.md §5.2) at the area points (a_i, d_i, t_h);
///    the first stage of dg_element_forces, exposed for verification.
///  * dg_element_forces: DG derivatives by lifting of the jumps over the element's lifted edges (theory.md
///    §5.2), strains, resultants (a point law passed in), the element's internal forces on its own nodes
///    and its lifting fluxes on the neighbours' edge nodes (§5.4). Returns the element's strain energy.
/// The interface stabilization (penalty) forces are in dg_interface.hpp.
/// Sign convention: forces are gradients of the energy (internal forces); the acceleration is
/// (f_ext - f)/m. Spatial director moments g (3-vectors) are projected with Lambda-bar^T by the caller.
/// Pure functions on plain arrays, usable in Kokkos kernels; they write only their own outputs, so the
/// caller assembles by gather in a fixed order (no atomics).
/// Number type: the element's functions and data are templates on T, double for one element or Batch for
/// batch_width elements in lock-step (lanes.hpp; the `...Of<T>` structs, with the double ones named without the
/// suffix). An operation on a Batch is, on each lane, the same IEEE operation as on a double, and where one
/// element skips work that another in its batch does (an edge that is not lifted) the batch computes both and
/// selects per lane: each element's result is bitwise the same in a batch as on its own.
///
/// Edge-local node order of local edge k: (first vertex, second vertex, mid-side) in the element's own
/// counter-clockwise traversal, i.e. nodes edge_vertex[k][0], edge_vertex[k][1], 3 + k; the edge
/// parameter s runs from the first to the second vertex. Edge point g sits at s = edge3_rule.s[g].
#include <Kokkos_Macros.hpp>

#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/core/types.hpp"
#include "shellfrac/disc/element_geometry.hpp"
#include "shellfrac/disc/lanes.hpp"
#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/disc/shell_strains.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/disc/strain_treatment.hpp"
#include "shellfrac/disc/stress_power.hpp"

namespace shellfrac::disc {

constexpr int num_area_points = 6;  ///< tri6_rule
constexpr int num_edge_points = 3;  ///< edge3_rule

/// Node of the element at edge-local position j (0, 1: vertices; 2: mid-side) of local edge k.
KOKKOS_INLINE_FUNCTION int edge_node(int k, int j) {
  return j == 2 ? 3 + k : (j == 0 ? k : (k + 1) % 3);  // = edge_vertex[k][j] for j < 2
}

/// Quadratic shape values along an edge at parameter s, edge-local order (vertex, vertex, mid-side).
template <class T>
KOKKOS_INLINE_FUNCTION void edge_shape_p2(T s, T n[3]) {
  n[0] = (1 - s) * (1 - 2 * s);
  n[1] = s * (2 * s - 1);
  n[2] = 4 * s * (1 - s);
}

/// d/ds of the quadratic edge shape values (edge_shape_p2), edge-local order (vertex, vertex, mid-side).
KOKKOS_INLINE_FUNCTION void edge_shape_p2_derivative(double s, double dn[3]) {
  dn[0] = 4 * s - 3;
  dn[1] = 4 * s - 1;
  dn[2] = 4 - 8 * s;
}

/// Shape values at an edge point seen from two sides: quadratic (positions) and linear (directors), in each
/// side's edge-local order; `s` and `s_other` are the point's edge parameters in the two elements.
template <class T>
struct EdgePointShapesOf {
  double p2[3];
  T p2_other[3];
  double p1[2];
  T p1_other[2];
};
using EdgePointShapes = EdgePointShapesOf<double>;

template <class T>
KOKKOS_INLINE_FUNCTION EdgePointShapesOf<T> edge_point_shapes(double s, T s_other) {
  EdgePointShapesOf<T> e;
  edge_shape_p2(s, e.p2);
  edge_shape_p2(s_other, e.p2_other);
  e.p1[0] = 1 - s, e.p1[1] = s;
  e.p1_other[0] = 1 - s_other, e.p1_other[1] = s_other;
  return e;
}

/// The nodes of one edge of an element in edge-local order (edge_node): the positions of its 3 position nodes
/// (vertex, vertex, mid-side) and the directors of its 2 director nodes (the vertices).
template <class T>
struct EdgeNodesOf {
  T x[3][3];
  T t[2][3];
};
using EdgeNodes = EdgeNodesOf<double>;

/// Forces on the nodes of one edge, in the same order: on the 3 position nodes and the 2 director nodes.
template <class T>
struct EdgeForcesOf {
  T f[3][3];
  T g[2][3];
};
using EdgeForces = EdgeForcesOf<double>;

/// Sets the forces on the edge nodes of both sides of an interface to zero.
KOKKOS_INLINE_FUNCTION void clear_edge_forces(EdgeForces& on_minus, EdgeForces& on_plus) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) on_minus.f[j][c] = on_plus.f[j][c] = 0;
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) on_minus.g[j][c] = on_plus.g[j][c] = 0;
}

/// Reference data of one local edge of an element.
template <class T>
struct DgEdgeRefOf {
  T omega[num_edge_points];      ///< omega_g = w_g |dX/ds|: reference arc-length weights (theory.md §1.4)
  T nu_cov[num_edge_points][2];  ///< nu_{E,alpha}(g) = nu_E . G_alpha, nu_E the outward reference co-normal
  MaskOf<T> nbr_same_direction;  ///< the neighbour traverses the edge in the same direction (not for a
                                 ///< consistently oriented neighbour)
};
using DgEdgeRef = DgEdgeRefOf<double>;

/// Edge parameter, in the neighbour across edge E, of the point at edge point g of this element.
template <class T>
KOKKOS_INLINE_FUNCTION T neighbour_edge_parameter(const DgEdgeRefOf<T>& E, int g) {
  return select(E.nbr_same_direction, T(edge3_rule.s[g]), T(1 - edge3_rule.s[g]));
}

/// Reference data of one element (theory.md §5.3): only what differs between elements. The shape data of the
/// reference triangle (AreaPointShapes) and the lifting weights (LiftingWeights) follow from it.
template <class T>
struct DgElementRefOf {
  T wj0[num_area_points];                   ///< w_q j0_q
  T Jinv[num_area_points][2][2];            ///< (J^-1)_{alpha i}
  ShellReferenceOf<T> ref[num_area_points]; ///< reference strain offsets gam0, rho0
  DgEdgeRefOf<T> edge[3];
  T area;                                   ///< |E| = sum_q w_q j0_q
  T Minv[3][3];                             ///< inverse of the P1 lifting mass matrix M_psi = sum_q w_q j0_q psi psi^T
  /// How the membrane and shear strains are used (theory.md §5.4). The same for every element of a batch.
  StrainTreatment strains;
  /// s in P = (1 - s) Pi + s I for the membrane strains (theory.md eq. 5.4a; 0: the projection only).
  T membrane_remainder;
};
using DgElementRef = DgElementRefOf<double>;

/// Shape data of the reference triangle at the area points of tri6_rule: the same for every element.
struct AreaPointShapes {
  double dN[num_area_points][6][2];  ///< P2 shape derivatives dN^A/dxi^alpha
  double L[num_area_points][3];      ///< P1 shape values (also the P1 lifting basis psi_u)
  double dL[3][2];                   ///< P1 shape derivatives (constant)
};

KOKKOS_INLINE_FUNCTION void area_point_shapes(AreaPointShapes& S) {
  double N[6], L[3], dL[3][2];
  for (int q = 0; q < num_area_points; ++q) {
    p2_shape(tri6_rule.xi[q][0], tri6_rule.xi[q][1], N, S.dN[q]);
    p1_shape(tri6_rule.xi[q][0], tri6_rule.xi[q][1], L, dL);
    for (int a = 0; a < 3; ++a) S.L[q][a] = L[a];
  }
  for (int a = 0; a < 3; ++a) S.dL[a][0] = dL[a][0], S.dL[a][1] = dL[a][1];
}

/// Lifting weights of an element's edges (theory.md §5.2): W^u_{g,alpha} = 1/2 omega_g nu_alpha M_psi^-1 psi(xi_g)
/// (positions, P1 lifting) and W^t_{g,alpha} = 1/2 omega_g nu_alpha / |E| (directors, P0 lifting).
template <class T>
struct LiftingWeightsOf {
  T Wu[3][num_edge_points][2][3];
  T Wt[3][num_edge_points][2];
};
using LiftingWeights = LiftingWeightsOf<double>;

template <class T>
KOKKOS_INLINE_FUNCTION void lifting_weights(const DgElementRefOf<T>& R, LiftingWeightsOf<T>& W) {
  for (int k = 0; k < 3; ++k) {
    const int vi = edge_node(k, 0), vj = edge_node(k, 1);
    const DgEdgeRefOf<T>& E = R.edge[k];
    for (int g = 0; g < num_edge_points; ++g) {
      const double s = edge3_rule.s[g];
      const double xi1 = (1 - s) * p2_node_xi[vi][0] + s * p2_node_xi[vj][0];
      const double xi2 = (1 - s) * p2_node_xi[vi][1] + s * p2_node_xi[vj][1];
      double L[3], dL[3][2];
      p1_shape(xi1, xi2, L, dL);
      for (int al = 0; al < 2; ++al) {
        const T c = 0.5 * E.omega[g] * E.nu_cov[g][al];
        for (int b = 0; b < 3; ++b)
          W.Wu[k][g][al][b] = c * (R.Minv[b][0] * L[0] + R.Minv[b][1] * L[1] + R.Minv[b][2] * L[2]);
        W.Wt[k][g][al] = 0.5 * E.omega[g] * E.nu_cov[g][al] / R.area;
      }
    }
  }
}

/// The L2 projection on the element onto `space` as a matrix on area-point values,
/// (Pi f)(xi_q) = sum_p P[q][p] f(xi_p) (theory.md eq. 5.4b): P1, P[q][p] = psi(xi_q)^T M_psi^-1 psi(xi_p) w_p j0_p;
/// P0, P[q][p] = w_p j0_p / |E|; point values, the identity. Every one satisfies w_q j0_q P[q][p] = w_p j0_p P[p][q],
/// so the same matrix maps the strains and their work-conjugate resultants.
template <class T>
KOKKOS_INLINE_FUNCTION void projection_matrix(const DgElementRefOf<T>& R, const AreaPointShapes& S, StrainSpace space,
                                              T P[num_area_points][num_area_points]) {
  for (int q = 0; q < num_area_points; ++q)
    for (int p = 0; p < num_area_points; ++p) {
      if (space == StrainSpace::p1) {
        T v = 0;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) v += S.L[q][a] * R.Minv[a][b] * S.L[p][b];
        P[q][p] = v * R.wj0[p];
      } else if (space == StrainSpace::p0) {
        P[q][p] = R.wj0[p] / R.area;
      } else {
        P[q][p] = q == p ? T(1) : T(0);
      }
    }
}

/// The matrices through which an element uses its strains (theory.md eq. 5.4a): membrane (1 - s) Pi + s I,
/// shear the projection on the shear space. Only the ones the treatment maps are set.
template <class T>
struct StrainMatricesOf {
  T membrane[num_area_points][num_area_points];
  T shear[num_area_points][num_area_points];
};

template <class T>
KOKKOS_INLINE_FUNCTION void strain_matrices(const DgElementRefOf<T>& R, const AreaPointShapes& S,
                                            StrainMatricesOf<T>& P) {
  const StrainTreatment& st = R.strains;
  if (st.maps_membrane()) {
    projection_matrix(R, S, st.membrane, P.membrane);
    const T s = R.membrane_remainder;
    for (int q = 0; q < num_area_points; ++q)
      for (int p = 0; p < num_area_points; ++p) {
        const T blended = (1 - s) * P.membrane[q][p];
        P.membrane[q][p] = q == p ? blended + s : blended;
      }
  }
  if (st.maps_shear()) projection_matrix(R, S, st.shear, P.shear);
}

namespace detail {
/// Inverse of a symmetric positive definite 3x3 matrix (the P1 lifting mass matrix).
KOKKOS_INLINE_FUNCTION void inverse33(const double A[3][3], double B[3][3]) {
  const double det = det33(A);
  B[0][0] = (A[1][1] * A[2][2] - A[1][2] * A[2][1]) / det;
  B[0][1] = (A[0][2] * A[2][1] - A[0][1] * A[2][2]) / det;
  B[0][2] = (A[0][1] * A[1][2] - A[0][2] * A[1][1]) / det;
  B[1][0] = (A[1][2] * A[2][0] - A[1][0] * A[2][2]) / det;
  B[1][1] = (A[0][0] * A[2][2] - A[0][2] * A[2][0]) / det;
  B[1][2] = (A[0][2] * A[1][0] - A[0][0] * A[1][2]) / det;
  B[2][0] = (A[1][0] * A[2][1] - A[1][1] * A[2][0]) / det;
  B[2][1] = (A[0][1] * A[2][0] - A[0][0] * A[2][1]) / det;
  B[2][2] = (A[0][0] * A[1][1] - A[0][1] * A[1][0]) / det;
}
}  // namespace detail

/// Builds the reference data of an element from its reference node positions X (6 P2 nodes) and the
/// reference directors T0 at its 3 vertices (theory.md §1.5: equal in every element sharing a vertex).
/// nbr_same_direction[k]: the neighbour across edge k traverses the edge in the same direction (false for
/// consistently oriented neighbours; irrelevant for edges without a neighbour).
KOKKOS_INLINE_FUNCTION void build_dg_element_ref(const double X[6][3], const double T0[3][3],
                                                 const bool nbr_same_direction[3], DgElementRef& R,
                                                 StrainTreatment strains = {}, double membrane_remainder = 0) {
  double L[3], dL[3][2];
  // Area points: geometry, reference kinematics -> strain offsets; lifting mass matrix.
  double Mpsi[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  R.area = 0;
  for (int q = 0; q < num_area_points; ++q) {
    const double xi1 = tri6_rule.xi[q][0], xi2 = tri6_rule.xi[q][1];
    AreaPointGeometry geo;
    area_point_geometry(X, xi1, xi2, tri6_rule.w[q], geo);
    R.wj0[q] = geo.wj0;
    R.area += geo.wj0;
    for (int al = 0; al < 2; ++al)
      for (int i = 0; i < 2; ++i) R.Jinv[q][al][i] = geo.Jinv[al][i];
    double N[6], dN[6][2];
    p2_shape(xi1, xi2, N, dN);
    p1_shape(xi1, xi2, L, dL);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) Mpsi[a][b] += geo.wj0 * L[a] * L[b];
    // Reference kinematics: phi_0 and t_0 are continuous, so their DG derivatives are the ordinary ones.
    ShellKinematics k0;
    for (int c = 0; c < 3; ++c) {
      double ga[2] = {0, 0}, gd[2] = {0, 0};
      for (int A = 0; A < 6; ++A) ga[0] += X[A][c] * dN[A][0], ga[1] += X[A][c] * dN[A][1];
      for (int a = 0; a < 3; ++a) gd[0] += T0[a][c] * dL[a][0], gd[1] += T0[a][c] * dL[a][1];
      for (int i = 0; i < 2; ++i) {
        k0.a[i][c] = ga[0] * geo.Jinv[0][i] + ga[1] * geo.Jinv[1][i];
        k0.d[i][c] = gd[0] * geo.Jinv[0][i] + gd[1] * geo.Jinv[1][i];
      }
      k0.t[c] = L[0] * T0[0][c] + L[1] * T0[1][c] + L[2] * T0[2][c];
    }
    R.ref[q] = make_shell_reference(k0);
  }
  detail::inverse33(Mpsi, R.Minv);
  R.strains = strains;
  R.membrane_remainder = membrane_remainder;
  // Edges: arc-length weights and outward co-normals (theory.md §1.4).
  for (int k = 0; k < 3; ++k) {
    const int vi = edge_node(k, 0), vj = edge_node(k, 1);
    DgEdgeRef& E = R.edge[k];
    E.nbr_same_direction = nbr_same_direction[k];
    for (int g = 0; g < num_edge_points; ++g) {
      const double s = edge3_rule.s[g];
      const double xi1 = (1 - s) * p2_node_xi[vi][0] + s * p2_node_xi[vj][0];
      const double xi2 = (1 - s) * p2_node_xi[vi][1] + s * p2_node_xi[vj][1];
      const double dxi[2] = {p2_node_xi[vj][0] - p2_node_xi[vi][0], p2_node_xi[vj][1] - p2_node_xi[vi][1]};
      double G[2][3];
      covariant_tangents(X, xi1, xi2, G);
      double tau[3], n0[3], nu[3];
      for (int c = 0; c < 3; ++c) tau[c] = G[0][c] * dxi[0] + G[1][c] * dxi[1];  // dX/ds
      E.omega[g] = edge3_rule.w[g] * norm3(tau);
      normalize3(tau);
      cross3(G[0], G[1], n0);
      normalize3(n0);
      cross3(tau, n0, nu);  // outward for a counter-clockwise element (theory.md §1.4 check)
      E.nu_cov[g][0] = dot3(nu, G[0]);
      E.nu_cov[g][1] = dot3(nu, G[1]);
    }
  }
}

/// What the element forces read of one element (theory.md §5.4): its nodes and, across each lifted edge, the
/// neighbour's edge nodes in the neighbour's edge-local order.
template <class T>
struct DgElementNodesOf {
  T x[6][3];                  ///< current positions of the P2 nodes
  T t[3][3];                  ///< current directors of the P1 (vertex) nodes
  MaskOf<T> lift[3];          ///< edge k is an intact interface with a single neighbour (its jump is lifted)
  EdgeNodesOf<T> neighbour[3];  ///< across edge k: the neighbour's edge nodes (read only where lift[k])
};
using DgElementNodes = DgElementNodesOf<double>;

/// What the element forces write: the forces on the element's own nodes and the lifting fluxes on each
/// neighbour's edge nodes (zero across an edge that is not lifted).
template <class T>
struct DgElementForcesOf {
  T f[6][3];                    ///< on the position nodes
  T g[3][3];                    ///< on the director nodes
  EdgeForcesOf<T> neighbour[3]; ///< on the neighbour's edge nodes across edge k, in the neighbour's edge-local order
};
using DgElementForces = DgElementForcesOf<double>;

/// DG kinematics of one element at its area points (theory.md §2, §5.2):
/// a_i = d^DG_i phi_h (P1 lifting of the position jumps), d_i = d^DG_i t_h (P0 lifting of the director
/// jumps), both in the local Cartesian reference frame, and the interpolated director t_h(xi_q).
///   e: the element's nodes and its neighbours' edge nodes (DgElementNodes).
/// S, W: the reference triangle's shape data and the element's lifting weights.
/// Output (overwritten): kin[q] for q = 0..num_area_points-1.
template <class T>
KOKKOS_INLINE_FUNCTION void dg_kinematics(const DgElementRefOf<T>& R, const AreaPointShapes& S,
                                          const LiftingWeightsOf<T>& W, const DgElementNodesOf<T>& e,
                                          ShellKinematicsOf<T> kin[num_area_points]) {
  const auto& x = e.x;
  const auto& t = e.t;
  const auto& lift = e.lift;
  // 1. Liftings of the one-sided jumps [u]^E = u^E - u^E' (theory.md §5.2); in a batch also for the elements
  //    whose edge k is not lifted (their neighbour nodes are zero), which step 2 and 3 then do not use.
  T Rx[3][2][3][3] = {};  // [k][alpha][component][psi]
  T Rt[3][2][3] = {};     // [k][alpha][component]
  for (int k = 0; k < 3; ++k) {
    if (!any(lift[k])) continue;
    for (int gp = 0; gp < num_edge_points; ++gp) {
      const EdgePointShapesOf<T> sh = edge_point_shapes(edge3_rule.s[gp], neighbour_edge_parameter(R.edge[k], gp));
      const double *no = sh.p2, *lo = sh.p1;
      const T *nn = sh.p2_other, *ln = sh.p1_other;
      for (int c = 0; c < 3; ++c) {
        T jx = 0, jt = 0;
        for (int j = 0; j < 3; ++j) jx += no[j] * x[edge_node(k, j)][c] - nn[j] * e.neighbour[k].x[j][c];
        for (int j = 0; j < 2; ++j) jt += lo[j] * t[edge_node(k, j)][c] - ln[j] * e.neighbour[k].t[j][c];
        for (int al = 0; al < 2; ++al) {
          for (int b = 0; b < 3; ++b) Rx[k][al][c][b] += jx * W.Wu[k][gp][al][b];
          Rt[k][al][c] += jt * W.Wt[k][gp][al];
        }
      }
    }
  }
  // 2. The director's DG derivative: the P1 director and its lifting give the same one at every area point.
  T ddc[3][2];  // [component][alpha]
  for (int c = 0; c < 3; ++c)
    for (int al = 0; al < 2; ++al) {
      T dd = 0;
      for (int a = 0; a < 3; ++a) dd += t[a][c] * S.dL[a][al];
      for (int k = 0; k < 3; ++k)
        if (any(lift[k])) dd = select(lift[k], dd - Rt[k][al][c], dd);
      ddc[c][al] = dd;
    }
  // 3. Area points: DG derivatives (theory.md §5.2).
  for (int q = 0; q < num_area_points; ++q) {
    for (int c = 0; c < 3; ++c) {
      T aa[2];
      const T* dd = ddc[c];
      for (int al = 0; al < 2; ++al) {
        aa[al] = 0;
        for (int A = 0; A < 6; ++A) aa[al] += x[A][c] * S.dN[q][A][al];
        for (int k = 0; k < 3; ++k) {
          if (!any(lift[k])) continue;
          T lifted = aa[al];
          for (int b = 0; b < 3; ++b) lifted -= Rx[k][al][c][b] * S.L[q][b];
          aa[al] = select(lift[k], lifted, aa[al]);
        }
      }
      for (int i = 0; i < 2; ++i) {
        kin[q].a[i][c] = aa[0] * R.Jinv[q][0][i] + aa[1] * R.Jinv[q][1][i];
        kin[q].d[i][c] = dd[0] * R.Jinv[q][0][i] + dd[1] * R.Jinv[q][1][i];
      }
      kin[q].t[c] = S.L[q][0] * t[0][c] + S.L[q][1] * t[1][c] + S.L[q][2] * t[2][c];
    }
  }
}

/// The same, for one element on its own (verification and diagnostics).
KOKKOS_INLINE_FUNCTION void dg_kinematics(const DgElementRef& R, const DgElementNodes& e,
                                          ShellKinematics kin[num_area_points]) {
  AreaPointShapes S;
  area_point_shapes(S);
  LiftingWeights W;
  lifting_weights(R, W);
  dg_kinematics(R, S, W, e, kin);
}

/// f[q][c] <- sum_p P[q][p] f[p][c]: a matrix on area-point values (projection_matrix, strain_matrices) applied
/// to point values f[q][0..n-1].
template <int n, class T>
KOKKOS_INLINE_FUNCTION void apply_point_matrix(const T P[num_area_points][num_area_points], T f[num_area_points][n]) {
  T g[num_area_points][n];
  for (int q = 0; q < num_area_points; ++q)
    for (int c = 0; c < n; ++c) {
      g[q][c] = 0;
      for (int p = 0; p < num_area_points; ++p) g[q][c] += P[q][p] * f[p][c];
    }
  for (int q = 0; q < num_area_points; ++q)
    for (int c = 0; c < n; ++c) f[q][c] = g[q][c];
}

/// Strains at the area points from the DG kinematics (theory.md §2), the membrane and shear strains used
/// through the element's strain matrices P (theory.md eq. 5.4a; a matrix is read only where the element maps
/// that strain).
template <class T>
KOKKOS_INLINE_FUNCTION void dg_strains(const DgElementRefOf<T>& R, const StrainMatricesOf<T>& P,
                                       const ShellKinematicsOf<T> kin[num_area_points], T eps[num_area_points][3],
                                       T gam[num_area_points][2], T rho[num_area_points][3]) {
  for (int q = 0; q < num_area_points; ++q) compute_strains(kin[q], R.ref[q], eps[q], gam[q], rho[q]);
  if (R.strains.maps_membrane()) apply_point_matrix<3>(P.membrane, eps);
  if (R.strains.maps_shear()) apply_point_matrix<2>(P.shear, gam);
}

/// The same, for one element on its own (diagnostics).
KOKKOS_INLINE_FUNCTION void dg_strains(const DgElementRef& R, const ShellKinematics kin[num_area_points],
                                       double eps[num_area_points][3], double gam[num_area_points][2],
                                       double rho[num_area_points][3]) {
  AreaPointShapes S;
  area_point_shapes(S);
  StrainMatricesOf<double> P;
  strain_matrices(R, S, P);
  dg_strains(R, P, kin, eps, gam, rho);
}

/// The traction on an element across each of its edges at the edge points (theory.md §9.5 step 1), per unit
/// reference length, from the P1 L2 projections of its resultants: at[k][g][0..2] = sum_alpha (Pi n^alpha)(xi_g)
/// nu_{E,alpha} (the force that the material beyond edge k exerts on E), at[k][g][3..5] the same for m^alpha,
/// with nu_E the element's outward co-normal. Edge points in the element's own edge order.
template <class T>
struct EdgeTractionsOf {
  T at[3][num_edge_points][6];
};
using EdgeTractions = EdgeTractionsOf<double>;

/// The sums over the area points that the edge terms need (theory.md §5.4): the moments of the parametric
/// resultants n^alpha, m^alpha against the P1 lifting functions psi, sum_q w_q j0_q (.) (x) psi(xi_q).
template <class T>
struct ResultantMomentsOf {
  T x[2][3][3] = {};  ///< [alpha][component][psi]: sum_q w j0 n^alpha (x) psi
  T t[2][3] = {};     ///< [alpha][component]:      sum_q w j0 m^alpha
  T m[2][3][3] = {};  ///< [alpha][component][psi]: sum_q w j0 m^alpha (x) psi (only for edge tractions)
};
using ResultantMoments = ResultantMomentsOf<double>;

/// The edge tractions of the projected resultants (theory.md §9.5 step 1):
/// W^u_{g,alpha} = 1/2 omega_g nu_alpha Mpsi^-1 psi(xi_g).
template <class T>
KOKKOS_INLINE_FUNCTION void edge_tractions_of(const DgElementRefOf<T>& R, const LiftingWeightsOf<T>& W,
                                              const ResultantMomentsOf<T>& Pi, EdgeTractionsOf<T>& edge_tractions) {
  for (int k = 0; k < 3; ++k)
    for (int gp = 0; gp < num_edge_points; ++gp) {
      const DgEdgeRefOf<T>& E = R.edge[k];
      const T s = 2.0 / E.omega[gp];
      for (int c = 0; c < 3; ++c) {
        T n = 0, m = 0;
        for (int al = 0; al < 2; ++al)
          for (int b = 0; b < 3; ++b) n += Pi.x[al][c][b] * W.Wu[k][gp][al][b], m += Pi.m[al][c][b] * W.Wu[k][gp][al][b];
        edge_tractions.at[k][gp][c] = s * n, edge_tractions.at[k][gp][3 + c] = s * m;
      }
    }
}

/// The lifting fluxes F_g, H_g (theory.md §5.4) added to the forces on the element's own edge nodes and written
/// to the neighbours' edge nodes (zero across an edge that is not lifted).
template <class T>
KOKKOS_INLINE_FUNCTION void add_lifting_fluxes(const DgElementRefOf<T>& R, const LiftingWeightsOf<T>& W,
                                               const MaskOf<T> lift[3], const ResultantMomentsOf<T>& Pi,
                                               DgElementForcesOf<T>& out) {
  for (int k = 0; k < 3; ++k) {
    EdgeForcesOf<T>& across = out.neighbour[k];
    for (int j = 0; j < 3; ++j) across.f[j][0] = across.f[j][1] = across.f[j][2] = 0;
    for (int j = 0; j < 2; ++j) across.g[j][0] = across.g[j][1] = across.g[j][2] = 0;
    if (!any(lift[k])) continue;
    const MaskOf<T> lifted = lift[k];
    for (int gp = 0; gp < num_edge_points; ++gp) {
      const EdgePointShapesOf<T> sh = edge_point_shapes(edge3_rule.s[gp], neighbour_edge_parameter(R.edge[k], gp));
      const double *no = sh.p2, *lo = sh.p1;
      const T *nn = sh.p2_other, *ln = sh.p1_other;
      for (int c = 0; c < 3; ++c) {
        T F = 0, H = 0;
        for (int al = 0; al < 2; ++al) {
          for (int b = 0; b < 3; ++b) F += Pi.x[al][c][b] * W.Wu[k][gp][al][b];
          H += Pi.t[al][c] * W.Wt[k][gp][al];
        }
        for (int j = 0; j < 3; ++j) {
          T& own = out.f[edge_node(k, j)][c];
          own = select(lifted, own - no[j] * F, own);
          across.f[j][c] = select(lifted, across.f[j][c] + nn[j] * F, across.f[j][c]);
        }
        for (int j = 0; j < 2; ++j) {
          T& own = out.g[edge_node(k, j)][c];
          own = select(lifted, own - lo[j] * H, own);
          across.g[j][c] = select(lifted, across.g[j][c] + ln[j] * H, across.g[j][c]);
        }
      }
    }
  }
}

/// Internal forces of one element (theory.md §5.4) with the point law `law(q, eps, gam, rho, N, Q, M)` at
/// area point q, returning the stored energy per unit reference area. The law is called exactly once per area
/// point, in the order q = 0 .. num_area_points - 1.
///   e: the element's nodes and its neighbours' edge nodes, as for dg_kinematics.
/// Outputs (overwritten): the forces on the element's own nodes and the lifting fluxes on the neighbours' edge
/// nodes (DgElementForces); the edge tractions if `edge_tractions` is not null (the nucleation check needs them).
/// Returns the element's strain energy sum_q w_q j0_q W.
template <class T, class Law>
KOKKOS_INLINE_FUNCTION T dg_element_forces(const DgElementRefOf<T>& R, const DgElementNodesOf<T>& e, const Law& law,
                                           DgElementForcesOf<T>& out, EdgeTractionsOf<T>* edge_tractions = nullptr) {
  // 1.-2. Liftings of the jumps and DG kinematics at the area points.
  AreaPointShapes S;
  area_point_shapes(S);
  LiftingWeightsOf<T> W;
  lifting_weights(R, W);
  StrainMatricesOf<T> P;
  strain_matrices(R, S, P);
  ShellKinematicsOf<T> kins[num_area_points];
  dg_kinematics(R, S, W, e, kins);
  // 2'. Area points: strains, resultants, own forces; accumulate the projections Pi.
  auto& f = out.f;
  auto& g = out.g;
  for (int A = 0; A < 6; ++A) f[A][0] = f[A][1] = f[A][2] = 0;
  for (int a = 0; a < 3; ++a) g[a][0] = g[a][1] = g[a][2] = 0;
  ResultantMomentsOf<T> Pi;
  T eps[num_area_points][3], gam[num_area_points][2], rho[num_area_points][3];
  dg_strains(R, P, kins, eps, gam, rho);
  T N[num_area_points][3], Q[num_area_points][2], M[num_area_points][3];
  T energy = 0;
  for (int q = 0; q < num_area_points; ++q) energy += R.wj0[q] * law(q, eps[q], gam[q], rho[q], N[q], Q[q], M[q]);
  // The gradient of the energy of the mapped strains: the same matrices on N and Q (w_q P_qp = w_p P_pq).
  if (R.strains.maps_membrane()) apply_point_matrix<3>(P.membrane, N);
  if (R.strains.maps_shear()) apply_point_matrix<2>(P.shear, Q);
  for (int q = 0; q < num_area_points; ++q) {
    const ShellKinematicsOf<T>& kin = kins[q];
    T n[2][3], m[2][3], l[3];
    stress_power_vectors(kin, N[q], Q[q], M[q], n, m, l);
    const T w = R.wj0[q];
    for (int al = 0; al < 2; ++al)
      for (int c = 0; c < 3; ++c) {
        // parametric components n^alpha = (J^-1)_{alpha i} n^i
        const T na = R.Jinv[q][al][0] * n[0][c] + R.Jinv[q][al][1] * n[1][c];
        const T ma = R.Jinv[q][al][0] * m[0][c] + R.Jinv[q][al][1] * m[1][c];
        for (int A = 0; A < 6; ++A) f[A][c] += w * S.dN[q][A][al] * na;
        for (int a = 0; a < 3; ++a) g[a][c] += w * S.dL[a][al] * ma;
        for (int b = 0; b < 3; ++b) Pi.x[al][c][b] += w * na * S.L[q][b];
        Pi.t[al][c] += w * ma;
        if (edge_tractions)
          for (int b = 0; b < 3; ++b) Pi.m[al][c][b] += w * ma * S.L[q][b];
      }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) g[a][c] += w * S.L[q][a] * l[c];
  }
  if (edge_tractions) edge_tractions_of(R, W, Pi, *edge_tractions);  // 2''.
  add_lifting_fluxes(R, W, e.lift, Pi, out);                           // 3.
  return energy;
}

}  // namespace shellfrac::disc
