#pragma once
/// \file shell_dynamics.hpp
/// Explicit dynamics of the DG shell on the distributed element model (paper §4.3; math.md §7):
/// central differences for positions, the exponential-map update for directors, HRZ-lumped mass and
/// rotary inertia, the element-by-element stable time step. One step:
///   predictor (owned) -> Import of positions/directors to the ghost layer -> element kernel (own forces +
///   lifting fluxes for the neighbours) -> Import of the flux buffers -> interface kernel (penalty) ->
///   gather in a fixed order -> accelerations -> corrector.
/// No force is ever summed across ranks: every owned element gathers its own, its neighbours' and its
/// interfaces' contributions in the same order on any rank count, so results are bitwise identical for
/// any number of ranks. Energies are summed in global-id order for the same reason.
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/solver/dynamics_params.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}
namespace shellfrac::dist {
class DistributedMesh;
}

namespace shellfrac::solver {

/// Section and material of a block (by SerialMesh block index).
struct Section {
  double E = 0, nu = 0, rho = 0, h = 0;
  bool plastic = false;  ///< resultant plasticity (math.md §4) with yield stress Y0 and hardening modulus H
  double Y0 = 0, H = 0;
  bool shear_yield = false;  ///< transverse shear in the yield function (math.md §4.1 option (b))
  double sigma_c = 0, Gamma = 0;  ///< cohesive strength (0 = unbreakable) and work of separation (math.md §9)
};

/// Everything the dynamics needs from the deck.
struct DynamicsSetup {
  std::vector<Section> block_sections;
  DiscretizationParams discretization;
  TimeParams time;
  FractureParams fracture;
  std::vector<BoundaryCondition> boundary_conditions;
  std::vector<InitialVelocity> initial_velocities;
  std::vector<Load> loads;
  std::string deck_file;  ///< for messages
};

/// Global quantities of one step (identical on every rank).
struct StepRecord {
  long step = 0;
  double time = 0, dt = 0;
  double kinetic = 0, strain = 0, penalty = 0;
  double external_work = 0;   ///< work of the loads (trapezoidal rule, math.md §9.7)
  double reaction_work = 0;   ///< work of the support reactions (prescribed motions)
  double damping = 0;         ///< energy dissipated by mass damping
  double plastic_work = 0;    ///< plastic work (dissipation + stored hardening energy), math.md §4.2
  double cohesive_energy = 0;       ///< energy stored in the cohesive laws of activated edges (math.md §9.7)
  double cohesive_dissipation = 0;  ///< energy dissipated by them (Gamma h h_e per fully separated edge)
  double activation_loss = 0;       ///< DG energy (penalty + lifting) released when edges were activated (§9.6)
  GlobalId cohesive_edges = 0;      ///< activated (cohesive or separated) edges
  GlobalId separated_edges = 0;     ///< fully separated edges
  GlobalId fragments = 1;           ///< connected pieces through edges that are not fully separated
  Vec3 angular_momentum{0, 0, 0};  ///< about the origin: sum m x × v + sum I t × tdot
};

/// Wall time spent in each phase of the steps taken so far, on this rank [s].
struct PhaseTimes {
  double element = 0;    ///< element kernel: DG derivatives, resultants, own forces, lifting fluxes
  double interface = 0;  ///< interface kernel: penalty forces
  double gather = 0;     ///< gathering fluxes and interface forces into each element
  double exchange = 0;   ///< Tpetra Imports of positions/directors and of the flux buffers (incl. packing)
  double update = 0;     ///< predictor, director update, accelerations, corrector, checks
  double nucleation = 0; ///< fracture: the nucleation check of intact edges and activation (part of update)
};

/// The explicit DG shell solver on one rank's part of the mesh.
class ShellDynamics {
 public:
  /// Builds reference data, masses, conditions and the stable time step. InputError for unknown sets or a
  /// fixed time step above the stable estimate (unless forced). Collective.
  ShellDynamics(const mesh::SerialMesh& mesh, const dist::DistributedMesh& dm, const DynamicsSetup& setup);
  ~ShellDynamics();
  ShellDynamics(const ShellDynamics&) = delete;
  ShellDynamics& operator=(const ShellDynamics&) = delete;

  /// Stable estimate 2 / max omega over all elements (math.md §8), before the safety factor.
  double stable_time_step() const;
  /// The time step in use.
  double time_step() const;
  double time() const;
  long step_count() const;
  /// Advances one step. Throws Error (on every rank) if the state becomes non-finite. Collective.
  void step();
  /// Global energies of the current state, summed in global-id order. Collective.
  StepRecord record() const;
  /// Node-set probes: for each entry of `members` (a flag per mesh node), the mean displacement (3) and
  /// velocity (3) over every DG copy of its nodes, summed in global DG-node order. Collective.
  std::vector<double> probes(const std::vector<std::vector<char>>& members) const;
  /// Per boundary condition, in deck order: the support reaction force summed over its DG position nodes (3),
  /// then the support couple sum t x g over its constrained DG director nodes (3), in global DG-node order.
  /// Collective.
  std::vector<double> reactions() const;
  /// Accumulated phase timings on this rank.
  const PhaseTimes& phase_times() const;
  /// Bytes of per-element state and reference data held on this rank, divided by the owned elements.
  double bytes_per_element() const;
  /// Names of the element result fields written by element_fields (Exodus element variables).
  static std::vector<std::string> element_field_names();
  /// Owned element fields: area-weighted means over the element's area points of the equivalent plastic strain
  /// alpha, the von Mises norms of the membrane forces sqrt(N11^2 - N11 N22 + N22^2 + 3 N12^2) and of the moments
  /// (same form), and |Q|; then the damage (max over the element's edges of delta_max/delta_f, 1 if separated)
  /// and the fragment id (smallest element id + 1 of the element's fragment). fields[k][le] in
  /// element_field_names() order. Collective (fragments).
  void element_fields(std::vector<std::vector<double>>& fields) const;
  /// The whole state needed to continue bitwise (positions, velocities, accelerations, directors, rotations,
  /// director rates, forces, energies and work accounts, plastic state per area point, interface states),
  /// as tables by element and interface global id. Each rank gives its owned rows. (Not collective.)
  io::CheckpointData checkpoint() const;
  /// Restores a checkpoint written by checkpoint() on any rank count: every owned element and local interface
  /// looks up its row by global id; the ghosts' positions and directors are imported. InputError if the
  /// checkpoint does not belong to this mesh. Collective.
  void restore(const io::CheckpointData& data);
  /// Whether any edge of the mesh may break (Fracture; the same on every rank).
  bool fracture() const;
  /// One row per fragment, in increasing fragment id: {fragment id (smallest element id + 1), elements, mass,
  /// centre of mass x/y/z, momentum x/y/z}, summed over elements in global-id order (rank-count independent).
  /// Collective; the rows are the same on every rank.
  std::vector<std::vector<double>> fragment_table() const;
  /// The crack log: one row per interface activated since the last call, sorted by step and interface id,
  /// the same on every rank (and for any rank count): step, time, interface id (global, 1-based), the element
  /// ids (1-based) of its two sides, the current position of the edge's mid-point, the edge-averaged nucleation
  /// function fbar (>= 0), and the shares of the five terms of n_eq^2 (edge-averaged, summing to 1): normal
  /// opening, in-plane sliding, transverse (out-of-plane) sliding, normal and shear director couples
  /// (materials::equivalent_traction_parts). Collective.
  std::vector<std::vector<double>> crack_events();
  /// Column names of crack_events() rows.
  static std::vector<std::string> crack_event_columns();
  /// Owned DG nodal fields, element-major as DistributedMesh::node_coords: displacement, velocity, director
  /// (P1: mid-side nodes show the mean of their edge's vertex directors).
  void nodal_fields(std::vector<Vec3>& displacement, std::vector<Vec3>& velocity, std::vector<Vec3>& director) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellfrac::solver
