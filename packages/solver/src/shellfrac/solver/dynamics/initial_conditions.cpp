#include "shellfrac/solver/dynamics/initial_conditions.hpp"

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/step/constraints.hpp"

namespace shellfrac::solver {

namespace {

/// Every field sized for the model; positions and directors at their reference values, rotations from
/// Rodrigues' formula (paper A.1), everything else zero.
void size_state(const ShellModel& model, ShellState& s) {
  const auto& dm = model.dm;
  const LocalId no = model.owned, ni = static_cast<LocalId>(dm.interfaces().size());
  s.x.vector().assign(model.X.data(), model.X.data() + model.X.size());
  s.t.assign(model.overlap);
  for (LocalId le = 0; le < model.overlap; ++le)
    for (int a = 0; a < 3; ++a) disc::copy3(dm.reference_director(le, a).data(), s.t.at(le, a));
  for (auto* rows : {&s.v, &s.a, &s.internal_force, &s.external_force, &s.reaction}) rows->assign(no);
  s.director_force.assign(no), s.rotation.assign(no), s.director_rate.assign(no), s.director_acceleration.assign(no);
  s.external_director_force.assign(no);
  for (auto* rows : {&s.strain_energy, &s.external_work, &s.reaction_work, &s.damping_dissipation, &s.plastic_work,
                     &s.element_activation_loss, &s.friction_dissipation})
    rows->assign(no);
  s.plastic.assign(model.any_plastic ? no * disc::num_area_points : 0, materials::PlasticState{});
  s.mode.assign(ni, intact), s.delta_max.assign(ni), s.conormal.assign(ni), s.activation_offset.assign(ni);
  for (auto* rows : {&s.cohesive_energy, &s.cohesive_dissipation, &s.interface_activation_loss, &s.penalty_energy})
    rows->assign(ni);
  for (LocalId le = 0; le < no; ++le)
    for (int b = 0; b < 3; ++b) {
      double L[3][3];
      disc::initial_rotation(s.t.at(le, b), L);
      store_matrix(L, s.rotation.at(le, b));
    }
}

/// Initial velocity iv at position node A of owned element le: translation, spin about the centre, and the speed
/// along the reference normal (exact at vertices; at a mid-side node the normalized mean of its edge's vertex
/// directors, the same in every DG copy).
Vec3 initial_velocity(const InitialVelocity& iv, const ShellModel& model, const ShellState& s, LocalId le, int A) {
  Vec3 vel = iv.velocity;
  const double* X = model.X.at(le, A);
  const double r[3] = {X[0] - iv.center[0], X[1] - iv.center[1], X[2] - iv.center[2]};
  double spin[3];
  disc::cross3(iv.angular_velocity.data(), r, spin);
  for (int c = 0; c < 3; ++c) vel[c] += spin[c];
  if (iv.normal_velocity != 0) {
    double n[3];
    if (A < 3) {
      disc::copy3(s.t.at(le, A), n);
    } else {
      disc::add3(s.t.at(le, disc::edge_node(A - 3, 0)), s.t.at(le, disc::edge_node(A - 3, 1)), n);
      disc::normalize3(n);
    }
    for (int c = 0; c < 3; ++c) vel[c] += iv.normal_velocity * n[c];
  }
  return vel;
}

}  // namespace

void set_initial_state(const std::vector<InitialVelocity>& velocities, const MeshSets& sets, const ShellModel& model,
                       Constraints& constraints, ShellState& s) {
  const auto& dm = model.dm;
  size_state(model, s);
  std::vector<std::vector<char>> members;
  for (const auto& iv : velocities) {
    const std::string what = "initial condition '" + iv.name + "'";
    members.push_back(sets.nodes_of_elements(what, iv.elements));
    sets.require_some(what, iv.elements, members.back());
  }
  for (std::size_t k = 0; k < velocities.size(); ++k)
    for (LocalId le = 0; le < model.owned; ++le)
      for (int A = 0; A < 6; ++A) {
        const LocalId i = le * position_nodes + A;
        if (!members[k][dm.mesh_node(le, A)] || constraints.held(i) || constraints.prescribing(i) >= 0) continue;
        Vec3 vel = initial_velocity(velocities[k], model, s, le, A);
        constraints.position_planes().remove_normal_components(i, vel.data());
        disc::copy3(vel.data(), s.v.at(le, A));
      }
  constraints.capture_rotation_reference(s);
  // Director rates of a rigid spin: t-dot = omega x t, material components T-dot = Lambda-bar^T t-dot.
  for (std::size_t k = 0; k < velocities.size(); ++k) {
    const auto& w = velocities[k].angular_velocity;
    if (w == Vec3{0, 0, 0}) continue;
    for (LocalId le = 0; le < model.owned; ++le)
      for (int b = 0; b < 3; ++b) {
        if (!members[k][dm.mesh_node(le, b)] || constraints.director_held(le * director_nodes + b)) continue;
        double td[3], L[3][3], T[2];
        disc::cross3(w.data(), s.t.at(le, b), td);
        load_matrix(s.rotation.at(le, b), L);
        disc::lambda_bar_transpose_times(L, td, T);
        s.director_rate.at(le, b)[0] += T[0], s.director_rate.at(le, b)[1] += T[1];
      }
  }
  // Prescribed motions at t = 0.
  for (LocalId i = 0; i < model.owned * position_nodes; ++i)
    if (constraints.prescribing(i) >= 0) {
      const Vec3 pv = constraints.prescribed_velocity(constraints.prescribing(i), 0.0);
      for (int c = 0; c < 3; ++c)
        if (constraints.prescribed(i, c)) s.v.point(i)[c] = pv[c];
    }
  constraints.apply_rotations(0.0, s);
}

}  // namespace shellfrac::solver
