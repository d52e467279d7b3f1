#include "shellfrac/meshio/exodus_outline.hpp"

#include <filesystem>
#include <new>
#include <stdexcept>

#include "shellfrac/core/error.hpp"
#include "shellfrac/meshio/exodus_file_checks.hpp"

namespace shellfrac::meshio::detail {

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
  if (count > 0)
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(exo_id, type, ids.data()), path << ": cannot read " << what << " ids");
  return ids;
}

class OutlineReader {
 public:
  OutlineReader(int exo_id, const std::string& path, std::uint64_t stored_bytes) : id_(exo_id), path_(path) {
    o_.stored_bytes = stored_bytes;
  }

  ExodusOutline read() {
    read_header();
    read_blocks();
    o_.node_sets = read_sets(EX_NODE_SET, p_.num_node_sets, "node set", "nodeset", 4);
    o_.side_sets = read_sets(EX_SIDE_SET, p_.num_side_sets, "side set", "sideset", 8);
    o_.element_sets = read_sets(EX_ELEM_SET, p_.num_elem_sets, "element set", "elemset", 4);
    return std::move(o_);
  }

 private:
  void read_header() {
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_ext(id_, &p_), path_ << ": cannot read the Exodus header");
    SHELLFRAC_INPUT_REQUIRE(p_.num_dim == 2 || p_.num_dim == 3,
                            path_ << ": " << p_.num_dim << "-dimensional coordinates; a shell mesh needs 2 or 3");
    o_.num_dim = static_cast<int>(p_.num_dim);
    o_.num_nodes = checked_count(p_.num_nodes, path_, "node");
    o_.num_elements = checked_count(p_.num_elem, path_, "element");
    checked_count(p_.num_elem_blk, path_, "element block");
    checked_count(p_.num_node_sets, path_, "node set");
    checked_count(p_.num_side_sets, path_, "side set");
    checked_count(p_.num_elem_sets, path_, "element set");
    SHELLFRAC_INPUT_REQUIRE(o_.num_elements > 0 && p_.num_elem_blk > 0, path_ << ": the file has no elements");
    const std::uint64_t bytes = o_.stored_bytes;
    check_stored(o_.num_nodes, 4 * static_cast<std::uint64_t>(p_.num_dim), bytes, path_, "nodes");
    check_stored(o_.num_elements, 3 * 4, bytes, path_, "elements");
    check_stored(p_.num_elem_blk, 4, bytes, path_, "element blocks");
    check_stored(p_.num_node_sets, 4, bytes, path_, "node sets");
    check_stored(p_.num_side_sets, 4, bytes, path_, "side sets");
    check_stored(p_.num_elem_sets, 4, bytes, path_, "element sets");
  }

  /// Element blocks, in file order; elements are numbered in that order.
  void read_blocks() {
    const auto ids = get_ids(id_, EX_ELEM_BLOCK, p_.num_elem_blk, path_, "element block");
    const auto names = exodus::get_names(id_, EX_ELEM_BLOCK, p_.num_elem_blk, path_);
    std::int64_t total = 0, first_with_elements = 0;
    for (std::size_t b = 0; b < ids.size(); ++b) {
      ExodusBlock blk = read_block(ids[b], default_name(names[b], "block", ids[b]));
      blk.first = total;
      if (blk.count > 0 && o_.nodes_per_element == 0) first_with_elements = blk.id;
      if (blk.count > 0 && o_.nodes_per_element == 0) o_.nodes_per_element = npe_;
      SHELLFRAC_INPUT_REQUIRE(blk.count == 0 || npe_ == o_.nodes_per_element,
                              path_ << ": " << blk.what << " has " << npe_ << "-node elements but element block "
                                    << first_with_elements << " has " << o_.nodes_per_element
                                    << "-node elements; mixed TRI3/TRI6 blocks are not supported");
      total += blk.count;
      SHELLFRAC_INPUT_REQUIRE(total <= o_.num_elements, path_ << ": the element blocks hold more elements than the "
                                                                 "header's "
                                                              << o_.num_elements);
      o_.blocks.push_back(std::move(blk));
    }
    SHELLFRAC_INPUT_REQUIRE(total == o_.num_elements, path_ << ": the element blocks hold " << total
                                                            << " elements but the header says " << o_.num_elements);
  }

  /// One block's parameters; sets npe_ to its nodes per element.
  ExodusBlock read_block(std::int64_t block_id, const std::string& name) {
    ExodusBlock out;
    out.id = block_id;
    out.name = name;
    out.what = "element block " + std::to_string(block_id) + " ('" + name + "')";
    ex_block blk{};
    blk.id = block_id;
    blk.type = EX_ELEM_BLOCK;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_block_param(id_, &blk), path_ << ": cannot read " << out.what);
    blk.topology[MAX_STR_LENGTH] = '\0';
    const std::string type = blk.topology;
    out.count = checked_count(blk.num_entry, path_, out.what.c_str());
    check_stored(blk.num_entry, 3 * 4, o_.stored_bytes, path_, "elements in " + out.what);
    npe_ = triangle_type_nodes(type, out.shell);
    checked_id(block_id, path_, out.what.c_str());
    if (blk.num_entry == 0) return out;  // Exodus stores empty blocks with type "NULL" and 0 nodes per element
    if (npe_ == -1 && (blk.num_nodes_per_entry == 3 || blk.num_nodes_per_entry == 6))
      npe_ = static_cast<int>(blk.num_nodes_per_entry);
    SHELLFRAC_INPUT_REQUIRE(npe_ > 0 && npe_ == blk.num_nodes_per_entry,
                            path_ << ": " << out.what << " has unsupported element type '" << type << "' with "
                                  << blk.num_nodes_per_entry
                                  << " nodes per element; shell meshes need TRI3/TRISHELL3 or TRI6/TRISHELL6");
    return out;
  }

  /// The ids, names and sizes of the sets of `type`; each entry takes at least `entry_bytes` in the file.
  std::vector<ExodusSet> read_sets(ex_entity_type type, std::int64_t count, const char* kind,
                                   const char* default_prefix, std::uint64_t entry_bytes) {
    const auto ids = get_ids(id_, type, count, path_, kind);
    const auto names = exodus::get_names(id_, type, count, path_);
    std::vector<ExodusSet> out;
    for (std::size_t s = 0; s < ids.size(); ++s) {
      ExodusSet set;
      set.id = ids[s];
      set.name = default_name(names[s], default_prefix, ids[s]);
      set.what = std::string(kind) + " " + std::to_string(ids[s]) + " ('" + set.name + "')";
      checked_id(set.id, path_, set.what.c_str());
      std::int64_t ndf = 0;
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_set_param(id_, type, set.id, &set.count, &ndf),
                                path_ << ": cannot read " << set.what);
      checked_count(set.count, path_, set.what.c_str());
      check_stored(set.count, entry_bytes, o_.stored_bytes, path_, "entries in " + set.what);
      out.push_back(std::move(set));
    }
    return out;
  }

  int id_;
  const std::string& path_;
  ex_init_params p_{};
  int npe_ = 0;
  ExodusOutline o_;
};

}  // namespace

const ExodusBlock& ExodusOutline::block_of(GlobalId e) const {
  std::size_t b = blocks.size() - 1;
  while (b > 0 && (blocks[b].first > e || blocks[b].count == 0)) --b;
  return blocks[b];
}

exodus::File open_checked_exodus(const std::string& path, std::uint64_t& stored_bytes) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(std::filesystem::is_regular_file(path, ec), path << ": Exodus file not found");
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  SHELLFRAC_INPUT_REQUIRE(!ec, path << ": cannot read the file size (" << ec.message() << ")");
  // Upper bound for counts read from the header (0 = none: netCDF-4 files may be compressed).
  stored_bytes = check_netcdf_classic_header(path, file_size) ? file_size : 0;
  check_exodus_structure(path);
  exodus::File file = exodus::open_read(path);
  SHELLFRAC_INPUT_REQUIRE(file.is_open(),
                          path << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
  return file;
}

ExodusOutline read_exodus_outline(int exo_id, const std::string& path, std::uint64_t stored_bytes) {
  return OutlineReader(exo_id, path, stored_bytes).read();
}

GlobalId checked_node(std::int64_t value, std::int64_t k, int nodes_per_element, const ExodusBlock& b,
                      std::int64_t num_nodes, const std::string& path) {
  SHELLFRAC_INPUT_REQUIRE(value >= 1 && value <= num_nodes, path << ": " << b.what << ", element "
                                                                 << k / nodes_per_element + 1
                                                                 << " of the block refers to node " << value
                                                                 << ", but the file has " << num_nodes << " nodes");
  return value - 1;
}

GlobalId checked_index(std::int64_t value, std::int64_t n, const std::string& path, const std::string& what,
                       const char* entity) {
  SHELLFRAC_INPUT_REQUIRE(value >= 1 && value <= n, path << ": " << what << " refers to " << entity << " " << value
                                                         << ", but the file has " << n << " " << entity << "s");
  return value - 1;
}

int local_edge_of_side(const ExodusOutline& o, std::int64_t e, std::int64_t side, const std::string& path,
                       const std::string& what) {
  SHELLFRAC_INPUT_REQUIRE(e >= 1 && e <= o.num_elements, path << ": " << what << " refers to element " << e
                                                              << ", but the file has " << o.num_elements
                                                              << " elements");
  const bool shell = o.block_of(e - 1).shell;
  const std::int64_t first = shell ? 3 : 1;
  SHELLFRAC_INPUT_REQUIRE(!(shell && (side == 1 || side == 2)),
                          path << ": " << what << ", element " << e << ": side " << side
                               << " is a face of a shell element; side sets of shells must use edge sides 3, 4, 5");
  SHELLFRAC_INPUT_REQUIRE(side >= first && side < first + 3, path << ": " << what << ", element " << e
                                                                  << ": invalid side number " << side << " (expected "
                                                                  << first << ".." << first + 2 << ")");
  return static_cast<int>(side - first);
}

void read_set(int exo_id, ex_entity_type type, const ExodusSet& set, std::vector<std::int64_t>& entries,
              std::vector<std::int64_t>* extra, const std::string& path) {
  entries.assign(static_cast<std::size_t>(set.count), 0);
  if (extra) extra->assign(static_cast<std::size_t>(set.count), 0);
  if (set.count > 0)
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_set(exo_id, type, set.id, entries.data(), extra ? extra->data() : nullptr),
                              path << ": cannot read the entries of " << set.what);
}

mesh::MeshOutline mesh_outline_of(const ExodusOutline& o, const std::string& path) {
  mesh::MeshOutline m;
  m.nodes_per_element = o.nodes_per_element;
  m.num_elements = o.num_elements;
  m.num_nodes = o.num_nodes;
  m.source = path;
  for (const auto& b : o.blocks) m.blocks.push_back({b.name, static_cast<int>(b.id)});
  const auto labels = [](const std::vector<ExodusSet>& sets) {
    std::vector<mesh::SetLabel> v;
    for (const auto& s : sets) v.push_back({s.name, static_cast<int>(s.id)});
    return v;
  };
  m.node_sets = labels(o.node_sets);
  m.side_sets = labels(o.side_sets);
  m.element_sets = labels(o.element_sets);
  const auto ids_and_names = [](const auto& labels) {
    std::vector<std::pair<int, std::string>> v;
    for (const auto& s : labels) v.emplace_back(s.id, s.name);
    return v;
  };
  mesh::check_ids_and_names(ids_and_names(m.blocks), "element block", path);
  mesh::check_ids_and_names(ids_and_names(m.node_sets), "node set", path);
  mesh::check_ids_and_names(ids_and_names(m.side_sets), "side set", path);
  mesh::check_ids_and_names(ids_and_names(m.element_sets), "element set", path);
  return m;
}

void read_exodus_file(const std::string& path, const std::function<void(int, ExodusOutline&)>& read) {
  bool too_much = false;
  try {
    std::uint64_t stored_bytes = 0;
    exodus::File file = open_checked_exodus(path, stored_bytes);
    ExodusOutline outline = read_exodus_outline(file.id(), path, stored_bytes);
    read(file.id(), outline);
  } catch (const std::bad_alloc&) {
    too_much = true;
  } catch (const std::length_error&) {
    too_much = true;
  }
  SHELLFRAC_INPUT_REQUIRE(!too_much, path << ": the Exodus file declares more data than fits in memory");
}

}  // namespace shellfrac::meshio::detail
