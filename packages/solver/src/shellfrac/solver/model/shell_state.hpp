#pragma once
/// \file shell_state.hpp
/// The evolving state of the DG shell on one rank (docs/theory.md §1.1, §7): flat arrays of fixed-width rows,
/// one row per element (or per interface), and the one list of the fields a checkpoint holds. Checkpoint,
/// restore and the memory count all iterate that list, so they cannot drift apart.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"

namespace shellfrac::solver {

/// What the rows of a row array are: one per element (owned, or the overlap with the ghost layer) or one per
/// interface (the local interfaces of docs/parallel.md).
struct PerElement {};
struct PerInterface {};

/// Rows of Points x Values doubles: row r (an element or an interface, as Over says), point p (a node, an edge or
/// an edge point) holds Values doubles at (r * Points + p) * Values. Point index i = r * Points + p addresses one
/// point directly.
template <class Over, int Points, int Values>
class Rows {
 public:
  using over = Over;
  static constexpr int points = Points, values = Values, width = Points * Values;
  void assign(LocalId rows, double value = 0.0) { v_.assign(std::size_t(rows) * width, value); }
  LocalId rows() const { return static_cast<LocalId>(v_.size() / width); }
  /// The values of point p of row r.
  double* at(LocalId r, int p = 0) { return v_.data() + (std::size_t(r) * Points + p) * Values; }
  const double* at(LocalId r, int p = 0) const { return v_.data() + (std::size_t(r) * Points + p) * Values; }
  /// Row r as Points points of Values values (an argument `double values[][Values]` of a point-wise function).
  double (*points_of(LocalId r))[Values] { return reinterpret_cast<double(*)[Values]>(at(r)); }
  /// The values of point i = r * Points + p.
  double* point(LocalId i) { return v_.data() + std::size_t(i) * Values; }
  const double* point(LocalId i) const { return v_.data() + std::size_t(i) * Values; }
  double* data() { return v_.data(); }
  const double* data() const { return v_.data(); }
  std::size_t size() const { return v_.size(); }
  std::vector<double>& vector() { return v_; }
  const std::vector<double>& vector() const { return v_; }

 private:
  std::vector<double> v_;
};

template <int Points, int Values>
using ElementRows = Rows<PerElement, Points, Values>;
template <int Points, int Values>
using InterfaceRows = Rows<PerInterface, Points, Values>;

constexpr int position_nodes = 6;  ///< P2 positions: 3 vertices, then the mid-sides of edges 1-2, 2-3, 3-1
constexpr int director_nodes = 3;  ///< P1 directors: the vertices
constexpr int edge_points = 3;     ///< the edge points of an interface (disc::num_edge_points)
using PositionRows = ElementRows<position_nodes, 3>;  ///< a 3-vector per position node (positions, velocities, forces)
using DirectorRows = ElementRows<director_nodes, 3>;  ///< a 3-vector per director node (directors, director forces)
using RotationRows = ElementRows<director_nodes, 9>;  ///< the rotation Lambda per director node, row-major 3 x 3
using RateRows = ElementRows<director_nodes, 2>;  ///< the two material components of a director rate per director node
using PositionNodeScalars = ElementRows<position_nodes, 1>;  ///< a value per position node (the lumped mass)
using DirectorNodeScalars = ElementRows<director_nodes, 1>;  ///< a value per director node (the rotary inertia)
using Scalars = ElementRows<1, 1>;                            ///< one value per element
using InterfaceScalars = InterfaceRows<1, 1>;                 ///< one value per interface
constexpr int position_values = PositionRows::width;  ///< 18
constexpr int director_values = DirectorRows::width;  ///< 9

/// Position rows held elsewhere, read only (the reference positions, which the distributed mesh keeps).
class PositionRowsView {
 public:
  PositionRowsView() = default;
  PositionRowsView(const double* data, LocalId rows) : data_(data), rows_(rows) {}
  static constexpr int width = PositionRows::width;
  LocalId rows() const { return rows_; }
  const double* at(LocalId r, int p = 0) const { return data_ + (std::size_t(r) * position_nodes + p) * 3; }
  const double* point(LocalId i) const { return data_ + std::size_t(i) * 3; }
  const double* data() const { return data_; }
  std::size_t size() const { return std::size_t(rows_) * width; }

 private:
  const double* data_ = nullptr;
  LocalId rows_ = 0;
};

/// 3 x 3 matrix from / to 9 row-major values.
inline void load_matrix(const double* v, double L[3][3]) {
  for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = v[i];
}
inline void store_matrix(const double L[3][3], double* v) {
  for (int i = 0; i < 9; ++i) v[i] = L[i / 3][i % 3];
}

/// State of an interface element (paper §5.1): intact (penalty), cohesive (activated, docs/theory.md §9.6), or
/// fully separated.
enum InterfaceMode : int { intact = 0, cohesive = 1, separated = 2 };

/// The motion of a rigid body (contact/rigid_bodies.hpp), the same on every rank: where its Point is, its velocity
/// and acceleration, and the contact force the shells exert on it. Between the predictor and the corrector of a
/// step, v holds the predictor's half-step velocity.
struct RigidBodyState {
  std::string name;  ///< the deck's name of the body (checkpoint keys, history columns)
  Vec3 x{0, 0, 0}, v{0, 0, 0}, a{0, 0, 0}, force{0, 0, 0};
};

/// Where a static relaxation stands (theory.md §7.5), global scalars the same on every rank, checkpointed so that
/// a restart continues it bitwise.
struct RelaxationProgress {
  double kinetic_before = 0;  ///< the global kinetic energy after the previous step
  double best_residual = std::numeric_limits<double>::infinity();  ///< the smallest residual at a kinetic-energy peak
  double peaks_since_best = 0;  ///< peaks since the residual last fell below stall_drop of the best
  double u_low = 0, u_high = 0;  ///< the smallest and largest displacement norm at those peaks
  /// Calls visit(key, value) for each scalar with its checkpoint key.
  template <class Self, class Visit>
  static void visit(Self& r, Visit&& visit) {
    visit("relaxation kinetic before", r.kinetic_before), visit("relaxation best residual", r.best_residual);
    visit("relaxation peaks since best", r.peaks_since_best);
    visit("relaxation displacement low", r.u_low), visit("relaxation displacement high", r.u_high);
  }
};

/// Everything that evolves in time. Positions and directors cover the overlap (owned elements, then the ghost
/// layer, whose rows the ghost exchange fills); the other element rows cover the owned elements; interface rows
/// cover every local interface.
struct ShellState {
  double time = 0;
  long step = 0;
  RelaxationProgress relaxation;
  // Element rows.
  PositionRows x;                ///< current positions (overlap)
  DirectorRows t;                ///< current directors (overlap)
  PositionRows v, a;             ///< velocities, accelerations
  RotationRows rotation;         ///< Lambda: maps E3 to the director (paper A.1)
  RateRows director_rate;        ///< material director rates T-dot (Lambda-bar^T t-dot)
  RateRows director_acceleration;  ///< T-ddot
  PositionRows internal_force;   ///< f: internal forces on the position nodes
  DirectorRows director_force;   ///< g: spatial internal director moments
  PositionRows external_force;   ///< f_ext at the current time
  DirectorRows external_director_force;  ///< g_ext: external director forces (edge moments) at the current time
  PositionRows reaction;         ///< support reactions R = m a - f_ext + f on constrained components
  Scalars strain_energy;         ///< U_el per element (frozen plastic strains)
  Scalars external_work, reaction_work, damping_dissipation;  ///< accumulated work accounts per element
  Scalars plastic_work;          ///< accumulated plastic work per element (docs/theory.md §4.2)
  Scalars element_activation_loss;  ///< strain energy released by switching liftings off (docs/theory.md §9.6)
  Scalars friction_dissipation;  ///< accumulated energy taken by friction at the element's nodes (theory.md §12.6)
  /// Committed plastic state at each area point of each owned element (empty without plasticity).
  std::vector<materials::PlasticState> plastic;
  // Interface rows.
  std::vector<int> mode;         ///< InterfaceMode
  InterfaceRows<edge_points, 1> delta_max;  ///< largest effective opening reached at each edge point (theory.md §9.2)
  InterfaceRows<edge_points, 3> conormal;   ///< last current co-normal at each edge point (docs/theory.md §9.1)
  /// Jumps less the law's opening at activation at each edge point, in the interface frame (theory.md §9.6).
  InterfaceRows<edge_points, 6> activation_offset;
  InterfaceScalars cohesive_energy, cohesive_dissipation;  ///< stored and dissipated cohesive energy
  InterfaceScalars interface_activation_loss;  ///< penalty energy released at activation
  InterfaceScalars penalty_energy;             ///< U_stab of an intact interface
  /// The rigid bodies, in deck order (none without Contact->Rigid Bodies).
  std::vector<RigidBodyState> bodies;

  /// Calls visit(name, rows) for each element field a checkpoint holds, in the checkpoint's column order
  /// (state: a ShellState or a const ShellState).
  template <class State, class Visit>
  static void visit_element_fields(State& s, Visit&& visit) {
    visit("x", s.x), visit("v", s.v), visit("a", s.a), visit("f", s.internal_force);
    visit("fext", s.external_force), visit("reaction", s.reaction), visit("t", s.t), visit("g", s.director_force);
    visit("rotation", s.rotation), visit("director_rate", s.director_rate);
    visit("director_acceleration", s.director_acceleration), visit("strain_energy", s.strain_energy);
    visit("external_work", s.external_work), visit("reaction_work", s.reaction_work);
    visit("damping_dissipation", s.damping_dissipation), visit("plastic_work", s.plastic_work);
    visit("activation_loss", s.element_activation_loss), visit("gext", s.external_director_force);
    visit("friction_dissipation", s.friction_dissipation);
  }
  /// The same for the interface fields (mode is a std::vector<int>).
  template <class State, class Visit>
  static void visit_interface_fields(State& s, Visit&& visit) {
    visit("mode", s.mode), visit("delta_max", s.delta_max), visit("conormal", s.conormal);
    visit("activation_offset", s.activation_offset);
    visit("cohesive_energy", s.cohesive_energy), visit("cohesive_dissipation", s.cohesive_dissipation);
    visit("activation_loss", s.interface_activation_loss), visit("penalty_energy", s.penalty_energy);
  }
  /// Bytes held by every field above, summed.
  double bytes() const;
};

/// Values of one plastic state in a checkpoint row: eps_p (3), rho_p (3), alpha, gam_p (2).
constexpr int plastic_state_values = 9;
void pack_plastic_state(const materials::PlasticState& s, double out[plastic_state_values]);
void unpack_plastic_state(const double in[plastic_state_values], materials::PlasticState& s);

}  // namespace shellfrac::solver
