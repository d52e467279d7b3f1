// Tests of ExodusResultsWriter at several rank counts, read_results of per-rank sets, and the join
// (write_results of a merged set). Run at np = 1, 2, 3.
// References: (1) expected() in results_test_util.hpp, the data set built in memory from the same closed
// formulas the ranks write; (2) a single-rank write of the whole mesh by rank 0 (MPI_COMM_SELF), which the
// merged per-rank set must equal exactly; (3) the naming rule `path.<np>.<rank>` spelled out by hand; (4) the
// Nemesis records of every per-rank file (docs/output.md "Nemesis records") against counts of the test mesh and
// of each rank's chunk written out by hand, read back with the Exodus API; the join (write_results, what
// shellfrac_exojoin calls) writes one file without them.
#include <exodusII.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "results_test_util.hpp"
#include "shellfrac/core/error.hpp"

namespace shellfrac::io {
namespace {

constexpr GlobalId num_elements = 11;

int np() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}
int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

/// Opens a results file read-only with the 64-bit integer API (as the writer creates it); -1 on failure.
int open_exodus(const std::string& path) {
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  return ex_open(path.c_str(), EX_READ | EX_ALL_INT64_API, &cpu_ws, &io_ws, &version);
}

using Counts = std::vector<std::int64_t>;

/// The Nemesis records of rank r's file of a set of np files of the whole test mesh (num_elements = 11), whose
/// rank r owns `elements` elements. By hand from results_test_util.hpp: 11 elements of npe DG nodes; block 3 holds
/// 7 of them, block 8 the 4 with gid % 3 == 1 (1, 4, 7, 10); node set 5 ("odd") holds the DG nodes with gid + a
/// odd, 16 for P1 (1 per even element, 2 per odd one), 33 for P2 (3 per element); node set 9 is empty; side set 7
/// holds the 6 even elements; no distribution factors. Every node and element of the file is internal.
/// Returns {internal nodes, internal elements} as read.
std::pair<std::int64_t, std::int64_t> expect_nemesis(const std::string& file, int np, int r, int npe,
                                                     std::int64_t elements) {
  SCOPED_TRACE(file);
  const int id = open_exodus(file);
  EXPECT_GE(id, 0);
  if (id < 0) return {-1, -1};
  int num_proc = 0, num_proc_in_file = 0;
  char ftype[8] = "";
  EXPECT_GE(ex_get_init_info(id, &num_proc, &num_proc_in_file, ftype), 0);
  EXPECT_EQ(num_proc, np);
  EXPECT_EQ(num_proc_in_file, 1);
  EXPECT_EQ(std::string(ftype), "p");

  std::int64_t nodes_g = 0, elems_g = 0, blocks_g = 0, node_sets_g = 0, side_sets_g = 0;
  EXPECT_GE(ex_get_init_global(id, &nodes_g, &elems_g, &blocks_g, &node_sets_g, &side_sets_g), 0);
  EXPECT_EQ(nodes_g, npe == 3 ? 33 : 66);  // the placeholder node of an empty rank is not counted
  EXPECT_EQ(elems_g, 11);
  EXPECT_EQ(blocks_g, 2);
  EXPECT_EQ(node_sets_g, 2);
  EXPECT_EQ(side_sets_g, 1);

  std::int64_t int_nodes = -1, bor_nodes = -1, ext_nodes = -1, int_elems = -1, bor_elems = -1, node_cmaps = -1,
               elem_cmaps = -1;
  EXPECT_GE(
      ex_get_loadbal_param(id, &int_nodes, &bor_nodes, &ext_nodes, &int_elems, &bor_elems, &node_cmaps, &elem_cmaps, r),
      0);
  EXPECT_EQ(int_nodes, elements * npe);
  EXPECT_EQ(int_elems, elements);
  EXPECT_EQ(bor_nodes, 0);
  EXPECT_EQ(ext_nodes, 0);
  EXPECT_EQ(bor_elems, 0);
  EXPECT_EQ(node_cmaps, 0);
  EXPECT_EQ(elem_cmaps, 0);

  Counts ids(2), counts(2), factors(2);
  EXPECT_GE(ex_get_eb_info_global(id, ids.data(), counts.data()), 0);
  EXPECT_EQ(ids, Counts({3, 8}));
  EXPECT_EQ(counts, Counts({7, 4}));
  EXPECT_GE(ex_get_ns_param_global(id, ids.data(), counts.data(), factors.data()), 0);
  EXPECT_EQ(ids, Counts({5, 9}));
  EXPECT_EQ(counts, Counts({npe == 3 ? 16 : 33, 0}));
  EXPECT_EQ(factors, Counts({0, 0}));
  ids.resize(1), counts.resize(1), factors.resize(1);
  EXPECT_GE(ex_get_ss_param_global(id, ids.data(), counts.data(), factors.data()), 0);
  EXPECT_EQ(ids, Counts({7}));
  EXPECT_EQ(counts, Counts({6}));
  EXPECT_EQ(factors, Counts({0}));

  // The internal maps list the file's nodes and elements by local 1-based index.
  Counts node_map(static_cast<std::size_t>(std::max<std::int64_t>(int_nodes, 1)), -1), expected_nodes(node_map);
  Counts elem_map(static_cast<std::size_t>(std::max<std::int64_t>(int_elems, 1)), -1), expected_elems(elem_map);
  EXPECT_GE(ex_get_processor_node_maps(id, node_map.data(), nullptr, nullptr, r), 0);
  EXPECT_GE(ex_get_processor_elem_maps(id, elem_map.data(), nullptr, r), 0);
  if (int_nodes > 0) std::iota(expected_nodes.begin(), expected_nodes.end(), 1);
  if (int_elems > 0) std::iota(expected_elems.begin(), expected_elems.end(), 1);
  EXPECT_EQ(node_map, expected_nodes);
  EXPECT_EQ(elem_map, expected_elems);
  ex_close(id);
  return {int_nodes, int_elems};
}

/// A file that is not part of a set (one rank's run.exo, a join) carries no Nemesis records. The libraries report
/// that differently: on such a file Exodus 6.02's ex_get_init_info and ex_get_init_global fail (no dimensions
/// "num_processors", "num_nodes_global"), SEACAS Exodus 8's succeed with 1 processor, 1 in the file, and 0 for
/// every global count.
void expect_no_nemesis(const std::string& file) {
  SCOPED_TRACE(file);
  const int id = open_exodus(file);
  ASSERT_GE(id, 0);
  int num_proc = 1, num_proc_in_file = 1;
  char ftype[8] = "";
  if (ex_get_init_info(id, &num_proc, &num_proc_in_file, ftype) >= 0) {
    EXPECT_EQ(num_proc, 1);
    EXPECT_EQ(num_proc_in_file, 1);
  }
  std::int64_t nodes_g = 0, elems_g = 0, blocks_g = 0, node_sets_g = 0, side_sets_g = 0;
  if (ex_get_init_global(id, &nodes_g, &elems_g, &blocks_g, &node_sets_g, &side_sets_g) >= 0) {
    EXPECT_EQ(nodes_g, 0);
    EXPECT_EQ(elems_g, 0);
    EXPECT_EQ(blocks_g, 0);
    EXPECT_EQ(node_sets_g, 0);
    EXPECT_EQ(side_sets_g, 0);
  }
  ex_close(id);
}

/// Runs one case: every rank writes elements [begin(r), begin(r+1)), rank 0 checks the set. rank_elements[np] are
/// the element counts of the ranks at np, by hand.
template <class Begin>
void run_case(const std::string& name, int npe, Begin begin, const std::map<int, Counts>& rank_elements) {
  const std::string stem = "results_" + name + "_p" + std::to_string(npe) + "_np" + std::to_string(np());
  const std::string base = stem + ".exo", ref = stem + "_ref.exo", joined = stem + "_joined.exo";
  if (rank() == 0)
    for (const auto& f : {base, ref, joined}) test::remove_results(f);
  MPI_Barrier(MPI_COMM_WORLD);
  {
    const auto l = test::layout(npe, begin(rank()), begin(rank() + 1));
    ExodusResultsWriter w(base, l);
    // Naming rule by hand: np = 1 -> base; np < 10 -> base.<np>.<rank> (width 1, no padding).
    EXPECT_EQ(w.file_name(), np() == 1 ? base : base + "." + std::to_string(np()) + "." + std::to_string(rank()));
    test::write_steps(w, l);
  }
  MPI_Barrier(MPI_COMM_WORLD);  // all files closed
  if (rank() != 0) return;

  for (int r = 0; r < np(); ++r) EXPECT_TRUE(std::filesystem::exists(rank_file_name(base, np(), r)));
  if (np() > 1) {
    ASSERT_EQ(rank_elements.count(np()), 1u) << "no element counts by hand for np = " << np();
    const Counts& elements = rank_elements.at(np());
    ASSERT_EQ(elements.size(), static_cast<std::size_t>(np()));
    std::int64_t sum_nodes = 0, sum_elements = 0;
    for (int r = 0; r < np(); ++r) {
      const auto [nodes, elems] = expect_nemesis(rank_file_name(base, np(), r), np(), r, npe, elements[r]);
      sum_nodes += nodes, sum_elements += elems;
    }
    EXPECT_EQ(sum_nodes, num_elements * npe);
    EXPECT_EQ(sum_elements, num_elements);
  } else {
    expect_no_nemesis(base);
  }
  const ExodusResults merged = read_results(base);
  EXPECT_EQ(merged.num_files, np());
  test::expect_same(merged, test::expected(npe, num_elements));

  {  // the same mesh written whole by one rank
    const auto l = test::layout(npe, 0, num_elements);
    ExodusResultsWriter w(ref, l, MPI_COMM_SELF);
    EXPECT_EQ(w.file_name(), ref);
    test::write_steps(w, l);
  }
  expect_no_nemesis(ref);
  const ExodusResults single = read_results(ref);
  EXPECT_EQ(single.num_files, 1);
  test::expect_same(merged, single);
  EXPECT_TRUE(compare_results(merged, single, CompareTolerances{}).empty());

  // Join: the set written as one file reads back equal to the set.
  if (np() > 1) {
    EXPECT_EQ(find_rank_files(base).size(), static_cast<std::size_t>(np()));
    write_results(read_results_files(find_rank_files(base)), joined);
    expect_no_nemesis(joined);  // a single file: the set's Nemesis records are not copied
    const ExodusResults j = read_results(joined);
    EXPECT_EQ(j.num_files, 1);
    test::expect_same(j, merged);
  } else {
    EXPECT_TRUE(find_rank_files(base).empty());
  }
}

// Elements split in contiguous, nearly equal chunks: 5 + 6 at np = 2, 3 + 4 + 4 at np = 3.
GlobalId even_begin(int r) { return num_elements * r / np(); }
const std::map<int, Counts> even_split = {{2, {5, 6}}, {3, {3, 4, 4}}};
TEST(ExodusResultsParallel, EvenSplitP1) { run_case("even", 3, even_begin, even_split); }
TEST(ExodusResultsParallel, EvenSplitP2) { run_case("even", 6, even_begin, even_split); }

// Rank 0 owns nothing when np > 1 (its file has empty blocks but the variables, steps and info records, and
// Nemesis records with no internal nodes or elements): 0 + 11 at np = 2, 0 + 5 + 6 at np = 3.
TEST(ExodusResultsParallel, RankZeroOwnsNothing) {
  run_case("empty0", 3,
           [](int r) {
             if (np() == 1) return r == 0 ? GlobalId{0} : num_elements;
             return r == 0 ? GlobalId{0} : num_elements * (r - 1) / (np() - 1);
           },
           {{2, {0, 11}}, {3, {0, 5, 6}}});
}

// Reference: the naming rule (rank padded to the width of np) written out by hand.
TEST(ExodusResultsParallel, RankFileNames) {
  EXPECT_EQ(rank_file_name("run.exo", 1, 0), "run.exo");
  EXPECT_EQ(rank_file_name("run.exo", 3, 0), "run.exo.3.0");
  EXPECT_EQ(rank_file_name("run.exo", 3, 2), "run.exo.3.2");
  EXPECT_EQ(rank_file_name("run.exo", 12, 3), "run.exo.12.03");
  EXPECT_EQ(rank_file_name("out/run.e", 100, 7), "out/run.e.100.007");
}

// Reference: the header's error contract for read_results.
TEST(ExodusResultsParallel, MissingResultsAreInputErrors) {
  if (rank() != 0) return;
  const std::string base = "results_missing_np" + std::to_string(np()) + ".exo";
  test::remove_results(base);
  try {
    read_results(base);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(base), std::string::npos) << e.what();
  }
  // An incomplete per-rank set (rank 1 of 3 missing) names the missing file.
  for (int r : {0, 2}) {
    const auto l = test::layout(3, r, r + 1);
    ExodusResultsWriter w(base + ".3." + std::to_string(r), l, MPI_COMM_SELF);
  }
  try {
    read_results(base);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(base + ".3.1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shellfrac::io
