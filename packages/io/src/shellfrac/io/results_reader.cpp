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

}  // namespace shellfrac::io
