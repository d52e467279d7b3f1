#include "shellfrac/io/results_reader.hpp"

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
#include "shellfrac/io/results_conventions.hpp"

namespace shellfrac::io {

namespace fs = std::filesystem;

namespace {

/// Largest count accepted from a file header before allocating.
constexpr std::int64_t max_count = std::int64_t{1} << 31;

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
class ResultsFileReader {
 public:
  explicit ResultsFileReader(const std::string& path) : path_(path) {}

  ExodusResults read() {
    std::error_code ec;
    SHELLFRAC_INPUT_REQUIRE(fs::is_regular_file(path_, ec), path_ << ": results file not found");
    exodus::File file = exodus::open_read(path_);
    SHELLFRAC_INPUT_REQUIRE(file.is_open(),
                            path_ << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
    id_ = file.id();
    read_header();
    read_blocks();
    read_id_maps_and_coordinates();
    r_.node_sets = read_sets(id_, EX_NODE_SET, nmap_, path_);
    r_.side_sets = read_sets(id_, EX_SIDE_SET, emap_, path_);
    read_variable_names();
    for (int step = 1; step <= static_cast<int>(r_.times.size()); ++step) read_step(step);
    read_info();
    return std::move(r_);
  }

 private:
  static constexpr const char* not_ours = ": not a shellfrac DG results file: ";

  void read_header() {
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_ext(id_, &p_), path_ << ": cannot read the Exodus header");
    SHELLFRAC_INPUT_REQUIRE(p_.num_dim == 2 || p_.num_dim == 3, path_ << not_ours << p_.num_dim << "-D coordinates");
    num_nodes_ = checked_count(p_.num_nodes, path_, "node");
    num_elem_ = checked_count(p_.num_elem, path_, "element");
    num_blk_ = checked_count(p_.num_elem_blk, path_, "element block");
    SHELLFRAC_INPUT_REQUIRE(num_blk_ > 0, path_ << not_ours << "no element blocks");
    r_.title = p_.title;
  }

  void read_blocks() {
    block_ids_.assign(static_cast<std::size_t>(num_blk_), 0);
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(id_, EX_ELEM_BLOCK, block_ids_.data()),
                              path_ << ": cannot read element block ids");
    const auto names = exodus::get_names(id_, EX_ELEM_BLOCK, num_blk_, path_);
    for (std::size_t b = 0; b < block_ids_.size(); ++b) read_block(block_ids_[b], names[b]);
    r_.nodes_per_element = npe_;  // 0 for a file without elements (merge() takes it from the others)
    SHELLFRAC_INPUT_REQUIRE(static_cast<std::int64_t>(r_.element_block_ids.size()) == num_elem_,
                            path_ << ": the element blocks hold " << r_.element_block_ids.size()
                                  << " elements but the header says " << num_elem_);
    SHELLFRAC_INPUT_REQUIRE(num_nodes_ == num_elem_ * npe_ || (num_elem_ == 0 && num_nodes_ <= 1),
                            path_ << not_ours << num_nodes_ << " nodes for " << num_elem_ << " elements of " << npe_
                                  << " nodes (DG nodes are not shared)");
    for (auto c : conn_)
      SHELLFRAC_INPUT_REQUIRE(c >= 1 && c <= num_nodes_, path_ << ": connectivity refers to node " << c
                                                               << " but the file has " << num_nodes_ << " nodes");
  }

  void read_block(std::int64_t block_id, const std::string& name) {
    ex_block blk{};
    blk.id = block_id;
    blk.type = EX_ELEM_BLOCK;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_block_param(id_, &blk), path_ << ": cannot read element block " << block_id);
    blk.topology[MAX_STR_LENGTH] = '\0';
    const std::string type = exodus::upper(blk.topology);
    SHELLFRAC_INPUT_REQUIRE(block_id > 0 && block_id <= exodus::max_stored_int,
                            path_ << ": element block id " << block_id << " is out of range");
    checked_count(blk.num_entry, path_, "block element");
    r_.block_ids.push_back(static_cast<int>(block_id));
    r_.block_names.push_back(name.empty() ? "block_" + std::to_string(block_id) : name);
    block_count_.push_back(blk.num_entry);
    if (blk.num_entry == 0) return;  // Exodus stores empty blocks with type "NULL" and 0 nodes
    SHELLFRAC_INPUT_REQUIRE(type.rfind("TRI", 0) == 0 && (blk.num_nodes_per_entry == 3 || blk.num_nodes_per_entry == 6),
                            path_ << not_ours << "element block " << block_id << " has type '" << blk.topology
                                  << "' with " << blk.num_nodes_per_entry << " nodes (expected TRISHELL3/TRISHELL6)");
    if (npe_ == 0) npe_ = static_cast<int>(blk.num_nodes_per_entry);
    SHELLFRAC_INPUT_REQUIRE(npe_ == blk.num_nodes_per_entry,
                            path_ << not_ours << "element blocks mix " << npe_ << "- and " << blk.num_nodes_per_entry
                                  << "-node elements");
    SHELLFRAC_INPUT_REQUIRE(static_cast<std::int64_t>(r_.element_block_ids.size()) + blk.num_entry <= num_elem_,
                            path_ << ": the element blocks hold more elements than the header's " << num_elem_);
    r_.element_block_ids.insert(r_.element_block_ids.end(), static_cast<std::size_t>(blk.num_entry),
                                static_cast<int>(block_id));
    std::vector<std::int64_t> c(static_cast<std::size_t>(blk.num_entry * npe_));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id_, EX_ELEM_BLOCK, block_id, c.data(), nullptr, nullptr),
                              path_ << ": cannot read the connectivity of element block " << block_id);
    conn_.insert(conn_.end(), c.begin(), c.end());
  }

  /// Id maps: element gid = map - 1; DG node of (element, a) must have id gid * npe + a + 1.
  void read_id_maps_and_coordinates() {
    if (num_elem_ == 0) return;
    emap_.resize(static_cast<std::size_t>(num_elem_)), nmap_.resize(static_cast<std::size_t>(num_nodes_));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id_, EX_ELEM_MAP, emap_.data()), path_ << ": cannot read the element id map");
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id_, EX_NODE_MAP, nmap_.data()), path_ << ": cannot read the node id map");
    for (std::size_t i = 0; i < emap_.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(emap_[i] >= 1, path_ << ": element id " << emap_[i] << " is not positive");
      const GlobalId gid = emap_[i] - 1;
      r_.element_gids.push_back(gid);
      for (int a = 0; a < npe_; ++a) {
        const std::int64_t node = conn_[i * npe_ + a] - 1;
        SHELLFRAC_INPUT_REQUIRE(nmap_[static_cast<std::size_t>(node)] == gid * npe_ + a + 1,
                                path_ << not_ours << "node " << node + 1 << " (node " << a + 1 << " of element id "
                                      << emap_[i] << ") has id " << nmap_[static_cast<std::size_t>(node)]
                                      << ", expected " << gid * npe_ + a + 1);
      }
    }
    std::vector<double> x(static_cast<std::size_t>(num_nodes_)), y(x.size()), z(x.size(), 0.0);
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id_, x.data(), y.data(), p_.num_dim == 3 ? z.data() : nullptr),
                              path_ << ": cannot read the coordinates");
    for (auto c : conn_) {
      const auto n = static_cast<std::size_t>(c - 1);
      r_.node_coords.push_back({x[n], y[n], z[n]});
    }
  }

  /// The times, the variable names and the element variable truth table.
  void read_variable_names() {
    const std::int64_t num_steps = ex_inquire_int(id_, EX_INQ_TIME);
    checked_count(num_steps, path_, "time step");
    r_.times.assign(static_cast<std::size_t>(num_steps), 0.0);
    if (num_steps > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_all_times(id_, r_.times.data()), path_ << ": cannot read the times");
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id_, EX_NODAL, &nv_), path_ << ": cannot read the nodal variables");
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id_, EX_ELEM_BLOCK, &ev_),
                              path_ << ": cannot read the element variables");
    checked_count(nv_, path_, "nodal variable");
    checked_count(ev_, path_, "element variable");
    r_.nodal_names = exodus::get_names(id_, EX_NODAL, nv_, path_, true);
    r_.element_names = exodus::get_names(id_, EX_ELEM_BLOCK, ev_, path_, true);
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_variable_param(id_, EX_GLOBAL, &gv_), path_ << ": cannot read the global variables");
    checked_count(gv_, path_, "global variable");
    r_.global_names = exodus::get_names(id_, EX_GLOBAL, gv_, path_, true);
    truth_.assign(static_cast<std::size_t>(num_blk_ * ev_), 1);
    if (ev_ > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_truth_table(id_, EX_ELEM_BLOCK, static_cast<int>(num_blk_), ev_, truth_.data()),
                                path_ << ": cannot read the element variable truth table");
  }

  void read_step(int step) {
    std::vector<std::vector<double>> nodal(static_cast<std::size_t>(nv_)), element(static_cast<std::size_t>(ev_));
    for (int v = 0; v < nv_; ++v) {
      if (num_nodes_ == 0) continue;
      buf_.assign(static_cast<std::size_t>(num_nodes_), 0.0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id_, step, EX_NODAL, v + 1, 1, num_nodes_, buf_.data()),
                                path_ << ": cannot read nodal variable '" << r_.nodal_names[v] << "' at step " << step);
      auto& out = nodal[v];
      out.reserve(conn_.size());
      for (auto c : conn_) out.push_back(buf_[static_cast<std::size_t>(c - 1)]);
    }
    for (int v = 0; v < ev_; ++v) element[v] = read_element_variable(step, v);
    std::vector<double> global(static_cast<std::size_t>(gv_), 0.0);
    if (gv_ > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id_, step, EX_GLOBAL, 1, 0, gv_, global.data()),
                                path_ << ": cannot read the global variables at step " << step);
    r_.nodal.push_back(std::move(nodal));
    r_.element.push_back(std::move(element));
    r_.global.push_back(std::move(global));
  }

  /// Element variable v at `step` over the blocks in order (NaN where the truth table says it is not stored).
  std::vector<double> read_element_variable(int step, int v) {
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(num_elem_));
    for (std::size_t b = 0; b < block_ids_.size(); ++b) {
      const std::int64_t n = block_count_[b];
      if (n == 0) continue;
      if (truth_[b * ev_ + v] == 0) {  // not stored for this block
        out.insert(out.end(), static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      buf_.assign(static_cast<std::size_t>(n), 0.0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_var(id_, step, EX_ELEM_BLOCK, v + 1, block_ids_[b], n, buf_.data()),
                                path_ << ": cannot read element variable '" << r_.element_names[v] << "' of block "
                                      << block_ids_[b] << " at step " << step);
      out.insert(out.end(), buf_.begin(), buf_.end());
    }
    return out;
  }

  void read_info() {
    const std::int64_t num_info = ex_inquire_int(id_, EX_INQ_INFO);
    checked_count(num_info, path_, "information record");
    if (num_info == 0) return;
    std::vector<std::vector<char>> lines(static_cast<std::size_t>(num_info),
                                         std::vector<char>(MAX_LINE_LENGTH + 2, '\0'));
    std::vector<char*> ptr;
    for (auto& l : lines) ptr.push_back(l.data());
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_info(id_, ptr.data()), path_ << ": cannot read the information records");
    for (auto& l : lines) {
      l.back() = '\0';
      r_.info.emplace_back(l.data());
    }
  }

  const std::string& path_;
  int id_ = -1;
  ex_init_params p_{};
  std::int64_t num_nodes_ = 0, num_elem_ = 0, num_blk_ = 0;
  int npe_ = 0;
  std::vector<std::int64_t> block_ids_, block_count_;
  std::vector<std::int64_t> conn_;          ///< 1-based file nodes of each element, file order
  std::vector<std::int64_t> emap_, nmap_;  ///< the element and node id maps
  int nv_ = 0, ev_ = 0, gv_ = 0;           ///< nodal, element and global variables
  std::vector<int> truth_;                 ///< element variable truth table, block-major
  std::vector<double> buf_;
  ExodusResults r_;
};

ExodusResults read_file(const std::string& path) { return ResultsFileReader(path).read(); }

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

}  // namespace

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

std::vector<double> read_result_times(const std::string& file) {
  exodus::File f = exodus::open_read(file);
  SHELLFRAC_INPUT_REQUIRE(f.is_open(), file << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
  const std::int64_t n = checked_count(ex_inquire_int(f.id(), EX_INQ_TIME), file, "time step");
  std::vector<double> times(static_cast<std::size_t>(n), 0.0);
  if (n > 0) SHELLFRAC_EXO_INPUT_CHECK(ex_get_all_times(f.id(), times.data()), file << ": cannot read the times");
  return times;
}

}  // namespace shellfrac::io
