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

namespace {

/// One comparison of two results (A and B): structure first (element order, sets, elements, blocks), then
/// coordinates, times and the variables matched by name, each within its tolerance.
class ResultsComparison {
 public:
  ResultsComparison(const ExodusResults& a, const ExodusResults& b, const CompareTolerances& tol, std::size_t max_report)
      : a_(a), b_(b), tol_(tol), rep_(max_report) {}

  std::vector<std::string> run() {
    if (a_.nodes_per_element != b_.nodes_per_element) {
      rep_.add("nodes per element differ: A " + std::to_string(a_.nodes_per_element) + ", B " +
               std::to_string(b_.nodes_per_element));
      return rep_.finish();
    }
    npe_ = static_cast<std::size_t>(a_.nodes_per_element);
    compare_sets();
    match_elements();
    compare_blocks();
    compare_coordinates();
    compare_times();
    compare_field_variables(a_.nodal_names, b_.nodal_names, true);
    compare_field_variables(a_.element_names, b_.element_names, false);
    compare_global_variables();
    return rep_.finish();
  }

 private:
  /// Tolerance of a variable: its own entry, else that of its vector (displ for displ_x), else the default.
  std::pair<double, double> tolerance(const std::string& name) const {
    auto find = [&](const std::string& n) -> const CompareTolerances::Entry* {
      for (const auto& e : tol_.per_variable)
        if (e.name == n) return &e;
      return nullptr;
    };
    const CompareTolerances::Entry* e = find(name);
    if (!e && name.size() > 2)
      for (const char* suffix : component_suffix)
        if (name.compare(name.size() - 2, 2, suffix) == 0) e = find(name.substr(0, name.size() - 2));
    return e ? std::make_pair(e->abs, e->rel) : std::make_pair(tol_.default_abs, tol_.default_rel);
  }

  void compare_sets() {
    for (const auto& [sa, sb, what] : {std::tuple{&a_.node_sets, &b_.node_sets, "node set"},
                                       std::tuple{&a_.side_sets, &b_.side_sets, "side set"}}) {
      if (*sa == *sb) continue;
      std::string first = sa->size() != sb->size() ? std::string("their number") : std::string();
      for (std::size_t k = 0; first.empty() && k < sa->size(); ++k)
        if (!((*sa)[k] == (*sb)[k])) first = "'" + (*sa)[k].name + "' (id " + std::to_string((*sa)[k].id) + ")";
      rep_.add(std::string(what) + "s differ: " + first);
    }
  }

  /// Elements: those present in both are compared; the others are reported.
  void match_elements() {
    const auto& ga = a_.element_gids;
    const auto& gb = b_.element_gids;
    std::vector<GlobalId> only_a, only_b;
    for (std::size_t i = 0, j = 0; i < ga.size() || j < gb.size();) {
      if (j == gb.size() || (i < ga.size() && ga[i] < gb[j]))
        only_a.push_back(ga[i++]);
      else if (i == ga.size() || gb[j] < ga[i])
        only_b.push_back(gb[j++]);
      else
        common_.emplace_back(i++, j++);
    }
    if (!only_a.empty())
      rep_.add(std::to_string(only_a.size()) + " element(s) only in A, gids: " + first_few(only_a));
    if (!only_b.empty())
      rep_.add(std::to_string(only_b.size()) + " element(s) only in B, gids: " + first_few(only_b));
  }

  void compare_blocks() {
    std::map<int, std::string> names_a, names_b;
    for (std::size_t k = 0; k < a_.block_ids.size() && k < a_.block_names.size(); ++k)
      names_a[a_.block_ids[k]] = a_.block_names[k];
    for (std::size_t k = 0; k < b_.block_ids.size() && k < b_.block_names.size(); ++k)
      names_b[b_.block_ids[k]] = b_.block_names[k];
    if (names_a != names_b) {
      std::ostringstream os;
      os << "element blocks differ: A {";
      for (const auto& [id, n] : names_a) os << " " << id << ":'" << n << "'";
      os << " }, B {";
      for (const auto& [id, n] : names_b) os << " " << id << ":'" << n << "'";
      os << " }";
      rep_.add(os.str());
    }
    std::size_t block_diffs = 0;
    std::string first_block_diff;
    for (const auto& [i, j] : common_)
      if (a_.element_block_ids[i] != b_.element_block_ids[j] && block_diffs++ == 0)
        first_block_diff = "element gid " + std::to_string(a_.element_gids[i]) + " is in block " +
                           std::to_string(a_.element_block_ids[i]) + " in A, " +
                           std::to_string(b_.element_block_ids[j]) + " in B";
    if (block_diffs > 0)
      rep_.add(std::to_string(block_diffs) + " element(s) in different blocks; first: " + first_block_diff);
  }

  /// "element gid G, local node n (DG node gid D)" of A's element i.
  std::string dg_node(std::size_t i, std::size_t n) const {
    return "element gid " + std::to_string(a_.element_gids[i]) + ", local node " + std::to_string(n) +
           " (DG node gid " +
           std::to_string(a_.element_gids[i] * static_cast<GlobalId>(npe_) + static_cast<GlobalId>(n)) + ")";
  }

  void compare_coordinates() {
    const auto [ta, tr] = tolerance("coordinates");
    Worst w;
    for (const auto& [i, j] : common_)
      for (std::size_t n = 0; n < npe_; ++n)
        for (int c = 0; c < 3; ++c)
          w.check(a_.node_coords[i * npe_ + n][c], b_.node_coords[j * npe_ + n][c], ta, tr,
                  [&, i = i] { return dg_node(i, n) + ", component " + "xyz"[c]; });
    w.report(rep_, "coordinates");
  }

  void compare_times() {
    if (a_.times.size() != b_.times.size())
      rep_.add("number of time steps differs: A " + std::to_string(a_.times.size()) + ", B " +
               std::to_string(b_.times.size()) + " (the common steps are compared)");
    steps_ = std::min(a_.times.size(), b_.times.size());
    const auto [ta, tr] = tolerance("time");
    Worst w;
    for (std::size_t s = 0; s < steps_; ++s)
      w.check(a_.times[s], b_.times[s], ta, tr, [&] { return "step " + std::to_string(s + 1); });
    w.report(rep_, "time");
  }

  /// Reports the names only in A or only in B; returns each name of A with its index in B (the matched ones).
  std::vector<std::pair<std::size_t, std::size_t>> match_names(const std::vector<std::string>& na,
                                                               const std::vector<std::string>& nb,
                                                               const std::string& kind) {
    for (const auto& n : na)
      if (std::find(nb.begin(), nb.end(), n) == nb.end()) rep_.add(kind + " '" + n + "' only in A");
    for (const auto& n : nb)
      if (std::find(na.begin(), na.end(), n) == na.end()) rep_.add(kind + " '" + n + "' only in B");
    std::vector<std::pair<std::size_t, std::size_t>> matched;
    for (std::size_t va = 0; va < na.size(); ++va) {
      const auto it = std::find(nb.begin(), nb.end(), na[va]);
      if (it != nb.end()) matched.emplace_back(va, static_cast<std::size_t>(it - nb.begin()));
    }
    return matched;
  }

  std::string step(std::size_t s) const {
    return "step " + std::to_string(s + 1) + " (t = " + num(a_.times[s]) + ")";
  }

  /// Nodal or element variables, matched by name, over the common elements and steps.
  void compare_field_variables(const std::vector<std::string>& na, const std::vector<std::string>& nb, bool nodal) {
    const std::string kind = nodal ? "nodal variable" : "element variable";
    for (const auto& [va, vb] : match_names(na, nb, kind)) {
      const auto [ta, tr] = tolerance(na[va]);
      Worst w;
      for (std::size_t s = 0; s < steps_; ++s) {
        const auto& xa = nodal ? a_.nodal[s][va] : a_.element[s][va];
        const auto& xb = nodal ? b_.nodal[s][vb] : b_.element[s][vb];
        for (const auto& [i, j] : common_) {
          if (nodal) {
            for (std::size_t n = 0; n < npe_; ++n)
              w.check(xa[i * npe_ + n], xb[j * npe_ + n], ta, tr, [&, i = i] { return step(s) + ", " + dg_node(i, n); });
          } else {
            w.check(xa[i], xb[j], ta, tr,
                    [&, i = i] { return step(s) + ", element gid " + std::to_string(a_.element_gids[i]); });
          }
        }
      }
      w.report(rep_, kind + " '" + na[va] + "'");
    }
  }

  void compare_global_variables() {
    for (const auto& [va, vb] : match_names(a_.global_names, b_.global_names, "global variable")) {
      const auto [ta, tr] = tolerance(a_.global_names[va]);
      Worst w;
      for (std::size_t s = 0; s < steps_; ++s)
        w.check(a_.global[s][va], b_.global[s][vb], ta, tr, [&] { return step(s); });
      w.report(rep_, "global variable '" + a_.global_names[va] + "'");
    }
  }

  const ExodusResults& a_;
  const ExodusResults& b_;
  const CompareTolerances& tol_;
  Report rep_;
  std::size_t npe_ = 0;
  std::size_t steps_ = 0;  ///< time steps in both
  std::vector<std::pair<std::size_t, std::size_t>> common_;  ///< (index in A, index in B) of the elements in both
};

}  // namespace

std::vector<std::string> compare_results(const ExodusResults& a, const ExodusResults& b, const CompareTolerances& tol,
                                         std::size_t max_report) {
  return ResultsComparison(a, b, tol, max_report).run();
}

}  // namespace shellfrac::io
