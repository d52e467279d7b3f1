// A mesh decomposed beforehand into one file per rank (nemesis_piece_reader.hpp), at 1-4 ranks. Reference:
// tests/data/nemesis/two_blocks_tri6.exo (two TRI6 blocks, node and side sets, two element sets), decomposed by
// SEACAS nem_slice (inertial) + nem_spread for 1-4 ranks (tests/data/nemesis/make_nemesis.sh). Each rank's piece
// must be exactly mesh::piece_of_elements of the whole mesh read by read_exodus_mesh for the same elements (ids,
// blocks, nodes, coordinate bits, side and node set entries), less the element sets, which nem_spread drops; the
// pieces must hold every element once. A decomposition for another number of ranks, and files of two meshes, are
// refused on every rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/meshio/nemesis_piece_reader.hpp"

namespace {

using namespace shellfrac;

const std::string data_dir = std::string(SHELLFRAC_SOURCE_DIR) + "/tests/data/nemesis/";
const std::string base = data_dir + "two_blocks_tri6.par";

TEST(NemesisPieceReader, FileNames) {
  EXPECT_EQ(meshio::nemesis_file_name("m.par", 3, 2), "m.par.3.2");
  EXPECT_EQ(meshio::nemesis_file_name("m.par", 12, 3), "m.par.12.03");
  EXPECT_EQ(meshio::nemesis_file_name("m.par", 100, 7), "m.par.100.007");
  EXPECT_EQ(meshio::nemesis_file_name("m.par", 10, 10), "m.par.10.10");
}

TEST(NemesisPieceReader, EachRankReadsItsFileOfTheWholeMesh) {
  const mesh::MeshPiece got = meshio::read_nemesis_piece(base, MPI_COMM_WORLD);
  const mesh::SerialMesh whole = meshio::read_exodus_mesh(data_dir + "two_blocks_tri6.exo");
  ASSERT_FALSE(whole.element_sets.empty());  // so that dropping them is seen

  const mesh::MeshOutline& o = got.outline;
  EXPECT_EQ(o.nodes_per_element, 6);
  EXPECT_EQ(o.num_elements, whole.num_elements());
  EXPECT_EQ(o.num_nodes, whole.num_nodes());
  ASSERT_EQ(o.blocks.size(), whole.blocks.size());
  for (std::size_t b = 0; b < o.blocks.size(); ++b)
    EXPECT_TRUE(o.blocks[b].name == whole.blocks[b].name && o.blocks[b].id == whole.blocks[b].id) << b;
  ASSERT_EQ(o.node_sets.size(), whole.node_sets.size());
  for (std::size_t s = 0; s < o.node_sets.size(); ++s) EXPECT_EQ(o.node_sets[s].name, whole.node_sets[s].name);
  ASSERT_EQ(o.side_sets.size(), whole.side_sets.size());
  for (std::size_t s = 0; s < o.side_sets.size(); ++s) EXPECT_EQ(o.side_sets[s].name, whole.side_sets[s].name);
  EXPECT_TRUE(o.element_sets.empty());

  const mesh::ElementPiece& p = got.piece;
  mesh::ElementPiece expected = mesh::piece_of_elements(whole, p.elements);
  expected.element_set_entries.clear();
  expected.source = base;
  EXPECT_EQ(p.nodes_per_element, expected.nodes_per_element);
  EXPECT_EQ(p.blocks, expected.blocks);
  EXPECT_EQ(p.nodes, expected.nodes);
  EXPECT_EQ(p.coords, expected.coords);  // bit for bit
  const auto side_key = [](const mesh::SideEntry& x) { return std::tie(x.element, x.local_edge, x.side_set); };
  ASSERT_EQ(p.side_entries.size(), expected.side_entries.size());
  for (std::size_t i = 0; i < p.side_entries.size(); ++i)
    EXPECT_TRUE(side_key(p.side_entries[i]) == side_key(expected.side_entries[i])) << i;
  const auto set_key = [](const mesh::SetEntry& x) { return std::tie(x.member, x.set); };
  ASSERT_EQ(p.node_set_entries.size(), expected.node_set_entries.size());
  for (std::size_t i = 0; i < p.node_set_entries.size(); ++i)
    EXPECT_TRUE(set_key(p.node_set_entries[i]) == set_key(expected.node_set_entries[i])) << i;
  EXPECT_TRUE(p.element_set_entries.empty());
  EXPECT_EQ(p.source, base);

  // Every element on exactly one rank.
  std::vector<GlobalId> all = parallel::all_gather(p.elements);
  std::sort(all.begin(), all.end());
  ASSERT_EQ(static_cast<GlobalId>(all.size()), whole.num_elements());
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], static_cast<GlobalId>(i));
}

/// A folder of its own for this rank count (the rank counts' tests may run at once) holding `files` of the data
/// folder under new names (name -> data file), copied by rank 0.
std::string folder_with(const std::vector<std::pair<std::string, std::string>>& files) {
  const std::string dir = "nemesis_np" + std::to_string(parallel::size());
  if (parallel::rank() == 0) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directory(dir);
    for (const auto& [name, data] : files) std::filesystem::copy_file(data_dir + data, dir + "/" + name);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

/// The message of read_nemesis_piece(base), which must refuse it on every rank.
std::string refusal(const std::string& base) {
  try {
    meshio::read_nemesis_piece(base, MPI_COMM_WORLD);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << base << " is not refused";
  return {};
}

TEST(NemesisPieceReader, ADecompositionForOtherRanksIsRefusedOnEveryRank) {
  // The 2-rank files named as if they were for this number of ranks.
  const int P = parallel::size();
  if (P == 2) GTEST_SKIP() << "the 2-rank files are right at 2 ranks";
  std::vector<std::pair<std::string, std::string>> files;
  for (int r = 0; r < P; ++r)
    files.emplace_back(meshio::nemesis_file_name("m.par", P, r), "two_blocks_tri6.par.2." + std::to_string(r % 2));
  const std::string what = refusal(folder_with(files) + "/m.par");
  EXPECT_NE(what.find("decomposed for 2 ranks"), std::string::npos) << what;
  EXPECT_NE(what.find("the run has " + std::to_string(P) + " ranks"), std::string::npos) << what;
}

TEST(NemesisPieceReader, FilesOfTwoMeshesAreRefused) {
  // Rank 0's file of the TRI6 mesh beside rank 1's file of the TRI3 mesh, both decomposed for 2 ranks.
  if (parallel::size() != 2) GTEST_SKIP() << "the files are of 2-rank decompositions";
  const std::string dir =
      folder_with({{"m.par.2.0", "two_blocks_tri6.par.2.0"}, {"m.par.2.1", "two_blocks_tri3.par.2.1"}});
  const std::string what = refusal(dir + "/m.par");
  EXPECT_NE(what.find("m.par.2.1: its blocks, sets or element type differ from those of"), std::string::npos) << what;
}

TEST(NemesisPieceReader, AMissingDecompositionNamesThoseThere) {
  const int P = parallel::size();
  if (P == 3) GTEST_SKIP() << "the folder holds the 3-rank decomposition";
  std::vector<std::pair<std::string, std::string>> files;
  for (int r = 0; r < 3; ++r)
    files.emplace_back(meshio::nemesis_file_name("m.par", 3, r), "two_blocks_tri6.par.3." + std::to_string(r));
  const std::string what = refusal(folder_with(files) + "/m.par");
  EXPECT_NE(what.find("is not there; it is decomposed for 3 rank(s)"), std::string::npos) << what;
  EXPECT_NE(refusal("no_such_mesh.par").find("no decomposition of it is there"), std::string::npos);
}

}  // namespace
