// Tests of compare_results and CompareTolerances::from_file (serial).
// References: the tolerance rule of the header, |a - b| <= max(abs, rel * max(|a|, |b|)), applied by hand to
// single perturbed values of the in-memory data set test::expected(); the tolerance-file grammar of the header.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "results_test_util.hpp"
#include "shellfrac/core/error.hpp"

namespace shellfrac::io {
namespace {

/// All difference lines joined, for substring checks.
std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "missing '" << part << "' in:\n" << text;
}

TEST(ExodusCompare, IdenticalDataSetsHaveNoDifferences) {
  const auto a = test::expected(3, 7);
  EXPECT_TRUE(compare_results(a, a, CompareTolerances{}).empty());
}

// Perturbing nodal displ_y (variable index 1) of element gid 5, local node 1, step 2 by 1e-3: DG node gid 5*3+1.
TEST(ExodusCompare, NodalPerturbationBeyondToleranceIsReported) {
  const auto a = test::expected(3, 7);
  auto b = a;
  b.nodal[1][1][5 * 3 + 1] += 1e-3;
  CompareTolerances tol;
  tol.default_abs = 1e-6;
  const auto d = compare_results(a, b, tol);
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "nodal variable 'displ_y'");
  expect_contains(d[0], "1 value out of tolerance");
  expect_contains(d[0], "step 2");
  expect_contains(d[0], "element gid 5");
  expect_contains(d[0], "local node 1");
  expect_contains(d[0], "DG node gid 16");
}

TEST(ExodusCompare, ElementPerturbationBeyondToleranceIsReported) {
  const auto a = test::expected(6, 7);
  auto b = a;
  b.element[0][1][3] -= 0.5;  // step 1, 'thickness', element gid 3
  const auto d = compare_results(a, b, CompareTolerances{});
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "element variable 'thickness'");
  expect_contains(d[0], "step 1");
  expect_contains(d[0], "element gid 3");
}

TEST(ExodusCompare, GlobalVariablePerturbationIsReported) {
  const auto a = test::expected(6, 7);
  auto b = a;
  b.global[1][1] += 1e-9;  // step 2, the reaction
  const auto d = compare_results(a, b, CompareTolerances{});
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "global variable 'end xL simply supported_reaction_x'");
  expect_contains(d[0], "step 2");
  b.global_names[0] = "strain_energy";
  expect_contains(joined(compare_results(a, b, CompareTolerances{})), "global variable 'kinetic_energy' only in A");
}

TEST(ExodusCompare, PerturbationWithinToleranceIsAccepted) {
  const auto a = test::expected(3, 7);
  auto b = a;
  b.nodal[0][0][4] += 1e-9;  // absolute: 1e-9 <= 1e-8
  CompareTolerances tol;
  tol.default_abs = 1e-8;
  EXPECT_TRUE(compare_results(a, b, tol).empty());

  auto c = a;
  c.element[1][0][2] = 1000.0;  // relative: |1000 - 1000.0005| = 5e-4 <= 1e-6 * 1000.0005
  auto e = c;
  e.element[1][0][2] = 1000.0005;
  CompareTolerances rel;
  rel.default_rel = 1e-6;
  EXPECT_TRUE(compare_results(c, e, rel).empty());
  rel.default_rel = 1e-7;  // 5e-4 > 1e-4
  EXPECT_EQ(compare_results(c, e, rel).size(), 1u);
}

// The entry of a vector ("displ") applies to its components; the exact entry wins; others use the default.
TEST(ExodusCompare, PerVariableTolerances) {
  const auto a = test::expected(3, 7);
  auto b = a;
  b.nodal[0][2][0] += 1e-3;  // displ_z
  b.nodal[1][0][0] += 1e-3;  // step 2 displ_x
  CompareTolerances tol;
  tol.per_variable = {{"displ", 1e-2, 0}, {"displ_x", 1e-4, 0}};
  const auto d = compare_results(a, b, tol);
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "'displ_x'");
  b.node_coords[2][1] += 1e-12;
  tol.per_variable.push_back({"coordinates", 1e-15, 0});
  expect_contains(joined(compare_results(a, b, tol)), "coordinates");
}

TEST(ExodusCompare, StructuralDifferences) {
  const auto a = test::expected(3, 7);
  auto b = test::expected(3, 8);   // one more element (gid 7)
  b.element_names[1] = "rank";     // a variable only in each
  b.times.pop_back();              // fewer steps
  b.nodal.pop_back();
  b.element.pop_back();
  const std::string d = joined(compare_results(a, b, CompareTolerances{}));
  expect_contains(d, "1 element(s) only in B, gids: 7");
  expect_contains(d, "'thickness' only in A");
  expect_contains(d, "'rank' only in B");
  expect_contains(d, "number of time steps differs: A 2, B 1");
}

// A DG node dropped from node set "odd", or an edge moved in side set "edges": the set is named.
TEST(ExodusCompare, SetDifferencesAreReported) {
  const auto a = test::expected(3, 7);
  auto b = a;
  b.node_sets[0].entries.pop_back();
  auto d = compare_results(a, b, CompareTolerances{});
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "node sets differ: 'odd' (id 5)");
  b = a;
  b.side_sets[0].edges[0] = (b.side_sets[0].edges[0] + 1) % 3;
  d = compare_results(a, b, CompareTolerances{});
  ASSERT_EQ(d.size(), 1u) << joined(d);
  expect_contains(d[0], "side sets differ: 'edges' (id 7)");
}

TEST(ExodusCompare, ReportIsCapped) {
  const auto a = test::expected(3, 7);
  auto b = a;
  for (auto& step : b.nodal)
    for (auto& v : step) v[0] += 1;  // all 6 nodal variables differ
  const auto d = compare_results(a, b, CompareTolerances{}, 4);
  ASSERT_EQ(d.size(), 4u);
  expect_contains(d.back(), "3 more differences not shown (6 in all)");
}

TEST(ExodusCompare, ToleranceFile) {
  const std::string path = "exodus_compare_tolerances.txt";
  std::ofstream(path) << "# tolerances\n"
                         "default absolute 1e-12 relative 1e-9\n"
                         "\n"
                         "coordinates absolute 0   # exact\n"
                         "displ relative 1e-6\n"
                         "damage abs 2.5e-3 rel 0.5\n";
  const auto t = CompareTolerances::from_file(path);
  EXPECT_EQ(t.default_abs, 1e-12);
  EXPECT_EQ(t.default_rel, 1e-9);
  ASSERT_EQ(t.per_variable.size(), 3u);
  EXPECT_EQ(t.per_variable[0].name, "coordinates");
  EXPECT_EQ(t.per_variable[0].abs, 0.0);
  EXPECT_EQ(t.per_variable[1].name, "displ");
  EXPECT_EQ(t.per_variable[1].abs, 0.0);
  EXPECT_EQ(t.per_variable[1].rel, 1e-6);
  EXPECT_EQ(t.per_variable[2].abs, 2.5e-3);
  EXPECT_EQ(t.per_variable[2].rel, 0.5);
}

TEST(ExodusCompare, ToleranceFileErrorsNameFileAndLine) {
  const std::string path = "exodus_compare_bad_tolerances.txt";
  const std::pair<std::string, std::string> cases[] = {
      {"displ absolute\n", ":1:"},                    // missing value
      {"# ok\ndispl absolut 1\n", ":2: unknown keyword 'absolut'"},
      {"displ relative -1\n", "not a non-negative number"},
      {"displ relative 1x\n", "not a non-negative number"},
      {"displ abs 1\ndispl abs 2\n", ":2: 'displ' is given twice"},
  };
  for (const auto& [text, part] : cases) {
    std::ofstream(path) << text;
    try {
      CompareTolerances::from_file(path);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      expect_contains(e.what(), path);
      expect_contains(e.what(), part);
    }
  }
  EXPECT_THROW(CompareTolerances::from_file("exodus_compare_no_such_file.txt"), InputError);
}

}  // namespace
}  // namespace shellfrac::io
