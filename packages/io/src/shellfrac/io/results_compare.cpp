#include "shellfrac/io/results_compare.hpp"

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
