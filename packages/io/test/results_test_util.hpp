#pragma once
/// \file results_test_util.hpp
/// Deterministic DG results used by the io tests: a mesh of `n` elements (global ids 0..n-1) in two interleaved
/// blocks, with nodal and element values given by closed formulas of (gid, local node, step). Any rank can
/// build any contiguous chunk of it, and the whole data set can be built in memory as an ExodusResults, which
/// is the reference the files are checked against.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "shellfrac/io/results_compare.hpp"

namespace shellfrac::io::test {

constexpr int num_steps = 2;
inline const std::vector<std::string> block_names = {"shell_a", "shell_b"};
inline const std::vector<int> block_ids = {3, 8};
inline const std::vector<std::string> vectors = {"displ", "velocity"};
inline const std::vector<std::string> scalars = {"damage", "thickness"};
/// Global variables (history columns), one longer than Exodus' default 32-character names: it must come back
/// whole.
inline const std::vector<std::string> globals = {"kinetic_energy", "end xL simply supported_reaction_x"};
/// The second line is longer than an Exodus information record (80 characters) and comes back wrapped.
inline const std::vector<std::string> info = {"shellfrac io test", std::string(100, 'x')};
inline const std::vector<std::string> info_read_back = {"shellfrac io test", std::string(80, 'x'),
                                                        std::string(20, 'x')};

inline int block_of(GlobalId gid) { return gid % 3 == 1 ? 1 : 0; }
inline Vec3 coord(GlobalId gid, int a) { return {gid + 0.25 * a, 0.5 * a * a - 1.0 / 3.0, 0.1 * gid}; }
inline double time_of(int step) { return 1e-3 * step / 3.0; }
/// Component c of nodal vector v at DG node (gid, a), step 1..num_steps.
inline double nodal_value(int v, int c, GlobalId gid, int a, int step) {
  return std::sin(1.1 * gid + 0.3 * a + v + 0.7 * c) * step;
}
inline double element_value(int s, GlobalId gid, int step) { return std::cos(0.9 * gid + s) + step; }
inline double global_value(int k, int step) { return std::exp(-0.5 * step) + k; }

/// The test sets on elements [begin, end): node set "odd" (DG nodes with gid + a odd), an empty node set "none",
/// side set "edges" (edge gid % 3 of the even elements).
inline void add_sets(int npe, GlobalId begin, GlobalId end, std::vector<ResultsSet>& nodes,
                     std::vector<ResultsSet>& sides) {
  nodes = {{"odd", 5, {}, {}}, {"none", 9, {}, {}}};
  sides = {{"edges", 7, {}, {}}};
  for (GlobalId g = begin; g < end; ++g) {
    for (int a = 0; a < npe; ++a)
      if ((g + a) % 2 == 1) nodes[0].entries.push_back(g * npe + a);
    if (g % 2 == 0) sides[0].entries.push_back(g), sides[0].edges.push_back(int(g % 3));
  }
}

/// The layout of elements [begin, end) of the test mesh.
inline ResultsLayout layout(int npe, GlobalId begin, GlobalId end) {
  ResultsLayout l;
  l.title = "io test";
  l.nodes_per_element = npe;
  l.block_names = block_names;
  l.block_ids = block_ids;
  l.nodal_vectors = vectors;
  l.element_scalars = scalars;
  l.global_variables = globals;
  l.info = info;
  add_sets(npe, begin, end, l.node_sets, l.side_sets);
  for (GlobalId g = begin; g < end; ++g) {
    l.element_gids.push_back(g);
    l.element_block.push_back(block_of(g));
    for (int a = 0; a < npe; ++a) l.node_coords.push_back(coord(g, a));
  }
  return l;
}

/// Writes num_steps steps of the formulas for layout l.
inline void write_steps(ExodusResultsWriter& w, const ResultsLayout& l) {
  const int npe = l.nodes_per_element;
  for (int step = 1; step <= num_steps; ++step) {
    std::vector<std::vector<Vec3>> nodal(vectors.size());
    std::vector<std::vector<double>> element(scalars.size());
    for (GlobalId g : l.element_gids)
      for (int a = 0; a < npe; ++a)
        for (std::size_t v = 0; v < vectors.size(); ++v)
          nodal[v].push_back({nodal_value(int(v), 0, g, a, step), nodal_value(int(v), 1, g, a, step),
                              nodal_value(int(v), 2, g, a, step)});
    for (GlobalId g : l.element_gids)
      for (std::size_t s = 0; s < scalars.size(); ++s) element[s].push_back(element_value(int(s), g, step));
    std::vector<double> global;
    for (std::size_t k = 0; k < globals.size(); ++k) global.push_back(global_value(int(k), step));
    EXPECT_EQ(w.write_step(time_of(step), nodal, element, global), step);
  }
}

/// The whole data set of elements 0..n-1 as read_results must return it.
inline ExodusResults expected(int npe, GlobalId n) {
  ExodusResults r;
  r.title = "io test";
  r.nodes_per_element = npe;
  add_sets(npe, 0, n, r.node_sets, r.side_sets);
  r.block_names = block_names;
  r.block_ids = block_ids;
  r.info = info_read_back;
  for (const auto& v : vectors)
    for (const char* c : {"_x", "_y", "_z"}) r.nodal_names.push_back(v + c);
  r.element_names = scalars;
  r.global_names = globals;
  for (GlobalId g = 0; g < n; ++g) {
    r.element_gids.push_back(g);
    r.element_block_ids.push_back(block_ids[block_of(g)]);
    for (int a = 0; a < npe; ++a) r.node_coords.push_back(coord(g, a));
  }
  for (int step = 1; step <= num_steps; ++step) {
    r.times.push_back(time_of(step));
    std::vector<std::vector<double>> nodal, element;
    for (std::size_t v = 0; v < vectors.size(); ++v)
      for (int c = 0; c < 3; ++c) {
        nodal.emplace_back();
        for (GlobalId g = 0; g < n; ++g)
          for (int a = 0; a < npe; ++a) nodal.back().push_back(nodal_value(int(v), c, g, a, step));
      }
    for (std::size_t s = 0; s < scalars.size(); ++s) {
      element.emplace_back();
      for (GlobalId g = 0; g < n; ++g) element.back().push_back(element_value(int(s), g, step));
    }
    r.nodal.push_back(nodal);
    r.element.push_back(element);
    r.global.emplace_back();
    for (std::size_t k = 0; k < globals.size(); ++k) r.global.back().push_back(global_value(int(k), step));
  }
  return r;
}

/// Exact equality of two data sets (num_files excepted).
inline void expect_same(const ExodusResults& a, const ExodusResults& b) {
  EXPECT_EQ(a.title, b.title);
  EXPECT_TRUE(a.node_sets == b.node_sets) << "node sets differ";
  EXPECT_TRUE(a.side_sets == b.side_sets) << "side sets differ";
  EXPECT_EQ(a.nodes_per_element, b.nodes_per_element);
  EXPECT_EQ(a.element_gids, b.element_gids);
  EXPECT_EQ(a.element_block_ids, b.element_block_ids);
  EXPECT_EQ(a.block_names, b.block_names);
  EXPECT_EQ(a.block_ids, b.block_ids);
  EXPECT_EQ(a.node_coords, b.node_coords);
  EXPECT_EQ(a.times, b.times);
  EXPECT_EQ(a.nodal_names, b.nodal_names);
  EXPECT_EQ(a.element_names, b.element_names);
  EXPECT_EQ(a.nodal, b.nodal);
  EXPECT_EQ(a.element, b.element);
  EXPECT_EQ(a.global_names, b.global_names);
  EXPECT_EQ(a.global, b.global);
  EXPECT_EQ(a.info, b.info);
}

/// Removes `path` and every file of a per-rank set of it (left over from an earlier run).
inline void remove_results(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename().string().rfind(p.filename().string(), 0) == 0) fs::remove(e.path(), ec);
}

}  // namespace shellfrac::io::test
