// Partitioners (METIS direct, Zoltan2 scotch/rcb/multijagged/phg) and their input validation, at 1-4 ranks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/decomposition/partitioner.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"

namespace {

using namespace shellfrac;
using decomposition::PartitionParams;

struct NamedMesh {
  std::string name;
  mesh::SerialMesh mesh;
};

std::vector<NamedMesh> test_meshes() {
  // A few hundred elements: a flat rectangle (open boundary) and a closed tube (periodic in theta), so
  // both a planar and a curved, boundary-free-in-one-direction dual graph are partitioned.
  return {{"rectangle", mesh::make_rectangle(2.0, 1.0, 12, 8)}, {"cylinder", mesh::make_cylinder(1.0, 3.0, 10, 12)}};
}

/// A hand-made 3-triangle strip (nodes 0..4): fewer elements than ranks at np = 4, so the Zoltan2
/// back end has to run on a sub-communicator.
mesh::SerialMesh strip3() {
  mesh::SerialMesh m;
  m.coords = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
  m.connectivity = {0, 1, 2, 1, 3, 2, 2, 3, 4};
  m.element_block = {0, 0, 0};
  m.blocks.push_back({"shell", 1});
  m.source = "strip3";
  return m;
}

PartitionParams make_params(const std::string& method, const std::string& algorithm = "scotch") {
  Teuchos::ParameterList pl("Partitioning");
  pl.set("Method", method);
  pl.set("Zoltan2 Algorithm", algorithm);
  return PartitionParams::from_parameters(pl, {"test.xml", "shellfrac->Partitioning"});
}

/// Every element exactly once with a part in range, and the same vector on every rank (checked against
/// rank 0's copy). Returns the part sizes.
std::vector<GlobalId> check_partition(const std::vector<int>& part, GlobalId ne, int nparts, const std::string& what) {
  // part.size() == ne: each element has exactly one entry, so it belongs to exactly one part.
  EXPECT_EQ(static_cast<GlobalId>(part.size()), ne) << what;
  std::vector<GlobalId> sizes(nparts, 0);
  for (std::size_t e = 0; e < part.size(); ++e) {
    EXPECT_TRUE(part[e] >= 0 && part[e] < nparts) << what << ": element " << e << " has part " << part[e];
    if (part[e] >= 0 && part[e] < nparts) ++sizes[part[e]];
  }
  // Identical on all ranks: a rank-dependent result would give inconsistent ownership later.
  std::vector<int> root = part;
  parallel::broadcast_vector(root, 0, MPI_COMM_WORLD);
  EXPECT_TRUE(root == part) << what << ": partition differs from rank 0's";
  return sizes;
}

/// Number of interfaces whose two elements are in different parts.
GlobalId edge_cut(const mesh::EdgeTopology& topo, const std::vector<int>& part) {
  GlobalId cut = 0;
  for (const auto& f : topo.interfaces) cut += part[f.minus.element] != part[f.plus.element];
  return cut;
}

TEST(Partitioner, MetisCoversBalancedAndDeterministic) {
  const int np = parallel::size();
  for (const auto& [name, m] : test_meshes()) {
    const auto topo = mesh::build_edge_topology(m);
    const GlobalId ne = m.num_elements();
    for (int nparts : {np, 5}) {
      const auto params = make_params("METIS");
      const auto part = decomposition::partition_elements(m, topo, nparts, params);
      const auto sizes = check_partition(part, ne, nparts, "METIS " + name);
      if (nparts == 1) continue;
      // Balance: METIS targets 5 % imbalance; on a few hundred elements allow 15 % (a bug such as an
      // ignored ufactor or a wrong nparts gives far worse, e.g. empty parts or one part holding everything).
      const double avg = static_cast<double>(ne) / nparts;
      const GlobalId max_size = *std::max_element(sizes.begin(), sizes.end());
      const GlobalId min_size = *std::min_element(sizes.begin(), sizes.end());
      EXPECT_LE(static_cast<double>(max_size), 1.15 * avg + 1) << "METIS " << name << " nparts " << nparts;
      EXPECT_GE(min_size, 1) << "METIS " << name << ": empty part";
      // Quality: a graph partitioner cuts few interfaces; a random or interleaved assignment of 2-5 parts
      // would cut 50-80 % of them.
      EXPECT_LT(edge_cut(topo, part), static_cast<GlobalId>(0.25 * static_cast<double>(topo.interfaces.size())))
          << "METIS " << name;
      // Deterministic for a fixed seed (the solver relies on reproducible decompositions).
      EXPECT_TRUE(decomposition::partition_elements(m, topo, nparts, params) == part) << "METIS " << name;
    }
  }
}

TEST(Partitioner, Zoltan2AllAlgorithmsCover) {
  const int np = parallel::size();
  for (const std::string alg : {"scotch", "rcb", "multijagged", "phg"}) {
    for (const auto& [name, m] : test_meshes()) {
      const auto topo = mesh::build_edge_topology(m);
      const GlobalId ne = m.num_elements();
      const int nparts = std::max(np, 2);  // at np = 1 still make Zoltan2 actually partition
      const auto part = decomposition::partition_elements(m, topo, nparts, make_params("Zoltan2", alg));
      const auto sizes = check_partition(part, ne, nparts, "Zoltan2 " + alg + " " + name);
      // Every part used and none grossly overloaded (Zoltan2 is asked for 5 % imbalance).
      const double avg = static_cast<double>(ne) / nparts;
      for (int p = 0; p < nparts; ++p) {
        EXPECT_GE(sizes[p], 1) << alg << " " << name << ": part " << p << " is empty";
        EXPECT_LE(static_cast<double>(sizes[p]), 1.5 * avg + 1) << alg << " " << name << ": part " << p;
      }
      // Graph and geometric partitioners both give compact parts: far fewer cut interfaces than a
      // random assignment (>= 50 % for 2 parts).
      EXPECT_LT(edge_cut(topo, part), static_cast<GlobalId>(0.3 * static_cast<double>(topo.interfaces.size())))
          << alg << " " << name;
    }
  }
}

/// This rank's share [r W, (r + 1) W), W = ceil(N / P), of m as a piece, with its distributed topology.
struct SharePiece {
  mesh::ElementPiece piece;
  decomposition::LocalTopology topo;
  GlobalId first = 0;
};

SharePiece share_piece(const mesh::SerialMesh& m) {
  const GlobalId ne = m.num_elements(), P = parallel::size(), r = parallel::rank(), w = (ne + P - 1) / P;
  SharePiece s;
  s.first = std::min(ne, r * w);
  s.piece = mesh::element_range_piece(m, s.first, std::min(ne, (r + 1) * w));
  std::vector<std::array<GlobalId, 3>> vertices;
  for (GlobalId e : s.piece.elements) vertices.push_back({m.node(e, 0), m.node(e, 1), m.node(e, 2)});
  s.topo = decomposition::build_local_topology(s.piece.elements, vertices, mesh::NonManifoldPolicy::Star, m.source,
                                               MPI_COMM_WORLD);
  return s;
}

TEST(Partitioner, Zoltan2OnPiecesGivesThePartsOfTheWholeMesh) {
  // A mesh held in pieces (each rank its element share, as read_exodus_piece gives them) is partitioned from the
  // pieces alone, with the same parts as the whole mesh partitioned by Zoltan2, for every algorithm and for the
  // trivial cases; each rank gets the parts of its own elements.
  const int np = parallel::size();
  std::vector<NamedMesh> meshes = test_meshes();
  meshes.push_back({"strip3", strip3()});
  for (const auto& [name, m] : meshes) {
    const auto topo = mesh::build_edge_topology(m);
    const SharePiece s = share_piece(m);
    for (const std::string alg : {"scotch", "rcb", "multijagged", "phg"})
      for (int nparts : {1, std::max(np, 2), 3, 50}) {
        const auto params = make_params("Zoltan2", alg);
        const auto whole = decomposition::partition_elements(m, topo, nparts, params);
        const auto mine = decomposition::partition_piece(s.piece, s.topo, m.num_elements(), nparts, params);
        const std::vector<int> expected(whole.begin() + s.first,
                                        whole.begin() + s.first + static_cast<GlobalId>(s.piece.elements.size()));
        EXPECT_EQ(mine, expected) << name << " " << alg << " " << nparts << " parts";
      }
    EXPECT_THROW(decomposition::partition_piece(s.piece, s.topo, m.num_elements(), 2, make_params("METIS")), Error);
  }
}

TEST(Partitioner, Zoltan2FewerElementsThanRanks) {
  // 3 elements, 2 parts: at np = 4 one rank holds no element of the block distribution and must sit
  // out of the Zoltan2 call without hanging the others.
  const auto m = strip3();
  const auto topo = mesh::build_edge_topology(m);
  for (const std::string alg : {"scotch", "rcb", "multijagged", "phg"}) {
    const auto part = decomposition::partition_elements(m, topo, 2, make_params("Zoltan2", alg));
    check_partition(part, 3, 2, "strip3 " + alg);
  }
  check_partition(decomposition::partition_elements(m, topo, 2, make_params("METIS")), 3, 2, "strip3 METIS");
}

TEST(Partitioner, TrivialCases) {
  const auto m = mesh::make_rectangle(1.0, 1.0, 1, 1);  // 2 elements
  const auto topo = mesh::build_edge_topology(m);
  for (const std::string method : {"METIS", "Zoltan2"}) {
    const auto params = make_params(method);
    // One part: no library call, every element in part 0.
    EXPECT_EQ(decomposition::partition_elements(m, topo, 1, params), std::vector<int>({0, 0})) << method;
    // More parts than elements: must not fail; element i -> part i, the remaining parts empty.
    for (int nparts : {2, 3, 4}) {
      const auto part = decomposition::partition_elements(m, topo, nparts, params);
      check_partition(part, 2, nparts, method + " 2 elements");
      EXPECT_NE(part[0], part[1]) << method << " nparts " << nparts;
    }
  }
}

TEST(Partitioner, DefaultsAndConversion) {
  Teuchos::ParameterList pl("Partitioning");
  auto p = PartitionParams::from_parameters(pl, {"test.xml", "shellfrac->Partitioning"});
  EXPECT_EQ(p.method, PartitionParams::Method::METIS);
  EXPECT_EQ(p.zoltan2_algorithm, "scotch");
  EXPECT_DOUBLE_EQ(p.imbalance_tolerance, 1.05);
  EXPECT_EQ(p.seed, 1);
  Teuchos::ParameterList q("Partitioning");
  q.set("Method", std::string("Zoltan2"));
  q.set("Zoltan2 Algorithm", std::string("multijagged"));
  q.set("Imbalance Tolerance", 1.2);
  q.set("Seed", 7);
  p = PartitionParams::from_parameters(q, {"test.xml", "shellfrac->Partitioning"});
  EXPECT_EQ(p.method, PartitionParams::Method::Zoltan2);
  EXPECT_EQ(p.zoltan2_algorithm, "multijagged");
  EXPECT_DOUBLE_EQ(p.imbalance_tolerance, 1.2);
  EXPECT_EQ(p.seed, 7);
}

/// Expects from_parameters to throw InputError whose message contains every string of `needles`.
void expect_input_error(Teuchos::ParameterList pl, const std::vector<std::string>& needles) {
  try {
    PartitionParams::from_parameters(pl, {"deck.xml", "shellfrac->Partitioning"});
    ADD_FAILURE() << "no InputError for " << pl;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }
}

TEST(Partitioner, InvalidParametersAreInputErrors) {
  // Misspelled method: the message must name the deck, the parameter and list both choices.
  Teuchos::ParameterList a("Partitioning");
  a.set("Method", std::string("Metis2"));
  expect_input_error(a, {"deck.xml", "Method", "Metis2", "'METIS'", "'Zoltan2'"});
  // parmetis is a Zoltan2 algorithm name, but not available in Debian's Zoltan2: rejected with the list.
  Teuchos::ParameterList b("Partitioning");
  b.set("Zoltan2 Algorithm", std::string("parmetis"));
  expect_input_error(b, {"Zoltan2 Algorithm", "parmetis", "'scotch'", "'rcb'", "'multijagged'", "'phg'"});
  // A tolerance below 1 is meaningless (max/average part size).
  Teuchos::ParameterList c("Partitioning");
  c.set("Imbalance Tolerance", 0.5);
  expect_input_error(c, {"Imbalance Tolerance", "0.5", ">= 1"});
  // Unknown parameter name: suggestion of the closest valid one.
  Teuchos::ParameterList d("Partitioning");
  d.set("Imbalance Tolerence", 1.1);
  expect_input_error(d, {"Imbalance Tolerence", "Imbalance Tolerance"});
}

}  // namespace
