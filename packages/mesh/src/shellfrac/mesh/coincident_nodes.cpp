#include "shellfrac/mesh/coincident_nodes.hpp"

#include <algorithm>
#include <vector>

namespace shellfrac::mesh {

CoincidentNodes coincident_nodes(const SerialMesh& mesh) {
  std::vector<char> used(mesh.coords.size(), 0);
  for (const GlobalId n : mesh.connectivity)
    if (n >= 0 && n < mesh.num_nodes()) used[n] = 1;
  std::vector<GlobalId> nodes;
  for (GlobalId n = 0; n < mesh.num_nodes(); ++n)
    if (used[n]) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end(), [&](GlobalId a, GlobalId b) { return mesh.coords[a] < mesh.coords[b]; });
  CoincidentNodes out;
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    if (mesh.coords[nodes[k]] != mesh.coords[nodes[k - 1]]) continue;
    if (out.count++ == 0) out.example = mesh.coords[nodes[k]];
  }
  return out;
}

}  // namespace shellfrac::mesh
