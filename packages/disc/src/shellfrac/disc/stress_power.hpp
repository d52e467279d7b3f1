#pragma once
/// \file stress_power.hpp
/// Spatial stress-power vectors n^i, m^i, l of paper eq. (8) from the resultants (theory.md §3.2):
///   n^i = N^{ij} a_j + Q^i t + M^{ij} d_j,   m^i = M^{ij} a_j,   l = Q^i a_i,
/// with N^{ij} = [[N11, N12], [N12, N22]] and M^{ij} likewise from the Voigt vectors [X11, X22, X12].
/// They are the exact gradient of the stored energy W with respect to a_i, d_i and t (local frame).
/// For the parametric form use n^alpha = (J^{-1})_{alpha i} n^i, m^alpha = (J^{-1})_{alpha i} m^i.
#include <Kokkos_Macros.hpp>

#include "shellfrac/disc/shell_strains.hpp"

namespace shellfrac::disc {

/// N[3] = [N11, N22, N12], Q[2] = [Q1, Q2], M[3] = [M11, M22, M12] (per unit reference area).
/// Outputs n[i][:] = n^i, m[i][:] = m^i (i = 0,1 for i = 1,2) and l[3].
template <class T>
KOKKOS_INLINE_FUNCTION void stress_power_vectors(const ShellKinematicsOf<T>& kin, const T N[3], const T Q[2],
                                                 const T M[3], T n[2][3], T m[2][3], T l[3]) {
  const T Nt[2][2] = {{N[0], N[2]}, {N[2], N[1]}};
  const T Mt[2][2] = {{M[0], M[2]}, {M[2], M[1]}};
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 3; ++k) {
      n[i][k] = Nt[i][0] * kin.a[0][k] + Nt[i][1] * kin.a[1][k] + Q[i] * kin.t[k] + Mt[i][0] * kin.d[0][k] +
                Mt[i][1] * kin.d[1][k];
      m[i][k] = Mt[i][0] * kin.a[0][k] + Mt[i][1] * kin.a[1][k];
    }
  }
  for (int k = 0; k < 3; ++k) l[k] = Q[0] * kin.a[0][k] + Q[1] * kin.a[1][k];
}

}  // namespace shellfrac::disc
