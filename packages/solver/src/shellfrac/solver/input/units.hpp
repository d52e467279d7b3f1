#pragma once
/// \file units.hpp
/// The deck's system of units (`Units`, docs/input_reference.xml and docs/output.md, "Units"). shellfrac computes
/// in whatever consistent system the deck is written in; the declaration names it so that the results say which
/// (Exodus information record, <base>_summary.json, the tools' axis labels) and so that material constants and
/// thicknesses far outside what real shell structures have in that system are reported (a modulus typed 70e3
/// instead of 70e9 in SI). `none`: no declared system, no check, no unit labels.
#include <string>
#include <vector>

namespace shellfrac::solver {

struct Deck;

/// A consistent system of units: its base units in SI and the names of the units of what the deck and the
/// results hold.
struct UnitSystem {
  std::string name;                            ///< as in the deck: "SI", "mm-t-s", ..., "none"
  double metre = 1, kilogram = 1, second = 1;  ///< its length, mass and time units, in m, kg and s
  std::string length, mass, time, force, stress, energy;  ///< unit names ("" for `none`)

  bool declared() const { return name != "none"; }
  /// "SI (length m, mass kg, time s, force N, stress Pa, energy J)", or "none (not declared)".
  std::string description() const;
  /// A stress (force / length^2), a density (mass / length^3), a length and an energy per area of this system in SI.
  double stress_in_si(double v) const { return v * kilogram / (metre * second * second); }
  double density_in_si(double v) const { return v * kilogram / (metre * metre * metre); }
  double length_in_si(double v) const { return v * metre; }
  double energy_per_area_in_si(double v) const { return v * kilogram / (second * second); }
};

/// The systems `Units` accepts, the default (SI) first.
const std::vector<UnitSystem>& unit_systems();
/// The system of that name (one of unit_systems(); the deck validates the name).
const UnitSystem& unit_system(const std::string& name);

/// Warnings, each naming the parameter, for a density, modulus, stress, fracture energy or thickness of the deck
/// that is outside the range real shell structures have (stated in docs/input_reference.xml) in the deck's
/// declared system; none for `none`.
std::vector<std::string> implausible_constants(const Deck& deck);

}  // namespace shellfrac::solver
