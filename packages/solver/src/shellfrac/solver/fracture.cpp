#include "shellfrac/solver/fracture.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/solver/cohesive_interface.hpp"
#include "shellfrac/solver/force_assembly.hpp"
#include "shellfrac/solver/mesh_sets.hpp"
#include "shellfrac/solver/shell_model.hpp"

namespace shellfrac::solver {

namespace {
/// The edge nodes (positions 3, directors 2, edge-local order) of local edge k of overlap element le.
void edge_nodes(const ShellState& s, LocalId le, int k, double xk[3][3], double tk[2][3]) {
  for (int j = 0; j < 3; ++j) disc::copy3(s.x.at(le, disc::edge_node(k, j)), xk[j]);
  for (int j = 0; j < 2; ++j) disc::copy3(s.t.at(le, disc::edge_node(k, j)), tk[j]);
}
}  // namespace

Fracture::Fracture(const FractureParams& fr, const MeshSets& sets, const ShellModel& model)
    : dm_(model.dm), interface_refs_(model.interface_refs) {
  const auto& ifs = dm_.interfaces();
  std::set<std::pair<GlobalId, int>> allowed;
  if (fr.edges != "all") allowed = sets.side_set("'Fracture->Edges'", fr.edges);
  breakable_.assign(ifs.size(), 0), cohesive_.resize(ifs.size());
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
    // Sides of different sections use the mean thickness, strength and work of separation (a choice the paper
    // leaves open; docs/theory.md §9.2).
    breakable_[i] = 1, any = true;
    cohesive_[i] = materials::make_cohesive_params(
        0.5 * (a.thickness + b.thickness), 0.5 * (ma.cohesive_strength + mb.cohesive_strength),
        0.5 * (ma.fracture_energy + mb.fracture_energy), fr.alpha1, fr.alpha2, fr.alpha3);
  }
  enabled_ = parallel::any(any, dm_.comm());
  if (!enabled_) return;
  std::vector<GlobalId> mine;
  for (const auto& fc : ifs)
    if (fc.owned) mine.insert(mine.end(), {fc.gid, dm_.element_gid(fc.minus), dm_.element_gid(fc.plus)});
  const auto all = parallel::all_gather(mine, dm_.comm());
  for (std::size_t k = 0; k + 2 < all.size(); k += 3) all_interfaces_.push_back({all[k], all[k + 1], all[k + 2]});
  std::sort(all_interfaces_.begin(), all_interfaces_.end());
}

void Fracture::nucleate(long step, double t1, ShellState& s, ShellModel& model, const ForceAssembly& assembly) {
  const auto& ifs = dm_.interfaces();
  const auto& edge = assembly.edge_tractions();
  std::vector<LocalId> changed;
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (!breakable_[i] || s.mode[i] != intact) continue;
    const auto& fc = ifs[i];
    double n[3][3], m[3][3];
    const auto& em = edge[fc.minus].at[fc.minus_edge];
    const auto& ep = edge[fc.plus].at[fc.plus_edge];
    if (interface_edge_tractions(model.interface_refs[i], cohesive_[i], em, ep, n, m) < 0) continue;  // cheap
    double xm[3][3], tm[2][3], xq[3][3], tq[2][3], nu[3][3];
    edge_nodes(s, fc.minus, fc.minus_edge, xm, tm);
    edge_nodes(s, fc.plus, fc.plus_edge, xq, tq);
    const double fbar = interface_nucleation(model.interface_refs[i], cohesive_[i], xm, tm, tq, n, m, nu);
    if (fbar < 0) continue;
    if (fc.owned) log_activation(i, step, t1, fbar, xm, n, m, nu);
    s.mode[i] = cohesive_[i].Gamma > 0 ? cohesive : separated;
    for (int g = 0; g < 3; ++g) {
      s.delta_max.at(i)[g] = 0;
      disc::copy3(nu[g], s.conormal.at(i, g));
    }
    *s.interface_activation_loss.at(i) += *s.penalty_energy.at(i);
    *s.penalty_energy.at(i) = 0;
    for (const auto& [le, k] : {std::pair{fc.minus, fc.minus_edge}, std::pair{fc.plus, fc.plus_edge}})
      if (le < model.owned) model.lifted[le][k] = false, changed.push_back(le);
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (LocalId le : changed) {
    const double after = element_energy(s, model, assembly, le);
    *s.element_activation_loss.at(le) += *s.strain_energy.at(le) - after;
    *s.strain_energy.at(le) = after;
  }
}

// Stored elastic energy of owned element le in the current state (frozen plastic strains).
double Fracture::element_energy(const ShellState& s, const ShellModel& model, const ForceAssembly& assembly,
                                LocalId le) const {
  PointStrains p[disc::num_area_points];
  assembly.element_strains(s, le, p);
  const double zero[3] = {0, 0, 0};
  double energy = 0;
  for (int q = 0; q < disc::num_area_points; ++q) {
    const materials::PlasticState* st = model.is_plastic[le] ? &s.plastic[le * disc::num_area_points + q] : nullptr;
    energy += p[q].weight * materials::elastic_energy(model.elastic[le], p[q].eps, p[q].gam, p[q].rho,
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
}

std::vector<std::string> Fracture::crack_event_columns() {
  return {"step",        "time",          "interface",         "element_minus",         "element_plus",
          "x",           "y",             "z",                 "fbar",                  "share_normal",
          "share_inplane_shear", "share_transverse_shear", "share_couple_normal", "share_couple_shear"};
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

// Fragments: connected components of the elements through interfaces that are not fully separated, by
// union-find over the global interface list (the same on every rank); recomputed only when the global number
// of separated interfaces has changed.
GlobalId Fracture::fragments(const ShellState& s) const {
  std::vector<GlobalId> mine;
  const auto& ifs = dm_.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned && s.mode[i] == separated) mine.push_back(ifs[i].gid);
  const GlobalId count = parallel::sum(static_cast<std::int64_t>(mine.size()), dm_.comm());
  if (count == fragments_at_) return fragments_;
  auto cut = parallel::all_gather(mine, dm_.comm());
  std::sort(cut.begin(), cut.end());
  const GlobalId ne = dm_.num_global_elements();
  fragment_root_.resize(ne);
  for (GlobalId e = 0; e < ne; ++e) fragment_root_[e] = e;
  const auto find = [&](GlobalId e) {
    while (fragment_root_[e] != e) e = fragment_root_[e] = fragment_root_[fragment_root_[e]];
    return e;
  };
  for (const auto& [gid, a, b] : all_interfaces_) {
    if (std::binary_search(cut.begin(), cut.end(), gid)) continue;
    const GlobalId ra = find(a), rb = find(b);
    if (ra != rb) fragment_root_[std::max(ra, rb)] = std::min(ra, rb);  // the root is the smallest id
  }
  fragments_ = 0;
  for (GlobalId e = 0; e < ne; ++e) {
    fragment_root_[e] = find(e);
    fragments_ += fragment_root_[e] == e;
  }
  fragments_at_ = count;
  return fragments_;
}

std::vector<std::vector<double>> Fracture::fragment_table(const ShellState& s, const ShellModel& model) const {
  if (enabled_) fragments(s);
  constexpr int nv = 9;  // element gid, fragment root, m, m x (3), m v (3)
  std::vector<double> mine(model.owned * nv, 0.0);
  for (LocalId le = 0; le < model.owned; ++le) {
    double* r = &mine[le * nv];
    const GlobalId gid = dm_.element_gid(le);
    r[0] = double(gid), r[1] = enabled_ ? double(fragment_root_[gid]) : 0.0;
    for (int A = 0; A < 6; ++A) {
      const double m = *model.mass.at(le, A);
      r[2] += m;
      for (int c = 0; c < 3; ++c) r[3 + c] += m * s.x.at(le, A)[c], r[6 + c] += m * s.v.at(le, A)[c];
    }
  }
  const auto all = parallel::all_gather(mine, dm_.comm());
  std::vector<std::size_t> order(all.size() / nv);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a * nv] < all[b * nv]; });
  std::map<GlobalId, std::vector<double>> frag;  // root -> {elements, m, m x, m v}
  for (std::size_t i : order) {
    auto& f = frag[GlobalId(all[i * nv + 1])];
    f.resize(8, 0.0);
    f[0] += 1;
    for (int k = 0; k < 7; ++k) f[1 + k] += all[i * nv + 2 + k];
  }
  std::vector<std::vector<double>> rows;
  for (const auto& [root, f] : frag)
    rows.push_back({double(root + 1), f[0], f[1], f[2] / f[1], f[3] / f[1], f[4] / f[1], f[5], f[6], f[7]});
  return rows;
}

double Fracture::damage(const ShellState& s, const ShellModel& model, LocalId le) const {
  double damage = 0;
  for (const auto& [i, side] : model.incident[le]) {
    double d = s.mode[i] == separated ? 1.0 : 0.0;
    if (s.mode[i] == cohesive)
      for (int g = 0; g < 3; ++g) d = std::max(d, std::min(1.0, s.delta_max.at(i)[g] / cohesive_[i].delta_f));
    damage = std::max(damage, d);
  }
  return damage;
}

}  // namespace shellfrac::solver
