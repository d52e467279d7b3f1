#pragma once
/// \file energy_accounts.hpp
/// The global quantities of a state that the history records (docs/theory.md §9.7, §11; docs/output.md):
/// energies and work accounts, fracture counts, angular momentum, node-set probes and support reactions. Every
/// sum is exact (ExactSum: one integer MPI_Allreduce per call, no gather), so it is bitwise independent of the
/// rank count and of the order of the contributions. The history row is built as (name, value) pairs, so its header and its values come from one list.
#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

class Constraints;
class Fracture;
struct ShellModel;

/// Global quantities of one step (identical on every rank).
struct StepRecord {
  long step = 0;
  double time = 0, dt = 0;
  double kinetic = 0, strain = 0, penalty = 0;
  double external_work = 0;   ///< work of the loads (trapezoidal rule, docs/theory.md §9.7)
  double reaction_work = 0;   ///< work of the support reactions (prescribed motions)
  double damping = 0;         ///< energy dissipated by mass damping
  double plastic_work = 0;    ///< plastic work (dissipation + stored hardening energy), docs/theory.md §4.2
  double cohesive_energy = 0;       ///< energy stored in the cohesive laws of activated edges (§9.7)
  double cohesive_dissipation = 0;  ///< work of separation done on them (Gamma h h_e per fully separated edge)
  double activation_loss = 0;       ///< change of the discrete energy at activations, less what softening released (§9.6-9.7)
  GlobalId cohesive_edges = 0;      ///< activated (cohesive or separated) edges
  GlobalId separated_edges = 0;     ///< fully separated edges
  GlobalId fragments = 1;           ///< connected pieces through edges that are not fully separated
  Vec3 angular_momentum{0, 0, 0};  ///< about the origin: sum m x × v + sum I t × tdot
};

/// The record of the current state. Collective.
StepRecord step_record(const ShellState& s, const ShellModel& model, const Fracture& fracture, double dt);

/// Energy balance error (docs/theory.md §9.7): K + U_el + U_stab + D_damp + W_p + U_coh + D_coh + D_act
/// - E0 - W_ext - W_react, with E0 the initial kinetic + strain + penalty energy.
double energy_balance_error(const StepRecord& r, double e0);

/// Node-set probes: for each flag list (a flag per mesh node), the mean displacement (3) and velocity (3) over
/// every DG copy of its nodes. Collective.
std::vector<double> probe_values(const ShellState& s, const ShellModel& model,
                                 const std::vector<std::vector<char>>& members);

/// Per boundary condition in deck order: its reaction force (3) and its support couple (3). Collective.
std::vector<double> reaction_values(const ShellState& s, const ShellModel& model, const Constraints& constraints);

/// One history row as (column name, value) pairs in column order: step, time, dt, energies and the balance
/// error, the probes (<set>_displ_x ... <set>_vel_z), the other work accounts, the fracture counts, the
/// reactions (<condition>_reaction_x ... _moment_z), the angular momentum and the contact partners' columns
/// (ShellDynamics::contact_columns: the walls' normal forces <wall>_wall_force, the rigid bodies' motion).
using HistoryRow = std::vector<std::pair<std::string, double>>;
HistoryRow history_row(const StepRecord& r, double e0, const std::vector<std::string>& probe_names,
                       const std::vector<double>& probes, const std::vector<std::string>& condition_names,
                       const std::vector<double>& reactions, const std::vector<std::string>& contact_columns,
                       const std::vector<double>& contact_values);

}  // namespace shellfrac::solver
