#pragma once
/// \file distributed_mesh.hpp
/// The distributed DG element model (paper §4.3, §5; docs/parallel.md). Elements, not nodes, are
/// distributed. Each rank has
///  * owned elements: those the partition gives it, in ascending global id;
///  * an overlap list: owned elements first, then exactly one ghost layer (every element that shares an
///    interface with an owned element and is owned elsewhere), ghosts in ascending global id;
///  * the DG nodes of every overlap element (no node is shared: node a of element E has global DG node id
///    E * nodes_per_element + a), with reference coordinates and the original mesh node id;
///  * interfaces (paper's map P): every interface with at least one owned side is listed with the local
///    overlap ids of both sides; it is *owned* by exactly one rank, the lower of the two owners' ranks;
///  * boundary edges of owned elements with their side-set membership;
///  * Tpetra maps and the Imports (owned -> overlap, owned -> ghosts) of element rows, built
///    once (element_maps.hpp; kept out of this header because Tpetra headers are slow to compile).
/// Works on a rank that owns no element. Construction is collective.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}

namespace shellfrac::decomposition {

struct ElementMaps;    // element_maps.hpp
struct LocalTopology;  // distributed_topology.hpp

/// An interface seen from this rank: P(e) = (E-, ê-), (E+, ê+) with local overlap ids.
struct LocalInterface {
  GlobalId gid = -1;  ///< index into EdgeTopology::interfaces (rank-independent)
  LocalId minus = -1, plus = -1;  ///< local overlap ids of E- and E+
  int minus_edge = -1, plus_edge = -1;
  bool owned = false;  ///< this rank computes it (exactly one rank does)
  bool non_manifold = false;
};

/// A boundary edge of an owned element.
struct LocalBoundaryEdge {
  LocalId element = -1;  ///< local (owned) id
  int local_edge = -1;
  std::vector<int> side_sets;  ///< indices into SerialMesh::side_sets
};

/// Per-rank view of the distributed DG mesh.
class DistributedMesh {
 public:
  /// Builds this rank's part. mesh, topo and part must be identical on every rank. Collective.
  DistributedMesh(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, const std::vector<int>& part,
                  MPI_Comm comm = MPI_COMM_WORLD);
  /// Builds this rank's part from the pieces of the mesh the ranks hold (element_migration.hpp) and their topology
  /// (build_local_topology): part[i] is the rank that owns piece.elements[i]. No rank holds the whole mesh. The same
  /// view, bit for bit, as the constructor above given the whole mesh and the same partition. Collective.
  DistributedMesh(const mesh::ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part,
                  MPI_Comm comm = MPI_COMM_WORLD);
  ~DistributedMesh();
  DistributedMesh(const DistributedMesh&) = delete;
  DistributedMesh& operator=(const DistributedMesh&) = delete;

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int num_ranks() const { return num_ranks_; }
  int nodes_per_element() const { return npe_; }
  GlobalId num_global_elements() const { return num_global_elements_; }

  LocalId num_owned() const { return num_owned_; }
  LocalId num_overlap() const { return static_cast<LocalId>(element_gid_.size()); }
  LocalId num_ghosts() const { return num_overlap() - num_owned(); }

  /// Global id of overlap element le (owned first, then ghosts).
  GlobalId element_gid(LocalId le) const { return element_gid_[le]; }
  const std::vector<GlobalId>& element_gids() const { return element_gid_; }
  /// The id of overlap element le in the mesh file's element id map (mesh::FileIds), gid + 1 without one.
  std::int64_t element_file_id(LocalId le) const {
    return element_file_ids_.empty() ? element_gid_[le] + 1 : element_file_ids_[le];
  }
  /// Owning rank of overlap element le.
  int element_owner(LocalId le) const { return element_owner_[le]; }
  /// Block index (into SerialMesh::blocks) of overlap element le.
  int element_block(LocalId le) const { return element_block_[le]; }
  const std::vector<int>& element_blocks() const { return element_block_; }
  /// Reference coordinates of DG node a of overlap element le.
  const Vec3& node_coords(LocalId le, int a) const { return coords_[le * npe_ + a]; }
  /// The same for every overlap element at once: coordinate c of node a of element le at (le * npe + a) * 3 + c.
  const double* node_coords_data() const {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
    return coords_.empty() ? nullptr : coords_.front().data();
  }
  /// Original (conforming) mesh node of DG node a of overlap element le.
  GlobalId mesh_node(LocalId le, int a) const { return mesh_node_[le * npe_ + a]; }
  /// Global DG node id of node a of overlap element le.
  GlobalId dg_node_gid(LocalId le, int a) const { return element_gid_[le] * npe_ + a; }
  /// Reference director (theory.md §1.5: averaged unit normal at the mesh vertex) at vertex a (0..2) of le.
  const Vec3& reference_director(LocalId le, int a) const { return directors_[le * 3 + a]; }
  /// Replaces that reference director (a unit vector; the same on every copy of the vertex that the caller moves:
  /// solver/model/symmetry_directors.hpp).
  void set_reference_director(LocalId le, int a, const Vec3& t) { directors_[le * 3 + a] = t; }
  /// Neighbour across local edge k of overlap element le: local overlap id (-1 if none or not in overlap)
  /// and its local edge.
  LocalId neighbor(LocalId le, int k) const { return neighbor_[le * 3 + k]; }
  int neighbor_edge(LocalId le, int k) const { return neighbor_edge_[le * 3 + k]; }
  /// The same for every overlap element at once: entry le * 3 + k.
  const std::vector<LocalId>& neighbors() const { return neighbor_; }
  const std::vector<int>& neighbor_edges() const { return neighbor_edge_; }
  /// Local overlap id of a global element id, -1 if not in the overlap.
  LocalId local_id(GlobalId gid) const;

  /// Interfaces with at least one owned side, sorted by gid.
  const std::vector<LocalInterface>& interfaces() const { return interfaces_; }
  /// Boundary edges of owned elements.
  const std::vector<LocalBoundaryEdge>& boundary_edges() const { return boundary_; }

  /// The set entries of the overlap elements (owned and ghosts): the side-set entries of their edges, interior
  /// edges included, the node-set entries of their mesh nodes, their element-set entries (set indices into the
  /// mesh's sets; mesh/mesh_piece.hpp).
  const mesh::SetEntries& overlap_set_entries() const { return overlap_sets_; }

  /// Tpetra maps and Imports (include shellfrac/decomposition/element_maps.hpp to use).
  const ElementMaps& maps() const { return *maps_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0, num_ranks_ = 1, npe_ = 3;
  GlobalId num_global_elements_ = 0;
  LocalId num_owned_ = 0;
  std::vector<GlobalId> element_gid_;
  std::vector<std::int64_t> element_file_ids_;  ///< empty: the file numbers its elements by position
  std::vector<int> element_owner_, element_block_;
  std::vector<Vec3> coords_, directors_;
  std::vector<GlobalId> mesh_node_;
  std::vector<LocalId> neighbor_;
  std::vector<int> neighbor_edge_;
  std::vector<LocalInterface> interfaces_;
  std::vector<LocalBoundaryEdge> boundary_;
  mesh::SetEntries overlap_sets_;
  std::unique_ptr<ElementMaps> maps_;
};

}  // namespace shellfrac::decomposition
