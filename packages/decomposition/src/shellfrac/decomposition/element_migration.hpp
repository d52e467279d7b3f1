#pragma once
/// \file element_migration.hpp
/// From the pieces of a mesh the ranks hold (each a slice of the mesh file, say) to each rank's part of the
/// distributed mesh: the elements the partition gives it, their ghosts, their interfaces and boundary edges, sent
/// by the ranks that hold them. No rank sees more than its piece, its part and the parts of the ids of O(N / P)
/// elements it keeps as a directory (docs/parallel.md, "Distributed set-up").
#include <mpi.h>

#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"

namespace shellfrac::decomposition {

using mesh::ElementPiece;
using mesh::SideEntry;

/// An element of a rank's overlap, with what the distributed mesh keeps of it.
struct MigratedElement {
  GlobalId gid = -1;
  std::int64_t file_id = 0;  ///< its id in the mesh file's element id map, 0 without one
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
  mesh::SetEntries sets;                      ///< the set entries of all the elements above (owned and ghosts)
};

/// Sends every element of `piece` (whose topology is `topo`, build_local_topology) to the rank part[i] that owns it
/// and to the ranks that hold it as a ghost, with its interfaces and boundary edges, and returns what comes here.
/// InputError on every rank for an element id given twice or out of range, or a part that is not a rank.
/// Collective.
MigratedPart migrate_elements(const ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part,
                              MPI_Comm comm);

}  // namespace shellfrac::decomposition
