/// \file partitioner_metis.cpp
/// METIS 5.1 back end (the paper's partitioner). Serial: rank 0 partitions the element dual graph with
/// METIS_PartGraphKway and broadcasts the part vector. idx_t is 32-bit in Debian's METIS, so sizes are checked.
#include <metis.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/partitioner_detail.hpp"
#include "shellfrac/mesh/edge_topology.hpp"

namespace shellfrac::decomposition::detail {

namespace {
const char* metis_status(int rc) {
  switch (rc) {
    case METIS_ERROR_INPUT: return "METIS_ERROR_INPUT (erroneous input or options)";
    case METIS_ERROR_MEMORY: return "METIS_ERROR_MEMORY (out of memory)";
    case METIS_ERROR: return "METIS_ERROR";
    default: return "unknown METIS return code";
  }
}

std::vector<int> run_metis(const mesh::EdgeTopology& topo, long long num_elements, int nparts, double tolerance,
                           int seed) {
  std::vector<GlobalId> offsets, adjacency;
  mesh::dual_graph(topo, num_elements, offsets, adjacency);
  SHELLFRAC_REQUIRE(static_cast<long long>(offsets.size()) == num_elements + 1,
                    "METIS partitioner: dual graph has " << offsets.size() << " offsets for " << num_elements
                                                         << " elements");
  constexpr auto idx_max = static_cast<long long>(std::numeric_limits<idx_t>::max());
  SHELLFRAC_REQUIRE(num_elements <= idx_max && static_cast<long long>(adjacency.size()) <= idx_max,
                    "METIS partitioner: the dual graph (" << num_elements << " vertices, " << adjacency.size()
                                                          << " adjacency entries) exceeds METIS' 32-bit idx_t");
  // CSR in idx_t, without self loops and duplicate neighbours (METIS requires a simple symmetric graph).
  std::vector<idx_t> xadj(static_cast<std::size_t>(num_elements) + 1, 0), adjncy;
  adjncy.reserve(adjacency.size());
  for (long long e = 0; e < num_elements; ++e) {
    const auto begin = adjacency.begin() + offsets[e], end = adjacency.begin() + offsets[e + 1];
    std::vector<GlobalId> row(begin, end);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    for (GlobalId n : row) {
      SHELLFRAC_REQUIRE(n >= 0 && n < num_elements, "METIS partitioner: dual graph neighbour " << n
                                                         << " of element " << e << " out of range");
      if (n != e) adjncy.push_back(static_cast<idx_t>(n));
    }
    xadj[e + 1] = static_cast<idx_t>(adjncy.size());
  }

  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed);
  // ufactor: allowed load imbalance in units of 1/1000 (1.05 -> 50); METIS needs at least 1.
  options[METIS_OPTION_UFACTOR] =
      static_cast<idx_t>(std::clamp(std::lround((tolerance - 1.0) * 1000.0), 1L, 100000L));
  options[METIS_OPTION_NUMBERING] = 0;
  idx_t nvtxs = static_cast<idx_t>(num_elements), ncon = 1, np = static_cast<idx_t>(nparts), objval = 0;
  std::vector<idx_t> part(static_cast<std::size_t>(num_elements), 0);
  const int rc = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr, &np,
                                     nullptr, nullptr, options, &objval, part.data());
  SHELLFRAC_REQUIRE(rc == METIS_OK, "METIS_PartGraphKway failed on " << num_elements << " elements, " << nparts
                                                                      << " parts: " << metis_status(rc));
  std::vector<int> out(part.begin(), part.end());
  for (int p : out) SHELLFRAC_REQUIRE(p >= 0 && p < nparts, "METIS returned part " << p << " out of [0, " << nparts << ")");
  return out;
}
}  // namespace

std::vector<int> partition_metis(const mesh::EdgeTopology& topo, long long num_elements, int nparts,
                                 double imbalance_tolerance, int seed, MPI_Comm comm) {
  std::vector<int> part;
  // Rank 0 computes; a failure there is thrown on every rank (no hang).
  parallel::on_root_then_agree([&] { part = run_metis(topo, num_elements, nparts, imbalance_tolerance, seed); }, 0,
                               comm);
  parallel::broadcast_vector(part, 0, comm);
  return part;
}

}  // namespace shellfrac::decomposition::detail
