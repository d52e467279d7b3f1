#include "shellfrac/solver/model/symmetry_directors.hpp"

#include <cmath>

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"

namespace shellfrac::solver {

long hold_reference_directors_in_symmetry_planes(const Deck& deck, const mesh::SerialMesh& mesh,
                                                 decomposition::DistributedMesh& dm, double max_angle_degrees) {
  const double max_sine = std::sin(max_angle_degrees * M_PI / 180);
  const MeshSets sets(mesh, deck.file, deck.regions);
  long moved = 0;
  for (const auto& bc : deck.boundary_conditions) {
    if (bc.type != BoundaryCondition::Type::Symmetry) continue;
    const std::string what = "boundary condition '" + bc.name + "'";
    const auto member = sets.node_set(what, bc.node_set, true);
    const auto in_elements = sets.elements(what + " (Elements)", bc.elements);
    const Vec3& n = bc.normal;
    for (LocalId le = 0; le < dm.num_overlap(); ++le) {
      if (!in_elements[dm.element_gid(le)]) continue;
      for (int a = 0; a < 3; ++a) {
        if (!member[dm.mesh_node(le, a)]) continue;
        Vec3 t = dm.reference_director(le, a);
        const double off = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        if (off == 0 || std::abs(off) > max_sine) continue;
        for (int c = 0; c < 3; ++c) t[c] -= off * n[c];
        const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (double& c : t) c /= length;
        dm.set_reference_director(le, a, t);
        ++moved;
      }
    }
  }
  return moved;
}

}  // namespace shellfrac::solver
