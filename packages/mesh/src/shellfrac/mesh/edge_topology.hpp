#pragma once
/// \file edge_topology.hpp
/// Unique edges of a SerialMesh and the interface map P of paper §5.1:
///   P : interface -> (E-, ê-), (E+, ê+)
/// built deterministically (same ids on every rank and for every rank count).
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh {

struct SerialMesh;

/// (element, local edge) pair.
struct ElementEdge {
  GlobalId element = -1;
  int local_edge = -1;
};

/// An interior interface between two elements (paper §5.1). minus.element < plus.element.
/// The traversal direction of the shared edge is opposite in the two elements when their orientations
/// agree (consistent normals); `same_orientation` records it (false for consistently oriented meshes).
struct Interface {
  GlobalId edge = -1;  ///< unique edge id
  ElementEdge minus, plus;
  bool same_orientation = false;  ///< true if the two elements traverse the edge in the same direction
  bool non_manifold = false;      ///< the edge has 3 or more elements (see NonManifoldPolicy)
};

/// What to do with an edge shared by 3 or more elements (T-joints, wing roots).
enum class NonManifoldPolicy {
  Error,  ///< reject the mesh, naming the edge and its elements
  Star,   ///< couple the lowest-id element to each other one (k elements -> k-1 interfaces)
  Free    ///< no coupling: every element sees a free (boundary) edge
};

/// Edge data of a mesh. Edge ids follow the sorted order of (min vertex, max vertex).
struct EdgeTopology {
  std::vector<std::array<GlobalId, 2>> edge_vertices;  ///< per edge: its two vertex node ids, ascending
  std::vector<std::array<GlobalId, 3>> element_edges;  ///< per element: edge id of local edges 0,1,2
  std::vector<Interface> interfaces;                  ///< sorted by (edge, minus.element, plus.element)
  std::vector<ElementEdge> boundary;                  ///< edges with one element (and Free non-manifold sides)
  std::vector<std::vector<int>> boundary_side_sets;   ///< per boundary entry: indices of side sets containing it
  /// Per element and local edge: index into `interfaces` (-1 if none) and the neighbour across it.
  std::vector<std::array<GlobalId, 3>> element_interface;
  std::vector<std::array<ElementEdge, 3>> neighbor;  ///< neighbour element/local edge, element -1 if none
  GlobalId num_non_manifold_edges = 0;

  GlobalId num_edges() const { return static_cast<GlobalId>(edge_vertices.size()); }
};

/// Builds the edge topology. Side sets may name any edge. Edges with 3+ elements follow `policy`
/// (Error: InputError naming mesh.source, the edge's vertices and its elements).
EdgeTopology build_edge_topology(const SerialMesh& mesh, NonManifoldPolicy policy = NonManifoldPolicy::Star);

/// The element dual graph in CSR form (vertex = element, graph edge = interface), neighbours sorted.
void dual_graph(const EdgeTopology& topo, GlobalId num_elements, std::vector<GlobalId>& offsets,
                std::vector<GlobalId>& adjacency);

}  // namespace shellfrac::mesh
