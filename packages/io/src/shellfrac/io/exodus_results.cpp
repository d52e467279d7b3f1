#include "shellfrac/io/exodus_results.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
#include "shellfrac/exodus/exodus_api.hpp"

namespace shellfrac::io {

namespace fs = std::filesystem;

namespace {

/// Suffixes of the scalar components of a nodal vector.
constexpr const char* component_suffix[3] = {"_x", "_y", "_z"};

/// Largest count accepted from a file header before allocating.
constexpr std::int64_t max_count = std::int64_t{1} << 31;

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

/// Exodus side number of local edge k of a shell triangle (sides 1 and 2 are its faces).
constexpr int first_edge_side = 3;

/// The QA record: program, version, date and time of writing.
int put_qa(int id) {
  const std::time_t now = std::time(nullptr);
  char date[MAX_STR_LENGTH + 1] = "", clock[MAX_STR_LENGTH + 1] = "";
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  std::strftime(clock, sizeof clock, "%H:%M:%S", std::gmtime(&now));
  char name[] = "shellfrac", version[] = "0.1.0";
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

    {  // one coordinate at a time (ex_put_coord skips the null arrays)
      std::vector<double> c(num_file_nodes_, 0.0);
      for (int k = 0; k < 3; ++k) {
        for (std::size_t n = 0; n < num_nodes_; ++n) c[n] = l.node_coords[n][k];
        SHELLFRAC_EXO_CHECK(ex_put_coord(id, k == 0 ? c.data() : nullptr, k == 1 ? c.data() : nullptr,
                                         k == 2 ? c.data() : nullptr),
                            path);
      }
    }

    // Blocks: file elements are grouped by block; DG node i*npe + a belongs to (layout) element i.
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
    put_sets(id, l, file_element, path);

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

  std::size_t num_elements() const { return num_elements_; }
  std::size_t num_nodes() const { return num_nodes_; }
  std::size_t num_nodal() const { return num_nodal_; }
  std::size_t num_element_vars() const { return num_element_vars_; }
  std::size_t num_global() const { return num_global_; }

 private:
  exodus::File file_;
  std::string path_;
  std::size_t num_elements_ = 0, num_nodes_ = 0, num_nodal_ = 0, num_element_vars_ = 0, num_global_ = 0;
  std::size_t num_file_nodes_ = 0;  ///< num_nodes_, or 1 (the placeholder) when there are no elements
  std::vector<int> block_ids_;
  std::vector<std::vector<std::size_t>> block_elements_;  ///< layout element indices per block, ascending
  int steps_ = 0;
};

// ------------------------------------------------------------------------------------------------ reading

std::int64_t checked_count(std::int64_t n, const std::string& path, const char* what) {
  SHELLFRAC_INPUT_REQUIRE(n >= 0 && n < max_count, path << ": invalid " << what << " count " << n);
  return n;
}

/// The node sets (members as DG node ids, from the node id map `map`) or side sets (element gids from the element
/// id map, edges from the shell edge sides 3..5) of a file, each sorted.
std::vector<ResultsSet> read_sets(int id, ex_entity_type type, const std::vector<std::int64_t>& map,
                                  const std::string& path) {
  const bool nodes = type == EX_NODE_SET;
  const char* what = nodes ? "node set" : "side set";
  const std::int64_t n = checked_count(ex_inquire_int(id, nodes ? EX_INQ_NODE_SETS : EX_INQ_SIDE_SETS), path, what);
  std::vector<ResultsSet> sets(static_cast<std::size_t>(n));
  if (n == 0) return sets;
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(id, type, ids.data()), path << ": cannot read the " << what << " ids");
  const auto names = exodus::get_names(id, type, n, path);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    auto& set = sets[k];
    set.id = static_cast<int>(ids[k]);
    set.name = names[k].empty() ? std::string(nodes ? "nodeset_" : "sideset_") + std::to_string(ids[k]) : names[k];
    std::int64_t count = 0, factors = 0;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_set_param(id, type, ids[k], &count, &factors),
                              path << ": cannot read " << what << " " << ids[k]);
    checked_count(count, path, what);
    std::vector<std::int64_t> entries(static_cast<std::size_t>(count)), sides(nodes ? 0 : entries.size());
    if (count > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_set(id, type, ids[k], entries.data(), nodes ? nullptr : sides.data()),
                                path << ": cannot read " << what << " " << ids[k]);
    std::vector<std::pair<GlobalId, int>> members;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(entries[i] >= 1 && entries[i] <= static_cast<std::int64_t>(map.size()),
                              path << ": " << what << " " << ids[k] << " refers to entry " << entries[i]
                                   << ", which the file does not have");
      const int edge = nodes ? 0 : static_cast<int>(sides[i]) - first_edge_side;
      SHELLFRAC_INPUT_REQUIRE(edge >= 0 && edge < 3, path << ": side set " << ids[k] << " has side " << sides[i]
                                                          << " (shell edges are sides 3 to 5)");
      members.push_back({map[static_cast<std::size_t>(entries[i] - 1)] - 1, edge});
    }
    std::sort(members.begin(), members.end());
    for (const auto& [entry, edge] : members) {
      set.entries.push_back(entry);
      if (!nodes) set.edges.push_back(edge);
    }
  }
  return sets;
}

/// Reads one results file; elements in file order (not yet sorted).
ExodusResults read_file(const std::string& path) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(fs::is_regular_file(path, ec), path << ": results file not found");
  exodus::File file = exodus::open_read(path);
  SHELLFRAC_INPUT_REQUIRE(file.is_open(), path << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
  const int id = file.id();
  const std::string not_ours = ": not a shellfrac DG results file: ";

  ex_init_params p{};
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_ext(id, &p), path << ": cannot read the Exodus header");
  SHELLFRAC_INPUT_REQUIRE(p.num_dim == 2 || p.num_dim == 3, path << not_ours << p.num_dim << "-D coordinates");
  const std::int64_t num_nodes = checked_count(p.num_nodes, path, "node");
  const std::int64_t num_elem = checked_count(p.num_elem, path, "element");
  const std::int64_t num_blk = checked_count(p.num_elem_blk, path, "element block");
  SHELLFRAC_INPUT_REQUIRE(num_blk > 0, path << not_ours << "no element blocks");

  ExodusResults r;
  r.title = p.title;
  std::vector<std::int64_t> ids(static_cast<std::size_t>(num_blk));
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(id, EX_ELEM_BLOCK, ids.data()), path << ": cannot read element block ids");
  const auto names = exodus::get_names(id, EX_ELEM_BLOCK, num_blk, path);
  int npe = 0;
  std::vector<std::int64_t> conn, block_count;
  for (std::size_t b = 0; b < ids.size(); ++b) {
    ex_block blk{};
    blk.id = ids[b];
    blk.type = EX_ELEM_BLOCK;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_block_param(id, &blk), path << ": cannot read element block " << ids[b]);
    blk.topology[MAX_STR_LENGTH] = '\0';
    const std::string type = exodus::upper(blk.topology);
    SHELLFRAC_INPUT_REQUIRE(ids[b] > 0 && ids[b] <= exodus::max_stored_int,
                            path << ": element block id " << ids[b] << " is out of range");
    checked_count(blk.num_entry, path, "block element");
    r.block_ids.push_back(static_cast<int>(ids[b]));
    r.block_names.push_back(names[b].empty() ? "block_" + std::to_string(ids[b]) : names[b]);
    block_count.push_back(blk.num_entry);
    if (blk.num_entry == 0) continue;  // Exodus stores empty blocks with type "NULL" and 0 nodes
    SHELLFRAC_INPUT_REQUIRE(type.rfind("TRI", 0) == 0 && (blk.num_nodes_per_entry == 3 || blk.num_nodes_per_entry == 6),
                            path << not_ours << "element block " << ids[b] << " has type '" << blk.topology
                                 << "' with " << blk.num_nodes_per_entry << " nodes (expected TRISHELL3/TRISHELL6)");
    if (npe == 0) npe = static_cast<int>(blk.num_nodes_per_entry);
    SHELLFRAC_INPUT_REQUIRE(npe == blk.num_nodes_per_entry,
                            path << not_ours << "element blocks mix " << npe << "- and " << blk.num_nodes_per_entry
                                 << "-node elements");
    SHELLFRAC_INPUT_REQUIRE(static_cast<std::int64_t>(r.element_block_ids.size()) + blk.num_entry <= num_elem,
                            path << ": the element blocks hold more elements than the header's " << num_elem);
    r.element_block_ids.insert(r.element_block_ids.end(), static_cast<std::size_t>(blk.num_entry),
                               static_cast<int>(ids[b]));
    std::vector<std::int64_t> c(static_cast<std::size_t>(blk.num_entry * npe));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id, EX_ELEM_BLOCK, ids[b], c.data(), nullptr, nullptr),
                              path << ": cannot read the connectivity of element block " << ids[b]);
    conn.insert(conn.end(), c.begin(), c.end());
  }
  r.nodes_per_element = npe;  // 0 for a file without elements (merge() takes it from the others)
  SHELLFRAC_INPUT_REQUIRE(static_cast<std::int64_t>(r.element_block_ids.size()) == num_elem,
                          path << ": the element blocks hold " << r.element_block_ids.size()
                               << " elements but the header says " << num_elem);
  SHELLFRAC_INPUT_REQUIRE(num_nodes == num_elem * npe || (num_elem == 0 && num_nodes <= 1), path << not_ours << num_nodes << " nodes for " << num_elem
                                                            << " elements of " << npe
                                                            << " nodes (DG nodes are not shared)");
  for (auto c : conn)
    SHELLFRAC_INPUT_REQUIRE(c >= 1 && c <= num_nodes, path << ": connectivity refers to node " << c
                                                           << " but the file has " << num_nodes << " nodes");

  // Id maps: element gid = map - 1; DG node of (element, a) must have id gid * npe + a + 1.
  std::vector<std::int64_t> emap, nmap;
  if (num_elem > 0) {
    emap.resize(static_cast<std::size_t>(num_elem)), nmap.resize(static_cast<std::size_t>(num_nodes));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id, EX_ELEM_MAP, emap.data()), path << ": cannot read the element id map");
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id, EX_NODE_MAP, nmap.data()), path << ": cannot read the node id map");
    for (std::size_t i = 0; i < emap.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(emap[i] >= 1, path << ": element id " << emap[i] << " is not positive");
      const GlobalId gid = emap[i] - 1;
      r.element_gids.push_back(gid);
      for (int a = 0; a < npe; ++a) {
        const std::int64_t node = conn[i * npe + a] - 1;
        SHELLFRAC_INPUT_REQUIRE(nmap[static_cast<std::size_t>(node)] == gid * npe + a + 1,
                                path << not_ours << "node " << node + 1 << " (node " << a + 1 << " of element id "
                                     << emap[i] << ") has id " << nmap[static_cast<std::size_t>(node)] << ", expected "
                                     << gid * npe + a + 1);
      }
    }
    std::vector<double> x(static_cast<std::size_t>(num_nodes)), y(x.size()), z(x.size(), 0.0);
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id, x.data(), y.data(), p.num_dim == 3 ? z.data() : nullptr),
                              path << ": cannot read the coordinates");
    for (auto c : conn) {
      const auto n = static_cast<std::size_t>(c - 1);
      r.node_coords.push_back({x[n], y[n], z[n]});
    }
  }

  r.node_sets = read_sets(id, EX_NODE_SET, nmap, path);
  r.side_sets = read_sets(id, EX_SIDE_SET, emap, path);

  // Variables and steps.
  const std::int64_t num_steps = ex_inquire_int(id, EX_INQ_TIME);
  checked_count(num_steps, path, "time step");
  r.times.assign(static_cast<std::size_t>(num_steps), 0.0);
  if (num_steps > 0) SHELLFRAC_EXO_INPUT_CHECK(ex_get_all_times(id, r.times.data()), path << ": cannot read the times");
  int nv = 0, ev = 0;
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id, EX_NODAL, &nv), path << ": cannot read the nodal variables");
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id, EX_ELEM_BLOCK, &ev), path << ": cannot read the element variables");
  checked_count(nv, path, "nodal variable");
  checked_count(ev, path, "element variable");
  r.nodal_names = exodus::get_names(id, EX_NODAL, nv, path, true);
  r.element_names = exodus::get_names(id, EX_ELEM_BLOCK, ev, path, true);
  int gv = 0;
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id, EX_GLOBAL, &gv), path << ": cannot read the global variables");
  checked_count(gv, path, "global variable");
  r.global_names = exodus::get_names(id, EX_GLOBAL, gv, path, true);
  std::vector<int> truth(static_cast<std::size_t>(num_blk * ev), 1);
  if (ev > 0)
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_truth_table(id, EX_ELEM_BLOCK, static_cast<int>(num_blk), ev, truth.data()),
                              path << ": cannot read the element variable truth table");

  const auto ne = static_cast<std::size_t>(num_elem);
  std::vector<double> buf;
  for (int step = 1; step <= num_steps; ++step) {
    std::vector<std::vector<double>> nodal(static_cast<std::size_t>(nv)), element(static_cast<std::size_t>(ev));
    for (int v = 0; v < nv; ++v) {
      if (num_nodes == 0) continue;
      buf.assign(static_cast<std::size_t>(num_nodes), 0.0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id, step, EX_NODAL, v + 1, 1, num_nodes, buf.data()),
                                path << ": cannot read nodal variable '" << r.nodal_names[v] << "' at step " << step);
      auto& out = nodal[v];
      out.reserve(conn.size());
      for (auto c : conn) out.push_back(buf[static_cast<std::size_t>(c - 1)]);
    }
    for (int v = 0; v < ev; ++v) {
      auto& out = element[v];
      out.reserve(ne);
      for (std::size_t b = 0; b < ids.size(); ++b) {
        const std::int64_t n = block_count[b];
        if (n == 0) continue;
        if (truth[b * ev + v] == 0) {  // not stored for this block
          out.insert(out.end(), static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
          continue;
        }
        buf.assign(static_cast<std::size_t>(n), 0.0);
        SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id, step, EX_ELEM_BLOCK, v + 1, ids[b], n, buf.data()),
                                  path << ": cannot read element variable '" << r.element_names[v] << "' of block "
                                       << ids[b] << " at step " << step);
        out.insert(out.end(), buf.begin(), buf.end());
      }
    }
    std::vector<double> global(static_cast<std::size_t>(gv), 0.0);
    if (gv > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id, step, EX_GLOBAL, 1, 0, gv, global.data()),
                                path << ": cannot read the global variables at step " << step);
    r.nodal.push_back(std::move(nodal));
    r.element.push_back(std::move(element));
    r.global.push_back(std::move(global));
  }

  const std::int64_t num_info = ex_inquire_int(id, EX_INQ_INFO);
  checked_count(num_info, path, "information record");
  if (num_info > 0) {
    std::vector<std::vector<char>> lines(static_cast<std::size_t>(num_info),
                                         std::vector<char>(MAX_LINE_LENGTH + 2, '\0'));
    std::vector<char*> ptr;
    for (auto& l : lines) ptr.push_back(l.data());
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_info(id, ptr.data()), path << ": cannot read the information records");
    for (auto& l : lines) {
      l.back() = '\0';
      r.info.emplace_back(l.data());
    }
  }
  return r;
}

/// The union of the sets of every file (each file declares the same sets), sorted.
std::vector<ResultsSet> merge_sets(const std::vector<ExodusResults>& parts, const std::vector<std::string>& files,
                                   std::vector<ResultsSet> ExodusResults::*sets) {
  std::vector<ResultsSet> out = parts.front().*sets;
  for (auto& set : out) set.entries.clear(), set.edges.clear();
  for (std::size_t f = 0; f < parts.size(); ++f) {
    const auto& mine = parts[f].*sets;
    SHELLFRAC_INPUT_REQUIRE(mine.size() == out.size(), files[f] << " differs from " << files.front()
                                                                << " (not the same data set): node or side sets");
    for (std::size_t k = 0; k < out.size(); ++k) {
      SHELLFRAC_INPUT_REQUIRE(mine[k].name == out[k].name && mine[k].id == out[k].id,
                              files[f] << " differs from " << files.front() << " (not the same data set): set "
                                       << out[k].name);
      out[k].entries.insert(out[k].entries.end(), mine[k].entries.begin(), mine[k].entries.end());
      out[k].edges.insert(out[k].edges.end(), mine[k].edges.begin(), mine[k].edges.end());
    }
  }
  for (auto& set : out) {
    std::vector<std::pair<GlobalId, int>> members;
    for (std::size_t i = 0; i < set.entries.size(); ++i)
      members.push_back({set.entries[i], set.edges.empty() ? 0 : set.edges[i]});
    std::sort(members.begin(), members.end());
    const bool sides = !set.edges.empty();
    set.entries.clear(), set.edges.clear();
    for (const auto& [entry, edge] : members) {
      set.entries.push_back(entry);
      if (sides) set.edges.push_back(edge);
    }
  }
  return out;
}

/// Merges files read by read_file into one data set sorted by element gid.
ExodusResults merge(std::vector<ExodusResults>& parts, const std::vector<std::string>& files) {
  ExodusResults out;
  const ExodusResults& first = parts.front();
  out.nodes_per_element = 3;  // only matters when no file has elements
  for (const auto& q : parts)
    if (q.nodes_per_element != 0) {
      out.nodes_per_element = q.nodes_per_element;
      break;
    }
  out.block_ids = first.block_ids;
  out.block_names = first.block_names;
  out.times = first.times;
  out.nodal_names = first.nodal_names;
  out.element_names = first.element_names;
  out.global_names = first.global_names;
  out.global = first.global;  // every file of a set holds the same global values
  out.info = first.info;
  out.title = first.title;
  out.node_sets = merge_sets(parts, files, &ExodusResults::node_sets);
  out.side_sets = merge_sets(parts, files, &ExodusResults::side_sets);
  out.num_files = static_cast<int>(parts.size());
  const std::string differs = " differs from " + files.front() + " (not the same data set): ";
  for (std::size_t f = 1; f < parts.size(); ++f) {
    const auto& q = parts[f];
    SHELLFRAC_INPUT_REQUIRE(q.nodes_per_element == out.nodes_per_element || q.nodes_per_element == 0,
                            files[f] << differs << "nodes per element");
    SHELLFRAC_INPUT_REQUIRE(q.block_ids == out.block_ids && q.block_names == out.block_names,
                            files[f] << differs << "element blocks");
    SHELLFRAC_INPUT_REQUIRE(q.times == out.times, files[f] << differs << "time steps");
    SHELLFRAC_INPUT_REQUIRE(q.nodal_names == out.nodal_names && q.element_names == out.element_names &&
                                q.global_names == out.global_names,
                            files[f] << differs << "variable names");
    // Every rank of a run writes the same title and the same global values (the history at each frame): files of
    // two runs of one deck with other physics, or restarted differently, differ there.
    SHELLFRAC_INPUT_REQUIRE(q.title == out.title, files[f] << differs << "title ('" << q.title << "')");
    SHELLFRAC_INPUT_REQUIRE(q.global == out.global, files[f] << differs
                                                            << "global values (the run's history at each frame): "
                                                               "the files were written by different runs");
  }
  // (gid, file, index in file), sorted by gid.
  struct Where {
    GlobalId gid;
    std::size_t file, index;
  };
  std::vector<Where> all;
  for (std::size_t f = 0; f < parts.size(); ++f)
    for (std::size_t i = 0; i < parts[f].element_gids.size(); ++i) all.push_back({parts[f].element_gids[i], f, i});
  std::sort(all.begin(), all.end(), [](const Where& a, const Where& b) { return a.gid < b.gid; });
  for (std::size_t k = 1; k < all.size(); ++k)
    SHELLFRAC_INPUT_REQUIRE(all[k - 1].gid != all[k].gid, "element id " << all[k].gid + 1 << " appears in both "
                                                                         << files[all[k - 1].file] << " and "
                                                                         << files[all[k].file]);
  const std::size_t npe = static_cast<std::size_t>(out.nodes_per_element);
  const std::size_t steps = out.times.size(), nv = out.nodal_names.size(), ev = out.element_names.size();
  out.nodal.assign(steps, std::vector<std::vector<double>>(nv));
  out.element.assign(steps, std::vector<std::vector<double>>(ev));
  for (const auto& w : all) {
    const auto& q = parts[w.file];
    out.element_gids.push_back(w.gid);
    out.element_block_ids.push_back(q.element_block_ids[w.index]);
    for (std::size_t a = 0; a < npe; ++a) out.node_coords.push_back(q.node_coords[w.index * npe + a]);
    for (std::size_t s = 0; s < steps; ++s) {
      for (std::size_t v = 0; v < nv; ++v)
        for (std::size_t a = 0; a < npe; ++a) out.nodal[s][v].push_back(q.nodal[s][v][w.index * npe + a]);
      for (std::size_t v = 0; v < ev; ++v) out.element[s][v].push_back(q.element[s][v][w.index]);
    }
  }
  return out;
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// ------------------------------------------------------------------------------------------------ compare

/// Collects differences, keeping at most `max` lines (the last one says how many were left out).
class Report {
 public:
  explicit Report(std::size_t max) : max_(std::max<std::size_t>(max, 1)) {}
  void add(const std::string& line) {
    ++total_;
    if (lines_.size() < max_) lines_.push_back(line);
  }
  std::vector<std::string> finish() {
    if (total_ > lines_.size())
      lines_.back() = "... " + std::to_string(total_ - lines_.size() + 1) + " more differences not shown (" +
                      std::to_string(total_) + " in all)";
    return std::move(lines_);
  }

 private:
  std::size_t max_, total_ = 0;
  std::vector<std::string> lines_;
};

std::string num(double x) {
  std::ostringstream os;
  os << std::setprecision(16) << x;
  return os.str();
}

/// Worst out-of-tolerance value of one variable (over all steps and entities).
struct Worst {
  std::size_t count = 0;
  double diff = -1, a = 0, b = 0, tol = 0;
  std::string where;
  /// Checks one pair; `where` is called only when the pair differs.
  template <class Where>
  void check(double x, double y, double abs_tol, double rel_tol, Where&& where_fn) {
    if (x == y || (std::isnan(x) && std::isnan(y))) return;
    const double tol_here = std::max(abs_tol, rel_tol * std::max(std::abs(x), std::abs(y)));
    double d = std::abs(x - y);
    if (d <= tol_here) return;
    if (std::isnan(d)) d = std::numeric_limits<double>::infinity();
    ++count;
    if (d > diff) {
      diff = d;
      a = x;
      b = y;
      tol = tol_here;
      where = where_fn();
    }
  }
  void report(Report& rep, const std::string& what) const {
    if (count == 0) return;
    rep.add(what + ": " + std::to_string(count) + " value" + (count == 1 ? "" : "s") +
            " out of tolerance; largest at " + where + ": A = " + num(a) + ", B = " + num(b) +
            ", |A - B| = " + num(diff) + " > tolerance " + num(tol));
  }
};

template <class T>
std::string first_few(const std::vector<T>& v) {
  std::ostringstream os;
  for (std::size_t i = 0; i < v.size() && i < 5; ++i) os << (i ? ", " : "") << v[i];
  if (v.size() > 5) os << ", ...";
  return os.str();
}

}  // namespace

// ------------------------------------------------------------------------------------------------ public

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
  // Every rank learns whether every file took the frame: a failed write stops all ranks at once (exit 6).
  int index = 0;
  parallel::on_all_then_agree([&] { index = w.put_step(time, nodal_variable, element_ptr, global.data()); },
                              impl_->comm);
  return index;
}

std::vector<std::string> find_rank_files(const std::string& path) {
  const fs::path p(path);
  const std::string base = p.filename().string();
  fs::path dir = p.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (base.empty() || !fs::is_directory(dir, ec)) return {};
  std::map<int, std::set<int>> sets;  // np -> ranks present
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= base.size() + 1 || name.compare(0, base.size() + 1, base + ".") != 0) continue;
    const std::string rest = name.substr(base.size() + 1);
    const auto dot = rest.find('.');
    if (dot == std::string::npos) continue;
    const std::string s_np = rest.substr(0, dot), s_rank = rest.substr(dot + 1);
    if (!all_digits(s_np) || !all_digits(s_rank) || s_np.size() > 6 || s_np.size() != s_rank.size()) continue;
    const int np = std::stoi(s_np), rank = std::stoi(s_rank);
    if (np < 2 || rank >= np || s_np != std::to_string(np)) continue;
    sets[np].insert(rank);
  }
  if (sets.empty()) return {};
  if (sets.size() > 1) {
    std::ostringstream os;
    for (const auto& [np, ranks] : sets) os << (os.tellp() > 0 ? ", " : "") << np;
    SHELLFRAC_INPUT_REQUIRE(false, path << ": several per-rank sets are present (np = " << os.str()
                                        << "); remove the stale files");
  }
  const int np = sets.begin()->first;
  std::vector<std::string> files;
  for (int r = 0; r < np; ++r) {
    files.push_back(rank_file_name(path, np, r));
    SHELLFRAC_INPUT_REQUIRE(sets.begin()->second.count(r), path << ": the per-rank set for np = " << np
                                                                << " is incomplete: " << files.back()
                                                                << " is missing");
  }
  return files;
}

ExodusResults read_results_files(const std::vector<std::string>& files) {
  SHELLFRAC_INPUT_REQUIRE(!files.empty(), "read_results_files: no files given");
  std::vector<ExodusResults> parts;
  try {
    for (const auto& f : files) parts.push_back(read_file(f));
    auto out = merge(parts, files);
    return out;
  } catch (const std::bad_alloc&) {
    SHELLFRAC_INPUT_REQUIRE(false, files.front() << ": the results file(s) declare more data than fits in memory");
  } catch (const std::length_error&) {
    SHELLFRAC_INPUT_REQUIRE(false, files.front() << ": the results file(s) declare more data than fits in memory");
  }
  return {};
}

ExodusResults read_results(const std::string& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return read_results_files({path});
  const auto files = find_rank_files(path);
  SHELLFRAC_INPUT_REQUIRE(!files.empty(), path << ": no such results file, and no per-rank set " << path
                                               << ".<np>.<rank>");
  return read_results_files(files);
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

CompareTolerances CompareTolerances::from_file(const std::string& path) {
  std::ifstream in(path);
  SHELLFRAC_INPUT_REQUIRE(in, path << ": cannot open the tolerance file");
  CompareTolerances t;
  std::set<std::string> seen;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string name;
    if (!(words >> name)) continue;
    const std::string where = path + ":" + std::to_string(lineno) + ": ";
    SHELLFRAC_INPUT_REQUIRE(seen.insert(name).second, where << "'" << name << "' is given twice");
    double abs_tol = 0, rel_tol = 0;
    std::string key;
    std::set<std::string> keys;
    while (words >> key) {
      std::string value;
      SHELLFRAC_INPUT_REQUIRE(words >> value, where << "'" << key << "' needs a value");
      const bool is_abs = key == "absolute" || key == "abs";
      const bool is_rel = key == "relative" || key == "rel";
      SHELLFRAC_INPUT_REQUIRE(is_abs || is_rel, where << "unknown keyword '" << key
                                                      << "' (expected 'absolute A' and/or 'relative R')");
      SHELLFRAC_INPUT_REQUIRE(keys.insert(is_abs ? "absolute" : "relative").second,
                              where << "'" << key << "' is given twice");
      std::size_t used = 0;
      double x = 0;
      try {
        x = std::stod(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      SHELLFRAC_INPUT_REQUIRE(used == value.size() && std::isfinite(x) && x >= 0,
                              where << "'" << value << "' is not a non-negative number");
      (is_abs ? abs_tol : rel_tol) = x;
    }
    if (name == "default") {
      t.default_abs = abs_tol;
      t.default_rel = rel_tol;
    } else {
      t.per_variable.push_back({name, abs_tol, rel_tol});
    }
  }
  return t;
}

std::vector<std::string> compare_results(const ExodusResults& a, const ExodusResults& b, const CompareTolerances& tol,
                                         std::size_t max_report) {
  Report rep(max_report);
  // Tolerance of a variable: its own entry, else that of its vector (displ for displ_x), else the default.
  auto lookup = [&](const std::string& name) -> std::pair<double, double> {
    auto find = [&](const std::string& n) -> const CompareTolerances::Entry* {
      for (const auto& e : tol.per_variable)
        if (e.name == n) return &e;
      return nullptr;
    };
    const CompareTolerances::Entry* e = find(name);
    if (!e && name.size() > 2)
      for (const char* suffix : component_suffix)
        if (name.compare(name.size() - 2, 2, suffix) == 0) e = find(name.substr(0, name.size() - 2));
    return e ? std::make_pair(e->abs, e->rel) : std::make_pair(tol.default_abs, tol.default_rel);
  };

  if (a.nodes_per_element != b.nodes_per_element) {
    rep.add("nodes per element differ: A " + std::to_string(a.nodes_per_element) + ", B " +
            std::to_string(b.nodes_per_element));
    return rep.finish();
  }
  const std::size_t npe = static_cast<std::size_t>(a.nodes_per_element);
  for (const auto& [sa, sb, what] : {std::tuple{&a.node_sets, &b.node_sets, "node set"},
                                     std::tuple{&a.side_sets, &b.side_sets, "side set"}}) {
    if (*sa == *sb) continue;
    std::string first = sa->size() != sb->size() ? std::string("their number") : std::string();
    for (std::size_t k = 0; first.empty() && k < sa->size(); ++k)
      if (!((*sa)[k] == (*sb)[k])) first = "'" + (*sa)[k].name + "' (id " + std::to_string((*sa)[k].id) + ")";
    rep.add(std::string(what) + "s differ: " + first);
  }

  // Elements: compare those present in both; report the others.
  std::vector<std::pair<std::size_t, std::size_t>> common;
  std::vector<GlobalId> only_a, only_b;
  for (std::size_t i = 0, j = 0; i < a.element_gids.size() || j < b.element_gids.size();) {
    if (j == b.element_gids.size() || (i < a.element_gids.size() && a.element_gids[i] < b.element_gids[j]))
      only_a.push_back(a.element_gids[i++]);
    else if (i == a.element_gids.size() || b.element_gids[j] < a.element_gids[i])
      only_b.push_back(b.element_gids[j++]);
    else
      common.emplace_back(i++, j++);
  }
  if (!only_a.empty())
    rep.add(std::to_string(only_a.size()) + " element(s) only in A, gids: " + first_few(only_a));
  if (!only_b.empty())
    rep.add(std::to_string(only_b.size()) + " element(s) only in B, gids: " + first_few(only_b));

  // Blocks.
  std::map<int, std::string> names_a, names_b;
  for (std::size_t k = 0; k < a.block_ids.size() && k < a.block_names.size(); ++k) names_a[a.block_ids[k]] = a.block_names[k];
  for (std::size_t k = 0; k < b.block_ids.size() && k < b.block_names.size(); ++k) names_b[b.block_ids[k]] = b.block_names[k];
  if (names_a != names_b) {
    std::ostringstream os;
    os << "element blocks differ: A {";
    for (const auto& [id, n] : names_a) os << " " << id << ":'" << n << "'";
    os << " }, B {";
    for (const auto& [id, n] : names_b) os << " " << id << ":'" << n << "'";
    os << " }";
    rep.add(os.str());
  }
  std::size_t block_diffs = 0;
  std::string first_block_diff;
  for (const auto& [i, j] : common)
    if (a.element_block_ids[i] != b.element_block_ids[j] && block_diffs++ == 0)
      first_block_diff = "element gid " + std::to_string(a.element_gids[i]) + " is in block " +
                         std::to_string(a.element_block_ids[i]) + " in A, " + std::to_string(b.element_block_ids[j]) +
                         " in B";
  if (block_diffs > 0) rep.add(std::to_string(block_diffs) + " element(s) in different blocks; first: " + first_block_diff);

  // Coordinates.
  {
    const auto [ta, tr] = lookup("coordinates");
    Worst w;
    for (const auto& [i, j] : common)
      for (std::size_t n = 0; n < npe; ++n)
        for (int c = 0; c < 3; ++c)
          w.check(a.node_coords[i * npe + n][c], b.node_coords[j * npe + n][c], ta, tr, [&, i = i] {
            return "element gid " + std::to_string(a.element_gids[i]) + ", local node " + std::to_string(n) +
                   " (DG node gid " + std::to_string(a.element_gids[i] * static_cast<GlobalId>(npe) +
                                                     static_cast<GlobalId>(n)) +
                   "), component " + "xyz"[c];
          });
    w.report(rep, "coordinates");
  }

  // Times.
  if (a.times.size() != b.times.size())
    rep.add("number of time steps differs: A " + std::to_string(a.times.size()) + ", B " +
            std::to_string(b.times.size()) + " (the common steps are compared)");
  const std::size_t steps = std::min(a.times.size(), b.times.size());
  {
    const auto [ta, tr] = lookup("time");
    Worst w;
    for (std::size_t s = 0; s < steps; ++s)
      w.check(a.times[s], b.times[s], ta, tr, [&] { return "step " + std::to_string(s + 1); });
    w.report(rep, "time");
  }

  // Variables, matched by name.
  auto compare_vars = [&](const std::vector<std::string>& na, const std::vector<std::string>& nb, bool nodal) {
    const char* kind = nodal ? "nodal variable" : "element variable";
    for (const auto& n : na)
      if (std::find(nb.begin(), nb.end(), n) == nb.end()) rep.add(std::string(kind) + " '" + n + "' only in A");
    for (const auto& n : nb)
      if (std::find(na.begin(), na.end(), n) == na.end()) rep.add(std::string(kind) + " '" + n + "' only in B");
    for (std::size_t va = 0; va < na.size(); ++va) {
      const auto it = std::find(nb.begin(), nb.end(), na[va]);
      if (it == nb.end()) continue;
      const auto vb = static_cast<std::size_t>(it - nb.begin());
      const auto [ta, tr] = lookup(na[va]);
      Worst w;
      for (std::size_t s = 0; s < steps; ++s) {
        const auto& xa = nodal ? a.nodal[s][va] : a.element[s][va];
        const auto& xb = nodal ? b.nodal[s][vb] : b.element[s][vb];
        auto where = [&](std::size_t i, std::size_t n) {
          std::string w = "step " + std::to_string(s + 1) + " (t = " + num(a.times[s]) + "), element gid " +
                          std::to_string(a.element_gids[i]);
          if (nodal)
            w += ", local node " + std::to_string(n) + " (DG node gid " +
                 std::to_string(a.element_gids[i] * static_cast<GlobalId>(npe) + static_cast<GlobalId>(n)) + ")";
          return w;
        };
        for (const auto& [i, j] : common) {
          if (nodal) {
            for (std::size_t n = 0; n < npe; ++n)
              w.check(xa[i * npe + n], xb[j * npe + n], ta, tr, [&, i = i] { return where(i, n); });
          } else {
            w.check(xa[i], xb[j], ta, tr, [&, i = i] { return where(i, 0); });
          }
        }
      }
      w.report(rep, std::string(kind) + " '" + na[va] + "'");
    }
  };
  compare_vars(a.nodal_names, b.nodal_names, true);
  compare_vars(a.element_names, b.element_names, false);
  for (const auto& n : a.global_names)
    if (std::find(b.global_names.begin(), b.global_names.end(), n) == b.global_names.end())
      rep.add("global variable '" + n + "' only in A");
  for (const auto& n : b.global_names)
    if (std::find(a.global_names.begin(), a.global_names.end(), n) == a.global_names.end())
      rep.add("global variable '" + n + "' only in B");
  for (std::size_t va = 0; va < a.global_names.size(); ++va) {
    const auto it = std::find(b.global_names.begin(), b.global_names.end(), a.global_names[va]);
    if (it == b.global_names.end()) continue;
    const auto vb = static_cast<std::size_t>(it - b.global_names.begin());
    const auto [ta, tr] = lookup(a.global_names[va]);
    Worst w;
    for (std::size_t s = 0; s < steps; ++s)
      w.check(a.global[s][va], b.global[s][vb], ta, tr,
              [&] { return "step " + std::to_string(s + 1) + " (t = " + num(a.times[s]) + ")"; });
    w.report(rep, "global variable '" + a.global_names[va] + "'");
  }
  return rep.finish();
}

}  // namespace shellfrac::io
