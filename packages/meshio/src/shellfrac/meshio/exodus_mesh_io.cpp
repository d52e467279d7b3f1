#include "shellfrac/meshio/exodus_mesh_io.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <new>
#include <numeric>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/exodus/exodus_api.hpp"
#include "shellfrac/meshio/exodus_file_checks.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"

namespace shellfrac::meshio {


namespace {

/// Largest entity count accepted from a file before allocating (a hostile header must not exhaust memory).
constexpr std::int64_t max_count = std::int64_t{1} << 31;

/// Nodes per element implied by an Exodus triangle type name, 0 if the type is not a supported triangle,
/// -1 if the name does not fix it (TRI, TRIANGLE, TRISHELL). Sets `shell`.
int triangle_type_nodes(const std::string& type, bool& shell) {
  const std::string t = exodus::upper(type);
  shell = t.rfind("TRISHELL", 0) == 0;
  if (t == "TRI3" || t == "TRISHELL3" || t == "TRIANGLE3") return 3;
  if (t == "TRI6" || t == "TRISHELL6" || t == "TRIANGLE6") return 6;
  if (t == "TRI" || t == "TRIANGLE" || t == "TRISHELL") return -1;
  return 0;
}

/// Reads an entity count header value and checks it is sane.
std::int64_t checked_count(std::int64_t n, const std::string& path, const char* what) {
  SHELLFRAC_INPUT_REQUIRE(n >= 0 && n < max_count, path << ": invalid " << what << " count " << n);
  return n;
}

/// In a netCDF classic file (no compression) every declared entity is stored: n entities of at least
/// `bytes_each` bytes must fit in the file's `file_bytes` (0 = no such bound: netCDF-4 / HDF5 file). Guards
/// the allocations sized by header values against a hostile header.
void check_stored(std::int64_t n, std::uint64_t bytes_each, std::uint64_t file_bytes, const std::string& path,
                  const std::string& what) {
  SHELLFRAC_INPUT_REQUIRE(file_bytes == 0 || static_cast<std::uint64_t>(n) <= file_bytes / bytes_each,
                          path << ": the file declares " << n << " " << what << ", more than its " << file_bytes
                               << " bytes can hold (truncated or corrupt file)");
}

/// Exodus entity id -> SerialMesh id (positive int).
int checked_id(std::int64_t id, const std::string& path, const char* what) {
  SHELLFRAC_INPUT_REQUIRE(id > 0 && id <= exodus::max_stored_int,
                          path << ": " << what << " has id " << id << "; ids must be positive 32-bit integers");
  return static_cast<int>(id);
}

std::string default_name(const std::string& name, const char* prefix, std::int64_t id) {
  return name.empty() ? std::string(prefix) + "_" + std::to_string(id) : name;
}

/// Ids of all entities of `type` (count from the header).
std::vector<std::int64_t> get_ids(int exo_id, ex_entity_type type, std::int64_t count, const std::string& path,
                                  const char* what) {
  std::vector<std::int64_t> ids(static_cast<std::size_t>(count));
  if (count > 0) SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(exo_id, type, ids.data()), path << ": cannot read " << what << " ids");
  return ids;
}

/// Reads one set's entries (and extra list for side sets) as 1-based file values.
void get_set(int exo_id, ex_entity_type type, std::int64_t id, std::vector<std::int64_t>& entries,
             std::vector<std::int64_t>* extra, const std::string& path, const std::string& what,
             std::uint64_t file_bytes) {
  std::int64_t n = 0, ndf = 0;
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_set_param(exo_id, type, id, &n, &ndf), path << ": cannot read " << what);
  checked_count(n, path, what.c_str());
  check_stored(n, extra ? 8 : 4, file_bytes, path, "entries in " + what);
  entries.assign(static_cast<std::size_t>(n), 0);
  if (extra) extra->assign(static_cast<std::size_t>(n), 0);
  if (n > 0)
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_set(exo_id, type, id, entries.data(), extra ? extra->data() : nullptr),
                              path << ": cannot read the entries of " << what);
}

/// 1-based file indices -> sorted, unique 0-based indices; each must be in [1, n].
std::vector<GlobalId> to_sorted_indices(const std::vector<std::int64_t>& v, std::int64_t n, const std::string& path,
                                        const std::string& what, const char* entity) {
  std::vector<GlobalId> out;
  out.reserve(v.size());
  for (auto x : v) {
    SHELLFRAC_INPUT_REQUIRE(x >= 1 && x <= n, path << ": " << what << " refers to " << entity << " " << x
                                                   << ", but the file has " << n << " " << entity << "s");
    out.push_back(x - 1);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Reads one Exodus shell mesh: the header, the id maps, the coordinates, the element blocks and the sets, each
/// checked against the header's counts (and, for a netCDF classic file, against the file's size) before use.
class ExodusMeshReader {
 public:
  explicit ExodusMeshReader(const std::string& path) : path_(path) {}

  mesh::SerialMesh read() {
    std::error_code ec;
    SHELLFRAC_INPUT_REQUIRE(std::filesystem::is_regular_file(path_, ec), path_ << ": Exodus file not found");
    const std::uintmax_t file_size = std::filesystem::file_size(path_, ec);
    SHELLFRAC_INPUT_REQUIRE(!ec, path_ << ": cannot read the file size (" << ec.message() << ")");
    // Upper bound for counts read from the header (0 = none: netCDF-4 files may be compressed).
    stored_bytes_ = check_netcdf_classic_header(path_, file_size) ? file_size : 0;
    check_exodus_structure(path_);
    exodus::File file = exodus::open_read(path_);
    SHELLFRAC_INPUT_REQUIRE(file.is_open(),
                            path_ << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
    id_ = file.id();
    read_header();
    m_.source = path_;
    read_id_maps();
    read_coordinates();
    read_blocks();
    read_node_sets();
    read_side_sets();
    read_element_sets();
    return std::move(m_);
  }

 private:
  void read_header() {
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_ext(id_, &p_), path_ << ": cannot read the Exodus header");
    SHELLFRAC_INPUT_REQUIRE(p_.num_dim == 2 || p_.num_dim == 3,
                            path_ << ": " << p_.num_dim << "-dimensional coordinates; a shell mesh needs 2 or 3");
    num_nodes_ = checked_count(p_.num_nodes, path_, "node");
    num_elem_ = checked_count(p_.num_elem, path_, "element");
    checked_count(p_.num_elem_blk, path_, "element block");
    checked_count(p_.num_node_sets, path_, "node set");
    checked_count(p_.num_side_sets, path_, "side set");
    checked_count(p_.num_elem_sets, path_, "element set");
    SHELLFRAC_INPUT_REQUIRE(num_elem_ > 0 && p_.num_elem_blk > 0, path_ << ": the file has no elements");
    check_stored(num_nodes_, 4 * static_cast<std::uint64_t>(p_.num_dim), stored_bytes_, path_, "nodes");
    check_stored(num_elem_, 3 * 4, stored_bytes_, path_, "elements");
    check_stored(p_.num_elem_blk, 4, stored_bytes_, path_, "element blocks");
    check_stored(p_.num_node_sets, 4, stored_bytes_, path_, "node sets");
    check_stored(p_.num_side_sets, 4, stored_bytes_, path_, "side sets");
    check_stored(p_.num_elem_sets, 4, stored_bytes_, path_, "element sets");
  }

  /// The file's element and node ids (its id maps; 1..n without them). shellfrac numbers elements and nodes by
  /// their position in the file, so two entities with one id would be two things under one name: refused.
  /// Messages name them by these ids (mesh::FileIds), kept when they are not the positions.
  void read_id_maps() {
    read_id_map(EX_ELEM_MAP, num_elem_, "element", m_.element_ids);
    read_id_map(EX_NODE_MAP, num_nodes_, "node", m_.node_ids);
  }

  void read_id_map(ex_entity_type type, std::int64_t count, const char* what, mesh::FileIds& file_ids) {
    std::vector<std::int64_t> ids(static_cast<std::size_t>(count));
    if (count > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id_, type, ids.data()), path_ << ": cannot read the " << what << " id map");
    std::vector<std::pair<std::int64_t, std::size_t>> sorted;
    sorted.reserve(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(ids[i] > 0, path_ << ": " << what << " " << i + 1 << " has the id " << ids[i]
                                                << " in the file's " << what << " id map; ids must be positive");
      sorted.emplace_back(ids[i], i);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
      SHELLFRAC_INPUT_REQUIRE(sorted[k].first != sorted[k - 1].first,
                              path_ << ": the " << what << " id " << sorted[k].first << " is given to " << what
                                    << "s " << sorted[k - 1].second + 1 << " and " << sorted[k].second + 1
                                    << " (positions in the file) by its " << what << " id map; ids must be unique");
    bool positions = true;
    for (std::size_t i = 0; i < ids.size() && positions; ++i) positions = ids[i] == static_cast<std::int64_t>(i) + 1;
    if (!positions) file_ids.ids = std::move(ids);
  }

  void read_coordinates() {
    std::vector<double> x(static_cast<std::size_t>(num_nodes_)), y(x.size()), z(x.size(), 0.0);
    if (num_nodes_ > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id_, x.data(), y.data(), p_.num_dim == 3 ? z.data() : nullptr),
                                path_ << ": cannot read the node coordinates");
    m_.coords.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) m_.coords[i] = {x[i], y[i], z[i]};
  }

  /// Element blocks, in file order; elements are numbered in that order.
  void read_blocks() {
    const auto block_ids = get_ids(id_, EX_ELEM_BLOCK, p_.num_elem_blk, path_, "element block");
    const auto block_names = exodus::get_names(id_, EX_ELEM_BLOCK, p_.num_elem_blk, path_);
    m_.nodes_per_element = 0;
    for (std::size_t b = 0; b < block_ids.size(); ++b)
      read_block(block_ids[b], default_name(block_names[b], "block", block_ids[b]));
    SHELLFRAC_INPUT_REQUIRE(total_ == num_elem_, path_ << ": the element blocks hold " << total_
                                                       << " elements but the header says " << num_elem_);
  }

  void read_block(std::int64_t block_id, const std::string& name) {
    const std::string what = "element block " + std::to_string(block_id) + " ('" + name + "')";
    ex_block blk{};
    blk.id = block_id;
    blk.type = EX_ELEM_BLOCK;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_block_param(id_, &blk), path_ << ": cannot read " << what);
    blk.topology[MAX_STR_LENGTH] = '\0';
    const std::string type = blk.topology;
    checked_count(blk.num_entry, path_, what.c_str());
    check_stored(blk.num_entry, 3 * 4, stored_bytes_, path_, "elements in " + what);
    bool shell = false;
    int npe = triangle_type_nodes(type, shell);
    const int block_index = static_cast<int>(m_.blocks.size());
    m_.blocks.push_back({name, checked_id(block_id, path_, what.c_str())});
    if (blk.num_entry == 0) return;  // Exodus stores empty blocks with type "NULL" and 0 nodes per element
    if (npe == -1 && (blk.num_nodes_per_entry == 3 || blk.num_nodes_per_entry == 6))
      npe = static_cast<int>(blk.num_nodes_per_entry);
    SHELLFRAC_INPUT_REQUIRE(npe > 0 && npe == blk.num_nodes_per_entry,
                            path_ << ": " << what << " has unsupported element type '" << type << "' with "
                                  << blk.num_nodes_per_entry
                                  << " nodes per element; shell meshes need TRI3/TRISHELL3 or TRI6/TRISHELL6");
    if (m_.nodes_per_element == 0) {
      m_.nodes_per_element = npe;
      first_block_with_elements_ = block_id;
    }
    SHELLFRAC_INPUT_REQUIRE(npe == m_.nodes_per_element,
                            path_ << ": " << what << " has " << npe << "-node elements but element block "
                                  << first_block_with_elements_ << " has " << m_.nodes_per_element
                                  << "-node elements; mixed TRI3/TRI6 blocks are not supported");
    total_ += blk.num_entry;
    SHELLFRAC_INPUT_REQUIRE(total_ <= num_elem_, path_ << ": the element blocks hold more elements than the header's "
                                                       << num_elem_);
    std::vector<std::int64_t> conn(static_cast<std::size_t>(blk.num_entry * npe));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id_, EX_ELEM_BLOCK, blk.id, conn.data(), nullptr, nullptr),
                              path_ << ": cannot read the connectivity of " << what);
    for (std::size_t k = 0; k < conn.size(); ++k) {
      SHELLFRAC_INPUT_REQUIRE(conn[k] >= 1 && conn[k] <= num_nodes_,
                              path_ << ": " << what << ", element " << k / npe + 1 << " of the block refers to node "
                                    << conn[k] << ", but the file has " << num_nodes_ << " nodes");
      m_.connectivity.push_back(conn[k] - 1);
    }
    m_.element_block.insert(m_.element_block.end(), static_cast<std::size_t>(blk.num_entry), block_index);
    // Per element: does side s of a TRISHELL element (3,4,5) or a TRI element (1,2,3) map to an edge?
    elem_is_shell_.insert(elem_is_shell_.end(), static_cast<std::size_t>(blk.num_entry), shell);
  }

  /// The ids, names and a description of each set of `type`; calls read_one(index, id, name, what).
  template <class ReadOne>
  void for_each_set(ex_entity_type type, std::int64_t count, const char* kind, const char* default_prefix,
                    ReadOne read_one) {
    const auto ids = get_ids(id_, type, count, path_, kind);
    const auto names = exodus::get_names(id_, type, count, path_);
    for (std::size_t s = 0; s < ids.size(); ++s) {
      const std::string name = default_name(names[s], default_prefix, ids[s]);
      const std::string what = std::string(kind) + " " + std::to_string(ids[s]) + " ('" + name + "')";
      read_one(ids[s], name, what);
    }
  }

  void read_node_sets() {
    read_index_sets(EX_NODE_SET, p_.num_node_sets, "node set", "nodeset", &mesh::NodeSet::nodes, num_nodes_, "node",
                    m_.node_sets);
  }

  /// Node or element sets: each a sorted list of 0-based indices (`members`) below `n`.
  template <class Set>
  void read_index_sets(ex_entity_type type, std::int64_t count, const char* kind, const char* default_prefix,
                       std::vector<GlobalId> Set::*members, std::int64_t n, const char* entity, std::vector<Set>& out) {
    std::vector<std::int64_t> entries;
    for_each_set(type, count, kind, default_prefix,
                 [&](std::int64_t set_id, const std::string& name, const std::string& what) {
                   Set set;
                   set.name = name;
                   set.id = checked_id(set_id, path_, what.c_str());
                   get_set(id_, type, set_id, entries, nullptr, path_, what, stored_bytes_);
                   set.*members = to_sorted_indices(entries, n, path_, what, entity);
                   out.push_back(std::move(set));
                 });
  }

  void read_side_sets() {
    std::vector<std::int64_t> elems, sides;
    for_each_set(EX_SIDE_SET, p_.num_side_sets, "side set", "sideset",
                 [&](std::int64_t set_id, const std::string& name, const std::string& what) {
                   mesh::SideSet ss;
                   ss.name = name;
                   ss.id = checked_id(set_id, path_, what.c_str());
                   get_set(id_, EX_SIDE_SET, set_id, elems, &sides, path_, what, stored_bytes_);
                   for (std::size_t k = 0; k < elems.size(); ++k) add_side(ss, elems[k], sides[k], what);
                   m_.side_sets.push_back(std::move(ss));
                 });
  }

  /// Side `side` of file element `e` (1-based) as an element and local edge of `ss`.
  void add_side(mesh::SideSet& ss, std::int64_t e, std::int64_t side, const std::string& what) const {
    SHELLFRAC_INPUT_REQUIRE(e >= 1 && e <= num_elem_, path_ << ": " << what << " refers to element " << e
                                                            << ", but the file has " << num_elem_ << " elements");
    const bool shell = elem_is_shell_[static_cast<std::size_t>(e - 1)] != 0;
    const std::int64_t first = shell ? 3 : 1;
    SHELLFRAC_INPUT_REQUIRE(!(shell && (side == 1 || side == 2)),
                            path_ << ": " << what << ", element " << e << ": side " << side
                                  << " is a face of a shell element; side sets of shells must use edge sides 3, 4, 5");
    SHELLFRAC_INPUT_REQUIRE(side >= first && side < first + 3,
                            path_ << ": " << what << ", element " << e << ": invalid side number " << side
                                  << " (expected " << first << ".." << first + 2 << ")");
    ss.elements.push_back(e - 1);
    ss.local_edges.push_back(static_cast<int>(side - first));
  }

  void read_element_sets() {
    read_index_sets(EX_ELEM_SET, p_.num_elem_sets, "element set", "elemset", &mesh::ElementSet::elements, num_elem_,
                    "element", m_.element_sets);
  }

  const std::string& path_;
  std::uint64_t stored_bytes_ = 0;  ///< bound on stored data (the file size) for a classic file, else 0
  int id_ = -1;
  ex_init_params p_{};
  std::int64_t num_nodes_ = 0, num_elem_ = 0;
  std::int64_t total_ = 0;                     ///< elements in the blocks read so far
  std::int64_t first_block_with_elements_ = 0;  ///< its id, for the mixed-order message
  std::vector<char> elem_is_shell_;            ///< per file element: TRISHELL (sides 3,4,5 are edges)
  mesh::SerialMesh m_;
};

/// Writes one set of `type` with 1-based entries (and optional side numbers).
void put_set(int exo_id, ex_entity_type type, int set_id, const std::vector<std::int64_t>& entries,
             const std::vector<std::int64_t>* extra, const std::string& path) {
  SHELLFRAC_EXO_CHECK(ex_put_set_param(exo_id, type, set_id, static_cast<std::int64_t>(entries.size()), 0),
                      path << ": set " << set_id);
  if (!entries.empty())
    SHELLFRAC_EXO_CHECK(ex_put_set(exo_id, type, set_id, entries.data(), extra ? extra->data() : nullptr),
                        path << ": set " << set_id);
}

template <class Set>
std::vector<std::string> names_of(const std::vector<Set>& sets) {
  std::vector<std::string> out;
  for (const auto& s : sets) out.push_back(s.name);
  return out;
}

/// The mesh can be written as Exodus: 3 or 6 nodes per element, 32-bit counts, names that fit.
void check_writable(const mesh::SerialMesh& mesh, const std::string& path) {
  const int npe = mesh.nodes_per_element;
  SHELLFRAC_REQUIRE(npe == 3 || npe == 6, path << ": nodes_per_element is " << npe);
  SHELLFRAC_REQUIRE(mesh.connectivity.size() == mesh.element_block.size() * static_cast<std::size_t>(npe),
                    path << ": connectivity size does not match the element count");
  SHELLFRAC_REQUIRE(mesh.num_nodes() < exodus::max_stored_int && mesh.num_elements() < exodus::max_stored_int,
                    path << ": mesh too large for 32-bit Exodus integers");
  exodus::check_name_lengths(names_of(mesh.blocks), "element block", path);
  exodus::check_name_lengths(names_of(mesh.node_sets), "node set", path);
  exodus::check_name_lengths(names_of(mesh.side_sets), "side set", path);
  exodus::check_name_lengths(names_of(mesh.element_sets), "element set", path);
}

void put_header_and_coordinates(int id, const mesh::SerialMesh& mesh, const std::string& path) {
  ex_init_params p{};
  const std::string title = "shellfrac mesh from " + mesh.source;
  title.copy(p.title, MAX_LINE_LENGTH);
  p.num_dim = 3;
  p.num_nodes = mesh.num_nodes();
  p.num_elem = mesh.num_elements();
  p.num_elem_blk = static_cast<std::int64_t>(mesh.blocks.size());
  p.num_node_sets = static_cast<std::int64_t>(mesh.node_sets.size());
  p.num_side_sets = static_cast<std::int64_t>(mesh.side_sets.size());
  p.num_elem_sets = static_cast<std::int64_t>(mesh.element_sets.size());
  SHELLFRAC_EXO_CHECK(ex_put_init_ext(id, &p), path);

  if (!mesh.coords.empty()) {
    std::vector<double> x, y, z;
    for (const auto& c : mesh.coords) {
      x.push_back(c[0]);
      y.push_back(c[1]);
      z.push_back(c[2]);
    }
    SHELLFRAC_EXO_CHECK(ex_put_coord(id, x.data(), y.data(), z.data()), path);
  }
}

/// The element blocks, TRISHELL3/TRISHELL6, elements in the file order `order` (mesh element of file element k).
void put_element_blocks(int id, const mesh::SerialMesh& mesh, const std::vector<std::size_t>& order,
                        const std::string& path) {
  const int npe = mesh.nodes_per_element;
  const char* type = npe == 3 ? "TRISHELL3" : "TRISHELL6";
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    std::vector<std::int64_t> conn;
    for (std::size_t e : order)
      if (mesh.element_block[e] == static_cast<int>(b))
        for (int a = 0; a < npe; ++a) conn.push_back(mesh.connectivity[e * npe + a] + 1);
    const std::int64_t count = static_cast<std::int64_t>(conn.size()) / npe;
    SHELLFRAC_EXO_CHECK(ex_put_block(id, EX_ELEM_BLOCK, mesh.blocks[b].id, type, count, npe, 0, 0, 0),
                        path << ": element block " << mesh.blocks[b].id);
    if (count > 0)
      SHELLFRAC_EXO_CHECK(ex_put_conn(id, EX_ELEM_BLOCK, mesh.blocks[b].id, conn.data(), nullptr, nullptr),
                          path << ": element block " << mesh.blocks[b].id);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_BLOCK, names_of(mesh.blocks)), path);
}

/// Node, side and element sets with their names; `file_number` is each mesh element's 1-based file number.
void put_sets(int id, const mesh::SerialMesh& mesh, const std::vector<std::int64_t>& file_number,
              const std::string& path) {
  for (const auto& ns : mesh.node_sets) {
    std::vector<std::int64_t> entries;
    for (GlobalId n : ns.nodes) entries.push_back(n + 1);
    put_set(id, EX_NODE_SET, ns.id, entries, nullptr, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_NODE_SET, names_of(mesh.node_sets)), path);

  for (const auto& ss : mesh.side_sets) {
    SHELLFRAC_REQUIRE(ss.elements.size() == ss.local_edges.size(), path << ": side set '" << ss.name << "' sizes differ");
    std::vector<std::int64_t> elems, sides;
    for (std::size_t k = 0; k < ss.elements.size(); ++k) {
      elems.push_back(file_number.at(static_cast<std::size_t>(ss.elements[k])));
      sides.push_back(ss.local_edges[k] + 3);  // TRISHELL: sides 3,4,5 are edges 0,1,2
    }
    put_set(id, EX_SIDE_SET, ss.id, elems, &sides, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_SIDE_SET, names_of(mesh.side_sets)), path);

  for (const auto& es : mesh.element_sets) {
    std::vector<std::int64_t> entries;
    for (GlobalId e : es.elements) entries.push_back(file_number.at(static_cast<std::size_t>(e)));
    std::sort(entries.begin(), entries.end());
    put_set(id, EX_ELEM_SET, es.id, entries, nullptr, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_SET, names_of(mesh.element_sets)), path);
}

}  // namespace

mesh::SerialMesh read_exodus_mesh(const std::string& path) {
  mesh::SerialMesh m;
  try {
    m = ExodusMeshReader(path).read();
  } catch (const std::bad_alloc&) {
    SHELLFRAC_INPUT_REQUIRE(false, path << ": the Exodus file declares more data than fits in memory");
  } catch (const std::length_error&) {
    SHELLFRAC_INPUT_REQUIRE(false, path << ": the Exodus file declares more data than fits in memory");
  }
  mesh::check_mesh(m);
  return m;
}

void write_exodus_mesh(const mesh::SerialMesh& mesh, const std::string& path) {
  check_writable(mesh, path);
  // Exodus numbers elements block by block: file element k is mesh element order[k].
  const std::size_t ne = mesh.element_block.size();
  std::vector<std::size_t> order(ne);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return mesh.element_block[a] < mesh.element_block[b]; });
  std::vector<std::int64_t> file_number(ne);  // 1-based file element number of each mesh element
  for (std::size_t k = 0; k < ne; ++k) file_number[order[k]] = static_cast<std::int64_t>(k) + 1;

  exodus::File file = exodus::create(path);
  if (!file.is_open()) throw OutputError(path + ": cannot create the Exodus file: " + exodus::last_error());
  const int id = file.id();
  put_header_and_coordinates(id, mesh, path);
  put_element_blocks(id, mesh, order, path);
  put_sets(id, mesh, file_number, path);
  SHELLFRAC_EXO_CHECK(file.close(), path);
}

mesh::SerialMesh read_mesh_file(const std::string& path) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(std::filesystem::exists(path, ec), path << ": mesh file not found");
  files::require_regular_input(path, "the mesh file");  // a FIFO would block in open(), a device never end
  std::string ext = exodus::upper(std::filesystem::path(path).extension().string());
  if (ext == ".MSH") return read_gmsh(path);
  if (ext == ".EXO" || ext == ".E" || ext == ".G" || ext == ".GEN" || ext == ".EX2") return read_exodus_mesh(path);
  SHELLFRAC_INPUT_REQUIRE(false, path << ": unknown mesh file extension '"
                                      << std::filesystem::path(path).extension().string()
                                      << "' (expected .msh for Gmsh, or .exo .e .g .gen .ex2 for Exodus II)");
  return {};
}

}  // namespace shellfrac::meshio
