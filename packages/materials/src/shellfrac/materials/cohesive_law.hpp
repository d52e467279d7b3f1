#pragma once
/// \file cohesive_law.hpp
/// Extrinsic (initially rigid) resultant cohesive law of the shell (theory.md §9.1-9.3, §9.5 step 2, §9.7;
/// paper §3, eqs. 19-31). Header-only and kernel-safe: no Teuchos, no
/// allocation, no exceptions, no output, plain arrays.
///
/// Kinematics at an edge point (paper eq. 19, theory.md §9.1), nu = unit co-normal (caller's choice of nu, see
/// theory.md §9.1; it must be a unit vector), jumps [[u]] = u^- - u^+:
///   delta_N = [[phi]].nu ,  delta_S = (1 - nu(x)nu)[[phi]] ,  theta_N = [[t]].nu ,  theta_S = (1 - nu(x)nu)[[t]]
///   delta^2 = delta_N^2 + (alpha1 |delta_S|)^2 + (alpha2 h theta_N)^2 + (alpha3 h |theta_S|)^2      (eq. 20)
/// Free energy per unit reference length (eq. 24) with the linear strength (paper §3.1, theory.md §9.2):
///   phi(delta, delta_max) = 1/2 S(delta_max) delta^2 / delta_max ,   S(delta_max) = max(S0 - k delta_max, 0)
/// Tractions = gradient of phi w.r.t. the jumps at fixed delta_max (Coleman-Noll, eq. 17, giving eqs. 22-23):
/// with the secant s = S(delta_max)/delta_max = n/delta (eq. 25, n = dphi/d delta = S delta/delta_max),
///   d(delta^2/2)/d[[phi]] = delta_N nu + alpha1^2 delta_S ,  d(delta^2/2)/d[[t]] = h^2 (alpha2^2 theta_N nu + alpha3^2 theta_S)
///   n_c = s (delta_N nu + alpha1^2 delta_S) ,   m_c = s h^2 (alpha2^2 theta_N nu + alpha3^2 theta_S)
/// i.e. the h^2 of m_c is exactly the square of the h in the theta terms of eq. 20 (no inconsistency between the
/// paper's eqs. 20, 22, 23 and theory.md §9.3). Resolving (n_c, m_c) with eq. 29/31:
///   n_c.nu = s delta_N ,  |(1-nu(x)nu) n_c|/alpha1 = s alpha1 |delta_S| ,
///   m_c.nu/(alpha2 h) = s alpha2 h theta_N ,  |(1-nu(x)nu) m_c|/(alpha3 h) = s alpha3 h |theta_S| ,
/// so equivalent_traction(n_c, m_c) = s delta = n (eq. 29), = S(delta_max) on a loading state (delta = delta_max):
/// the nucleation criterion (eqs. 30-31) and the traction law (eqs. 22-23) measure tractions the same way.
/// Dissipation (eq. 18/26): D_rate = -dphi/d delta_max d delta_max = 1/2 (S - S' delta_max) d delta_max
/// = 1/2 S0 d delta_max for the linear S, so D = 1/2 S0 min(delta_max, delta_f) and, at complete separation
/// (delta_max >= delta_f = 2 Gamma/sigma_c), D = 1/2 h sigma_c 2 Gamma/sigma_c = Gamma h (theory.md §9.7).
/// Along any path, int n_c.d[[phi]] + m_c.d[[t]] = phi + D (test_cohesive_law_dissipation verifies this numerically).
///
/// Bounds: n = s delta <= S(delta_max) <= S0, hence |n_c| <= max(1, alpha1) S0 and |m_c| <= max(alpha2, alpha3) h S0
/// (so |n_c| <= S0 holds for alpha1 <= 1 only; theory.md §9.3).
///
/// With crack-face contact (p.contact, theory.md §9.9) closing is not opening: delta_N enters delta as
/// <delta_N> = max(delta_N, 0), the normal force of the nucleation criterion as <n.nu>, and
/// crack_face_contact_energy resists the faces' interpenetration; without it delta_N enters as delta_N^2 (paper).
#include <Kokkos_Macros.hpp>
#include <cmath>
#include <limits>

#include "shellfrac/core/dual_number.hpp"

namespace shellfrac::materials {

/// Cohesive parameters of an interface (paper §3.1, Tables 2-4; theory.md §9.2).
///   S0 = h sigma_c (force per unit length), k = h sigma_c^2 / (2 Gamma) (force per unit area),
///   delta_f = S0/k = 2 Gamma / sigma_c (effective opening of complete separation).
/// Gamma = 0 (paper §6.3, theory.md §9.3): stored as k = +infinity and delta_f = 0. k is then never multiplied
/// (cohesive_strength tests delta_max >= delta_f first), so S(delta_max) = 0 for EVERY delta_max >= 0,
/// including delta_max = 0: the strength drops at once and the edge is separated at activation. S0 keeps
/// its value h sigma_c, which the nucleation criterion (eq. 30) still uses.
struct CohesiveParams {
  double h;        ///< shell thickness (> 0)
  double sigma_c;  ///< cohesive strength (> 0)
  double Gamma;    ///< work of separation per unit area (>= 0; 0 = strength drops at once)
  double alpha1;   ///< weight of the sliding opening |delta_S| in eq. 20 (> 0)
  double alpha2;   ///< weight of the normal director jump h theta_N (bending) in eq. 20 (> 0)
  double alpha3;   ///< weight of the tangential director jump h |theta_S| (twist) in eq. 20 (> 0)
  double S0;       ///< initial strength h sigma_c
  double k;        ///< softening rate h sigma_c^2 / (2 Gamma); +infinity if Gamma = 0
  double delta_f;  ///< softening length 2 Gamma / sigma_c; 0 if Gamma = 0
  double delta0;   ///< opening at which softening starts (theory.md §9.6: the activation opening); 0 = rigid law
  double contact_stiffness = 0;  ///< k_c of the crack-face contact (theory.md §9.9) [force / length^2]
  bool contact = false;  ///< crack-face contact (Fracture->Crack Face Contact): a closing normal jump is no opening,
                         ///< a compressive normal force does not nucleate, the faces resist interpenetration
};

/// Host helper: cohesive parameters from the thickness h, the strength sigma_c, the work of separation Gamma,
/// the eq. 20 weights alpha1..3 and the activation opening as a fraction of delta_f (paper §3.1: S0 = h sigma_c,
/// k = h sigma_c^2/(2 Gamma), delta_f = 2 Gamma/sigma_c; Gamma = 0 stores k = +inf, delta_f = 0, see
/// CohesiveParams). No validation here (preconditions h > 0, sigma_c > 0, Gamma >= 0, alpha_i > 0,
/// delta0_ratio >= 0; parameter parsing validates).
inline CohesiveParams make_cohesive_params(double h, double sigma_c, double Gamma, double alpha1 = 1,
                                           double alpha2 = 1, double alpha3 = 1, double delta0_ratio = 0) {
  CohesiveParams p{};
  p.h = h;
  p.sigma_c = sigma_c;
  p.Gamma = Gamma;
  p.alpha1 = alpha1;
  p.alpha2 = alpha2;
  p.alpha3 = alpha3;
  p.S0 = h * sigma_c;
  if (Gamma > 0.0) {
    p.k = h * sigma_c * sigma_c / (2.0 * Gamma);
    p.delta_f = 2.0 * Gamma / sigma_c;
  } else {
    p.k = std::numeric_limits<double>::infinity();
    p.delta_f = 0.0;
  }
  p.delta0 = delta0_ratio * p.delta_f;
  return p;
}

namespace detail {

/// Normal and tangential parts of a jump (paper eq. 19): a_N = a.nu, a_S = a - a_N nu (nu a unit vector).
/// Returns |a_S|^2, computed from the subtracted vector (accurate also when a is nearly parallel to nu).
KOKKOS_INLINE_FUNCTION double split_jump(const double a[3], const double nu[3], double& a_N, double a_S[3]) {
  a_N = a[0] * nu[0] + a[1] * nu[1] + a[2] * nu[2];
  double s2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    a_S[i] = a[i] - a_N * nu[i];
    s2 += a_S[i] * a_S[i];
  }
  return s2;
}

/// Components of the jumps (paper eq. 19) and the squared effective opening delta^2 of eq. 20,
///   delta^2 = <delta_N>^2 + alpha1^2 |delta_S|^2 + h^2 (alpha2^2 theta_N^2 + alpha3^2 |theta_S|^2),
/// <x> = max(x, 0) with crack-face contact (p.contact): a closing normal jump is then no opening (dN is returned
/// as <delta_N>); without it, delta_N^2 (the paper's eq. 20).
/// Shared by effective_opening and cohesive_tractions, so that both give bitwise the same delta.
KOKKOS_INLINE_FUNCTION double opening_squared(const CohesiveParams& p, const double jphi[3], const double jt[3],
                                              const double nu[3], double& dN, double dS[3], double& tN,
                                              double tS[3]) {
  const double dS2 = split_jump(jphi, nu, dN, dS);
  const double tS2 = split_jump(jt, nu, tN, tS);
  if (p.contact && dN < 0.0) dN = 0.0;  // with crack-face contact, closing is no opening (theory.md §9.9)
  const double a1s = p.alpha1 * p.alpha1, a2s = p.alpha2 * p.alpha2, a3s = p.alpha3 * p.alpha3;
  return dN * dN + a1s * dS2 + p.h * p.h * (a2s * tN * tN + a3s * tS2);
}

}  // namespace detail

/// Strength S(delta_max) = max(S0 - k (delta_max - delta0), 0) for delta_max >= delta0 (paper eqs. 24-25 with
/// the linear strength of §3.1, theory.md §9.2; delta0 = 0 is the paper's rigid law, delta0 > 0 the law that
/// starts at the activation opening, §9.6), S0 below delta0. Returns 0 whenever delta_max >= delta0 + delta_f,
/// without evaluating k, so that Gamma = 0 (k = +inf, delta_f = delta0 = 0) gives S = 0 for all delta_max >= 0
/// (no inf * 0). For Gamma > 0: S(delta0) = S0, S(delta0 + delta_f) = 0, linear in between; the clamp at 0 also
/// absorbs the last-ulp round-off just below delta0 + delta_f.
KOKKOS_INLINE_FUNCTION double cohesive_strength(const CohesiveParams& p, double delta_max) {
  if (!(delta_max < p.delta0 + p.delta_f)) return 0.0;
  if (delta_max <= p.delta0) return p.S0;
  const double S = p.S0 - p.k * (delta_max - p.delta0);
  return S > 0.0 ? S : 0.0;
}

/// Effective opening delta of paper eq. 20 (theory.md §9.1) from the jumps [[phi]], [[t]] (3-vectors,
/// u^- - u^+) and the unit co-normal nu:
///   delta = sqrt( delta_N^2 + (alpha1 |delta_S|)^2 + (alpha2 h theta_N)^2 + (alpha3 h |theta_S|)^2 ).
/// Plain sum of squares: jumps below ~1e-154 underflow to delta = 0 (harmless: no traction).
KOKKOS_INLINE_FUNCTION double effective_opening(const CohesiveParams& p, const double jphi[3], const double jt[3],
                                                const double nu[3]) {
  double dN, dS[3], tN, tS[3];
  return std::sqrt(detail::opening_squared(p, jphi, jt, nu, dN, dS, tN, tS));
}

/// Result of one cohesive evaluation at an edge point (theory.md §9.7), per unit reference length.
struct CohesiveResult {
  double stored;      ///< phi = 1/2 S(delta_max) delta^2/delta_max (eq. 24); 0 if delta_max = 0 or S = 0
  double dissipated;  ///< D = 1/2 S0 (min(delta_max, delta0 + delta_f) - delta0)^+ (eq. 26 integrated), total
                      ///< so far; Gamma h once separated, 0 for Gamma = 0
  bool separated;     ///< S(delta_max) = 0, i.e. delta_max >= delta_f (always true for Gamma = 0): the point
                      ///< carries no traction any more (theory.md §9.3: the point is separated)
};

/// Cohesive tractions n_c (force per unit reference length, conjugate to [[phi]]) and m_c (couple per unit
/// reference length, conjugate to [[t]]) of paper eqs. 22-23 / theory.md §9.3, with the history variable updated
/// in place first (theory.md §9.2): delta_max = max(delta_max, delta), delta from effective_opening (eq. 20).
/// With the secant s = S(delta_max)/delta_max (eq. 25: n/delta):
///   n_c = s (delta_N nu + alpha1^2 delta_S) ,   m_c = s h^2 (alpha2^2 theta_N nu + alpha3^2 theta_S) ,
/// which are exactly d phi/d[[phi]] and d phi/d[[t]] at fixed delta_max (eq. 17 with phi of eq. 24).
/// n_c = m_c = 0 if delta_max = 0 (the right-hand-limit convention of paper §3.1 at activation with zero jump)
/// or if S(delta_max) = 0 (separated; Gamma = 0 is separated at once: dissipated = 0, separated = true).
/// Also returns the stored energy phi and the dissipated energy D (theory.md §9.7). nu must be a unit vector.
/// Preconditions: delta_max >= 0 on entry (0 at activation), params from make_cohesive_params.
KOKKOS_INLINE_FUNCTION CohesiveResult cohesive_tractions(const CohesiveParams& p, const double jphi[3],
                                                         const double jt[3], const double nu[3], double& delta_max,
                                                         double n_c[3], double m_c[3]) {
  double dN, dS[3], tN, tS[3];
  const double delta2 = detail::opening_squared(p, jphi, jt, nu, dN, dS, tN, tS);  // eq. 20 squared
  const double delta = std::sqrt(delta2);  // bitwise = effective_opening(p, jphi, jt, nu)
  const double a1s = p.alpha1 * p.alpha1, a2s = p.alpha2 * p.alpha2, a3s = p.alpha3 * p.alpha3, h2 = p.h * p.h;
  if (delta > delta_max) delta_max = delta;  // theory.md §9.2: update on entry

  const double S = cohesive_strength(p, delta_max);
  CohesiveResult r{0.0, 0.0, !(S > 0.0)};
  if (r.separated) {
    r.dissipated = 0.5 * p.S0 * (p.delta_f + p.delta0);  // = Gamma h + S0 delta0 / 2 (0 for Gamma = 0)
  } else if (delta_max > p.delta0) {
    r.dissipated = 0.5 * (p.S0 + p.k * p.delta0) * (delta_max - p.delta0);  // delta_max < delta0 + delta_f here
  }
  if (delta_max > 0.0 && S > 0.0) {
    const double s = S / delta_max;  // secant (eq. 25): n = s delta <= S
    const double sm = s * h2;
    for (int i = 0; i < 3; ++i) {
      n_c[i] = s * (dN * nu[i] + a1s * dS[i]);         // eq. 22
      m_c[i] = sm * (a2s * tN * nu[i] + a3s * tS[i]);  // eq. 23
    }
    r.stored = 0.5 * s * delta2;  // eq. 24
  } else {
    for (int i = 0; i < 3; ++i) {
      n_c[i] = 0.0;
      m_c[i] = 0.0;
    }
  }
  return r;
}

/// The gradient of the free energy phi (eq. 24) with respect to the unit co-normal nu at fixed jumps and fixed
/// delta_max (theory.md §9.4): eq. 20 splits the jumps along nu, so with s = S(delta_max)/delta_max
///   dphi/dnu = s [ (c_N - alpha1^2) delta_N [[phi]] + h^2 (alpha2^2 - alpha3^2) theta_N [[t]] ],
/// c_N = 0 for a closing normal jump with crack-face contact (<delta_N> = 0 there), else 1. Zero when
/// alpha1 = alpha2 = alpha3 = 1 and the normal jump counts (the law is then isotropic in the jumps); zero when the
/// point carries nothing (delta_max = 0 or S = 0). Only its part orthogonal to nu matters (nu stays a unit vector).
/// delta_max is the value after cohesive_tractions updated it.
KOKKOS_INLINE_FUNCTION void cohesive_conormal_gradient(const CohesiveParams& p, const double jphi[3],
                                                       const double jt[3], const double nu[3], double delta_max,
                                                       double dphi_dnu[3]) {
  const double S = cohesive_strength(p, delta_max);
  double dN, tN;
  detail::split_jump(jphi, nu, dN, dphi_dnu);  // dphi_dnu as scratch: only the normal parts are needed
  detail::split_jump(jt, nu, tN, dphi_dnu);
  if (!(delta_max > 0.0 && S > 0.0)) {
    for (int i = 0; i < 3; ++i) dphi_dnu[i] = 0.0;
    return;
  }
  const double s = S / delta_max;
  const double cN = p.contact && dN < 0.0 ? 0.0 : 1.0;
  const double a = s * (cN - p.alpha1 * p.alpha1) * dN;
  const double b = s * p.h * p.h * (p.alpha2 * p.alpha2 - p.alpha3 * p.alpha3) * tN;
  for (int i = 0; i < 3; ++i) dphi_dnu[i] = a * jphi[i] + b * jt[i];
}

/// The part of the dissipation D (cohesive_tractions) that releases the energy of the law's starting state
/// (theory.md §9.7): 1/2 k delta0 (min(delta_max, delta0 + delta_f) - delta0)^+, which reaches 1/2 S0 delta0 at
/// separation; D less it is 1/2 S0 (min(delta_max, delta0 + delta_f) - delta0)^+, the work of separation (Gamma h
/// once separated). 0 for delta0 = 0 (also Gamma = 0).
KOKKOS_INLINE_FUNCTION double starting_energy_released(const CohesiveParams& p, double delta_max) {
  if (!(p.delta0 > 0.0) || !(delta_max > p.delta0)) return 0.0;
  const double end = p.delta0 + p.delta_f;
  return 0.5 * p.k * p.delta0 * ((delta_max < end ? delta_max : end) - p.delta0);
}

/// Crack-face contact at an edge point (theory.md §9.9): the faces of an activated edge are the through-thickness
/// lines z in [-h/2, h/2] of its two sides, and fibre z of the minus side is ahead of the plus side's by the
/// normal gap g(z) = d_N + z t_N (d_N = [[phi]].nu, t_N = [[t]].nu, the raw DG jumps). Where g < 0 a penalty of
/// k_c / h per unit thickness pushes the faces apart, with the energy per unit reference length
///   U = k_c/(2h) int_{g<0} g^2 dz
/// (the exact integral over the part of the thickness in contact; U is C1 in d_N and t_N). Closed over the whole
/// thickness: U = 1/2 k_c (d_N^2 + h^2/12 t_N^2). T is double or a dual number (disc/dual_number.hpp): its
/// derivatives are then the contact force f_N = dU/d d_N and couple m_N = dU/d t_N along nu.
template <class T>
KOKKOS_INLINE_FUNCTION T crack_face_contact_energy(double k_c, double h, const T& d_N, const T& t_N) {
  const double dv = value_of(d_N), tv = value_of(t_N);
  if (!(k_c > 0.0)) return T(0.0);
  // The part [z1, z2] of the thickness where g(z) = d_N + z t_N < 0.
  T z1(-0.5 * h), z2(0.5 * h);
  if (tv > 0.0) {
    const T z0 = -d_N / t_N;
    if (value_of(z0) < 0.5 * h) z2 = z0;
  } else if (tv < 0.0) {
    const T z0 = -d_N / t_N;
    if (value_of(z0) > -0.5 * h) z1 = z0;
  } else if (!(dv < 0.0)) {
    return T(0.0);
  }
  if (!(value_of(z2) > value_of(z1))) return T(0.0);
  const T i0 = z2 - z1, i1 = T(0.5) * (z2 * z2 - z1 * z1), i2 = (z2 * z2 * z2 - z1 * z1 * z1) / T(3.0);
  return T(0.5 * k_c / h) * (d_N * d_N * i0 + T(2.0) * d_N * t_N * i1 + t_N * t_N * i2);
}

/// crack_face_contact_energy with its force f_N = dU/d d_N and couple m_N = dU/d t_N (0 when apart).
KOKKOS_INLINE_FUNCTION double crack_face_contact(double k_c, double h, double d_N, double t_N, double& f_N,
                                                 double& m_N) {
  using D = Dual<2>;
  const D U = crack_face_contact_energy(k_c, h, D::variable(d_N, 0), D::variable(t_N, 1));
  f_N = U.d[0], m_N = U.d[1];
  return U.v;
}

/// Equivalent traction of the nucleation criterion (paper eqs. 29-31, theory.md §9.5 step 2) from the average
/// edge force n and couple m (per unit reference length) and the unit co-normal nu:
///   n_eq = sqrt( <n.nu>^2 + (|(1-nu(x)nu) n|/alpha1)^2 + ((m.nu)/(alpha2 h))^2 + (|(1-nu(x)nu) m|/(alpha3 h))^2 ),
/// <x> = max(x, 0) with crack-face contact (p.contact: the faces are pressed together, not pulled apart);
/// (n.nu)^2 without it (the paper's eq. 31).
/// Nucleation when n_eq >= S0 (eq. 30: f = n_eq/S0 - 1 >= 0; theory.md §9.5 averages f over the edge, eq. 51).
/// Applied to the tractions of cohesive_tractions it returns the effective traction n = S(delta_max)
/// delta/delta_max (eq. 29), i.e. S(delta_max) on a loading state. Pure membrane tension n = sigma h nu gives
/// n_eq = sigma h (nucleation at sigma = sigma_c).
KOKKOS_INLINE_FUNCTION double equivalent_traction(const CohesiveParams& p, const double n[3], const double m[3],
                                                  const double nu[3]) {
  double nN, nS[3], mN, mS[3];
  const double nS2 = detail::split_jump(n, nu, nN, nS);
  const double mS2 = detail::split_jump(m, nu, mN, mS);
  if (p.contact && nN < 0.0) nN = 0.0;  // with crack-face contact compression does not drive an edge open (§9.9)
  const double a2h = p.alpha2 * p.h, a3h = p.alpha3 * p.h;
  return std::sqrt(nN * nN + nS2 / (p.alpha1 * p.alpha1) + (mN * mN) / (a2h * a2h) + mS2 / (a3h * a3h));
}

/// The five squared terms of n_eq^2 (equivalent_traction) for the crack log: [0] (n.nu)^2 (normal opening),
/// <n.nu>^2 = 0 under compression, [1] (n.tau)^2/alpha1^2 (in-plane sliding along the edge), [2] (|n_S|^2 - (n.tau)^2)/alpha1^2 (transverse,
/// out-of-plane sliding: shear-off), [3] (m.nu)^2/(alpha2 h)^2, [4] |m_S|^2/(alpha3 h)^2 (director couples).
/// tau: a unit tangent of the edge orthogonal to nu. Their sum is n_eq^2.
KOKKOS_INLINE_FUNCTION void equivalent_traction_parts(const CohesiveParams& p, const double n[3], const double m[3],
                                                      const double nu[3], const double tau[3], double parts[5]) {
  double nN, nS[3], mN, mS[3];
  const double nS2 = detail::split_jump(n, nu, nN, nS);
  const double mS2 = detail::split_jump(m, nu, mN, mS);
  const double nT = nS[0] * tau[0] + nS[1] * tau[1] + nS[2] * tau[2];
  const double a1 = p.alpha1 * p.alpha1, a2h = p.alpha2 * p.h, a3h = p.alpha3 * p.h;
  parts[0] = p.contact && nN < 0.0 ? 0.0 : nN * nN;
  parts[1] = nT * nT / a1;
  parts[2] = (nS2 - nT * nT) / a1;
  parts[3] = mN * mN / (a2h * a2h);
  parts[4] = mS2 / (a3h * a3h);
}

}  // namespace shellfrac::materials
