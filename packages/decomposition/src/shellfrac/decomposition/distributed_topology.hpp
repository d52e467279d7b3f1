#pragma once
/// \file distributed_topology.hpp
/// The edge topology (mesh/edge_topology.hpp) and the reference directors (mesh::reference_vertex_normals) of a
/// mesh whose elements are spread over the ranks, each rank holding some of them: no rank sees the whole mesh.
/// Every id and every bit is the one the serial functions give on the whole mesh, whatever the ranks and
/// however the elements are spread (docs/parallel.md, "Distributed set-up").
///
/// How: each use of an edge (element, local edge) goes to the rank that holds its lower vertex's share of the node
/// ids (rank q holds the ids [q B, (q + 1) B), B = ceil(num_nodes / P)); that rank sorts the uses as the serial
/// code does, so the ranks' edges follow each other in the serial order and an exclusive scan of their counts gives
/// the global edge, interface and boundary ids; the answers go back to the ranks that asked. A vertex normal is
/// summed the same way, at the rank of the node's share, in element order.
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/mesh/edge_topology.hpp"

namespace shellfrac::decomposition {

/// The edge topology of the whole mesh as far as it concerns this rank's elements, with the whole mesh's ids.
struct LocalTopology {
  /// Per element of this rank (in the order given), as mesh::EdgeTopology::element_edges, element_interface and
  /// neighbor of that element (element ids are global).
  std::vector<std::array<GlobalId, 3>> element_edges;
  std::vector<std::array<GlobalId, 3>> element_interface;
  std::vector<std::array<mesh::ElementEdge, 3>> neighbor;
  /// Every interface with a side among this rank's elements, by ascending id (interface_ids[i] is the index of
  /// interfaces[i] in EdgeTopology::interfaces).
  std::vector<GlobalId> interface_ids;
  std::vector<mesh::Interface> interfaces;
  /// The boundary entries of this rank's elements, in the order of EdgeTopology::boundary (boundary_ids[i]: the
  /// index of boundary[i] there).
  std::vector<GlobalId> boundary_ids;
  std::vector<mesh::ElementEdge> boundary;
  /// Of the whole mesh.
  GlobalId num_edges = 0, num_interfaces = 0, num_boundary = 0, num_non_manifold_edges = 0;
};

/// The topology of the mesh whose elements `elements` (global ids, each on exactly one rank, in any order) have the
/// vertex node ids `vertices` (first three nodes, global ids) on this rank. `policy` as for
/// mesh::build_edge_topology; with Error an edge of 3+ elements is an InputError on every rank naming `source`,
/// the edge's nodes and its elements (by their numbers in the results: position + 1). Collective.
LocalTopology build_local_topology(const std::vector<GlobalId>& elements,
                                   const std::vector<std::array<GlobalId, 3>>& vertices, mesh::NonManifoldPolicy policy,
                                   const std::string& source, MPI_Comm comm);

/// mesh::reference_vertex_normals at the three vertices of each element of this rank: entry 3 i + a is the
/// normal at vertex a of elements[i]. `nodes` has nodes_per_element global node ids per element and `coords`
/// their coordinates (same layout). Bitwise the serial values. A zero Jacobian is an InputError on every rank
/// naming `source`. Collective.
std::vector<Vec3> local_vertex_normals(const std::vector<GlobalId>& elements, int nodes_per_element,
                                       const std::vector<GlobalId>& nodes, const std::vector<Vec3>& coords,
                                       const std::string& source, MPI_Comm comm);

}  // namespace shellfrac::decomposition
