#pragma once
/// \file force_assembly.hpp
/// Internal forces of the current state (docs/theory.md §5.4-5.5, §9.4; paper eqs. 41-44, 53-56), in four
/// phases that never add a number across ranks:
///   1. element kernel over the owned elements: DG derivatives, the point law at each area point (elastic, or
///      the plastic return map, which updates the plastic state in place), the element's own forces, its
///      lifting fluxes for its neighbours and (with fracture) its projected edge tractions;
///   2. ghost exchange of the fluxes and edge tractions;
///   3. interface kernel over every local interface: penalty forces of intact interfaces, the cohesive law
///      of activated ones (which updates their opening history);
///   4. gather: each owned element adds its neighbours' fluxes (by local edge) and its interfaces' forces
///      (by increasing interface id) to its own, in a fixed order.
/// Every kernel writes only its own slots, so results are bitwise independent of the rank and thread counts.
#include <vector>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/materials/cohesive_law.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"
#include "shellfrac/solver/model/ghost_exchange.hpp"
#include "shellfrac/solver/model/phase_times.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

struct ShellModel;

/// The lifting fluxes an element writes for its neighbours: across each local edge k, the forces on the
/// neighbour's edge nodes (in the neighbour's edge-local order).
struct LiftingFluxes {
  disc::EdgeForces across[3];
};

/// The forces of an interface on the edge nodes of its two sides (0: minus, 1: plus), each in its edge-local order.
struct InterfaceForces {
  disc::EdgeForces side[2];
};

class ForceAssembly {
 public:
  /// `edge_tractions`: compute and exchange the projected edge tractions (fracture runs).
  ForceAssembly(const ShellModel& model, bool edge_tractions, PhaseTimes& times);

  /// Copies the owned positions and directors of `s` into the ghost rows of the ranks that hold them. Collective.
  void exchange_state(ShellState& s);
  /// Internal forces, strain and interface energies of the current state (ghosts current). Writes
  /// s.internal_force, s.director_force, s.strain_energy, the interface rows of s and the plastic state
  /// s.plastic (the return map from the last state: call once per new configuration), and the plastic work
  /// increments below. `cohesive`: the cohesive law of each local interface (used where s.mode != intact).
  /// Collective (the flux exchange).
  void compute_forces(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive);

  /// Projected edge tractions of every overlap element from the last compute_forces (fracture runs only).
  const std::vector<disc::EdgeTractions>& edge_tractions() const { return edge_tractions_; }
  /// The plastic work per element of the last element kernel, and whether the return map of an element reached
  /// its iteration limit.
  const std::vector<double>& plastic_work_increment() const { return plastic_work_increment_; }
  const std::vector<int>& return_failed() const { return return_failed_; }
  /// Bytes of the force buffers (fluxes, edge tractions, interface forces, transfer buffers).
  double bytes() const;

 private:
  void element_kernel(ShellState& s);
  void interface_kernel(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive);
  void gather(ShellState& s);

  const ShellModel& model_;
  PhaseTimes& times_;
  std::vector<LiftingFluxes> flux_;                  ///< overlap
  std::vector<disc::EdgeTractions> edge_tractions_;  ///< overlap (fracture runs)
  std::vector<InterfaceForces> interface_force_;     ///< per local interface
  std::vector<double> plastic_work_increment_;
  std::vector<int> return_failed_;
  GhostExchange exchange_;
};

}  // namespace shellfrac::solver
