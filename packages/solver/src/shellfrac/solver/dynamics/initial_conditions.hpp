#pragma once
/// \file initial_conditions.hpp
/// The state at t = 0 (docs/theory.md §7.2, §10.2): reference positions and directors, the initial rotations,
/// initial velocities (translation, rigid spin, speed along the normal) on every DG copy of the nodes of the
/// listed elements, so that no spurious initial jumps appear, and the prescribed motions at t = 0.
#include <vector>

#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

class Constraints;
class MeshSets;
struct ShellModel;

/// Sizes every field of `s` for the model (fracture: with interface rows) and sets the initial state. The
/// velocities skip held and prescribed nodes and have no component across a symmetry plane; director rates
/// skip held directors. Also records the rotation program's reference (Constraints::capture_rotation_reference).
void set_initial_state(const std::vector<InitialVelocity>& velocities, const MeshSets& sets, const ShellModel& model,
                       Constraints& constraints, ShellState& s);

}  // namespace shellfrac::solver
