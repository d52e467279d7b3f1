#pragma once
/// \file restart_fingerprint.hpp
/// What a checkpoint must share with the deck that restarts from it (docs/output.md, "Restart"): the mesh
/// (a digest of every element's global id, block, mesh nodes and reference coordinates, and one of the mesh's node,
/// side and element sets: names, ids and members) and the physics (every
/// parameter that changes the equations or the discretization, as "path = value" lines). Free to change on a
/// restart: End Time, Output Interval, History Interval, Time Step, Safety Factor, Force Time Step, Relaxation
/// Tolerance, the mesh file's path and the Output, Checkpoint, Partitioning and Initial Conditions sublists.
#include <string>

#include "shellfrac/io/checkpoint.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}
namespace shellfrac::mesh {
struct SerialMesh;
}

namespace shellfrac::solver {

struct Deck;

struct RestartFingerprint {
  std::string mesh;     ///< Digest::hex of the mesh, the same on any number of ranks
  std::string physics;  ///< sorted "path = value" lines of the physics parameters (the Regions sublist included)
  std::string sets;     ///< Digest::hex of the mesh's node, side and element sets

  /// The fingerprint of a deck, its distributed mesh and the whole mesh (for its sets). Collective.
  static RestartFingerprint of(const Deck& deck, const decomposition::DistributedMesh& dm,
                               const mesh::SerialMesh& whole);
  /// Stores it in a checkpoint's strings.
  void stamp(io::CheckpointData& data) const;
  /// InputError naming `file` unless the checkpoint was written for this mesh and its sets and (unless
  /// `allow_physics_change`) this physics; the message lists the parameters that differ.
  void check(const io::CheckpointData& data, const std::string& file, bool allow_physics_change) const;
  /// The physics parameters in which this deck differs from the run that wrote the checkpoint, as a message ("" if
  /// none, or if the checkpoint records no physics). A parameter added since the checkpoint was written counts
  /// only if it is not at its default (or belongs to a new entry: a new material, a new wall).
  std::string physics_differences(const io::CheckpointData& data) const;
};

}  // namespace shellfrac::solver
