#include "shellfrac/io/results_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/core/version.hpp"
#include "shellfrac/exodus/exodus_api.hpp"
#include "shellfrac/io/results_conventions.hpp"
#include "shellfrac/io/results_reader.hpp"

namespace shellfrac::io {

namespace fs = std::filesystem;

namespace {

std::string pad(int value, std::size_t width) {
  std::string s = std::to_string(value);
  return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

/// The Nemesis I global information of one file of a per-rank set (docs/output.md "Nemesis records"): the totals
/// of the set, summed over its ranks, and the rank the file belongs to.
struct NemesisGlobal {
  int num_ranks = 1, rank = 0;
  /// Real DG nodes (placeholder nodes not counted) and elements.
  std::int64_t num_nodes = 0, num_elements = 0;
  /// Elements per block (block_ids order), entries per set (node_sets, side_sets order).
  std::vector<std::int64_t> block_elements, node_set_entries, side_set_entries;
};

/// Everything one file holds apart from the time steps. element_block[i] indexes block_ids/block_names.
struct FileLayout {
  std::string title;
  int nodes_per_element = 3;
  std::vector<GlobalId> element_gids;
  std::vector<int> element_block;
  std::vector<std::string> block_names;
  std::vector<int> block_ids;
  std::vector<Vec3> node_coords;
  std::vector<std::string> nodal_names;    ///< scalar names (displ_x, ...)
  std::vector<std::string> element_names;
  std::vector<std::string> global_names;  ///< global variables (one value per step)
  std::vector<std::string> info;
  std::vector<ResultsSet> node_sets, side_sets;
  std::optional<NemesisGlobal> nemesis;  ///< the per-rank files of a set only (not a 1-rank file, not a join)
};
/// The QA record: program, version, date and time of writing.
int put_qa(int id) {
  const std::time_t now = std::time(nullptr);
  char date[MAX_STR_LENGTH + 1] = "", clock[MAX_STR_LENGTH + 1] = "";
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  std::strftime(clock, sizeof clock, "%H:%M:%S", std::gmtime(&now));
  char name[] = "shellfrac", version[MAX_STR_LENGTH + 1] = "";
  std::snprintf(version, sizeof version, "%s", shellfrac::version);
  char* record[1][4] = {{name, version, date, clock}};
  return ex_put_qa(id, 1, record);
}

int put_coordinate_names(int id) {
  char x[] = "x", y[] = "y", z[] = "z";
  char* names[3] = {x, y, z};
  return ex_put_coord_names(id, names);
}

/// Writes the sets of a file: layout element i is file element file_element[i] (1-based, block-grouped order),
/// its DG node a is file node i * npe + a + 1.
void put_sets(int id, const FileLayout& l, const std::vector<std::int64_t>& file_element, const std::string& path) {
  const auto index = [&](GlobalId gid) {
    const auto it = std::lower_bound(l.element_gids.begin(), l.element_gids.end(), gid);
    SHELLFRAC_REQUIRE(it != l.element_gids.end() && *it == gid, path << ": a set refers to element " << gid + 1
                                                                     << ", which is not in this file");
    return static_cast<std::size_t>(it - l.element_gids.begin());
  };
  const auto npe = static_cast<GlobalId>(l.nodes_per_element);
  for (const auto& set : l.node_sets) {
    std::vector<std::int64_t> nodes;
    for (GlobalId g : set.entries) nodes.push_back(static_cast<std::int64_t>(index(g / npe) * npe + g % npe) + 1);
    SHELLFRAC_EXO_CHECK(ex_put_set_param(id, EX_NODE_SET, set.id, std::int64_t(nodes.size()), 0),
                        path << ": node set " << set.name);
    if (!nodes.empty())
      SHELLFRAC_EXO_CHECK(ex_put_set(id, EX_NODE_SET, set.id, nodes.data(), nullptr), path << ": node set " << set.name);
  }
  for (const auto& set : l.side_sets) {
    std::vector<std::int64_t> elements, sides;
    for (std::size_t k = 0; k < set.entries.size(); ++k) {
      elements.push_back(file_element[index(set.entries[k])]);
      sides.push_back(set.edges[k] + first_edge_side);
    }
    SHELLFRAC_EXO_CHECK(ex_put_set_param(id, EX_SIDE_SET, set.id, std::int64_t(elements.size()), 0),
                        path << ": side set " << set.name);
    if (!elements.empty())
      SHELLFRAC_EXO_CHECK(ex_put_set(id, EX_SIDE_SET, set.id, elements.data(), sides.data()),
                          path << ": side set " << set.name);
  }
  std::vector<std::string> names;
  for (const auto& set : l.node_sets) names.push_back(set.name);
  if (!names.empty()) SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_NODE_SET, names), path);
  names.clear();
  for (const auto& set : l.side_sets) names.push_back(set.name);
  if (!names.empty()) SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_SIDE_SET, names), path);
}

/// The Nemesis global parameters of the node sets or of the side sets, put(ids, counts, factors): their ids, entry
/// counts over the set and no distribution factors (put_sets writes none). Nothing without sets.
template <class Put>
void put_set_params_global(const std::vector<ResultsSet>& sets, std::vector<std::int64_t> counts, const Put& put) {
  if (sets.empty()) return;
  std::vector<std::int64_t> ids, factors(sets.size(), 0);
  for (const auto& set : sets) ids.push_back(set.id);
  put(ids.data(), counts.data(), factors.data());
}

/// The Nemesis I records of a per-rank file (docs/output.md "Nemesis records"): the set's global counts, block and
/// set totals, and this rank's load-balance parameters and maps. A DG node belongs to one element, so every node
/// and element of the file is internal: no border or external nodes, no border elements, no communication maps.
/// The internal maps hold local 1-based indices (the Nemesis convention for a parallel file); the placeholder node
/// of an empty rank is not counted. Files are created with the 64-bit integer API: every array is int64_t. `n` is
/// a copy because Exodus 6.02 takes non-const arrays.
void put_nemesis(int id, NemesisGlobal n, const FileLayout& l, const std::string& path) {
  const auto num_elements = static_cast<std::int64_t>(l.element_gids.size());
  const std::int64_t num_nodes = num_elements * l.nodes_per_element;
  char parallel_file[] = "p";  // one rank's part of a set ('s' would be a whole decomposition in one file)
  SHELLFRAC_EXO_CHECK(ex_put_init_info(id, n.num_ranks, 1, parallel_file), path << ": Nemesis information");
  SHELLFRAC_EXO_CHECK(ex_put_init_global(id, n.num_nodes, n.num_elements, std::int64_t(l.block_ids.size()),
                                         std::int64_t(l.node_sets.size()), std::int64_t(l.side_sets.size())),
                      path << ": Nemesis global counts");
  SHELLFRAC_EXO_CHECK(ex_put_loadbal_param(id, num_nodes, 0, 0, num_elements, 0, 0, 0, n.rank),
                      path << ": Nemesis load-balance parameters");
  std::vector<std::int64_t> ids(l.block_ids.begin(), l.block_ids.end());
  SHELLFRAC_EXO_CHECK(ex_put_eb_info_global(id, ids.data(), n.block_elements.data()), path << ": Nemesis blocks");
  put_set_params_global(l.node_sets, n.node_set_entries, [&](auto* ids, auto* counts, auto* factors) {
    SHELLFRAC_EXO_CHECK(ex_put_ns_param_global(id, ids, counts, factors), path << ": Nemesis node sets");
  });
  put_set_params_global(l.side_sets, n.side_set_entries, [&](auto* ids, auto* counts, auto* factors) {
    SHELLFRAC_EXO_CHECK(ex_put_ss_param_global(id, ids, counts, factors), path << ": Nemesis side sets");
  });
  std::vector<std::int64_t> node_map(static_cast<std::size_t>(num_nodes)), elem_map(l.element_gids.size());
  for (std::size_t k = 0; k < node_map.size(); ++k) node_map[k] = static_cast<std::int64_t>(k) + 1;
  for (std::size_t k = 0; k < elem_map.size(); ++k) elem_map[k] = static_cast<std::int64_t>(k) + 1;
  SHELLFRAC_EXO_CHECK(ex_put_processor_node_maps(id, node_map.data(), nullptr, nullptr, n.rank),
                      path << ": Nemesis node map");
  SHELLFRAC_EXO_CHECK(ex_put_processor_elem_maps(id, elem_map.data(), nullptr, n.rank),
                      path << ": Nemesis element map");
}

/// The Nemesis global information of this rank's file of the set written over `comm`: element counts per block and
/// entry counts per set summed over the ranks (one all-gather, the same on every rank). Collective. Throws Error
/// naming `path` if the ranks disagree on the number of blocks or sets.
NemesisGlobal gather_nemesis_global(const ResultsLayout& l, MPI_Comm comm, const std::string& path) {
  NemesisGlobal n;
  n.num_ranks = parallel::size(comm);
  n.rank = parallel::rank(comm);
  // This rank's counts: [elements, elements per block..., entries per node set..., entries per side set...].
  std::vector<std::int64_t> local(1 + l.block_ids.size(), 0);
  local[0] = static_cast<std::int64_t>(l.element_gids.size());
  for (int b : l.element_block)
    if (b >= 0 && b < static_cast<int>(l.block_ids.size())) ++local[1 + b];  // FileWriter::open reports the others
  for (const auto& set : l.node_sets) local.push_back(static_cast<std::int64_t>(set.entries.size()));
  for (const auto& set : l.side_sets) local.push_back(static_cast<std::int64_t>(set.entries.size()));
  const std::vector<std::int64_t> all = parallel::all_gather(local, comm);
  SHELLFRAC_REQUIRE(all.size() == local.size() * static_cast<std::size_t>(n.num_ranks),
                    path << ": the ranks disagree on the number of element blocks or sets");
  std::vector<std::int64_t> total(local.size(), 0);
  for (std::size_t k = 0; k < all.size(); ++k) total[k % local.size()] += all[k];
  n.num_elements = total[0];
  n.num_nodes = total[0] * l.nodes_per_element;
  const auto part = [&](std::size_t first, std::size_t count) {
    return std::vector<std::int64_t>(total.begin() + first, total.begin() + first + count);
  };
  const std::size_t num_blocks = l.block_ids.size(), num_node_sets = l.node_sets.size();
  n.block_elements = part(1, num_blocks);
  n.node_set_entries = part(1 + num_blocks, num_node_sets);
  n.side_set_entries = part(1 + num_blocks + num_node_sets, l.side_sets.size());
  return n;
}

/// Writes one DG results file: the mesh part on open(), then one time step per put_step(). Used by both the
/// per-rank writer and write_results (the join), so both produce the same file structure.
class FileWriter {
 public:
  void open(const std::string& path, const FileLayout& l) {
    path_ = path;
    check_layout(path, l);
    const std::size_t ne = l.element_gids.size();
    const int npe = l.nodes_per_element;
    num_elements_ = ne;
    num_nodes_ = ne * npe;
    // Exodus stores no nodal variables in a file without nodes, so a rank owning no elements writes one
    // unconnected placeholder node (ParaView drops unused points; read_file ignores it).
    num_file_nodes_ = ne == 0 ? 1 : num_nodes_;
    num_nodal_ = l.nodal_names.size();
    num_element_vars_ = l.element_names.size();
    block_ids_ = l.block_ids;
    block_elements_.assign(l.block_ids.size(), {});
    for (std::size_t i = 0; i < ne; ++i) block_elements_[l.element_block[i]].push_back(i);

    file_ = exodus::create(path);
    if (!file_.is_open()) throw OutputError(path + ": cannot create the results file: " + exodus::last_error());
    const int id = file_.id();
    put_header(id, l);
    put_coordinates(id, l);
    const std::vector<std::int64_t> file_element = put_blocks_and_id_maps(id, l);
    put_sets(id, l, file_element, path);
    put_variable_names(id, l);
    SHELLFRAC_EXO_CHECK(ex_update(id), path);
  }

  /// nodal(v, buffer): the num_nodes values (layout node order) of nodal variable v, either its own storage or
  /// `buffer` (num_nodes long, reused for every variable) filled; element[s]: one value per element (layout order);
  /// global: num_global values (null if none).
  int put_step(double time, const std::function<const double*(std::size_t, double*)>& nodal,
               const std::vector<const double*>& element, const double* global) {
    const int id = file_.id();
    const int step = ++steps_;
    SHELLFRAC_EXO_CHECK(ex_put_time(id, step, &time), path_ << ": step " << step);
    const double placeholder_value = 0.0;
    std::vector<double> buffer(num_nodal_ > 0 ? num_nodes_ : 0);
    for (std::size_t v = 0; v < num_nodal_; ++v)
      SHELLFRAC_EXO_CHECK(ex_put_var(id, step, EX_NODAL, static_cast<int>(v) + 1, 1,
                                     static_cast<std::int64_t>(num_file_nodes_),
                                     num_nodes_ > 0 ? nodal(v, buffer.data()) : &placeholder_value),
                          path_ << ": step " << step << ", nodal variable " << v + 1);
    std::vector<double> buf;
    for (std::size_t s = 0; s < element.size(); ++s)
      for (std::size_t b = 0; b < block_ids_.size(); ++b) {
        const auto& elems = block_elements_[b];
        if (elems.empty()) continue;
        buf.clear();
        for (std::size_t i : elems) buf.push_back(element[s][i]);
        SHELLFRAC_EXO_CHECK(ex_put_var(id, step, EX_ELEM_BLOCK, static_cast<int>(s) + 1, block_ids_[b],
                                       static_cast<std::int64_t>(buf.size()), buf.data()),
                            path_ << ": step " << step << ", element variable " << s + 1 << ", block "
                                  << block_ids_[b]);
      }
    if (num_global_ > 0)
      SHELLFRAC_EXO_CHECK(ex_put_var(id, step, EX_GLOBAL, 1, 0, static_cast<std::int64_t>(num_global_), global),
                          path_ << ": step " << step << ", global variables");
    SHELLFRAC_EXO_CHECK(ex_update(id), path_ << ": step " << step);
    return step;
  }

  void close() { SHELLFRAC_EXO_CHECK(file_.close(), path_); }

  /// After a frame failed on some rank: closes the file (errors ignored: the disk may be full) and cuts it back
  /// to the frames before the one being written, so that every file of a per-rank set ends on the same frame.
  /// Returns the frames kept, or -1 if the file could not be cut (it may then end in a partial frame).
  int drop_unfinished_frame() {
    file_.close();
    steps_ = std::max(steps_ - 1, 0);
    return exodus::cut_record_count(path_, static_cast<std::uint64_t>(steps_)) ? steps_ : -1;
  }

  std::size_t num_elements() const { return num_elements_; }
  std::size_t num_nodes() const { return num_nodes_; }
  std::size_t num_nodal() const { return num_nodal_; }
  std::size_t num_element_vars() const { return num_element_vars_; }
  std::size_t num_global() const { return num_global_; }

 private:
  /// The layout is consistent: 3 or 6 nodes per element, sizes that agree, block indices in range, element gids
  /// strictly ascending within the 32-bit Exodus id range, names that fit.
  static void check_layout(const std::string& path, const FileLayout& l) {
    const int npe = l.nodes_per_element;
    const std::size_t ne = l.element_gids.size();
    SHELLFRAC_REQUIRE(npe == 3 || npe == 6, path << ": nodes_per_element is " << npe << " (expected 3 or 6)");
    SHELLFRAC_REQUIRE(l.element_block.size() == ne, path << ": element_block has " << l.element_block.size()
                                                         << " entries for " << ne << " elements");
    SHELLFRAC_REQUIRE(l.node_coords.size() == ne * npe, path << ": node_coords has " << l.node_coords.size()
                                                             << " entries, expected " << ne * npe);
    SHELLFRAC_REQUIRE(l.block_names.size() == l.block_ids.size(), path << ": block_names and block_ids differ in size");
    for (std::size_t i = 0; i < ne; ++i) {
      SHELLFRAC_REQUIRE(l.element_block[i] >= 0 && l.element_block[i] < static_cast<int>(l.block_ids.size()),
                        path << ": element " << l.element_gids[i] << " has block index " << l.element_block[i]);
      SHELLFRAC_REQUIRE(l.element_gids[i] >= 0 && (l.element_gids[i] + 1) * npe <= exodus::max_stored_int,
                        path << ": element gid " << l.element_gids[i] << " is out of the 32-bit Exodus id range");
      SHELLFRAC_REQUIRE(i == 0 || l.element_gids[i - 1] < l.element_gids[i],
                        path << ": element gids are not strictly ascending at " << l.element_gids[i]);
    }
    exodus::check_name_lengths(l.block_names, "element block", path);
    exodus::check_name_lengths(l.nodal_names, "nodal variable", path);
    exodus::check_name_lengths(l.element_names, "element variable", path);
  }

  void put_header(int id, const FileLayout& l) {
    const std::string& path = path_;
    const std::size_t ne = num_elements_;
    // History column names may exceed Exodus' default 32 characters: the file declares the longest before its
    // dimensions are defined, and stores them whole.
    std::size_t longest = 0;
    for (const auto& n : l.global_names) longest = std::max(longest, n.size());
    SHELLFRAC_REQUIRE(longest <= max_global_name_length,
                      path << ": a global variable name is longer than " << max_global_name_length << " characters");
    if (longest > static_cast<std::size_t>(MAX_NAME_LENGTH)) ex_set_max_name_length(id, static_cast<int>(longest));

    ex_init_params p{};
    l.title.copy(p.title, MAX_LINE_LENGTH);
    p.num_dim = 3;
    p.num_nodes = static_cast<std::int64_t>(num_file_nodes_);
    p.num_elem = static_cast<std::int64_t>(ne);
    p.num_elem_blk = static_cast<std::int64_t>(l.block_ids.size());
    p.num_node_sets = static_cast<std::int64_t>(l.node_sets.size());
    p.num_side_sets = static_cast<std::int64_t>(l.side_sets.size());
    SHELLFRAC_EXO_CHECK(ex_put_init_ext(id, &p), path);
    if (l.nemesis) put_nemesis(id, *l.nemesis, l, path);
    SHELLFRAC_EXO_CHECK(exodus::put_info(id, l.info), path);
    SHELLFRAC_EXO_CHECK(put_qa(id), path << ": QA record");
    SHELLFRAC_EXO_CHECK(put_coordinate_names(id), path << ": coordinate names");
  }

  /// One coordinate at a time (ex_put_coord skips the null arrays).
  void put_coordinates(int id, const FileLayout& l) {
    const std::string& path = path_;
    std::vector<double> c(num_file_nodes_, 0.0);
    for (int k = 0; k < 3; ++k) {
      for (std::size_t n = 0; n < num_nodes_; ++n) c[n] = l.node_coords[n][k];
      SHELLFRAC_EXO_CHECK(ex_put_coord(id, k == 0 ? c.data() : nullptr, k == 1 ? c.data() : nullptr,
                                       k == 2 ? c.data() : nullptr),
                          path);
    }
  }

  /// Blocks: file elements are grouped by block; DG node i*npe + a belongs to (layout) element i. Then the node and
  /// element id maps. Returns the 1-based file element of each layout element.
  std::vector<std::int64_t> put_blocks_and_id_maps(int id, const FileLayout& l) {
    const std::string& path = path_;
    const int npe = l.nodes_per_element;
    const std::size_t ne = num_elements_;
    const char* type = npe == 3 ? "TRISHELL3" : "TRISHELL6";
    std::vector<std::int64_t> elem_map, file_element(ne);
    for (std::size_t b = 0; b < block_ids_.size(); ++b) {
      const auto& elems = block_elements_[b];
      SHELLFRAC_EXO_CHECK(ex_put_block(id, EX_ELEM_BLOCK, block_ids_[b], type,
                                       static_cast<std::int64_t>(elems.size()), npe, 0, 0, 0),
                          path << ": element block " << block_ids_[b]);
      if (elems.empty()) continue;
      std::vector<std::int64_t> conn;
      for (std::size_t i : elems) {
        for (int a = 0; a < npe; ++a) conn.push_back(static_cast<std::int64_t>(i * npe + a) + 1);
        elem_map.push_back(l.element_gids[i] + 1);
        file_element[i] = static_cast<std::int64_t>(elem_map.size());
      }
      SHELLFRAC_EXO_CHECK(ex_put_conn(id, EX_ELEM_BLOCK, block_ids_[b], conn.data(), nullptr, nullptr),
                          path << ": element block " << block_ids_[b]);
    }
    SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_BLOCK, l.block_names), path);
    if (ne > 0) {
      std::vector<std::int64_t> node_map(num_nodes_);
      for (std::size_t i = 0; i < ne; ++i)
        for (int a = 0; a < npe; ++a) node_map[i * npe + a] = l.element_gids[i] * npe + a + 1;
      SHELLFRAC_EXO_CHECK(ex_put_id_map(id, EX_NODE_MAP, node_map.data()), path);
      SHELLFRAC_EXO_CHECK(ex_put_id_map(id, EX_ELEM_MAP, elem_map.data()), path);
    } else {
      const std::int64_t placeholder_id = exodus::max_stored_int;
      SHELLFRAC_EXO_CHECK(ex_put_id_map(id, EX_NODE_MAP, &placeholder_id), path);
    }
    return file_element;
  }

  void put_variable_names(int id, const FileLayout& l) {
    const std::string& path = path_;
    if (num_nodal_ > 0) {
      SHELLFRAC_EXO_CHECK(ex_put_variable_param(id, EX_NODAL, static_cast<int>(num_nodal_)), path);
      SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_NODAL, l.nodal_names, true), path);
    }
    if (num_element_vars_ > 0 && !block_ids_.empty()) {
      SHELLFRAC_EXO_CHECK(ex_put_variable_param(id, EX_ELEM_BLOCK, static_cast<int>(num_element_vars_)), path);
      SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_BLOCK, l.element_names, true), path);
      std::vector<int> truth;  // [block][variable]; empty blocks have no values
      for (const auto& elems : block_elements_) truth.insert(truth.end(), num_element_vars_, elems.empty() ? 0 : 1);
      SHELLFRAC_EXO_CHECK(ex_put_truth_table(id, EX_ELEM_BLOCK, static_cast<int>(block_ids_.size()),
                                             static_cast<int>(num_element_vars_), truth.data()),
                          path);
    }
    num_global_ = l.global_names.size();
    if (num_global_ > 0) {
      SHELLFRAC_EXO_CHECK(ex_put_variable_param(id, EX_GLOBAL, static_cast<int>(num_global_)), path);
      SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_GLOBAL, l.global_names, true), path);
    }
  }

  exodus::File file_;
  std::string path_;
  std::size_t num_elements_ = 0, num_nodes_ = 0, num_nodal_ = 0, num_element_vars_ = 0, num_global_ = 0;
  std::size_t num_file_nodes_ = 0;  ///< num_nodes_, or 1 (the placeholder) when there are no elements
  std::vector<int> block_ids_;
  std::vector<std::vector<std::size_t>> block_elements_;  ///< layout element indices per block, ascending
  int steps_ = 0;
};

}  // namespace

std::string rank_file_name(const std::string& path, int np, int rank) {
  if (np <= 1) return path;
  const std::size_t width = std::to_string(np).size();
  return path + "." + pad(np, width) + "." + pad(rank, width);
}

struct ExodusResultsWriter::Impl {
  FileWriter writer;
  std::size_t num_vectors = 0;
  MPI_Comm comm = MPI_COMM_NULL;
};

ExodusResultsWriter::ExodusResultsWriter(const std::string& path, ResultsLayout layout, MPI_Comm comm)
    : impl_(std::make_unique<Impl>()) {
  impl_->comm = comm;
  int np = 1, rank = 0;
  MPI_Comm_size(comm, &np);
  MPI_Comm_rank(comm, &rank);
  file_ = rank_file_name(path, np, rank);

  std::exception_ptr failure;
  try {
    FileLayout l;
    if (np > 1) {
      // Collective, before anything that can fail on one rank only. A set without any element gets no Nemesis
      // records: there is nothing to describe, and Exodus stores the global counts as netCDF dimensions (not 0).
      NemesisGlobal nemesis = gather_nemesis_global(layout, comm, file_);
      if (nemesis.num_elements > 0) l.nemesis = std::move(nemesis);
    }
    l.title = layout.title;
    l.nodes_per_element = layout.nodes_per_element;
    l.element_gids = std::move(layout.element_gids);
    l.element_block = std::move(layout.element_block);
    l.block_names = layout.block_names;
    l.block_ids = layout.block_ids;
    l.node_coords = std::move(layout.node_coords);
    for (const auto& v : layout.nodal_vectors)
      for (const char* suffix : component_suffix) l.nodal_names.push_back(v + suffix);
    l.element_names = layout.element_scalars;
    l.global_names = layout.global_variables;
    if (rank == 0) l.info = layout.info;  // the deck once per set, not once per rank
    l.node_sets = std::move(layout.node_sets);
    l.side_sets = std::move(layout.side_sets);
    impl_->num_vectors = layout.nodal_vectors.size();
    impl_->writer.open(file_, l);
  } catch (...) {
    failure = std::current_exception();
  }
  // Collective: every rank learns whether all files were created, so no rank runs on alone.
  parallel::on_all_then_agree([&] { if (failure) std::rethrow_exception(failure); }, comm);
}

ExodusResultsWriter::~ExodusResultsWriter() = default;

int ExodusResultsWriter::write_step(double time, const std::vector<std::vector<Vec3>>& nodal,
                                    const std::vector<std::vector<double>>& element,
                                    const std::vector<double>& global) {
  SHELLFRAC_REQUIRE(nodal.size() == impl_->num_vectors,
                    file_ << ": write_step got " << nodal.size() << " nodal vectors, expected " << impl_->num_vectors);
  for (std::size_t v = 0; v < nodal.size(); ++v)
    SHELLFRAC_REQUIRE(nodal[v].size() == impl_->writer.num_nodes(), file_ << ": nodal vector " << v << " has "
                                                                          << nodal[v].size() << " values, expected "
                                                                          << impl_->writer.num_nodes());
  const auto component = [&](std::size_t v, int c, double* out) {
    for (const auto& x : nodal[v]) *out++ = x[c];
  };
  return write_step(time, component, element, global);
}

int ExodusResultsWriter::write_step(double time, const NodalComponent& nodal,
                                    const std::vector<std::vector<double>>& element,
                                    const std::vector<double>& global) {
  auto& w = impl_->writer;
  SHELLFRAC_REQUIRE(element.size() == w.num_element_vars(), file_ << ": write_step got " << element.size()
                                                                  << " element scalars, expected "
                                                                  << w.num_element_vars());
  std::vector<const double*> element_ptr;
  const auto nodal_variable = [&](std::size_t var, double* buffer) -> const double* {
    nodal(var / 3, static_cast<int>(var % 3), buffer);
    return buffer;
  };
  for (std::size_t s = 0; s < element.size(); ++s) {
    SHELLFRAC_REQUIRE(element[s].size() == w.num_elements(), file_ << ": element scalar " << s << " has "
                                                                   << element[s].size() << " values, expected "
                                                                   << w.num_elements());
    element_ptr.push_back(element[s].data());
  }
  SHELLFRAC_REQUIRE(global.size() == w.num_global(),
                    file_ << ": write_step got " << global.size() << " global values, expected " << w.num_global());
  // Every rank learns whether every file took the frame: a failed write stops all ranks at once (exit 6), and
  // every file of the set is cut back to the frames before this one (a partial frame on one rank and a whole one
  // on the others would not make one time step).
  int index = 0;
  try {
    parallel::on_all_then_agree([&] { index = w.put_step(time, nodal_variable, element_ptr, global.data()); },
                                impl_->comm);
  } catch (const OutputError& e) {
    const int kept = w.drop_unfinished_frame();
    const bool all_cut = parallel::sum(kept < 0 ? 1 : 0, impl_->comm) == 0;
    throw OutputError(std::string(e.what()) +
                      (all_cut ? "; the results files now end at step " + std::to_string(kept)
                               : std::string("; a results file could not be cut back to the steps before and may "
                                             "end in a partial one")));
  }
  return index;
}
void write_results(const ExodusResults& results, const std::string& path) {
  const auto& r = results;
  const std::size_t ne = r.element_gids.size();
  SHELLFRAC_REQUIRE(r.element_block_ids.size() == ne, path << ": element_block_ids size " << r.element_block_ids.size()
                                                           << " != " << ne);
  SHELLFRAC_REQUIRE(r.nodal.size() == r.times.size() && r.element.size() == r.times.size(),
                    path << ": the number of steps of values and times differ");
  FileLayout l;
  l.title = r.title.empty() ? "shellfrac results" : r.title;
  l.nodes_per_element = r.nodes_per_element;
  l.node_sets = r.node_sets;
  l.side_sets = r.side_sets;
  l.element_gids = r.element_gids;
  l.block_names = r.block_names;
  l.block_ids = r.block_ids;
  l.node_coords = r.node_coords;
  l.nodal_names = r.nodal_names;
  l.element_names = r.element_names;
  l.global_names = r.global_names;
  l.info = r.info;
  std::map<int, int> index;
  for (std::size_t b = 0; b < r.block_ids.size(); ++b) index[r.block_ids[b]] = static_cast<int>(b);
  for (int bid : r.element_block_ids) {
    const auto it = index.find(bid);
    SHELLFRAC_REQUIRE(it != index.end(), path << ": element block id " << bid << " is not in block_ids");
    l.element_block.push_back(it->second);
  }
  FileWriter w;
  w.open(path, l);
  for (std::size_t s = 0; s < r.times.size(); ++s) {
    SHELLFRAC_REQUIRE(r.nodal[s].size() == l.nodal_names.size() && r.element[s].size() == l.element_names.size(),
                      path << ": step " << s + 1 << " has the wrong number of variables");
    std::vector<const double*> nodal, element;
    for (const auto& v : r.nodal[s]) {
      SHELLFRAC_REQUIRE(v.size() == w.num_nodes(), path << ": step " << s + 1 << ": nodal variable size " << v.size());
      nodal.push_back(v.data());
    }
    for (const auto& v : r.element[s]) {
      SHELLFRAC_REQUIRE(v.size() == ne, path << ": step " << s + 1 << ": element variable size " << v.size());
      element.push_back(v.data());
    }
    SHELLFRAC_REQUIRE(r.global.size() == r.times.size() && r.global[s].size() == l.global_names.size(),
                      path << ": step " << s + 1 << " has the wrong number of global values");
    w.put_step(r.times[s], [&](std::size_t v, double*) { return nodal[v]; }, element, r.global[s].data());
  }
  w.close();
}

}  // namespace shellfrac::io
