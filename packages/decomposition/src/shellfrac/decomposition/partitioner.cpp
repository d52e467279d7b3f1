#include "shellfrac/decomposition/partitioner.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/partitioner_detail.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::decomposition {

namespace {
const std::vector<std::string>& zoltan2_algorithms() {
  static const std::vector<std::string> a = {"scotch", "rcb", "multijagged", "phg"};
  return a;
}
}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> PartitionParams::valid_parameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Partitioning"));
    params::set_choice(*pl, "Method", "METIS",
                       "Element partitioner: METIS 5.1 called directly (serial, on rank 0) or Zoltan2 (parallel). "
                       "Debian's Zoltan2 is built without METIS, hence the separate choice.",
                       {"METIS", "Zoltan2"});
    params::set_choice(*pl, "Zoltan2 Algorithm", "scotch",
                       "Zoltan2 algorithm (Method = Zoltan2): scotch and phg partition the element dual graph, "
                       "rcb and multijagged the element centroids.",
                       zoltan2_algorithms());
    pl->set("Imbalance Tolerance", 1.05, "Allowed max part size / average part size (>= 1).",
            params::double_range(1.0, std::numeric_limits<double>::max()));
    pl->set("Seed", 1, "Random seed of METIS (the partition is deterministic for a given seed).",
            params::int_range(0, std::numeric_limits<int>::max()));
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

PartitionParams PartitionParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  PartitionParams p;
  p.method = pl.get<std::string>("Method") == "Zoltan2" ? Method::Zoltan2 : Method::METIS;
  p.zoltan2_algorithm = pl.get<std::string>("Zoltan2 Algorithm");
  p.imbalance_tolerance = pl.get<double>("Imbalance Tolerance");
  p.seed = pl.get<int>("Seed");
  return p;
}

std::vector<int> partition_elements(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                    const PartitionParams& params, MPI_Comm comm) {
  SHELLFRAC_REQUIRE(nparts >= 1, "partition_elements: nparts must be >= 1, got " << nparts);
  const GlobalId ne = mesh.num_elements();
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(topo.element_edges.size()) == ne,
                    "partition_elements: the edge topology has " << topo.element_edges.size()
                                                                 << " elements but the mesh has " << ne);
  // Trivial cases, no library call: one part, or at least as many parts as elements (element i -> part i;
  // METIS 5.1 is unreliable when nparts >= number of vertices).
  if (nparts == 1) return std::vector<int>(static_cast<std::size_t>(ne), 0);
  if (static_cast<GlobalId>(nparts) >= ne) {
    std::vector<int> part(static_cast<std::size_t>(ne));
    std::iota(part.begin(), part.end(), 0);
    return part;
  }
  SHELLFRAC_REQUIRE(params.imbalance_tolerance >= 1.0,
                    "partition_elements: imbalance tolerance must be >= 1, got " << params.imbalance_tolerance);
  if (params.method == PartitionParams::Method::METIS)
    return detail::partition_metis(topo, ne, nparts, params.imbalance_tolerance, params.seed, comm);
  const auto& algs = zoltan2_algorithms();
  SHELLFRAC_REQUIRE(std::find(algs.begin(), algs.end(), params.zoltan2_algorithm) != algs.end(),
                    "partition_elements: unknown Zoltan2 algorithm '" << params.zoltan2_algorithm << "'");
  return detail::partition_zoltan2(mesh, topo, nparts, params.zoltan2_algorithm, params.imbalance_tolerance, comm);
}

}  // namespace shellfrac::decomposition
