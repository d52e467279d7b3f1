#include "shellfrac/solver/step/constraints.hpp"

#include <algorithm>
#include <cmath>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

double CosineRamp::value(double t, double amplitude) const {
  return (duration > 0 && t < duration) ? 0.5 * amplitude * (1 - std::cos(M_PI * t / duration)) : amplitude;
}
double CosineRamp::integral(double t) const {
  return (duration > 0 && t < duration) ? 0.5 * t - duration / (2 * M_PI) * std::sin(M_PI * t / duration)
                                        : t - 0.5 * duration;
}
double CosineRamp::rate(double t, double amplitude) const {
  return (duration > 0 && t < duration) ? 0.5 * amplitude * M_PI / duration * std::sin(M_PI * t / duration) : 0.0;
}

void PlaneLists::assign(std::vector<std::vector<Plane>> lists) {
  offset_.assign(1, 0), planes_.clear();
  for (auto& l : lists) {
    std::vector<Plane> basis;
    for (const Plane& p : l) {
      Vec3 n = p.normal;
      for (const Plane& q : basis) {
        const double c = n[0] * q.normal[0] + n[1] * q.normal[1] + n[2] * q.normal[2];
        for (int k = 0; k < 3; ++k) n[k] -= c * q.normal[k];
      }
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (len < 1e-12) continue;  // in the span of the earlier planes: no new constraint
      if (!basis.empty())
        for (double& c : n) c /= len;
      basis.push_back({basis.empty() ? p.normal : n, p.condition});
    }
    planes_.insert(planes_.end(), basis.begin(), basis.end());
    offset_.push_back(static_cast<int>(planes_.size()));
  }
}

void DirectorConstraintLists::assign(const std::vector<std::vector<DirectorConstraint>>& lists) {
  offset_.assign(1, 0), constraints_.clear();
  for (const auto& l : lists) {
    constraints_.insert(constraints_.end(), l.begin(), l.end());
    offset_.push_back(static_cast<int>(constraints_.size()));
  }
}

namespace {
/// Two unit vectors spanning the plane normal to the unit vector n.
void in_plane_basis(const Vec3& n, Vec3& e1, Vec3& e2) {
  int k = 0;  // the coordinate axis least aligned with n
  for (int c = 1; c < 3; ++c)
    if (std::abs(n[c]) < std::abs(n[k])) k = c;
  double a[3] = {0, 0, 0}, u[3], w[3];
  a[k] = 1;
  disc::cross3(n.data(), a, u);
  disc::normalize3(u);
  disc::cross3(n.data(), u, w);
  e1 = {u[0], u[1], u[2]}, e2 = {w[0], w[1], w[2]};
}
}  // namespace

Constraints::Constraints(const std::vector<BoundaryCondition>& conditions, const MeshSets& sets,
                         const decomposition::DistributedMesh& dm, const std::string& deck_file)
    : dm_(dm), conditions_(conditions) {
  const LocalId no = dm.num_owned();
  SHELLFRAC_INPUT_REQUIRE(conditions_.size() <= 32, deck_file << ": at most 32 boundary conditions");
  held_by_.assign(no * position_nodes, -1), prescribing_.assign(no * position_nodes, -1), director_held_by_.assign(no * director_nodes, -1);
  acts_on_.assign(no * position_nodes, 0);
  std::vector<int> rotating(no * director_nodes, -1);
  std::vector<std::vector<Plane>> planes_x(no * position_nodes);
  std::vector<std::vector<DirectorConstraint>> planes_t(no * director_nodes);
  using T = BoundaryCondition::Type;
  for (std::size_t ib = 0; ib < conditions_.size(); ++ib) {
    const auto& bc = conditions_[ib];
    const int b = static_cast<int>(ib);
    ramps_.push_back({bc.ramp_time});
    const std::string what = "boundary condition '" + bc.name + "'";
    const auto member = sets.node_set(what, bc.node_set, true);
    const auto in_elements = sets.elements(what + " (Elements)", bc.elements);
    {
      auto acted_on = sets.nodes_of_elements(what, bc.elements);
      for (std::size_t n = 0; n < acted_on.size(); ++n) acted_on[n] = acted_on[n] && member[n];
      sets.require_some(what, bc.elements == "all" ? bc.node_set : bc.node_set + "' within '" + bc.elements, acted_on);
    }
    for (LocalId le = 0; le < no; ++le)
      for (int A = 0; A < 6; ++A) {
        if (!member[dm.mesh_node(le, A)] || !in_elements[dm.element_gid(le)]) continue;
        const LocalId i = le * position_nodes + A, j = le * director_nodes + A;  // j: the director node, for vertices (A < 3)
        acts_on_[i] |= 1u << ib;
        const bool holds_position = bc.type == T::Clamped || bc.type == T::SimplySupported;
        if (holds_position && held_by_[i] < 0) held_by_[i] = b;
        if (bc.type == T::PrescribedVelocity) prescribing_[i] = b;
        if (bc.type == T::Symmetry) planes_x[i].push_back({bc.normal, b});
        if (bc.type == T::RigidDiaphragm) {
          Vec3 e1, e2;
          in_plane_basis(bc.normal, e1, e2);
          planes_x[i].push_back({e1, b}), planes_x[i].push_back({e2, b});
        }
        if (A >= 3) continue;
        const bool holds_director = bc.type == T::Clamped || bc.type == T::PrescribedVelocity;
        if (holds_director && director_held_by_[j] < 0) director_held_by_[j] = b;
        if (bc.type == T::Symmetry || bc.type == T::RigidDiaphragm)
          planes_t[j].push_back({bc.normal, bc.type == T::RigidDiaphragm, b});
        if (bc.type == T::PrescribedRotation) rotating[j] = b;
      }
  }
  // A held node is held whatever else acts on it; a prescribed one ignores symmetry planes; a director held by
  // another condition is not rotated.
  prescribed_components_.assign(no * position_nodes, 0), motion_.assign(no * position_nodes, Motion::free);
  for (LocalId i = 0; i < no * position_nodes; ++i) {
    if (held_by_[i] >= 0) prescribing_[i] = -1;
    if (held_by_[i] >= 0 || prescribing_[i] >= 0) planes_x[i].clear();
    if (prescribing_[i] >= 0)
      for (int c = 0; c < 3; ++c) prescribed_components_[i] |= conditions_[prescribing_[i]].components[c] << c;
    motion_[i] = held_by_[i] >= 0        ? Motion::held
                 : prescribing_[i] >= 0  ? Motion::prescribed
                 : !planes_x[i].empty()  ? Motion::on_planes
                                         : Motion::free;
  }
  for (LocalId j = 0; j < no * director_nodes; ++j) {
    if (director_held_by_[j] < 0 && rotating[j] >= 0) {
      director_held_by_[j] = rotating[j];
      rotated_.push_back(RotatedNode{j / 3, int(j % 3), rotating[j], {}, {}, {}, {}, {}});
    }
    if (director_held_by_[j] >= 0) planes_t[j].clear();
  }
  position_planes_.assign(planes_x);
  director_constraints_.assign(planes_t);
  refuse_overridden_programs(deck_file);
}

// A Prescribed Velocity or Rotation whose every node is taken by another condition (composition rules of
// constraints.hpp, docs/theory.md §10.1-10.2) would be ignored without a word: refuse it, naming both.
void Constraints::refuse_overridden_programs(const std::string& deck_file) const {
  using T = BoundaryCondition::Type;
  const MPI_Comm comm = dm_.comm();
  for (std::size_t ib = 0; ib < conditions_.size(); ++ib) {
    const auto& bc = conditions_[ib];
    const int b = static_cast<int>(ib);
    const bool velocity = bc.type == T::PrescribedVelocity;
    if (!velocity && bc.type != T::PrescribedRotation) continue;
    std::int64_t acting = 0, effective = 0;
    int taker = static_cast<int>(conditions_.size());
    for (LocalId le = 0; le < dm_.num_owned(); ++le)
      for (int A = 0; A < (velocity ? 6 : 3); ++A) {
        const LocalId i = le * position_nodes + A;
        if (!(acts_on_[i] & (1u << ib))) continue;
        const int by = velocity ? (held_by_[i] >= 0 ? held_by_[i] : prescribing_[i]) : director_held_by_[le * director_nodes + A];
        ++acting;
        if (by == b)
          ++effective;
        else
          taker = std::min(taker, by);
      }
    if (parallel::sum(acting, comm) == 0 || parallel::sum(effective, comm) > 0) continue;
    const int t = static_cast<int>(-parallel::max(-double(taker), comm));
    throw InputError(
        deck_file + ": boundary condition '" + bc.name + "' (" +
        (velocity ? "Prescribed Velocity" : "Prescribed Rotation") + ") has no effect: every " +
        (velocity ? "node" : "director") + " of its Node Set '" + bc.node_set + "' is taken by boundary condition '" +
        conditions_[t].name +
        "', which takes precedence (docs/theory.md §10.1); remove one of them or give them different node sets");
  }
}

Vec3 Constraints::prescribed_velocity(int bc, double t) const {
  const double r = ramps_[bc].value(t);
  const auto& V = conditions_[bc].velocity;
  return {r * V[0], r * V[1], r * V[2]};
}
Vec3 Constraints::prescribed_displacement(int bc, double t) const {
  const double u = ramps_[bc].integral(t);
  const auto& V = conditions_[bc].velocity;
  return {u * V[0], u * V[1], u * V[2]};
}
Vec3 Constraints::prescribed_acceleration(int bc, double t) const {
  const double r = ramps_[bc].rate(t);
  const auto& V = conditions_[bc].velocity;
  return {r * V[0], r * V[1], r * V[2]};
}

void Constraints::capture_rotation_reference(const ShellState& s) {
  for (auto& rn : rotated_) {
    disc::copy3(s.t.at(rn.le, rn.b), rn.t0);
    load_matrix(s.rotation.at(rn.le, rn.b), rn.L0);
  }
}

void Constraints::apply_rotations(double time, ShellState& s) const {
  for (const auto& rn : rotated_) {
    const auto& bc = conditions_[rn.bc];
    const double theta = ramps_[rn.bc].value(time, bc.angle), rate = ramps_[rn.bc].rate(time, bc.angle);
    double R[3][3], L[3][3], w[3], td[3];
    disc::axis_angle_rotation(bc.axis.data(), theta, R);
    double* t = s.t.at(rn.le, rn.b);
    disc::mat_vec(R, rn.t0, t);
    disc::mat_mat(R, rn.L0, L);
    store_matrix(L, s.rotation.at(rn.le, rn.b));
    for (int c = 0; c < 3; ++c) w[c] = rate * bc.axis[c];
    disc::cross3(w, t, td);
    disc::lambda_bar_transpose_times(L, td, s.director_rate.at(rn.le, rn.b));
  }
}

void Constraints::begin_step(const ShellState& s, const ShellModel& model) {
  for (auto& rn : rotated_) {
    disc::copy3(s.t.at(rn.le, rn.b), rn.t_prev);
    disc::copy3(s.director_force.at(rn.le, rn.b), rn.g_prev);
    rn.kinetic_prev = model.rotary_kinetic(s, rn.le, rn.b);
  }
}

void Constraints::add_rotation_work(ShellState& s, const ShellModel& model) const {
  for (const auto& rn : rotated_) {
    const double* g1 = s.director_force.at(rn.le, rn.b);
    const double* t1 = s.t.at(rn.le, rn.b);
    double w = model.rotary_kinetic(s, rn.le, rn.b) - rn.kinetic_prev;
    for (int c = 0; c < 3; ++c) w += 0.5 * (rn.g_prev[c] + g1[c]) * (t1[c] - rn.t_prev[c]);
    *s.reaction_work.at(rn.le) += w;
  }
}

void Constraints::reaction_contributions(const ShellState& s, std::size_t bc, Contribution& force,
                                         Contribution& couple) const {
  const int b = static_cast<int>(bc);
  force = {}, couple = {};
  for (LocalId le = 0; le < dm_.num_owned(); ++le)
    for (int A = 0; A < 6; ++A) {
      const LocalId i = le * position_nodes + A;
      if (!(acts_on_[i] & (1u << bc))) continue;
      const bool holder = held_by_[i] == b || prescribing_[i] == b;  // the node's reaction is this condition's
      const double* R = s.reaction.point(i);
      const double* f = s.internal_force.point(i);
      const double* fe = s.external_force.point(i);
      for (int c = 0; c < 3; ++c) {
        double r = holder ? R[c] : 0.0;
        // A symmetry plane's reaction is the normal force that keeps the node on the plane.
        for (const Plane* p = position_planes_.begin(i); p != position_planes_.end(i); ++p) {
          if (p->condition != b) continue;
          const double* n = p->normal.data();
          r += n[c] * ((f[0] - fe[0]) * n[0] + (f[1] - fe[1]) * n[1] + (f[2] - fe[2]) * n[2]);
        }
        force.values[c].push_back(r);
      }
    }
  // Support couple on the director nodes the condition holds: t x g per node (g = dU/dt is balanced by the
  // support; the virtual work g . (dtheta x t) = dtheta . (t x g)).
  for (LocalId le = 0; le < dm_.num_owned(); ++le)
    for (int a = 0; a < 3; ++a) {
      if (director_held_by_[le * director_nodes + a] != b) continue;
      double m[3];
      disc::cross3(s.t.at(le, a), s.director_force.at(le, a), m);
      for (int c = 0; c < 3; ++c) couple.values[c].push_back(m[c]);
    }
}

}  // namespace shellfrac::solver
