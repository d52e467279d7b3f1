#pragma once
/// \file cohesive_interface.hpp
/// The fracture side of an interface element (paper §3, §5; theory.md §9): the cohesive forces of an activated
/// interface and the nucleation check of an intact one. Pure functions on plain arrays, usable in Kokkos
/// kernels; they write only their own outputs.
///
/// Conventions (those of disc::dg_penalty_forces): the interface joins E- ("minus", whose edge points and
/// reference data DgInterfaceRef holds) and E+ ("plus"); jumps are [[u]] = u^- - u^+; inputs are the edge
/// nodes of each side in its own edge-local order. The unit co-normal nu is the CURRENT outward co-normal of
/// E+ (theory.md §9.1: objective under large rotations): nu = normalize(dbar x tau-), with tau- the
/// current edge tangent of E- (its counter-clockwise direction, opposite to E+'s) and dbar the normalized
/// mean of the two directors. An opening of E- away from E+ is then delta_N = [[phi]] . nu > 0.
#include <Kokkos_Macros.hpp>
#include <cmath>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/dg_interface.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/materials/cohesive_law.hpp"

namespace shellfrac::solver {

/// What the co-normal at an edge point is made of (theory.md §9.1, §9.4): the unit edge tangent tau of E- and the
/// normalized mean director dbar, the lengths they were normalized from (|dx/ds| and |sum L t|), and |dbar x tau|.
struct ConormalGeometry {
  double tau[3], dbar[3];
  double tau_length, dbar_length, cross_length;
};

/// Current unit co-normal nu (outward of E+) at edge point g of an interface (theory.md §9.1) and what it is built
/// from (geo). Returns false if the faces are degenerate (|dbar x tau| < 1e-8); nu is then left unchanged (the
/// caller keeps its last one).
KOKKOS_INLINE_FUNCTION bool interface_conormal(const disc::DgInterfaceRef& I, int g, const double xm[3][3],
                                               const double tm[2][3], const double tp[2][3], double nu[3],
                                               ConormalGeometry& geo) {
  const double s = disc::edge3_rule.s[g];
  const disc::EdgePointShapes sh = disc::edge_point_shapes(s, I.s_plus[g]);
  double dn[3], n[3];
  disc::edge_shape_p2_derivative(s, dn);
  for (int c = 0; c < 3; ++c) {
    geo.tau[c] = 0, geo.dbar[c] = 0;
    for (int j = 0; j < 3; ++j) geo.tau[c] += dn[j] * xm[j][c];
    for (int j = 0; j < 2; ++j) geo.dbar[c] += sh.p1[j] * tm[j][c] + sh.p1_other[j] * tp[j][c];
  }
  geo.tau_length = disc::normalize3(geo.tau);
  geo.dbar_length = disc::normalize3(geo.dbar);
  disc::cross3(geo.dbar, geo.tau, n);
  geo.cross_length = disc::norm3(n);
  if (!(geo.cross_length >= 1e-8)) return false;
  for (int c = 0; c < 3; ++c) nu[c] = n[c] / geo.cross_length;
  return true;
}

/// interface_conormal with only the normalized mean director dbar besides nu.
KOKKOS_INLINE_FUNCTION bool interface_conormal(const disc::DgInterfaceRef& I, int g, const double xm[3][3],
                                               const double tm[2][3], const double tp[2][3], double nu[3],
                                               double dbar[3]) {
  ConormalGeometry geo;
  const bool found = interface_conormal(I, g, xm, tm, tp, nu, geo);
  disc::copy3(geo.dbar, dbar);
  return found;
}

/// The jumps [[phi]] = phi^-(g) - phi^+(g) and [[t]] = t^-(g) - t^+(g) at edge point g (theory.md §9.1).
KOKKOS_INLINE_FUNCTION void interface_jumps(const disc::DgInterfaceRef& I, int g, const double xm[3][3],
                                            const double tm[2][3], const double xp[3][3], const double tp[2][3],
                                            double jx[3], double jt[3]) {
  const disc::EdgePointShapes sh = disc::edge_point_shapes(disc::edge3_rule.s[g], I.s_plus[g]);
  for (int c = 0; c < 3; ++c) {
    jx[c] = 0, jt[c] = 0;
    for (int j = 0; j < 3; ++j) jx[c] += sh.p2[j] * xm[j][c] - sh.p2_other[j] * xp[j][c];
    for (int j = 0; j < 2; ++j) jt[c] += sh.p1[j] * tm[j][c] - sh.p1_other[j] * tp[j][c];
  }
}

/// The orthonormal interface frame at an edge point (theory.md §9.6): e[0] = nu, e[1] = the mean director dbar
/// made orthogonal to nu (it already is unless nu was kept from a degenerate configuration), e[2] = e[0] x e[1]
/// (the edge tangent). It turns with the interface, so components in it are objective.
KOKKOS_INLINE_FUNCTION void interface_frame(const double nu[3], const double dbar[3], double e[3][3]) {
  const double dn = disc::dot3(dbar, nu);
  for (int c = 0; c < 3; ++c) e[0][c] = nu[c], e[1][c] = dbar[c] - dn * nu[c];
  disc::normalize3(e[1]);
  disc::cross3(e[0], e[1], e[2]);
}

/// The state of the cohesive law of an interface that activates now (theory.md §9.6), from the average edge force
/// and couple n, m of the nucleation check and its co-normals nu. At each edge point the law starts from the
/// opening Q0 whose tractions are (n, m) scaled to the strength S0 (time-continuous activation): with the
/// initial secant s0 = S0/delta0,
///   [[phi]]0 = ((n.nu) nu + n_S/alpha1^2)/s0 ,   [[t]]0 = ((m.nu) nu/alpha2^2 + m_S/alpha3^2)/(h^2 s0) ,
/// with <n.nu> = max(n.nu, 0) in place of n.nu when the law has crack-face contact (p.contact),
/// whose effective opening is delta(Q0) = n_eq delta0/S0. The opening of the law is measured from the jumps
/// now (the DG jumps that the penalty and the lifting held) plus Q0: offset[g] = components in the interface
/// frame of (current jumps - Q0); delta_max[g] = max(delta0, delta(Q0)). With delta0 = 0 (Gamma = 0, or the
/// rigid law) Q0 = 0 and delta_max = 0.
KOKKOS_INLINE_FUNCTION void activation_state(const disc::DgInterfaceRef& I, const materials::CohesiveParams& p,
                                             const double xm[3][3], const double tm[2][3], const double xp[3][3],
                                             const double tp[2][3], const double n[disc::num_edge_points][3],
                                             const double m[disc::num_edge_points][3],
                                             const double nu[disc::num_edge_points][3],
                                             double offset[disc::num_edge_points][6],
                                             double delta_max[disc::num_edge_points]) {
  for (int g = 0; g < disc::num_edge_points; ++g) {
    double nu_g[3], dbar[3], e[3][3], jx[3], jt[3];
    disc::copy3(nu[g], nu_g);
    interface_conormal(I, g, xm, tm, tp, nu_g, dbar);
    interface_frame(nu[g], dbar, e);
    interface_jumps(I, g, xm, tm, xp, tp, jx, jt);
    delta_max[g] = 0;
    if (p.delta0 > 0) {
      const double inv_s0 = p.delta0 / p.S0;
      // With crack-face contact a compressive normal force is carried by the contact (§9.9), not by an opening.
      const double nN_raw = disc::dot3(n[g], nu[g]), mN = disc::dot3(m[g], nu[g]);
      const double nN = p.contact && nN_raw < 0 ? 0.0 : nN_raw;
      const double a1 = p.alpha1 * p.alpha1, a2 = p.alpha2 * p.alpha2 * p.h * p.h, a3 = p.alpha3 * p.alpha3 * p.h * p.h;
      for (int c = 0; c < 3; ++c) {
        jx[c] -= inv_s0 * (nN * nu[g][c] + (n[g][c] - nN_raw * nu[g][c]) / a1);
        jt[c] -= inv_s0 * (mN * nu[g][c] / a2 + (m[g][c] - mN * nu[g][c]) / a3);
      }
      const double d0 = materials::equivalent_traction(p, n[g], m[g], nu[g]) * inv_s0;
      delta_max[g] = d0 > p.delta0 ? d0 : p.delta0;
    }
    for (int k = 0; k < 3; ++k) offset[g][k] = disc::dot3(jx, e[k]), offset[g][3 + k] = disc::dot3(jt, e[k]);
  }
}

/// Energies and state of a cohesive interface after one evaluation.
struct CohesiveInterfaceResult {
  double stored = 0;      ///< sum_g omega_g (phi_g + U_contact,g) (theory.md §9.7, §9.9)
  double dissipated = 0;  ///< sum_g omega_g D_g
  bool separated = true;  ///< every edge point is fully separated (the interface carries nothing any more)
};

/// How much two crack faces still face each other, from a sliding or turning measured against its limit: 1 up to
/// half the limit, 0 beyond the limit, (1 - q^2)^2 with q = 2|x| - 1 between (theory.md §9.9).
KOKKOS_INLINE_FUNCTION double facing_weight(double x) {
  const double a = std::abs(x);
  if (a <= 0.5) return 1.0;
  if (a >= 1.0) return 0.0;
  const double q = 2 * a - 1, w = 1 - q * q;
  return w * w;
}

/// The crack-face contact at one edge point (theory.md §9.9) on the law's jumps d = [[phi]] - offset, dt =
/// [[t]] - offset (the same origin as the cohesive law, so that a closed edge is neither pulled nor pushed), in the
/// interface frame e: materials::crack_face_contact_energy U_c of the normal gap d.nu + z dt.nu, times the share
/// of the faces' length still opposite each other, (1 - |d.e2|/h_e)^+ (the sliding along the edge), and
/// facing_weight of the sliding out of the surface against h and of |dt| against 1/2 (about 30 degrees between the
/// sides' directors). Adds the gradient of that energy with respect to the jumps to nc, mc (the contact force and
/// couple along nu, and the overlap's share along e2), its gradient with respect to the frame vectors at fixed
/// jumps to dphi_de (the facing weights are not differentiated), and returns the energy per unit reference length.
KOKKOS_INLINE_FUNCTION double crack_face_contact_forces(const materials::CohesiveParams& p, double edge_length,
                                                        const double d[3], const double dt[3], const double e[3][3],
                                                        double nc[3], double mc[3], double dphi_de[3][3]) {
  const double along = disc::dot3(d, e[2]) / edge_length;
  const double overlap = 1.0 - std::abs(along);
  const double others = facing_weight(disc::dot3(d, e[1]) / p.h) * facing_weight(disc::norm3(dt) / 0.5);
  const double facing = others * (overlap > 0.0 ? overlap : 0.0);
  if (!(facing > 0.0)) return 0.0;
  double fN, mN;
  const double energy = materials::crack_face_contact(p.contact_stiffness, p.h, disc::dot3(d, e[0]), disc::dot3(dt, e[0]), fN, mN);
  const double g_along = -others * energy * (along < 0.0 ? -1.0 : 1.0) / edge_length;  // d(energy)/d(d.e2)
  for (int c = 0; c < 3; ++c) {
    nc[c] += facing * fN * e[0][c] + g_along * e[2][c], mc[c] += facing * mN * e[0][c];
    dphi_de[0][c] += facing * (fN * d[c] + mN * dt[c]);  // the gaps are d.e0 and dt.e0
    dphi_de[2][c] += g_along * d[c];                     // the sliding along the edge is d.e2
  }
  return facing * energy;
}

/// The forces of an activated interface's energy through its frame at edge point g (theory.md §9.4b). The energy
/// depends on the frame e (the law's jumps are the DG jumps less the offset o held in e, and the law splits them
/// along nu = e[0], the contact measures its gap and overlap in e); e is made of the directors of both sides and,
/// through nu, of the positions of E-. With P_k = dphi/de_k = -(o_k n_c + o_{3+k} m_c) + dphi_de[k] (the derivative
/// at fixed jumps), the gradient is carried
/// back through e2 = e0 x e1, e1 = w/|w| with w = dbar - (dbar.nu) nu, nu = (dbar x tau)/|dbar x tau|,
/// dbar = b/|b| with b = sum L t, tau = a/|a| with a = sum N' x-, and omega_g times it is added to fm (positions
/// of E-) and gm, gp (directors). `nu_follows`: nu was computed from this configuration (false: it was kept from
/// a degenerate one and does not move with the nodes).
KOKKOS_INLINE_FUNCTION void add_frame_forces(const disc::DgInterfaceRef& I, int g, bool nu_follows,
                                             const ConormalGeometry& geo, const double e[3][3], const double o[6],
                                             const double nc[3], const double mc[3], const double dphi_de[3][3],
                                             double fm[3][3], double gm[2][3], double gp[2][3]) {
  double P[3][3], r[3];
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) P[k][c] = dphi_de[k][c] - (o[k] * nc[c] + o[3 + k] * mc[c]);
  disc::cross3(e[1], P[2], r);  // e2 = e0 x e1
  for (int c = 0; c < 3; ++c) P[0][c] += r[c];
  disc::cross3(P[2], e[0], r);
  for (int c = 0; c < 3; ++c) P[1][c] += r[c];
  const double* nu = e[0];
  const double* dbar = geo.dbar;
  const double dbar_nu = disc::dot3(dbar, nu);
  double w[3], Pw[3], Pdbar[3];
  for (int c = 0; c < 3; ++c) w[c] = dbar[c] - dbar_nu * nu[c];
  const double e1_P1 = disc::dot3(e[1], P[1]), w_length = disc::norm3(w);
  for (int c = 0; c < 3; ++c) Pw[c] = (P[1][c] - e1_P1 * e[1][c]) / w_length;
  const double nu_Pw = disc::dot3(nu, Pw);
  for (int c = 0; c < 3; ++c) Pdbar[c] = Pw[c] - nu_Pw * nu[c];
  const double omega = I.omega[g], s = disc::edge3_rule.s[g];
  if (nu_follows) {
    double Pnu[3], Pc[3], Ptau[3];
    for (int c = 0; c < 3; ++c) Pnu[c] = P[0][c] - nu_Pw * dbar[c] - dbar_nu * Pw[c];
    const double nu_Pnu = disc::dot3(nu, Pnu);
    for (int c = 0; c < 3; ++c) Pc[c] = (Pnu[c] - nu_Pnu * nu[c]) / geo.cross_length;
    disc::cross3(geo.tau, Pc, r);
    for (int c = 0; c < 3; ++c) Pdbar[c] += r[c];
    disc::cross3(Pc, dbar, Ptau);
    const double tau_Ptau = disc::dot3(geo.tau, Ptau);
    double dn[3];
    disc::edge_shape_p2_derivative(s, dn);
    for (int c = 0; c < 3; ++c) {
      const double Pa = (Ptau[c] - tau_Ptau * geo.tau[c]) / geo.tau_length;
      for (int j = 0; j < 3; ++j) fm[j][c] += omega * dn[j] * Pa;
    }
  }
  const disc::EdgePointShapes sh = disc::edge_point_shapes(s, I.s_plus[g]);
  const double dbar_P = disc::dot3(dbar, Pdbar);
  for (int c = 0; c < 3; ++c) {
    const double Pb = (Pdbar[c] - dbar_P * dbar[c]) / geo.dbar_length;
    for (int j = 0; j < 2; ++j) gm[j][c] += omega * sh.p1[j] * Pb, gp[j][c] += omega * sh.p1_other[j] * Pb;
  }
}

/// Cohesive forces of an activated interface (theory.md §9.4, §9.6, §9.9; paper eqs. 55-56): at each edge point the
/// jumps less the offset fixed at activation (components in the interface frame, activation_state), the current
/// co-normal (nu[g] keeps the last good one), the tractions n_c, m_c of the cohesive law with delta_max[g]
/// updated in place, plus those of the crack-face contact when the law has it (p.contact), and the nodal forces
///   f^A(-) += omega_g n_c N^A_-,  f^A(+) -= omega_g n_c N^A_+,  g^a(-) += omega_g m_c L^a_-,  g^a(+) -= ...
/// plus the forces through the frame (add_frame_forces), so that the nodal forces are the exact gradient of the
/// stored energy sum_g omega_g (phi_g + U_contact,g) at fixed delta_max (internal forces: they resist the opening
/// and the interpenetration). Not differentiated: the contact's facing weights of the sliding out of the surface
/// and of the turning. Outputs are overwritten.
KOKKOS_INLINE_FUNCTION CohesiveInterfaceResult cohesive_interface_forces(
    const disc::DgInterfaceRef& I, const materials::CohesiveParams& p, const disc::EdgeNodes& minus,
    const disc::EdgeNodes& plus, const double offset[disc::num_edge_points][6], double delta_max[disc::num_edge_points],
    double nu[disc::num_edge_points][3], disc::EdgeForces& on_minus, disc::EdgeForces& on_plus) {
  const auto &xm = minus.x, &xp = plus.x;
  const auto &tm = minus.t, &tp = plus.t;
  auto &fm = on_minus.f, &fp = on_plus.f;
  auto &gm = on_minus.g, &gp = on_plus.g;
  disc::clear_edge_forces(on_minus, on_plus);
  CohesiveInterfaceResult r;
  for (int g = 0; g < disc::num_edge_points; ++g) {
    const disc::EdgePointShapes sh = disc::edge_point_shapes(disc::edge3_rule.s[g], I.s_plus[g]);
    double jx[3], jt[3], e[3][3], nc[3], mc[3], dphi_de[3][3] = {};
    ConormalGeometry geo;
    const bool nu_follows = interface_conormal(I, g, xm, tm, tp, nu[g], geo);
    interface_frame(nu[g], geo.dbar, e);
    interface_jumps(I, g, xm, tm, xp, tp, jx, jt);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) jx[c] -= offset[g][k] * e[k][c], jt[c] -= offset[g][3 + k] * e[k][c];
    const materials::CohesiveResult cr = materials::cohesive_tractions(p, jx, jt, nu[g], delta_max[g], nc, mc);
    materials::cohesive_conormal_gradient(p, jx, jt, nu[g], delta_max[g], dphi_de[0]);
    const double contact = p.contact ? crack_face_contact_forces(p, 1 / I.inv_he, jx, jt, e, nc, mc, dphi_de) : 0.0;
    r.stored += I.omega[g] * (cr.stored + contact);
    r.dissipated += I.omega[g] * cr.dissipated;
    r.separated = r.separated && cr.separated;
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < 3; ++j) fm[j][c] += I.omega[g] * nc[c] * sh.p2[j], fp[j][c] -= I.omega[g] * nc[c] * sh.p2_other[j];
      for (int j = 0; j < 2; ++j) gm[j][c] += I.omega[g] * mc[c] * sh.p1[j], gp[j][c] -= I.omega[g] * mc[c] * sh.p1_other[j];
    }
    add_frame_forces(I, g, nu_follows, geo, e, offset[g], nc, mc, dphi_de, fm, gm, gp);
  }
  return r;
}

/// Average edge force and couple of an intact interface at its edge points (theory.md §9.5 step 1; paper eqs. 27-28):
/// n = (t^+ - t^-)/2 with t^E the traction on element E across its edge from its projected resultants
/// (disc::EdgeTractions of edge k of each side: [g][0..2] force, [3..5] couple, in that side's own edge-point order).
/// The plus side's point matched with the minus side's point g is g' = g if its parameter s_plus[g] equals
/// edge3_rule.s[g], else 2 - g (a symmetric rule). Returns a cheap upper bound of fbar (below): with
/// n_eq^2 <= c_n |n|^2 + c_m |m|^2 for any unit nu, c_n = max(1, 1/alpha1^2), c_m = max(1/alpha2^2, 1/alpha3^2)/h^2.
/// If it is negative the edge cannot activate, and the co-normals need not be computed (the common case).
KOKKOS_INLINE_FUNCTION double interface_edge_tractions(const disc::DgInterfaceRef& I, const materials::CohesiveParams& p,
                                                       const double edge_minus[disc::num_edge_points][6],
                                                       const double edge_plus[disc::num_edge_points][6],
                                                       double n[disc::num_edge_points][3],
                                                       double m[disc::num_edge_points][3]) {
  const double cn = p.alpha1 < 1 ? 1 / (p.alpha1 * p.alpha1) : 1.0;
  const double am = p.alpha2 < p.alpha3 ? p.alpha2 : p.alpha3;
  const double cm = 1 / (am * am * p.h * p.h);
  double fbound = 0;
  for (int g = 0; g < disc::num_edge_points; ++g) {
    const int gq = std::abs(I.s_plus[g] - disc::edge3_rule.s[g]) < 1e-12 ? g : disc::num_edge_points - 1 - g;
    for (int c = 0; c < 3; ++c) {
      n[g][c] = 0.5 * (edge_plus[gq][c] - edge_minus[g][c]);
      m[g][c] = 0.5 * (edge_plus[gq][3 + c] - edge_minus[g][3 + c]);
    }
    fbound += I.omega[g] * (std::sqrt(cn * disc::dot3(n[g], n[g]) + cm * disc::dot3(m[g], m[g])) / p.S0 - 1.0);
  }
  return fbound * I.inv_he;
}

/// Nucleation check of an intact interface (theory.md §9.5; paper eqs. 29-31, 51) from the average edge force and
/// couple n, m of interface_edge_tractions: the equivalent traction with the current co-normal and the edge
/// average fbar = (1/h_e) sum_g omega_g (n_eq,g / S0 - 1). nu (out): the co-normal at each point (kept if
/// degenerate). Returns fbar; the edge activates if fbar >= 0.
KOKKOS_INLINE_FUNCTION double interface_nucleation(const disc::DgInterfaceRef& I, const materials::CohesiveParams& p,
                                                   const double xm[3][3], const double tm[2][3], const double tp[2][3],
                                                   const double n[disc::num_edge_points][3],
                                                   const double m[disc::num_edge_points][3],
                                                   double nu[disc::num_edge_points][3]) {
  double fbar = 0;
  for (int g = 0; g < disc::num_edge_points; ++g) {
    double dbar[3];
    interface_conormal(I, g, xm, tm, tp, nu[g], dbar);
    fbar += I.omega[g] * (materials::equivalent_traction(p, n[g], m[g], nu[g]) / p.S0 - 1.0);
  }
  return fbar * I.inv_he;
}

}  // namespace shellfrac::solver
