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
#include <dlfcn.h>
#include <algorithm>
#include <cstdlib>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/decomposition/partitioner_detail.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"
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

/// Scotch (behind scotch) and Zoltan (behind phg) draw from a random state of the process that every call
/// advances, so a second partition of the same graph in one process differs from the first. Both states are reset
/// to their initial seeds before each call: the same input gives the same parts, in any call. Looked up at run
/// time: a Trilinos built without Scotch has no SCOTCH_randomReset.
void reset_random_states() {
  using reset_type = void (*)();
  using seed_type = void (*)(unsigned int, unsigned int*);
  if (auto scotch = reinterpret_cast<reset_type>(dlsym(RTLD_DEFAULT, "SCOTCH_randomReset"))) scotch();
  constexpr unsigned int zoltan_initial_seed = 123456789U;  // ZOLTAN_RAND_INIT of zoltan/src/zz/zz_rand.h
  if (auto zoltan = reinterpret_cast<seed_type>(dlsym(RTLD_DEFAULT, "Zoltan_Srand")))
    zoltan(zoltan_initial_seed, nullptr);
}

/// Runs the Zoltan2 problem on `adapter` and returns the part of each local row (adapter order).
template <class Adapter>
std::vector<int> solve(Adapter& adapter, Teuchos::ParameterList& zparams, const Teuchos::RCP<const Teuchos::Comm<int>>& tcomm,
                       std::size_t num_local) {
  Zoltan2::PartitioningProblem<Adapter> problem(&adapter, &zparams, tcomm);
  reset_random_states();
  problem.solve();
  const auto* parts = problem.getSolution().getPartListView();
  std::vector<int> out(num_local, 0);
  if (num_local > 0) {
    SHELLFRAC_REQUIRE(parts != nullptr, "Zoltan2 returned no part list");
    for (std::size_t i = 0; i < num_local; ++i) out[i] = static_cast<int>(parts[i]);
  }
  return out;
}

/// The part of each element of `in` (its order) from a Zoltan2 problem over tcomm.
std::vector<int> solve_on(const ZoltanInput& in, int nparts, const std::string& algorithm, double tolerance,
                          const Teuchos::RCP<const Teuchos::Comm<int>>& tcomm) {
  const std::size_t num_local = in.elements.size();
  std::vector<go_type> gids(in.elements.begin(), in.elements.end());
  auto map = Teuchos::rcp(new map_type(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                       Teuchos::ArrayView<const go_type>(gids.data(), gids.size()), go_type(0), tcomm));

  Teuchos::ParameterList zparams("Zoltan2");
  zparams.set("algorithm", algorithm);
  zparams.set("partitioning_approach", "partition");
  zparams.set("num_global_parts", nparts);
  zparams.set("imbalance_tolerance", tolerance);
  // Zoltan (behind phg and rcb) prints every parameter at its default debug level.
  zparams.sublist("zoltan_parameters").set("DEBUG_LEVEL", std::string("0"));
  if (algorithm == "scotch") limit_scotch_threads();

  if (uses_centroids(algorithm)) {
    auto centroids = Teuchos::rcp(new coords_type(map, 3));
    {
      auto view = centroids->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t i = 0; i < num_local; ++i)
        for (int d = 0; d < 3; ++d) view(i, d) = in.centroids[i][static_cast<std::size_t>(d)];
    }
    using adapter_type = Zoltan2::XpetraMultiVectorAdapter<coords_type>;
    const Teuchos::RCP<const coords_type> input = centroids;
    adapter_type adapter(input);
    return solve(adapter, zparams, tcomm, num_local);
  }
  std::vector<std::size_t> counts(num_local);
  for (std::size_t i = 0; i < num_local; ++i) counts[i] = in.rows[i].size();
  auto graph = Teuchos::rcp(new graph_type(map, Teuchos::ArrayView<const std::size_t>(counts.data(), counts.size())));
  std::vector<go_type> row;
  for (std::size_t i = 0; i < num_local; ++i) {
    row.assign(in.rows[i].begin(), in.rows[i].end());
    graph->insertGlobalIndices(gids[i], Teuchos::ArrayView<const go_type>(row.data(), row.size()));
  }
  graph->fillComplete();
  using adapter_type = Zoltan2::XpetraCrsGraphAdapter<graph_type>;
  const Teuchos::RCP<const graph_type> input = graph;
  adapter_type adapter(input);
  return solve(adapter, zparams, tcomm, num_local);
}

/// Sorts `row`, removes repeats and `self`.
void sorted_unique_without(std::vector<GlobalId>& row, GlobalId self) {
  std::sort(row.begin(), row.end());
  row.erase(std::unique(row.begin(), row.end()), row.end());
  row.erase(std::remove(row.begin(), row.end(), self), row.end());
}

/// The centroid (vertex average, vertices in order) of the element whose vertices are at x[0..2].
Vec3 centroid(const Vec3* x) {
  Vec3 c{};
  for (std::size_t d = 0; d < 3; ++d) {
    double s = 0;
    for (int a = 0; a < num_vertices_tri; ++a) s += x[a][d];
    c[d] = s / num_vertices_tri;
  }
  return c;
}

}  // namespace

bool uses_centroids(const std::string& algorithm) { return algorithm == "rcb" || algorithm == "multijagged"; }

std::vector<int> partition_zoltan2(const ZoltanInput& in, int nparts, const std::string& algorithm,
                                   double imbalance_tolerance, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  // Zoltan2 runs on the ranks that hold elements, so that every participating rank has at least one row.
  const bool active = !in.elements.empty();
  MPI_Comm sub = MPI_COMM_NULL;
  MPI_Comm_split(comm, active ? 0 : MPI_UNDEFINED, me, &sub);
  std::vector<int> local;
  parallel::on_all_then_agree(
      [&] {
        if (!active) return;
        try {
          auto tcomm = Teuchos::rcp(new Teuchos::MpiComm<int>(sub));
          local = solve_on(in, nparts, algorithm, imbalance_tolerance, tcomm);
          for (int p : local)
            SHELLFRAC_REQUIRE(p >= 0 && p < nparts, "Zoltan2 returned part " << p << " out of [0, " << nparts << ")");
        } catch (const Error&) {
          throw;
        } catch (const std::exception& e) {
          SHELLFRAC_REQUIRE(false, "Zoltan2 partitioning (algorithm '" << algorithm << "', " << nparts
                                                                      << " parts) failed: " << e.what());
        }
      },
      comm);
  if (sub != MPI_COMM_NULL) MPI_Comm_free(&sub);
  return local;
}

ZoltanInput zoltan_input_of_share(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo,
                                  const std::string& algorithm, MPI_Comm comm) {
  const GlobalId ne = mesh.num_elements(), P = parallel::size(comm), r = parallel::rank(comm);
  const GlobalId w = (ne + P - 1) / P, first = std::min(ne, r * w), end = std::min(ne, (r + 1) * w);
  ZoltanInput in;
  for (GlobalId e = first; e < end; ++e) in.elements.push_back(e);
  if (uses_centroids(algorithm)) {
    for (GlobalId e = first; e < end; ++e) {
      const Vec3 x[3] = {mesh.coords[mesh.node(e, 0)], mesh.coords[mesh.node(e, 1)], mesh.coords[mesh.node(e, 2)]};
      in.centroids.push_back(centroid(x));
    }
    return in;
  }
  in.rows.resize(in.elements.size());
  for (const auto& f : topo.interfaces) {
    if (f.minus.element >= first && f.minus.element < end)
      in.rows[static_cast<std::size_t>(f.minus.element - first)].push_back(f.plus.element);
    if (f.plus.element >= first && f.plus.element < end)
      in.rows[static_cast<std::size_t>(f.plus.element - first)].push_back(f.minus.element);
  }
  for (std::size_t i = 0; i < in.rows.size(); ++i) sorted_unique_without(in.rows[i], in.elements[i]);
  return in;
}

ZoltanInput zoltan_input_of_piece(const mesh::ElementPiece& piece, const LocalTopology& topo,
                                  const std::string& algorithm) {
  ZoltanInput in;
  in.elements = piece.elements;
  const auto npe = static_cast<std::size_t>(piece.nodes_per_element);
  if (uses_centroids(algorithm)) {
    for (std::size_t i = 0; i < piece.elements.size(); ++i) in.centroids.push_back(centroid(&piece.coords[npe * i]));
    return in;
  }
  // The piece's position of each element id, to file each interface under its sides here.
  std::vector<std::pair<GlobalId, std::size_t>> position;
  for (std::size_t i = 0; i < piece.elements.size(); ++i) position.emplace_back(piece.elements[i], i);
  std::sort(position.begin(), position.end());
  const auto add = [&](GlobalId e, GlobalId other) {
    auto it = std::lower_bound(position.begin(), position.end(), std::make_pair(e, std::size_t{0}));
    if (it != position.end() && it->first == e) in.rows[it->second].push_back(other);
  };
  in.rows.resize(in.elements.size());
  for (const auto& f : topo.interfaces) {
    add(f.minus.element, f.plus.element);
    add(f.plus.element, f.minus.element);
  }
  for (std::size_t i = 0; i < in.rows.size(); ++i) sorted_unique_without(in.rows[i], in.elements[i]);
  return in;
}

}  // namespace shellfrac::decomposition::detail
