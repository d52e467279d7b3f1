#pragma once
/// \file simulation.hpp
/// A shellfrac run: read and validate the whole deck, build the mesh, partition it, build the distributed
/// DG model (model_setup.hpp) — all before any output file is created, so bad input leaves nothing
/// half-written — then step in time and write the results (run_outputs.hpp) and checkpoints.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/mass_scaling.hpp"
#include "shellfrac/solver/outputs/run_outputs.hpp"
#include "shellfrac/solver/restart/restart_fingerprint.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

namespace shellfrac::solver {

/// Mesh and partition statistics of a run (global values, the same on every rank).
struct RunSummary {
  GlobalId elements = 0, nodes = 0, edges = 0, interfaces = 0, boundary_edges = 0, non_manifold_edges = 0;
  GlobalId min_owned = 0, max_owned = 0, min_ghosts = 0, max_ghosts = 0;
  double stable_dt = 0, dt = 0;  ///< stable estimate (before the safety factor) and the step used
  long steps = 0;                ///< time steps taken
  double wall_seconds = 0;       ///< wall time of the time loop
  std::vector<std::string> files;  ///< output files written (rank 0's view: base names)
  long restart_step = -1;          ///< the step the run restarted from (-1: started at t = 0)
  bool stopped_by_signal = false;  ///< SIGTERM or SIGUSR2: a checkpoint was written and the run stopped early
  std::string stop_signal;         ///< ... and that signal's name
  std::string checkpoint;          ///< the last checkpoint the run wrote ("" if none)
  std::vector<MeshSets::RegionSize> regions;  ///< the deck's regions and their sizes
  MassScaling mass_scaling;                   ///< what Target Time Step added (no elements: none)
  materials::StrengthSummary strengths;       ///< the breakable edges' strengths (no interfaces: no fracture)
  long seed = 0;                              ///< Fracture->Seed, the key of their draws
  bool static_relaxation = false;  ///< the deck asked for the static state (Static Relaxation)
  bool relaxed = false;            ///< ... and the run reached it before End Time
  double residual = 0;             ///< the last relative residual of the static relaxation
  bool stalled = false;            ///< the residual stopped falling while the displacement still changed
  bool at_floor = false;           ///< relaxed: the residual stopped falling at a settled displacement
  double displacement_change = 0;  ///< ... the relative change of the displacement norm over those peaks
  double best_residual = 0;        ///< the smallest residual at a kinetic-energy peak
  double peak_memory_max = 0;      ///< the largest peak resident memory of a rank [bytes] (at the end of run())
  int peak_memory_rank = 0;        ///< ... and that rank
  double peak_memory_sum = 0;      ///< the peak resident memories of all ranks added [bytes]
  PhysicsSummary physics;          ///< what the run's physics came to (the end of run())
};

class SignalGuard;

/// A run. Construction does all the input work (collective); run() writes the outputs. SIGTERM, SIGUSR2 and
/// SIGUSR1 are caught from the start of construction to the end of the run (stop_signals.hpp): SIGTERM or SIGUSR2
/// during the construction stops it at the next phase (StoppedDuringSetUp), nothing written.
class Simulation {
 public:
  /// `restart_file` (if not empty) overrides the deck's Checkpoint->Restart From. The checkpoint must have been
  /// written for this mesh and physics (restart_fingerprint.hpp); `allow_physics_change` accepts other physics.
  Simulation(const std::string& deck_file, MPI_Comm comm = MPI_COMM_WORLD, const std::string& restart_file = "",
             bool allow_physics_change = false);
  ~Simulation();
  /// Writes step 0, then (End Time > 0) integrates in time, writing Exodus at the output interval and the
  /// history every History Interval steps. Returns the summary. Collective.
  RunSummary run();
  /// No progress lines (shellfrac --quiet), whatever Output->Progress Interval says.
  void set_quiet() { progress_interval_ = 0; }
  const Deck& deck() const { return deck_; }
  const RunSummary& summary() const { return summary_; }
  /// What the model check found valid but probably not meant (model_warnings), for rank 0 to print.
  const std::vector<std::string>& warnings() const { return model_.warnings; }
  /// Wall time of each set-up phase on the slowest rank (model_setup.hpp).
  const std::vector<std::pair<std::string, double>>& setup_seconds() const { return model_.setup_seconds; }
  /// Path of the Exodus results (the per-rank set's base name when np > 1).
  std::string exodus_path() const;
  std::string history_path() const;
  /// <dir>/<base>_fragments.csv: one row per fragment at each output time (fracture runs only).
  std::string fragments_path() const;
  /// <dir>/<base>_cracks.csv: one row per activated edge (fracture runs only; ShellDynamics::crack_events).
  std::string cracks_path() const;

 private:
  void restart_from_checkpoint();
  std::vector<std::string> start_notices(const RunOutputs& out) const;
  void print_notices(const std::vector<std::string>& notices) const;
  void refuse_changed_physics_over_its_origin(const io::CheckpointData& header) const;
  void resolve_history_points();
  void summarize();
  void check_time_step();
  void record_peak_memory();
  void complete_summary(RunOutputs& out, const std::string& last_checkpoint, double wall_seconds);
  std::string element_description(GlobalId element, int block) const;

  std::unique_ptr<SignalGuard> signals_;  ///< first: the handlers cover the set-up
  MPI_Comm comm_;
  Deck deck_;
  bool allow_physics_change_ = false;
  RestartFingerprint fingerprint_;
  RunModel model_;
  HistoryPoints history_points_;  // probes, single nodes and elements of the history
  ResultsSets results_sets_;  ///< the sets of the Exodus results, resolved at set-up
  RunSummary summary_;
  double restart_e0_ = 0;  ///< initial energy of the restarted run (for the balance error)
  TableMarks restart_marks_;        ///< where the CSV tables stood at the checkpoint restarted from
  PhysicsSummary restart_physics_;  ///< the physics summary as the checkpoint restarted from left it
  std::string restart_origin_;      ///< the <directory>/<base> of the run the checkpoint was written by ("" unknown)
  double progress_interval_ = 10;  ///< seconds between progress lines (Output->Progress Interval; 0 = none)
};

}  // namespace shellfrac::solver
