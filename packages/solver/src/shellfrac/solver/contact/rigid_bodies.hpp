#pragma once
/// \file rigid_bodies.hpp
/// Contact of the shells with rigid bodies (docs/theory.md §12.4): spheres and projectiles (a cylinder with a
/// hemispherical, conical or flat nose) that translate without turning, either at a prescribed velocity or as free
/// bodies moved by the contact forces. Every DG position node whose offset point (the node less h/2 along the
/// body's normal) is inside a body gets the penalty force k <-g> n of the walls (§12.1), with g the node's signed
/// distance from the body's surface less h/2. The forces join the external forces (so their work is external
/// work, as for the walls); a free body takes minus their sum, an exact sum over all ranks, and is integrated with
/// the shells' central-difference scheme. With friction, the walls' Coulomb law of §12.6 on the slip relative to the
/// body. Rank- and thread-independent like the walls.
#include <string>
#include <vector>

#include "shellfrac/solver/input/contact_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

struct ShellModel;

class RigidBodies {
 public:
  /// The bodies of `params` for a run with time step dt (penalty k = Penalty Scale m / dt^2 per node, the walls').
  RigidBodies(const ContactParams& params, const ShellModel& model, double dt, const std::string& file);
  bool empty() const { return bodies_.empty(); }
  /// The bodies at t = 0: at their Point, moving at their Velocity.
  void initial_state(ShellState& s) const;
  /// The predictor of a step to t1 (before the forces): a free body's x^{n+1} = x^n + dt v^n + dt^2/2 a^n and
  /// half-step velocity v^n + dt/2 a^n; a prescribed one at Point + Velocity t1.
  void predict(ShellState& s, double dt, double t1) const;
  /// Adds the bodies' contact forces on the shells at the bodies' current positions to f_ext (owned rows), and sets
  /// each body's force (minus their exact sum over all ranks) and a free body's acceleration. NumericalError if a
  /// free body is so light against the shells in contact with it that the step is unstable. Collective.
  /// With friction (theory.md §12.6) the nodes also get the Coulomb force of their trial slip relative to the body
  /// (s.external_force holds the loads then: the other forces of the trial velocity), the body minus it, and the
  /// dissipation over the step of length `step` is booked in the state's friction account.
  void add_forces(double step, ShellState& s) const;
  /// The corrector: a free body's v^{n+1} = v^n + dt/2 (a^n + a^{n+1}).
  void correct(ShellState& s, double dt) const;
  /// History columns, per body: <name>_x, _y, _z (its Point), _vel_x.._z, _force_x.._z (the contact force on it),
  /// _kinetic_energy.
  std::vector<std::string> history_columns() const;
  std::vector<double> history_values(const ShellState& s) const;

 private:
  const ShellModel& model_;
  std::vector<RigidBody> bodies_;
  double penalty_scale_, stiffness_per_mass_;  ///< s, and s / dt^2
  double step_ratio_squared_;                  ///< (2 S_f)^2 with S_f = dt / stable step
  FrictionParams friction_;
  double dt_;
};

}  // namespace shellfrac::solver
