#pragma once
/// \file simulation.hpp
/// A shellfrac run: read and validate the whole deck, build the mesh, partition it, build the distributed
/// DG model — all before any output file is created, so bad input leaves nothing half-written — then
/// write the results (Exodus, history).
#include <mpi.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/materials/material_params.hpp"
#include "shellfrac/solver/dynamics_params.hpp"
#include "shellfrac/solver/mesh_factory.hpp"

namespace shellfrac::dist {
class DistributedMesh;
struct PartitionParams;
}  // namespace shellfrac::dist

namespace shellfrac::solver {

/// Validated "Output" sublist.
struct OutputParams {
  std::string base_name;  ///< results are <directory>/<base_name>.exo and <base_name>_history.csv
  std::string directory;  ///< "" = the current directory
  std::vector<std::string> probes;  ///< node sets whose mean displacement/velocity go to the history

  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
};

/// Validated "Checkpoint" sublist (HDF5 checkpoints and restart; io/checkpoint.hpp).
struct CheckpointParams {
  int step_interval = 0;      ///< write every N steps (0 = never by count)
  double wall_minutes = 0;    ///< write every M minutes of wall time (0 = never by time)
  std::string file;           ///< path; default <Output Directory>/<Base Name>_checkpoint.h5
  std::string restart_from;   ///< restart from this checkpoint ("" = start at t = 0)
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
};

/// The whole validated deck, as plain structs.
struct Deck {
  std::string file;  ///< the deck's path
  MeshParams mesh;
  std::map<std::string, materials::BlockParams> blocks;
  std::map<std::string, materials::MaterialParams> materials;
  std::shared_ptr<dist::PartitionParams> partition;
  OutputParams output;
  CheckpointParams checkpoint;
  DiscretizationParams discretization;
  TimeParams time;
  FractureParams fracture;
  std::vector<BoundaryCondition> boundary_conditions;
  std::vector<InitialVelocity> initial_velocities;
  std::vector<Load> loads;
  Teuchos::RCP<Teuchos::ParameterList> expanded;  ///< the deck with every default filled in

  /// The complete valid parameter tree (user-named sublists shown with one example entry), as printed by
  /// `shellfrac --print-valid-parameters`; the skeleton is itself a runnable deck.
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// Reads (rank 0 + broadcast) and validates a deck. InputError on any problem. Collective.
  static Deck read(const std::string& file, MPI_Comm comm = MPI_COMM_WORLD);
};

/// Mesh and partition statistics of a run (global values, the same on every rank).
struct RunSummary {
  GlobalId elements = 0, nodes = 0, edges = 0, interfaces = 0, boundary_edges = 0, non_manifold_edges = 0;
  GlobalId min_owned = 0, max_owned = 0, min_ghosts = 0, max_ghosts = 0;
  double stable_dt = 0, dt = 0;  ///< stable estimate (before the safety factor) and the step used
  long steps = 0;                ///< time steps taken
  double wall_seconds = 0;       ///< wall time of the time loop
  std::vector<std::string> files;  ///< output files written (rank 0's view: base names)
  long restart_step = -1;          ///< the step the run restarted from (-1: started at t = 0)
  bool stopped_by_signal = false;  ///< SIGTERM: a checkpoint was written and the run stopped early
};

/// A run. Construction does all the input work (collective); run() writes the outputs.
class ShellDynamics;
struct DynamicsSetup;  // shell_dynamics.hpp

/// What ShellDynamics needs from the deck (sections by mesh block index, discretization, time, conditions),
/// as Simulation builds it. Every block of `mesh` must have an entry in deck.blocks (Simulation checks this
/// first). Used by the benchmark to build exactly the model of a run.
DynamicsSetup make_dynamics_setup(const Deck& deck, const mesh::SerialMesh& mesh);

class Simulation {
 public:
  /// `restart_file` (if not empty) overrides the deck's Checkpoint->Restart From.
  Simulation(const std::string& deck_file, MPI_Comm comm = MPI_COMM_WORLD, const std::string& restart_file = "");
  ~Simulation();
  /// Writes step 0, then (End Time > 0) integrates in time, writing Exodus at the output interval and the
  /// history every History Interval steps. Returns the summary. Collective.
  RunSummary run();
  const Deck& deck() const { return deck_; }
  const RunSummary& summary() const { return summary_; }
  /// Path of the Exodus results (the per-rank set's base name when np > 1).
  std::string exodus_path() const;
  std::string history_path() const;
  /// <dir>/<base>_fragments.csv: one row per fragment at each output time (fracture runs only).
  std::string fragments_path() const;
  /// <dir>/<base>_cracks.csv: one row per activated edge (fracture runs only; ShellDynamics::crack_events).
  std::string cracks_path() const;
  /// Path of the checkpoint file this run writes.
  std::string checkpoint_path() const;

 private:
  MPI_Comm comm_;
  Deck deck_;
  std::unique_ptr<mesh::SerialMesh> mesh_;
  std::unique_ptr<dist::DistributedMesh> dmesh_;
  std::unique_ptr<ShellDynamics> dynamics_;
  std::vector<std::string> probe_names_;
  std::vector<std::vector<char>> probe_members_;
  RunSummary summary_;
  double restart_e0_ = 0;  ///< initial energy of the restarted run (for the balance error)
};

}  // namespace shellfrac::solver
