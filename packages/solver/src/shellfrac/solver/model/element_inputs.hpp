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

/// The neighbour across each edge of every overlap element (entry le * 3 + k: its local id, and its local edge).
struct NeighborViews {
  KernelView<const LocalId> element;
  KernelView<const int> edge;
  explicit NeighborViews(const decomposition::DistributedMesh& d)
      : element(kernel_view(d.neighbors())), edge(kernel_view(d.neighbor_edges())) {}
};

/// The inputs of the element kernel for owned element le (dg_element_forces / dg_kinematics): its nodes, its
/// lifted edges and, across each lifted edge, the neighbour's edge nodes in the neighbour's edge-local order.
KOKKOS_INLINE_FUNCTION void element_inputs(const NeighborViews& nb, const KernelView<const double>& xp,
                                           const KernelView<const double>& tp, const std::array<bool, 3>& lift,
                                           LocalId le, double xe[6][3], double te[3][3], bool lf[3], double xn[3][3][3],
                                           double tn[3][2][3]) {
  constexpr int nx = position_values, nt = director_values;
  for (int i = 0; i < nx; ++i) xe[i / 3][i % 3] = xp(le * nx + i);
  for (int i = 0; i < nt; ++i) te[i / 3][i % 3] = tp(le * nt + i);
  for (int k = 0; k < 3; ++k) {
    lf[k] = lift[k];
    if (!lf[k]) continue;
    const LocalId n = nb.element(le * 3 + k);
    const int kk = nb.edge(le * 3 + k);
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) xn[k][j][c] = xp(n * nx + disc::edge_node(kk, j) * 3 + c);
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) tn[k][j][c] = tp(n * nt + disc::edge_node(kk, j) * 3 + c);
  }
}

}  // namespace shellfrac::solver
