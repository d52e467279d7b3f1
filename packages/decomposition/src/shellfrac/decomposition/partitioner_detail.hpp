#pragma once
/// \file partitioner_detail.hpp
/// Internal to shellfrac_decomposition: the two back ends of partition_elements(). Not installed, not for callers.
#include <mpi.h>

#include <string>
#include <vector>

namespace shellfrac::mesh {
struct SerialMesh;
struct EdgeTopology;
}  // namespace shellfrac::mesh

namespace shellfrac::decomposition::detail {

/// METIS_PartGraphKway on the element dual graph, run on rank 0 and broadcast. Requires
/// 1 < nparts < num_elements. Collective.
std::vector<int> partition_metis(const mesh::EdgeTopology& topo, long long num_elements, int nparts,
                                 double imbalance_tolerance, int seed, MPI_Comm comm);

/// Zoltan2 PartitioningProblem (scotch, phg: dual graph; rcb, multijagged: element centroids) from a
/// contiguous block distribution of the elements; the result is gathered on every rank. Requires
/// 1 < nparts < num_elements. Collective.
std::vector<int> partition_zoltan2(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                   const std::string& algorithm, double imbalance_tolerance, MPI_Comm comm);

}  // namespace shellfrac::decomposition::detail
