#include "shellfrac/materials/material_params.hpp"

namespace shellfrac::materials {

Teuchos::RCP<const Teuchos::ParameterList> MaterialParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<material name>"));
  params::set_choice(*pl, "Model", "Elastic", "Bulk constitutive model (elastic resultant law, math.md §3)",
                     {"Elastic"});
  pl->set("Density", 7800.0, "Mass density rho0 [mass/length^3]", params::positive_double());
  pl->set("Young's Modulus", 200.0e9, "Young's modulus E [force/length^2]", params::positive_double());
  pl->set("Poisson's Ratio", 0.3, "Poisson's ratio nu", params::double_range(-1.0, 0.5, true, true));
  return pl;
}

MaterialParams MaterialParams::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                               const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  MaterialParams m;
  m.name = name;
  m.model = pl.get<std::string>("Model");
  m.density = pl.get<double>("Density");
  m.youngs_modulus = pl.get<double>("Young's Modulus");
  m.poissons_ratio = pl.get<double>("Poisson's Ratio");
  return m;
}

Teuchos::RCP<const Teuchos::ParameterList> BlockParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<block name>"));
  pl->set("Thickness", 0.01, "Shell thickness h [length]", params::positive_double());
  pl->set("Material", "steel", "Name of an entry of the Materials sublist");
  return pl;
}

BlockParams BlockParams::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                         const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  return {name, pl.get<double>("Thickness"), pl.get<std::string>("Material")};
}

}  // namespace shellfrac::materials
