#pragma once
/// \file constraints.hpp
/// Boundary conditions on the DG copies of mesh nodes (docs/theory.md §10.1-10.2): which position and director
/// nodes are held, follow a velocity program, stay on symmetry planes or rigid diaphragms, or follow a rotation
/// program; the projections that the time integrator applies to increments, velocities and accelerations; and
/// the support reactions of each condition.
///
/// Composition on one node: a held node (Clamped, Simply Supported) is held whatever else acts on it; a node
/// that follows a Prescribed Velocity ignores planes; the directions that symmetry planes and diaphragms forbid
/// are composed into the orthogonal projection on the intersection of their constraints (so the composition
/// is workless); the directors of Clamped and Prescribed Velocity nodes are held, and a Prescribed Rotation acts
/// only on directors that nothing else holds. Each node's reaction belongs to the condition that holds it: the
/// first holding condition in deck order, or the prescribing one; a symmetry plane or diaphragm reports the
/// force along the directions it forbids.
#include <cstdint>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

class MeshSets;
struct ShellModel;

/// The cosine ramp r(t) = (1 - cos(pi t / t_r)) / 2 for t < t_r, 1 afterwards (1 at once for t_r = 0), with
/// its integral and its rate (docs/theory.md §10.2); value and rate of amplitude x r(t).
struct CosineRamp {
  double duration = 0;
  double value(double t, double amplitude = 1.0) const;
  double integral(double t) const;
  double rate(double t, double amplitude = 1.0) const;
};

/// A direction along which a position node may not move (a symmetry plane's normal, or one of the two in-plane
/// directions of a rigid diaphragm), and the condition it belongs to. The planes of one node are orthonormal.
struct Plane {
  Vec3 normal;
  int condition;
};

/// w -= (w . n) n for the normal n of each plane in [first, last), in order.
inline void remove_plane_normals(const Plane* first, const Plane* last, double w[3]) {
  for (const Plane* p = first; p != last; ++p) {
    const double* n = p->normal.data();
    const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
    for (int c = 0; c < 3; ++c) w[c] -= wn * n[c];
  }
}

/// Short lists of planes per node, compressed (most nodes have none), in deck order.
class PlaneLists {
 public:
  /// From one list per node; each list is made orthonormal (Gram-Schmidt in deck order: a normal already in the
  /// span of the earlier ones adds no constraint and is dropped), so that removing the components along the
  /// planes one after the other is the orthogonal projection on the intersection of the constraints.
  void assign(std::vector<std::vector<Plane>> lists);
  const Plane* begin(LocalId i) const { return planes_.data() + offset_[i]; }
  const Plane* end(LocalId i) const { return planes_.data() + offset_[i + 1]; }
  bool empty(LocalId i) const { return offset_[i] == offset_[i + 1]; }
  /// w -= (w . n) n for each plane normal n of node i, in order.
  void remove_normal_components(LocalId i, double w[3]) const { remove_plane_normals(begin(i), end(i), w); }
  /// The lists: node i's planes are planes()[offsets()[i]] .. planes()[offsets()[i + 1] - 1].
  const std::vector<int>& offsets() const { return offset_; }
  const std::vector<Plane>& planes() const { return planes_; }
  std::size_t bytes() const { return sizeof(int) * offset_.size() + sizeof(Plane) * planes_.size(); }

 private:
  std::vector<int> offset_{0};
  std::vector<Plane> planes_;
};

/// A constraint on a director node: the director keeps its component along `axis` (a symmetry plane with normal
/// `axis`: t . n stays 0), or it does not rotate about `axis` (a rigid diaphragm with normal `axis`).
struct DirectorConstraint {
  Vec3 axis;
  bool no_rotation_about_axis;
  int condition;
};

/// Removes from the material components w[2] of a director rate, increment or force (current director t,
/// rotation L) the directions the constraints [first, last) forbid (docs/theory.md §10.1): d = Lambda-bar^T n for
/// a kept component t . n, d = Lambda-bar^T (n x t) for no rotation about n. Several constraints are composed by
/// an orthogonal projection on the intersection (two independent ones hold the director).
inline void remove_forbidden_director_components(const DirectorConstraint* first, const DirectorConstraint* last,
                                                 const double L[3][3], const double t[3], double w[2]) {
  double d[2][2];
  int nd = 0;
  for (const DirectorConstraint* k = first; k != last && nd < 2; ++k) {
    const DirectorConstraint& c = *k;
    double v[3];
    if (c.no_rotation_about_axis)
      disc::cross3(c.axis.data(), t, v);
    else
      disc::copy3(c.axis.data(), v);
    disc::lambda_bar_transpose_times(L, v, d[nd]);
    if (nd == 1) {  // orthogonalize against the first (2-D Gram-Schmidt)
      const double d00 = d[0][0] * d[0][0] + d[0][1] * d[0][1];
      if (d00 > 0) {
        const double f = (d[1][0] * d[0][0] + d[1][1] * d[0][1]) / d00;
        d[1][0] -= f * d[0][0], d[1][1] -= f * d[0][1];
      }
      if (d[1][0] * d[1][0] + d[1][1] * d[1][1] <= 1e-24 * (d00 > 0 ? d00 : 1.0)) continue;  // dependent
    }
    ++nd;
  }
  for (int k = 0; k < nd; ++k) disc::project_out(w, d[k]);
}

/// Short lists of director constraints per node, compressed, in deck order.
class DirectorConstraintLists {
 public:
  void assign(const std::vector<std::vector<DirectorConstraint>>& lists);
  bool empty(LocalId j) const { return offset_[j] == offset_[j + 1]; }
  /// Removes from the material components w[2] of a director rate, increment or force of director node j the
  /// directions its constraints forbid (remove_forbidden_director_components).
  void remove_forbidden_components(LocalId j, const double L[3][3], const double t[3], double w[2]) const {
    if (empty(j)) return;
    remove_forbidden_director_components(constraints_.data() + offset_[j], constraints_.data() + offset_[j + 1], L,
                                         t, w);
  }
  /// The lists: node j's constraints are constraints()[offsets()[j]] .. constraints()[offsets()[j + 1] - 1].
  const std::vector<int>& offsets() const { return offset_; }
  const std::vector<DirectorConstraint>& constraints() const { return constraints_; }

 private:
  std::vector<int> offset_{0};
  std::vector<DirectorConstraint> constraints_;
};

class Constraints {
 public:
  /// Resolves every condition's node set and elements (InputError for unknown names) on the owned DG copies.
  Constraints(const std::vector<BoundaryCondition>& conditions, const MeshSets& sets,
              const decomposition::DistributedMesh& dm, const std::string& deck_file);

  /// How position node i = le * position_nodes + A of an owned element moves: freely, freely but on symmetry planes, with some
  /// components prescribed, or not at all.
  enum class Motion : unsigned char { free, on_planes, prescribed, held };
  Motion motion(LocalId i) const { return motion_[i]; }
  bool held(LocalId i) const { return motion_[i] == Motion::held; }
  /// The Prescribed Velocity condition that drives node i, or -1.
  int prescribing(LocalId i) const { return prescribing_[i]; }
  /// Whether component c of node i follows a velocity program.
  bool prescribed(LocalId i, int c) const { return (prescribed_components_[i] >> c) & 1; }
  /// Whether node i moves freely in component c (not held, not prescribed in c).
  bool free(LocalId i, int c) const { return !held(i) && !prescribed(i, c); }
  const PlaneLists& position_planes() const { return position_planes_; }
  // Director node j = le * director_nodes + b of an owned element.
  bool director_held(LocalId j) const { return director_held_by_[j] >= 0; }
  const DirectorConstraintLists& director_constraints() const { return director_constraints_; }
  /// The per-node arrays behind the queries above (owned position nodes; owned director nodes), for kernels.
  const std::vector<Motion>& motions() const { return motion_; }
  const std::vector<unsigned char>& prescribed_components() const { return prescribed_components_; }
  const std::vector<int>& prescribings() const { return prescribing_; }
  const std::vector<int>& director_holders() const { return director_held_by_; }

  /// Displacement, velocity and acceleration programs of Prescribed Velocity condition bc at time t.
  Vec3 prescribed_displacement(int bc, double t) const;
  Vec3 prescribed_velocity(int bc, double t) const;
  Vec3 prescribed_acceleration(int bc, double t) const;

  /// Prescribed Rotation: directors, rotations and director rates of the rotated nodes at time t
  /// (t = R(a, theta(t)) t0, Lambda = R Lambda0, T-dot = Lambda-bar^T (theta-dot a x t)).
  void apply_rotations(double t, ShellState& s) const;
  /// Records the reference directors and rotations of the rotated nodes (once, from the initial state).
  void capture_rotation_reference(const ShellState& s);
  /// Saves t, g and the rotary kinetic energy of each rotated node before a step (for its reaction work).
  void begin_step(const ShellState& s, const ShellModel& model);
  /// Adds to reaction_work the work of the support couples of the rotated nodes over the step just taken:
  /// their director force work (trapezoidal) and the rotary kinetic energy they supplied.
  void add_rotation_work(ShellState& s, const ShellModel& model) const;

  /// Per condition in deck order: its reaction force (3), then its support couple sum t x g over the director
  /// nodes it holds (3), as this rank's contributions, one per node (for an exact global sum).
  struct Contribution {
    std::vector<double> values[3];
  };
  void reaction_contributions(const ShellState& s, std::size_t bc, Contribution& force, Contribution& couple) const;

  std::size_t size() const { return conditions_.size(); }

 private:
  struct RotatedNode {
    LocalId le;
    int b, bc;
    double t0[3], L0[3][3];
    double t_prev[3], g_prev[3], kinetic_prev;  // the previous step, for the reaction work
  };
  /// InputError (collective) if every node of a Prescribed Velocity or Rotation is taken by another condition.
  void refuse_overridden_programs(const std::string& deck_file) const;

  const decomposition::DistributedMesh& dm_;
  std::vector<BoundaryCondition> conditions_;
  std::vector<CosineRamp> ramps_;            // per condition
  std::vector<int> held_by_, prescribing_;   // per owned position node: condition index or -1
  std::vector<unsigned char> prescribed_components_;  // per owned position node: bit c = component c prescribed
  std::vector<Motion> motion_;                         // per owned position node
  std::vector<int> director_held_by_;        // per owned director node: condition index or -1
  std::vector<std::uint32_t> acts_on_;       // per owned position node: bit b set if condition b acts on it
  PlaneLists position_planes_;                        // per owned position node
  DirectorConstraintLists director_constraints_;      // per owned director node
  std::vector<RotatedNode> rotated_;
};

}  // namespace shellfrac::solver
