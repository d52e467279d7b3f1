#include "shellfrac/solver/contact/rigid_walls.hpp"

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/solver/contact/contact_penalty.hpp"
#include "shellfrac/solver/contact/coulomb_friction.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

RigidWalls::RigidWalls(const ContactParams& params, const ShellModel& model, double dt, const std::string& file)
    : model_(model),
      walls_(params.walls),
      stiffness_per_mass_(params.penalty_scale / (dt * dt)),
      friction_(params.friction),
      dt_(dt) {
  if (!walls_.empty()) check_contact_penalty(params.penalty_scale, dt, model.stable_dt, file);
}

double RigidWalls::node_force(const RigidWall& w, double t, const ShellState& s, LocalId le, int A) const {
  const Vec3 p = w.point_at(t);
  const double* x = s.x.at(le, A);
  const double h = model_.sections[model_.dm.element_block(le)].thickness;
  const double gap = (x[0] - p[0]) * w.normal[0] + (x[1] - p[1]) * w.normal[1] + (x[2] - p[2]) * w.normal[2] - 0.5 * h;
  return gap < 0 ? -stiffness_per_mass_ * *model_.mass.at(le, A) * gap : 0.0;
}

void RigidWalls::add_forces(double t, double step, ShellState& s) const {
  PositionRows& fext = s.external_force;
  for (const RigidWall& w : walls_)
    for (LocalId le = 0; le < model_.owned; ++le)
      for (int A = 0; A < position_nodes; ++A) {
        const double f = node_force(w, t, s, le, A);
        if (f == 0) continue;
        double* fe = fext.at(le, A);
        for (int c = 0; c < 3; ++c) fe[c] += f * w.normal[c];
        if (!friction_.enabled()) continue;
        // The trial slip (eq. 12.6a): the velocity relative to the wall at the next half step without friction.
        const double m = *model_.mass.at(le, A);
        const double *v = s.v.at(le, A), *fi = s.internal_force.at(le, A);
        double slip[3], trial[3], ff[3];
        for (int c = 0; c < 3; ++c) slip[c] = v[c] - w.velocity[c], trial[c] = slip[c] + dt_ * (fe[c] - fi[c]) / m;
        coulomb_friction(friction_, w.normal.data(), trial, f, m, dt_, ff);
        for (int c = 0; c < 3; ++c) fe[c] += ff[c];
        *s.friction_dissipation.at(le) += friction_dissipation(ff, slip, step);
      }
}

std::vector<double> RigidWalls::normal_forces(double t, const ShellState& s) const {
  std::vector<ExactSum> sums(walls_.size());
  for (std::size_t k = 0; k < walls_.size(); ++k)
    for (LocalId le = 0; le < model_.owned; ++le)
      for (int A = 0; A < position_nodes; ++A) sums[k].add(node_force(walls_[k], t, s, le, A));
  ExactSum::allreduce(sums, model_.dm.comm());
  std::vector<double> out;
  for (const auto& f : sums) out.push_back(f.value());
  return out;
}

std::vector<std::string> RigidWalls::names() const {
  std::vector<std::string> out;
  for (const auto& w : walls_) out.push_back(w.name);
  return out;
}

}  // namespace shellfrac::solver
