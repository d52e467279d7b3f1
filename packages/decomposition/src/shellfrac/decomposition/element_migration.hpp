#pragma once
/// \file element_migration.hpp
/// From the pieces of a mesh the ranks hold (each a slice of the mesh file, say) to each rank's part of the
/// distributed mesh: the elements the partition gives it, their ghosts, their interfaces and boundary edges, sent
/// by the ranks that hold them. No rank sees more than its piece, its part and the parts of the ids of O(N / P)
/// elements it keeps as a directory (docs/parallel.md, "Distributed set-up").
#include <mpi.h>

#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"

namespace shellfrac::decomposition {

/// A side-set entry: local edge `local_edge` of element `element` is in side set `side_set` (an index into the
/// mesh's side sets).
struct SideEntry {
  GlobalId element = -1;
  int local_edge = -1, side_set = -1;
};

/// The elements one rank holds of a mesh whose elements are numbered 0..N-1 over all ranks.
struct ElementPiece {
  int nodes_per_element = 3;            ///< the same on every rank
  std::vector<GlobalId> elements;       ///< global ids, each on exactly one rank, any order
  std::vector<int> blocks;              ///< per element: its block index
  std::vector<GlobalId> nodes;          ///< per element: its nodes_per_element mesh node ids
  std::vector<Vec3> coords;             ///< their coordinates, in the same layout
  std::vector<SideEntry> side_entries;  ///< the side-set entries of these elements
  std::string source;                   ///< the mesh file, for messages
};

/// An element of a rank's overlap, with what the distributed mesh keeps of it.
struct MigratedElement {
  GlobalId gid = -1;
  int owner = -1, block = -1;
  GlobalId nodes[num_nodes_tri6] = {};
  Vec3 coords[num_nodes_tri6] = {};
  Vec3 directors[num_vertices_tri] = {};  ///< mesh::reference_vertex_normals at its vertices
  mesh::ElementEdge neighbor[num_vertices_tri];
};

struct MigratedInterface {
  GlobalId id = -1;
  mesh::Interface interface;
  int minus_owner = -1, plus_owner = -1;
};

struct MigratedBoundary {
  GlobalId id = -1;
  mesh::ElementEdge side;
  std::vector<int> side_sets;  ///< ascending, as mesh::EdgeTopology::boundary_side_sets
};

/// A rank's part of the distributed mesh.
struct MigratedPart {
  int nodes_per_element = 3;
  GlobalId num_global_elements = 0;
  LocalId num_owned = 0;
  std::vector<MigratedElement> elements;      ///< owned elements by ascending id, then the ghosts by ascending id
  std::vector<MigratedInterface> interfaces;  ///< every interface with a side owned here, by ascending id
  std::vector<MigratedBoundary> boundary;     ///< the boundary entries of the owned elements, by ascending id
};

/// Sends every element of `piece` (whose topology is `topo`, build_local_topology) to the rank part[i] that owns it
/// and to the ranks that hold it as a ghost, with its interfaces and boundary edges, and returns what comes here.
/// InputError on every rank for an element id given twice or out of range, or a part that is not a rank.
/// Collective.
MigratedPart migrate_elements(const ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part,
                              MPI_Comm comm);

}  // namespace shellfrac::decomposition
