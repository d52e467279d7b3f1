#include "shellfrac/solver/contact/shell_contact.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/contact/closest_point.hpp"
#include "shellfrac/solver/contact/contact_penalty.hpp"
#include "shellfrac/solver/contact/coulomb_friction.hpp"
#include "shellfrac/solver/model/kernel_views.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

namespace {

constexpr int face_values = position_nodes * 3;  // 18: a face's six nodes
/// The four linear sub-triangles of a TRI6 (nodes 3, 4, 5 on edges 0-1, 1-2, 2-0).
constexpr int sub_triangles[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
/// A reaction record: face gid, node gid, face node, force (3), stiffness share k w (for the stability bound).
constexpr int reaction_values = 7;



/// The nearest point of face `fx` (18 values) to p: its sub-triangle, weights, point and distance.
struct FacePoint {
  int sub = 0;
  double w[3] = {0, 0, 0}, y[3] = {0, 0, 0}, distance = 0;
};

FacePoint nearest_point_of_face(const double* p, const double* fx) {
  FacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int sub = 0; sub < 4; ++sub) {
    const double* a = fx + 3 * sub_triangles[sub][0];
    const double* b = fx + 3 * sub_triangles[sub][1];
    const double* c = fx + 3 * sub_triangles[sub][2];
    const TrianglePoint t = closest_point_on_triangle(p, a, b, c);
    double y[3], d2 = 0;
    for (int i = 0; i < 3; ++i) y[i] = t.w[0] * a[i] + t.w[1] * b[i] + t.w[2] * c[i], d2 += (p[i] - y[i]) * (p[i] - y[i]);
    const double d = std::sqrt(d2);
    if (d < best.distance) {
      best.sub = sub, best.distance = d;
      for (int i = 0; i < 3; ++i) best.w[i] = t.w[i], best.y[i] = y[i];
    }
  }
  return best;
}

/// The squared distance between the centroids of the vertices of two faces (18 values each).
double centroid_distance2(const double* f, const double* g) {
  double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double d = (f[i] + f[3 + i] + f[6 + i] - g[i] - g[3 + i] - g[6 + i]) / 3;
    d2 += d * d;
  }
  return d2;
}

/// A face's bounds (bound_values numbers): a sphere around its six nodes (centre, radius) and their box (lo, hi).
/// Both contain the sub-triangles, which lie in the nodes' convex hull.
constexpr int bound_values = 10;

/// The contact faces as the kernels see them, owned ones first, then the contact ghosts (ShellContact::faces_): a
/// face's six position nodes (positions, velocities), its bounds, and its bounds with how far it has moved since
/// the search.
struct PerContactFace {};
using FaceNodesView = RowsView<PerContactFace, position_nodes, 3, const double>;
using FaceBoundsView = RowsView<PerContactFace, 1, bound_values, const double>;
using FaceBoundsAndMoveView = RowsView<PerContactFace, 1, bound_values + 1, double>;
FaceNodesView face_nodes(const std::vector<double>& values) { return {values.data(), values.size() / face_values}; }

/// How far the farthest of a face's six nodes (18 values) has moved from where it was (18 values).
double largest_move(const double* fx, const double* before) {
  double d2 = 0;
  for (int A = 0; A < position_nodes; ++A) {
    const double d[3] = {fx[3 * A] - before[3 * A], fx[3 * A + 1] - before[3 * A + 1], fx[3 * A + 2] - before[3 * A + 2]};
    d2 = std::max(d2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  return std::sqrt(d2);
}

void write_face_bounds(const double* fx, double* out) {
  for (int i = 0; i < 3; ++i) {
    double c = 0, lo = fx[i], hi = fx[i];
    for (int A = 0; A < position_nodes; ++A) c += fx[3 * A + i], lo = std::min(lo, fx[3 * A + i]), hi = std::max(hi, fx[3 * A + i]);
    out[i] = c / position_nodes, out[4 + i] = lo, out[7 + i] = hi;
  }
  double r2 = 0;
  for (int A = 0; A < position_nodes; ++A) {
    const double d[3] = {fx[3 * A] - out[0], fx[3 * A + 1] - out[1], fx[3 * A + 2] - out[2]};
    r2 = std::max(r2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  out[3] = std::sqrt(r2);
}

/// A lower bound of the distance from p to a face, from its bounds: the larger of the sphere's and the box's.
double distance_bound(const double* p, const double* bounds) {
  const double d[3] = {p[0] - bounds[0], p[1] - bounds[1], p[2] - bounds[2]};
  double box2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double out = std::max({bounds[4 + i] - p[i], 0.0, p[i] - bounds[7 + i]});
    box2 += out * out;
  }
  return std::max(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - bounds[3], std::sqrt(box2));
}

}  // namespace

ShellContact::ShellContact(const ContactParams& params, const ShellModel& model, double dt,
                           const std::vector<std::string>& block_names, const std::string& file)
    : model_(model), in_contact_(block_names.size(), 0) {
  const ShellContactParams& p = params.shells;
  const bool all = p.blocks.size() == 1 && p.blocks[0] == "all";
  for (const std::string& name : p.blocks) {
    if (all) break;
    const auto it = std::find(block_names.begin(), block_names.end(), name);
    std::ostringstream known;
    for (const auto& b : block_names) known << " '" << b << "'";
    SHELLFRAC_INPUT_REQUIRE(it != block_names.end(), file << ": 'Contact->Shells->Blocks' names the block '" << name
                                                          << "', which the mesh does not have (its blocks:"
                                                          << known.str() << "; or {all})");
    in_contact_[std::size_t(it - block_names.begin())] = 1;
  }
  if (all) std::fill(in_contact_.begin(), in_contact_.end(), 1);
  enabled_ = std::find(in_contact_.begin(), in_contact_.end(), 1) != in_contact_.end();
  if (!enabled_) return;
  check_contact_penalty(p.penalty_scale, dt, model.stable_dt, file, "Contact->Shells->Penalty Scale");
  penalty_per_dt2_ = p.penalty_scale / (dt * dt);
  friction_ = p.friction, dt_ = dt;
  const double sf = dt / model.stable_dt;
  step_room_ = (4 - 4 * sf * sf) / (dt * dt);
  for (std::size_t b = 0; b < in_contact_.size(); ++b)
    if (in_contact_[b]) max_half_thickness_ = std::max(max_half_thickness_, 0.5 * model.sections[b].thickness);
  margin_ = p.search_margin > 0 ? p.search_margin : 2 * max_half_thickness_;
  tie_ = 0.01 * max_half_thickness_;
  for (LocalId le = 0; le < model.owned; ++le)
    if (in_contact_[std::size_t(model.dm.element_block(le))]) nodes_of_.push_back(le);
  contact_.resize(nodes_of_.size() * position_nodes);
  bound_.resize(nodes_of_.size() * position_nodes);
}

void ShellContact::add_forces(double step, ShellState& s) {
  if (!enabled_) return;
  pack_owned_motion(s);
  if (!searched_ || moved_beyond_margin())
    search();
  else
    exchange_ghost_positions();
  find_contacts(step);
  apply_forces(s);
}

void ShellContact::pack_owned_motion(const ShellState& s) {
  face_x_.resize(std::max(face_x_.size(), nodes_of_.size() * face_values));
  for (std::size_t i = 0; i < nodes_of_.size(); ++i)
    std::copy(s.x.at(nodes_of_[i], 0), s.x.at(nodes_of_[i], 0) + face_values, face_x_.begin() + i * face_values);
  if (!friction_.enabled()) return;
  face_v_.resize(std::max(face_v_.size(), nodes_of_.size() * face_values));
  for (std::size_t i = 0; i < nodes_of_.size(); ++i)
    std::copy(s.v.at(nodes_of_[i], 0), s.v.at(nodes_of_[i], 0) + face_values, face_v_.begin() + i * face_values);
}

bool ShellContact::moved_beyond_margin() const {
  bool moved = false;
  for (std::size_t i = 0; i < nodes_of_.size() && !moved; ++i)
    moved = largest_move(&face_x_[i * face_values], &x_search_[i * face_values]) > 0.5 * margin_;
  return parallel::any(moved, model_.dm.comm());
}

// The candidate lists (theory.md §12.5). A node can only meet a face within its reach c_A + c_F of it; while no node
// has moved more than half the margin since the search, no face has come nearer to a node than it was at the search
// less the margin, so a face whose box (grown by c_F) is farther than c_A + margin from the node at the search cannot
// be in contact before the next search. The same argument, with this rank's nodes' box, picks the other ranks' faces
// this rank needs: the contact ghosts. The reach also covers the tie band of find_contacts (faces within `tie` of the
// nearest contact's gap), so that the face chosen is a function of the faces near the node only.
void ShellContact::search() {
  describe_owned_faces();
  build_candidate_lists(gather_contact_ghosts());
  measure_gaps_at_search();
  searched_ = true;
}

// The owned faces in nodes_of_ order: ids, thickness, mean node mass, vertices and reference positions.
void ShellContact::describe_owned_faces() {
  const auto& dm = model_.dm;
  const std::size_t owned_faces = nodes_of_.size();
  faces_.resize(owned_faces);
  for (std::size_t i = 0; i < owned_faces; ++i) {
    const LocalId le = nodes_of_[i];
    Face& f = faces_[i];
    f.gid = dm.element_gid(le), f.local = le, f.owner = dm.rank();
    f.half_thickness = 0.5 * model_.sections[std::size_t(dm.element_block(le))].thickness;
    f.mean_mass = 0;
    for (int A = 0; A < position_nodes; ++A) f.mean_mass += *model_.mass.at(le, A) / position_nodes;
    for (int v = 0; v < 3; ++v) f.vertex[v] = dm.mesh_node(le, v);
  }
  face_X_.resize(owned_faces * face_values);
  for (std::size_t i = 0; i < owned_faces; ++i)
    std::copy(model_.X.at(nodes_of_[i]), model_.X.at(nodes_of_[i]) + face_values, face_X_.begin() + std::ptrdiff_t(i * face_values));
}

// The contact ghosts: every rank's reach (the box of its nodes grown by the largest c_A, the margin and the tie
// band) from O(P) numbers, each owned face that overlaps another rank's reach sent to it, the ghosts' positions
// received. Returns every face's box (owned, then ghosts) grown by its half thickness.
std::vector<Box> ShellContact::gather_contact_ghosts() {
  const auto& dm = model_.dm;
  const int P = dm.num_ranks(), me = dm.rank();
  const std::size_t owned_faces = nodes_of_.size();
  std::vector<double> mine(7, 0.0);  // lo, hi, then 1 (0: no nodes here)
  if (owned_faces > 0) {
    const Box b = Box::around(face_x_.data(), int(owned_faces * position_nodes)).inflated(max_half_thickness_ + margin_ + tie_);
    for (std::size_t c = 0; c < 3; ++c) mine[c] = b.lo[c], mine[3 + c] = b.hi[c];
    mine[6] = 1;
  }
  const std::vector<double> reach = parallel::all_gather(mine, dm.comm());
  std::vector<Box> face_boxes(owned_faces);
  for (std::size_t i = 0; i < owned_faces; ++i)
    face_boxes[i] = Box::around(&face_x_[i * face_values], position_nodes).inflated(faces_[i].half_thickness);
  send_.assign(std::size_t(P), {});
  std::vector<std::vector<double>> send_faces(static_cast<std::size_t>(P));
  for (int q = 0; q < P; ++q) {
    if (q == me || reach[7 * std::size_t(q) + 6] == 0) continue;
    Box r;
    for (int c = 0; c < 3; ++c) r.lo[c] = reach[7 * std::size_t(q) + std::size_t(c)], r.hi[c] = reach[7 * std::size_t(q) + 3 + std::size_t(c)];
    for (std::size_t i = 0; i < owned_faces; ++i) {
      if (!face_boxes[i].overlaps(r)) continue;
      const Face& f = faces_[i];
      send_[std::size_t(q)].push_back(LocalId(i));
      std::vector<double>& out = send_faces[std::size_t(q)];
      out.insert(out.end(), {double(f.gid), f.half_thickness, f.mean_mass, double(f.vertex[0]), double(f.vertex[1]),
                             double(f.vertex[2]), double(me)});
      out.insert(out.end(), face_X_.begin() + std::ptrdiff_t(i * face_values),
                 face_X_.begin() + std::ptrdiff_t((i + 1) * face_values));
    }
  }
  const std::vector<double> ghosts = parallel::all_to_all(send_faces, dm.comm());
  for (std::size_t k = 0; k < ghosts.size(); k += 7 + face_values) {
    Face f;
    f.gid = GlobalId(ghosts[k]), f.half_thickness = ghosts[k + 1], f.mean_mass = ghosts[k + 2];
    for (int v = 0; v < 3; ++v) f.vertex[v] = GlobalId(ghosts[k + 3 + std::size_t(v)]);
    f.owner = int(ghosts[k + 6]);
    faces_.push_back(f);
    face_X_.insert(face_X_.end(), ghosts.begin() + std::ptrdiff_t(k + 7), ghosts.begin() + std::ptrdiff_t(k + 7 + face_values));
  }
  face_x_.resize(faces_.size() * face_values);
  if (friction_.enabled()) face_v_.resize(faces_.size() * face_values);
  exchange_ghost_positions();
  x_search_ = face_x_;
  for (std::size_t i = owned_faces; i < faces_.size(); ++i)
    face_boxes.push_back(Box::around(&face_x_[i * face_values], position_nodes).inflated(faces_[i].half_thickness));
  return face_boxes;
}

// Each owned node's candidate faces (a Kokkos kernel: each iteration fills its own node's list only), ascending
// face gid: the faces whose boxes come within its reach, less those sharing a vertex with its element and those
// overlapping it in the reference configuration.
void ShellContact::build_candidate_lists(std::vector<Box> face_boxes) {
  const BinGrid grid(std::move(face_boxes), margin_ + 2 * max_half_thickness_);
  const std::size_t nodes = nodes_of_.size() * position_nodes;
  std::vector<std::vector<int>> lists(nodes);
  std::vector<int>* list_of = lists.data();
  const BinGrid* bins = &grid;  // read only: its queries are safe from any thread
  const Face* faces = faces_.data();
  const FaceNodesView x = face_nodes(face_x_), X = face_nodes(face_X_);
  // The faces' bounds in the reference configuration, for the overlap test.
  std::vector<double> reference_bounds(faces_.size() * bound_values);
  for (std::size_t j = 0; j < faces_.size(); ++j) write_face_bounds(&face_X_[j * face_values], &reference_bounds[j * bound_values]);
  const FaceBoundsView X_bounds(reference_bounds.data(), faces_.size());
  const double node_reach = margin_ + tie_;  // the tie band too: every face within it of a contact is a candidate
  static const std::string label_contact_candidates("shellfrac::ContactCandidates");
  Kokkos::parallel_for(label_contact_candidates, KernelRange(0, nodes), [=](const std::size_t k) {
    const Face& own = faces[k / position_nodes];
    const Box q = Box::around(x.point(LocalId(k)), 1).inflated(own.half_thickness + node_reach);
    std::vector<int>& list = list_of[k];
    for (int j : bins->overlapping(q)) {
      const Face& f = faces[j];
      bool shares_vertex = false;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) shares_vertex = shares_vertex || own.vertex[a] == f.vertex[b];
      if (shares_vertex) continue;
      // Shells that overlap in the reference configuration (a thick shell's neighbours beyond the vertex ring,
      // parts placed inside each other) never contact: the pair is the shell itself, not two surfaces meeting.
      const double overlap = own.half_thickness + f.half_thickness;
      if (distance_bound(X.point(LocalId(k)), X_bounds.at(j)) < overlap * (1 + 1e-9) &&  // the bound allowed its round-off
          nearest_point_of_face(X.point(LocalId(k)), X.at(j)).distance < overlap)
        continue;
      list.push_back(j);
    }
    std::sort(list.begin(), list.end(), [&](int a, int b) { return faces[a].gid < faces[b].gid; });
  });
  candidate_offset_.assign(1, 0);
  candidates_.clear();
  for (const auto& list : lists) {
    candidates_.insert(candidates_.end(), list.begin(), list.end());
    candidate_offset_.push_back(int(candidates_.size()));
  }
  candidate_gap_.resize(candidates_.size());
}

// Each candidate's gap at the search: find_contacts need not measure a face that cannot have come near enough
// since (its gap now is at least this less how far the node and the face's nodes have moved).
void ShellContact::measure_gaps_at_search() {
  gap_at_search_.resize(candidates_.size());
  double* gap_at_search = gap_at_search_.data();
  const int* offset = candidate_offset_.data();
  const int* candidates = candidates_.data();
  const Face* faces = faces_.data();
  const FaceNodesView x = face_nodes(face_x_);
  static const std::string label_contact_gaps_at_search("shellfrac::ContactGapsAtSearch");
  Kokkos::parallel_for(label_contact_gaps_at_search, KernelRange(0, nodes_of_.size() * position_nodes),
                       [=](const std::size_t k) {
                         const Face& own = faces[k / position_nodes];
                         for (int n = offset[k]; n < offset[k + 1]; ++n) {
                           const int j = candidates[n];
                           gap_at_search[n] = nearest_point_of_face(x.point(LocalId(k)), x.at(j)).distance -
                                              (own.half_thickness + faces[j].half_thickness);
                         }
                       });
}

// The ghosts' positions (and, with friction, velocities), in the order of send_.
void ShellContact::exchange_ghost_positions() {
  const int P = model_.dm.num_ranks();
  const bool velocities = friction_.enabled();
  std::vector<std::vector<double>> send(static_cast<std::size_t>(P));
  for (int q = 0; q < P; ++q)
    for (LocalId i : send_[std::size_t(q)]) {
      std::vector<double>& out = send[std::size_t(q)];
      out.insert(out.end(), face_x_.begin() + std::ptrdiff_t(i) * face_values,
                 face_x_.begin() + std::ptrdiff_t(i + 1) * face_values);
      if (velocities)
        out.insert(out.end(), face_v_.begin() + std::ptrdiff_t(i) * face_values,
                   face_v_.begin() + std::ptrdiff_t(i + 1) * face_values);
    }
  const std::vector<double> in = parallel::all_to_all(send, model_.dm.comm());
  const std::size_t record = velocities ? 2 * face_values : face_values, first = nodes_of_.size() * face_values;
  for (std::size_t g = 0; g * record < in.size(); ++g) {
    const auto from = in.begin() + std::ptrdiff_t(g * record);
    std::copy(from, from + face_values, face_x_.begin() + std::ptrdiff_t(first + g * face_values));
    if (velocities) std::copy(from + face_values, from + 2 * face_values, face_v_.begin() + std::ptrdiff_t(first + g * face_values));
  }
}

/// The contact of each owned node (find_contacts): the gaps to its candidates, the face chosen, the contact's normal,
/// stiffness and friction. Reads the faces and candidates of the last search; writes the node's own entries only.
struct ShellContact::NodeSearch {
  const Face* faces;
  FaceNodesView x, v, at_search;          // the faces' nodes now, their velocities (friction), at the search
  const int *offset, *candidates;         // per node: its candidates' range, and the faces
  double* gaps;                           // per candidate: the step's gap
  const double* gap_at_search;            // per candidate
  ConstViewOf<PositionNodeScalars> mass;  // the owned nodes' masses
  const LocalId* element;                 // per owned face: its element
  FaceBoundsAndMoveView bounds;           // per face: its bounds now and how far it has moved since the search
  NodeContact* out;
  double penalty, tie, dt, step;
  FrictionParams friction;

  NodeSearch(ShellContact& c, double step_length)
      : faces(c.faces_.data()), x(face_nodes(c.face_x_)), v(face_nodes(c.face_v_)), at_search(face_nodes(c.x_search_)),
        offset(c.candidate_offset_.data()), candidates(c.candidates_.data()), gaps(c.candidate_gap_.data()),
        gap_at_search(c.gap_at_search_.data()), mass(kernel_view(c.model_.mass)), element(c.nodes_of_.data()),
        bounds(c.face_bounds_.data(), c.faces_.size()), out(c.contact_.data()), penalty(c.penalty_per_dt2_),
        tie(c.tie_), dt(c.dt_), step(step_length), friction(c.friction_) {}

  void operator()(const std::size_t node) const {
    const LocalId k = LocalId(node);
    const std::size_t e = node / position_nodes;
    const Face& own = faces[e];
    const double nearest = measure_gaps(k, own);
    out[k] = NodeContact{};
    if (!(nearest < 0)) return;
    NodeContact best = choose_in_tie_band(k, LocalId(e), nearest);
    if (!(best.gap < 0)) return;  // the face chosen in the tie band is not touched: no force (never a pull)
    set_normal(x.point(k), best);
    // k = s m_A mbar_F / ((mbar_A + mbar_F) dt^2), mbar the elements' mean node masses: the same k / m_A on every node
    // of an element, half the wall's between equal elements, and a heavy element's nodes do not press a light one's
    // harder than it can take (theory.md §12.5).
    const double mA = mass(element[e] * position_nodes + k % position_nodes);
    const double mF = faces[best.face].mean_mass;
    best.stiffness = penalty * mA * mF / (own.mean_mass + mF);
    if (friction.enabled()) add_friction(k, mA, mF, best);
    out[k] = best;
  }

  // The gap to each candidate, and the nearest. Only gaps below the tie band's upper end (nearest + tie with
  // nearest < 0) can matter, so a face whose gap is bounded from below by more than twice the band (room for
  // round-off) keeps the bound as its gap: the same faces are chosen, with the same gaps, as if every face were
  // measured. The bounds, cheapest first: the gap at the search less how far the node and the face have moved
  // since; the face's sphere and box now.
  double measure_gaps(LocalId k, const Face& own) const {
    const double *p = x.point(k), *q = at_search.point(k);
    const double moved = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    double nearest = std::numeric_limits<double>::infinity();
    for (int n = offset[k]; n < offset[k + 1]; ++n) {
      const int j = candidates[n];
      const double* b = bounds.at(j);
      const double since_search = gap_at_search[n] - moved - b[bound_values];
      if (since_search > 2 * tie) {
        gaps[n] = since_search;
      } else {
        const double reach = own.half_thickness + faces[j].half_thickness;
        const double bound = distance_bound(p, b) - reach;
        gaps[n] = bound > 2 * tie ? bound : nearest_point_of_face(p, x.at(j)).distance - reach;
      }
      nearest = std::min(nearest, gaps[n]);
    }
    return nearest;
  }

  // Among the faces within `tie` of the nearest gap, the one whose centre is nearest to the node's own element's.
  NodeContact choose_in_tie_band(LocalId k, LocalId e, double nearest) const {
    NodeContact best;
    double best_centre = std::numeric_limits<double>::infinity();
    for (int n = offset[k]; n < offset[k + 1]; ++n) {
      if (gaps[n] > nearest + tie) continue;
      const int j = candidates[n];
      const double centre = centroid_distance2(x.at(e), x.at(j));
      if (centre < best_centre) best_centre = centre, best.face = j, best.gap = gaps[n];
    }
    return best;
  }

  // The nearest point of the chosen face to node p: its sub-triangle and weights, and the contact normal from it to
  // the node (the sub-triangle's normal if the node is on the face's mid-surface).
  void set_normal(const double* p, NodeContact& best) const {
    const FacePoint best_point = nearest_point_of_face(p, x.at(best.face));
    best.sub = best_point.sub;
    for (int i = 0; i < 3; ++i) best.w[i] = best_point.w[i];
    if (best_point.distance > 0) {
      for (int i = 0; i < 3; ++i) best.normal[i] = (p[i] - best_point.y[i]) / best_point.distance;
      return;
    }
    const int* corner = sub_triangles[best.sub];
    const double *a = &x(best.face, corner[0], 0), *b = &x(best.face, corner[1], 0);
    const double* c = &x(best.face, corner[2], 0);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double nrm[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int i = 0; i < 3; ++i) best.normal[i] = l > 0 ? nrm[i] / l : (i == 2 ? 1.0 : 0.0);
  }

  // The slip of the node against the face's nearest point, whose velocity is the face nodes' weighted as the
  // reaction; the pair's effective mass 1 / (1/m_A + sum w_j^2 / mbar_F) stops it in one step (eq. 12.6b).
  void add_friction(LocalId k, double mA, double mF, NodeContact& best) const {
    double slip[3], w2 = 0;
    for (int i = 0; i < 3; ++i) slip[i] = v.point(k)[i];
    for (int j = 0; j < 3; ++j) {
      const double* vj = &v(best.face, sub_triangles[best.sub][j], 0);
      for (int i = 0; i < 3; ++i) slip[i] -= best.w[j] * vj[i];
      w2 += best.w[j] * best.w[j];
    }
    const double m_eff = 1 / (1 / mA + w2 / mF);
    coulomb_friction(friction, best.normal, slip, -best.stiffness * best.gap, m_eff, dt, best.friction);
    best.dissipation = friction_dissipation(best.friction, slip, step);
  }
};

// Per node (a Kokkos kernel: each iteration writes its own node's result only). The face is the nearest one, except
// that among the faces within `tie` of the nearest gap the one whose centre is nearest to the node's own element's
// wins (theory.md §12.5): where the node meets a vertex or an edge of the other surface, every DG copy of that vertex
// is equally near, and the rule gives each element's nodes the element opposite, instead of piling every node on the
// copy of the lowest id. A function of the set of faces within reach, so of neither the search's timing nor the ranks.
void ShellContact::find_contacts(const double step) {
  face_bounds_.resize(faces_.size() * (bound_values + 1));
  const FaceBoundsAndMoveView bounds(face_bounds_.data(), faces_.size());
  const FaceNodesView x = face_nodes(face_x_), at_search = face_nodes(x_search_);
  static const std::string label_contact_face_bounds("shellfrac::ContactFaceBounds");
  Kokkos::parallel_for(label_contact_face_bounds, KernelRange(0, faces_.size()), [=](const std::size_t j) {
    double* b = bounds.at(LocalId(j));
    write_face_bounds(x.at(LocalId(j)), b);
    b[bound_values] = largest_move(x.at(LocalId(j)), at_search.at(LocalId(j)));
  });
  static const std::string label_shell_contact("shellfrac::ShellContact");
  Kokkos::parallel_for(label_shell_contact, KernelRange(0, contact_.size()), NodeSearch(*this, step));
}

// The forces: each node's own first, then the reactions on each face node in the order of (face gid, node gid, face
// node), whichever rank computed them. The stability bound per node is Gershgorin's on M^-1 K (theory.md §12.5).
void ShellContact::apply_forces(ShellState& s) {
  PositionRows& fext = s.external_force;
  const auto& dm = model_.dm;
  const int P = dm.num_ranks();
  std::vector<std::vector<double>> send(static_cast<std::size_t>(P));
  reactions_.clear();
  std::fill(bound_.begin(), bound_.end(), 0.0);
  for (std::size_t k = 0; k < contact_.size(); ++k) {
    const NodeContact& c = contact_[k];
    if (c.face < 0) continue;
    const LocalId le = nodes_of_[k / position_nodes];
    const int A = int(k % position_nodes);
    const double f = -c.stiffness * c.gap;
    const double force[3] = {f * c.normal[0] + c.friction[0], f * c.normal[1] + c.friction[1],
                             f * c.normal[2] + c.friction[2]};
    double* fe = fext.at(le, A);
    for (int i = 0; i < 3; ++i) fe[i] += force[i];
    *s.friction_dissipation.at(le) += c.dissipation;
    bound_[k] += 2 * c.stiffness / *model_.mass.at(le, A);
    const Face& face = faces_[std::size_t(c.face)];
    std::vector<double>& to = face.local >= 0 ? reactions_ : send[std::size_t(face.owner)];
    for (int j = 0; j < 3; ++j)
      to.insert(to.end(), {double(face.gid), double(dm.dg_node_gid(le, A)), double(sub_triangles[c.sub][j]),
                           -c.w[j] * force[0], -c.w[j] * force[1], -c.w[j] * force[2],
                           c.w[j] * c.stiffness});
  }
  const std::vector<double> received = parallel::all_to_all(send, dm.comm());
  reactions_.insert(reactions_.end(), received.begin(), received.end());
  const std::size_t n = reactions_.size() / reaction_values;
  order_.resize(n);
  for (std::size_t r = 0; r < n; ++r) order_[r] = r;
  const double* R = reactions_.data();
  std::sort(order_.begin(), order_.end(), [R](std::size_t a, std::size_t b) {
    const double* x = R + a * reaction_values;
    const double* y = R + b * reaction_values;
    return std::lexicographical_compare(x, x + 3, y, y + 3);
  });
  for (std::size_t r : order_) {
    const double* rec = R + r * reaction_values;
    const LocalId le = dm.local_id(GlobalId(rec[0]));
    const int node = int(rec[2]);
    double* fe = fext.at(le, node);
    for (int i = 0; i < 3; ++i) fe[i] += rec[3 + i];
    const std::size_t slot = std::size_t(std::lower_bound(nodes_of_.begin(), nodes_of_.end(), le) - nodes_of_.begin());
    bound_[slot * position_nodes + std::size_t(node)] += 2 * rec[6] / *model_.mass.at(le, node);
  }
  check_stability();
}

void ShellContact::check_stability() const {
  double worst = 0;
  for (double b : bound_) worst = std::max(worst, b);
  worst = parallel::max(worst, model_.dm.comm());
  if (worst < step_room_) return;
  GlobalId where = std::numeric_limits<GlobalId>::max();
  for (std::size_t k = 0; k < bound_.size(); ++k)
    if (bound_[k] == worst) where = std::min(where, model_.dm.element_gid(nodes_of_[k / position_nodes]));
  MPI_Allreduce(MPI_IN_PLACE, &where, 1, MPI_INT64_T, MPI_MIN, model_.dm.comm());
  std::ostringstream os;
  os << "shell contact: the contacts on " << model_.element_name(where) << " pile up so that the step is unstable "
     << "(their stiffness adds " << worst / step_room_ << " of what the time step leaves free, theory.md §12.5); "
     << "lower 'Contact->Shells->Penalty Scale' or the 'Time Integration->Safety Factor'";
  throw NumericalError(os.str());
}

std::vector<std::string> ShellContact::history_columns() const {
  if (!enabled_) return {};
  return {"shell_contact_energy", "shell_contact_nodes"};
}

std::vector<double> ShellContact::history_values() const {
  if (!enabled_) return {};
  ExactSum energy, nodes;
  for (const NodeContact& c : contact_)
    if (c.face >= 0) energy.add(0.5 * c.stiffness * c.gap * c.gap), nodes.add(1);
  std::vector<ExactSum> sums{energy, nodes};
  ExactSum::allreduce(sums, model_.dm.comm());
  return {sums[0].value(), sums[1].value()};
}

}  // namespace shellfrac::solver
