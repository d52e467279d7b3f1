#pragma once
/// \file shell_dynamics.hpp
/// The explicit DG shell solver on one rank's part of the mesh: the model (shell_model.hpp), its state
/// (shell_state.hpp), the conditions (constraints.hpp), the loads (loads.hpp), the force assembly
/// (force_assembly.hpp), the fracture bookkeeping (fracture.hpp) and the time integrator
/// (central_difference.hpp), wired together. One step (paper Algorithm 1; docs/architecture.md):
///   predictor -> ghost exchange of positions/directors -> element kernel -> exchange of the fluxes ->
///   interface kernel -> gather -> plasticity commit -> nucleation -> loads -> accelerations -> corrector.
/// No force is ever summed across ranks and every global sum runs in global-id order, so results are bitwise
/// identical for any number of ranks.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"
#include "shellfrac/solver/model/phase_times.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}
namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

struct Deck;
struct ShellModel;
struct ShellState;

class ShellDynamics {
 public:
  /// Builds the model, resolves the conditions, loads and fracture sets, sets the initial state and computes
  /// the start-up accelerations. InputError for unknown sets or a fixed time step above the stable estimate
  /// (unless forced). Every block of the mesh must have a section in the deck. Collective.
  ShellDynamics(const mesh::SerialMesh& mesh, const decomposition::DistributedMesh& dm, const Deck& deck);
  ~ShellDynamics();
  ShellDynamics(const ShellDynamics&) = delete;
  ShellDynamics& operator=(const ShellDynamics&) = delete;

  /// Stable estimate 2 / max omega over all elements (docs/theory.md §8), before the safety factor.
  double stable_time_step() const;
  /// The time step in use.
  double time_step() const;
  double time() const;
  long step_count() const;
  /// Advances one step. Throws NumericalError (on every rank) if the state becomes non-finite. Collective.
  void step();
  /// Advances one step that ends exactly at t1, after the current time and at most one time step later (a step
  /// shortened to land on an output time). Collective.
  void step_to(double t1);
  /// Global energies of the current state, summed in global-id order. Collective.
  StepRecord record() const;
  /// Node-set probes: for each entry of `members` (a flag per mesh node), the mean displacement (3) and
  /// velocity (3) over every DG copy of its nodes, summed in global DG-node order. Collective.
  std::vector<double> probes(const std::vector<std::vector<char>>& members) const;
  /// Single-node histories: for each mesh node of `nodes` (positions), the mean displacement, velocity and
  /// acceleration over its DG copies (node_history_values). Collective.
  std::vector<double> node_histories(const std::vector<GlobalId>& nodes) const;
  /// Single-element histories: for each element of `elements` (global ids), in the order of
  /// element_history_suffixes(): the area means of the resultants N11 N22 N12 M11 M22 M12 Q1 Q2 (components in the
  /// local basis e_1, e_2 of each area point, theory.md §1.4; on a flat element one basis, e_1 along its first
  /// edge), of the equivalent plastic strain, and the element's strain energy. Collective.
  std::vector<double> element_histories(const std::vector<GlobalId>& elements) const;
  /// Per element block: its kinetic energy, strain energy and plastic work (block_energy_values). Collective.
  std::vector<double> block_energies(std::size_t num_blocks) const;
  /// Per boundary condition, in deck order: its support reaction force (3), then its support couple sum t x g
  /// over the director nodes it holds (3) (constraints.hpp: which condition a node's reaction belongs to).
  /// Collective.
  std::vector<double> reactions() const;
  /// Per rigid wall, in deck order: the normal force it exerts on the shells now (history <wall>_wall_force).
  /// Collective.
  std::vector<double> wall_forces() const;
  /// The history columns of the contact partners: <wall>_wall_force per wall, then per rigid body its position,
  /// velocity, contact force and kinetic energy (contact/rigid_bodies.hpp), the shell contact's columns, and
  /// friction_dissipation when a contact has friction; and their values now (collective).
  std::vector<std::string> contact_columns() const;
  std::vector<double> contact_values() const;
  /// The energy friction has taken from the shells so far (theory.md §12.6; part of the external work, as every
  /// contact force is an external force). Collective.
  double friction_dissipation() const;
  /// Accumulated phase timings on this rank.
  const PhaseTimes& phase_times() const;
  /// Bytes of state, reference data and force buffers held on this rank, divided by the owned elements.
  double bytes_per_element() const;
  /// Owned element fields: area-weighted means over the element's area points of the equivalent plastic strain
  /// alpha, the von Mises norms of the membrane forces sqrt(N11^2 - N11 N22 + N22^2 + 3 N12^2) and of the moments
  /// (same form), and |Q|; then the damage (max over the element's edges of delta_max/delta_f, 1 if separated)
  /// and the fragment id (smallest element id + 1 of the element's fragment). fields[k][le] with
  /// k an ElementField (input/element_fields.hpp). Collective (fragments).
  void element_fields(std::vector<std::vector<double>>& fields) const;
  /// The whole state needed to continue bitwise, as tables by element and interface global id
  /// (state_checkpoint.hpp). Each rank gives its owned rows. (Not collective.)
  io::CheckpointData checkpoint() const;
  /// Restores the checkpoint file `file` written by checkpoint() on any rank count, reading it one table at a time
  /// (no rank holds more than one table of its rows): `check` first sees the file's scalars and strings and may
  /// refuse it (throw, on every rank); then the state is restored and the ghosts' positions and directors
  /// imported. InputError if the checkpoint does not belong to this mesh or fails its checksum. Collective.
  void restore(const std::string& file, const std::function<void(const io::CheckpointData& header)>& check);
  /// Whether any edge of the mesh may break (Fracture; the same on every rank).
  bool fracture() const;
  /// Whether some block is plastic (the same on every rank).
  bool plasticity() const;
  /// The largest equivalent plastic strain alpha at an area point of any element (0 without plasticity; alpha
  /// never decreases, so this is also the peak over the run). Collective.
  double peak_plastic_strain() const;
  /// The breakable interfaces' drawn strengths (Fracture::strengths; the same on every rank).
  const materials::StrengthSummary& strengths() const;
  /// Static Relaxation: whether the static equilibrium has been reached, and the last relative residual (NaN
  /// before the loads and prescribed motions reached their final values).
  bool relaxed() const;
  double relaxation_residual() const;
  /// Static relaxation (theory.md §7.5): whether the residual stopped falling while the displacement still changed,
  /// whether it stopped falling at a settled displacement (relaxed() too), and its smallest value.
  bool relaxation_stalled() const;
  bool relaxed_at_floor() const;
  double best_relaxation_residual() const;
  double relaxation_displacement_change() const;
  /// One row per fragment (Fracture::fragment_table). Collective.
  std::vector<std::vector<double>> fragment_table() const;
  /// The crack log since the last call (Fracture::crack_events). Collective.
  std::vector<std::vector<double>> crack_events();
  /// Component c of an owned DG nodal field at every owned node, element-major as DistributedMesh::node_coords,
  /// into out (6 values per owned element). field indexes nodal_result_names(): the displacement, the velocity or
  /// the director (P1: a mid-side node shows the mean of its edge's vertex directors).
  void nodal_field_component(int field, int c, double* out) const;

  /// The state and the model, for tests and diagnostics (read only).
  const ShellState& state() const;
  const ShellModel& model() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellfrac::solver
