#include "shellfrac/solver/loads.hpp"

#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/mesh_sets.hpp"
#include "shellfrac/solver/shell_model.hpp"

namespace shellfrac::solver {

Loads::Loads(const std::vector<Load>& loads, const MeshSets& sets, const ShellModel& model) : loads_(loads) {
  const auto& dm = model.dm;
  gravity_force_.assign(model.owned, 0.0);
  for (const auto& load : loads_) {
    const auto member = sets.elements("load '" + load.name + "'", load.elements);
    loaded_elements_.emplace_back();
    for (LocalId le = 0; le < model.owned; ++le) {
      if (!member[dm.element_gid(le)]) continue;
      loaded_elements_.back().push_back(le);
      if (load.type != Load::Type::Gravity) continue;
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) gravity_force_.at(le, A)[c] += *model.mass.at(le, A) * load.acceleration[c];
    }
  }
}

// Follower pressure (docs/theory.md §10.3): f_ext^A = p(t) sum_q w_q N^A(xi_q) (dphi/dxi1 x dphi/dxi2)(xi_q) on the
// current mid-surface, with the ordinary (not DG) element derivatives.
void Loads::external_forces(double t, const PositionRows& x, PositionRows& fext) const {
  std::copy(gravity_force_.vector().begin(), gravity_force_.vector().end(), fext.vector().begin());
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const auto& load = loads_[l];
    if (load.type != Load::Type::Pressure) continue;
    const double p = load.pressure_at(t);
    for (LocalId le : loaded_elements_[l])
      for (int q = 0; q < disc::tri6_rule.num_points; ++q) {
        double N[6], dN[6][2], g1[3] = {0, 0, 0}, g2[3] = {0, 0, 0}, n[3];
        p2_shape(disc::tri6_rule.xi[q][0], disc::tri6_rule.xi[q][1], N, dN);
        for (int A = 0; A < 6; ++A)
          for (int c = 0; c < 3; ++c) g1[c] += dN[A][0] * x.at(le, A)[c], g2[c] += dN[A][1] * x.at(le, A)[c];
        disc::cross3(g1, g2, n);
        for (int A = 0; A < 6; ++A)
          for (int c = 0; c < 3; ++c) fext.at(le, A)[c] += p * disc::tri6_rule.w[q] * N[A] * n[c];
      }
  }
}

}  // namespace shellfrac::solver
