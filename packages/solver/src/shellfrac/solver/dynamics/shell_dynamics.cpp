#include "shellfrac/solver/dynamics/shell_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/contact/rigid_bodies.hpp"
#include "shellfrac/solver/contact/rigid_walls.hpp"
#include "shellfrac/solver/contact/shell_contact.hpp"
#include "shellfrac/solver/dynamics/initial_conditions.hpp"
#include "shellfrac/solver/fracture/fracture.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/element_fields.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/element_strains.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/restart/state_checkpoint.hpp"
#include "shellfrac/solver/step/central_difference.hpp"
#include "shellfrac/solver/step/constraints.hpp"
#include "shellfrac/solver/step/force_assembly.hpp"
#include "shellfrac/solver/step/loads.hpp"

namespace shellfrac::solver {

namespace {

/// The time step: the deck's fixed step (refused above the stable estimate unless forced), or the safety factor
/// times the stable estimate.
double choose_time_step(const TimeParams& tp, double stable_dt, const std::string& file) {
  if (tp.time_step <= 0) return tp.safety_factor * stable_dt;
  SHELLFRAC_INPUT_REQUIRE(tp.force_time_step || tp.time_step <= stable_dt,
                          file << ": 'Time Integration->Time Step' = " << tp.time_step << " exceeds the stable estimate "
                               << stable_dt << " (docs/theory.md §8); lower it, or set 'Force Time Step' to true to "
                               << "run anyway");
  return tp.time_step;
}

/// Static relaxation settings: active once every ramp and load table has reached its end (never for an
/// Exponential load).
CentralDifference::Relaxation relaxation_settings(const Deck& deck) {
  CentralDifference::Relaxation r;
  r.enabled = deck.time.static_relaxation, r.tolerance = deck.time.relaxation_tolerance;
  for (const auto& bc : deck.boundary_conditions) r.start = std::max(r.start, bc.ramp_time);
  for (const auto& load : deck.loads) {
    if (load.function == Load::Function::Table) r.start = std::max(r.start, load.times.back());
    if (load.function == Load::Function::Exponential) r.start = std::numeric_limits<double>::infinity();
  }
  return r;
}

std::vector<std::string> block_names(const mesh::SerialMesh& mesh) {
  std::vector<std::string> names;
  for (const auto& b : mesh.blocks) names.push_back(b.name);
  return names;
}

/// von Mises norm of a resultant triple [X11, X22, X12]: sqrt(X11^2 - X11 X22 + X22^2 + 3 X12^2).
double vm_norm(const double X[3]) {
  return std::sqrt(std::max(0.0, X[0] * X[0] - X[0] * X[1] + X[1] * X[1] + 3 * X[2] * X[2]));
}

/// Calls f(w, N, Q, M, alpha) at each area point of owned element le: the resultants of the current strains (the
/// element kernel's kinematics with the current lifted edges) and the committed plastic state, w the point's
/// share of the element's area and alpha its equivalent plastic strain (0 for an elastic block).
template <class F>
void for_each_point_resultants(const ShellModel& model, const ShellState& state, LocalId le, F&& f) {
  constexpr int nq = disc::num_area_points;
  const double zero[3] = {0, 0, 0};
  const double area = model.element_refs[le].area;
  PointStrains p[nq];
  element_strains(model, state, le, p);
  for (int q = 0; q < nq; ++q) {
    const materials::PlasticState* st = model.is_plastic(le) ? &state.plastic[le * nq + q] : nullptr;
    double N[3], Q[2], M[3];
    materials::elastic_resultants(model.elastic(le), p[q].eps, p[q].gam, p[q].rho, st ? st->eps_p : zero,
                                  st ? st->gam_p : zero, st ? st->rho_p : zero, N, Q, M);
    f(p[q].weight / area, N, Q, M, st ? st->alpha : 0.0);
  }
}

}  // namespace

struct ShellDynamics::Impl {
  Impl(const mesh::SerialMesh& mesh, const decomposition::DistributedMesh& dm, const Deck& deck)
      : Impl(MeshSets(mesh, deck.file, deck.regions), mesh, dm, deck) {}
  // The sets are resolved on the conforming mesh during the construction only: the dynamics keep no reference to
  // it (the run releases it after the set-up).
  Impl(const MeshSets& sets, const mesh::SerialMesh& mesh, const decomposition::DistributedMesh& dm, const Deck& deck)
      : file(deck.file),
        model(dm,
              {deck.file, deck.mesh.file.empty() ? deck.file : deck.mesh.file, deck.discretization, deck.time,
               mesh.element_ids},
              block_sections(deck.blocks, deck.materials, block_names(mesh))),
        dt(choose_time_step(deck.time, model.stable_dt, deck.file)),
        fracture(deck.fracture, sets, model),
        constraints(deck.boundary_conditions, sets, dm, deck.file),
        loads(deck.loads, sets, mesh, model),
        walls(deck.contact, model, dt, deck.file),
        bodies(deck.contact, model, dt, deck.file),
        shells(deck.contact, model, dt, block_names(mesh), deck.file),
        assembly(model, fracture.enabled(), times),
        integrator(model, constraints, loads, walls, bodies, shells, assembly, fracture, times, deck.time.mass_damping,
                   relaxation_settings(deck)),
        friction((deck.contact.friction.enabled() && (!walls.empty() || !bodies.empty())) ||
                 (shells.enabled() && deck.contact.shells.friction.enabled())) {
    set_initial_state(deck.initial_velocities, sets, model, constraints, state);
    bodies.initial_state(state);
    integrator.start(state);
  }

  std::string file;
  PhaseTimes times;
  ShellModel model;
  double dt;
  Fracture fracture;
  Constraints constraints;
  Loads loads;
  RigidWalls walls;
  RigidBodies bodies;
  ShellContact shells;
  ForceAssembly assembly;
  CentralDifference integrator;
  bool friction;  ///< whether any contact has friction (the history's friction_dissipation column)
  ShellState state;
};

ShellDynamics::ShellDynamics(const mesh::SerialMesh& mesh, const decomposition::DistributedMesh& dm, const Deck& deck)
    : impl_(std::make_unique<Impl>(mesh, dm, deck)) {}
ShellDynamics::~ShellDynamics() = default;
double ShellDynamics::stable_time_step() const { return impl_->model.stable_dt; }
double ShellDynamics::time_step() const { return impl_->dt; }
double ShellDynamics::time() const { return impl_->state.time; }
long ShellDynamics::step_count() const { return impl_->state.step; }
void ShellDynamics::step() { impl_->integrator.step(impl_->state, impl_->dt, impl_->state.time + impl_->dt); }
void ShellDynamics::step_to(double t1) {
  const double dt = t1 - impl_->state.time;
  SHELLFRAC_REQUIRE(dt > 0 && dt <= impl_->dt * (1 + 1e-6), "step_to(" << t1 << ") from t = " << impl_->state.time
                                                                       << " with the time step " << impl_->dt);
  impl_->integrator.step(impl_->state, dt, t1);
}
const PhaseTimes& ShellDynamics::phase_times() const { return impl_->times; }
bool ShellDynamics::fracture() const { return impl_->fracture.enabled(); }
bool ShellDynamics::plasticity() const { return impl_->model.any_plastic; }
double ShellDynamics::peak_plastic_strain() const {
  double peak = 0;
  for (const materials::PlasticState& p : impl_->state.plastic) peak = std::max(peak, p.alpha);
  return parallel::max(peak, impl_->model.dm.comm());
}
const materials::StrengthSummary& ShellDynamics::strengths() const { return impl_->fracture.strengths(); }
bool ShellDynamics::relaxed() const { return impl_->integrator.relaxed(); }
double ShellDynamics::relaxation_residual() const { return impl_->integrator.relaxation_residual(); }
bool ShellDynamics::relaxation_stalled() const { return impl_->integrator.relaxation_stalled(); }
bool ShellDynamics::relaxed_at_floor() const { return impl_->integrator.relaxed_at_floor(); }
double ShellDynamics::best_relaxation_residual() const { return impl_->state.relaxation.best_residual; }
double ShellDynamics::relaxation_displacement_change() const {
  return impl_->integrator.relaxation_displacement_change();
}
const ShellState& ShellDynamics::state() const { return impl_->state; }
const ShellModel& ShellDynamics::model() const { return impl_->model; }

StepRecord ShellDynamics::record() const {
  return step_record(impl_->state, impl_->model, impl_->fracture, impl_->dt);
}

std::vector<double> ShellDynamics::probes(const std::vector<std::vector<char>>& members) const {
  return probe_values(impl_->state, impl_->model, members);
}

std::vector<double> ShellDynamics::node_histories(const std::vector<GlobalId>& nodes) const {
  return node_history_values(impl_->state, impl_->model, nodes);
}

std::vector<double> ShellDynamics::block_energies(std::size_t num_blocks) const {
  return block_energy_values(impl_->state, impl_->model, num_blocks);
}

std::vector<double> ShellDynamics::element_histories(const std::vector<GlobalId>& elements) const {
  const Impl& s = *impl_;
  const std::size_t width = element_history_suffixes().size();
  std::vector<ExactSum> sum(width * elements.size());  // the owner's values; the other ranks add nothing
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const LocalId le = s.model.dm.local_id(elements[k]);
    if (le < 0 || le >= s.model.owned) continue;
    double mean[10] = {};
    for_each_point_resultants(s.model, s.state, le, [&](double w, const double* N, const double* Q, const double* M,
                                                        double alpha) {
      for (int c = 0; c < 3; ++c) mean[c] += w * N[c], mean[3 + c] += w * M[c];
      for (int c = 0; c < 2; ++c) mean[6 + c] += w * Q[c];
      mean[8] += w * alpha;
    });
    mean[9] = *s.state.strain_energy.at(le);
    for (std::size_t c = 0; c < width; ++c) sum[width * k + c].add(mean[c]);
  }
  ExactSum::allreduce(sum, s.model.dm.comm());
  std::vector<double> out;
  for (const auto& x : sum) out.push_back(x.value());
  return out;
}

std::vector<double> ShellDynamics::reactions() const {
  return reaction_values(impl_->state, impl_->model, impl_->constraints);
}

std::vector<double> ShellDynamics::wall_forces() const {
  return impl_->walls.normal_forces(impl_->state.time, impl_->state);
}

std::vector<std::string> ShellDynamics::contact_columns() const {
  std::vector<std::string> out;
  for (const auto& w : impl_->walls.names()) out.push_back(w + "_wall_force");
  for (auto& c : impl_->bodies.history_columns()) out.push_back(std::move(c));
  for (auto& c : impl_->shells.history_columns()) out.push_back(std::move(c));
  if (impl_->friction) out.push_back("friction_dissipation");
  return out;
}

std::vector<double> ShellDynamics::contact_values() const {
  std::vector<double> out = wall_forces();
  for (double v : impl_->bodies.history_values(impl_->state)) out.push_back(v);
  for (double v : impl_->shells.history_values()) out.push_back(v);
  if (impl_->friction) out.push_back(friction_dissipation());
  return out;
}

double ShellDynamics::friction_dissipation() const {
  ExactSum sum;
  for (LocalId le = 0; le < impl_->model.owned; ++le) sum.add(*impl_->state.friction_dissipation.at(le));
  sum.allreduce(impl_->model.dm.comm());
  return sum.value();
}

double ShellDynamics::bytes_per_element() const {
  const Impl& s = *impl_;
  const double bytes = s.state.bytes() + s.model.bytes() + s.assembly.bytes();
  return s.model.owned > 0 ? bytes / s.model.owned : 0.0;
}

io::CheckpointData ShellDynamics::checkpoint() const {
  auto data = state_checkpoint(impl_->state, impl_->model.dm, impl_->model.any_plastic);
  data.scalars["dt"] = impl_->dt;
  return data;
}

void ShellDynamics::restore(const std::string& file, const std::function<void(const io::CheckpointData&)>& check) {
  Impl& s = *impl_;
  // The time step stays the deck's (the same deck gives the same step, hence a bitwise continuation; a deck with
  // a smaller Time Step or Safety Factor continues a blown-up run from its last good state).
  StateRestore restore(file, s.model.dm, s.model.any_plastic, s.state);
  io::read_checkpoint(
      file, s.model.dm.comm(), [&](const std::string& table) { return restore.rows()(table); },
      [&](const io::CheckpointData& header) { check(header), restore.header(header); },
      [&](const std::string& name, const io::CheckpointTable& rows) { restore.table(name, rows); });
  restore.finish();
  s.fracture.restore(s.state, s.model);
  s.assembly.exchange_state(s.state);
}

std::vector<std::vector<double>> ShellDynamics::fragment_table() const {
  return impl_->fracture.fragment_table(impl_->state, impl_->model);
}

std::vector<std::vector<double>> ShellDynamics::crack_events() { return impl_->fracture.crack_events(); }

// Element fields from the current state: the kinematics of the element kernel with the current lifted edges
// (after any activation of this step), and the resultants of the committed plastic state.
void ShellDynamics::element_fields(std::vector<std::vector<double>>& fields) const {
  const Impl& s = *impl_;
  const ShellModel& model = s.model;
  fields.assign(std::size_t(ElementField::count), std::vector<double>(model.owned, 0.0));
  for (LocalId le = 0; le < model.owned; ++le) {
    for_each_point_resultants(model, s.state, le, [&](double w, const double* N, const double* Q, const double* M,
                                                      double alpha) {
      fields[int(ElementField::eq_plastic_strain)][le] += w * alpha;
      fields[int(ElementField::membrane_force)][le] += w * vm_norm(N);
      fields[int(ElementField::bending_moment)][le] += w * vm_norm(M);
      fields[int(ElementField::shear_force)][le] += w * std::sqrt(Q[0] * Q[0] + Q[1] * Q[1]);
    });
    fields[int(ElementField::damage)][le] = s.fracture.damage(s.state, model, le);
    fields[int(ElementField::edge_strength)][le] = s.fracture.weakest_edge_strength(model, le);
  }
  if (s.fracture.enabled()) s.fracture.fragments(s.state);
  for (LocalId le = 0; le < model.owned; ++le)
    fields[int(ElementField::fragment_id)][le] = s.fracture.enabled() ? double(s.fracture.fragment_of(le) + 1) : 1.0;
}

void ShellDynamics::nodal_field_component(int field, int c, double* out) const {
  const ShellState& s = impl_->state;
  const ShellModel& model = impl_->model;
  SHELLFRAC_REQUIRE(field >= 0 && field < 3 && c >= 0 && c < 3, "nodal field " << field << ", component " << c);
  for (LocalId le = 0; le < model.owned; ++le)
    for (int A = 0; A < 6; ++A, ++out)
      if (field == 0) {
        *out = s.x.at(le, A)[c] - model.X.at(le, A)[c];
      } else if (field == 1) {
        *out = s.v.at(le, A)[c];
      } else {  // P1 directors: a mid-side node shows the mean of its edge's vertex directors (t_h is linear)
        *out = A < 3 ? s.t.at(le, A)[c]
                     : 0.5 * (s.t.at(le, disc::edge_node(A - 3, 0))[c] + s.t.at(le, disc::edge_node(A - 3, 1))[c]);
      }
}

}  // namespace shellfrac::solver
