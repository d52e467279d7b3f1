// End-to-end runs of the foundation (issue: foundation, acceptance): a generated cylindrical panel and a
// Gmsh-meshed curved surface are read, partitioned on 1, 2 and 3 ranks, written to Exodus, and read back.
// Reference: the serial mesh itself. Every DG node written must carry exactly (bitwise) the coordinates of
// its mesh node and the reference director of theory.md §1.5, whatever the rank count; the element count must
// equal the mesh's. Bad decks must raise InputError naming the problem and must write nothing.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/results_reader.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/solver/simulation.hpp"
#include "deck_test_util.hpp"

using namespace shellfrac;
using shellfrac::test::work_dir;
using shellfrac::test::write_deck;
namespace fs = std::filesystem;

namespace {

/// A deck without a mesh: the block `block` of the aluminium material "al", results written to `dir`.
Teuchos::RCP<Teuchos::ParameterList> aluminium_deck(const std::string& block, const std::string& dir) {
  auto deck = Teuchos::rcp(new Teuchos::ParameterList("shellfrac"));
  auto& b = deck->sublist("Blocks").sublist(block);
  b.set("Thickness", 0.125), b.set("Material", std::string("al"));
  auto& al = deck->sublist("Materials").sublist("al");
  al.set("Density", 2.5e-4), al.set("Young's Modulus", 10.5e6), al.set("Poisson's Ratio", 0.33);
  deck->sublist("Output").set("Directory", dir);
  return deck;
}

/// The aluminium deck on the generated cylindrical panel R = 2.9375, L = 12.56, 120 degrees, 16 x 6 cells.
Teuchos::RCP<Teuchos::ParameterList> panel_deck(const std::string& block, const std::string& dir) {
  auto deck = aluminium_deck(block, dir);
  test::set_cylindrical_panel(*deck, 2.9375, 12.56, 120, 16, 6);
  return deck;
}

/// Runs the deck and checks the written results against `expected` (the P2 serial mesh).
void run_and_check(const std::string& deck_path, const mesh::SerialMesh& expected) {
  solver::Simulation sim(deck_path);
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  if (parallel::rank() != 0) return;
  const auto res = io::read_results(sim.exodus_path());
  ASSERT_EQ(res.num_files, parallel::size());
  ASSERT_EQ(GlobalId(res.element_gids.size()), expected.num_elements());
  ASSERT_EQ(res.nodes_per_element, 6);
  const auto normals = mesh::reference_vertex_normals(expected);
  ASSERT_EQ(res.times.size(), 1u);
  ASSERT_EQ(res.nodal_names.size(), 9u);
  EXPECT_EQ(res.nodal_names[6], "director_x");
  for (std::size_t i = 0; i < res.element_gids.size(); ++i) {
    const GlobalId e = res.element_gids[i];
    ASSERT_EQ(e, GlobalId(i));
    for (int a = 0; a < 6; ++a) {
      const auto& x = expected.coords[expected.node(e, a)];
      EXPECT_EQ(res.node_coords[6 * i + a], x) << "element " << e << " node " << a;
      if (a < 3) {
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(res.nodal[0][6 + c][6 * i + a], normals[expected.node(e, a)][c]) << "director, element " << e;
      }
    }
    const double rank = res.element[0][1][i];
    EXPECT_TRUE(rank >= 0 && rank < parallel::size());
  }
  // The mesh's node and side sets on the DG copies: every copy of a set node, every set edge, whatever the ranks.
  ASSERT_EQ(res.node_sets.size(), expected.node_sets.size());
  for (std::size_t k = 0; k < expected.node_sets.size(); ++k) {
    const auto& set = expected.node_sets[k];
    std::vector<GlobalId> copies;
    for (GlobalId e = 0; e < expected.num_elements(); ++e)
      for (int a = 0; a < 6; ++a)
        if (std::binary_search(set.nodes.begin(), set.nodes.end(), expected.node(e, a))) copies.push_back(6 * e + a);
    EXPECT_EQ(res.node_sets[k].name, set.name);
    EXPECT_EQ(res.node_sets[k].id, set.id);
    EXPECT_FALSE(copies.empty()) << set.name;
    EXPECT_EQ(res.node_sets[k].entries, copies) << "node set " << set.name;
  }
  ASSERT_EQ(res.side_sets.size(), expected.side_sets.size());
  for (std::size_t k = 0; k < expected.side_sets.size(); ++k) {
    const auto& set = expected.side_sets[k];
    std::vector<std::pair<GlobalId, int>> sides;
    for (std::size_t i = 0; i < set.elements.size(); ++i) sides.push_back({set.elements[i], set.local_edges[i]});
    std::sort(sides.begin(), sides.end());
    std::vector<std::pair<GlobalId, int>> written;
    for (std::size_t i = 0; i < res.side_sets[k].entries.size(); ++i)
      written.push_back({res.side_sets[k].entries[i], res.side_sets[k].edges[i]});
    // a side set named like a node set is written as <name>_edges (ParaView's reader needs distinct names)
    const bool shared = std::any_of(expected.node_sets.begin(), expected.node_sets.end(),
                                    [&](const auto& n) { return n.name == set.name; });
    EXPECT_EQ(res.side_sets[k].name, shared ? set.name + "_edges" : set.name);
    EXPECT_EQ(written, sides) << "side set " << set.name;
  }
}

}  // namespace

TEST(Run, GeneratedCylindricalPanel) {
  const auto dir = work_dir("run_panel");
  write_deck(dir + "/panel.xml", *panel_deck("shell", dir));
  auto expected = mesh::make_cylindrical_panel(2.9375, 12.56, 120 * M_PI / 180, 16, 6);
  mesh::promote_to_p2(expected);
  run_and_check(dir + "/panel.xml", expected);
}

TEST(Run, GmshCurvedSurface) {
  const auto dir = work_dir("gmsh");
  const std::string msh = dir + "/panel.msh";
  if (parallel::rank() == 0) {
    const std::string cmd = std::string(SHELLFRAC_GMSH) + " -2 -order 2 -nt 1 -format msh41 -v 0 " + SHELLFRAC_SOURCE_DIR +
                            "/tests/data/gmsh/cylinder_panel.geo -o " + msh;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const auto curved = aluminium_deck("skin", dir);
  test::set_mesh_file(*curved, "panel.msh");
  write_deck(dir + "/curved.xml", *curved);
  const auto expected = meshio::read_mesh_file(msh);
  EXPECT_EQ(expected.nodes_per_element, 6);  // Gmsh order 2: no promotion, the file's own mid-side nodes
  run_and_check(dir + "/curved.xml", expected);
}

// Output->Fields: only the chosen nodal vectors and element fields are written, in file order; the history stays
// whole as global variables. A name that is no field is refused (the deck reference lists the fields).
TEST(Run, OutputFieldsSelectTheWrittenFields) {
  const auto dir = work_dir("fields");
  auto deck = panel_deck("shell", dir);
  deck->sublist("Output").set("Fields", Teuchos::Array<std::string>(std::vector<std::string>{"damage", "displ", "rank"}));
  write_deck(dir + "/fields.xml", *deck);
  solver::Simulation sim(dir + "/fields.xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  if (parallel::rank() == 0) {
    const auto res = io::read_results(sim.exodus_path());
    EXPECT_EQ(res.nodal_names, (std::vector<std::string>{"displ_x", "displ_y", "displ_z"}));
    EXPECT_EQ(res.element_names, (std::vector<std::string>{"rank", "damage"}));
    EXPECT_FALSE(res.global_names.empty());
  }
  MPI_Barrier(MPI_COMM_WORLD);
  deck->sublist("Output").set("Fields", Teuchos::Array<std::string>(std::vector<std::string>{"displacement"}));
  write_deck(dir + "/fields.xml", *deck);
  try {
    solver::Simulation bad(dir + "/fields.xml");
    ADD_FAILURE() << "Fields = {displacement} accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'Output->Fields' names 'displacement', which is not a result field; the "
                                         "fields are 'displ' 'velocity' 'director' 'block' 'rank'"),
              std::string::npos)
        << e.what();
  }
}

namespace {
/// Expects Simulation(deck) to throw an InputError containing every phrase, and the directory to stay empty
/// but for the deck.
void expect_rejected(const std::string& dir, const Teuchos::ParameterList& deck, const std::vector<std::string>& phrases) {
  write_deck(dir + "/bad.xml", deck);
  try {
    solver::Simulation sim(dir + "/bad.xml");
    sim.run();
    ADD_FAILURE() << "deck accepted:\n" << deck;
  } catch (const InputError& e) {
    for (const auto& p : phrases) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.path().filename() != "bad.xml";
  EXPECT_EQ(files, 0u) << "a rejected deck wrote files";
}
}  // namespace

TEST(Run, BadDecksAreRejectedBeforeAnyOutput) {
  const auto dir = work_dir("bad");
  const auto misspelled = panel_deck("shell", dir);
  misspelled->sublist("Blocks").sublist("shell").remove("Thickness");
  misspelled->sublist("Blocks").sublist("shell").set("Thicknes", 0.125);
  expect_rejected(dir, *misspelled, {"bad.xml: unknown parameter 'Thicknes' in 'shellfrac->Blocks->shell'",
                                     "Did you mean 'Thickness'?", "'Material'"});
  const auto negative = panel_deck("shell", dir);
  negative->sublist("Blocks").sublist("shell").set("Thickness", -0.125);
  expect_rejected(dir, *negative, {"invalid value '-0.125' for parameter 'shellfrac->Blocks->shell->Thickness'", "> 0"});
  expect_rejected(dir, *panel_deck("skin", dir), {"mesh block 'shell'", "has no entry in the Blocks sublist"});
  const auto missing_mesh = aluminium_deck("shell", dir);
  test::set_mesh_file(*missing_mesh, "missing.exo");
  expect_rejected(dir, *missing_mesh, {"missing.exo"});
  const auto unknown_material = panel_deck("shell", dir);
  unknown_material->sublist("Blocks").sublist("shell").set("Material", std::string("steel"));
  expect_rejected(dir, *unknown_material, {"'Blocks->shell->Material' is 'steel', which is not in Materials", "'al'"});
  const auto bad_partitioner = panel_deck("shell", dir);
  bad_partitioner->sublist("Partitioning").set("Method", std::string("ParMETIS"));
  expect_rejected(dir, *bad_partitioner, {"'shellfrac->Partitioning->Method'", "'METIS' 'Zoltan2'"});
  Teuchos::ParameterList mesh_only("shellfrac");
  mesh_only.sublist("Mesh");
  expect_rejected(dir, mesh_only, {"the deck needs a 'Blocks' sublist"});
  // Plasticity parameters: the model needs a yield stress; an elastic material must not carry one.
  const auto no_yield = panel_deck("shell", dir);
  no_yield->sublist("Materials").sublist("al").set("Model", std::string("Resultant Plasticity"));
  expect_rejected(dir, *no_yield, {"'shellfrac->Materials->al' has Model = Resultant Plasticity but no positive 'Yield Stress'"});
  const auto elastic_yield = panel_deck("shell", dir);
  elastic_yield->sublist("Materials").sublist("al").set("Yield Stress", 44e3);
  expect_rejected(dir, *elastic_yield, {"gives a yield stress, hardening modulus or shear yield, which only Model = Resultant Plasticity uses"});
}
