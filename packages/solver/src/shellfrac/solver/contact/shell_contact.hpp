#pragma once
/// \file shell_contact.hpp
/// Contact between the shells (docs/theory.md §12.5): crack faces, flaps and fragments that collide instead of
/// passing through each other. Every DG position node A of a block in contact (the "node") is pushed off the
/// nearest mid-surface of another element F of those blocks (the "face": its four linear sub-triangles) when it
/// is closer than the two half-thicknesses, g = d(x_A, F) - (h_A + h_F)/2 < 0, by the penalty force k <-g> n along
/// the direction from the face's nearest point to the node; the face's nodes take the reaction, shared by the
/// nearest point's weights. Elements that share a vertex of the mesh never contact each other (intact, they are one
/// surface; across a separated edge the crack faces meet edge-on, which is the crack-face contact of §9.9), nor do a
/// node and a face that overlap in the reference configuration (a thick shell's near neighbours).
///
/// Search: candidate lists (each node's faces within its reach plus a margin), rebuilt when a node has moved half
/// the margin; faces by a bin grid (bin_grid.hpp). Parallel: the faces of other ranks within reach of this rank's
/// nodes are a contact ghost layer, their positions exchanged every step; the reactions on another rank's faces are
/// sent to it, and every face node sums its reactions in the order of the nodes' global ids. The forces join the
/// external forces: rank- and thread-independent, bitwise, like the rest of the step.
///
/// Friction (§12.6): a node in contact also gets the Coulomb force of its slip velocity relative to the face's
/// nearest point (the face nodes' velocities weighted as the reaction), for the pair's effective mass; the face
/// takes the reaction with the same weights.
#include <string>
#include <vector>

#include "shellfrac/solver/contact/bin_grid.hpp"
#include "shellfrac/solver/input/contact_params.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

struct ShellModel;

class ShellContact {
 public:
  /// Contact of the blocks params.shells.blocks names (`block_names`: the mesh's, by block index) in a run with
  /// time step dt. InputError naming `file` for an unknown block or a penalty that makes the step unstable.
  /// Collective.
  ShellContact(const ContactParams& params, const ShellModel& model, double dt,
               const std::vector<std::string>& block_names, const std::string& file);
  bool enabled() const { return enabled_; }
  /// Adds the contact forces of state s to s.external_force (owned rows) and books the friction's dissipation over
  /// the step of length `step` that ends now.
  /// NumericalError if the contacts pile up on a node so that the step is no longer stable (theory.md §12.5).
  /// Collective.
  void add_forces(double step, ShellState& s);
  /// History columns: shell_contact_energy (the penalty energy stored now), shell_contact_nodes (the nodes in
  /// contact), and their values after the last add_forces (collective).
  std::vector<std::string> history_columns() const;
  std::vector<double> history_values() const;

 private:
  /// A face: an element of a block in contact, owned here or a contact ghost.
  struct Face {
    GlobalId gid = -1;
    LocalId local = -1;  ///< owned element's local id; -1 for a contact ghost
    int owner = 0;
    double half_thickness = 0;
    double mean_mass = 0;  ///< the mean of its position nodes' masses
    GlobalId vertex[3] = {-1, -1, -1};  ///< mesh vertices
  };
  /// A node's contact found by the last add_forces.
  struct NodeContact {
    int face = -1;  ///< index into faces_; -1: none
    int sub = 0;    ///< sub-triangle of the face
    double w[3] = {0, 0, 0};
    double normal[3] = {0, 0, 0};
    double gap = 0;
    double stiffness = 0;
    double friction[3] = {0, 0, 0};  ///< the Coulomb force on the node (theory.md §12.6)
    double dissipation = 0;          ///< what it takes over the step
  };

  struct NodeSearch;  // the per-node kernel of find_contacts

  void pack_owned_motion(const ShellState& s);
  bool moved_beyond_margin() const;
  void search();
  void describe_owned_faces();
  std::vector<Box> gather_contact_ghosts();
  void build_candidate_lists(std::vector<Box> face_boxes);
  void measure_gaps_at_search();
  void exchange_ghost_positions();
  void find_contacts(double step);
  void apply_forces(ShellState& s);
  void check_stability() const;

  const ShellModel& model_;
  bool enabled_ = false;
  std::vector<char> in_contact_;        ///< by block index
  double penalty_per_dt2_ = 0;          ///< s / dt^2
  double step_room_ = 0;                ///< (4 - (2 S_f)^2) / dt^2: what contact may add to omega^2
  double margin_ = 0;
  double tie_ = 0;                      ///< gaps this close count as equally near (theory.md §12.5)
  double max_half_thickness_ = 0;       ///< over every block in contact
  FrictionParams friction_;
  double dt_ = 0;
  std::vector<LocalId> nodes_of_;       ///< owned elements in contact (their 6 nodes are the nodes)
  std::vector<Face> faces_;             ///< owned ones first (in nodes_of_ order), then the contact ghosts
  std::vector<double> face_x_;          ///< 18 per face
  std::vector<double> face_X_;          ///< the faces' reference positions, 18 per face
  std::vector<double> face_v_;          ///< with friction: the faces' velocities, 18 per face
  std::vector<double> x_search_;        ///< every face's nodes at the last search (18 per face)
  std::vector<int> candidate_offset_{0}, candidates_;  ///< per node: face indices, ascending face gid
  std::vector<double> candidate_gap_;                  ///< the step's gap to each candidate (find_contacts)
  std::vector<double> gap_at_search_;                  ///< each candidate's gap at the search
  std::vector<double> face_bounds_;                    ///< the step's sphere and box around each face, its move
  std::vector<std::vector<LocalId>> send_;  ///< per rank: owned faces (indices into faces_) sent as its ghosts
  std::vector<int> receive_count_;          ///< per rank: the ghosts it sends
  std::vector<NodeContact> contact_;        ///< per node
  std::vector<double> bound_;               ///< per node: Gershgorin's bound of its contact stiffness over mass
  std::vector<double> reactions_;           ///< the step's reaction records on this rank's faces
  std::vector<std::size_t> order_;          ///< their summation order
  bool searched_ = false;
};

}  // namespace shellfrac::solver
