#include "shellfrac/mesh/edge_topology.hpp"

#include <algorithm>
#include <map>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/mesh/edge_incidence.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::mesh {

namespace {
/// True if element e traverses its local edge k from the lower to the higher vertex id.
bool ascending(const SerialMesh& m, GlobalId e, int k) {
  return m.node(e, edge_vertex[k][0]) < m.node(e, edge_vertex[k][1]);
}
}  // namespace

EdgeTopology build_edge_topology(const SerialMesh& mesh, NonManifoldPolicy policy) {
  const GlobalId ne = mesh.num_elements();
  const auto uses = detail::edge_uses(ne, [&](GlobalId e, int i) { return mesh.node(e, i); });
  EdgeTopology t;
  t.element_edges.assign(ne, {-1, -1, -1});
  t.element_interface.assign(ne, {-1, -1, -1});
  t.neighbor.assign(ne, {ElementEdge{}, ElementEdge{}, ElementEdge{}});

  // Side-set membership of (element, local edge).
  std::map<std::pair<GlobalId, int>, std::vector<int>> side_membership;
  for (std::size_t s = 0; s < mesh.side_sets.size(); ++s)
    for (std::size_t i = 0; i < mesh.side_sets[s].elements.size(); ++i)
      side_membership[{mesh.side_sets[s].elements[i], mesh.side_sets[s].local_edges[i]}].push_back(static_cast<int>(s));
  auto add_boundary = [&](const detail::EdgeUse& u) {
    t.boundary.push_back({u.element, u.local_edge});
    auto it = side_membership.find({u.element, u.local_edge});
    t.boundary_side_sets.push_back(it == side_membership.end() ? std::vector<int>{} : it->second);
  };
  auto add_interface = [&](GlobalId edge, const detail::EdgeUse& m, const detail::EdgeUse& p, bool non_manifold) {
    Interface f;
    f.edge = edge;
    f.minus = {m.element, m.local_edge};
    f.plus = {p.element, p.local_edge};
    f.same_orientation = ascending(mesh, m.element, m.local_edge) == ascending(mesh, p.element, p.local_edge);
    f.non_manifold = non_manifold;
    const GlobalId id = static_cast<GlobalId>(t.interfaces.size());
    t.interfaces.push_back(f);
    // The first interface on an element edge defines its neighbour (a non-manifold centre element of a
    // Star has several; the interface list is the complete record).
    if (t.element_interface[m.element][m.local_edge] < 0) {
      t.element_interface[m.element][m.local_edge] = id;
      t.neighbor[m.element][m.local_edge] = f.plus;
    }
    t.element_interface[p.element][p.local_edge] = id;
    t.neighbor[p.element][p.local_edge] = f.minus;
  };

  detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
    const GlobalId edge = t.num_edges();
    t.edge_vertices.push_back({uses[first].a, uses[first].b});
    for (std::size_t u = first; u < last; ++u) t.element_edges[uses[u].element][uses[u].local_edge] = edge;
    const std::size_t count = last - first;
    if (count == 1) {
      add_boundary(uses[first]);
    } else if (count == 2) {
      add_interface(edge, uses[first], uses[first + 1], false);  // uses are sorted by element: minus < plus
    } else {
      ++t.num_non_manifold_edges;
      if (policy == NonManifoldPolicy::Error) {
        std::ostringstream os;
        // Named by the file's ids (mesh::FileIds), the elements also by their numbers in the results.
        const auto& node_ids = mesh.node_ids.ids;
        const auto& element_ids = mesh.element_ids.ids;
        const auto node_id = [&](GlobalId n) { return n < GlobalId(node_ids.size()) ? node_ids[n] : n + 1; };
        os << mesh.source << ": edge between nodes " << node_id(uses[first].a) << " and " << node_id(uses[first].b)
           << " is shared by " << count << " elements (";
        for (std::size_t u = first; u < last; ++u)
          os << (u > first ? ", " : "") << (element_ids.empty() ? uses[u].element + 1 : element_ids[uses[u].element]);
        if (!element_ids.empty()) {
          os << " in the mesh file; ";
          for (std::size_t u = first; u < last; ++u) os << (u > first ? ", " : "") << uses[u].element + 1;
          os << " in the results";
        }
        os << "): a T-joint or non-manifold edge. Set 'Mesh->Non-Manifold Edges' to 'Star' or 'Free' to accept it";
        throw InputError(os.str());
      }
      for (std::size_t u = first + 1; u < last; ++u) {
        if (policy == NonManifoldPolicy::Star)
          add_interface(edge, uses[first], uses[u], true);
        else
          add_boundary(uses[u]);
      }
      if (policy == NonManifoldPolicy::Free) add_boundary(uses[first]);
    }
  });
  return t;
}

void dual_graph(const EdgeTopology& topo, GlobalId num_elements, std::vector<GlobalId>& offsets,
                std::vector<GlobalId>& adjacency) {
  std::vector<std::vector<GlobalId>> adj(num_elements);
  for (const auto& f : topo.interfaces) {
    adj[f.minus.element].push_back(f.plus.element);
    adj[f.plus.element].push_back(f.minus.element);
  }
  offsets.assign(num_elements + 1, 0);
  adjacency.clear();
  for (GlobalId e = 0; e < num_elements; ++e) {
    std::sort(adj[e].begin(), adj[e].end());
    adj[e].erase(std::unique(adj[e].begin(), adj[e].end()), adj[e].end());
    adjacency.insert(adjacency.end(), adj[e].begin(), adj[e].end());
    offsets[e + 1] = static_cast<GlobalId>(adjacency.size());
  }
}

}  // namespace shellfrac::mesh
