#pragma once
/// \file coulomb_friction.hpp
/// Coulomb friction of a contact (docs/theory.md §12.6, eqs. 12.6a-c), the same law for the walls, the rigid bodies
/// and the shells. The explicit step knows, when it computes the forces at t_{n+1}, the half-step velocity
/// v^{n+1/2}; without friction the next one would be v^{n+3/2} = v^{n+1/2} + dt (f_other / m), whose tangential
/// part is the trial slip velocity w. The friction force that stops the slip in this step is -m w / dt: while it is
/// within the static cone (|m w / dt| <= mu_s f_n) the contact sticks with it, otherwise it slides with the dynamic
/// force -mu_d f_n w / |w|. The force depends on the pair alone: rank- and thread-independent.
#include <cmath>

#include "shellfrac/solver/input/contact_params.hpp"

namespace shellfrac::solver {

/// The friction force on a contact pressed with the normal force fn (>= 0) along the unit normal n, whose trial slip
/// velocity (relative, at the next half step without friction) is w, for the effective mass m_eff of the pair and
/// the step dt (eqs. 12.6a-b). Returns the force in `f` (tangential; zero when there is no friction or no slip) and
/// whether the contact sticks.
inline bool coulomb_friction(const FrictionParams& mu, const double n[3], const double w[3], double fn,
                             double m_eff, double dt, double f[3]) {
  f[0] = f[1] = f[2] = 0;
  if (!mu.enabled() || !(fn > 0)) return false;
  const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
  double wt[3], wt2 = 0;
  for (int c = 0; c < 3; ++c) wt[c] = w[c] - wn * n[c], wt2 += wt[c] * wt[c];
  if (wt2 == 0) return true;
  const double stick = m_eff / dt, slip = std::sqrt(wt2);
  if (stick * slip <= mu.static_coefficient * fn) {
    for (int c = 0; c < 3; ++c) f[c] = -stick * wt[c];
    return true;
  }
  const double scale = mu.dynamic_coefficient * fn / slip;
  for (int c = 0; c < 3; ++c) f[c] = -scale * wt[c];
  return false;
}

/// The energy a friction force f takes over a step dt from a contact slipping at the relative velocity v (eq. 12.6c):
/// -f . v dt (>= 0 when f opposes the slip).
inline double friction_dissipation(const double f[3], const double v[3], double dt) {
  return -(f[0] * v[0] + f[1] * v[1] + f[2] * v[2]) * dt;
}

}  // namespace shellfrac::solver
