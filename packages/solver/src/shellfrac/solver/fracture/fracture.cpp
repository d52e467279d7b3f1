#include "shellfrac/solver/fracture/fracture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/solver/fracture/cohesive_interface.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/element_inputs.hpp"
#include "shellfrac/solver/model/element_strains.hpp"
#include "shellfrac/solver/model/ghost_exchange.hpp"
#include "shellfrac/solver/model/prefetch.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

namespace {
/// The edge nodes (positions 3, directors 2, edge-local order) of local edge k of overlap element le.
disc::EdgeNodes edge_nodes(const ShellState& s, LocalId le, int k) {
  disc::EdgeNodes out;
  edge_nodes_of(kernel_view(s.x), kernel_view(s.t), le, k, out);
  return out;
}
}  // namespace

Fracture::Fracture(const FractureParams& fr, const MeshSets& sets, const ShellModel& model)
    : dm_(model.dm), interface_refs_(model.interface_refs) {
  const auto& ifs = dm_.interfaces();
  std::set<std::pair<GlobalId, int>> allowed;
  if (fr.edges != "all") allowed = sets.side_set("'Fracture->Edges'", fr.edges);
  breakable_.assign(ifs.size(), 0), cohesive_.resize(ifs.size());
  std::vector<char> scattered(ifs.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    const auto& fc = ifs[i];
    const BlockSection& a = model.sections.at(dm_.element_block(fc.minus));
    const BlockSection& b = model.sections.at(dm_.element_block(fc.plus));
    const auto &ma = a.material, &mb = b.material;
    if (fc.non_manifold || ma.cohesive_strength <= 0 || mb.cohesive_strength <= 0) continue;
    if (fr.edges != "all" && !allowed.count({dm_.element_gid(fc.minus), fc.minus_edge}) &&
        !allowed.count({dm_.element_gid(fc.plus), fc.plus_edge}))
      continue;
    // Each side's material turns the interface's one draw into its strength (theory.md §9.8); sides of different
    // sections use the mean thickness, strength and work of separation (a choice the paper leaves open, §9.2).
    breakable_[i] = 1, any = true;
    const double u = materials::unit_draw(std::uint64_t(fr.seed), std::uint64_t(fc.gid));
    const double length = 1 / interface_refs_[i].inv_he;
    const double sigma_c = 0.5 * (materials::edge_strength(ma.strength_scatter, ma.cohesive_strength, u, length) +
                                  materials::edge_strength(mb.strength_scatter, mb.cohesive_strength, u, length));
    cohesive_[i] = materials::make_cohesive_params(0.5 * (a.thickness + b.thickness), sigma_c,
                                                   0.5 * (ma.fracture_energy + mb.fracture_energy), fr.alpha1,
                                                   fr.alpha2, fr.alpha3, fr.activation_opening);
    // The crack faces touch with the stiffness of the intact interface's penalty (theory.md §9.9).
    cohesive_[i].contact_stiffness = model.interface_beta_x[i] * interface_refs_[i].inv_he;
    cohesive_[i].contact = fr.crack_face_contact;
    if (ma.strength_scatter.scattered() || mb.strength_scatter.scattered()) scattered[i] = 1;
  }
  enabled_ = parallel::any(any, dm_.comm());
  summarize_strengths(scattered);
  label_.resize(dm_.num_overlap());
  for (LocalId le = 0; le < dm_.num_overlap(); ++le) label_[le] = dm_.element_gid(le);
  if (enabled_) label_exchange_ = std::make_unique<GhostExchange>(dm_, std::initializer_list<int>{1});
}

Fracture::~Fracture() = default;

// Min, max and the exact mean of the breakable interfaces' strengths, each interface counted by its owner.
void Fracture::summarize_strengths(const std::vector<char>& scattered_here) {
  const auto& ifs = dm_.interfaces();
  std::int64_t count = 0, scattered = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::vector<ExactSum> total(1);
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (!breakable_[i] || !ifs[i].owned) continue;
    const double sigma_c = cohesive_[i].sigma_c;
    ++count, scattered += scattered_here[i], total[0].add(sigma_c);
    lo = std::min(lo, sigma_c), hi = std::max(hi, sigma_c);
  }
  ExactSum::allreduce(total, dm_.comm());
  strengths_.interfaces = parallel::sum(count, dm_.comm());
  strengths_.scattered = parallel::sum(scattered, dm_.comm());
  if (strengths_.interfaces == 0) return;
  strengths_.min = -parallel::max(-lo, dm_.comm());
  strengths_.max = parallel::max(hi, dm_.comm());
  strengths_.mean = total[0].value() / double(strengths_.interfaces);
}

double Fracture::weakest_edge_strength(const ShellModel& model, LocalId le) const {
  double weakest = 0;
  for (const auto& [i, side] : model.incident.of(le))
    if (breakable_[i]) weakest = weakest > 0 ? std::min(weakest, cohesive_[i].sigma_c) : cohesive_[i].sigma_c;
  return weakest;
}

void Fracture::nucleate(long step, double t1, ShellState& s, ShellModel& model,
                        const std::vector<disc::EdgeTractions>& edge) {
  const auto& ifs = dm_.interfaces();
  std::vector<LocalId> changed;
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (const std::size_t ahead = i + prefetch_distance; ahead < ifs.size()) {  // scattered rows (a hint)
      prefetch(edge[ifs[ahead].minus].at[ifs[ahead].minus_edge]);
      prefetch(edge[ifs[ahead].plus].at[ifs[ahead].plus_edge]);
    }
    if (!breakable_[i] || s.mode[i] != intact) continue;
    const auto& fc = ifs[i];
    double n[3][3], m[3][3];
    const auto& em = edge[fc.minus].at[fc.minus_edge];
    const auto& ep = edge[fc.plus].at[fc.plus_edge];
    if (interface_edge_tractions(model.interface_refs[i], cohesive_[i], em, ep, n, m) < 0) continue;  // cheap
    double nu[3][3];
    const disc::EdgeNodes minus = edge_nodes(s, fc.minus, fc.minus_edge), plus = edge_nodes(s, fc.plus, fc.plus_edge);
    const double fbar = interface_nucleation(model.interface_refs[i], cohesive_[i], minus.x, minus.t, plus.t, n, m, nu);
    if (fbar < 0) continue;
    if (fc.owned) log_activation(i, step, t1, fbar, minus.x, n, m, nu);
    s.mode[i] = cohesive_[i].Gamma > 0 ? cohesive : separated;
    for (int g = 0; g < 3; ++g) disc::copy3(nu[g], s.conormal.at(i, g));
    double(*offset)[6] = s.activation_offset.points_of(i);
    activation_state(model.interface_refs[i], cohesive_[i], minus.x, minus.t, plus.x, plus.t, n, m, nu, offset,
                     s.delta_max.at(i));
    // The law's energy in the same configuration (frozen: its forces are not used here), booked with the
    // penalty energy as the change of the discrete energy at activation.
    double nu_now[3][3], dmax[3];
    disc::EdgeForces on_minus, on_plus;
    std::copy(nu[0], nu[0] + 9, nu_now[0]), std::copy(s.delta_max.at(i), s.delta_max.at(i) + 3, dmax);
    const CohesiveInterfaceResult law = cohesive_interface_forces(model.interface_refs[i], cohesive_[i], minus, plus,
                                                                  offset, dmax, nu_now, on_minus, on_plus);
    *s.cohesive_energy.at(i) = law.stored, *s.cohesive_dissipation.at(i) = law.dissipated;
    *s.interface_activation_loss.at(i) += *s.penalty_energy.at(i) - law.stored - law.dissipated;
    *s.penalty_energy.at(i) = 0;
    for (const auto& [le, k] : {std::pair{fc.minus, fc.minus_edge}, std::pair{fc.plus, fc.plus_edge}})
      if (le < model.owned) model.lifted[le][k] = false, changed.push_back(le);
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (LocalId le : changed) {
    const double after = element_energy(s, model, le);
    *s.element_activation_loss.at(le) += *s.strain_energy.at(le) - after;
    *s.strain_energy.at(le) = after;
  }
}

// Stored elastic energy of owned element le in the current state (frozen plastic strains).
double Fracture::element_energy(const ShellState& s, const ShellModel& model, LocalId le) const {
  PointStrains p[disc::num_area_points];
  element_strains(model, s, le, p);
  const double zero[3] = {0, 0, 0};
  double energy = 0;
  for (int q = 0; q < disc::num_area_points; ++q) {
    const materials::PlasticState* st = model.is_plastic(le) ? &s.plastic[le * disc::num_area_points + q] : nullptr;
    energy += p[q].weight * materials::elastic_energy(model.elastic(le), p[q].eps, p[q].gam, p[q].rho,
                                                      st ? st->eps_p : zero, st ? st->gam_p : zero,
                                                      st ? st->rho_p : zero);
  }
  return energy;
}

void Fracture::restore(const ShellState& s, ShellModel& model) {
  const auto& ifs = dm_.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (s.mode[i] != intact) {  // an activated edge is lifted by neither side
      if (ifs[i].minus < model.owned) model.lifted[ifs[i].minus][ifs[i].minus_edge] = false;
      if (ifs[i].plus < model.owned) model.lifted[ifs[i].plus][ifs[i].plus_edge] = false;
    }
  fragments_at_ = -1;
  crack_log_.clear();
}

// One row of the crack log for interface i activated at t1: where it is and which terms of the equivalent
// traction made it break. The in-plane tangent at each edge point is the edge chord of the minus side made
// orthogonal to nu (a diagnostic: exact for straight edges).
void Fracture::log_activation(std::size_t i, long step, double t1, double fbar, const double xm[3][3],
                              const double n[3][3], const double m[3][3], const double nu[3][3]) {
  const auto& fc = dm_.interfaces()[i];
  const double* omega = interface_refs_[i].omega;
  double parts[5] = {0, 0, 0, 0, 0}, total = 0;
  for (int g = 0; g < 3; ++g) {
    double tau[3], tn = 0, tt = 0;
    for (int c = 0; c < 3; ++c) tau[c] = xm[1][c] - xm[0][c], tn += tau[c] * nu[g][c];
    for (int c = 0; c < 3; ++c) tau[c] -= tn * nu[g][c], tt += tau[c] * tau[c];
    for (double& c : tau) c /= std::sqrt(tt);
    double pg[5];
    materials::equivalent_traction_parts(cohesive_[i], n[g], m[g], nu[g], tau, pg);
    for (int k = 0; k < 5; ++k) parts[k] += omega[g] * pg[k], total += omega[g] * pg[k];
  }
  crack_log_.insert(crack_log_.end(), {double(step + 1), t1, double(fc.gid + 1), double(dm_.element_gid(fc.minus) + 1),
                                       double(dm_.element_gid(fc.plus) + 1), xm[2][0], xm[2][1], xm[2][2], fbar});
  for (double p : parts) crack_log_.push_back(total > 0 ? p / total : 0.0);
  crack_log_.push_back(cohesive_[i].sigma_c);
}

std::vector<std::string> Fracture::crack_event_columns() {
  return {"step",        "time",          "interface",         "element_minus",         "element_plus",
          "x",           "y",             "z",                 "fbar",                  "share_normal",
          "share_inplane_shear", "share_transverse_shear", "share_couple_normal", "share_couple_shear",
          "cohesive_strength"};
}

std::vector<std::vector<double>> Fracture::crack_events() {
  const std::size_t width = crack_event_columns().size();
  const auto all = parallel::all_gather(crack_log_, dm_.comm());
  crack_log_.clear();
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k + width <= all.size(); k += width) rows.emplace_back(all.begin() + k, all.begin() + k + width);
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return a[0] != b[0] ? a[0] < b[0] : a[2] < b[2];  // by step, then interface id
  });
  return rows;
}

// Fragments: connected components of the elements through interfaces that are not fully separated, labelled by
// their smallest element id. Each rank joins its overlap elements through its local interfaces (union-find),
// then repeats: every local piece takes the smallest label of its elements, the ghosts take their owners'
// labels; until no owned label changes on any rank. Recomputed only when the global number of separated
// interfaces has changed.
GlobalId Fracture::fragments(const ShellState& s) const {
  const auto& ifs = dm_.interfaces();
  std::int64_t separated_here = 0;
  for (std::size_t i = 0; i < ifs.size(); ++i) separated_here += ifs[i].owned && s.mode[i] == separated;
  const GlobalId count = parallel::sum(separated_here, dm_.comm());
  if (count == fragments_at_) return fragments_;
  const LocalId n = dm_.num_overlap();
  std::vector<LocalId> root(n);
  for (LocalId le = 0; le < n; ++le) root[le] = le;
  const auto find = [&](LocalId e) {
    while (root[e] != e) e = root[e] = root[root[e]];
    return e;
  };
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (s.mode[i] == separated) continue;
    const LocalId a = find(ifs[i].minus), b = find(ifs[i].plus);
    if (a != b) root[std::max(a, b)] = std::min(a, b);
  }
  for (LocalId le = 0; le < n; ++le) root[le] = find(le), label_[le] = dm_.element_gid(le);
  std::vector<double> labels(n);
  for (bool changed = true; changed;) {
    std::vector<GlobalId> smallest(n, std::numeric_limits<GlobalId>::max());
    for (LocalId le = 0; le < n; ++le) smallest[root[le]] = std::min(smallest[root[le]], label_[le]);
    bool mine = false;
    for (LocalId le = 0; le < n; ++le) {
      mine |= le < dm_.num_owned() && smallest[root[le]] != label_[le];
      label_[le] = smallest[root[le]];
      labels[le] = double(label_[le]);  // element ids are below 2^53: exact as doubles
    }
    label_exchange_->import_ghost_rows(0, {RowBuffer{labels.data(), 1}});
    for (LocalId le = dm_.num_owned(); le < n; ++le) label_[le] = static_cast<GlobalId>(labels[le]);
    changed = parallel::any(mine, dm_.comm());
  }
  std::int64_t roots = 0;
  for (LocalId le = 0; le < dm_.num_owned(); ++le) roots += label_[le] == dm_.element_gid(le);
  fragments_ = parallel::sum(roots, dm_.comm());
  fragments_at_ = count;
  return fragments_;
}

std::vector<std::vector<double>> Fracture::fragment_table(const ShellState& s, const ShellModel& model) const {
  if (enabled_) fragments(s);
  // This rank's piece of each fragment: its element count and the exact sums of m, m x, m v.
  struct Piece {
    std::int64_t elements = 0;
    std::array<ExactSum, 7> sums;
  };
  std::map<GlobalId, Piece> pieces;
  for (LocalId le = 0; le < model.owned; ++le) {
    Piece& p = pieces[enabled_ ? label_[le] : 0];
    ++p.elements;
    for (int A = 0; A < 6; ++A) {
      const double m = *model.mass.at(le, A);
      p.sums[0].add(m);
      for (int c = 0; c < 3; ++c) p.sums[1 + c].add(m * s.x.at(le, A)[c]), p.sums[4 + c].add(m * s.v.at(le, A)[c]);
    }
  }
  parallel::ByteWriter w;
  for (const auto& [label, p] : pieces) {
    w.put(std::int64_t(label)), w.put(p.elements);
    for (const auto& sum : p.sums) sum.pack(w);
  }
  const auto all = parallel::all_gather(w.buffer(), dm_.comm());
  std::map<GlobalId, Piece> fragments;
  parallel::ByteReader r(all);
  while (!r.done()) {
    Piece& f = fragments[r.get<std::int64_t>()];
    f.elements += r.get<std::int64_t>();
    for (auto& sum : f.sums) sum += ExactSum::unpack(r);
  }
  std::vector<std::vector<double>> rows;
  for (const auto& [label, f] : fragments) {
    const double m = f.sums[0].value();
    rows.push_back({double(label + 1), double(f.elements), m, f.sums[1].value() / m, f.sums[2].value() / m,
                    f.sums[3].value() / m, f.sums[4].value(), f.sums[5].value(), f.sums[6].value()});
  }
  return rows;
}

double Fracture::damage(const ShellState& s, const ShellModel& model, LocalId le) const {
  double damage = 0;
  for (const auto& [i, side] : model.incident.of(le)) {
    double d = s.mode[i] == separated ? 1.0 : 0.0;
    if (s.mode[i] == cohesive)
      for (int g = 0; g < 3; ++g)  // the strength lost, 1 - S(delta_max)/S0 (theory.md §9.2)
        d = std::max(d, std::clamp((s.delta_max.at(i)[g] - cohesive_[i].delta0) / cohesive_[i].delta_f, 0.0, 1.0));
    damage = std::max(damage, d);
  }
  return damage;
}

}  // namespace shellfrac::solver
