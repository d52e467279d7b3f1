#include "shellfrac/solver/input/units.hpp"

#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/solver/input/deck.hpp"

namespace shellfrac::solver {

namespace {

/// The SI range of a quantity in real shell structures, with the reason of each bound.
struct PlausibleRange {
  double low, high;
  const char* si_unit;
};
// Density: aerogel and foam cores ~1-100 kg/m^3; osmium 22 590 kg/m^3.
constexpr PlausibleRange density_range{1.0, 3e4, "kg/m^3"};
// Young's modulus: soft elastomers ~1e5 Pa; diamond 1.2e12 Pa.
constexpr PlausibleRange modulus_range{1e5, 1.5e12, "Pa"};
// Yield and cohesive strengths: soft polymers ~1e5 Pa; the theoretical strength of the stiffest solids ~E/10 ~ 1e11 Pa.
constexpr PlausibleRange strength_range{1e5, 1e11, "Pa"};
// Fracture energy: glass ~1-10 J/m^2, tough metals up to ~1e6 J/m^2.
constexpr PlausibleRange fracture_energy_range{1e-2, 1e7, "J/m^2"};
// Thickness: foils and membranes from ~1 um; hull and armour plates up to ~0.5 m.
constexpr PlausibleRange thickness_range{1e-6, 1.0, "m"};

const double pound_force = 4.4482216152605, inch = 0.0254;

}  // namespace

std::string UnitSystem::description() const {
  if (!declared()) return "none (not declared)";
  return name + " (length " + length + ", mass " + mass + ", time " + time + ", force " + force + ", stress " + stress +
         ", energy " + energy + ")";
}

const std::vector<UnitSystem>& unit_systems() {
  static const std::vector<UnitSystem> systems = {
      {"SI", 1.0, 1.0, 1.0, "m", "kg", "s", "N", "Pa", "J"},
      {"mm-t-s", 1e-3, 1e3, 1.0, "mm", "t", "s", "N", "MPa", "mJ"},
      {"mm-kg-ms", 1e-3, 1.0, 1e-3, "mm", "kg", "ms", "kN", "GPa", "J"},
      {"mm-g-ms", 1e-3, 1e-3, 1e-3, "mm", "g", "ms", "N", "MPa", "mJ"},
      {"in-lbf-s", inch, pound_force / inch, 1.0, "in", "lbf s^2/in", "s", "lbf", "psi", "in lbf"},
      {"none", 1.0, 1.0, 1.0, "", "", "", "", "", ""},
  };
  return systems;
}

const UnitSystem& unit_system(const std::string& name) {
  for (const auto& s : unit_systems())
    if (s.name == name) return s;
  SHELLFRAC_REQUIRE(false, "unknown system of units '" << name << "'");
  return unit_systems().front();
}

std::vector<std::string> implausible_constants(const Deck& deck) {
  const UnitSystem& u = unit_system(deck.units);
  std::vector<std::string> out;
  if (!u.declared()) return out;
  const auto check = [&](const std::string& parameter, double value, double si, const PlausibleRange& range,
                         const std::string& unit, const char* what) {
    if (si >= range.low && si <= range.high) return;
    std::ostringstream os;
    os << deck.file << ": '" << parameter << "' = " << value << " " << unit << " is " << (si < range.low ? "below" : "above")
       << " what " << what << " have (" << range.low << " to " << range.high << " " << range.si_unit
       << ") in the declared 'Units' = " << u.name << ": is the deck in another system? Name it with 'Units' (";
    for (std::size_t k = 0; k < unit_systems().size(); ++k) os << (k ? ", " : "") << unit_systems()[k].name;
    os << ")";
    out.push_back(os.str());
  };
  for (const auto& [name, m] : deck.materials) {
    const std::string p = "Materials->" + name + "->";
    check(p + "Density", m.density, u.density_in_si(m.density), density_range, u.mass + "/" + u.length + "^3",
          "structural materials");
    check(p + "Young's Modulus", m.youngs_modulus, u.stress_in_si(m.youngs_modulus), modulus_range, u.stress,
          "solids");
    if (m.yield_stress > 0)
      check(p + "Yield Stress", m.yield_stress, u.stress_in_si(m.yield_stress), strength_range, u.stress, "solids");
    if (m.cohesive_strength > 0)
      check(p + "Cohesive Strength", m.cohesive_strength, u.stress_in_si(m.cohesive_strength), strength_range,
            u.stress, "solids");
    if (m.fracture_energy > 0)
      check(p + "Fracture Energy", m.fracture_energy, u.energy_per_area_in_si(m.fracture_energy),
            fracture_energy_range, u.energy + "/" + u.length + "^2", "solids");
  }
  for (const auto& [name, b] : deck.blocks)
    check("Blocks->" + name + "->Thickness", b.thickness, u.length_in_si(b.thickness), thickness_range, u.length,
          "shell structures");
  return out;
}

}  // namespace shellfrac::solver
