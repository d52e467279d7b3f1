#pragma once
/// \file loads.hpp
/// External forces on the position nodes (docs/theory.md §10.3): gravity on the lumped masses, and follower
/// pressures on the current mid-surface, each with its time function.
#include <string>
#include <vector>

#include "shellfrac/solver/dynamics_params.hpp"
#include "shellfrac/solver/shell_state.hpp"

namespace shellfrac::solver {

class MeshSets;
struct ShellModel;

class Loads {
 public:
  /// Resolves each load's elements (InputError for unknown names) on the owned elements.
  Loads(const std::vector<Load>& loads, const MeshSets& sets, const ShellModel& model);
  /// f_ext at time t on the current positions x (owned rows), overwriting `fext`.
  void external_forces(double t, const PositionRows& x, PositionRows& fext) const;

 private:
  std::vector<Load> loads_;
  PositionRows gravity_force_;                       // constant lumped gravity loads (owned)
  std::vector<std::vector<LocalId>> loaded_elements_;  // per load: the owned elements it acts on
};

}  // namespace shellfrac::solver
