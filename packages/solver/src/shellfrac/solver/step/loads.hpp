#pragma once
/// \file loads.hpp
/// External forces (docs/theory.md §10.3): gravity on the lumped masses, forces at mesh nodes, follower pressures
/// on the current mid-surface, line loads along element edges (fixed or following the edge) and couples per unit
/// length on the edges' directors, each with its time function.
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}

namespace shellfrac::solver {

class MeshSets;
struct ShellModel;

class Loads {
 public:
  /// Resolves each load's elements, node set or side set (InputError for unknown names) on the owned elements.
  Loads(const std::vector<Load>& loads, const MeshSets& sets, const mesh::SerialMesh& mesh, const ShellModel& model);
  /// f_ext on the position nodes and g_ext on the director nodes at time t in state s (owned rows; both
  /// overwritten; g_ext only if has_director_loads()).
  void external_forces(double t, const ShellState& s, PositionRows& fext, DirectorRows& gext) const;
  /// Whether some load acts on directors (Edge Moment).
  bool has_director_loads() const { return director_loads_; }

 private:
  /// An edge of an owned element carrying a line load or an edge moment, with (follower line loads) the load's
  /// components in the edge's reference frame (tangent, co-normal, director) at each edge point.
  struct LoadedEdge {
    LocalId element;
    int edge;
    double local[3][3];
  };
  void add_pressure(const Load& load, std::size_t l, double t, const ShellState& s, PositionRows& fext) const;
  void add_line_load(const Load& load, std::size_t l, double t, const ShellState& s, PositionRows& fext) const;
  void add_edge_moment(const Load& load, std::size_t l, double t, const ShellState& s, DirectorRows& gext) const;

  const ShellModel& model_;
  std::vector<Load> loads_;
  PositionRows constant_force_;                   // gravity and nodal forces with a Constant function (owned)
  std::vector<PositionRows> scaled_force_;        // per load: its gravity or nodal force distribution if f(t) varies
  std::vector<std::vector<LocalId>> elements_;    // per load: the owned elements it acts on (Pressure)
  std::vector<std::vector<LoadedEdge>> edges_;    // per load: the owned edges it acts on (Line Load, Edge Moment)
  bool director_loads_ = false;
};

}  // namespace shellfrac::solver
