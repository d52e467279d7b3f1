/// \file partitioner_zoltan2.cpp
/// Zoltan2 back end. The only translation unit that includes Zoltan2 (about 70 s to compile).
/// The elements start on a contiguous block distribution; scotch and phg partition the element dual graph
/// (a Tpetra::CrsGraph through XpetraCrsGraphAdapter), rcb and multijagged the element centroids (a
/// Tpetra::MultiVector through XpetraMultiVectorAdapter). Zoltan2 runs on the ranks that hold at least
/// one element (a sub-communicator when there are fewer elements than ranks); every rank then gathers the
/// whole part vector in global element order.
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Zoltan2_PartitioningProblem.hpp>
#include <Zoltan2_XpetraCrsGraphAdapter.hpp>
#include <Zoltan2_XpetraMultiVectorAdapter.hpp>
#include <algorithm>
#include <cstdlib>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/partitioner_detail.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::decomposition::detail {

namespace {

using map_type = Tpetra::Map<>;
using go_type = map_type::global_ordinal_type;
using graph_type = Tpetra::CrsGraph<>;
using coords_type = Tpetra::MultiVector<double>;

/// Debian's PT-Scotch 7 is built with threads (SCOTCH_PTHREAD). Unless MPI runs at MPI_THREAD_MULTIPLE
/// (Tpetra::ScopeGuard initialises it with MPI_Init), its threaded mapping intermittently deadlocks inside
/// SCOTCH_dgraphMap (seen here at np = 4: about one run in six). One thread per process avoids it; Scotch
/// reads SCOTCH_PTHREAD_NUMBER from the environment when it sets up its context.
void limit_scotch_threads() {
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  if (level < MPI_THREAD_MULTIPLE) setenv("SCOTCH_PTHREAD_NUMBER", "1", 1);
}

/// Runs the Zoltan2 problem on `adapter` and returns the part of each local row (adapter order).
template <class Adapter>
std::vector<int> solve(Adapter& adapter, Teuchos::ParameterList& zparams, const Teuchos::RCP<const Teuchos::Comm<int>>& tcomm,
                       std::size_t num_local) {
  Zoltan2::PartitioningProblem<Adapter> problem(&adapter, &zparams, tcomm);
  problem.solve();
  const auto* parts = problem.getSolution().getPartListView();
  std::vector<int> out(num_local, 0);
  if (num_local > 0) {
    SHELLFRAC_REQUIRE(parts != nullptr, "Zoltan2 returned no part list");
    for (std::size_t i = 0; i < num_local; ++i) out[i] = static_cast<int>(parts[i]);
  }
  return out;
}

/// Partitions the rows of a contiguous block map over tcomm; returns this rank's block of parts.
std::vector<int> partition_block(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                 const std::string& algorithm, double tolerance,
                                 const Teuchos::RCP<const Teuchos::Comm<int>>& tcomm) {
  const GlobalId ne = mesh.num_elements();
  auto map = Teuchos::rcp(new map_type(static_cast<Tpetra::global_size_t>(ne), go_type(0), tcomm));
  SHELLFRAC_REQUIRE(map->isContiguous(), "Zoltan2 partitioner: the block map is not contiguous");
  const std::size_t num_local = map->getNodeNumElements();
  const GlobalId first = num_local > 0 ? static_cast<GlobalId>(map->getMinGlobalIndex()) : 0;

  Teuchos::ParameterList zparams("Zoltan2");
  zparams.set("algorithm", algorithm);
  zparams.set("partitioning_approach", "partition");
  zparams.set("num_global_parts", nparts);
  zparams.set("imbalance_tolerance", tolerance);
  // Zoltan (behind phg and rcb) prints every parameter at its default debug level.
  zparams.sublist("zoltan_parameters").set("DEBUG_LEVEL", std::string("0"));
  if (algorithm == "scotch") limit_scotch_threads();

  if (algorithm == "rcb" || algorithm == "multijagged") {
    // Element centroids (vertex average) as coordinates.
    auto centroids = Teuchos::rcp(new coords_type(map, 3));
    {
      auto view = centroids->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t i = 0; i < num_local; ++i) {
        const GlobalId e = first + static_cast<GlobalId>(i);
        for (int d = 0; d < 3; ++d) {
          double c = 0;
          for (int a = 0; a < num_vertices_tri; ++a) c += mesh.coords[mesh.node(e, a)][d];
          view(i, d) = c / num_vertices_tri;
        }
      }
    }
    using adapter_type = Zoltan2::XpetraMultiVectorAdapter<coords_type>;
    const Teuchos::RCP<const coords_type> input = centroids;
    adapter_type adapter(input);
    return solve(adapter, zparams, tcomm, num_local);
  }

  // Dual graph rows of this block (neighbours unique, no self loops).
  std::vector<GlobalId> offsets, adjacency;
  mesh::dual_graph(topo, ne, offsets, adjacency);
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(offsets.size()) == ne + 1, "Zoltan2 partitioner: bad dual graph size");
  std::vector<std::vector<go_type>> rows(num_local);
  std::vector<std::size_t> counts(num_local);
  for (std::size_t i = 0; i < num_local; ++i) {
    const GlobalId e = first + static_cast<GlobalId>(i);
    for (GlobalId k = offsets[e]; k < offsets[e + 1]; ++k)
      if (adjacency[k] != e) rows[i].push_back(static_cast<go_type>(adjacency[k]));
    std::sort(rows[i].begin(), rows[i].end());
    rows[i].erase(std::unique(rows[i].begin(), rows[i].end()), rows[i].end());
    counts[i] = rows[i].size();
  }
  auto graph = Teuchos::rcp(new graph_type(map, Teuchos::ArrayView<const std::size_t>(counts.data(), counts.size())));
  for (std::size_t i = 0; i < num_local; ++i)
    graph->insertGlobalIndices(static_cast<go_type>(first + static_cast<GlobalId>(i)),
                               Teuchos::ArrayView<const go_type>(rows[i].data(), rows[i].size()));
  graph->fillComplete();
  using adapter_type = Zoltan2::XpetraCrsGraphAdapter<graph_type>;
  const Teuchos::RCP<const graph_type> input = graph;
  adapter_type adapter(input);
  return solve(adapter, zparams, tcomm, num_local);
}

}  // namespace

std::vector<int> partition_zoltan2(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                   const std::string& algorithm, double imbalance_tolerance, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  const GlobalId ne = mesh.num_elements();
  // Zoltan2 runs on the first min(np, ne) ranks so that every participating rank has at least one row.
  const bool active = static_cast<GlobalId>(me) < ne;
  MPI_Comm sub = MPI_COMM_NULL;
  MPI_Comm_split(comm, active ? 0 : MPI_UNDEFINED, me, &sub);
  std::vector<int> local;
  parallel::on_all_then_agree(
      [&] {
        if (!active) return;
        try {
          auto tcomm = Teuchos::rcp(new Teuchos::MpiComm<int>(sub));
          local = partition_block(mesh, topo, nparts, algorithm, imbalance_tolerance, tcomm);
        } catch (const Error&) {
          throw;
        } catch (const std::exception& e) {
          SHELLFRAC_REQUIRE(false, "Zoltan2 partitioning (algorithm '" << algorithm << "', " << nparts
                                                                      << " parts) failed: " << e.what());
        }
      },
      comm);
  if (sub != MPI_COMM_NULL) MPI_Comm_free(&sub);
  // Blocks are contiguous and in rank order, so the concatenation is in global element order.
  std::vector<int> part = parallel::all_gather(local, comm);
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(part.size()) == ne,
                    "Zoltan2 partitioner: gathered " << part.size() << " parts for " << ne << " elements");
  for (int p : part)
    SHELLFRAC_REQUIRE(p >= 0 && p < nparts, "Zoltan2 returned part " << p << " out of [0, " << nparts << ")");
  return part;
}

}  // namespace shellfrac::decomposition::detail
