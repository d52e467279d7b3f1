#pragma once
/// \file partitioner.hpp
/// Element partitioning behind one interface. Methods:
///  * "METIS" (default; the paper's choice): METIS 5.1 called directly (METIS_PartGraphKway on the element
///    dual graph, computed on rank 0 and broadcast). Debian's Zoltan2 is built without METIS.
///  * "Zoltan2": Zoltan2 13.2 with algorithm "scotch" (graph), "rcb" or "multijagged" (element centroids),
///    or "phg" (hypergraph/graph), run in parallel: from each rank's share of the elements [r W, (r + 1) W),
///    W = ceil(N / P), for the whole mesh; from the pieces themselves for a mesh held in pieces, which gives the
///    same parts when the pieces are those shares (a mesh file read by meshio::read_exodus_piece).
/// Every element gets exactly one part in [0, nparts). nparts may exceed the number of elements (some
/// parts are then empty); with nparts == 1 no library is called.
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
struct EdgeTopology;
struct ElementPiece;
}  // namespace shellfrac::mesh

namespace shellfrac::decomposition {

struct LocalTopology;  // distributed_topology.hpp

/// Validated partitioning options (deck sublist "Partitioning").
struct PartitionParams {
  enum class Method { METIS, Zoltan2 };
  Method method = Method::METIS;
  std::string zoltan2_algorithm = "scotch";  ///< scotch | rcb | multijagged | phg
  double imbalance_tolerance = 1.05;         ///< max part weight / average part weight
  int seed = 1;                              ///< METIS seed (results are deterministic for a given seed)

  /// Valid parameters of the "Partitioning" sublist.
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// Validates `pl` (sets defaults) and converts it.
  static PartitionParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// Partitions the elements into nparts parts; returns the part of every element, the same on every rank.
/// mesh and topo must be the same on every rank. Collective over comm.
std::vector<int> partition_elements(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo, int nparts,
                                    const PartitionParams& params, MPI_Comm comm = MPI_COMM_WORLD);

/// Partitions the elements of a mesh held in pieces (`piece` here, its topology `topo`, build_local_topology; N =
/// num_elements over all ranks) into nparts parts with Zoltan2; returns the part of each element of the piece, in
/// its order. No rank sees more than its piece. Error for Method METIS (it needs the whole graph on one rank).
/// Collective over comm.
std::vector<int> partition_piece(const mesh::ElementPiece& piece, const LocalTopology& topo, GlobalId num_elements,
                                 int nparts, const PartitionParams& params, MPI_Comm comm = MPI_COMM_WORLD);

}  // namespace shellfrac::decomposition
