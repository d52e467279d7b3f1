#include "shellfrac/solver/outputs/physics_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"

namespace shellfrac::solver {

namespace {

/// A number for JSON: 17 significant digits; "null" for a time that never came (negative) when `none_if_negative`.
std::string number(double v, bool none_if_negative = false) {
  if ((none_if_negative && v < 0) || !std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// A string for JSON, with quotes and backslashes escaped and control characters dropped.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

/// The members a checkpoint keeps, by name.
template <class Summary, class Visit>
void visit_values(Summary& s, Visit&& visit) {
  visit("largest_balance_error", s.largest_balance_error);
  visit("largest_balance_error_time", s.largest_balance_error_time);
  visit("largest_energy_put_in", s.largest_energy_put_in);
  visit("first_activation_time", s.first_activation_time);
  visit("first_separation_time", s.first_separation_time);
}

}  // namespace

void PhysicsSummary::observe(const StepRecord& r, double e0) {
  const double put_in = std::abs(e0) + std::abs(r.external_work) + std::abs(r.reaction_work);
  const double error = std::abs(energy_balance_error(r, e0));
  if (error > largest_balance_error) largest_balance_error = error, largest_balance_error_time = r.time;
  largest_energy_put_in = std::max(largest_energy_put_in, put_in);
  activated_edges = r.cohesive_edges, separated_edges = r.separated_edges, fragments = r.fragments;
  if (r.separated_edges > 0 && first_separation_time < 0) first_separation_time = r.time;
}

double PhysicsSummary::relative_balance_error() const {
  return largest_energy_put_in > 0 ? largest_balance_error / largest_energy_put_in : 0.0;
}

void PhysicsSummary::observe_crack(const std::vector<double>& row) {
  if (row.size() > 1 && first_activation_time < 0) first_activation_time = row[1];
}

void PhysicsSummary::observe_fragments(const std::vector<std::vector<double>>& table) {
  largest_fragment_mass = largest_fragment_speed = fastest_fragment_mass = fastest_fragment_speed = 0;
  for (const auto& row : table) {
    if (row.size() < 9 || !(row[2] > 0)) continue;
    const double mass = row[2];
    const double speed = std::sqrt(row[6] * row[6] + row[7] * row[7] + row[8] * row[8]) / mass;
    if (mass > largest_fragment_mass) largest_fragment_mass = mass, largest_fragment_speed = speed;
    if (speed > fastest_fragment_speed) fastest_fragment_speed = speed, fastest_fragment_mass = mass;
  }
}

std::string PhysicsSummary::json(const std::string& deck, const std::string& units, double end_time) const {
  std::ostringstream os;
  os << "{\n  \"deck\": " << quoted(deck) << ",\n  \"units\": " << quoted(units) << ",\n  \"time\": "
     << number(end_time) << ",\n"
     << "  \"largest_energy_balance_error\": " << number(relative_balance_error()) << ",\n"
     << "  \"largest_energy_balance_error_time\": " << number(largest_balance_error_time) << ",\n"
     << "  \"largest_energy_put_in\": " << number(largest_energy_put_in) << ",\n"
     << "  \"fracture\": " << (fracture ? "true" : "false") << ",\n"
     << "  \"first_activation_time\": " << number(first_activation_time, true) << ",\n"
     << "  \"first_separation_time\": " << number(first_separation_time, true) << ",\n"
     << "  \"activated_edges\": " << activated_edges << ",\n  \"separated_edges\": " << separated_edges << ",\n"
     << "  \"fragments\": " << fragments << ",\n"
     << "  \"largest_fragment\": {\"mass\": " << number(largest_fragment_mass)
     << ", \"speed\": " << number(largest_fragment_speed) << "},\n"
     << "  \"fastest_fragment\": {\"mass\": " << number(fastest_fragment_mass)
     << ", \"speed\": " << number(fastest_fragment_speed) << "},\n"
     << "  \"plasticity\": " << (plasticity ? "true" : "false") << ",\n"
     << "  \"peak_equivalent_plastic_strain\": " << number(peak_plastic_strain) << "\n}\n";
  return os.str();
}

std::string PhysicsSummary::text() const {
  std::ostringstream os;
  os.precision(4);
  os << "  physics: largest energy-balance error " << relative_balance_error()
     << " of the largest energy put in (at t = " << largest_balance_error_time << ")\n";
  if (fracture) {
    os << "  fracture: " << activated_edges << " edges activated";
    if (first_activation_time >= 0) os << " (first at t = " << first_activation_time << ")";
    os << ", " << separated_edges << " separated";
    if (first_separation_time >= 0) os << " (first seen at t = " << first_separation_time << ")";
    os << "; " << fragments << (fragments == 1 ? " piece" : " pieces");
    if (fragments > 1)
      os << "; the heaviest: mass " << largest_fragment_mass << ", speed " << largest_fragment_speed
         << "; the fastest: mass " << fastest_fragment_mass << ", speed " << fastest_fragment_speed;
    os << "\n";
  }
  if (plasticity) os << "  plasticity: peak equivalent plastic strain " << peak_plastic_strain << "\n";
  return os.str();
}

void PhysicsSummary::store(std::map<std::string, double>& scalars) const {
  visit_values(*this, [&](const char* name, double v) { scalars[std::string("physics ") + name] = v; });
}

PhysicsSummary PhysicsSummary::restored(const std::map<std::string, double>& scalars) {
  PhysicsSummary s;
  visit_values(s, [&](const char* name, double& v) {
    const auto it = scalars.find(std::string("physics ") + name);
    if (it != scalars.end()) v = it->second;
  });
  return s;
}

void write_whole_file(const std::string& path, const std::string& text) {
  files::require_result_path(path);
  const std::string tmp = files::fresh_temporary(path);
  {
    files::OutputFile f(tmp, files::OutputFile::Mode::append);
    f.write(text);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw OutputError(path + ": cannot write the file (" + ec.message() + ")");
}

}  // namespace shellfrac::solver
