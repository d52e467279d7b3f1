#pragma once
/// \file elastic_resultant.hpp
/// Elastic resultant law of the shell (theory.md §3.1): St. Venant-Kirchhoff in resultants, Kirchhoff-type
/// (per unit reference area). Header-only and kernel-safe: no Teuchos, no allocation, plain arrays.
///   C0 = [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]
///   N_v = D_n C0 (eps_v - eps_v^p),  M_v = D_m C0 (rho_v - rho_v^p),  Q = D_s (gam - gam^p)
///   W   = 1/2 N_v.(eps_v - eps_v^p) + 1/2 M_v.(rho_v - rho_v^p) + 1/2 Q.(gam - gam^p)
/// Voigt with engineering shear: eps_v = [eps_11, eps_22, 2 eps_12], rho_v likewise; N_v = [N11, N22, N12],
/// M_v = [M11, M22, M12]. The plastic strains eps^p, gam^p, rho^p (same conventions) are inputs of the
/// overloads taking them; gam^p is zero unless the transverse shear is in the yield function (`Shear Yield`,
/// theory.md §4.1, resultant_plasticity.hpp).
#include <Kokkos_Macros.hpp>

namespace shellfrac::materials {

/// Section stiffnesses of an elastic shell section (T: double, or one per element of a batch, disc/lanes.hpp).
template <class T>
struct ElasticSectionOf {
  T Dn;  ///< membrane stiffness E h / (1 - nu^2)
  T Dm;  ///< bending stiffness E h^3 / (12 (1 - nu^2))
  T Ds;  ///< transverse shear stiffness kappa G h, G = E / (2 (1 + nu))
  T nu;  ///< Poisson's ratio
};
using ElasticSection = ElasticSectionOf<double>;

/// Host helper: section stiffnesses from Young's modulus E, Poisson's ratio nu, thickness h and shear
/// correction factor kappa (default 5/6). No validation here (MaterialParams/BlockParams validate).
inline ElasticSection make_elastic_section(double E, double nu, double h, double kappa = 5.0 / 6.0) {
  ElasticSection s{};
  s.Dn = E * h / (1.0 - nu * nu);
  s.Dm = E * h * h * h / (12.0 * (1.0 - nu * nu));
  s.Ds = kappa * (E / (2.0 * (1.0 + nu))) * h;
  s.nu = nu;
  return s;
}

namespace detail {
/// y = D C0 x for a Voigt vector x with engineering shear.
template <class T>
KOKKOS_INLINE_FUNCTION void apply_c0(T D, T nu, const T x[3], T y[3]) {
  y[0] = D * (x[0] + nu * x[1]);
  y[1] = D * (nu * x[0] + x[1]);
  y[2] = D * (0.5 * (1.0 - nu) * x[2]);
}
}  // namespace detail

/// Resultants with plastic strains: N = D_n C0 (eps - eps_p), Q = D_s (gam - gam_p), M = D_m C0 (rho - rho_p).
template <class T>
KOKKOS_INLINE_FUNCTION void elastic_resultants(const ElasticSectionOf<T>& s, const T eps[3], const T gam[2],
                                               const T rho[3], const T eps_p[3], const T gam_p[2], const T rho_p[3],
                                               T N[3], T Q[2], T M[3]) {
  const T ee[3] = {eps[0] - eps_p[0], eps[1] - eps_p[1], eps[2] - eps_p[2]};
  const T re[3] = {rho[0] - rho_p[0], rho[1] - rho_p[1], rho[2] - rho_p[2]};
  detail::apply_c0(s.Dn, s.nu, ee, N);
  detail::apply_c0(s.Dm, s.nu, re, M);
  Q[0] = s.Ds * (gam[0] - gam_p[0]);
  Q[1] = s.Ds * (gam[1] - gam_p[1]);
}

/// Purely elastic resultants (eps_p = gam_p = rho_p = 0).
template <class T>
KOKKOS_INLINE_FUNCTION void elastic_resultants(const ElasticSectionOf<T>& s, const T eps[3], const T gam[2],
                                               const T rho[3], T N[3], T Q[2], T M[3]) {
  const T zero[3] = {0.0, 0.0, 0.0};
  elastic_resultants(s, eps, gam, rho, zero, zero, zero, N, Q, M);
}

/// Stored energy per unit reference area with plastic strains (theory.md §3.1).
template <class T>
KOKKOS_INLINE_FUNCTION T elastic_energy(const ElasticSectionOf<T>& s, const T eps[3], const T gam[2], const T rho[3],
                                        const T eps_p[3], const T gam_p[2], const T rho_p[3]) {
  T N[3], Q[2], M[3];
  elastic_resultants(s, eps, gam, rho, eps_p, gam_p, rho_p, N, Q, M);
  T w = 0.0;
  for (int k = 0; k < 3; ++k) w += N[k] * (eps[k] - eps_p[k]) + M[k] * (rho[k] - rho_p[k]);
  w += Q[0] * (gam[0] - gam_p[0]) + Q[1] * (gam[1] - gam_p[1]);
  return 0.5 * w;
}

/// Purely elastic stored energy per unit reference area.
template <class T>
KOKKOS_INLINE_FUNCTION T elastic_energy(const ElasticSectionOf<T>& s, const T eps[3], const T gam[2], const T rho[3]) {
  const T zero[3] = {0.0, 0.0, 0.0};
  return elastic_energy(s, eps, gam, rho, zero, zero, zero);
}

}  // namespace shellfrac::materials
