#pragma once
/// \file partitioner_detail.hpp
/// Internal to shellfrac_decomposition: the two back ends of partition_elements(). Not installed, not for callers.
#include <mpi.h>

#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
struct EdgeTopology;
struct ElementPiece;
}  // namespace shellfrac::mesh

namespace shellfrac::decomposition {
struct LocalTopology;
}

namespace shellfrac::decomposition::detail {

/// METIS_PartGraphKway on the element dual graph, run on rank 0 and broadcast. Requires
/// 1 < nparts < num_elements. Collective.
std::vector<int> partition_metis(const mesh::EdgeTopology& topo, long long num_elements, int nparts,
                                 double imbalance_tolerance, int seed, MPI_Comm comm);

/// What Zoltan2 partitions on one rank: some elements (global ids) with their centroids (rcb, multijagged) or
/// their rows of the element dual graph (scotch, phg: the elements across their interfaces, ascending, each once).
struct ZoltanInput {
  std::vector<GlobalId> elements;
  std::vector<Vec3> centroids;
  std::vector<std::vector<GlobalId>> rows;
};

/// Whether the algorithm partitions element centroids (rcb, multijagged) rather than the dual graph.
bool uses_centroids(const std::string& algorithm);

/// The Zoltan2 input of this rank's share of the whole mesh: the elements [r W, (r + 1) W), W = ceil(N / P).
ZoltanInput zoltan_input_of_share(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo,
                                  const std::string& algorithm, MPI_Comm comm);
/// The Zoltan2 input of a piece of the mesh: the same as zoltan_input_of_share's when the piece is that share.
ZoltanInput zoltan_input_of_piece(const mesh::ElementPiece& piece, const LocalTopology& topo,
                                  const std::string& algorithm);

/// Zoltan2 PartitioningProblem (scotch, phg: dual graph; rcb, multijagged: element centroids) over the elements
/// the ranks give; returns the part of each of this rank's elements. The same input gives the same parts.
/// Requires 1 < nparts < the number of elements. Collective.
std::vector<int> partition_zoltan2(const ZoltanInput& input, int nparts, const std::string& algorithm,
                                   double imbalance_tolerance, MPI_Comm comm);

}  // namespace shellfrac::decomposition::detail
