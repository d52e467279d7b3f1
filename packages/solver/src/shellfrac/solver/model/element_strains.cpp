#include "shellfrac/solver/model/element_strains.hpp"

#include "shellfrac/solver/model/element_inputs.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

void element_strains(const ShellModel& model, const ShellState& s, LocalId le,
                     PointStrains out[disc::num_area_points]) {
  constexpr int nq = disc::num_area_points;
  disc::DgElementNodes in;
  element_inputs(NeighborViews(model.dm), kernel_view(s.x), kernel_view(s.t), model.lifted[le], le, in);
  disc::ShellKinematics kin[nq];
  const disc::DgElementRef& R = model.element_refs[le];
  disc::dg_kinematics(R, in, kin);
  double eps[nq][3], gam[nq][2], rho[nq][3];
  disc::dg_strains(R, kin, eps, gam, rho);
  for (int q = 0; q < nq; ++q) {
    out[q].weight = R.wj0[q];
    for (int c = 0; c < 3; ++c) out[q].eps[c] = eps[q][c], out[q].rho[c] = rho[q][c];
    for (int c = 0; c < 2; ++c) out[q].gam[c] = gam[q][c];
  }
}

}  // namespace shellfrac::solver
