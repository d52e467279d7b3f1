#pragma once
/// \file central_difference.hpp
/// Explicit central differences in time (paper eqs. 47-50 and Algorithm 1; docs/theory.md §7): Newmark with
/// gamma = 1/2 for positions and for the material director rates, the exponential-map update of the directors,
/// and the constraints, loads, plastic work and fracture checks of each step, as named phases.
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/solver/model/phase_times.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

class Constraints;
class ForceAssembly;
class Fracture;
class Loads;
class RigidWalls;
class RigidBodies;
class ShellContact;
struct ShellModel;

class CentralDifference {
 public:
  /// Static relaxation (docs/theory.md §7.5): kinetic-energy peak resets and the stopping test, active from
  /// time `start` (when the loads and prescribed motions have reached their final values).
  struct Relaxation {
    bool enabled = false;
    double tolerance = 1e-6, start = 0;
    /// The residual has stopped falling when it has not fallen below stall_drop of its smallest value over this
    /// many kinetic-energy peaks (theory.md §7.5).
    int stall_peaks = 100;
    double stall_drop = 0.99;
    /// ... and the displacement has settled when its norm changed over those peaks by at most the tolerance or
    /// this factor times the smallest residual, relative.
    double settled_factor = 10;
  };
  /// `mass_damping`: alpha of the damping force alpha m v (dynamic relaxation; 0 = none).
  /// `walls`, `bodies`: the rigid walls and bodies, whose contact forces join the loads' (docs/theory.md §12);
  /// the free bodies are integrated with the shells; `shells`: the contact between the shells (§12.5).
  CentralDifference(ShellModel& model, Constraints& constraints, const Loads& loads, const RigidWalls& walls,
                    const RigidBodies& bodies, ShellContact& shells, ForceAssembly& assembly, Fracture& fracture, PhaseTimes& times, double mass_damping,
                    Relaxation relaxation);

  /// Start-up (docs/theory.md §7.4): forces, loads, accelerations and reactions of the initial state.
  /// Collective.
  void start(ShellState& s);
  /// One step from t_n = s.time to t1 = t_n + dt (t1 given, so that a shortened step ends exactly on it).
  /// NumericalError (on every rank) if the state becomes non-finite; Error if a plastic return map fails.
  /// Collective.
  void step(ShellState& s, double dt, double t1);
  /// Static relaxation: whether the last step reached the static equilibrium, and its relative residual
  /// (NaN before the first test).
  bool relaxed() const { return relaxed_; }
  double relaxation_residual() const { return residual_; }
  /// Static relaxation (theory.md §7.5): whether the residual stopped falling while the displacement still changed
  /// (stalled: no equilibrium), and whether it stopped falling at a settled displacement (relaxed() too: the
  /// equilibrium at the residual's round-off floor). The smallest residual is the state's
  /// (ShellState::relaxation.best_residual), which a restart restores.
  bool relaxation_stalled() const { return stalled_; }
  bool relaxed_at_floor() const { return at_floor_; }
  /// The change of the displacement norm over the peaks since the residual last fell, relative to it.
  double relaxation_displacement_change() const { return displacement_change_; }

 private:
  void remember_step_start(const ShellState& s);
  void predict(ShellState& s, double dt, double t1);
  void book_plastic_work(ShellState& s) const;
  void correct(ShellState& s, double dt, double t1);
  void check_finite(const ShellState& s) const;
  /// The loads and the contact forces at time t (the walls', the bodies' where s.bodies has them, the shells'):
  /// s.external_force, s.external_director_force, the bodies' forces and accelerations. Collective.
  void external_forces(double t, ShellState& s);
  void relax(ShellState& s);
  void watch_for_stall(ShellState& s);
  double displacement_norm(const ShellState& s) const;
  void reset_free_velocities(ShellState& s) const;
  double relative_residual(const ShellState& s) const;

  ShellModel& model_;
  Constraints& constraints_;
  const Loads& loads_;
  const RigidWalls& walls_;
  const RigidBodies& bodies_;
  ShellContact& shells_;
  ForceAssembly& assembly_;
  Fracture& fracture_;
  PhaseTimes& times_;
  double alpha_;
  Relaxation relaxation_;
  // Static relaxation: the outcome of the last test (where the relaxation stands is in ShellState::relaxation).
  bool relaxed_ = false;
  double residual_, displacement_change_ = 0;
  bool stalled_ = false, at_floor_ = false;
  // At t_n, for the work accounts: the positions, and the external forces of the elements loaded at t_n only
  // (fext_start_slot_[le]: the row of owned element le in fext_start_, -1 if its forces were all zero). The
  // reactions at t_n need no copy: the corrector reads them before it overwrites them.
  PositionRows x_start_, fext_start_;  // x_start_: written by the predictor before it moves a node
  std::vector<int> fext_start_slot_;
  DirectorRows t_start_, gext_start_;                   // directors and director loads at t_n (edge moments)
  RateRows director_rate_predicted_;  // T-dot + dt/2 T-ddot (eq. 48)
  std::vector<char> finite_;           // per owned element: its positions and forces finite (set by the corrector)
  std::vector<double> programs_u_, programs_v_, programs_a_;  // the conditions' programs at the kernel's time
};

}  // namespace shellfrac::solver
