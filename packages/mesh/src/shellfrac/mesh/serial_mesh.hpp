#pragma once
/// \file serial_mesh.hpp
/// The conforming input mesh, as read from a file or made by a generator, held whole on every rank before
/// distribution. Nodes are shared between elements here; the DG duplication of nodes (theory.md §1.1) is
/// done when the mesh is distributed (distributed_mesh.hpp). All indices are 0-based.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh {

/// A named set of mesh nodes (e.g. a clamped edge). Indices into SerialMesh::coords, sorted, unique.
struct NodeSet {
  std::string name;
  int id = 0;  ///< Exodus id (positive, unique among node sets)
  std::vector<GlobalId> nodes;
};

/// A named set of element edges (Exodus side set / Gmsh line group). local_edges[i] in {0,1,2}
/// is the local edge of elements[i] (edge k joins vertices edge_vertex[k][0], edge_vertex[k][1]).
struct SideSet {
  std::string name;
  int id = 0;
  std::vector<GlobalId> elements;
  std::vector<int> local_edges;
};

/// A named set of elements (e.g. the loaded patch). Sorted, unique.
struct ElementSet {
  std::string name;
  int id = 0;
  std::vector<GlobalId> elements;
};

/// An element block: elements with one thickness and one material (assigned from the deck by name).
struct ElementBlock {
  std::string name;
  int id = 0;  ///< Exodus block id (positive, unique)
};

/// The exact surface a generator meshed, so that new nodes (P2 promotion, refinement) land on it.
struct ExactSurface {
  enum class Kind { None, Cylinder };
  Kind kind = Kind::None;
  Vec3 axis_point{0, 0, 0};     ///< a point on the cylinder axis
  Vec3 axis_direction{0, 0, 1};  ///< unit axis direction
  double radius = 0;
  /// Closest point of the surface to x (identity for Kind::None).
  Vec3 project(const Vec3& x) const;
};

/// The ids a mesh file gives its elements or its nodes (Exodus id maps), by shellfrac's number (the 0-based
/// position in the file, which is the global id). Empty when they are the positions 1..n: generated meshes, Gmsh
/// files, Exodus files without a map or with the identity map, and after a uniform refinement (new entities).
/// shellfrac numbers results and tables by position (the results' element id is global id + 1); messages name
/// an element or node by the file's id, and an element also by its number in the results when the two differ.
struct FileIds {
  std::vector<std::int64_t> ids;
  bool empty() const { return ids.empty(); }
  /// "element 1001 (7 in the results)", or "element 7" when the file numbers by position.
  std::string element(GlobalId e) const;
  /// "node 2001"; "node 57" without ids; a node added by shellfrac (a mid-side node of a TRI3 file promoted to
  /// TRI6) has no id in the file: "mid-side node 57 (added by shellfrac)".
  std::string node(GlobalId n) const;
};

/// "element 1001 (7 in the results)" for element global id e whose id in the mesh file is file_id; "element 7"
/// when file_id is e + 1.
std::string element_label(GlobalId e, std::int64_t file_id);

/// Conforming triangle mesh: TRI3 (nodes_per_element = 3) or TRI6 (6; node order of types.hpp).
struct SerialMesh {
  int nodes_per_element = 3;
  std::vector<Vec3> coords;                 ///< node coordinates
  std::vector<GlobalId> connectivity;       ///< num_elements() * nodes_per_element node indices
  std::vector<int> element_block;           ///< per element: index into blocks
  std::vector<ElementBlock> blocks;
  std::vector<NodeSet> node_sets;
  std::vector<SideSet> side_sets;
  std::vector<ElementSet> element_sets;
  ExactSurface surface;
  std::string source;  ///< file name or generator description, for messages
  FileIds element_ids, node_ids;  ///< the file's own ids, for messages (empty: the positions)

  GlobalId num_elements() const { return static_cast<GlobalId>(element_block.size()); }
  GlobalId num_nodes() const { return static_cast<GlobalId>(coords.size()); }
  /// Node a (0-based, < nodes_per_element) of element e.
  GlobalId node(GlobalId e, int a) const { return connectivity[e * nodes_per_element + a]; }
};

/// Checks the invariants above (sizes, index ranges, unique positive ids, unique names, set contents,
/// no degenerate triangle (repeated vertex or zero area)). Throws InputError naming mesh.source and the
/// offending element/node/set.
void check_mesh(const SerialMesh& mesh);

/// check_mesh's check of the blocks or the sets of one kind, given as (id, name): ids positive and unique, names
/// not empty, printable and unique. InputError naming `source` and `kind` ("element block", "node set", ...).
void check_ids_and_names(const std::vector<std::pair<int, std::string>>& ids_and_names, const char* kind,
                         const std::string& source);

/// check_mesh's checks of element e, whose id in the mesh file is element_file_id (e + 1 without an id map) and
/// whose nodes are `nodes` (nodes_per_element of them): each below num_nodes and none twice. InputError naming
/// `source`, the element (element_label) and the node (node_ids).
void check_element_nodes(GlobalId e, std::int64_t element_file_id, const GlobalId* nodes, int nodes_per_element,
                         GlobalId num_nodes, const FileIds& node_ids, const std::string& source);
/// check_mesh's check of element e whose vertices are at a, b, c: not collinear. InputError as above.
void check_element_area(GlobalId e, std::int64_t element_file_id, const Vec3& a, const Vec3& b, const Vec3& c,
                        const std::string& source);

/// Serializes the mesh for a broadcast.
std::vector<char> pack(const SerialMesh& mesh);
/// Inverse of pack().
SerialMesh unpack(const std::vector<char>& buffer);
/// Broadcasts the mesh from root to every rank of comm. Collective.
void broadcast(SerialMesh& mesh, int root = 0, MPI_Comm comm = MPI_COMM_WORLD);

/// Promotes a TRI3 mesh to TRI6: one new node per unique edge at its midpoint, projected on mesh.surface.
/// Sets: side sets and element sets are unchanged; a new node joins a node set when both end vertices of
/// its edge are members and the edge is on the boundary, or is interior with no adjacent triangle whose
/// third vertex is also a member (so node sets describing lines keep their mid-side nodes, while the
/// diagonal of a corner triangle does not join a boundary set). The new nodes have no id of the file
/// (FileIds::node). No-op for a TRI6 mesh.
void promote_to_p2(SerialMesh& mesh);

/// Uniform refinement: each triangle -> 4 (corner children 0,1,2 at vertices 1,2,3, then the centre one).
/// The children are new elements: the file's ids are dropped (positions from then on).
/// TRI6 children take their new mid-side nodes on the parent's P2 map (then projected on mesh.surface);
/// TRI3 children take the projected edge midpoints. Blocks, element sets, side sets (each edge -> its two
/// halves) and node sets (rule of promote_to_p2) follow.
void refine_uniform(SerialMesh& mesh);

/// Signed area of element e using its vertices only (flat-triangle area), for checks and statistics.
double vertex_area(const SerialMesh& mesh, GlobalId e);

}  // namespace shellfrac::mesh
