#pragma once
/// \file material_params.hpp
/// Material and section parameters, validated from the deck and turned into plain structs
/// (kernels never see a ParameterList). Units are the user's, consistently (e.g. SI, or lbf-in-s).
#include <map>
#include <string>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"

namespace shellfrac::materials {

/// Smallest yield strain Y0 / E that Resultant Plasticity accepts: far below any real material (metals yield at
/// strains of 1e-4 to 1e-2); smaller ratios only arise from mistakes and defeat the return map.
constexpr double min_yield_strain = 1e-6;

/// Bulk material of a shell block (paper Tables 1-4). The elastic resultant law (theory.md §3) uses E, nu;
/// Model = "Resultant Plasticity" (theory.md §4) adds the yield stress Y0, the hardening modulus H and whether the
/// transverse shear force enters the yield function.
struct MaterialParams {
  std::string name;
  std::string model = "Elastic";
  double density = 0;          ///< rho0 [mass / length^3]
  double youngs_modulus = 0;   ///< E [force / length^2]
  double poissons_ratio = 0;   ///< nu, in (-1, 0.5)
  double yield_stress = 0;     ///< Y0 [force / length^2] (Resultant Plasticity)
  double hardening_modulus = 0;  ///< H [force / length^2], linear isotropic (Resultant Plasticity)
  bool shear_in_yield = false;   ///< transverse shear in the yield function (`Shear Yield`, theory.md §4.1)
  double cohesive_strength = 0;  ///< sigma_c [force / length^2]; 0 = edges of this material never break
  double fracture_energy = 0;    ///< Gamma [force / length] (work of separation per unit area), >= 0
  StrengthScatter strength_scatter;  ///< how the edges' strengths scatter about cohesive_strength (theory.md §9.8)
  bool plastic() const { return model == "Resultant Plasticity"; }

  /// Valid parameters of one entry of the "Materials" sublist.
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// Validates `pl` (sets defaults) and converts it. ctx names the deck and the sublist.
  static MaterialParams from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                        const params::Context& ctx);
};

/// Section of an element block: thickness and material.
struct BlockParams {
  std::string name;
  double thickness = 0;  ///< h [length]
  std::string material;  ///< key into the Materials sublist

  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static BlockParams from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

}  // namespace shellfrac::materials
