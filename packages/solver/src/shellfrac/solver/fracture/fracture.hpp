#pragma once
/// \file fracture.hpp
/// The fracture bookkeeping (paper §3, §5.1; docs/theory.md §9): which interfaces may break and their cohesive
/// laws, the nucleation check after each step and the activation of edges, the crack log, and the fragments
/// (connected pieces through edges that are not fully separated). The cohesive forces themselves are computed
/// by the interface kernel (cohesive_interface.hpp) within the force assembly (step/force_assembly.hpp).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/dg_interface.hpp"
#include "shellfrac/materials/cohesive_law.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"
#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

class GhostExchange;
class MeshSets;
struct ShellModel;

class Fracture {
 public:
  /// An interface may break when it is interior and manifold, both sides' materials have a Cohesive Strength
  /// > 0, and it is in params.edges ('all' or a side set: InputError if the mesh has none of that name).
  /// Collective.
  Fracture(const FractureParams& params, const MeshSets& sets, const ShellModel& model);
  ~Fracture();
  Fracture(const Fracture&) = delete;
  Fracture& operator=(const Fracture&) = delete;

  /// Whether any interface of the mesh may break (the same on every rank).
  bool enabled() const { return enabled_; }
  /// The cohesive law of each local interface (meaningful where breakable).
  const std::vector<materials::CohesiveParams>& cohesive_params() const { return cohesive_; }
  /// The breakable interfaces' strengths, the same on every rank.
  const materials::StrengthSummary& strengths() const { return strengths_; }
  /// The strength of the weakest breakable edge of owned element le (0 if none may break).
  double weakest_edge_strength(const ShellModel& model, LocalId le) const;

  /// Nucleation and activation after the forces at t1 of step `step` (docs/theory.md §9.5-9.6). Both ranks that
  /// hold an interface decide from the same numbers (the ghosts' edge tractions come with the flux exchange),
  /// so the decision needs no message. An activated interface leaves the lifting of both sides; its penalty
  /// energy and the change of its neighbours' strain energy are booked as activation loss.
  /// `edge`: the projected edge tractions of every overlap element from the last force computation.
  void nucleate(long step, double t1, ShellState& s, ShellModel& model, const std::vector<disc::EdgeTractions>& edge);
  /// After a restart: the liftings of the activated interfaces switched off, the fragment cache and the crack
  /// log cleared.
  void restore(const ShellState& s, ShellModel& model);

  /// Crack log rows of the activations not yet reported, gathered, sorted by step and interface id (the same
  /// on every rank and any rank count). Collective.
  std::vector<std::vector<double>> crack_events();
  static std::vector<std::string> crack_event_columns();
  /// Number of fragments; recomputes them when the global number of separated interfaces changed: connected
  /// components through the interfaces not separated, labelled by their smallest element id (local union-find,
  /// then the labels of the ghosts from their owners until no label changes; no rank sees the whole mesh).
  /// Collective.
  GlobalId fragments(const ShellState& s) const;
  /// Fragment of overlap element le: the smallest element id of its piece (after fragments()).
  GlobalId fragment_of(LocalId le) const { return label_[le]; }
  /// One row per fragment, in increasing fragment id: {fragment id (smallest element id + 1), elements, mass,
  /// centre of mass x/y/z, momentum x/y/z}, as exact sums (rank-count independent). Each rank sends only its
  /// pieces of fragments. Collective; the rows are the same on every rank.
  std::vector<std::vector<double>> fragment_table(const ShellState& s, const ShellModel& model) const;
  /// Damage of owned element le: the largest (delta_max - delta0) / delta_f over its edges' points, 1 if separated.
  double damage(const ShellState& s, const ShellModel& model, LocalId le) const;

 private:
  void log_activation(std::size_t i, long step, double t1, double fbar, const double xm[3][3], const double n[3][3],
                      const double m[3][3], const double nu[3][3]);
  void summarize_strengths(const std::vector<char>& scattered);
  double element_energy(const ShellState& s, const ShellModel& model, LocalId le) const;

  const decomposition::DistributedMesh& dm_;
  const std::vector<disc::DgInterfaceRef>& interface_refs_;
  bool enabled_ = false;
  std::vector<char> breakable_;  // per local interface
  std::vector<materials::CohesiveParams> cohesive_;
  materials::StrengthSummary strengths_;
  std::vector<double> crack_log_;  // activations of owned interfaces not yet reported, one row each
  std::unique_ptr<GhostExchange> label_exchange_;  // the fragment labels of the ghosts (fracture runs)
  mutable GlobalId fragments_at_ = -1;  // the number of separated interfaces the cache belongs to
  mutable GlobalId fragments_ = 0;
  mutable std::vector<GlobalId> label_;  // per overlap element: its fragment (smallest element id)
};

}  // namespace shellfrac::solver
