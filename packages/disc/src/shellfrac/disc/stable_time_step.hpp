#pragma once
/// \file stable_time_step.hpp
/// Element-by-element stable time step estimate (theory.md §8):
///   c_L = sqrt(E / (rho (1 - nu^2))),  c_S = sqrt(G / rho),  G = E / (2 (1 + nu)),
///   omega_mem = (c_L / l_E) sqrt(40 + 20 c_x),
///   omega_rot = sqrt(12 kappa c_S^2 / (h^2 s_I) + (c_L / l_E)^2 (40 + 20 c_T)),
///   dt_E = 2 / max(omega_mem, omega_rot).
/// The safety factor S_f (0.8, at most 0.9) is applied by the caller. For thin shells (l_E/h > ~5) the
/// rotary-inertia/shear term sets the limit: dt ~= 2 h / (sqrt(12 kappa) c_S) = 0.63 h / c_S.
#include <Kokkos_Macros.hpp>
#include <cmath>

namespace shellfrac::disc {

/// Material, thickness and DG parameters entering the estimate.
struct StableStepParams {
  double E;                  ///< Young's modulus
  double nu;                 ///< Poisson's ratio
  double rho;                ///< mass density rho0 (per unit volume)
  double h;                  ///< shell thickness
  double kappa = 5.0 / 6;    ///< shear correction factor
  double cx = 3;             ///< membrane DG penalty coefficient c_x
  double cT = 3;             ///< director DG penalty coefficient c_T
  double rotary_scale = 1;   ///< rotary-inertia scale s_I >= 1 (Ibar = s_I rho h^3 / 12)
};

/// Highest element frequencies of the membrane (omega_mem) and director (omega_rot) estimates of
/// theory.md §8 for an element with characteristic length l_E (see characteristic_length()).
KOKKOS_INLINE_FUNCTION void element_max_frequency(const StableStepParams& p, double l_E, double& omega_mem,
                                                  double& omega_rot) {
  const double cL2 = p.E / (p.rho * (1.0 - p.nu * p.nu));
  const double cS2 = p.E / (2.0 * (1.0 + p.nu)) / p.rho;
  const double wave2 = cL2 / (l_E * l_E);  // (c_L / l_E)^2
  omega_mem = std::sqrt(wave2 * (40.0 + 20.0 * p.cx));
  omega_rot = std::sqrt(12.0 * p.kappa * cS2 / (p.h * p.h * p.rotary_scale) + wave2 * (40.0 + 20.0 * p.cT));
}

/// Stable time step 2 / max(omega_mem, omega_rot) of one element, without the safety factor.
KOKKOS_INLINE_FUNCTION double element_stable_dt(const StableStepParams& p, double l_E) {
  double wm = 0.0, wr = 0.0;
  element_max_frequency(p, l_E, wm, wr);
  return 2.0 / (wm > wr ? wm : wr);
}

}  // namespace shellfrac::disc
