#include "shellfrac/solver/step/energy_accounts.hpp"

#include <algorithm>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/materials/cohesive_law.hpp"
#include "shellfrac/solver/fracture/fracture.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/step/constraints.hpp"

namespace shellfrac::solver {

namespace {

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

}  // namespace

// One exact accumulator per quantity, reduced together with one MPI_Allreduce: O(1) communication, and the
// sums are exact, hence independent of the rank count and of the order of the contributions.
StepRecord step_record(const ShellState& s, const ShellModel& model, const Fracture& fracture, double dt) {
  enum Quantity { kinetic, strain, penalty, external, reaction, damping, plastic, cohesive_stored, cohesive_lost,
                  activation, cohesive_edges, separated_edges, momentum_x, momentum_y, momentum_z, count };
  std::vector<ExactSum> sum(count);
  const LocalId no = model.owned;
  for (LocalId le = 0; le < no; ++le) {
    sum[kinetic].add(model.element_kinetic(s, le));
    sum[strain].add(*s.strain_energy.at(le));
    sum[external].add(*s.external_work.at(le));
    sum[reaction].add(*s.reaction_work.at(le));
    sum[damping].add(*s.damping_dissipation.at(le));
    sum[plastic].add(*s.plastic_work.at(le));
    double h[3] = {0, 0, 0};
    element_angular_momentum(s, model, le, h);
    for (int c = 0; c < 3; ++c) sum[momentum_x + c].add(h[c]);
  }
  const auto& ifs = model.dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned) sum[penalty].add(*s.penalty_energy.at(i));
  if (fracture.enabled()) {
    for (LocalId le = 0; le < no; ++le) sum[activation].add(*s.element_activation_loss.at(le));
    for (std::size_t i = 0; i < ifs.size(); ++i) {
      if (!ifs[i].owned) continue;
      // The law's dissipation is reported as the work of separation plus, in activation_loss, the release of
      // the energy of its starting state (docs/theory.md §9.7).
      double released = 0;
      if (s.mode[i] != intact)
        for (int g = 0; g < 3; ++g)
          released += model.interface_refs[i].omega[g] *
                      materials::starting_energy_released(fracture.cohesive_params()[i], s.delta_max.at(i)[g]);
      sum[cohesive_stored].add(*s.cohesive_energy.at(i)), sum[cohesive_lost].add(*s.cohesive_dissipation.at(i));
      sum[cohesive_lost].add(-released), sum[activation].add(released);
      sum[activation].add(*s.interface_activation_loss.at(i));
      if (s.mode[i] != intact) sum[cohesive_edges].add(1.0);
      if (s.mode[i] == separated) sum[separated_edges].add(1.0);
    }
  }
  ExactSum::allreduce(sum, model.dm.comm());
  StepRecord r;
  r.step = s.step, r.time = s.time, r.dt = dt;
  r.kinetic = sum[kinetic].value(), r.strain = sum[strain].value(), r.penalty = sum[penalty].value();
  r.external_work = sum[external].value(), r.reaction_work = sum[reaction].value();
  r.damping = sum[damping].value(), r.plastic_work = sum[plastic].value();
  r.cohesive_energy = sum[cohesive_stored].value(), r.cohesive_dissipation = sum[cohesive_lost].value();
  r.activation_loss = sum[activation].value();
  r.cohesive_edges = static_cast<GlobalId>(sum[cohesive_edges].value());
  r.separated_edges = static_cast<GlobalId>(sum[separated_edges].value());
  if (fracture.enabled()) r.fragments = fracture.fragments(s);
  for (int c = 0; c < 3; ++c) r.angular_momentum[c] = sum[momentum_x + c].value();
  return r;
}

double energy_balance_error(const StepRecord& r, double e0) {
  return r.kinetic + r.strain + r.penalty + r.damping + r.plastic_work + r.cohesive_energy + r.cohesive_dissipation +
         r.activation_loss - e0 - r.external_work - r.reaction_work;
}

namespace {

/// Means over the DG copies of groups of mesh nodes: `groups(n, visit)` calls visit(g) for each group g that mesh
/// node n belongs to. Per group: displacement (3), velocity (3) and, if `acceleration`, acceleration (3).
template <class Groups>
std::vector<double> dg_copy_means(const ShellState& s, const ShellModel& model, std::size_t num_groups,
                                  bool acceleration, Groups&& groups) {
  const auto& dm = model.dm;
  const std::size_t width = acceleration ? 9 : 6;
  std::vector<ExactSum> sum((width + 1) * num_groups);  // per group: the quantities, then the number of copies
  for (LocalId le = 0; le < model.owned; ++le)
    for (int A = 0; A < 6; ++A)
      groups(dm.mesh_node(le, A), [&](std::size_t g) {
        ExactSum* out = &sum[(width + 1) * g];
        for (int c = 0; c < 3; ++c) {
          out[c].add(s.x.at(le, A)[c] - model.X.at(le, A)[c]);
          out[3 + c].add(s.v.at(le, A)[c]);
          if (acceleration) out[6 + c].add(s.a.at(le, A)[c]);
        }
        out[width].add(1.0);
      });
  ExactSum::allreduce(sum, dm.comm());
  std::vector<double> out;
  for (std::size_t g = 0; g < num_groups; ++g) {
    const double copies = sum[(width + 1) * g + width].value();
    for (std::size_t c = 0; c < width; ++c) out.push_back(copies > 0 ? sum[(width + 1) * g + c].value() / copies : 0.0);
  }
  return out;
}

}  // namespace

std::vector<double> probe_values(const ShellState& s, const ShellModel& model,
                                 const std::vector<std::vector<char>>& members) {
  return dg_copy_means(s, model, members.size(), false, [&](GlobalId n, const auto& visit) {
    for (std::size_t p = 0; p < members.size(); ++p)
      if (members[p][std::size_t(n)]) visit(p);
  });
}

std::vector<double> node_history_values(const ShellState& s, const ShellModel& model,
                                        const std::vector<GlobalId>& nodes) {
  std::vector<std::pair<GlobalId, std::size_t>> sorted;  // (mesh node, its place in `nodes`)
  for (std::size_t k = 0; k < nodes.size(); ++k) sorted.push_back({nodes[k], k});
  std::sort(sorted.begin(), sorted.end());
  return dg_copy_means(s, model, nodes.size(), true, [&](GlobalId n, const auto& visit) {
    auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair<GlobalId, std::size_t>{n, 0});
    for (; it != sorted.end() && it->first == n; ++it) visit(it->second);
  });
}

std::vector<std::string> node_history_suffixes() {
  return {"_displ_x", "_displ_y", "_displ_z", "_vel_x", "_vel_y", "_vel_z", "_acc_x", "_acc_y", "_acc_z"};
}

std::vector<double> block_energy_values(const ShellState& s, const ShellModel& model, std::size_t num_blocks) {
  std::vector<ExactSum> sum(3 * num_blocks);  // per block: kinetic, strain, plastic work
  for (LocalId le = 0; le < model.owned; ++le) {
    ExactSum* out = &sum[3 * std::size_t(model.dm.element_block(le))];
    out[0].add(model.element_kinetic(s, le));
    out[1].add(*s.strain_energy.at(le));
    out[2].add(*s.plastic_work.at(le));
  }
  ExactSum::allreduce(sum, model.dm.comm());
  std::vector<double> out;
  for (const auto& x : sum) out.push_back(x.value());
  return out;
}

std::vector<std::string> block_energy_suffixes() {
  return {"_kinetic_energy", "_strain_energy", "_plastic_dissipation"};
}

std::vector<std::string> element_history_suffixes() {
  return {"_N11", "_N22", "_N12", "_M11", "_M22", "_M12", "_Q1", "_Q2", "_eq_plastic_strain", "_strain_energy"};
}

std::vector<double> reaction_values(const ShellState& s, const ShellModel& model, const Constraints& constraints) {
  std::vector<ExactSum> sum(6 * constraints.size());  // per condition: force (3), couple (3)
  Constraints::Contribution force, couple;
  for (std::size_t bc = 0; bc < constraints.size(); ++bc) {
    constraints.reaction_contributions(s, bc, force, couple);
    for (int c = 0; c < 3; ++c) {
      for (double v : force.values[c]) sum[6 * bc + c].add(v);
      for (double v : couple.values[c]) sum[6 * bc + 3 + c].add(v);
    }
  }
  ExactSum::allreduce(sum, model.dm.comm());
  std::vector<double> out;
  for (const auto& x : sum) out.push_back(x.value());
  return out;
}

HistoryGroups HistoryGroups::names_only() const {
  HistoryGroups g = *this;
  const auto zeros = [](std::vector<double>& v, std::size_t n) { v.assign(n, 0.0); };
  zeros(g.probes, 6 * probe_names.size()), zeros(g.reactions, 6 * condition_names.size());
  zeros(g.contact_values, contact_columns.size());
  zeros(g.nodes, node_history_suffixes().size() * node_names.size());
  zeros(g.elements, element_history_suffixes().size() * element_names.size());
  zeros(g.blocks, block_energy_suffixes().size() * block_names.size());
  return g;
}

namespace {

/// Appends name + suffix for every name and suffix (names outer) with the next value of `values`.
void append_group(HistoryRow& row, const std::vector<std::string>& names, const std::vector<std::string>& suffixes,
                  const std::vector<double>& values) {
  SHELLFRAC_REQUIRE(values.size() == names.size() * suffixes.size(),
                    "history group of " << names.size() << " x " << suffixes.size() << " has " << values.size()
                                        << " values");
  std::size_t k = 0;
  for (const auto& name : names)
    for (const auto& suffix : suffixes) row.push_back({name + suffix, values[k++]});
}

}  // namespace

HistoryRow history_row(const StepRecord& r, double e0, const HistoryGroups& g) {
  HistoryRow row = {{"step", double(r.step)},           {"time", r.time},
                    {"dt", r.dt},                       {"kinetic_energy", r.kinetic},
                    {"strain_energy", r.strain},        {"penalty_energy", r.penalty},
                    {"external_work", r.external_work}, {"energy_balance_error", energy_balance_error(r, e0)}};
  append_group(row, g.probe_names, {"_displ_x", "_displ_y", "_displ_z", "_vel_x", "_vel_y", "_vel_z"}, g.probes);
  row.insert(row.end(), {{"reaction_work", r.reaction_work},
                         {"damping_dissipation", r.damping},
                         {"plastic_dissipation", r.plastic_work},
                         {"cohesive_energy", r.cohesive_energy},
                         {"cohesive_dissipation", r.cohesive_dissipation},
                         {"activation_loss", r.activation_loss},
                         {"num_cohesive_edges", double(r.cohesive_edges)},
                         {"num_separated_edges", double(r.separated_edges)},
                         {"num_fragments", double(r.fragments)}});
  append_group(row, g.condition_names,
               {"_reaction_x", "_reaction_y", "_reaction_z", "_moment_x", "_moment_y", "_moment_z"}, g.reactions);
  for (int c = 0; c < 3; ++c) row.push_back({std::string("angular_momentum_") + char('x' + c), r.angular_momentum[c]});
  append_group(row, g.contact_columns, {""}, g.contact_values);
  append_group(row, g.node_names, node_history_suffixes(), g.nodes);
  append_group(row, g.element_names, element_history_suffixes(), g.elements);
  append_group(row, g.block_names, block_energy_suffixes(), g.blocks);
  return row;
}

}  // namespace shellfrac::solver
