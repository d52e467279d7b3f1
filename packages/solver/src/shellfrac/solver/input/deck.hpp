#pragma once
/// \file deck.hpp
/// The input deck: the complete valid parameter tree, and the deck read, validated and converted to plain
/// structs (kernels never see a ParameterList). Every error here is an InputError naming the deck and the
/// parameter path, raised before any output exists.
#include <mpi.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/materials/material_params.hpp"
#include "shellfrac/solver/input/contact_params.hpp"
#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/input/mesh_factory.hpp"
#include "shellfrac/solver/input/regions.hpp"

namespace shellfrac::decomposition {
struct PartitionParams;
}

namespace shellfrac::solver {

/// Validated "Output" sublist.
struct OutputParams {
  std::string base_name;  ///< results are <directory>/<base_name>.exo and <base_name>_history.csv
  std::string directory;  ///< "" = the current directory
  std::vector<std::string> probes;  ///< node sets whose mean displacement/velocity go to the history
  std::vector<long long> history_nodes;     ///< mesh nodes (the mesh file's ids) with their own history columns
  std::vector<long long> history_elements;  ///< elements (the mesh file's ids) with their own history columns
  bool block_energies = true;               ///< per element block: kinetic, strain energy and plastic work
  double progress_interval = 10;    ///< seconds of wall time between progress lines on rank 0 (0 = none)
  std::vector<std::string> fields;  ///< Exodus fields to write (nodal_result_names, element_result_names; empty = all)

  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// <directory>/<base_name><suffix> (no directory part when directory is empty).
  std::string path(const std::string& suffix) const;
};

/// The Exodus result fields a run can write (Output->Fields), in file order: the nodal vectors ...
std::vector<std::string> nodal_result_names();
/// ... and the element scalars.
std::vector<std::string> element_result_names();

/// Validated "Checkpoint" sublist (HDF5 checkpoints and restart; io/checkpoint.hpp).
struct CheckpointParams {
  int step_interval = 0;      ///< write every N steps (0 = never by count)
  double wall_minutes = 0;    ///< write every M minutes of wall time (0 = never by time)
  std::string file;           ///< name of the series; default <Output Directory>/<Base Name>_checkpoint.h5
  int keep = 3;               ///< checkpoints of this run kept (checkpoint_series.hpp)
  std::string restart_from;   ///< restart from this checkpoint ("" = start at t = 0)
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
};

/// The whole validated deck, as plain structs.
struct Deck {
  std::string file;  ///< the deck's path (or a label for decks built in memory)
  std::string units = "SI";  ///< the declared system of units (`Units`; units.hpp), "none" if not declared
  MeshParams mesh;
  std::map<std::string, materials::BlockParams> blocks;
  std::map<std::string, materials::MaterialParams> materials;
  std::shared_ptr<decomposition::PartitionParams> partition;
  OutputParams output;
  CheckpointParams checkpoint;
  DiscretizationParams discretization;
  TimeParams time;
  FractureParams fracture;
  ContactParams contact;
  std::vector<BoundaryCondition> boundary_conditions;
  std::vector<InitialVelocity> initial_velocities;
  std::vector<Load> loads;
  std::vector<Region> regions;  ///< named regions, usable as element, node and side sets
  Teuchos::RCP<Teuchos::ParameterList> expanded;  ///< the deck with every default filled in

  /// The complete valid parameter tree (user-named sublists shown with one example entry), as printed by
  /// `shellfrac --print-valid-parameters`; the skeleton is itself a runnable deck.
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// Reads (rank 0 + broadcast) and validates a deck file. InputError on any problem. Collective.
  static Deck read(const std::string& file, MPI_Comm comm = MPI_COMM_WORLD);
  /// Validates a parameter list (defaults are filled into it) and converts it. `file` names the deck in
  /// messages; relative paths in it (mesh file, output directory, restart file) are relative to its directory.
  static Deck from_parameters(const Teuchos::RCP<Teuchos::ParameterList>& pl, const std::string& file);
};

}  // namespace shellfrac::solver
