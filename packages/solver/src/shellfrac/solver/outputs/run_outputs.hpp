#pragma once
/// \file run_outputs.hpp
/// The result files of a run (docs/output.md): DG Exodus frames (one file, or a per-rank set for np > 1; a
/// restarted run writes <base>.exo-s.<step>, which ParaView opens as the continuation of <base>.exo:
/// results_series.hpp), the history CSV, and with fracture the fragment table and the
/// crack log. A restarted run continues a CSV table only where the rows on disk are provably those its checkpoint
/// was written after (TableMarks), else it starts a table of its own (docs/output.md, "Checkpoints and restart").
#include <mpi.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/io/results_writer.hpp"
#include "shellfrac/io/history.hpp"
#include "shellfrac/solver/outputs/physics_summary.hpp"
#include "shellfrac/solver/outputs/results_series.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

namespace shellfrac::solver {

struct Deck;
struct RunModel;
struct StepRecord;

/// Paths of a run's result files (Output->Directory and Base Name).
struct ResultPaths {
  explicit ResultPaths(const Deck& deck);
  std::string exodus, history, fragments, cracks, checkpoint;
  /// The run's lock file (<base>.lock): held while the run writes (core/files.hpp, RunLock).
  std::string lock;
  /// The result names of a run restarted at `step`: the Exodus series member <base>.exo-s.<step>, and for the
  /// tables it cannot continue <base>.restart<step>_history.csv, ...
  ResultPaths restarted(long step) const;
  /// <directory>/<base>: the names above are it and a suffix.
  const std::string& prefix() const { return prefix_; }
  /// `name` (a file name without directory) in the output directory.
  std::string in_directory(const std::string& name) const;
  /// Whether `name` (without directory) is this base's table `suffix` ("_history.csv"): <base><suffix> or
  /// <base>.restart<N><suffix>.
  bool of_this_base(const std::string& name, const std::string& suffix) const;

 private:
  std::string prefix_;          ///< <directory>/<base>
  std::string directory_, base_;  ///< Output->Directory ("" = the current one) and Base Name
  ResultPaths() = default;
  void name(const std::string& prefix);
};

/// The CSV tables of a run by name ("history", "fragments", "cracks") and where each stood when a checkpoint was
/// written (RunOutputs::checkpoint stores them; read back by table_marks).
using TableMarks = std::map<std::string, io::CsvMark>;
TableMarks table_marks(const io::CheckpointData& header);

/// The sets written with the results (docs/output.md): the mesh's node and side sets, then the deck's regions
/// (ids after the mesh's), on this rank's owned DG copies (a node set holds every DG copy of its mesh nodes, a
/// side set the owned element edges). Resolved on the conforming mesh: at set-up, while the model has it.
struct ResultsSets {
  std::vector<io::ResultsSet> node_sets, side_sets;
};
ResultsSets results_sets(const Deck& deck, const RunModel& model);

/// What the history records beyond the global quantities (Output->Probes, History Nodes, History Elements),
/// resolved against the mesh at set-up.
struct HistoryPoints {
  std::vector<std::string> probe_names;
  std::vector<std::vector<char>> probe_members;  ///< per probe: a flag per mesh node
  std::vector<long long> node_ids, element_ids;  ///< as the deck names them (the mesh file's ids; column names)
  std::vector<GlobalId> nodes, elements;         ///< their mesh node positions and global element ids
};

class RunOutputs {
 public:
  /// Creates the files (removing stale results of an earlier run first) with the sets `sets` (results_sets). `e0`
  /// is the initial energy of the balance (the restart's, if restarted). A run restarted at `restart_step` (>= 0)
  /// writes its Exodus frames to <base>.exo-s.<step> and continues each CSV table the checkpoint names (`marks`)
  /// if that file is one of this base's and its rows on disk are provably those the checkpoint was written after;
  /// otherwise the table on disk is left as it is and the run starts <base>_<table>.csv, or if that exists
  /// <base>.restart<step>_<table>.csv, and says so (`notices`) when a table it could have continued was not
  /// provably its own. Collective.
  RunOutputs(const Deck& deck, RunModel& model, const ResultsSets& sets, const HistoryPoints& points,
             long restart_step, const TableMarks& marks, double e0, MPI_Comm comm);
  ~RunOutputs();

  /// An Exodus frame of the current state, and (if `fragment_rows`, fracture runs) the fragment table. Collective.
  void write_frame(bool fragment_rows = true);
  /// A history row, and the crack log rows if new edges were activated. Collective.
  void write_history();
  /// The crack log rows not yet written, if the global count of activated edges changed. Collective.
  void flush_crack_log();
  /// `state` (ShellDynamics::checkpoint, taken now) with what a restart of this run needs besides the state: the
  /// initial energy of the balance, the deck's name and the marks of the CSV tables as they are now.
  io::CheckpointData checkpoint(io::CheckpointData state) const;
  /// The Exodus file (rank 0's view: the set's first file for np > 1), for the run summary.
  const std::string& exodus_path() const { return exodus_path_; }
  /// The CSV tables' files (the fragment and crack tables are "" without fracture).
  std::string history_path() const;
  std::string fragments_path() const;
  std::string cracks_path() const;
  /// What the user must know about the files (a restart that could not continue a table, or whose results
  /// ParaView cannot open with those before it), on rank 0.
  const std::vector<std::string>& notices() const { return notices_; }
  /// At the end of a restarted run: the earlier results' frames after the restart's time that ParaView shows
  /// between this run's (results_series.hpp, interleaving_notices), on rank 0.
  std::vector<std::string> series_notices() const;
  /// The physics summary goes on from where the checkpoint a run restarted from left it.
  void resume_physics(const PhysicsSummary& p) { physics_ = p; }
  /// Completes the physics summary with the end state (fragments, peak plastic strain), writes it as
  /// <base>_summary.json beside the history (rank 0) and returns it. Collective.
  const PhysicsSummary& finish_physics();
  /// <base>_summary.json (beside the history file).
  std::string summary_path() const;

 private:
  /// Rank 0: removes what an earlier run left under our names, or (restarted) surveys the series continued.
  void prepare_result_files(const ResultPaths& paths, bool restarted);
  /// The values of a history row of the current state (and its record, if `record`). Collective.
  std::vector<double> history_values(StepRecord* record);
  const Deck& deck_;
  RunModel& model_;
  const HistoryPoints& points_;
  HistoryGroups history_groups_;  // the history's column groups: names fixed at construction, values of the last row
  double e0_;
  std::string exodus_path_;
  std::unique_ptr<io::ExodusResultsWriter> exodus_;
  std::unique_ptr<io::HistoryWriter> history_, fragments_, cracks_;
  std::vector<std::vector<double>> element_constant_;  // block id and rank per owned element
  std::vector<int> nodal_written_, element_written_;   // the fields Output->Fields selects (all by default)
  GlobalId cracks_logged_ = -1;  // the count of activated edges the crack log was last written at
  std::vector<std::string> notices_;
  double restart_time_ = 0;                ///< the time a restarted run started from
  std::vector<LaterFrames> later_frames_;  ///< rank 0: the earlier results' frames after it
  std::vector<double> frame_times_;        ///< rank 0: this run's frame times
  PhysicsSummary physics_;
  MPI_Comm comm_;
};

}  // namespace shellfrac::solver
