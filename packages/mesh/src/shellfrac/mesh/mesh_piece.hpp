#pragma once
/// \file mesh_piece.hpp
/// A mesh held in pieces: each rank holds some of its elements, with their nodes, coordinates and set entries,
/// and every rank knows the mesh's outline (counts, blocks, the names of its sets). No rank holds the whole mesh
/// (docs/parallel.md, "Distributed set-up"). A piece comes from a mesh file read by ranges
/// (meshio::read_exodus_piece) or from a whole mesh (element_range_piece); decomposition::migrate_elements makes
/// the distributed mesh of it.
#include <cstdint>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::mesh {

/// A side-set entry: local edge `local_edge` of element `element` is in side set `side_set` (an index into the
/// mesh's side sets).
struct SideEntry {
  GlobalId element = -1;
  int local_edge = -1, side_set = -1;
};

/// A node-set or element-set entry: `member` (a node or an element id) is in set `set` (an index into the mesh's
/// node or element sets).
struct SetEntry {
  GlobalId member = -1;
  int set = -1;
};

/// A set's name and id, as NodeSet, SideSet and ElementSet have them.
struct SetLabel {
  std::string name;
  int id = 0;
};

/// What every rank knows of a mesh held in pieces: O(blocks + sets), the same on every rank.
struct MeshOutline {
  int nodes_per_element = 3;
  GlobalId num_elements = 0, num_nodes = 0;
  std::vector<ElementBlock> blocks;
  std::vector<SetLabel> node_sets, side_sets, element_sets;
  std::string source;  ///< the mesh file or generator, for messages
};

/// The elements one rank holds of a mesh whose elements are numbered 0..N-1 over all ranks.
struct ElementPiece {
  int nodes_per_element = 3;            ///< the same on every rank
  std::vector<GlobalId> elements;       ///< global ids, each on exactly one rank, any order
  std::vector<int> blocks;              ///< per element: its block index
  std::vector<GlobalId> nodes;          ///< per element: its nodes_per_element mesh node ids
  std::vector<Vec3> coords;             ///< their coordinates, in the same layout
  std::vector<SideEntry> side_entries;  ///< the side-set entries of these elements, by (element, edge, set)
  /// The node-set entries of the nodes of these elements, and the element-set entries of these elements, by
  /// (member, set), each once.
  std::vector<SetEntry> node_set_entries, element_set_entries;
  /// Per element: its id in the mesh file's element id map (FileIds); empty when the file numbers its elements by
  /// position (empty on every rank then).
  std::vector<std::int64_t> element_file_ids;
  std::string source;  ///< the mesh file, for messages
};

/// The set entries of some elements of a mesh, sorted as ElementPiece keeps them: the side-set entries of their
/// edges, the node-set entries of their nodes, their element-set entries.
struct SetEntries {
  std::vector<SideEntry> side_entries;
  std::vector<SetEntry> node_set_entries, element_set_entries;
};

/// A mesh read in pieces: the outline every rank has and this rank's piece.
struct MeshPiece {
  MeshOutline outline;
  ElementPiece piece;
};

/// The outline of a whole mesh.
MeshOutline outline_of(const SerialMesh& mesh);

/// The piece of `mesh` made of its elements [first, end), with their set entries in the order ElementPiece
/// gives: what a rank holds when it reads that element range of the mesh's file.
ElementPiece element_range_piece(const SerialMesh& mesh, GlobalId first, GlobalId end);
/// The piece of `mesh` made of `elements` (global ids, in that order).
ElementPiece piece_of_elements(const SerialMesh& mesh, const std::vector<GlobalId>& elements);
/// The set entries of `elements` (global ids) of `mesh`.
SetEntries set_entries_of(const SerialMesh& mesh, const std::vector<GlobalId>& elements);

/// check_mesh's element checks on the elements of `piece` (nodes below num_nodes and distinct, vertices not
/// collinear), naming elements as check_mesh does and nodes by their positions + 1. InputError naming
/// piece.source.
void check_piece_elements(const ElementPiece& piece, GlobalId num_nodes);

/// Sorts entries by (member, set) and removes repeats; side entries by (element, local edge, set), repeats kept
/// as a side set keeps them.
void sort_set_entries(std::vector<SetEntry>& entries);
void sort_side_entries(std::vector<SideEntry>& entries);

}  // namespace shellfrac::mesh
