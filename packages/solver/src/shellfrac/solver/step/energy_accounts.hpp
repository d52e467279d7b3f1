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

/// Single-node histories: for each mesh node of `nodes` (positions), the mean displacement (3), velocity (3) and
/// acceleration (3) over its DG copies, in the order of node_history_suffixes(). Collective.
std::vector<double> node_history_values(const ShellState& s, const ShellModel& model,
                                        const std::vector<GlobalId>& nodes);
std::vector<std::string> node_history_suffixes();

/// Per element block (block index order): the kinetic energy, the strain energy and the plastic work of its
/// elements, in the order of block_energy_suffixes(); over the blocks they sum to the totals. Collective.
std::vector<double> block_energy_values(const ShellState& s, const ShellModel& model, std::size_t num_blocks);
std::vector<std::string> block_energy_suffixes();

/// The quantities of a single element's history (ShellDynamics::element_histories): its resultants N11 N22 N12
/// M11 M22 M12 Q1 Q2, its equivalent plastic strain and its strain energy.
std::vector<std::string> element_history_suffixes();

/// Per boundary condition in deck order: its reaction force (3) and its support couple (3). Collective.
std::vector<double> reaction_values(const ShellState& s, const ShellModel& model, const Constraints& constraints);

/// The columns of a history row beyond the fixed ones, by group: the names (a set, condition, node, element or
/// block name, to which each group's suffixes are appended; the contact columns are whole names) and the values
/// (per name, one per suffix).
struct HistoryGroups {
  std::vector<std::string> probe_names, condition_names, contact_columns, node_names, element_names, block_names;
  std::vector<double> probes, reactions, contact_values, nodes, elements, blocks;
  /// The same names with every value 0 (for the header).
  HistoryGroups names_only() const;
};

/// One history row as (column name, value) pairs in column order: step, time, dt, energies and the balance
/// error, the probes (<set>_displ_x ... <set>_vel_z), the other work accounts, the fracture counts, the
/// reactions (<condition>_reaction_x ... _moment_z), the angular momentum, the contact partners' columns
/// (ShellDynamics::contact_columns: the walls' normal forces <wall>_wall_force, the rigid bodies' motion), then the
/// single nodes (node<id>_displ_x ... _acc_z), the single elements (element<id>_N11 ... _strain_energy, see
/// ShellDynamics::element_histories) and the blocks (<block>_kinetic_energy, ...).
using HistoryRow = std::vector<std::pair<std::string, double>>;
HistoryRow history_row(const StepRecord& r, double e0, const HistoryGroups& groups);

}  // namespace shellfrac::solver
