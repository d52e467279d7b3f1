#include "shellfrac/meshio/nemesis_piece_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/meshio/exodus_outline.hpp"

namespace shellfrac::meshio {

namespace {

/// The ranks of the decompositions of BASE present beside it (the P of every BASE.P.0), for the message of a
/// missing file.
std::string decompositions_present(const std::string& base) {
  const std::filesystem::path b(base);
  const std::filesystem::path dir = b.has_parent_path() ? b.parent_path() : std::filesystem::path(".");
  const std::string stem = b.filename().string() + ".";
  std::vector<int> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0) continue;
    const std::string rest = name.substr(stem.size());  // "P.r" for a file of rank r of P
    const auto dot = rest.find('.');
    const bool numbers = dot != std::string::npos && dot > 0 && dot + 1 < rest.size() && dot <= 9 &&
                         rest.find_first_not_of("0123456789") == dot &&
                         rest.find_first_not_of("0123456789", dot + 1) == std::string::npos;
    if (numbers && rest.find_first_not_of('0', dot + 1) == std::string::npos)
      found.push_back(std::stoi(rest.substr(0, dot)));
  }
  std::sort(found.begin(), found.end());
  if (found.empty()) return "no decomposition of it is there";
  std::string s = "it is decomposed for";
  for (int P : found) s += " " + std::to_string(P);
  return s + " rank(s)";
}

class NemesisPieceReader {
 public:
  NemesisPieceReader(const std::string& base, MPI_Comm comm)
      : base_(base),
        comm_(comm),
        rank_(parallel::rank(comm)),
        size_(parallel::size(comm)),
        path_(nemesis_file_name(base, size_, rank_)) {}

  mesh::MeshPiece read() {
    parallel::on_all_then_agree([&] { read_own_file(); }, comm_);
    check_same_outline();
    parallel::on_all_then_agree([&] { mesh::check_piece_elements(out_.piece, out_.outline.num_nodes); }, comm_);
    return std::move(out_);
  }

 private:
  void read_own_file() {
    std::error_code ec;
    SHELLFRAC_INPUT_REQUIRE(std::filesystem::is_regular_file(path_, ec),
                            base_ << ": the file " << path_ << " of rank " << rank_ << " of a decomposition for "
                                  << size_ << " ranks is not there; " << decompositions_present(base_));
    detail::read_exodus_file(path_, [&](int exo_id, detail::ExodusOutline& outline) {
      id_ = exo_id;
      o_ = std::move(outline);
      read_decomposition();
      read_numbering();
      read_elements();
      read_sets();
    });
  }

  /// Every rank's file names the same blocks and sets, with the same ids, as rank 0's. Collective.
  void check_same_outline() const {
    const mesh::MeshOutline& o = out_.outline;
    std::string mine = std::to_string(o.nodes_per_element);
    const auto add = [&](const auto& labels) {
      mine += "|" + std::to_string(labels.size());
      for (const auto& l : labels) mine += "|" + std::to_string(l.id) + ":" + l.name;
    };
    add(o.blocks), add(o.node_sets), add(o.side_sets), add(o.element_sets);
    std::string first = mine;
    parallel::broadcast(first, 0, comm_);
    parallel::on_all_then_agree(
        [&] {
          SHELLFRAC_INPUT_REQUIRE(mine == first, path_ << ": its blocks, sets or element type differ from those of "
                                                       << nemesis_file_name(base_, size_, 0)
                                                       << "; the files are not of one decomposition");
        },
        comm_);
  }

  /// The Nemesis information: for this number of ranks, one rank per file, the mesh's counts, and the same blocks
  /// and sets as the mesh in the same order.
  void read_decomposition() {
    int ranks = 0, ranks_in_file = 0;
    char type[2] = {0, 0};
    SHELLFRAC_INPUT_REQUIRE(ex_get_init_info(id_, &ranks, &ranks_in_file, type) >= 0 && ranks > 0,
                            path_ << ": not a decomposed (Nemesis) mesh file: it has no decomposition information");
    SHELLFRAC_INPUT_REQUIRE(ranks == size_ && ranks_in_file == 1,
                            path_ << ": decomposed for " << ranks << " ranks (" << ranks_in_file
                                  << " in this file), but the run has " << size_
                                  << " ranks; decompose the mesh for them (nem_slice, nem_spread)");
    std::int64_t nodes = 0, elements = 0, blocks = 0, node_sets = 0, side_sets = 0;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_global(id_, &nodes, &elements, &blocks, &node_sets, &side_sets),
                              path_ << ": cannot read the mesh's global counts");
    SHELLFRAC_INPUT_REQUIRE(
        elements > 0 && nodes > 0 && elements < (std::int64_t{1} << 40) && nodes < (std::int64_t{1} << 40),
        path_ << ": invalid global counts (" << elements << " elements, " << nodes << " nodes)");
    SHELLFRAC_INPUT_REQUIRE(blocks == std::int64_t(o_.blocks.size()) &&
                                node_sets == std::int64_t(o_.node_sets.size()) &&
                                side_sets == std::int64_t(o_.side_sets.size()),
                            path_ << ": the file lists " << o_.blocks.size() << " blocks, " << o_.node_sets.size()
                                  << " node sets and " << o_.side_sets.size() << " side sets, but the mesh has "
                                  << blocks << ", " << node_sets << " and " << side_sets);
    same_ids("element block", o_.blocks,
             [&](std::int64_t* ids, std::int64_t* counts) { return ex_get_eb_info_global(id_, ids, counts); });
    same_ids("node set", o_.node_sets, [&](std::int64_t* ids, std::int64_t* counts) {
      std::vector<std::int64_t> df(o_.node_sets.size());
      return ex_get_ns_param_global(id_, ids, counts, df.data());
    });
    same_ids("side set", o_.side_sets, [&](std::int64_t* ids, std::int64_t* counts) {
      std::vector<std::int64_t> df(o_.side_sets.size());
      return ex_get_ss_param_global(id_, ids, counts, df.data());
    });
    out_.outline = detail::mesh_outline_of(o_, base_);
    out_.outline.num_elements = elements;
    out_.outline.num_nodes = nodes;
    out_.piece.nodes_per_element = o_.nodes_per_element;
    out_.piece.source = base_;
  }

  /// The global ids, in order, of the blocks or sets `local` of this file: the same as the file's.
  template <class Local, class Get>
  void same_ids(const char* kind, const std::vector<Local>& local, Get get) const {
    if (local.empty()) return;
    std::vector<std::int64_t> ids(local.size()), counts(local.size());
    SHELLFRAC_EXO_INPUT_CHECK(get(ids.data(), counts.data()), path_ << ": cannot read the mesh's " << kind << " ids");
    for (std::size_t k = 0; k < local.size(); ++k)
      SHELLFRAC_INPUT_REQUIRE(ids[k] == local[k].id, path_ << ": " << kind << " " << k + 1 << " of the file has id "
                                                           << local[k].id << ", but the mesh's " << kind << " " << k + 1
                                                           << " has id " << ids[k]);
  }

  /// The positions in the decomposed mesh of this file's elements and nodes (its number maps).
  void read_numbering() {
    elements_ = read_map(EX_ELEM_MAP, o_.num_elements, out_.outline.num_elements, "element");
    nodes_ = read_map(EX_NODE_MAP, o_.num_nodes, out_.outline.num_nodes, "node");
  }

  std::vector<GlobalId> read_map(ex_entity_type type, std::int64_t count, GlobalId global, const char* what) const {
    std::vector<std::int64_t> map(static_cast<std::size_t>(count));
    if (count > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id_, type, map.data()), path_ << ": cannot read the " << what << " map");
    std::vector<GlobalId> out(map.size());
    for (std::size_t i = 0; i < map.size(); ++i)
      out[i] = detail::checked_index(map[i], global, path_, std::string("the ") + what + " map", what);
    return out;
  }

  /// The elements block by block, with their global node ids and coordinates.
  void read_elements() {
    const int npe = o_.nodes_per_element;
    const auto n = static_cast<std::size_t>(o_.num_nodes);
    std::vector<double> x(n), y(n), z(n, 0.0);
    if (n > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id_, x.data(), y.data(), o_.num_dim == 3 ? z.data() : nullptr),
                                path_ << ": cannot read the node coordinates");
    for (std::size_t i = 0; i < n; ++i)
      SHELLFRAC_INPUT_REQUIRE(std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i]),
                              path_ << ": a node has a non-finite coordinate");
    mesh::ElementPiece& p = out_.piece;
    p.elements = elements_;
    std::vector<std::int64_t> conn;
    for (std::size_t b = 0; b < o_.blocks.size(); ++b) {
      const detail::ExodusBlock& blk = o_.blocks[b];
      if (blk.count == 0) continue;
      conn.assign(static_cast<std::size_t>(blk.count * npe), 0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id_, EX_ELEM_BLOCK, blk.id, conn.data(), nullptr, nullptr),
                                path_ << ": cannot read the connectivity of " << blk.what);
      for (std::size_t k = 0; k < conn.size(); ++k) {
        const auto local = static_cast<std::size_t>(
            detail::checked_node(conn[k], static_cast<std::int64_t>(k), npe, blk, o_.num_nodes, path_));
        p.nodes.push_back(nodes_[local]);
        p.coords.push_back({x[local], y[local], z[local]});
      }
      p.blocks.insert(p.blocks.end(), static_cast<std::size_t>(blk.count), static_cast<int>(b));
    }
  }

  /// Side, node and element sets, their members numbered as in the decomposed mesh.
  void read_sets() {
    mesh::ElementPiece& p = out_.piece;
    std::vector<std::int64_t> entries, sides;
    for (std::size_t s = 0; s < o_.side_sets.size(); ++s) {
      detail::read_set(id_, EX_SIDE_SET, o_.side_sets[s], entries, &sides, path_);
      for (std::size_t k = 0; k < entries.size(); ++k) {
        const int edge = detail::local_edge_of_side(o_, entries[k], sides[k], path_, o_.side_sets[s].what);
        p.side_entries.push_back({elements_[static_cast<std::size_t>(entries[k] - 1)], edge, static_cast<int>(s)});
      }
    }
    for (std::size_t s = 0; s < o_.node_sets.size(); ++s) {
      detail::read_set(id_, EX_NODE_SET, o_.node_sets[s], entries, nullptr, path_);
      for (auto v : entries) {
        const GlobalId local = detail::checked_index(v, o_.num_nodes, path_, o_.node_sets[s].what, "node");
        p.node_set_entries.push_back({nodes_[static_cast<std::size_t>(local)], static_cast<int>(s)});
      }
    }
    for (std::size_t s = 0; s < o_.element_sets.size(); ++s) {
      detail::read_set(id_, EX_ELEM_SET, o_.element_sets[s], entries, nullptr, path_);
      for (auto v : entries) {
        const GlobalId local = detail::checked_index(v, o_.num_elements, path_, o_.element_sets[s].what, "element");
        p.element_set_entries.push_back({elements_[static_cast<std::size_t>(local)], static_cast<int>(s)});
      }
    }
    mesh::sort_side_entries(p.side_entries);
    mesh::sort_set_entries(p.node_set_entries);
    mesh::sort_set_entries(p.element_set_entries);
  }

  const std::string& base_;
  MPI_Comm comm_;
  int rank_, size_;
  std::string path_;  ///< this rank's file
  int id_ = -1;
  detail::ExodusOutline o_;         ///< of this rank's file (local counts)
  std::vector<GlobalId> elements_;  ///< per element of the file: its position in the decomposed mesh
  std::vector<GlobalId> nodes_;     ///< per node of the file: its position in the decomposed mesh
  mesh::MeshPiece out_;
};

}  // namespace

std::string nemesis_file_name(const std::string& base, int P, int r) {
  std::string digits = std::to_string(r);
  const std::size_t width = std::to_string(P).size();
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return base + "." + std::to_string(P) + "." + digits;
}

mesh::MeshPiece read_nemesis_piece(const std::string& base, MPI_Comm comm) {
  return NemesisPieceReader(base, comm).read();
}

}  // namespace shellfrac::meshio
