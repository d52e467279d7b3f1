// Tests of meshio::read_gmsh (gmsh_reader.hpp): hand-written files with exactly known content, a curved P2
// mesh made by the gmsh CLI at test time in the four format variants, and error cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"
#include "mesh_compare.hpp"

namespace shellfrac::meshio {
namespace {

using mesh::SerialMesh;
using test::expect_same_mesh;

const std::string data_dir = std::string(SHELLFRAC_SOURCE_DIR) + "/tests/data/gmsh/";

/// Writes `content` to `name` in the working directory (the test's build dir); returns the name.
std::string write_file(const std::string& name, const std::string& content) {
  std::ofstream out(name, std::ios::binary);
  out << content;
  EXPECT_TRUE(out.good()) << "cannot write " << name;
  return name;
}

std::string read_whole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Reads `path` expecting an InputError whose message names the file and contains every phrase.
void expect_input_error(const std::string& path, const std::vector<std::string>& phrases) {
  try {
    read_gmsh(path);
    ADD_FAILURE() << path << ": no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << "message does not name the file: " << msg;
    for (const std::string& p : phrases) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": wrong exception type: " << e.what();
  }
}


// -----------------------------------------------------------------------------------------------------------
// Hand-written unit square: 4 triangles around a centre node, sparse unsorted node tags, an unused node.

/// The mesh that tests/data/gmsh/square_v22.msh and square_v41.msh describe, worked out by hand from the
/// mapping in gmsh_reader.hpp:
///  * node tags sorted 7, 10, 20, 30, 40 -> 0..4 (centre, (1,0), (0,1), (1,1), (0,0)); tag 99 is unused.
///  * triangles sorted by tag 101..104; all in surface group 3 "plate"; 102 also in group 5 (no name) ->
///    element set "block_5".
///  * curve group 1 "bottom" = line 40-10 = edge 0 of triangle 101 (nodes 4,1,0); curve group 2 "left" =
///    line 20-40 = edge 0 of triangle 104 (nodes 2,4,0).
///  * point group 1 "origin" = node 40; node-set id 1 is taken by curve "bottom" -> next free id, 3.
SerialMesh expected_square(const std::string& path) {
  SerialMesh m;
  m.nodes_per_element = 3;
  m.coords = {{0.5, 0.5, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 0}};
  m.connectivity = {4, 1, 0, 1, 3, 0, 3, 2, 0, 2, 4, 0};
  m.element_block = {0, 0, 0, 0};
  m.blocks = {{"plate", 3}};
  m.element_sets = {{"block_5", 5, {1}}};
  m.side_sets = {{"bottom", 1, {0}, {0}}, {"left", 2, {3}, {0}}};
  m.node_sets = {{"bottom", 1, {1, 4}}, {"left", 2, {2, 4}}, {"origin", 3, {4}}};
  m.source = path;
  return m;
}

TEST(GmshReader, HandWrittenV22) {
  const std::string path = data_dir + "square_v22.msh";
  const SerialMesh m = read_gmsh(path);
  EXPECT_EQ(m.source, path);
  expect_same_mesh(m, expected_square(path));
}

TEST(GmshReader, HandWrittenV41) {
  const std::string path = data_dir + "square_v41.msh";
  const SerialMesh m = read_gmsh(path);
  EXPECT_EQ(m.source, path);
  expect_same_mesh(m, expected_square(path));
}

/// Appends the bytes of v in the requested byte order.
template <class T>
void put(std::string& s, T v, bool big_endian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  const bool host_little = first == 1;
  if (big_endian == host_little) std::reverse(b, b + sizeof(T));
  s.append(reinterpret_cast<const char*>(b), sizeof(T));
}

/// square_v22.msh in binary 2.2, in either byte order (the reader must honour the endianness marker).
std::string square_binary_22(bool big_endian, std::int32_t marker = 1) {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  put<std::int32_t>(s, marker, big_endian);
  s += "\n$EndMeshFormat\n$PhysicalNames\n4\n0 1 \"origin\"\n1 1 \"bottom\"\n1 2 \"left\"\n2 3 \"plate\"\n"
       "$EndPhysicalNames\n$Nodes\n6\n";
  const std::vector<std::pair<int, Vec3>> nodes = {{40, {0, 0, 0}}, {10, {1, 0, 0}}, {30, {1, 1, 0}},
                                                   {20, {0, 1, 0}}, {99, {5, 5, 5}}, {7, {0.5, 0.5, 0}}};
  for (const auto& [tag, x] : nodes) {
    put<std::int32_t>(s, tag, big_endian);
    for (double c : x) put<double>(s, c, big_endian);
  }
  s += "\n$EndNodes\n$Elements\n8\n";
  // Blocks of (type, count, ntags), then count records (tag, physical, elementary, nodes...).
  const std::vector<std::pair<std::array<int, 3>, std::vector<std::vector<int>>>> blocks = {
      {{15, 1, 2}, {{301, 1, 1, 40}}},
      {{1, 2, 2}, {{202, 1, 1, 40, 10}, {201, 2, 4, 20, 40}}},
      {{2, 5, 2},
       {{103, 3, 1, 30, 20, 7}, {101, 3, 1, 40, 10, 7}, {104, 3, 1, 20, 40, 7}, {102, 3, 1, 10, 30, 7},
        {102, 5, 2, 10, 30, 7}}}};
  for (const auto& [header, records] : blocks) {
    for (int v : header) put<std::int32_t>(s, v, big_endian);
    for (const auto& r : records)
      for (int v : r) put<std::int32_t>(s, v, big_endian);
  }
  s += "\n$EndElements\n";
  return s;
}

TEST(GmshReader, HandWrittenBinaryV22BothByteOrders) {
  for (bool big : {false, true}) {
    const std::string path = write_file(big ? "square_v22_be.msh" : "square_v22_le.msh", square_binary_22(big));
    expect_same_mesh(read_gmsh(path), expected_square(path));
  }
  expect_input_error(write_file("square_bad_marker.msh", square_binary_22(false, 2)), {"endianness marker"});
}

// -----------------------------------------------------------------------------------------------------------
// Errors

TEST(GmshReaderErrors, MissingFile) {
  expect_input_error("no_such_mesh.msh", {"cannot open mesh file", "no such file"});
}

/// The body of square_v22.msh from $Nodes on, with the $Elements section replaced.
std::string square_v22_with_elements(const std::string& elements) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n40 0 0 0\n10 1 0 0\n30 1 1 0\n20 0 1 0\n"
         "99 5 5 5\n7 0.5 0.5 0\n$EndNodes\n$Elements\n" +
         elements + "$EndElements\n";
}

TEST(GmshReaderErrors, QuadrilateralElement) {
  const std::string path =
      write_file("quad.msh", square_v22_with_elements("2\n1 2 2 1 1 40 10 7\n2 3 2 1 1 40 10 30 20\n"));
  expect_input_error(path, {"line 16", "element type 3", "quadrangle", "not supported"});
  const std::string tet = write_file("tet.msh", square_v22_with_elements("1\n1 4 2 1 1 40 10 30 7\n"));
  expect_input_error(tet, {"element type 4", "tetrahedron", "not supported"});
}

TEST(GmshReaderErrors, UnsupportedVersion) {
  for (const std::string v : {"4.0", "3.0", "2.1", "x"}) {
    const std::string path = write_file("version.msh", "$MeshFormat\n" + v + " 0 8\n$EndMeshFormat\n");
    expect_input_error(path, {"unsupported Gmsh file format version '" + v + "'", "2.2 and 4.1"});
  }
  expect_input_error(write_file("not_gmsh.msh", "solid cube\nfacet normal 0 0 1\n"), {"not a Gmsh .msh file"});
}

TEST(GmshReaderErrors, UnknownNode) {
  const std::string path =
      write_file("unknown_node.msh", square_v22_with_elements("2\n101 2 2 3 1 40 10 7\n102 2 2 3 1 10 55 7\n"));
  expect_input_error(path, {"element 102", "unknown node 55"});
}

TEST(GmshReaderErrors, LineNotOnTriangleEdge) {
  // 40-30 is the diagonal of the square; the triangles only have its halves 40-7 and 7-30 as edges.
  const std::string path = write_file(
      "line_off_edge.msh", square_v22_with_elements("5\n101 2 2 3 1 40 10 7\n102 2 2 3 1 10 30 7\n"
                                                    "103 2 2 3 1 30 20 7\n104 2 2 3 1 20 40 7\n"
                                                    "201 1 2 2 2 40 30\n"));
  expect_input_error(path, {"line element 201", "not an edge of any triangle"});
}

TEST(GmshReaderErrors, MixedTriangleOrders) {
  const std::string path =
      write_file("mixed.msh", square_v22_with_elements("2\n101 2 2 3 1 40 10 7\n102 9 2 3 1 10 30 7 40 20 99\n"));
  expect_input_error(path, {"mixed 3- and 6-node triangles"});
}

TEST(GmshReaderErrors, HostileCounts) {
  // Counts far larger than the file: must be refused before any allocation.
  expect_input_error(write_file("huge_nodes.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
                                                  "999999999999999\n1 0 0 0\n$EndNodes\n"),
                     {"line 5", "number of nodes 999999999999999", "larger than the rest of the file"});
  expect_input_error(write_file("huge_blocks.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n"
                                                   "1 2 1 2\n2 1 0 4000000000000\n1\n2\n$EndNodes\n"),
                     {"larger than the rest of the file"});
  expect_input_error(write_file("negative.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n-3\n$EndNodes\n"),
                     {"number of nodes -3 is out of range"});
  // Binary 4.1 whose node count is 2^64 - 1 right after the header.
  std::string s = "$MeshFormat\n4.1 1 8\n";
  put<std::int32_t>(s, 1, false);
  s += "\n$EndMeshFormat\n$Nodes\n";
  for (std::uint64_t v : {std::uint64_t{1}, ~std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{2}})
    put<std::uint64_t>(s, v, false);
  expect_input_error(write_file("huge_binary.msh", s), {"larger than the rest of the file"});
}

// Fuzzing regression (docs/hostile_input.md): a physical tag of 2147483647 is legal in Gmsh, but when a later
// set clashed with it, "one more than the largest id" overflowed int (UBSan: signed integer overflow in
// unique_id). Here curve "left" and point "origin" both have tag 2147483647: the point's node set must get
// the smallest free id instead, 2 (1 is curve "bottom").
TEST(GmshReaderErrors, LargestPhysicalTagClash) {
  std::string s = read_whole(data_dir + "square_v22.msh");
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    s.replace(at, from.size(), to);
  };
  replace("0 1 \"origin\"", "0 2147483647 \"origin\"");
  replace("1 2 \"left\"", "1 2147483647 \"left\"");
  replace("301 15 2 1 1 40", "301 15 2 2147483647 1 40");
  replace("201 1 2 2 4 20 40", "201 1 2 2147483647 4 20 40");
  const SerialMesh m = read_gmsh(write_file("max_tag.msh", s));
  std::map<std::string, int> ids;
  for (const auto& ns : m.node_sets) ids[ns.name] = ns.id;
  EXPECT_EQ(ids, (std::map<std::string, int>{{"bottom", 1}, {"left", 2147483647}, {"origin", 2}}));
}

// A periodic mesh (its correspondences were ignored: the periodic boundaries became free edges, silently) and a
// mesh partitioned by Gmsh (refused with "entity not in $Entities") are refused as unsupported. An empty $Periodic
// section, as Gmsh writes when nothing is periodic, is read.
TEST(GmshReaderErrors, PeriodicAndPartitionedMeshesAreUnsupported) {
  const std::string s = read_whole(data_dir + "square_v41.msh");
  ASSERT_NE(s.find("$Periodic\n0\n$EndPeriodic"), std::string::npos);
  std::string periodic = s;
  periodic.replace(periodic.find("$Periodic\n0\n"), 12, "$Periodic\n1\n1 2 1\n0\n1\n10 20\n");
  expect_input_error(write_file("periodic.msh", periodic),
                     {"$Periodic (periodic node correspondences) is not supported: the periodic boundaries would be "
                      "free edges; mesh without Periodic constraints"});
  std::string partitioned = s;
  partitioned.replace(partitioned.find("$Nodes"), 6, "$PartitionedEntities\n2\n0\n$EndPartitionedEntities\n$Nodes");
  expect_input_error(write_file("partitioned.msh", partitioned),
                     {"$PartitionedEntities: the mesh was partitioned by Gmsh, which is not supported; save it "
                      "unpartitioned (shellfrac partitions the mesh itself: Partitioning sublist)"});
}

/// Reads every prefix length in [0, data.size()) with the given stride. A prefix must give an InputError
/// naming the file unless it ends (up to blanks) with "$EndElements" or "$EndPeriodic" (then it is a
/// complete file). Past the $MeshFormat section, the message must say the file looks truncated.
void check_prefixes(const std::string& name, const std::string& data, std::size_t stride) {
  const std::size_t header_end = data.find("$EndMeshFormat") + std::strlen("$EndMeshFormat");
  for (std::size_t len = 0; len < data.size(); len += (len + stride < data.size() ? stride : 1)) {
    std::string prefix = data.substr(0, len);
    std::string trimmed = prefix;
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.pop_back();
    auto ends_with = [&](const std::string& t) {
      return trimmed.size() >= t.size() && trimmed.compare(trimmed.size() - t.size(), t.size(), t) == 0;
    };
    const bool complete = ends_with("$EndElements") || ends_with("$EndPeriodic");
    const std::string path = write_file(name, prefix);
    try {
      read_gmsh(path);
      EXPECT_TRUE(complete) << name << ": prefix of " << len << " bytes was accepted";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_FALSE(complete) << name << ": complete prefix of " << len << " bytes refused: " << msg;
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      if (len > header_end) {
        EXPECT_NE(msg.find("truncated"), std::string::npos) << len << " bytes: " << msg;
      }
    }
  }
}

TEST(GmshReaderErrors, TruncatedHandWrittenFiles) {
  // Every prefix of the 2.2 ASCII file; every other one of the 4.1 ASCII and 2.2 big-endian binary files
  // (file writes dominate the run time).
  check_prefixes("truncated_v22.msh", read_whole(data_dir + "square_v22.msh"), 1);
  check_prefixes("truncated_v41.msh", read_whole(data_dir + "square_v41.msh"), 2);
  check_prefixes("truncated_v22_be.msh", square_binary_22(true), 2);
}

// -----------------------------------------------------------------------------------------------------------
// Curved P2 mesh generated by gmsh at test time: tests/data/gmsh/cylinder_panel.geo.

// Must match cylinder_panel.geo.
constexpr double radius = 1.5;
const double theta = std::acos(-1.0) / 3;
constexpr double length = 2.0;

/// Runs gmsh once per format variant (ASCII/binary x 2.2/4.1) for the whole suite.
class GmshCylinderPanel : public ::testing::Test {
 protected:
  struct Variant {
    std::string format;
    bool binary;
    std::string file;
  };
  static std::vector<Variant> variants;
  static std::string gmsh_error;

  static void SetUpTestSuite() {
#ifdef SHELLFRAC_GMSH_EXECUTABLE
    for (const std::string format : {"msh22", "msh41"})
      for (bool binary : {false, true}) {
        const std::string file = "cylinder_panel_" + format + (binary ? "_bin" : "_ascii") + ".msh";
        const std::string cmd = std::string(SHELLFRAC_GMSH_EXECUTABLE) + " -2 -order 2 -nt 1 -format " + format +
                                (binary ? " -bin " : " ") + data_dir + "cylinder_panel.geo -o " + file + " > " +
                                file + ".log 2>&1";
        if (std::system(cmd.c_str()) != 0) gmsh_error += "failed: " + cmd + "\n";
        variants.push_back({format, binary, file});
      }
#endif
  }

  void SetUp() override {
#ifndef SHELLFRAC_GMSH_EXECUTABLE
    GTEST_SKIP() << "gmsh not found at configure time";
#endif
    ASSERT_TRUE(gmsh_error.empty()) << gmsh_error;
  }
};
std::vector<GmshCylinderPanel::Variant> GmshCylinderPanel::variants;
std::string GmshCylinderPanel::gmsh_error;

TEST_F(GmshCylinderPanel, FourVariantsGiveTheSameMesh) {
  ASSERT_EQ(variants.size(), 4u);
  std::vector<SerialMesh> meshes;
  for (const Variant& v : variants) meshes.push_back(read_gmsh(v.file));
  // variants: 0 = 2.2 ASCII, 1 = 2.2 binary, 2 = 4.1 ASCII, 3 = 4.1 binary. Same encoding -> bitwise equal.
  expect_same_mesh(meshes[0], meshes[2]);
  expect_same_mesh(meshes[1], meshes[3]);
  // ASCII vs binary: Gmsh prints coordinates with 16 significant digits (%.16g), which does not always
  // round-trip a double (17 are needed), so they agree to a couple of ulps of |x| <= R only.
  expect_same_mesh(meshes[0], meshes[1], 4 * radius * std::numeric_limits<double>::epsilon());
  for (const SerialMesh& m : meshes) EXPECT_EQ(m.nodes_per_element, 6);
}

/// Boundary edges (element, local edge) of a conforming mesh: edges used by exactly one triangle.
std::set<std::pair<GlobalId, int>> boundary_edges(const SerialMesh& m) {
  std::vector<std::tuple<GlobalId, GlobalId, GlobalId, int>> edges;
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const GlobalId a = m.node(e, edge_vertex[k][0]), b = m.node(e, edge_vertex[k][1]);
      edges.emplace_back(std::min(a, b), std::max(a, b), e, k);
    }
  std::sort(edges.begin(), edges.end());
  std::set<std::pair<GlobalId, int>> boundary;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i]))
      ++j;
    if (j - i == 1) boundary.emplace(std::get<2>(edges[i]), std::get<3>(edges[i]));
    i = j;
  }
  return boundary;
}

/// Counts elements of each Gmsh type in a 2.2 ASCII file, independently of the reader.
std::map<int, int> count_types_v22_ascii(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line != "$Elements") {
  }
  int n = 0;
  in >> n;
  std::getline(in, line);
  std::map<int, int> counts;
  for (int i = 0; i < n && std::getline(in, line); ++i) {
    std::istringstream ls(line);
    int tag = 0, type = 0;
    ls >> tag >> type;
    ++counts[type];
  }
  return counts;
}

TEST_F(GmshCylinderPanel, CountsAndTopology) {
  const SerialMesh m = read_gmsh(variants[3].file);
  // Reference: the element counts of the 2.2 ASCII file, counted line by line here (only one physical
  // surface, so Gmsh writes each element once).
  const std::map<int, int> counts = count_types_v22_ascii(variants[0].file);
  ASSERT_TRUE(counts.count(9));
  EXPECT_EQ(m.num_elements(), counts.at(9));
  EXPECT_EQ(counts.count(2), 0u);
  // Every mesh boundary edge is in exactly one side set (the four physical curves are the whole boundary),
  // and there are as many of them as 3-node line elements in the file.
  const auto boundary = boundary_edges(m);
  std::multiset<std::pair<GlobalId, int>> in_sets;
  for (const auto& s : m.side_sets)
    for (std::size_t i = 0; i < s.elements.size(); ++i) in_sets.emplace(s.elements[i], s.local_edges[i]);
  EXPECT_EQ(in_sets.size(), boundary.size());
  const std::set<std::pair<GlobalId, int>> covered(in_sets.begin(), in_sets.end());
  EXPECT_EQ(covered, boundary);
  EXPECT_EQ(static_cast<int>(boundary.size()), counts.at(8));
  // Euler for a disc (chi = 1): F = 2V - Eb - 2; and P2 nodes = V + E with E = (3F + Eb) / 2.
  std::set<GlobalId> vertices;
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int a = 0; a < 3; ++a) vertices.insert(m.node(e, a));
  const GlobalId f = m.num_elements(), v = static_cast<GlobalId>(vertices.size()),
                 eb = static_cast<GlobalId>(boundary.size());
  EXPECT_EQ(f, 2 * v - eb - 2);
  EXPECT_EQ(m.num_nodes(), v + (3 * f + eb) / 2);
}

TEST_F(GmshCylinderPanel, NodesOnCylinderAndSetsOnTheirEdges) {
  const SerialMesh m = read_gmsh(variants[2].file);
  // Gmsh places P2 nodes on the CAD surface: radius exact to rounding (1e-9 R is far above it).
  for (const Vec3& x : m.coords) {
    EXPECT_NEAR(std::hypot(x[0], x[1]), radius, 1e-9 * radius);
    EXPECT_GE(x[2], -1e-12);
    EXPECT_LE(x[2], length + 1e-12);
    const double angle = std::atan2(x[1], x[0]);
    EXPECT_GE(angle, -1e-12);
    EXPECT_LE(angle, theta + 1e-12);
  }
  ASSERT_EQ(m.blocks.size(), 1u);
  EXPECT_EQ(m.blocks[0].name, "skin");
  EXPECT_EQ(m.blocks[0].id, 10);
  EXPECT_TRUE(m.element_sets.empty());
  // Each physical curve (geo file) lies on one boundary line of the panel: check the 3 nodes of each of its
  // edges (vertices and mid-side) satisfy that line's equation, which also checks the local edge numbers.
  auto angle_of = [](const Vec3& x) { return std::atan2(x[1], x[0]); };
  const std::vector<std::pair<std::string, std::function<double(const Vec3&)>>> curves = {
      {"bottom", [](const Vec3& x) { return x[2]; }},
      {"top", [](const Vec3& x) { return x[2] - length; }},
      {"side_a", [&](const Vec3& x) { return angle_of(x); }},
      {"side_b", [&](const Vec3& x) { return angle_of(x) - theta; }}};
  ASSERT_EQ(m.side_sets.size(), 4u);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const mesh::SideSet& s = m.side_sets[c];
    EXPECT_EQ(s.name, curves[c].first);
    EXPECT_EQ(s.id, static_cast<int>(c) + 1);
    ASSERT_FALSE(s.elements.empty());
    std::set<GlobalId> edge_nodes;
    for (std::size_t i = 0; i < s.elements.size(); ++i) {
      const int k = s.local_edges[i];
      for (int a : {edge_vertex[k][0], edge_vertex[k][1], 3 + k}) {
        const GlobalId n = m.node(s.elements[i], a);
        edge_nodes.insert(n);
        EXPECT_NEAR(curves[c].second(m.coords[static_cast<std::size_t>(n)]), 0, 1e-12) << s.name;
      }
    }
    // The node set of the same group: the same nodes (2 per edge + 1 for an open curve).
    const mesh::NodeSet& ns = m.node_sets[c];
    EXPECT_EQ(ns.name, s.name);
    EXPECT_EQ(ns.id, s.id);
    EXPECT_EQ(std::set<GlobalId>(ns.nodes.begin(), ns.nodes.end()), edge_nodes);
    EXPECT_EQ(ns.nodes.size(), 2 * s.elements.size() + 1);
  }
  // Physical point "corner" (tag 1) = geo point 2 at (R, 0, 0); node-set id 1 is taken by curve "bottom".
  ASSERT_EQ(m.node_sets.size(), 5u);
  EXPECT_EQ(m.node_sets[4].name, "corner");
  EXPECT_EQ(m.node_sets[4].id, 5);
  ASSERT_EQ(m.node_sets[4].nodes.size(), 1u);
  const Vec3& corner = m.coords[static_cast<std::size_t>(m.node_sets[4].nodes[0])];
  EXPECT_NEAR(corner[0], radius, 1e-14);
  EXPECT_NEAR(corner[1], 0, 1e-14);
  EXPECT_NEAR(corner[2], 0, 1e-14);
}

/// Area of the isoparametric P2 surface, integrated with the 6-point degree-4 rule (Dunavant 1985), and the
/// sum of the flat (vertex) triangle areas.
std::pair<double, double> p2_and_flat_area(const SerialMesh& m) {
  const double a = 0.445948490915965, b = 0.091576213509771;
  const double wa = 0.223381589678011, wb = 0.109951743655322;  // sum 3 (wa + wb) = 1
  const std::array<std::array<double, 3>, 6> points = {{{a, a, wa},
                                                        {1 - 2 * a, a, wa},
                                                        {a, 1 - 2 * a, wa},
                                                        {b, b, wb},
                                                        {1 - 2 * b, b, wb},
                                                        {b, 1 - 2 * b, wb}}};
  double p2 = 0, flat = 0;
  for (GlobalId e = 0; e < m.num_elements(); ++e) {
    std::array<Vec3, 6> x;
    for (int i = 0; i < 6; ++i) x[i] = m.coords[static_cast<std::size_t>(m.node(e, i))];
    for (const auto& q : points) {
      const double l1 = q[0], l2 = q[1], l0 = 1 - l1 - l2;
      // d/dxi and d/deta of the P2 shape functions (l1 = xi, l2 = eta), node order of types.hpp.
      const double dxi[6] = {-(4 * l0 - 1), 4 * l1 - 1, 0, 4 * (l0 - l1), 4 * l2, -4 * l2};
      const double deta[6] = {-(4 * l0 - 1), 0, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)};
      Vec3 t1{0, 0, 0}, t2{0, 0, 0};
      for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 3; ++c) {
          t1[c] += dxi[i] * x[i][c];
          t2[c] += deta[i] * x[i][c];
        }
      const Vec3 n{t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
      p2 += q[2] * 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    Vec3 u, v;
    for (int c = 0; c < 3; ++c) {
      u[c] = x[1][c] - x[0][c];
      v[c] = x[2][c] - x[0][c];
    }
    const Vec3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    flat += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return {p2, flat};
}

TEST_F(GmshCylinderPanel, AreaOfP2Surface) {
  const SerialMesh m = read_gmsh(variants[1].file);
  // Exact area of the panel: R * theta * L (= pi here).
  const double exact = radius * theta * length;
  const auto [p2, flat] = p2_and_flat_area(m);
  // The P2 geometry of an arc of angle phi = h/R ~ 0.23 has a relative area error ~ phi^4 / 1000 ~ 1e-6; the
  // flat triangles cut the chords, error ~ phi^2 / 24 ~ 2e-3. Tolerances with margin; if the mid-side nodes
  // were mis-ordered the P2 area would be off by far more than the flat one.
  EXPECT_NEAR(p2, exact, 2e-5 * exact);
  EXPECT_LT(flat, exact);
  EXPECT_NEAR(flat, exact, 5e-3 * exact);
  EXPECT_LT(std::abs(p2 - exact), 0.05 * std::abs(flat - exact));
}

TEST_F(GmshCylinderPanel, FirstOrderMesh) {
#ifdef SHELLFRAC_GMSH_EXECUTABLE
  // gmsh meshes at order 1 and then elevates the order, so "-order 1" gives the same triangulation: same
  // triangles, the P2 mesh's vertices as nodes, and 2-node lines in the same side sets.
  const std::string file = "cylinder_panel_p1.msh";
  const std::string cmd = std::string(SHELLFRAC_GMSH_EXECUTABLE) + " -2 -order 1 -nt 1 -format msh41 -bin " +
                          data_dir + "cylinder_panel.geo -o " + file + " > " + file + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const SerialMesh p1 = read_gmsh(file);
  const SerialMesh p2 = read_gmsh(variants[3].file);
  EXPECT_EQ(p1.nodes_per_element, 3);
  EXPECT_EQ(p1.num_elements(), p2.num_elements());
  std::set<GlobalId> p2_vertices;
  for (GlobalId e = 0; e < p2.num_elements(); ++e)
    for (int a = 0; a < 3; ++a) p2_vertices.insert(p2.node(e, a));
  EXPECT_EQ(p1.num_nodes(), static_cast<GlobalId>(p2_vertices.size()));
  ASSERT_EQ(p1.side_sets.size(), p2.side_sets.size());
  for (std::size_t i = 0; i < p1.side_sets.size(); ++i) {
    EXPECT_EQ(p1.side_sets[i].name, p2.side_sets[i].name);
    EXPECT_EQ(p1.side_sets[i].elements.size(), p2.side_sets[i].elements.size());
  }
  EXPECT_EQ(boundary_edges(p1).size(), boundary_edges(p2).size());
#endif
}

TEST_F(GmshCylinderPanel, SaveAllGivesTheSameMesh) {
#ifdef SHELLFRAC_GMSH_EXECUTABLE
  // With Mesh.SaveAll, gmsh 4.1 also writes the arc centres (points 1, 6 of the .geo) as point elements
  // outside any physical group, on nodes of no triangle: they must be ignored, and the mesh is unchanged.
  const std::string file = "cylinder_panel_save_all.msh";
  const std::string cmd = std::string(SHELLFRAC_GMSH_EXECUTABLE) +
                          " -2 -order 2 -nt 1 -save_all -format msh41 -bin " + data_dir +
                          "cylinder_panel.geo -o " + file + " > " + file + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  expect_same_mesh(read_gmsh(file), read_gmsh(variants[3].file));
#endif
}

TEST_F(GmshCylinderPanel, TruncatedBinaryFiles) {
  // Prefixes of the gmsh-made binary files: a 37-byte stride (prime, so cuts fall at every offset within the
  // 4- and 8-byte fields), and every byte over the last 37.
  check_prefixes("truncated_bin22.msh", read_whole(variants[1].file), 37);
  check_prefixes("truncated_bin41.msh", read_whole(variants[3].file), 37);
}

}  // namespace
}  // namespace shellfrac::meshio
