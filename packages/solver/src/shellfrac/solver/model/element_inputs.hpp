#pragma once
/// \file element_inputs.hpp
/// What the element kernel reads of one owned element (docs/theory.md §5.4): its nodes, its lifted edges and,
/// across each lifted edge, the neighbour's edge nodes in the neighbour's edge-local order. Shared by the force
/// kernel (step/force_assembly.cpp) and the strains of the output fields and the nucleation energy check
/// (element_strains.cpp), so both see the same kinematics. A kernel header: it includes Kokkos_Core.hpp.
#include <array>

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/solver/model/kernel_views.hpp"

namespace shellfrac::solver {

/// The neighbour across each edge of every overlap element: its local id, and its local edge.
struct NeighborViews {
  KernelView<const LocalId> element;  ///< entry le * 3 + k
  KernelView<const int> edge;         ///< entry le * 3 + k
  explicit NeighborViews(const decomposition::DistributedMesh& d)
      : element(kernel_view(d.neighbors())), edge(kernel_view(d.neighbor_edges())) {}
  /// The element across local edge k of element le, and that element's local edge there.
  KOKKOS_INLINE_FUNCTION LocalId element_across(LocalId le, int k) const { return element(le * 3 + k); }
  KOKKOS_INLINE_FUNCTION int edge_across(LocalId le, int k) const { return edge(le * 3 + k); }
};

/// The nodes of local edge k of element le, in its edge-local order (disc::edge_node).
KOKKOS_INLINE_FUNCTION void edge_nodes_of(const ConstPositionView& x, const ConstDirectorView& t, LocalId le, int k,
                                          disc::EdgeNodes& out) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) out.x[j][c] = x(le, disc::edge_node(k, j), c);
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) out.t[j][c] = t(le, disc::edge_node(k, j), c);
}

/// The inputs of the element kernel for owned element le (dg_element_forces / dg_kinematics): its nodes, its
/// lifted edges and, across each lifted edge, the neighbour's edge nodes in the neighbour's edge-local order
/// (zero across an edge that is not lifted).
KOKKOS_INLINE_FUNCTION void element_inputs(const NeighborViews& nb, const ConstPositionView& x,
                                           const ConstDirectorView& t, const std::array<bool, 3>& lift, LocalId le,
                                           disc::DgElementNodes& in) {
  for (int A = 0; A < position_nodes; ++A)
    for (int c = 0; c < 3; ++c) in.x[A][c] = x(le, A, c);
  for (int a = 0; a < director_nodes; ++a)
    for (int c = 0; c < 3; ++c) in.t[a][c] = t(le, a, c);
  for (int k = 0; k < 3; ++k) {
    in.lift[k] = lift[k];
    if (lift[k])
      edge_nodes_of(x, t, nb.element_across(le, k), nb.edge_across(le, k), in.neighbour[k]);
    else
      in.neighbour[k] = disc::EdgeNodes{};
  }
}

}  // namespace shellfrac::solver
