#pragma once
/// \file shell_strains.hpp
/// Shell kinematics at a quadrature point and the strain measures of the single-director Cosserat
/// shell (theory.md §2). Everything is expressed in the local orthonormal reference basis {e_1, e_2}:
/// a_i = a_alpha (J^{-1})_{alpha i}, d_i = d_alpha (J^{-1})_{alpha i}, i = 1,2. Pure point functions
/// on plain arrays, usable inside Kokkos kernels (no allocation, no exceptions, no std containers).
///
/// Voigt convention (engineering shear): eps_v = [eps_11, eps_22, 2 eps_12],
/// rho_v = [rho_11, rho_22, 2 rho_12], gam = [gam_1, gam_2].
#include <Kokkos_Macros.hpp>

#include "shellfrac/disc/small_tensor.hpp"

namespace shellfrac::disc {

/// Kinematics at one area quadrature point (current or reference configuration); T is double, or Batch for a
/// batch of elements in lock-step (lanes.hpp).
template <class T>
struct ShellKinematicsOf {
  T a[2][3];  ///< a_i = d^DG_i phi_h, in the local Cartesian reference frame (already times J^{-1})
  T d[2][3];  ///< d_i = d^DG_i t_h, likewise
  T t[3];     ///< t_h(xi_q): the interpolated director, NOT normalized (theory.md §2)
};
using ShellKinematics = ShellKinematicsOf<double>;

/// Reference offsets of the shear and bending strains at one quadrature point (theory.md §2), Voigt.
template <class T>
struct ShellReferenceOf {
  T gam0[2];  ///< gam0_i = a0_i . t0
  T rho0[3];  ///< [rho0_11, rho0_22, 2 rho0_12], rho0_ij = 1/2 (a0_i . d0_j + a0_j . d0_i)
};
using ShellReference = ShellReferenceOf<double>;


/// Reference offsets from the reference kinematics kin0 (a0_i, d0_i, t0). theory.md §2: a0_i = e_i
/// in exact arithmetic; the offsets are nevertheless computed with the given a0_i, so that the shear and bending
/// strains vanish exactly in the reference state whatever the frame of the reference kinematics.
KOKKOS_INLINE_FUNCTION ShellReference make_shell_reference(const ShellKinematics& kin0) {
  ShellReference ref{};
  ref.gam0[0] = dot3(kin0.a[0], kin0.t);
  ref.gam0[1] = dot3(kin0.a[1], kin0.t);
  ref.rho0[0] = dot3(kin0.a[0], kin0.d[0]);
  ref.rho0[1] = dot3(kin0.a[1], kin0.d[1]);
  ref.rho0[2] = dot3(kin0.a[0], kin0.d[1]) + dot3(kin0.a[1], kin0.d[0]);  // 2 rho0_12
  return ref;
}

/// Strain measures of theory.md §2 in Voigt form:
///   eps_ij = 1/2 (a_i . a_j - delta_ij),  gam_i = a_i . t - gam0_i,
///   rho_ij = 1/2 (a_i . d_j + a_j . d_i) - rho0_ij.
/// Outputs eps[3] = [eps_11, eps_22, 2 eps_12], gam[2], rho[3] = [rho_11, rho_22, 2 rho_12].
template <class T>
KOKKOS_INLINE_FUNCTION void compute_strains(const ShellKinematicsOf<T>& kin, const ShellReferenceOf<T>& ref, T eps[3],
                                            T gam[2], T rho[3]) {
  eps[0] = 0.5 * (dot3(kin.a[0], kin.a[0]) - 1.0);
  eps[1] = 0.5 * (dot3(kin.a[1], kin.a[1]) - 1.0);
  eps[2] = dot3(kin.a[0], kin.a[1]);  // 2 eps_12
  gam[0] = dot3(kin.a[0], kin.t) - ref.gam0[0];
  gam[1] = dot3(kin.a[1], kin.t) - ref.gam0[1];
  rho[0] = dot3(kin.a[0], kin.d[0]) - ref.rho0[0];
  rho[1] = dot3(kin.a[1], kin.d[1]) - ref.rho0[1];
  rho[2] = dot3(kin.a[0], kin.d[1]) + dot3(kin.a[1], kin.d[0]) - ref.rho0[2];  // 2 rho_12
}

}  // namespace shellfrac::disc
