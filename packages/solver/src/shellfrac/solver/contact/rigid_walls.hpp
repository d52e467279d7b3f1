#pragma once
/// \file rigid_walls.hpp
/// Contact of the shells with planar rigid walls (docs/theory.md §12): a penalty force on every DG position node
/// whose offset surface point (mid-surface - h/2 along the wall normal) is behind a wall. The forces are added to the
/// external forces, so the walls' work is part of the external work and the energy balance (§11) needs no term of
/// its own. With friction (§12.6) a node slipping along a wall also gets the Coulomb force of its trial slip velocity
/// relative to the wall; the energy it takes is booked in the state's friction account. Each node's force depends on
/// that node alone: no sum, rank- and thread-independent.
#include <string>
#include <vector>

#include "shellfrac/solver/input/contact_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

struct ShellModel;

class RigidWalls {
 public:
  /// The walls of `params` for a run with time step dt (penalty k = Penalty Scale m / dt^2 per node). InputError
  /// naming `file` if the penalty would make the step unstable: (2 S_f)^2 + Penalty Scale >= 4, S_f = dt /
  /// model.stable_dt (theory.md §12.2).
  RigidWalls(const ContactParams& params, const ShellModel& model, double dt, const std::string& file);
  bool empty() const { return walls_.empty(); }
  /// Adds the walls' forces at time t in state s to s.external_force (owned rows), which holds the loads (the other
  /// forces of the friction's trial velocity, with s.internal_force), and books the friction's dissipation over
  /// the step of length `step` that ends at t.
  void add_forces(double t, double step, ShellState& s) const;
  /// Per wall, in deck order: the total normal force it exerts on the shells at time t (>= 0). Collective.
  std::vector<double> normal_forces(double t, const ShellState& s) const;
  /// Per wall: its name (the history column is <name>_wall_force).
  std::vector<std::string> names() const;

 private:
  /// The penalty force magnitude on position node A of owned element le from wall w at time t (0 if not behind).
  double node_force(const RigidWall& w, double t, const ShellState& s, LocalId le, int A) const;

  const ShellModel& model_;
  std::vector<RigidWall> walls_;
  double stiffness_per_mass_ = 0;  ///< Penalty Scale / dt^2
  FrictionParams friction_;
  double dt_ = 0;
};

}  // namespace shellfrac::solver
