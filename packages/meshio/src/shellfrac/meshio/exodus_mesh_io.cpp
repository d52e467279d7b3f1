#include "shellfrac/meshio/exodus_mesh_io.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/exodus/exodus_api.hpp"
#include "shellfrac/meshio/exodus_outline.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"

namespace shellfrac::meshio {

namespace {

/// Reads one Exodus shell mesh whole: the outline (exodus_outline.hpp), the id maps, the coordinates, the
/// connectivity and the sets' entries.
class ExodusMeshReader {
 public:
  explicit ExodusMeshReader(const std::string& path) : path_(path) {}

  mesh::SerialMesh read() {
    detail::read_exodus_file(path_, [&](int exo_id, detail::ExodusOutline& outline) {
      id_ = exo_id;
      o_ = std::move(outline);
      m_.source = path_;
      m_.nodes_per_element = o_.nodes_per_element;
      read_id_maps();
      read_coordinates();
      read_blocks();
      read_node_sets();
      read_side_sets();
      read_element_sets();
    });
    return std::move(m_);
  }

 private:
  /// The file's element and node ids (its id maps; 1..n without them). shellfrac numbers elements and nodes by
  /// their position in the file, so two entities with one id would be two things under one name: refused.
  /// Messages name them by these ids (mesh::FileIds), kept when they are not the positions.
  void read_id_maps() {
    read_id_map(EX_ELEM_MAP, o_.num_elements, "element", m_.element_ids);
    read_id_map(EX_NODE_MAP, o_.num_nodes, "node", m_.node_ids);
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
    std::vector<double> x(static_cast<std::size_t>(o_.num_nodes)), y(x.size()), z(x.size(), 0.0);
    if (o_.num_nodes > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id_, x.data(), y.data(), o_.num_dim == 3 ? z.data() : nullptr),
                                path_ << ": cannot read the node coordinates");
    m_.coords.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) m_.coords[i] = {x[i], y[i], z[i]};
  }

  /// Element blocks, in file order; elements are numbered in that order.
  void read_blocks() {
    const int npe = o_.nodes_per_element;
    for (const detail::ExodusBlock& b : o_.blocks) {
      const int block_index = static_cast<int>(m_.blocks.size());
      m_.blocks.push_back({b.name, static_cast<int>(b.id)});
      if (b.count == 0) continue;
      std::vector<std::int64_t> conn(static_cast<std::size_t>(b.count * npe));
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id_, EX_ELEM_BLOCK, b.id, conn.data(), nullptr, nullptr),
                                path_ << ": cannot read the connectivity of " << b.what);
      for (std::size_t k = 0; k < conn.size(); ++k)
        m_.connectivity.push_back(
            detail::checked_node(conn[k], static_cast<std::int64_t>(k), npe, b, o_.num_nodes, path_));
      m_.element_block.insert(m_.element_block.end(), static_cast<std::size_t>(b.count), block_index);
    }
  }

  /// Node or element sets: each a sorted list of 0-based indices (`members`) below `n`.
  template <class Set>
  void read_index_sets(ex_entity_type type, const std::vector<detail::ExodusSet>& sets,
                       std::vector<GlobalId> Set::*members, std::int64_t n, const char* entity, std::vector<Set>& out) {
    std::vector<std::int64_t> entries;
    for (const detail::ExodusSet& s : sets) {
      Set set;
      set.name = s.name;
      set.id = static_cast<int>(s.id);
      detail::read_set(id_, type, s, entries, nullptr, path_);
      auto& list = set.*members;
      list.reserve(entries.size());
      for (auto x : entries) list.push_back(detail::checked_index(x, n, path_, s.what, entity));
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      out.push_back(std::move(set));
    }
  }

  void read_node_sets() {
    read_index_sets(EX_NODE_SET, o_.node_sets, &mesh::NodeSet::nodes, o_.num_nodes, "node", m_.node_sets);
  }

  void read_side_sets() {
    std::vector<std::int64_t> elems, sides;
    for (const detail::ExodusSet& s : o_.side_sets) {
      mesh::SideSet ss;
      ss.name = s.name;
      ss.id = static_cast<int>(s.id);
      detail::read_set(id_, EX_SIDE_SET, s, elems, &sides, path_);
      for (std::size_t k = 0; k < elems.size(); ++k) {
        const int edge = detail::local_edge_of_side(o_, elems[k], sides[k], path_, s.what);
        ss.elements.push_back(elems[k] - 1);
        ss.local_edges.push_back(edge);
      }
      m_.side_sets.push_back(std::move(ss));
    }
  }

  void read_element_sets() {
    read_index_sets(EX_ELEM_SET, o_.element_sets, &mesh::ElementSet::elements, o_.num_elements, "element",
                    m_.element_sets);
  }

  const std::string& path_;
  int id_ = -1;
  detail::ExodusOutline o_;
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
  mesh::SerialMesh m = ExodusMeshReader(path).read();
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
