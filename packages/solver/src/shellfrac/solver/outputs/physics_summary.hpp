#pragma once
/// \file physics_summary.hpp
/// What a run's physics came to (docs/output.md, "The run summary"): the largest energy-balance error, when edges
/// first broke and separated, how many pieces there are and how heavy and fast the largest and the fastest are, the
/// peak plastic strain. Updated at every history row, completed at the end of the run, printed by the program and
/// written as <base>_summary.json beside the history. A checkpoint carries it, so a restarted run reports the whole
/// run.
#include <map>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

namespace shellfrac::solver {

struct PhysicsSummary {
  double largest_balance_error = 0;       ///< the largest |energy balance error| of the history rows
  double largest_balance_error_time = 0;  ///< ... and when
  double largest_energy_put_in = 0;       ///< the largest |E0| + |W_ext| + |W_react| of the rows
  /// The largest balance error as a fraction of the largest energy put in (0 when nothing was put in): a measure
  /// that noise at the start, when almost nothing is put in, cannot inflate.
  double relative_balance_error() const;
  double first_activation_time = -1;      ///< the first activation in the crack log (-1: none)
  double first_separation_time = -1;      ///< the first history row with a fully separated edge (-1: none)
  GlobalId activated_edges = 0, separated_edges = 0, fragments = 1;  ///< at the end
  double largest_fragment_mass = 0, largest_fragment_speed = 0;      ///< the heaviest piece at the end
  double fastest_fragment_mass = 0, fastest_fragment_speed = 0;      ///< the fastest piece at the end
  double peak_plastic_strain = 0;  ///< the largest equivalent plastic strain alpha at an area point
  bool fracture = false;           ///< some edge can break
  bool plasticity = false;         ///< some block is plastic

  /// One history row: the balance error, the energy put in, the edge counts, the first separation.
  void observe(const StepRecord& r, double e0);
  /// One crack-log row (step, time, ...): the first activation time.
  void observe_crack(const std::vector<double>& row);
  /// The fragment table at the end (rows: fragment_id, elements, mass, com x/y/z, momentum x/y/z).
  void observe_fragments(const std::vector<std::vector<double>>& table);

  /// The summary as a small JSON object (the run's deck, its declared units and time added), numbers with 17 digits,
  /// null for "none".
  std::string json(const std::string& deck, const std::string& units, double end_time) const;
  /// The console lines ("  physics: ..."), one per topic.
  std::string text() const;

  /// The values a checkpoint keeps (keys "physics <name>"), and the summary from them (missing keys: the defaults).
  void store(std::map<std::string, double>& scalars) const;
  static PhysicsSummary restored(const std::map<std::string, double>& scalars);
};

/// Writes `text` to `path` through a temporary file renamed over it (never a half-written file; links refused).
/// OutputError naming the file if it cannot.
void write_whole_file(const std::string& path, const std::string& text);

}  // namespace shellfrac::solver
