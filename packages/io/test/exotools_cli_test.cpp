// Tests of the command-line tools shellfrac_exocompare and shellfrac_exojoin (serial; the tools are run with
// std::system). References: the exit-status contract (0 equal, 1 different, 2 usage/input error), and the
// in-memory data set test::expected(), written as files with write_results (a per-rank set is made by
// writing chunks under the names rank_file_name(base, 3, r)).
#include <gtest/gtest.h>

#include <algorithm>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "results_test_util.hpp"

#ifndef SHELLFRAC_EXOCOMPARE
#error "SHELLFRAC_EXOCOMPARE (path of shellfrac_exocompare) must be defined"
#endif
#ifndef SHELLFRAC_EXOJOIN
#error "SHELLFRAC_EXOJOIN (path of shellfrac_exojoin) must be defined"
#endif

namespace shellfrac::io {
namespace {

/// Runs a command with stdout+stderr to `log`; returns its exit status.
int run(const std::string& command, const std::string& log) {
  const int rc = std::system((command + " > " + log + " 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Elements [begin, end) of a data set.
ExodusResults chunk(const ExodusResults& r, std::size_t begin, std::size_t end) {
  const std::size_t npe = static_cast<std::size_t>(r.nodes_per_element);
  ExodusResults c = r;
  c.element_gids.assign(r.element_gids.begin() + begin, r.element_gids.begin() + end);
  c.element_block_ids.assign(r.element_block_ids.begin() + begin, r.element_block_ids.begin() + end);
  c.node_coords.assign(r.node_coords.begin() + begin * npe, r.node_coords.begin() + end * npe);
  const auto mine = [&](GlobalId element) {
    return std::binary_search(c.element_gids.begin(), c.element_gids.end(), element);
  };
  for (auto& set : c.node_sets) {
    std::vector<GlobalId> kept;
    for (GlobalId g : set.entries)
      if (mine(g / GlobalId(npe))) kept.push_back(g);
    set.entries = kept;
  }
  for (auto& set : c.side_sets) {
    ResultsSet kept{set.name, set.id, {}, {}};
    for (std::size_t i = 0; i < set.entries.size(); ++i)
      if (mine(set.entries[i])) kept.entries.push_back(set.entries[i]), kept.edges.push_back(set.edges[i]);
    set = kept;
  }
  for (std::size_t s = 0; s < r.times.size(); ++s) {
    for (std::size_t v = 0; v < r.nodal[s].size(); ++v)
      c.nodal[s][v].assign(r.nodal[s][v].begin() + begin * npe, r.nodal[s][v].begin() + end * npe);
    for (std::size_t v = 0; v < r.element[s].size(); ++v)
      c.element[s][v].assign(r.element[s][v].begin() + begin, r.element[s][v].begin() + end);
  }
  return c;
}

const std::string compare = SHELLFRAC_EXOCOMPARE;
const std::string join = SHELLFRAC_EXOJOIN;

TEST(ExoTools, CompareExitStatus) {
  const auto a = test::expected(3, 9);
  auto b = a;
  b.nodal[1][4][7] += 1e-4;  // step 2, velocity_y, element gid 2, local node 1
  write_results(a, "exotools_a.exo");
  write_results(b, "exotools_b.exo");

  EXPECT_EQ(run(compare + " exotools_a.exo exotools_a.exo", "exotools_log1.txt"), 0) << slurp("exotools_log1.txt");
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo", "exotools_log2.txt"), 1);
  const std::string out = slurp("exotools_log2.txt");
  EXPECT_NE(out.find("velocity_y"), std::string::npos) << out;
  EXPECT_NE(out.find("element gid 2"), std::string::npos) << out;
  EXPECT_NE(out.find("step 2"), std::string::npos) << out;

  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo --abs 1e-3", "exotools_log3.txt"), 0)
      << slurp("exotools_log3.txt");
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo --rel 1e-12", "exotools_log4.txt"), 1);
  std::ofstream("exotools_tol.txt") << "velocity absolute 1e-3\n";
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo --tolerances exotools_tol.txt", "exotools_log5.txt"), 0)
      << slurp("exotools_log5.txt");

  // Usage and input errors: 2 with a message.
  EXPECT_EQ(run(compare + " exotools_a.exo", "exotools_log6.txt"), 2);
  EXPECT_NE(slurp("exotools_log6.txt").find("usage"), std::string::npos);
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo --abs -1", "exotools_log7.txt"), 2);
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_missing.exo", "exotools_log8.txt"), 2);
  EXPECT_NE(slurp("exotools_log8.txt").find("exotools_missing.exo"), std::string::npos);
  EXPECT_EQ(run(compare + " exotools_a.exo exotools_b.exo --tolerances exotools_no_tol.txt", "exotools_log9.txt"), 2);
}

TEST(ExoTools, JoinPerRankSet) {
  const auto whole = test::expected(6, 10);
  const std::string base = "exotools_set.exo";
  test::remove_results(base);
  const std::size_t bounds[] = {0, 4, 4, 10};  // rank 1 owns nothing
  for (int r = 0; r < 3; ++r) write_results(chunk(whole, bounds[r], bounds[r + 1]), rank_file_name(base, 3, r));

  EXPECT_EQ(run(join + " " + base + " exotools_joined.exo", "exotools_log10.txt"), 0) << slurp("exotools_log10.txt");
  test::expect_same(read_results("exotools_joined.exo"), whole);
  // Comparing the set with the joined file works on the set directly.
  EXPECT_EQ(run(compare + " " + base + " exotools_joined.exo", "exotools_log11.txt"), 0) << slurp("exotools_log11.txt");
  // Default OUT = IN.
  EXPECT_EQ(run(join + " " + base, "exotools_log12.txt"), 0) << slurp("exotools_log12.txt");
  test::expect_same(read_results(base), whole);

  EXPECT_EQ(run(join + " exotools_no_such_set.exo", "exotools_log13.txt"), 2);
  EXPECT_NE(slurp("exotools_log13.txt").find("exotools_no_such_set.exo"), std::string::npos);
  EXPECT_EQ(run(join, "exotools_log14.txt"), 2);
}

// Found on an earlier version: `exojoin base.exo base.exo.2.0` overwrote rank 0's file, and the rank files of two
// runs (the same deck and frames, other physics) were joined with exit 0.
TEST(ExoTools, JoinRefusesItsInputAsOutputAndFilesOfDifferentRuns) {
  const auto whole = test::expected(6, 10);
  const std::string base = "exotools_mixed.exo";
  test::remove_results(base);
  write_results(chunk(whole, 0, 4), rank_file_name(base, 2, 0));
  write_results(chunk(whole, 4, 10), rank_file_name(base, 2, 1));
  const std::string rank0 = slurp(rank_file_name(base, 2, 0));
  EXPECT_EQ(run(join + " " + base + " " + rank_file_name(base, 2, 0), "exotools_log15.txt"), 2);
  EXPECT_NE(slurp("exotools_log15.txt").find("is one of the files to join"), std::string::npos)
      << slurp("exotools_log15.txt");
  EXPECT_EQ(slurp(rank_file_name(base, 2, 0)), rank0);
  auto other = whole;  // another run: the same frames, other energies
  for (auto& row : other.global)
    for (double& v : row) v += 1.0;
  write_results(chunk(other, 4, 10), rank_file_name(base, 2, 1));
  EXPECT_EQ(run(join + " " + base + " exotools_mixed_joined.exo", "exotools_log16.txt"), 2);
  EXPECT_NE(slurp("exotools_log16.txt").find("the files were written by different runs"), std::string::npos)
      << slurp("exotools_log16.txt");
}

}  // namespace
}  // namespace shellfrac::io
