#include "shellfrac/solver/energy_accounts.hpp"

#include <algorithm>

#include "shellfrac/core/parallel.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/constraints.hpp"
#include "shellfrac/solver/fracture.hpp"
#include "shellfrac/solver/shell_model.hpp"

namespace shellfrac::solver {

namespace {

/// The first `n` values of a row array (the owned rows of a one-value-per-row field).
std::vector<double> owned_values(const Scalars& rows, LocalId n) {
  return std::vector<double>(rows.vector().begin(), rows.vector().begin() + n);
}

/// Angular momentum of owned element le about the origin: sum m x × v + sum I t × t-dot (t-dot = Lambda-bar T-dot).
void element_angular_momentum(const ShellState& s, const ShellModel& model, LocalId le, double out[3]) {
  for (int A = 0; A < 6; ++A) {
    double h[3];
    disc::cross3(s.x.at(le, A), s.v.at(le, A), h);
    for (int c = 0; c < 3; ++c) out[c] += *model.mass.at(le, A) * h[c];
  }
  for (int b = 0; b < 3; ++b) {
    double L[3][3], td[3], h[3];
    load_matrix(s.rotation.at(le, b), L);
    disc::lambda_bar_times(L, s.director_rate.at(le, b), td);
    disc::cross3(s.t.at(le, b), td, h);
    for (int c = 0; c < 3; ++c) out[c] += *model.inertia.at(le, b) * h[c];
  }
}

/// Kinetic energy of owned element le: translational and rotary.
double element_kinetic(const ShellState& s, const ShellModel& model, LocalId le) {
  double k = 0;
  for (int A = 0; A < 6; ++A)
    for (int c = 0; c < 3; ++c) k += 0.5 * *model.mass.at(le, A) * s.v.at(le, A)[c] * s.v.at(le, A)[c];
  for (int b = 0; b < 3; ++b)
    for (int c = 0; c < 2; ++c)
      k += 0.5 * *model.inertia.at(le, b) * s.director_rate.at(le, b)[c] * s.director_rate.at(le, b)[c];
  return k;
}

/// Fracture accounts of the owned interfaces, summed in interface id order.
void fracture_accounts(const ShellState& s, const ShellModel& model, const Fracture& fracture,
                       const std::vector<GlobalId>& egid, const std::vector<GlobalId>& igid, StepRecord& r) {
  const auto& ifs = model.dm.interfaces();
  const MPI_Comm comm = model.dm.comm();
  std::vector<double> uc, dc, ai;
  std::int64_t ncoh = 0, nsep = 0;
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned) {
      uc.push_back(*s.cohesive_energy.at(i)), dc.push_back(*s.cohesive_dissipation.at(i));
      ai.push_back(*s.interface_activation_loss.at(i));
      ncoh += s.mode[i] != intact, nsep += s.mode[i] == separated;
    }
  r.cohesive_energy = ordered_sum(igid, uc, comm);
  r.cohesive_dissipation = ordered_sum(igid, dc, comm);
  r.activation_loss =
      ordered_sum(igid, ai, comm) + ordered_sum(egid, owned_values(s.element_activation_loss, model.owned), comm);
  r.cohesive_edges = parallel::sum(ncoh, comm);
  r.separated_edges = parallel::sum(nsep, comm);
  r.fragments = fracture.fragments(s);
}

}  // namespace

double ordered_sum(const std::vector<GlobalId>& ids, const std::vector<double>& vals, MPI_Comm comm) {
  const auto all_ids = parallel::all_gather(ids, comm);
  const auto all_vals = parallel::all_gather(vals, comm);
  std::vector<std::size_t> order(all_ids.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return all_ids[p] < all_ids[q]; });
  double sum = 0;
  for (std::size_t i : order) sum += all_vals[i];
  return sum;
}

StepRecord step_record(const ShellState& s, const ShellModel& model, const Fracture& fracture, double dt) {
  const auto& dm = model.dm;
  const MPI_Comm comm = dm.comm();
  const LocalId no = model.owned;
  std::vector<GlobalId> egid(no);
  std::vector<double> ek(no);
  std::vector<std::vector<double>> lm(3, std::vector<double>(no, 0.0));
  for (LocalId le = 0; le < no; ++le) {
    egid[le] = dm.element_gid(le);
    ek[le] = element_kinetic(s, model, le);
  }
  std::vector<GlobalId> igid;
  std::vector<double> ep;
  const auto& ifs = dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned) igid.push_back(ifs[i].gid), ep.push_back(*s.penalty_energy.at(i));
  StepRecord r;
  r.step = s.step, r.time = s.time, r.dt = dt;
  r.kinetic = ordered_sum(egid, ek, comm);
  r.strain = ordered_sum(egid, owned_values(s.strain_energy, no), comm);
  r.penalty = ordered_sum(igid, ep, comm);
  r.external_work = ordered_sum(egid, owned_values(s.external_work, no), comm);
  r.reaction_work = ordered_sum(egid, owned_values(s.reaction_work, no), comm);
  r.damping = ordered_sum(egid, owned_values(s.damping_dissipation, no), comm);
  r.plastic_work = ordered_sum(egid, owned_values(s.plastic_work, no), comm);
  if (fracture.enabled()) fracture_accounts(s, model, fracture, egid, igid, r);
  for (LocalId le = 0; le < no; ++le) {
    double h[3] = {0, 0, 0};
    element_angular_momentum(s, model, le, h);
    for (int c = 0; c < 3; ++c) lm[c][le] = h[c];
  }
  for (int c = 0; c < 3; ++c) r.angular_momentum[c] = ordered_sum(egid, lm[c], comm);
  return r;
}

double energy_balance_error(const StepRecord& r, double e0) {
  return r.kinetic + r.strain + r.penalty + r.damping + r.plastic_work + r.cohesive_energy + r.cohesive_dissipation +
         r.activation_loss - e0 - r.external_work - r.reaction_work;
}

std::vector<double> probe_values(const ShellState& s, const ShellModel& model,
                                 const std::vector<std::vector<char>>& members) {
  const auto& dm = model.dm;
  std::vector<double> out;
  for (const auto& member : members) {
    std::vector<GlobalId> ids;
    std::vector<std::vector<double>> vals(6);
    for (LocalId le = 0; le < model.owned; ++le)
      for (int A = 0; A < 6; ++A) {
        if (!member[dm.mesh_node(le, A)]) continue;
        ids.push_back(dm.dg_node_gid(le, A));
        for (int c = 0; c < 3; ++c) {
          vals[c].push_back(s.x.at(le, A)[c] - model.X.at(le, A)[c]);
          vals[3 + c].push_back(s.v.at(le, A)[c]);
        }
      }
    const double count = double(parallel::sum(static_cast<std::int64_t>(ids.size()), dm.comm()));
    for (int c = 0; c < 6; ++c) out.push_back(count > 0 ? ordered_sum(ids, vals[c], dm.comm()) / count : 0.0);
  }
  return out;
}

std::vector<double> reaction_values(const ShellState& s, const ShellModel& model, const Constraints& constraints) {
  std::vector<double> out;
  Constraints::Contribution force, couple;
  for (std::size_t bc = 0; bc < constraints.size(); ++bc) {
    constraints.reaction_contributions(s, bc, force, couple);
    for (int c = 0; c < 3; ++c) out.push_back(ordered_sum(force.ids, force.values[c], model.dm.comm()));
    for (int c = 0; c < 3; ++c) out.push_back(ordered_sum(couple.ids, couple.values[c], model.dm.comm()));
  }
  return out;
}

HistoryRow history_row(const StepRecord& r, double e0, const std::vector<std::string>& probe_names,
                       const std::vector<double>& probes, const std::vector<std::string>& condition_names,
                       const std::vector<double>& reactions) {
  HistoryRow row = {{"step", double(r.step)},           {"time", r.time},
                    {"dt", r.dt},                       {"kinetic_energy", r.kinetic},
                    {"strain_energy", r.strain},        {"penalty_energy", r.penalty},
                    {"external_work", r.external_work}, {"energy_balance_error", energy_balance_error(r, e0)}};
  std::size_t k = 0;
  for (const auto& p : probe_names)
    for (const char* q : {"_displ_x", "_displ_y", "_displ_z", "_vel_x", "_vel_y", "_vel_z"}) row.push_back({p + q, probes[k++]});
  row.insert(row.end(), {{"reaction_work", r.reaction_work},
                         {"damping_dissipation", r.damping},
                         {"plastic_dissipation", r.plastic_work},
                         {"cohesive_energy", r.cohesive_energy},
                         {"cohesive_dissipation", r.cohesive_dissipation},
                         {"activation_loss", r.activation_loss},
                         {"num_cohesive_edges", double(r.cohesive_edges)},
                         {"num_separated_edges", double(r.separated_edges)},
                         {"num_fragments", double(r.fragments)}});
  k = 0;
  for (const auto& bc : condition_names)
    for (const char* q : {"_reaction_x", "_reaction_y", "_reaction_z", "_moment_x", "_moment_y", "_moment_z"})
      row.push_back({bc + q, reactions[k++]});
  for (int c = 0; c < 3; ++c) row.push_back({std::string("angular_momentum_") + char('x' + c), r.angular_momentum[c]});
  return row;
}

}  // namespace shellfrac::solver
