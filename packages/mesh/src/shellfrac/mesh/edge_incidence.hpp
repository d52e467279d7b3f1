#pragma once
/// \file edge_incidence.hpp
/// Internal helper: every (element, local edge) keyed by its sorted vertex pair, sorted so that uses of
/// the same edge are adjacent and ordered by element id. Used by the topology, P2 promotion and refinement.
#include <algorithm>
#include <tuple>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh::detail {

/// One use of an edge by an element.
struct EdgeUse {
  GlobalId a, b;     ///< vertex node ids, a < b
  GlobalId element;  ///< element id
  int local_edge;    ///< 0..2
  bool operator<(const EdgeUse& o) const {
    return std::tie(a, b, element, local_edge) < std::tie(o.a, o.b, o.element, o.local_edge);
  }
};

/// All edge uses of a triangle mesh given its vertex (first three) nodes, sorted.
/// `vertex(e, i)` returns vertex i of element e.
template <class VertexFn>
std::vector<EdgeUse> edge_uses(GlobalId num_elements, VertexFn vertex) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * num_elements);
  for (GlobalId e = 0; e < num_elements; ++e)
    for (int k = 0; k < 3; ++k) {
      const GlobalId p = vertex(e, edge_vertex[k][0]), q = vertex(e, edge_vertex[k][1]);
      uses.push_back({std::min(p, q), std::max(p, q), e, k});
    }
  std::sort(uses.begin(), uses.end());
  return uses;
}

/// Calls fn(first, last) for each group [first, last) of uses of the same edge (`uses` sorted, each use with its
/// vertex ids a, b).
template <class Uses, class Fn>
void for_each_edge(const Uses& uses, Fn fn) {
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    fn(i, j);
    i = j;
  }
}

}  // namespace shellfrac::mesh::detail
