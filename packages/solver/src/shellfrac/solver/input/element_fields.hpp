#pragma once
/// \file element_fields.hpp
/// The element result fields a run computes (Exodus element variables, docs/output.md), in file order: what
/// Output->Fields may name and what ShellDynamics::element_fields fills.
#include <string>
#include <vector>

namespace shellfrac::solver {

enum class ElementField : int {
  eq_plastic_strain,  ///< area-weighted mean of the equivalent plastic strain alpha
  membrane_force,     ///< ... of the von Mises norm of the membrane forces N
  bending_moment,     ///< ... of the same norm of the moments M
  shear_force,        ///< ... of |Q|
  damage,             ///< max over the element's edges of (delta_max - delta0) / delta_f, 1 if separated
  fragment_id,        ///< smallest element id + 1 of the element's fragment
  edge_strength,      ///< cohesive strength of the element's weakest breakable edge (0 if none)
  count
};

inline std::vector<std::string> element_field_names() {
  return {"eq_plastic_strain", "membrane_force", "bending_moment", "shear_force", "damage",
          "fragment_id",       "edge_strength"};
}

}  // namespace shellfrac::solver
