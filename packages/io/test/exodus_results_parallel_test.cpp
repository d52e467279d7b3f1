// Tests of ExodusResultsWriter at several rank counts, read_results of per-rank sets, and the join
// (write_results of a merged set). Run at np = 1, 2, 3.
// References: (1) expected() in results_test_util.hpp, the data set built in memory from the same closed
// formulas the ranks write; (2) a single-rank write of the whole mesh by rank 0 (MPI_COMM_SELF), which the
// merged per-rank set must equal exactly; (3) the naming rule `path.<np>.<rank>` spelled out by hand.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <string>

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

/// Runs one case: every rank writes elements [begin(r), begin(r+1)), rank 0 checks the set.
template <class Begin>
void run_case(const std::string& name, int npe, Begin begin) {
  const std::string base = "results_" + name + "_p" + std::to_string(npe) + "_np" + std::to_string(np()) + ".exo";
  const std::string ref = "results_" + name + "_p" + std::to_string(npe) + "_np" + std::to_string(np()) + "_ref.exo";
  const std::string joined = "results_" + name + "_p" + std::to_string(npe) + "_np" + std::to_string(np()) + "_joined.exo";
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
  const ExodusResults merged = read_results(base);
  EXPECT_EQ(merged.num_files, np());
  test::expect_same(merged, test::expected(npe, num_elements));

  {  // the same mesh written whole by one rank
    const auto l = test::layout(npe, 0, num_elements);
    ExodusResultsWriter w(ref, l, MPI_COMM_SELF);
    EXPECT_EQ(w.file_name(), ref);
    test::write_steps(w, l);
  }
  const ExodusResults single = read_results(ref);
  EXPECT_EQ(single.num_files, 1);
  test::expect_same(merged, single);
  EXPECT_TRUE(compare_results(merged, single, CompareTolerances{}).empty());

  // Join: the set written as one file reads back equal to the set.
  if (np() > 1) {
    EXPECT_EQ(find_rank_files(base).size(), static_cast<std::size_t>(np()));
    write_results(read_results_files(find_rank_files(base)), joined);
    const ExodusResults j = read_results(joined);
    EXPECT_EQ(j.num_files, 1);
    test::expect_same(j, merged);
  } else {
    EXPECT_TRUE(find_rank_files(base).empty());
  }
}

// Elements split in contiguous, nearly equal chunks.
TEST(ExodusResultsParallel, EvenSplitP1) {
  run_case("even", 3, [](int r) { return num_elements * r / np(); });
}
TEST(ExodusResultsParallel, EvenSplitP2) {
  run_case("even", 6, [](int r) { return num_elements * r / np(); });
}

// Rank 0 owns nothing when np > 1 (its file has empty blocks but the variables, steps and info records).
TEST(ExodusResultsParallel, RankZeroOwnsNothing) {
  run_case("empty0", 3, [](int r) {
    if (np() == 1) return r == 0 ? GlobalId{0} : num_elements;
    return r == 0 ? GlobalId{0} : num_elements * (r - 1) / (np() - 1);
  });
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
