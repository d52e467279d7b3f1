#include "shellfrac/solver/contact/rigid_bodies.hpp"

#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/contact/contact_penalty.hpp"
#include "shellfrac/solver/contact/coulomb_friction.hpp"
#include "shellfrac/solver/contact/rigid_body_shape.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

RigidBodies::RigidBodies(const ContactParams& params, const ShellModel& model, double dt, const std::string& file)
    : model_(model),
      bodies_(params.bodies),
      penalty_scale_(params.penalty_scale),
      stiffness_per_mass_(params.penalty_scale / (dt * dt)),
      step_ratio_squared_(4 * (dt / model.stable_dt) * (dt / model.stable_dt)),
      friction_(params.friction),
      dt_(dt) {
  if (!bodies_.empty()) check_contact_penalty(penalty_scale_, dt, model.stable_dt, file);
}

void RigidBodies::initial_state(ShellState& s) const {
  s.bodies.clear();
  for (const auto& b : bodies_) s.bodies.push_back({b.name, b.point, b.velocity, {0, 0, 0}, {0, 0, 0}});
}

void RigidBodies::predict(ShellState& s, double dt, double t1) const {
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBody& b = bodies_[k];
    RigidBodyState& m = s.bodies[k];
    for (int c = 0; c < 3; ++c) {
      if (b.free()) {
        m.x[c] += dt * m.v[c] + 0.5 * dt * dt * m.a[c];
        m.v[c] += 0.5 * dt * m.a[c];
      } else {
        m.x[c] = b.point[c] + b.velocity[c] * t1, m.v[c] = b.velocity[c];
      }
    }
  }
}

void RigidBodies::add_forces(double step, ShellState& s) const {
  if (bodies_.empty()) return;
  const ShellState& shells = s;
  std::vector<RigidBodyState>& bodies = s.bodies;
  PositionRows& fext = s.external_force;
  // Per body: the force on the shells (3) and the mass of the nodes in contact (1), summed exactly.
  std::vector<ExactSum> sums(4 * bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBody& b = bodies_[k];
    const BoundingSphere bound = bounding_sphere(b);
    const Vec3 axis = b.shape == RigidBody::Shape::Sphere ? Vec3{0, 0, 0} : b.axis;
    Vec3 centre;
    for (int c = 0; c < 3; ++c) centre[c] = bodies[k].x[c] + bound.offset * axis[c];
    for (LocalId le = 0; le < model_.owned; ++le) {
      const double h = model_.sections[model_.dm.element_block(le)].thickness;
      const double reach = (bound.radius + 0.5 * h) * (bound.radius + 0.5 * h);
      for (int A = 0; A < position_nodes; ++A) {
        const double* x = shells.x.at(le, A);
        const double dx = x[0] - centre[0], dy = x[1] - centre[1], dz = x[2] - centre[2];
        if (dx * dx + dy * dy + dz * dz > reach) continue;  // outside the bounding sphere: no contact
        const SurfaceDistance d = surface_distance(bodies_[k], bodies[k].x, {x[0], x[1], x[2]});
        const double gap = d.distance - 0.5 * h;
        if (gap >= 0) continue;
        const double m = *model_.mass.at(le, A), f = -stiffness_per_mass_ * m * gap;
        double* fe = fext.at(le, A);
        double force[3] = {f * d.normal[0], f * d.normal[1], f * d.normal[2]};
        if (friction_.enabled()) {  // the trial slip relative to the body (eq. 12.6a), as at a wall
          const double *v = s.v.at(le, A), *fi = s.internal_force.at(le, A);
          double slip[3], trial[3], ff[3];
          for (int c = 0; c < 3; ++c)
            slip[c] = v[c] - bodies[k].v[c], trial[c] = slip[c] + dt_ * (fe[c] + force[c] - fi[c]) / m;
          coulomb_friction(friction_, d.normal.data(), trial, f, m, dt_, ff);
          for (int c = 0; c < 3; ++c) force[c] += ff[c];
          *s.friction_dissipation.at(le) += friction_dissipation(ff, slip, step);
        }
        for (int c = 0; c < 3; ++c) fe[c] += force[c], sums[4 * k + std::size_t(c)].add(force[c]);
        sums[4 * k + 3].add(m);
      }
    }
  }
  ExactSum::allreduce(sums, model_.dm.comm());
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBody& b = bodies_[k];
    RigidBodyState& m = bodies[k];
    for (int c = 0; c < 3; ++c) m.force[c] = -sums[4 * k + std::size_t(c)].value();
    if (!b.free()) continue;
    // The nodes in contact and the body vibrate against each other at sqrt(k (1/m_A + 1/M)): with every node's
    // k / m_A = s / dt^2 the step stays stable while (2 S_f)^2 + s (1 + m_contact / M) < 4 (theory.md §12.4).
    const double contact_mass = sums[4 * k + 3].value();
    if (step_ratio_squared_ + penalty_scale_ * (1 + contact_mass / b.mass) >= 4) {
      std::ostringstream os;
      os << "rigid body '" << b.name << "': the shells in contact with it (mass " << contact_mass << ") are too heavy "
         << "against its Mass " << b.mass << " for the time step: the contact is unstable ((2 S_f)^2 + Penalty Scale "
         << "(1 + m_contact / Mass) >= 4, theory.md §12.4); lower 'Contact->Penalty Scale' or the Safety Factor";
      throw NumericalError(os.str());
    }
    for (int c = 0; c < 3; ++c) m.a[c] = m.force[c] / b.mass;
  }
}

void RigidBodies::correct(ShellState& s, double dt) const {
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    if (bodies_[k].free())
      for (int c = 0; c < 3; ++c) s.bodies[k].v[c] += 0.5 * dt * s.bodies[k].a[c];
}

std::vector<std::string> RigidBodies::history_columns() const {
  std::vector<std::string> out;
  for (const auto& b : bodies_)
    for (const char* q : {"_x", "_y", "_z", "_vel_x", "_vel_y", "_vel_z", "_force_x", "_force_y", "_force_z",
                          "_kinetic_energy"})
      out.push_back(b.name + q);
  return out;
}

std::vector<double> RigidBodies::history_values(const ShellState& s) const {
  std::vector<double> out;
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBodyState& m = s.bodies[k];
    out.insert(out.end(), {m.x[0], m.x[1], m.x[2], m.v[0], m.v[1], m.v[2], m.force[0], m.force[1], m.force[2]});
    const double v2 = m.v[0] * m.v[0] + m.v[1] * m.v[1] + m.v[2] * m.v[2];
    out.push_back(bodies_[k].free() ? 0.5 * bodies_[k].mass * v2 : 0.0);
  }
  return out;
}

}  // namespace shellfrac::solver
