#include "shellfrac/materials/material_params.hpp"

#include "shellfrac/core/error.hpp"

namespace shellfrac::materials {

Teuchos::RCP<const Teuchos::ParameterList> MaterialParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<material name>"));
  params::set_choice(*pl, "Model", "Elastic",
                     "Bulk constitutive model: Elastic (resultant law, docs/theory.md §3) or Resultant Plasticity "
                     "(Ilyushin ellipsoid in membrane and bending resultants, linear isotropic hardening, "
                     "docs/theory.md §4)",
                     {"Elastic", "Resultant Plasticity"});
  pl->set("Density", 7800.0, "Mass density rho0 [mass/length^3]", params::positive_double());
  pl->set("Young's Modulus", 200.0e9, "Young's modulus E [force/length^2]", params::positive_double());
  pl->set("Poisson's Ratio", 0.3, "Poisson's ratio nu", params::double_range(-1.0, 0.5, true, true));
  pl->set("Yield Stress", 0.0, "Resultant Plasticity: initial yield stress Y0 [force/length^2] (required, > 0)",
          params::non_negative_double());
  pl->set("Hardening Modulus", 0.0, "Resultant Plasticity: linear isotropic hardening modulus H = d sigma_y / d "
                                    "(equivalent plastic strain) [force/length^2]; 0 = perfectly plastic",
          params::non_negative_double());
  pl->set("Shear Yield", false,
          "Resultant Plasticity: the transverse shear force Q enters the yield function, sigma_eq^2 += 3 |Q|^2 / h^2, "
          "so that pure shear yields at |Q| = h sigma_y / sqrt(3) (docs/theory.md §4.1); false = Q stays elastic. "
          "Turn it on where shear-off is possible: an elastic Q can reach the cohesive strength of an edge at impact");
  pl->set("Cohesive Strength", 0.0, "sigma_c: strength of the extrinsic cohesive law on the element edges "
                                    "[force/length^2] (paper §3); 0 = this material never breaks",
          params::non_negative_double());
  pl->set("Fracture Energy", 0.0, "Gamma: work of separation per unit crack area [force/length]; 0 = the "
                                  "strength drops to zero at once when an edge breaks (paper §6.3)",
          params::non_negative_double());
  params::set_choice(*pl, "Strength Distribution", "Constant",
                     "How the cohesive strength scatters from edge to edge (docs/theory.md §9.8): Constant (every edge "
                     "has the Cohesive Strength), Uniform (mean Cohesive Strength, half-width Strength Spread x mean), "
                     "Normal (mean Cohesive Strength, standard deviation Strength Spread x mean, truncated at 3 "
                     "standard deviations) or Weibull (modulus Weibull Modulus; an edge of the Weibull Reference "
                     "Length has the mean Cohesive Strength, a longer one is weaker as (L_ref/L)^(1/m)). Each edge's "
                     "draw is a hash of Fracture->Seed and its id: the same on any number of ranks and threads",
                     {"Constant", "Uniform", "Normal", "Weibull"});
  pl->set("Strength Spread", 0.0,
          "Uniform: half-width of the strengths as a fraction of the mean, in (0, 1); Normal: standard deviation as "
          "a fraction of the mean, in (0, 1/3) so that the truncated law stays positive",
          params::non_negative_double());
  pl->set("Weibull Modulus", 0.0, "Weibull: the modulus m > 0 (metals' flaw populations: about 5 to 40; larger is "
                                  "less scatter, the coefficient of variation is about 1.2/m)",
          params::non_negative_double());
  pl->set("Weibull Reference Length", 0.0,
          "Weibull: the edge length L_ref [length] > 0 at which the mean edge strength is the Cohesive Strength",
          params::non_negative_double());
  return pl;
}

namespace {

// The strength distribution of a material with a Cohesive Strength, its own parameters only.
StrengthScatter read_strength_scatter(const Teuchos::ParameterList& pl, double cohesive_strength,
                                 const params::Context& ctx) {
  StrengthScatter s;
  s.type = distribution_of(pl.get<std::string>("Strength Distribution"));
  s.spread = pl.get<double>("Strength Spread");
  s.weibull_modulus = pl.get<double>("Weibull Modulus");
  s.reference_length = pl.get<double>("Weibull Reference Length");
  const std::string where = ctx.file + ": '" + ctx.path + "'";
  const std::string type = distribution_name(s.type);
  SHELLFRAC_INPUT_REQUIRE(!s.scattered() || cohesive_strength > 0,
                          where << " has Strength Distribution = " << type << " but no 'Cohesive Strength'");
  const bool uses_spread = s.type == StrengthDistribution::Uniform || s.type == StrengthDistribution::Normal;
  const bool weibull = s.type == StrengthDistribution::Weibull;
  SHELLFRAC_INPUT_REQUIRE(uses_spread || s.spread == 0,
                          where << " gives a 'Strength Spread', which only the Uniform and Normal distributions use "
                                << "(the Strength Distribution is " << type << ")");
  SHELLFRAC_INPUT_REQUIRE(weibull || (s.weibull_modulus == 0 && s.reference_length == 0),
                          where << " gives a 'Weibull Modulus' or 'Weibull Reference Length', which only the Weibull "
                                << "distribution uses (the Strength Distribution is " << type << ")");
  const double max_spread = s.type == StrengthDistribution::Normal ? 1 / normal_truncation : 1.0;
  SHELLFRAC_INPUT_REQUIRE(!uses_spread || (s.spread > 0 && s.spread < max_spread),
                          where << "->Strength Spread' = " << s.spread << " must be in (0, " << max_spread << ") for "
                                << "the " << type << " distribution (its strengths must stay positive)");
  SHELLFRAC_INPUT_REQUIRE(!weibull || (s.weibull_modulus > 0 && s.reference_length > 0),
                          where << " has Strength Distribution = Weibull but no positive 'Weibull Modulus' and "
                                << "'Weibull Reference Length'");
  return s;
}

}  // namespace

MaterialParams MaterialParams::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                               const params::Context& ctx) {
  const bool has_yield = pl.isParameter("Yield Stress");
  params::validate(pl, *valid_parameters(), ctx);
  MaterialParams m;
  m.name = name;
  m.model = pl.get<std::string>("Model");
  m.density = pl.get<double>("Density");
  m.youngs_modulus = pl.get<double>("Young's Modulus");
  m.poissons_ratio = pl.get<double>("Poisson's Ratio");
  m.yield_stress = pl.get<double>("Yield Stress");
  m.hardening_modulus = pl.get<double>("Hardening Modulus");
  m.shear_in_yield = pl.get<bool>("Shear Yield");
  m.cohesive_strength = pl.get<double>("Cohesive Strength");
  m.fracture_energy = pl.get<double>("Fracture Energy");
  m.strength_scatter = read_strength_scatter(pl, m.cohesive_strength, ctx);
  SHELLFRAC_INPUT_REQUIRE(m.cohesive_strength > 0 || m.fracture_energy == 0,
                          ctx.file << ": '" << ctx.path << "' gives a 'Fracture Energy' but no 'Cohesive Strength'");
  // Stresses above the modulus are strains above 100 %: a modulus in other units than the stresses (70e3 typed for
  // 70e9 Pa), never a material. Unit-free, so it holds in any consistent unit system.
  for (const auto& [name, stress] : {std::pair<const char*, double>{"Yield Stress", m.yield_stress},
                                     std::pair<const char*, double>{"Cohesive Strength", m.cohesive_strength}})
    SHELLFRAC_INPUT_REQUIRE(stress < m.youngs_modulus,
                            ctx.file << ": '" << ctx.path << "->" << name << "' = " << stress << " is not below "
                                     << "Young's Modulus = " << m.youngs_modulus << " (a strain of "
                                     << stress / m.youngs_modulus << " at that stress; metals yield and break at "
                                     << "1e-4 to 1e-1): are they in the same units?");
  if (m.plastic()) {
    SHELLFRAC_INPUT_REQUIRE(has_yield && m.yield_stress > 0,
                            ctx.file << ": '" << ctx.path << "' has Model = Resultant Plasticity but no positive "
                                     << "'Yield Stress'");
    SHELLFRAC_INPUT_REQUIRE(m.yield_stress >= min_yield_strain * m.youngs_modulus,
                            ctx.file << ": '" << ctx.path << "->Yield Stress' = " << m.yield_stress << " is below "
                                     << min_yield_strain << " x Young's Modulus = "
                                     << min_yield_strain * m.youngs_modulus << "; no material yields at so small a "
                                     << "strain (metals: 1e-4 to 1e-2), and the return map cannot resolve it "
                                     << "(docs/theory.md §4.3)");
  } else {
    SHELLFRAC_INPUT_REQUIRE(m.yield_stress == 0 && m.hardening_modulus == 0 && !m.shear_in_yield,
                            ctx.file << ": '" << ctx.path << "' gives a yield stress, hardening modulus or shear yield, "
                                     << "which only Model = Resultant Plasticity uses (the Model is " << m.model << ")");
  }
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
