#pragma once
/// \file strain_treatment.hpp
/// How an element uses its membrane and transverse shear strains (theory.md §5.4): at the area points as the
/// kinematics gives them, or through an L2 projection on the element, the membrane strains keeping a fraction of
/// the remainder that grows as the element flattens.
#include <Kokkos_Macros.hpp>

#include <algorithm>
#include <cmath>

namespace shellfrac::disc {

/// The space a strain field is used in.
enum class StrainSpace : int {
  point_values,  ///< the strains at the area points as they are
  p0,            ///< their element mean (L2 projection on constants)
  p1,            ///< their L2 projection on linear fields in the element
};

/// The spaces of the membrane and transverse shear strains (theory.md eq. 5.4a), the same for every element of a
/// run. The membrane strains are used as P eps, P = (1 - s) Pi + s I, Pi the projection on `membrane` and s the
/// element's membrane remainder (DgElementRef::membrane_remainder); the shear strains through the projection on
/// `shear`.
struct StrainTreatment {
  StrainSpace membrane = StrainSpace::point_values;
  StrainSpace shear = StrainSpace::point_values;

  KOKKOS_INLINE_FUNCTION bool operator==(const StrainTreatment& o) const {
    return membrane == o.membrane && shear == o.shear;
  }
  KOKKOS_INLINE_FUNCTION bool operator!=(const StrainTreatment& o) const { return !(*this == o); }
  /// Whether the membrane strains are used other than at the points.
  KOKKOS_INLINE_FUNCTION bool maps_membrane() const { return membrane != StrainSpace::point_values; }
  /// Whether the shear strains are used other than at the points.
  KOKKOS_INLINE_FUNCTION bool maps_shear() const { return shear != StrainSpace::point_values; }
};

/// The largest sagitta of the element's edges: the distance of each mid-side node from its edge's chord midpoint
/// (c^2 / (8 R) for an edge of chord c on a circle of radius R; 0 for a flat element with straight edges).
inline double largest_edge_sagitta(const double X[6][3]) {
  double largest = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = k, j = (k + 1) % 3, m = 3 + k;
    double d2 = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = X[m][c] - 0.5 * (X[i][c] + X[j][c]);
      d2 += d * d;
    }
    largest = std::max(largest, std::sqrt(d2));
  }
  return largest;
}

/// The sagitta-to-thickness ratio at which the element mean takes half of the membrane energy's remainder away
/// (theory.md eq. 5.4c).
constexpr double remainder_sagitta_scale = 1.0 / 16;

/// The membrane remainder s of a Stabilized P0 element (theory.md eq. 5.4c): s^2 = max(kappa, 1 / (1 + (r / r0)^2))
/// with r = sagitta / thickness, r0 = remainder_sagitta_scale. A flat element keeps its point values (s = 1: P = I
/// exactly); a curved one whose edges rise above the thickness keeps the fraction kappa of the remainder's energy.
inline double mean_membrane_remainder(double sagitta_over_thickness, double kappa) {
  const double r = sagitta_over_thickness / remainder_sagitta_scale;
  return std::sqrt(std::max(kappa, 1 / (1 + r * r)));
}

}  // namespace shellfrac::disc
