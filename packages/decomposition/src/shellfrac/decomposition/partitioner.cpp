#include "shellfrac/decomposition/partitioner.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/decomposition/partitioner_detail.hpp"
#include "shellfrac/mesh/mesh_piece.hpp"
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

namespace {

/// The part of element e when no library is called: one part (0), or at least as many parts as elements (e;
/// METIS 5.1 is unreliable when nparts >= number of vertices). -1 when a library must be called.
int trivial_part(GlobalId e, GlobalId num_elements, int nparts) {
  if (nparts == 1) return 0;
  if (static_cast<GlobalId>(nparts) >= num_elements) return static_cast<int>(e);
  return -1;
}

void check_request(int nparts, const PartitionParams& params) {
  SHELLFRAC_REQUIRE(nparts >= 1, "partition_elements: nparts must be >= 1, got " << nparts);
  SHELLFRAC_REQUIRE(params.imbalance_tolerance >= 1.0,
                    "partition_elements: imbalance tolerance must be >= 1, got " << params.imbalance_tolerance);
  const auto& algs = zoltan2_algorithms();
  SHELLFRAC_REQUIRE(params.method != PartitionParams::Method::Zoltan2 ||
                        std::find(algs.begin(), algs.end(), params.zoltan2_algorithm) != algs.end(),
                    "partition_elements: unknown Zoltan2 algorithm '" << params.zoltan2_algorithm << "'");
}

}  // namespace

std::vector<int> partition_elements(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                    const PartitionParams& params, MPI_Comm comm) {
  check_request(nparts, params);
  const GlobalId ne = mesh.num_elements();
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(topo.element_edges.size()) == ne,
                    "partition_elements: the edge topology has " << topo.element_edges.size()
                                                                 << " elements but the mesh has " << ne);
  if (trivial_part(0, ne, nparts) >= 0) {
    std::vector<int> part(static_cast<std::size_t>(ne));
    for (GlobalId e = 0; e < ne; ++e) part[static_cast<std::size_t>(e)] = trivial_part(e, ne, nparts);
    return part;
  }
  if (params.method == PartitionParams::Method::METIS)
    return detail::partition_metis(topo, ne, nparts, params.imbalance_tolerance, params.seed, comm);
  const std::string& algorithm = params.zoltan2_algorithm;
  const std::vector<int> share = detail::partition_zoltan2(detail::zoltan_input_of_share(mesh, topo, algorithm, comm),
                                                           nparts, algorithm, params.imbalance_tolerance, comm);
  // The shares are contiguous and in rank order, so the concatenation is in global element order.
  std::vector<int> part = parallel::all_gather(share, comm);
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(part.size()) == ne,
                    "Zoltan2 partitioner: gathered " << part.size() << " parts for " << ne << " elements");
  return part;
}

std::vector<int> partition_piece(const mesh::ElementPiece& piece, const LocalTopology& topo, GlobalId num_elements,
                                 int nparts, const PartitionParams& params, MPI_Comm comm) {
  check_request(nparts, params);
  parallel::on_all_then_agree(
      [&] {
        SHELLFRAC_REQUIRE(topo.element_edges.size() == piece.elements.size(),
                          "partition_piece: the topology has " << topo.element_edges.size()
                                                               << " elements but the piece has "
                                                               << piece.elements.size());
      },
      comm);
  if (trivial_part(0, num_elements, nparts) >= 0) {
    std::vector<int> part;
    for (GlobalId e : piece.elements) part.push_back(trivial_part(e, num_elements, nparts));
    return part;
  }
  SHELLFRAC_REQUIRE(params.method == PartitionParams::Method::Zoltan2,
                    "partition_piece: METIS partitions the whole mesh on one rank; a mesh held in pieces is "
                    "partitioned with Zoltan2");
  const std::string& algorithm = params.zoltan2_algorithm;
  return detail::partition_zoltan2(detail::zoltan_input_of_piece(piece, topo, algorithm), nparts, algorithm,
                                   params.imbalance_tolerance, comm);
}

}  // namespace shellfrac::decomposition
