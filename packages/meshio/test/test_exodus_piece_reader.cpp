// An Exodus mesh read in pieces by all ranks at once (exodus_piece_reader.hpp), at 1-4 ranks, against the whole
// mesh read by read_exodus_mesh: each rank's piece is exactly mesh::element_range_piece of the whole mesh for its
// element share [r W, (r + 1) W), W = ceil(N / P) (the same ids, blocks, nodes, coordinate bits and set entries),
// and the outline is the whole mesh's. A file the serial reader refuses is refused on every rank with its message.
#include <exodusII.h>
#include <gtest/gtest.h>
#include <mpi.h>

#include <string>
#include <tuple>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/meshio/exodus_piece_reader.hpp"

namespace {

using namespace shellfrac;

/// A file name of its own for this rank count (the rank counts' tests may run at once), written by rank 0.
std::string written(const mesh::SerialMesh& m, const std::string& name) {
  const std::string path = name + "_np" + std::to_string(parallel::size()) + ".exo";
  if (parallel::rank() == 0) meshio::write_exodus_mesh(m, path);
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

/// `path`, rewritten with the element id map `ids` (by position), by rank 0.
void put_element_id_map(const std::string& path, const std::vector<std::int64_t>& ids) {
  if (parallel::rank() == 0) {
    int cpu_ws = 8, io_ws = 0;
    float version = 0;
    const int id = ex_open(path.c_str(), EX_WRITE | EX_ALL_INT64_API, &cpu_ws, &io_ws, &version);
    ASSERT_GE(id, 0);
    ASSERT_GE(ex_put_id_map(id, EX_ELEM_MAP, ids.data()), 0);
    ASSERT_GE(ex_close(id), 0);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

/// Two blocks (a rectangle beside a cylindrical panel's elements renumbered after it), every kind of set.
mesh::SerialMesh two_blocks(bool p2) {
  auto m = mesh::make_rectangle(2.0, 1.0, 7, 5, mesh::DiagonalPattern::Alternating);
  const GlobalId n = m.num_elements();
  for (GlobalId e = n / 3; e < n; ++e) m.element_block[static_cast<std::size_t>(e)] = 1;
  m.blocks.push_back({"stiffener", 7});
  m.element_sets.push_back({"patch", 2, {0, 5, 7, 20, n - 1}});
  m.element_sets.push_back({"empty", 3, {}});
  m.node_sets.push_back({"scattered", 9, {0, 3, 17, m.num_nodes() - 1}});
  if (p2) mesh::promote_to_p2(m);
  return m;
}

/// Whether a and b have the same entries, compared by key(entry) (a tuple of its fields).
template <class T, class Key>
bool same_by(const std::vector<T>& a, const std::vector<T>& b, Key key) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (key(a[i]) != key(b[i])) return false;
  return true;
}

const auto label_key = [](const auto& x) { return std::tie(x.name, x.id); };
const auto set_entry_key = [](const mesh::SetEntry& x) { return std::tie(x.member, x.set); };

void expect_same_outline(const mesh::MeshOutline& a, const mesh::MeshOutline& b) {
  EXPECT_EQ(a.nodes_per_element, b.nodes_per_element);
  EXPECT_EQ(a.num_elements, b.num_elements);
  EXPECT_EQ(a.num_nodes, b.num_nodes);
  EXPECT_TRUE(same_by(a.blocks, b.blocks, label_key));
  EXPECT_TRUE(same_by(a.node_sets, b.node_sets, label_key));
  EXPECT_TRUE(same_by(a.side_sets, b.side_sets, label_key));
  EXPECT_TRUE(same_by(a.element_sets, b.element_sets, label_key));
  EXPECT_EQ(a.source, b.source);
}

void expect_same_piece(const mesh::ElementPiece& a, const mesh::ElementPiece& b) {
  EXPECT_EQ(a.nodes_per_element, b.nodes_per_element);
  EXPECT_EQ(a.elements, b.elements);
  EXPECT_EQ(a.blocks, b.blocks);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.coords, b.coords);  // bit for bit: the file's doubles
  EXPECT_TRUE(same_by(a.side_entries, b.side_entries,
                      [](const mesh::SideEntry& x) { return std::tie(x.element, x.local_edge, x.side_set); }));
  EXPECT_TRUE(same_by(a.node_set_entries, b.node_set_entries, set_entry_key));
  EXPECT_TRUE(same_by(a.element_set_entries, b.element_set_entries, set_entry_key));
  EXPECT_EQ(a.element_file_ids, b.element_file_ids);
  EXPECT_EQ(a.source, b.source);
}

/// Reads `path` in pieces and compares this rank's piece with the whole mesh's element share.
void expect_piece_of_whole_mesh(const std::string& path) {
  const mesh::MeshPiece got = meshio::read_exodus_piece(path, MPI_COMM_WORLD);
  const mesh::SerialMesh whole = meshio::read_exodus_mesh(path);
  expect_same_outline(got.outline, mesh::outline_of(whole));
  const GlobalId n = whole.num_elements(), P = parallel::size(), r = parallel::rank();
  const GlobalId w = (n + P - 1) / P;
  const mesh::ElementPiece expected = mesh::element_range_piece(whole, std::min(n, r * w), std::min(n, (r + 1) * w));
  expect_same_piece(got.piece, expected);
  // Every element on exactly one rank, every set entry once.
  EXPECT_EQ(parallel::sum(static_cast<std::int64_t>(got.piece.elements.size())), n);
  std::int64_t side_entries = 0;
  for (const auto& s : whole.side_sets) side_entries += static_cast<std::int64_t>(s.elements.size());
  EXPECT_EQ(parallel::sum(static_cast<std::int64_t>(got.piece.side_entries.size())), side_entries);
  std::int64_t element_set_entries = 0, node_set_entries = 0;
  for (const auto& s : whole.element_sets) element_set_entries += static_cast<std::int64_t>(s.elements.size());
  for (const auto& s : whole.node_sets) node_set_entries += static_cast<std::int64_t>(s.nodes.size());
  EXPECT_EQ(parallel::sum(static_cast<std::int64_t>(got.piece.element_set_entries.size())), element_set_entries);
  // A node is on every rank whose elements use it: at least once.
  EXPECT_GE(parallel::sum(static_cast<std::int64_t>(got.piece.node_set_entries.size())), node_set_entries);
  EXPECT_GT(side_entries, 0);
  EXPECT_GT(node_set_entries, 0);
}

TEST(ExodusPieceReader, Tri3TwoBlocksEverySet) { expect_piece_of_whole_mesh(written(two_blocks(false), "piece3")); }

TEST(ExodusPieceReader, Tri6TwoBlocksEverySet) { expect_piece_of_whole_mesh(written(two_blocks(true), "piece6")); }

TEST(ExodusPieceReader, CylinderWithFewerElementsThanRanksPerBlock) {
  // 2 x 3 cells of a closed cylinder: 12 elements, so at 4 ranks every share has 3; a small block of 1.
  auto m = mesh::make_cylinder(1.0, 3.0, 2, 3);
  m.element_block.back() = 1;
  m.blocks.push_back({"lid", 4});
  expect_piece_of_whole_mesh(written(m, "piece_cylinder"));
}

/// The serial reader's message for `path`, and the same on every rank from the piece reader.
void expect_refused_alike(const std::string& path) {
  std::string serial;
  try {
    meshio::read_exodus_mesh(path);
  } catch (const InputError& e) {
    serial = e.what();
  }
  ASSERT_FALSE(serial.empty()) << path << " is not refused by read_exodus_mesh";
  try {
    meshio::read_exodus_piece(path, MPI_COMM_WORLD);
    ADD_FAILURE() << path << " is not refused by read_exodus_piece";
  } catch (const InputError& e) {
    // With several ranks the message may carry the rank that found it first.
    EXPECT_NE(std::string(e.what()).find(serial), std::string::npos) << e.what() << "\nexpected: " << serial;
  }
}

TEST(ExodusPieceReader, AnElementIdMapIsReadAndChecked) {
  // The file's element ids come with the elements (messages and history name elements by them); an id map that is
  // the identity is dropped, as the serial reader drops it.
  const auto m = two_blocks(false);
  const GlobalId n = m.num_elements();
  const std::string path = written(m, "piece_ids");
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  for (GlobalId e = 0; e < n; ++e) ids[std::size_t(e)] = e + 1;
  put_element_id_map(path, ids);
  expect_piece_of_whole_mesh(path);
  EXPECT_TRUE(meshio::read_exodus_piece(path, MPI_COMM_WORLD).piece.element_file_ids.empty());
  for (GlobalId e = 0; e < n; ++e) ids[std::size_t(e)] = 5000 + 2 * (n - e);
  put_element_id_map(path, ids);
  expect_piece_of_whole_mesh(path);
  EXPECT_FALSE(meshio::read_exodus_piece(path, MPI_COMM_WORLD).piece.element_file_ids.empty());
}

TEST(ExodusPieceReader, RefusesWhatTheSerialReaderRefuses) {
  auto degenerate = mesh::make_rectangle(1.0, 1.0, 4, 4);
  degenerate.coords[degenerate.node(13, 2)] = degenerate.coords[degenerate.node(13, 0)];  // a collapsed element
  expect_refused_alike(written(degenerate, "piece_degenerate"));

  // The same element named by its id in the file, and ids given twice or not positive.
  const GlobalId n = degenerate.num_elements();
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  for (GlobalId e = 0; e < n; ++e) ids[std::size_t(e)] = 7000 + e;
  const std::string with_ids = written(degenerate, "piece_degenerate_ids");
  put_element_id_map(with_ids, ids);
  expect_refused_alike(with_ids);
  ids[25] = ids[3], ids[30] = ids[2];  // two ids given twice: the smaller one is named
  put_element_id_map(with_ids, ids);
  expect_refused_alike(with_ids);
  ids[17] = -4;
  put_element_id_map(with_ids, ids);
  expect_refused_alike(with_ids);

  auto bad_side = mesh::make_rectangle(1.0, 1.0, 4, 4);
  bad_side.side_sets.back().local_edges.back() = 5;  // written as side 8 of a TRISHELL3
  expect_refused_alike(written(bad_side, "piece_bad_side"));
}

}  // namespace
