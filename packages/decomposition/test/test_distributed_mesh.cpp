// The distributed DG element model: ownership, ghost layer, Imports, interfaces, DG nodes, at 1-4
// ranks. Expected values are recomputed here by brute force from the serial mesh and topology.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/decomposition/element_maps.hpp"
#include "shellfrac/decomposition/element_migration.hpp"
#include "shellfrac/decomposition/partitioner.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"

namespace {

using namespace shellfrac;
using decomposition::DistributedMesh;

struct Case {
  std::string name;
  mesh::SerialMesh mesh;
  mesh::EdgeTopology topo;
  std::vector<int> part;
};

Case make_case(const std::string& name, mesh::SerialMesh m, const std::string& method = "METIS") {
  Case c{name, std::move(m), {}, {}};
  c.topo = mesh::build_edge_topology(c.mesh);
  Teuchos::ParameterList pl("Partitioning");
  pl.set("Method", method);
  const auto params = decomposition::PartitionParams::from_parameters(pl, {"test.xml", "Partitioning"});
  c.part = decomposition::partition_elements(c.mesh, c.topo, parallel::size(), params);
  return c;
}

std::vector<Case> cases() {
  std::vector<Case> v;
  auto rectangle = mesh::make_rectangle(2.0, 1.0, 10, 6);
  rectangle.element_sets.push_back({"patch", 1, {0, 7, 8, 50, 119}});
  rectangle.side_sets.push_back({"inner", 9, {3, 10, 20, 20}, {1, 2, 0, 1}});  // interior edges
  for (GlobalId e = 0; e < rectangle.num_elements(); ++e) rectangle.element_ids.ids.push_back(1000 + 3 * e);
  v.push_back(make_case("rectangle/METIS", std::move(rectangle)));
  v.push_back(make_case("cylinder/scotch", mesh::make_cylinder(1.0, 3.0, 8, 8), "Zoltan2"));
  auto p2 = mesh::make_cylindrical_panel(1.0, 2.0, 1.5, 6, 5, mesh::DiagonalPattern::Alternating);
  mesh::promote_to_p2(p2);
  v.push_back(make_case("panel-P2/METIS", std::move(p2)));
  v.push_back(make_case("two-elements/METIS", mesh::make_rectangle(1.0, 1.0, 1, 1)));  // empty ranks at np 3, 4
  return v;
}

/// Brute force: the elements that share an edge (same unique edge id) with element e, from element_edges
/// only (not from the interface list the implementation uses).
std::vector<std::set<GlobalId>> edge_neighbours(const Case& c) {
  std::map<GlobalId, std::vector<GlobalId>> by_edge;
  for (GlobalId e = 0; e < c.mesh.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) by_edge[c.topo.element_edges[e][k]].push_back(e);
  std::vector<std::set<GlobalId>> nb(c.mesh.num_elements());
  for (const auto& [edge, els] : by_edge)
    for (GlobalId a : els)
      for (GlobalId b : els)
        if (a != b) nb[a].insert(b);
  return nb;
}

TEST(DistributedMesh, OwnedSetsPartitionTheElements) {
  const int me = parallel::rank();
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const GlobalId ne = c.mesh.num_elements();
    // Sum of owned counts == ne and the gathered owned gids are exactly 0..ne-1: no element is lost or
    // owned twice.
    EXPECT_EQ(parallel::sum(dm.num_owned()), ne) << c.name;
    std::vector<std::int64_t> mine(dm.element_gids().begin(), dm.element_gids().begin() + dm.num_owned());
    auto all = parallel::all_gather(mine);
    std::sort(all.begin(), all.end());
    std::vector<std::int64_t> expect(ne);
    for (GlobalId e = 0; e < ne; ++e) expect[e] = e;
    EXPECT_EQ(all, expect) << c.name;
    // Owned elements are the ones the partition gives this rank, ascending.
    EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end())) << c.name;
    for (LocalId le = 0; le < dm.num_owned(); ++le) {
      EXPECT_EQ(c.part[dm.element_gid(le)], me) << c.name;
      EXPECT_EQ(dm.element_owner(le), me) << c.name;
    }
    EXPECT_EQ(dm.num_global_elements(), ne);
    EXPECT_EQ(static_cast<GlobalId>(dm.maps().owned->getGlobalNumElements()), ne) << c.name;
  }
}

TEST(DistributedMesh, GhostLayerIsExactlyTheRemoteFaceNeighbours) {
  const int me = parallel::rank();
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const auto nb = edge_neighbours(c);
    std::set<GlobalId> expect;
    for (GlobalId e = 0; e < c.mesh.num_elements(); ++e)
      if (c.part[e] == me)
        for (GlobalId n : nb[e])
          if (c.part[n] != me) expect.insert(n);
    // Ghosts (overlap rows after the owned ones) equal the brute-force set, ascending: a missing ghost
    // would leave an interface without its neighbour state, an extra one wastes communication.
    std::vector<GlobalId> ghosts(dm.element_gids().begin() + dm.num_owned(), dm.element_gids().end());
    EXPECT_EQ(ghosts, std::vector<GlobalId>(expect.begin(), expect.end())) << c.name;
    for (LocalId le = dm.num_owned(); le < dm.num_overlap(); ++le) {
      EXPECT_EQ(dm.element_owner(le), c.part[dm.element_gid(le)]) << c.name;
      EXPECT_NE(dm.element_owner(le), me) << c.name;
    }
    // local_id is the inverse of element_gid; the overlap map has the same order.
    const auto& overlap = *dm.maps().overlap;
    ASSERT_EQ(static_cast<LocalId>(overlap.getNodeNumElements()), dm.num_overlap()) << c.name;
    for (LocalId le = 0; le < dm.num_overlap(); ++le) {
      EXPECT_EQ(dm.local_id(dm.element_gid(le)), le) << c.name;
      EXPECT_EQ(static_cast<GlobalId>(overlap.getGlobalElement(le)), dm.element_gid(le)) << c.name;
      EXPECT_EQ(dm.element_block(le), c.mesh.element_block[dm.element_gid(le)]);
    }
    for (GlobalId e = 0; e < c.mesh.num_elements(); ++e)
      if (c.part[e] != me && !expect.count(e)) {
        EXPECT_EQ(dm.local_id(e), -1) << c.name << " element " << e;
      }
    // Neighbour arrays: every neighbour of an owned element is in the overlap and matches the topology.
    for (LocalId le = 0; le < dm.num_owned(); ++le)
      for (int k = 0; k < 3; ++k) {
        const auto& n = c.topo.neighbor[dm.element_gid(le)][k];
        if (n.element < 0) {
          EXPECT_EQ(dm.neighbor(le, k), -1);
          continue;
        }
        ASSERT_GE(dm.neighbor(le, k), 0) << c.name;
        EXPECT_EQ(dm.element_gid(dm.neighbor(le, k)), n.element) << c.name;
        EXPECT_EQ(dm.neighbor_edge(le, k), n.local_edge) << c.name;
      }
  }
}

TEST(DistributedMesh, ImportFillsGhostsFromOwners) {
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const auto& maps = dm.maps();
    constexpr int ncols = 3;
    auto f = [](GlobalId gid, int j) { return 1000.0 * static_cast<double>(j + 1) + 0.25 * static_cast<double>(gid); };
    decomposition::multivector_type owned(maps.owned, ncols), overlap(maps.overlap, ncols);
    {
      auto v = owned.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (LocalId le = 0; le < dm.num_owned(); ++le)
        for (int j = 0; j < ncols; ++j) v(le, j) = f(dm.element_gid(le), j);
    }
    overlap.putScalar(-1.0);  // a ghost row the Import misses keeps -1 and fails below
    overlap.doImport(owned, *maps.importer, Tpetra::INSERT);
    auto v = overlap.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LocalId le = 0; le < dm.num_overlap(); ++le)
      for (int j = 0; j < ncols; ++j) EXPECT_EQ(v(le, j), f(dm.element_gid(le), j)) << c.name << " row " << le;
  }
}

TEST(DistributedMesh, GhostImportMovesOnlyTheSendRows) {
  // The per-step transfer: only the owned rows that another rank holds as a ghost are filled (the others hold a
  // poison value), and every ghost row still receives its owner's value. send_rows are exactly the owned elements
  // with a neighbour across an interface on another rank (the one ghost layer), so nothing moves at np = 1.
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const auto& maps = dm.maps();
    constexpr int ncols = 2;
    auto f = [](GlobalId gid, int j) { return 100.0 * static_cast<double>(j + 1) + 0.5 * static_cast<double>(gid); };
    std::vector<LocalId> expected;
    for (LocalId le = 0; le < dm.num_owned(); ++le)
      for (int k = 0; k < 3; ++k)
        if (dm.neighbor(le, k) >= dm.num_owned()) {
          expected.push_back(le);
          break;
        }
    EXPECT_EQ(maps.send_rows, expected) << c.name;
    if (parallel::size() == 1) {
      EXPECT_TRUE(maps.send_rows.empty()) << c.name;
    }
    ASSERT_EQ(static_cast<LocalId>(maps.ghosts->getNodeNumElements()), dm.num_ghosts()) << c.name;
    decomposition::multivector_type owned(maps.owned, ncols), ghosts(maps.ghosts, ncols);
    owned.putScalar(-7.0);
    {
      auto v = owned.getLocalViewHost(Tpetra::Access::ReadWrite);
      for (const LocalId le : maps.send_rows)
        for (int j = 0; j < ncols; ++j) v(le, j) = f(dm.element_gid(le), j);
    }
    ghosts.putScalar(-1.0);
    ghosts.doImport(owned, *maps.ghost_importer, Tpetra::INSERT);
    auto v = ghosts.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LocalId r = 0; r < dm.num_ghosts(); ++r)
      for (int j = 0; j < ncols; ++j)
        EXPECT_EQ(v(r, j), f(dm.element_gid(dm.num_owned() + r), j)) << c.name << " ghost row " << r;
    // The same transfer from a vector of the send rows alone (what the time loop packs): `senders` holds their
    // global ids in send_rows order, and send_importer delivers every ghost row.
    ASSERT_EQ(static_cast<std::size_t>(maps.senders->getNodeNumElements()), maps.send_rows.size()) << c.name;
    decomposition::multivector_type senders(maps.senders, ncols), ghosts2(maps.ghosts, ncols);
    {
      auto s = senders.getLocalViewHost(Tpetra::Access::ReadWrite);
      for (std::size_t r = 0; r < maps.send_rows.size(); ++r) {
        ASSERT_EQ(GlobalId(maps.senders->getGlobalElement(LocalId(r))), dm.element_gid(maps.send_rows[r])) << c.name;
        for (int j = 0; j < ncols; ++j) s(r, j) = f(dm.element_gid(maps.send_rows[r]), j);
      }
    }
    ghosts2.putScalar(-1.0);
    ghosts2.doImport(senders, *maps.send_importer, Tpetra::INSERT);
    auto v2 = ghosts2.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LocalId r = 0; r < dm.num_ghosts(); ++r)
      for (int j = 0; j < ncols; ++j)
        EXPECT_EQ(v2(r, j), f(dm.element_gid(dm.num_owned() + r), j)) << c.name << " ghost row " << r << " (senders)";
  }
}

TEST(DistributedMesh, InterfacesOwnedOnceWithConsistentSides) {
  const int me = parallel::rank();
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const auto nif = static_cast<int>(c.topo.interfaces.size());
    std::vector<int> owned_count(nif, 0), total(nif, 0);
    GlobalId prev = -1;
    std::size_t expected_listed = 0;
    for (const auto& f : c.topo.interfaces) expected_listed += c.part[f.minus.element] == me || c.part[f.plus.element] == me;
    // Listed: exactly the interfaces with an owned side, sorted by gid.
    EXPECT_EQ(dm.interfaces().size(), expected_listed) << c.name;
    for (const auto& li : dm.interfaces()) {
      ASSERT_TRUE(li.gid >= 0 && li.gid < nif) << c.name;
      EXPECT_GT(li.gid, prev) << c.name;
      prev = li.gid;
      const auto& f = c.topo.interfaces[li.gid];
      // Both sides are overlap elements matching P(e) = (E-, ê-), (E+, ê+).
      ASSERT_GE(li.minus, 0);
      ASSERT_GE(li.plus, 0);
      EXPECT_EQ(dm.element_gid(li.minus), f.minus.element) << c.name;
      EXPECT_EQ(dm.element_gid(li.plus), f.plus.element) << c.name;
      EXPECT_EQ(li.minus_edge, f.minus.local_edge) << c.name;
      EXPECT_EQ(li.plus_edge, f.plus.local_edge) << c.name;
      EXPECT_EQ(li.non_manifold, f.non_manifold);
      // Owner rule: the lower of the two owners' ranks.
      EXPECT_EQ(li.owned, std::min(c.part[f.minus.element], c.part[f.plus.element]) == me) << c.name;
      if (li.owned) owned_count[li.gid] += 1;
    }
    // Every interface computed by exactly one rank (0 = a crack never seen, 2 = forces counted twice).
    MPI_Allreduce(owned_count.data(), total.data(), nif, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    for (int i = 0; i < nif; ++i) EXPECT_EQ(total[i], 1) << c.name << " interface " << i;
  }
}

TEST(DistributedMesh, BoundaryEdgesWithSideSets) {
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    // Every boundary edge appears on exactly one rank (its element's owner).
    EXPECT_EQ(parallel::sum(static_cast<std::int64_t>(dm.boundary_edges().size())),
              static_cast<std::int64_t>(c.topo.boundary.size()))
        << c.name;
    for (const auto& b : dm.boundary_edges()) {
      ASSERT_TRUE(b.element >= 0 && b.element < dm.num_owned()) << c.name;
      const GlobalId e = dm.element_gid(b.element);
      EXPECT_LT(dm.neighbor(b.element, b.local_edge), 0) << c.name;
      // Side-set membership recomputed from the mesh's side sets.
      std::vector<int> expect;
      for (std::size_t s = 0; s < c.mesh.side_sets.size(); ++s) {
        const auto& ss = c.mesh.side_sets[s];
        for (std::size_t i = 0; i < ss.elements.size(); ++i)
          if (ss.elements[i] == e && ss.local_edges[i] == b.local_edge) expect.push_back(static_cast<int>(s));
      }
      auto got = b.side_sets;
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, expect) << c.name << " element " << e << " edge " << b.local_edge;
    }
  }
}

TEST(DistributedMesh, DgNodesAndDirectors) {
  for (const auto& c : cases()) {
    DistributedMesh dm(c.mesh, c.topo, c.part);
    const int npe = c.mesh.nodes_per_element;
    ASSERT_EQ(dm.nodes_per_element(), npe);
    const auto normals = mesh::reference_vertex_normals(c.mesh);
    for (LocalId le = 0; le < dm.num_overlap(); ++le) {
      const GlobalId e = dm.element_gid(le);
      for (int a = 0; a < npe; ++a) {
        // DG nodes duplicate the conforming node: same coordinates, original id kept, unique DG id.
        EXPECT_EQ(dm.mesh_node(le, a), c.mesh.node(e, a)) << c.name;
        EXPECT_EQ(dm.node_coords(le, a), c.mesh.coords[c.mesh.node(e, a)]) << c.name;
        EXPECT_EQ(dm.dg_node_gid(le, a), e * npe + a) << c.name;
      }
      for (int a = 0; a < 3; ++a) {
        const Vec3& d = dm.reference_director(le, a);
        EXPECT_EQ(d, normals[c.mesh.node(e, a)]) << c.name;
        EXPECT_NEAR(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), 1.0, 1e-12) << c.name;
      }
    }
  }
}

TEST(DistributedMesh, RankWithoutElements) {
  // 2 elements on np ranks: ranks >= 2 own nothing. The partition still covers, construction and the
  // transfers are collective and must neither fail nor hang.
  const int me = parallel::rank(), np = parallel::size();
  const auto c = make_case("two", mesh::make_rectangle(1.0, 1.0, 1, 1));
  DistributedMesh dm(c.mesh, c.topo, c.part);
  EXPECT_EQ(parallel::sum(dm.num_owned()), 2);
  if (me >= 2) {
    EXPECT_EQ(dm.num_owned(), 0);
    EXPECT_EQ(dm.num_overlap(), 0);
    EXPECT_TRUE(dm.interfaces().empty());
  }
  // The only interface: both elements on one rank at np = 1, else one ghost each on ranks 0 and 1.
  if (np > 1 && me < 2) {
    EXPECT_EQ(dm.num_ghosts(), 1);
  }
  const auto& maps = dm.maps();
  decomposition::multivector_type owned(maps.owned, 1), overlap(maps.overlap, 1);
  {
    auto v = owned.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (LocalId le = 0; le < dm.num_owned(); ++le) v(le, 0) = 10.0 + static_cast<double>(dm.element_gid(le));
  }
  overlap.doImport(owned, *maps.importer, Tpetra::INSERT);
  {
    auto v = overlap.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (LocalId le = 0; le < dm.num_overlap(); ++le) EXPECT_EQ(v(le, 0), 10.0 + static_cast<double>(dm.element_gid(le)));
  }
}

TEST(DistributedMesh, RejectsBadPartition) {
  const auto c = make_case("rect", mesh::make_rectangle(1.0, 1.0, 2, 2));
  auto bad = c.part;
  bad[0] = parallel::size();  // not a rank
  EXPECT_THROW(DistributedMesh(c.mesh, c.topo, bad), Error);
  bad.pop_back();  // wrong length
  EXPECT_THROW(DistributedMesh(c.mesh, c.topo, bad), Error);
}

/// This rank's piece of c's mesh when the elements are spread over the ranks in blocks or round robin.
mesh::ElementPiece piece_of(const Case& c, bool round_robin) {
  const int me = parallel::rank(), P = parallel::size();
  const GlobalId ne = c.mesh.num_elements();
  std::vector<GlobalId> elements;
  for (GlobalId e = 0; e < ne; ++e)
    if ((round_robin ? int(e % P) : int(e * P / ne)) == me) elements.push_back(e);
  mesh::ElementPiece piece = mesh::piece_of_elements(c.mesh, elements);
  piece.source = c.name;
  return piece;
}

/// Every accessor of the two views, and the Imports' rows, compared (coordinates and directors bitwise).
void expect_same_view(const DistributedMesh& a, const DistributedMesh& b, const std::string& what) {
  ASSERT_EQ(a.num_owned(), b.num_owned()) << what;
  ASSERT_EQ(a.element_gids(), b.element_gids()) << what;
  EXPECT_EQ(a.num_global_elements(), b.num_global_elements()) << what;
  EXPECT_EQ(a.element_blocks(), b.element_blocks()) << what;
  EXPECT_EQ(a.neighbors(), b.neighbors()) << what;
  EXPECT_EQ(a.neighbor_edges(), b.neighbor_edges()) << what;
  for (LocalId le = 0; le < a.num_overlap(); ++le) {
    EXPECT_EQ(a.element_owner(le), b.element_owner(le)) << what;
    EXPECT_EQ(a.element_file_id(le), b.element_file_id(le)) << what;
    for (int n = 0; n < a.nodes_per_element(); ++n) {
      EXPECT_EQ(a.mesh_node(le, n), b.mesh_node(le, n)) << what;
      EXPECT_EQ(a.node_coords(le, n), b.node_coords(le, n)) << what;
    }
    for (int v = 0; v < 3; ++v) EXPECT_EQ(a.reference_director(le, v), b.reference_director(le, v)) << what;
  }
  ASSERT_EQ(a.interfaces().size(), b.interfaces().size()) << what;
  for (std::size_t i = 0; i < a.interfaces().size(); ++i) {
    const auto &x = a.interfaces()[i], &y = b.interfaces()[i];
    EXPECT_TRUE(x.gid == y.gid && x.minus == y.minus && x.plus == y.plus && x.minus_edge == y.minus_edge &&
                x.plus_edge == y.plus_edge && x.owned == y.owned && x.non_manifold == y.non_manifold)
        << what << " interface " << x.gid;
  }
  ASSERT_EQ(a.boundary_edges().size(), b.boundary_edges().size()) << what;
  for (std::size_t i = 0; i < a.boundary_edges().size(); ++i) {
    const auto &x = a.boundary_edges()[i], &y = b.boundary_edges()[i];
    EXPECT_TRUE(x.element == y.element && x.local_edge == y.local_edge && x.side_sets == y.side_sets) << what << i;
  }
  EXPECT_EQ(a.maps().send_rows, b.maps().send_rows) << what;
  const auto &sa = a.overlap_set_entries(), &sb = b.overlap_set_entries();
  const auto side_key = [](const mesh::SideEntry& x) { return std::tie(x.element, x.local_edge, x.side_set); };
  const auto set_key = [](const mesh::SetEntry& x) { return std::tie(x.member, x.set); };
  ASSERT_EQ(sa.side_entries.size(), sb.side_entries.size()) << what;
  for (std::size_t i = 0; i < sa.side_entries.size(); ++i)
    EXPECT_TRUE(side_key(sa.side_entries[i]) == side_key(sb.side_entries[i])) << what << " side entry " << i;
  ASSERT_EQ(sa.node_set_entries.size(), sb.node_set_entries.size()) << what;
  for (std::size_t i = 0; i < sa.node_set_entries.size(); ++i)
    EXPECT_TRUE(set_key(sa.node_set_entries[i]) == set_key(sb.node_set_entries[i])) << what << " node entry " << i;
  ASSERT_EQ(sa.element_set_entries.size(), sb.element_set_entries.size()) << what;
  for (std::size_t i = 0; i < sa.element_set_entries.size(); ++i)
    EXPECT_TRUE(set_key(sa.element_set_entries[i]) == set_key(sb.element_set_entries[i])) << what << " element " << i;
}

TEST(DistributedMesh, PiecesOfTheMeshGiveTheViewOfTheWholeMesh) {
  for (const auto& c : cases())
    for (const bool round_robin : {false, true}) {
      const DistributedMesh whole(c.mesh, c.topo, c.part);
      const auto piece = piece_of(c, round_robin);
      std::vector<std::array<GlobalId, 3>> vertices;
      std::vector<int> part;
      for (const GlobalId e : piece.elements)
        vertices.push_back({c.mesh.node(e, 0), c.mesh.node(e, 1), c.mesh.node(e, 2)}), part.push_back(c.part[e]);
      const auto topo = decomposition::build_local_topology(piece.elements, vertices, mesh::NonManifoldPolicy::Star,
                                                            piece.source, MPI_COMM_WORLD);
      const DistributedMesh from_pieces(piece, topo, part);
      expect_same_view(whole, from_pieces, c.name + (round_robin ? " round robin" : " blocks"));
    }
}

TEST(DistributedMesh, AnElementGivenByTwoRanksIsAnError) {
  if (parallel::size() < 2) GTEST_SKIP() << "needs two ranks";
  const Case c = make_case("two-ranks", mesh::make_rectangle(1.0, 1.0, 2, 1));
  mesh::ElementPiece piece;
  piece.source = "pieces.exo";
  const GlobalId e = parallel::rank() == 1 ? 0 : parallel::rank();  // ranks 0 and 1 both give element 0
  if (e < c.mesh.num_elements()) {
    piece.elements = {e};
    piece.blocks = {0};
    for (int a = 0; a < 3; ++a)
      piece.nodes.push_back(c.mesh.node(e, a)), piece.coords.push_back(c.mesh.coords[c.mesh.node(e, a)]);
  }
  std::vector<std::array<GlobalId, 3>> vertices;
  for (const GlobalId g : piece.elements) vertices.push_back({c.mesh.node(g, 0), c.mesh.node(g, 1), c.mesh.node(g, 2)});
  const auto topo = decomposition::build_local_topology(piece.elements, vertices, mesh::NonManifoldPolicy::Star,
                                                        piece.source, MPI_COMM_WORLD);
  const std::vector<int> part(piece.elements.size(), 0);
  try {
    DistributedMesh dm(piece, topo, part);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("pieces.exo: element 1 is given by two ranks"), std::string::npos)
        << err.what();
  }
}

}  // namespace
