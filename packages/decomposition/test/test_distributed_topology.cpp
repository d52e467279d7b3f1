// The edge topology and the reference directors of a mesh spread over the ranks (distributed_topology.hpp), at
// 1-4 ranks, against the serial functions on the whole mesh (mesh::build_edge_topology,
// mesh::reference_vertex_normals): the same ids, the same neighbours, the same bits, however the elements are
// spread.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace {

using namespace shellfrac;
using mesh::NonManifoldPolicy;

/// Three triangles on the common edge (0,1) (a stiffener on a skin), beside a fourth one on the skin.
mesh::SerialMesh t_joint() {
  mesh::SerialMesh m;
  m.source = "t_joint";
  m.coords = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}, {1.5, 1, 0}};
  m.connectivity = {0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 5, 2};
  m.element_block = {0, 0, 0, 0};
  m.blocks = {{"shell", 1}};
  return m;
}

std::vector<std::pair<std::string, mesh::SerialMesh>> meshes() {
  std::vector<std::pair<std::string, mesh::SerialMesh>> v;
  v.emplace_back("rectangle", mesh::make_rectangle(2.0, 1.0, 7, 5, mesh::DiagonalPattern::Alternating));
  v.emplace_back("cylinder", mesh::make_cylinder(1.0, 3.0, 6, 9));
  auto p2 = mesh::make_cylindrical_panel(1.0, 2.0, 1.5, 5, 4, mesh::DiagonalPattern::Left);
  mesh::promote_to_p2(p2);
  v.emplace_back("panel-P2", std::move(p2));
  v.emplace_back("t-joint", t_joint());
  v.emplace_back("one-element", mesh::make_rectangle(1.0, 1.0, 1, 1));  // ranks without elements
  return v;
}

/// Ways to spread the elements of a mesh of ne elements over P ranks: which rank holds element e. Within a rank the
/// elements are listed in descending id for "reversed", ascending otherwise.
struct Spread {
  std::string name;
  std::function<int(GlobalId e, GlobalId ne, int P)> rank_of;
  bool reversed = false;
};

std::vector<Spread> spreads() {
  return {{"blocks", [](GlobalId e, GlobalId ne, int P) { return int(e * P / ne); }, false},
          {"round-robin", [](GlobalId e, GlobalId, int P) { return int(e % P); }, false},
          {"reversed", [](GlobalId e, GlobalId ne, int P) { return P - 1 - int(e * P / ne); }, true}};
}

std::vector<GlobalId> elements_here(const mesh::SerialMesh& m, const Spread& s) {
  const int me = parallel::rank(), P = parallel::size();
  std::vector<GlobalId> mine;
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    if (s.rank_of(e, m.num_elements(), P) == me) mine.push_back(e);
  if (s.reversed) std::reverse(mine.begin(), mine.end());
  return mine;
}

bool operator==(const mesh::ElementEdge& x, const mesh::ElementEdge& y) {
  return x.element == y.element && x.local_edge == y.local_edge;
}

void expect_same_topology(const mesh::SerialMesh& m, const std::vector<GlobalId>& mine, NonManifoldPolicy policy,
                          const std::string& what) {
  const mesh::EdgeTopology serial = mesh::build_edge_topology(m, policy);
  std::vector<std::array<GlobalId, 3>> vertices;
  for (const GlobalId e : mine) vertices.push_back({m.node(e, 0), m.node(e, 1), m.node(e, 2)});
  const auto t = decomposition::build_local_topology(mine, vertices, policy, m.source, MPI_COMM_WORLD);
  EXPECT_EQ(t.num_edges, serial.num_edges()) << what;
  EXPECT_EQ(t.num_interfaces, GlobalId(serial.interfaces.size())) << what;
  EXPECT_EQ(t.num_boundary, GlobalId(serial.boundary.size())) << what;
  EXPECT_EQ(t.num_non_manifold_edges, serial.num_non_manifold_edges) << what;
  ASSERT_EQ(t.element_edges.size(), mine.size()) << what;
  for (std::size_t i = 0; i < mine.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const GlobalId e = mine[i];
      EXPECT_EQ(t.element_edges[i][k], serial.element_edges[e][k]) << what << " element " << e;
      EXPECT_EQ(t.element_interface[i][k], serial.element_interface[e][k]) << what << " element " << e;
      EXPECT_TRUE(t.neighbor[i][k] == serial.neighbor[e][k]) << what << " element " << e << " edge " << k;
    }
  const auto here = [&](GlobalId e) { return std::find(mine.begin(), mine.end(), e) != mine.end(); };
  std::vector<GlobalId> ids;
  for (std::size_t i = 0; i < serial.interfaces.size(); ++i)
    if (here(serial.interfaces[i].minus.element) || here(serial.interfaces[i].plus.element)) ids.push_back(GlobalId(i));
  ASSERT_EQ(t.interface_ids, ids) << what;
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const auto& f = serial.interfaces[std::size_t(ids[j])];
    const auto& g = t.interfaces[j];
    EXPECT_TRUE(g.edge == f.edge && g.minus == f.minus && g.plus == f.plus &&
                g.same_orientation == f.same_orientation && g.non_manifold == f.non_manifold)
        << what << " interface " << ids[j];
  }
  std::vector<mesh::ElementEdge> boundary;
  std::vector<GlobalId> boundary_ids;
  for (std::size_t i = 0; i < serial.boundary.size(); ++i)
    if (here(serial.boundary[i].element)) boundary.push_back(serial.boundary[i]), boundary_ids.push_back(GlobalId(i));
  EXPECT_EQ(t.boundary_ids, boundary_ids) << what;
  ASSERT_EQ(t.boundary.size(), boundary.size()) << what;
  for (std::size_t j = 0; j < boundary.size(); ++j) EXPECT_TRUE(t.boundary[j] == boundary[j]) << what << " " << j;
}

TEST(DistributedTopology, IsTheSerialTopologyWhereverTheElementsAre) {
  for (const auto& [name, m] : meshes())
    for (const auto& s : spreads()) {
      const auto mine = elements_here(m, s);
      expect_same_topology(m, mine, NonManifoldPolicy::Star, name + "/" + s.name + "/Star");
      if (name == "t-joint") expect_same_topology(m, mine, NonManifoldPolicy::Free, name + "/" + s.name + "/Free");
    }
}

TEST(DistributedTopology, NonManifoldEdgeIsAnErrorOnEveryRank) {
  const auto m = t_joint();
  for (const auto& s : spreads()) {
    const auto mine = elements_here(m, s);
    std::vector<std::array<GlobalId, 3>> vertices;
    for (const GlobalId e : mine) vertices.push_back({m.node(e, 0), m.node(e, 1), m.node(e, 2)});
    try {
      decomposition::build_local_topology(mine, vertices, NonManifoldPolicy::Error, m.source, MPI_COMM_WORLD);
      ADD_FAILURE() << "expected InputError (" << s.name << ")";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("t_joint: edge between nodes 1 and 2 is shared by 3 elements (1, 2, 3 in the results)"),
                std::string::npos)
          << msg;
      EXPECT_NE(msg.find("Non-Manifold Edges"), std::string::npos) << msg;
    }
  }
}

TEST(DistributedTopology, VertexNormalsAreTheSerialBits) {
  for (const auto& [name, m] : meshes()) {
    const std::vector<Vec3> serial = mesh::reference_vertex_normals(m);
    for (const auto& s : spreads()) {
      const auto mine = elements_here(m, s);
      const int npe = m.nodes_per_element;
      std::vector<GlobalId> nodes;
      std::vector<Vec3> coords;
      for (const GlobalId e : mine)
        for (int a = 0; a < npe; ++a) nodes.push_back(m.node(e, a)), coords.push_back(m.coords[m.node(e, a)]);
      const auto normals = decomposition::local_vertex_normals(mine, npe, nodes, coords, m.source, MPI_COMM_WORLD);
      ASSERT_EQ(normals.size(), 3 * mine.size());
      for (std::size_t i = 0; i < mine.size(); ++i)
        for (int a = 0; a < 3; ++a) {
          const Vec3& want = serial[std::size_t(m.node(mine[i], a))];
          const Vec3& got = normals[3 * i + std::size_t(a)];
          for (int c = 0; c < 3; ++c)  // bitwise: the same terms added in the same order
            EXPECT_EQ(got[std::size_t(c)], want[std::size_t(c)]) << name << "/" << s.name << " element " << mine[i];
        }
    }
  }
}

TEST(DistributedTopology, ZeroJacobianIsAnErrorOnEveryRank) {
  auto m = mesh::make_rectangle(1.0, 1.0, 2, 1);
  m.coords[std::size_t(m.node(1, 2))] = m.coords[std::size_t(m.node(1, 0))];  // element 2 collapses
  std::vector<GlobalId> mine =
      parallel::rank() == parallel::size() - 1 ? std::vector<GlobalId>{0, 1, 2, 3} : std::vector<GlobalId>{};
  std::vector<GlobalId> nodes;
  std::vector<Vec3> coords;
  for (const GlobalId e : mine)
    for (int a = 0; a < 3; ++a) nodes.push_back(m.node(e, a)), coords.push_back(m.coords[m.node(e, a)]);
  std::string serial;
  try {
    m.source = "flat.exo";
    mesh::reference_vertex_normals(m);
  } catch (const InputError& e) {
    serial = e.what();
  }
  ASSERT_NE(serial.find("flat.exo: element "), std::string::npos) << serial;
  try {
    decomposition::local_vertex_normals(mine, 3, nodes, coords, "flat.exo", MPI_COMM_WORLD);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(serial), std::string::npos) << e.what() << " vs " << serial;
  }
}

}  // namespace
