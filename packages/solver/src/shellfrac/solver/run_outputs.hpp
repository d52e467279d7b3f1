#pragma once
/// \file run_outputs.hpp
/// The result files of a run (docs/output.md): DG Exodus frames (one file, or a per-rank set for np > 1; a
/// restarted run opens <base>.restart<step>.exo), the history CSV, and with fracture the fragment table and the
/// crack log. A restarted run resumes the CSV files after its restart point.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/io/exodus_results.hpp"

namespace shellfrac::io {
class ExodusResultsWriter;
class HistoryWriter;
}  // namespace shellfrac::io

namespace shellfrac::solver {

struct Deck;
struct RunModel;
struct StepRecord;

/// Paths of a run's result files (Output->Directory and Base Name).
struct ResultPaths {
  explicit ResultPaths(const Deck& deck);
  std::string exodus, history, fragments, cracks, checkpoint;
  /// The Exodus results of a run restarted at `step`: <base>.restart<step>.exo.
  std::string restart_exodus(long step) const;
};

/// The sets written with the results (docs/output.md): the mesh's node and side sets, then the deck's regions
/// (ids after the mesh's), on this rank's owned DG copies (a node set holds every DG copy of its mesh nodes, a
/// side set the owned element edges). Resolved on the conforming mesh: at set-up, while the model has it.
struct ResultsSets {
  std::vector<io::ResultsSet> node_sets, side_sets;
};
ResultsSets results_sets(const Deck& deck, const RunModel& model);

class RunOutputs {
 public:
  /// Creates the files (removing stale results of an earlier run first; a restarted run keeps its CSV rows
  /// up to the restart point) with the sets `sets` (results_sets). `e0` is the initial energy of the balance (the
  /// restart's, if restarted). Collective.
  RunOutputs(const Deck& deck, RunModel& model, const ResultsSets& sets, const std::vector<std::string>& probe_names,
             const std::vector<std::vector<char>>& probe_members, long restart_step, double e0, MPI_Comm comm);
  ~RunOutputs();

  /// An Exodus frame of the current state, and (if `fragment_rows`, fracture runs) the fragment table. Collective.
  void write_frame(bool fragment_rows = true);
  /// A history row, and the crack log rows if new edges were activated. Collective.
  void write_history();
  /// The crack log rows not yet written, if the global count of activated edges changed. Collective.
  void flush_crack_log();
  /// `state` (ShellDynamics::checkpoint, now or earlier) with what a restart of this run needs besides the
  /// state: the initial energy of the balance and the deck's name.
  io::CheckpointData checkpoint(io::CheckpointData state) const;
  /// The Exodus file (rank 0's view: the set's first file for np > 1), for the run summary.
  const std::string& exodus_path() const { return exodus_path_; }

 private:
  /// The values of a history row of the current state (and its record, if `record`). Collective.
  std::vector<double> history_values(StepRecord* record);
  const Deck& deck_;
  RunModel& model_;
  std::vector<std::string> probe_names_, condition_names_;
  const std::vector<std::vector<char>>& probe_members_;
  double e0_;
  std::string exodus_path_;
  std::unique_ptr<io::ExodusResultsWriter> exodus_;
  std::unique_ptr<io::HistoryWriter> history_, fragments_, cracks_;
  std::vector<std::vector<double>> element_constant_;  // block id and rank per owned element
  std::vector<int> nodal_written_, element_written_;   // the fields Output->Fields selects (all by default)
  GlobalId cracks_logged_ = -1;  // the count of activated edges the crack log was last written at
};

}  // namespace shellfrac::solver
