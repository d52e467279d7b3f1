#pragma once
/// \file exodus_outline.hpp
/// What both Exodus mesh readers (the whole mesh, exodus_mesh_io.hpp; a rank's piece, exodus_piece_reader.hpp)
/// read first: the header, the element blocks' types and sizes, the sets' ids, names and sizes, each checked
/// against the header's counts and, for a netCDF classic file, against the file's size before anything is
/// allocated from them. Internal to shellfrac::meshio.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/exodus/exodus_api.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"

namespace shellfrac::meshio::detail {

/// An element block of the file.
struct ExodusBlock {
  std::int64_t id = 0;
  std::string name;  ///< the file's name, or "block_<id>"
  std::string what;  ///< "element block 3 ('skin')", for messages
  std::int64_t count = 0;
  GlobalId first = 0;  ///< the number (0-based, in file order) of its first element
  bool shell = false;  ///< TRISHELL: sides 3, 4, 5 are the edges
};

/// A node, side or element set of the file.
struct ExodusSet {
  std::int64_t id = 0;
  std::string name, what;
  std::int64_t count = 0;  ///< entries
};

struct ExodusOutline {
  int num_dim = 3;
  std::int64_t num_nodes = 0, num_elements = 0;
  int nodes_per_element = 0;
  std::vector<ExodusBlock> blocks;
  std::vector<ExodusSet> node_sets, side_sets, element_sets;
  std::uint64_t stored_bytes = 0;  ///< bound on stored data (the file size) for a classic file, else 0

  /// The block of element e (0-based number in the file).
  const ExodusBlock& block_of(GlobalId e) const;
};

/// Checks the file (netCDF classic header, Exodus structure: exodus_file_checks.hpp) and opens it read-only;
/// sets `stored_bytes`. InputError naming `path` for a missing, unreadable or malformed file.
exodus::File open_checked_exodus(const std::string& path, std::uint64_t& stored_bytes);

/// Reads and checks the outline of the open file `exo_id`.
ExodusOutline read_exodus_outline(int exo_id, const std::string& path, std::uint64_t stored_bytes);

/// File node number `value` (1-based) of entry k of block `b`'s connectivity as a 0-based node id; InputError
/// naming the block and the element when it is not a node of the file.
GlobalId checked_node(std::int64_t value, std::int64_t k, int nodes_per_element, const ExodusBlock& b,
                      std::int64_t num_nodes, const std::string& path);

/// 1-based file index `value` of an entry of set `what` as a 0-based index below n; InputError otherwise.
GlobalId checked_index(std::int64_t value, std::int64_t n, const std::string& path, const std::string& what,
                       const char* entity);

/// The local edge (0, 1, 2) of side `side` of file element e (1-based) in side set `what`; InputError for an
/// element out of range, a shell face or a side number out of range.
int local_edge_of_side(const ExodusOutline& o, std::int64_t e, std::int64_t side, const std::string& path,
                       const std::string& what);

/// The entries (1-based file values) of set `set` of `type`, and for a side set its side numbers in `extra`.
void read_set(int exo_id, ex_entity_type type, const ExodusSet& set, std::vector<std::int64_t>& entries,
              std::vector<std::int64_t>* extra, const std::string& path);

/// The mesh outline of the file's outline: counts, blocks, set names and ids (checked as check_mesh checks them).
mesh::MeshOutline mesh_outline_of(const ExodusOutline& o, const std::string& path);

/// Opens `path` (open_checked_exodus), reads its outline and runs read(exo_id, outline); the file is closed after.
/// An allocation failure (a header that declares more than fits in memory) is an InputError naming `path`.
void read_exodus_file(const std::string& path, const std::function<void(int, ExodusOutline&)>& read);

}  // namespace shellfrac::meshio::detail
