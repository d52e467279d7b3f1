#pragma once
/// \file model_setup.hpp
/// From a validated deck to the distributed model of a run, before any output exists: the mesh (read or
/// generated on rank 0, then broadcast), every check of the deck against the mesh, the edge topology, the
/// partition, the distributed mesh and the dynamics. The run, the benchmark and the tests build their models
/// here, so they are the same model.
#include <mpi.h>

#include <memory>
#include <string>

#include "shellfrac/core/types.hpp"
#include <utility>
#include <vector>

namespace shellfrac::mesh {
struct SerialMesh;
struct EdgeTopology;
}  // namespace shellfrac::mesh
namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

struct Deck;
class ShellDynamics;

/// The sizes of the conforming mesh and of its edge topology, kept for the run's summary.
struct MeshCounts {
  GlobalId elements = 0, nodes = 0, edges = 0, interfaces = 0, boundary_edges = 0, non_manifold_edges = 0;
};

struct RunModel {
  RunModel();
  RunModel(RunModel&&) noexcept;
  RunModel& operator=(RunModel&&) noexcept;
  ~RunModel();
  /// The whole conforming mesh, the same on every rank: set-up only (release_global_mesh). Its edge topology
  /// serves the partition and the distribution only, and is gone once the distributed mesh is built.
  std::unique_ptr<mesh::SerialMesh> mesh;
  MeshCounts counts;
  /// The mesh's element blocks (names and Exodus ids, by block index): kept after the mesh is released.
  std::vector<std::string> block_names;
  std::vector<int> block_ids;
  std::unique_ptr<decomposition::DistributedMesh> distributed;
  std::unique_ptr<ShellDynamics> dynamics;
  std::vector<std::string> warnings;  ///< model_warnings(), for the program to print (rank 0)
  /// Wall time of each set-up phase (mesh, topology, partition, distribution, model) on the slowest rank [s].
  std::vector<std::pair<std::string, double>> setup_seconds;
  /// Frees the conforming mesh once the set-up has taken from it what the run needs: a rank then holds only its
  /// part of the mesh (its elements and their ghosts, in `distributed`).
  void release_global_mesh();
};

/// Builds the model of `deck` on `comm`. InputError (on every rank) for any problem. Collective.
RunModel build_run_model(const Deck& deck, MPI_Comm comm);

/// The checks of the deck against the mesh that belong to no single condition: every mesh block has a section
/// and every section names a block of the mesh; block names fit Exodus. (Set names are checked where they are
/// resolved, mesh_sets.hpp.)
void check_deck_against_mesh(const Deck& deck, const mesh::SerialMesh& mesh);
/// What is valid but probably not meant, one sentence each: separate mesh nodes at one point (a seam, or
/// duplicate nodes from a mesher).
std::vector<std::string> mesh_warnings(const mesh::SerialMesh& mesh);
/// The same of the model: a time step so large that no step is taken before End Time.
std::vector<std::string> model_warnings(const Deck& deck, const RunModel& model);
/// Neighbouring elements must have consistent orientations (normals), except across non-manifold edges.
void check_orientation(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topology);

}  // namespace shellfrac::solver
