#pragma once
/// \file mesh_factory.hpp
/// The deck's "Mesh" sublist: where the mesh comes from (file or built-in generator), P2 promotion,
/// uniform refinement and the non-manifold edge policy.
#include <mpi.h>

#include <string>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::solver {

/// Validated "Mesh" sublist.
struct MeshParams {
  enum class Source { Rectangle, CylindricalPanel, Cylinder, File };
  Source source = Source::Rectangle;
  std::string file;  ///< resolved path (relative paths are relative to the deck's directory)
  std::string deck;  ///< the deck's path (for messages)
  int refinements = 0;
  mesh::NonManifoldPolicy non_manifold = mesh::NonManifoldPolicy::Star;
  mesh::DiagonalPattern pattern = mesh::DiagonalPattern::Right;
  std::string block_name = "shell";
  double length = 1, width = 1, radius = 1, angle_degrees = 90;
  int n_length = 1, n_width = 1;  ///< Rectangle: along length/width; panel, cylinder: axial/circumferential

  /// Valid parameters of the "Mesh" sublist (with its generator sublists).
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// Validates `pl` and converts it; deck_dir resolves relative file names.
  static MeshParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx, const std::string& deck_dir);
};

/// Builds the mesh on rank 0 (read or generate, promote TRI3 to TRI6, refine), checks it and broadcasts it
/// to every rank. Errors are InputErrors on every rank. Collective.
mesh::SerialMesh build_mesh(const MeshParams& params, MPI_Comm comm = MPI_COMM_WORLD);

}  // namespace shellfrac::solver
