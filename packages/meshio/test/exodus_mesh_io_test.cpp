// Tests of the Exodus II mesh reader/writer (shellfrac/meshio/exodus_mesh_io.hpp).
// References: hand-made meshes whose every entry is written out below (round trips must give them back
// exactly), and files written here with the raw Exodus C API to reproduce what other tools produce
// (TRI3 side numbering, QUAD4 blocks, mixed orders, 2-D files).
#include <exodusII.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "mesh_compare.hpp"

namespace shellfrac::meshio {
namespace {

using mesh::SerialMesh;
using test::expect_same_mesh;

/// A 2 x 1 rectangle (bent out of plane: z = 0.1 * sqrt(2) * x) cut into 4 TRI3, two blocks, every kind of set.
///   3 ---- 4 ---- 5
///   | 1  / | 3  / |
///   |  / 0 |  / 2 |
///   0 ---- 1 ---- 2
SerialMesh tri3_mesh() {
  SerialMesh m;
  m.nodes_per_element = 3;
  const double s = 0.1 * std::sqrt(2.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) m.coords.push_back({1.0 * i + 1e-13 * j, 1.0 / 3.0 * j, s * i});
  m.connectivity = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  m.element_block = {0, 0, 1, 1};
  m.blocks = {{"plate", 10}, {"patch", 20}};
  m.node_sets = {{"left", 1, {0, 3}}, {"corner", 5, {5}}};
  m.side_sets = {{"left_edge", 3, {1}, {2}}, {"bottom", 4, {0, 2}, {0, 0}}};
  m.element_sets = {{"loaded", 7, {1, 2}}};
  return m;
}

/// tri3_mesh() with a mid-side node per edge (Exodus TRI6 order: vertices, then mid-sides of edges 0-1, 1-2, 2-0).
SerialMesh tri6_mesh() {
  SerialMesh m = tri3_mesh();
  std::vector<GlobalId> conn;
  std::map<std::pair<GlobalId, GlobalId>, GlobalId> mid;
  for (GlobalId e = 0; e < m.num_elements(); ++e) {
    const GlobalId v[3] = {m.node(e, 0), m.node(e, 1), m.node(e, 2)};
    GlobalId extra[3];
    for (int k = 0; k < 3; ++k) {
      const GlobalId a = v[edge_vertex[k][0]], b = v[edge_vertex[k][1]];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it == mid.end()) {
        const Vec3 &p = m.coords[a], &q = m.coords[b];
        m.coords.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])});
        it = mid.emplace(key, m.num_nodes() - 1).first;
      }
      extra[k] = it->second;
    }
    conn.insert(conn.end(), {v[0], v[1], v[2], extra[0], extra[1], extra[2]});
  }
  m.nodes_per_element = 6;
  m.connectivity = conn;
  m.node_sets[0].nodes.push_back(mid.at({0, 3}));  // mid-side node of the left edge
  return m;
}


/// The message of the InputError thrown by f (fails the test if none is thrown).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError, nothing thrown";
  return {};
}

/// A block for write_raw: Exodus type name, nodes per element, 1-based connectivity.
struct RawBlock {
  int id;
  std::string type;
  int npe;
  std::vector<int> conn;
};

/// Writes a file with the raw Exodus API (32-bit integer API, as most tools do): blocks, optional side set.
void write_raw(const std::string& path, int dim, const std::vector<Vec3>& coords, const std::vector<RawBlock>& blocks,
               const std::vector<int>& side_elems = {}, const std::vector<int>& sides = {}) {
  int cpu = 8, io = 8;
  const int exo = ex_create(path.c_str(), EX_CLOBBER, &cpu, &io);
  ASSERT_GE(exo, 0);
  int ne = 0;
  for (const auto& b : blocks) ne += static_cast<int>(b.conn.size()) / b.npe;
  ASSERT_GE(ex_put_init(exo, "raw", dim, static_cast<int>(coords.size()), ne, static_cast<int>(blocks.size()), 0,
                        side_elems.empty() ? 0 : 1),
            0);
  std::vector<double> x, y, z;
  for (const auto& c : coords) x.push_back(c[0]), y.push_back(c[1]), z.push_back(c[2]);
  ASSERT_GE(ex_put_coord(exo, x.data(), y.data(), dim == 3 ? z.data() : nullptr), 0);
  for (const auto& b : blocks) {
    ASSERT_GE(ex_put_block(exo, EX_ELEM_BLOCK, b.id, b.type.c_str(), static_cast<int>(b.conn.size()) / b.npe, b.npe,
                           0, 0, 0),
              0);
    ASSERT_GE(ex_put_conn(exo, EX_ELEM_BLOCK, b.id, b.conn.data(), nullptr, nullptr), 0);
  }
  if (!side_elems.empty()) {
    ASSERT_GE(ex_put_set_param(exo, EX_SIDE_SET, 1, static_cast<int>(side_elems.size()), 0), 0);
    ASSERT_GE(ex_put_set(exo, EX_SIDE_SET, 1, side_elems.data(), sides.data()), 0);
  }
  ASSERT_EQ(ex_close(exo), 0);
}

const std::vector<Vec3> unit_square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

// Reference: tri3_mesh() itself; write then read must reproduce it exactly.
TEST(ExodusMeshIo, RoundTripTri3) {
  const SerialMesh m = tri3_mesh();
  write_exodus_mesh(m, "exodus_mesh_io_tri3.exo");
  const SerialMesh r = read_exodus_mesh("exodus_mesh_io_tri3.exo");
  expect_same_mesh(m, r);
  EXPECT_EQ(r.source, "exodus_mesh_io_tri3.exo");
  expect_same_mesh(m, read_mesh_file("exodus_mesh_io_tri3.exo"));  // dispatch by extension
}

// Reference: tri6_mesh() itself (TRI6 node order is the Exodus order, so nothing is permuted).
TEST(ExodusMeshIo, RoundTripTri6) {
  const SerialMesh m = tri6_mesh();
  write_exodus_mesh(m, "exodus_mesh_io_tri6.e");
  expect_same_mesh(m, read_mesh_file("exodus_mesh_io_tri6.e"));
}

// Reference: tri3_mesh() plus an element block without elements (Exodus stores it with type "NULL").
TEST(ExodusMeshIo, EmptyBlockRoundTrip) {
  SerialMesh m = tri3_mesh();
  m.blocks.push_back({"unused", 30});
  write_exodus_mesh(m, "exodus_mesh_io_empty_block.exo");
  expect_same_mesh(m, read_exodus_mesh("exodus_mesh_io_empty_block.exo"));
}

// Reference: Exodus numbers elements block by block, so a mesh whose blocks interleave comes back with its
// elements grouped by block (0, 2 | 1, 3) and its sets renumbered accordingly; worked out by hand below.
TEST(ExodusMeshIo, InterleavedBlocksAreGroupedAndSetsFollow) {
  SerialMesh m = tri3_mesh();
  m.element_block = {0, 1, 0, 1};
  write_exodus_mesh(m, "exodus_mesh_io_interleaved.exo");
  const SerialMesh r = read_exodus_mesh("exodus_mesh_io_interleaved.exo");
  EXPECT_EQ(r.element_block, (std::vector<int>{0, 0, 1, 1}));
  EXPECT_EQ(r.connectivity, (std::vector<GlobalId>{0, 1, 4, 1, 2, 5, 0, 4, 3, 1, 5, 4}));
  EXPECT_EQ(r.side_sets[0].elements, (std::vector<GlobalId>{2}));     // old element 1
  EXPECT_EQ(r.side_sets[1].elements, (std::vector<GlobalId>{0, 1}));  // old 0, 2
  EXPECT_EQ(r.element_sets[0].elements, (std::vector<GlobalId>{1, 2}));  // old 2, 1 -> sorted
}

// Reference: the Exodus convention for TRI (non-shell) sides, 1, 2, 3 = edges 0, 1, 2; 2-D files get z = 0;
// the default names "block_<id>" / "sideset_<id>" (header).
TEST(ExodusMeshIo, Tri3SidesAnd2dCoordinates) {
  write_raw("exodus_mesh_io_2d.exo", 2, unit_square, {{4, "TRI3", 3, {1, 2, 3, 1, 3, 4}}}, {2, 1}, {3, 1});
  const SerialMesh r = read_exodus_mesh("exodus_mesh_io_2d.exo");
  EXPECT_EQ(r.nodes_per_element, 3);
  EXPECT_EQ(r.coords, unit_square);
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_EQ(r.blocks[0].name, "block_4");
  ASSERT_EQ(r.side_sets.size(), 1u);
  EXPECT_EQ(r.side_sets[0].name, "sideset_1");
  EXPECT_EQ(r.side_sets[0].elements, (std::vector<GlobalId>{1, 0}));
  EXPECT_EQ(r.side_sets[0].local_edges, (std::vector<int>{2, 0}));
}

// Reference: the header's error contract (InputError naming the file).
TEST(ExodusMeshIo, MissingFileAndUnknownExtension) {
  const std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_no_such_file.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_no_such_file.exo"), std::string::npos) << msg;
  EXPECT_NE(input_error([] { read_mesh_file("exodus_mesh_io_no_such_file.g"); }).find("exodus_mesh_io_no_such_file.g"),
            std::string::npos);
  { std::ofstream("exodus_mesh_io_model.stl") << "solid x\n"; }
  const std::string ext = input_error([] { read_mesh_file("exodus_mesh_io_model.stl"); });
  EXPECT_NE(ext.find("exodus_mesh_io_model.stl"), std::string::npos) << ext;
  EXPECT_NE(ext.find("extension"), std::string::npos) << ext;
}

// Reference: the header's error contract; a file that is not netCDF at all must not crash the reader.
TEST(ExodusMeshIo, GarbageFileIsAnInputError) {
  { std::ofstream("exodus_mesh_io_garbage.exo") << "this is not an Exodus file\n"; }
  const std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_garbage.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_garbage.exo"), std::string::npos) << msg;
}

// Reference: the header: QUAD4 is not a shell triangle; the message names the file, the block and the type.
TEST(ExodusMeshIo, Quad4BlockIsRejected) {
  write_raw("exodus_mesh_io_quad4.exo", 3, unit_square, {{12, "QUAD4", 4, {1, 2, 3, 4}}});
  const std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_quad4.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_quad4.exo"), std::string::npos) << msg;
  EXPECT_NE(msg.find("element block 12"), std::string::npos) << msg;
  EXPECT_NE(msg.find("QUAD4"), std::string::npos) << msg;
}

// Reference: the header: all blocks must have the same number of nodes per element.
TEST(ExodusMeshIo, MixedTri3Tri6IsRejected) {
  std::vector<Vec3> c = unit_square;
  c.push_back({0.5, 0, 0});
  c.push_back({1, 0.5, 0});
  c.push_back({0.5, 0.5, 0});
  c.push_back({0.5, 1, 0});
  c.push_back({0, 0.5, 0});
  write_raw("exodus_mesh_io_mixed.exo", 3, c,
            {{1, "TRISHELL3", 3, {1, 2, 3}}, {2, "TRISHELL6", 6, {1, 3, 4, 7, 8, 9}}});
  const std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_mixed.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_mixed.exo"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mixed TRI3/TRI6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("element block 2"), std::string::npos) << msg;
}

// Reference: the header's hostile-file contract: out-of-range node numbers and shell faces in side sets.
TEST(ExodusMeshIo, BadConnectivityAndShellFaceSides) {
  write_raw("exodus_mesh_io_badconn.exo", 3, unit_square, {{1, "TRISHELL3", 3, {1, 2, 9}}});
  std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_badconn.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_badconn.exo"), std::string::npos) << msg;
  EXPECT_NE(msg.find("node 9"), std::string::npos) << msg;

  write_raw("exodus_mesh_io_face.exo", 3, unit_square, {{1, "TRISHELL3", 3, {1, 2, 3}}}, {1}, {1});
  msg = input_error([] { read_exodus_mesh("exodus_mesh_io_face.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_face.exo"), std::string::npos) << msg;
  EXPECT_NE(msg.find("side set 1"), std::string::npos) << msg;
}

// Found on an earlier version: a file whose element id map gives one id to two elements was read, and messages
// then named positions while the file's tools name ids. Two elements with id 7, and a node with id 0, are refused.
TEST(ExodusMeshIo, DuplicateOrNonPositiveIdsInTheIdMapsAreRefused) {
  const std::vector<Vec3> c = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto with_map = [&](const std::string& path, ex_entity_type type, std::vector<int> ids) {
    write_raw(path, 3, c, {{1, "TRISHELL3", 3, {1, 2, 3, 1, 3, 4}}});
    int cpu = 8, io = 8;
    float version = 0;
    const int exo = ex_open(path.c_str(), EX_WRITE, &cpu, &io, &version);
    ASSERT_GE(exo, 0);
    ASSERT_GE(ex_put_id_map(exo, type, ids.data()), 0);
    ASSERT_EQ(ex_close(exo), 0);
  };
  with_map("exodus_mesh_io_elem_ids.exo", EX_ELEM_MAP, {7, 7});
  EXPECT_EQ(input_error([] { read_exodus_mesh("exodus_mesh_io_elem_ids.exo"); }),
            "exodus_mesh_io_elem_ids.exo: the element id 7 is given to elements 1 and 2 (positions in the file) by its "
            "element id map; ids must be unique");
  with_map("exodus_mesh_io_node_ids.exo", EX_NODE_MAP, {10, 20, 0, 40});
  EXPECT_EQ(input_error([] { read_exodus_mesh("exodus_mesh_io_node_ids.exo"); }),
            "exodus_mesh_io_node_ids.exo: node 3 has the id 0 in the file's node id map; ids must be positive");
  with_map("exodus_mesh_io_good_ids.exo", EX_ELEM_MAP, {1001, 7});
  const auto m = read_exodus_mesh("exodus_mesh_io_good_ids.exo");
  EXPECT_EQ(m.num_elements(), 2);
  EXPECT_EQ(m.element_ids.ids, (std::vector<std::int64_t>{1001, 7}));
  EXPECT_TRUE(m.node_ids.empty());  // no node map: the positions
  EXPECT_EQ(m.element_ids.element(0), "element 1001 (1 in the results)");
  with_map("exodus_mesh_io_identity_ids.exo", EX_ELEM_MAP, {1, 2});
  EXPECT_TRUE(read_exodus_mesh("exodus_mesh_io_identity_ids.exo").element_ids.empty());
}

// Issue: messages named elements and nodes by their position in the file while the file's tools (its id maps)
// name them by id. Element 2 (id 7) uses its third node (id 30) twice: the message names both by their ids, and
// the element by its number in the results too.
TEST(ExodusMeshIo, MessagesNameElementsAndNodesByTheFilesIds) {
  const std::string path = "exodus_mesh_io_named_ids.exo";
  write_raw(path, 3, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{1, "TRISHELL3", 3, {1, 2, 3, 1, 3, 3}}});
  int cpu = 8, io = 8;
  float version = 0;
  const int exo = ex_open(path.c_str(), EX_WRITE, &cpu, &io, &version);
  ASSERT_GE(exo, 0);
  const std::vector<int> elements = {1001, 7}, nodes = {10, 20, 30, 40};
  ASSERT_GE(ex_put_id_map(exo, EX_ELEM_MAP, elements.data()), 0);
  ASSERT_GE(ex_put_id_map(exo, EX_NODE_MAP, nodes.data()), 0);
  ASSERT_EQ(ex_close(exo), 0);
  EXPECT_EQ(input_error([&] { read_exodus_mesh(path); }),
            path + ": element 7 (2 in the results) uses node 30 twice");
}

// Fuzzing regressions (docs/hostile_input.md). Files are crafted byte by byte or patched from a written mesh.

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

/// Big-endian 32-bit integer, as netCDF classic headers store them.
std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

// Reference: fuzz_exodus found that libnetcdf allocates (and touches) whatever a classic header declares
// before checking it: a 3 kB file declaring a variable with 2^31 dimensions took 6.5 GB and 2 minutes. The
// reader now checks the header first. This file: CDF-1, no dimensions, no attributes, one variable "x" with
// 0x7fffffff dimension ids, then 64 zero bytes.
TEST(ExodusMeshIo, NetcdfHeaderWithHugeDimensionCountIsAnInputError) {
  const std::string path = "exodus_mesh_io_huge_rank.exo";
  write_bytes(path, std::string("CDF\x01", 4) + be32(0) + be32(0) + be32(0) + be32(0) + be32(0) + be32(11) + be32(1) +
                        be32(1) + std::string("x\0\0\0", 4) + be32(0x7fffffff) + std::string(64, '\0'));
  const std::string msg = input_error([&] { read_exodus_mesh(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("corrupt or truncated netCDF header: variable dimension count 2147483647"), std::string::npos) << msg;
}

// Reference: same check for the other lists of the header: a truncated header and an unknown attribute type.
TEST(ExodusMeshIo, NetcdfHeaderTruncatedOrBadTypeIsAnInputError) {
  write_exodus_mesh(tri3_mesh(), "exodus_mesh_io_cut_src.exo");
  const std::string bytes = read_bytes("exodus_mesh_io_cut_src.exo");
  write_bytes("exodus_mesh_io_cut.exo", bytes.substr(0, 200));
  std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_cut.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_cut.exo: "), std::string::npos) << msg;
  EXPECT_NE(msg.find(" netCDF header"), std::string::npos) << msg;
  // Dimension list with one dimension "d" of length 1, then a global attribute "a" of type 99.
  write_bytes("exodus_mesh_io_bad_type.exo", std::string("CDF\x01", 4) + be32(0) + be32(10) + be32(1) + be32(1) +
                                                 std::string("d\0\0\0", 4) + be32(1) + be32(12) + be32(1) + be32(1) +
                                                 std::string("a\0\0\0", 4) + be32(99) + be32(0) + be32(0) + be32(0));
  msg = input_error([] { read_exodus_mesh("exodus_mesh_io_bad_type.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_bad_type.exo: corrupt netCDF header: unknown data type 99"), std::string::npos)
      << msg;
}

/// Copies the netCDF file `src` to `dst` (64-bit offset format) with the dimension num_nodes set to `nodes`
/// and the coordinate variables either defined last and never written (`define_coordinates`) or left out;
/// then cuts the file to `keep` bytes (0: no cut). Either way a small file whose header is valid for netCDF
/// but declares far more nodes than it stores.
void copy_with_missing_coordinates(const std::string& src, const std::string& dst, std::size_t nodes,
                                   bool define_coordinates, std::uintmax_t keep) {
  int in = -1, out = -1, old_fill = 0, ndims = 0, nvars = 0, ngatts = 0, unlimited = -1;
  ASSERT_EQ(nc_open(src.c_str(), NC_NOWRITE, &in), NC_NOERR);
  ASSERT_EQ(nc_create(dst.c_str(), NC_CLOBBER | NC_64BIT_OFFSET, &out), NC_NOERR);
  ASSERT_EQ(nc_set_fill(out, NC_NOFILL, &old_fill), NC_NOERR);
  ASSERT_EQ(nc_inq(in, &ndims, &nvars, &ngatts, &unlimited), NC_NOERR);
  char name[NC_MAX_NAME + 1];
  for (int d = 0; d < ndims; ++d) {
    std::size_t len = 0;
    int id = -1;
    ASSERT_EQ(nc_inq_dim(in, d, name, &len), NC_NOERR);
    if (std::string(name) == "num_nodes") len = nodes;
    ASSERT_EQ(nc_def_dim(out, name, d == unlimited ? NC_UNLIMITED : len, &id), NC_NOERR);
    ASSERT_EQ(id, d);
  }
  for (int a = 0; a < ngatts; ++a) {
    ASSERT_EQ(nc_inq_attname(in, NC_GLOBAL, a, name), NC_NOERR);
    ASSERT_EQ(nc_copy_att(in, NC_GLOBAL, name, out, NC_GLOBAL), NC_NOERR);
  }
  auto is_coordinate = [](const std::string& n) { return n == "coordx" || n == "coordy" || n == "coordz"; };
  std::vector<int> order, data_vars;
  for (int pass = 0; pass < 2; ++pass)
    for (int v = 0; v < nvars; ++v) {
      ASSERT_EQ(nc_inq_varname(in, v, name), NC_NOERR);
      if (is_coordinate(name) == (pass == 1) && (define_coordinates || !is_coordinate(name))) order.push_back(v);
    }
  for (int v : order) {
    nc_type type;
    int nd = 0, natts = 0, dims[NC_MAX_VAR_DIMS], id = -1;
    ASSERT_EQ(nc_inq_var(in, v, name, &type, &nd, dims, &natts), NC_NOERR);
    ASSERT_EQ(nc_def_var(out, name, type, nd, dims, &id), NC_NOERR);
    char att[NC_MAX_NAME + 1];
    for (int a = 0; a < natts; ++a) {
      ASSERT_EQ(nc_inq_attname(in, v, a, att), NC_NOERR);
      ASSERT_EQ(nc_copy_att(in, v, att, out, id), NC_NOERR);
    }
  }
  ASSERT_EQ(nc_enddef(out), NC_NOERR);
  for (int v : order) {
    nc_type type;
    int nd = 0, natts = 0, dims[NC_MAX_VAR_DIMS], id = -1;
    ASSERT_EQ(nc_inq_var(in, v, name, &type, &nd, dims, &natts), NC_NOERR);
    if (is_coordinate(name)) continue;
    std::size_t count = 1, type_size = 0;
    for (int d = 0; d < nd; ++d) {
      std::size_t len = 0;
      ASSERT_EQ(nc_inq_dimlen(in, dims[d], &len), NC_NOERR);
      count *= len;
    }
    if (count == 0) continue;
    ASSERT_EQ(nc_inq_type(in, type, nullptr, &type_size), NC_NOERR);
    std::vector<char> buffer(count * type_size);
    ASSERT_EQ(nc_get_var(in, v, buffer.data()), NC_NOERR);
    ASSERT_EQ(nc_inq_varid(out, name, &id), NC_NOERR);
    ASSERT_EQ(nc_put_var(out, id, buffer.data()), NC_NOERR);
  }
  ASSERT_EQ(nc_close(in), NC_NOERR);
  ASSERT_EQ(nc_close(out), NC_NOERR);
  if (keep > 0) std::filesystem::resize_file(dst, keep);
}

// Reference: a 4 kB file (valid netCDF header, coordinates cut off) declaring 4194304 nodes: the reader used
// to allocate the declared coordinates before reading them (with 2^27 nodes: 6.3 GB and 24 s, then a
// misleading "degenerate element" message, since netCDF reads zeros past the end of the file). Now: the data
// of every variable must lie in the file; and the declared counts must fit in the file even where the
// variables are missing altogether.
TEST(ExodusMeshIo, HeaderCountsLargerThanTheFileAreAnInputError) {
  write_exodus_mesh(tri3_mesh(), "exodus_mesh_io_big_src.exo");
  copy_with_missing_coordinates("exodus_mesh_io_big_src.exo", "exodus_mesh_io_big_nodes.exo", 4194304, true, 4096);
  std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_big_nodes.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_big_nodes.exo: truncated file: the data of variable 'coordx' end at byte "),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(", but the file has 4096 bytes"), std::string::npos) << msg;
  copy_with_missing_coordinates("exodus_mesh_io_big_src.exo", "exodus_mesh_io_no_coords.exo", 4194304, false, 0);
  msg = input_error([] { read_exodus_mesh("exodus_mesh_io_no_coords.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_no_coords.exo: the file declares 4194304 nodes, more than its "),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(" bytes can hold (truncated or corrupt file)"), std::string::npos) << msg;
}

/// Writes tri3_mesh() to `path`, then edits it with the netCDF API in define mode (`edit(ncid)`).
template <class Edit>
void write_and_edit(const std::string& path, Edit edit) {
  write_exodus_mesh(tri3_mesh(), path);
  int nc = -1;
  ASSERT_EQ(nc_open(path.c_str(), NC_WRITE, &nc), NC_NOERR);
  ASSERT_EQ(nc_redef(nc), NC_NOERR);
  edit(nc);
  ASSERT_EQ(nc_close(nc), NC_NOERR);
}

// Reference: fuzz_exodus found that libexodusII reads whole variables (coordinates, connectivity, ids, set
// entries) into buffers sized by the Exodus dimensions: a variable larger than its dimensions overflowed the
// heap (valgrind: invalid writes). Each variable is replaced by one over the 81-long dimension len_line.
TEST(ExodusMeshIo, VariableLargerThanItsDimensionsIsAnInputError) {
  for (const std::string var : {"coordx", "connect1", "eb_prop1", "node_ns1", "elem_ss1", "elem_els1"}) {
    const std::string path = "exodus_mesh_io_wide_" + var + ".exo";
    write_and_edit(path, [&](int nc) {
      int id = -1, len_line = -1;
      ASSERT_EQ(nc_inq_varid(nc, var.c_str(), &id), NC_NOERR) << var;
      ASSERT_EQ(nc_rename_var(nc, id, (var + "_old").c_str()), NC_NOERR);
      ASSERT_EQ(nc_inq_dimid(nc, "len_line", &len_line), NC_NOERR);
      ASSERT_EQ(nc_def_var(nc, var.c_str(), NC_INT, 1, &len_line, &id), NC_NOERR);
    });
    const std::string msg = input_error([&] { read_exodus_mesh(path); });
    EXPECT_NE(msg.find(path + ": corrupt Exodus file: variable '" + var + "' has 81 values"), std::string::npos)
        << msg;
  }
}

// Reference: fuzz_exodus: ex_open reads global attributes such as the word size into one number; with more
// values it smashed the stack. The element type of a block is read into a 33-character buffer (ASan:
// stack-buffer-overflow with a 5000-character type).
TEST(ExodusMeshIo, OversizedAttributesAreAnInputError) {
  write_and_edit("exodus_mesh_io_multi_ws.exo", [](int nc) {
    const std::vector<int> values(1000, 8);
    ASSERT_EQ(nc_put_att_int(nc, NC_GLOBAL, "floating_point_word_size", NC_INT, values.size(), values.data()),
              NC_NOERR);
  });
  std::string msg = input_error([] { read_exodus_mesh("exodus_mesh_io_multi_ws.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_multi_ws.exo: corrupt Exodus file: global attribute 'floating_point_word_size' "
                     "has 1000 values instead of one"),
            std::string::npos)
      << msg;
  write_and_edit("exodus_mesh_io_long_type.exo", [](int nc) {
    int id = -1;
    ASSERT_EQ(nc_inq_varid(nc, "connect1", &id), NC_NOERR);
    const std::string type = "TRISHELL3" + std::string(5000, 'X');
    ASSERT_EQ(nc_put_att_text(nc, id, "elem_type", type.size(), type.c_str()), NC_NOERR);
  });
  msg = input_error([] { read_exodus_mesh("exodus_mesh_io_long_type.exo"); });
  EXPECT_NE(msg.find("exodus_mesh_io_long_type.exo: corrupt Exodus file: the element type of variable 'connect1' is "
                     "5009 characters long (at most 32)"),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace shellfrac::meshio
