#pragma once
/// \file dg_interface.hpp
/// The DG operator on one intact interface (theory.md §5.5; paper eqs. 42-44, 52): its reference data and the
/// stabilization (penalty) forces and energy. Pure functions on plain arrays, as dg_element.hpp.
#include "shellfrac/disc/dg_element.hpp"

namespace shellfrac::disc {

/// Reference data of an interface (the minus side's edge geometry; both sides share the reference edge).
struct DgInterfaceRef {
  double omega[num_edge_points];  ///< arc-length weights of the minus side's edge points
  double s_plus[num_edge_points]; ///< plus side's edge parameter of the matched points
  double inv_he;                  ///< 1 / h_e, h_e = sum_g omega_g (reference arc length)
};

/// Interface reference data from the minus element's edge reference data.
KOKKOS_INLINE_FUNCTION void build_dg_interface_ref(const DgEdgeRef& minus_edge, DgInterfaceRef& I) {
  double he = 0;
  for (int g = 0; g < num_edge_points; ++g) {
    I.omega[g] = minus_edge.omega[g];
    I.s_plus[g] = neighbour_edge_parameter(minus_edge, g);
    he += I.omega[g];
  }
  I.inv_he = 1.0 / he;
}

/// Stabilization (penalty) forces of an intact interface (theory.md §5.5; paper eqs. 42-44, 52):
/// [[phi]] = phi^- - phi^+, n_stab = beta_x/h_e [[phi]], m_stab = beta_T/h_e [[t]]. Inputs are the edge
/// nodes of each side in its own edge-local order. Outputs (overwritten) are forces on those nodes.
/// Returns the stabilization energy U_stab.
KOKKOS_INLINE_FUNCTION double dg_penalty_forces(const DgInterfaceRef& I, double beta_x, double beta_t,
                                                const EdgeNodes& minus, const EdgeNodes& plus, EdgeForces& on_minus,
                                                EdgeForces& on_plus) {
  const auto &xm = minus.x, &xp = plus.x;
  const auto &tm = minus.t, &tp = plus.t;
  auto &fm = on_minus.f, &fp = on_plus.f;
  auto &gm = on_minus.g, &gp = on_plus.g;
  clear_edge_forces(on_minus, on_plus);
  double energy = 0;
  for (int g = 0; g < num_edge_points; ++g) {
    const EdgePointShapes sh = edge_point_shapes(edge3_rule.s[g], I.s_plus[g]);
    const double *nm = sh.p2, *np = sh.p2_other, *lm = sh.p1, *lp = sh.p1_other;
    double jx[3], jt[3];
    for (int c = 0; c < 3; ++c) {
      jx[c] = 0, jt[c] = 0;
      for (int j = 0; j < 3; ++j) jx[c] += nm[j] * xm[j][c] - np[j] * xp[j][c];
      for (int j = 0; j < 2; ++j) jt[c] += lm[j] * tm[j][c] - lp[j] * tp[j][c];
    }
    const double cx = I.omega[g] * beta_x * I.inv_he, ct = I.omega[g] * beta_t * I.inv_he;
    energy += 0.5 * (cx * dot3(jx, jx) + ct * dot3(jt, jt));
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < 3; ++j) fm[j][c] += cx * jx[c] * nm[j], fp[j][c] -= cx * jx[c] * np[j];
      for (int j = 0; j < 2; ++j) gm[j][c] += ct * jt[c] * lm[j], gp[j][c] -= ct * jt[c] * lp[j];
    }
  }
  return energy;
}

}  // namespace shellfrac::disc
