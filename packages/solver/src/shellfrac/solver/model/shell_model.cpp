#include "shellfrac/solver/model/shell_model.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/lumped_mass.hpp"
#include "shellfrac/disc/stable_time_step.hpp"

namespace shellfrac::solver {

namespace {

/// Reference positions and directors of overlap element le.
void reference_nodes(const decomposition::DistributedMesh& dm, LocalId le, double X[6][3], double T[3][3]) {
  for (int A = 0; A < 6; ++A)
    for (int c = 0; c < 3; ++c) X[A][c] = dm.node_coords(le, A)[c];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) T[a][c] = dm.reference_director(le, a)[c];
}

/// Whether the neighbour across local edge k of `le` numbers the shared edge's first vertex as its own first
/// (the matched edge parameter is then s, else 1 - s).
bool same_edge_direction(const decomposition::DistributedMesh& dm, LocalId le, int k, LocalId nb, int kk) {
  return dm.mesh_node(le, disc::edge_node(k, 0)) == dm.mesh_node(nb, disc::edge_node(kk, 0));
}

/// The density factor of an element with stable step dt_e (before the safety factor): 1, or the factor that
/// brings S_f dt_e up to the target step (theory.md §8.1), with a margin of 1e-12 so that the scaled step is not
/// below the target by round-off. The run's step S_f min(scaled dt_e) is then the target (or more, if no
/// element needed scaling).
double density_factor(const TimeParams& tp, double dt_e) {
  const double reached = tp.safety_factor * dt_e;
  if (tp.target_time_step <= 0 || reached >= tp.target_time_step) return 1.0;
  const double r = tp.target_time_step / reached;
  return r * r * (1 + 1e-12);
}

/// The owned elements' share of the mass scaling, summed over the ranks at the end.
class MassScalingTally {
 public:
  /// Element le with the (unscaled) lumped masses `masses` gets the density factor `factor`.
  void add(LocalId le, double factor, const double* masses) {
    for (int A = 0; A < position_nodes; ++A) physical_.add(masses[A]);
    if (factor == 1.0) return;
    for (int A = 0; A < position_nodes; ++A) added_.add((factor - 1) * masses[A]);
    ++elements_;
    if (factor > max_factor_) max_factor_ = factor, max_le_ = le;
  }
  MassScaling global_result(const decomposition::DistributedMesh& dm) {
    std::vector<ExactSum> sums{physical_, added_};
    ExactSum::allreduce(sums, dm.comm());
    MassScaling r;
    r.physical_mass = sums[0].value(), r.added_mass = sums[1].value();
    r.elements = parallel::sum(elements_, dm.comm());
    r.max_factor = parallel::max(max_factor_, dm.comm());
    const bool mine = max_le_ >= 0 && max_factor_ == r.max_factor;
    const double gid = mine ? double(dm.element_gid(max_le_)) : std::numeric_limits<double>::max();
    r.max_element = r.elements > 0 ? static_cast<GlobalId>(-parallel::max(-gid, dm.comm())) : -1;
    double c[3] = {0, 0, 0}, all[3];
    if (mine && dm.element_gid(max_le_) == r.max_element)
      for (int A = 0; A < 3; ++A)
        for (int k = 0; k < 3; ++k) c[k] += dm.node_coords(max_le_, A)[k] / 3;
    SHELLFRAC_REQUIRE(MPI_Allreduce(c, all, 3, MPI_DOUBLE, MPI_SUM, dm.comm()) == MPI_SUCCESS,
                      "MPI_Allreduce of the mass scaling failed");  // one rank contributes, the others add 0
    r.max_centroid = {all[0], all[1], all[2]};
    return r;
  }

 private:
  ExactSum physical_, added_;
  std::int64_t elements_ = 0;
  double max_factor_ = 1;
  LocalId max_le_ = -1;
};

/// InputError if the mass scaling adds more than Maximum Added Mass Fraction of the mass (unless forced).
/// Collective (all ranks decide alike).
void check_added_mass(const ModelParams& params, const MassScaling& ms, const ShellModel& model) {
  const TimeParams& time = params.time;
  if (ms.elements == 0 || time.force_mass_scaling) return;
  const double fraction = ms.added_mass / ms.physical_mass;
  SHELLFRAC_INPUT_REQUIRE(fraction <= time.max_added_mass_fraction,
                          params.deck_file << ": 'Time Integration->Target Time Step' = " << time.target_time_step
                                    << " adds " << fraction * 100 << " % of the mass (" << ms.elements
                                    << " elements scaled, the largest factor " << ms.max_factor << " at "
                                    << model.element_name(ms.max_element) << "), more than 'Maximum Added Mass Fraction' = "
                                    << time.max_added_mass_fraction
                                    << "; lower the target, remesh the small elements, or raise the maximum (or "
                                       "set 'Force Mass Scaling')");
}

/// InputError naming the element when the P2 map of an element is folded (orientation ratio <= 1e-3 at an area
/// point: a mid-side node far outside its triangle; docs/theory.md §1.4). The smallest such element id on any
/// rank is named, with its worst ratio. Collective.
void check_not_folded(const ShellModel& model, const std::string& mesh_name) {
  const auto& dm = model.dm;
  constexpr double folded = 1e-3;
  const double none = std::numeric_limits<double>::max();
  double worst = none, first = none;  // the smallest folded element id (as a double: exact below 2^53)
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    double Xe[6][3], Te[3][3];
    reference_nodes(dm, le, Xe, Te);
    double r = std::numeric_limits<double>::max();
    for (int q = 0; q < disc::tri6_rule.num_points; ++q)
      r = std::min(r, disc::orientation_ratio(Xe, disc::tri6_rule.xi[q][0], disc::tri6_rule.xi[q][1]));
    if (r <= folded && double(dm.element_gid(le)) < first) first = double(dm.element_gid(le)), worst = r;
  }
  const double bad = -parallel::max(-first, dm.comm());
  if (bad == none) return;
  const double ratio = -parallel::max(-(first == bad ? worst : none), dm.comm());
  SHELLFRAC_INPUT_REQUIRE(false, mesh_name << ": " << model.element_name(GlobalId(bad)) << " is folded: at one of its quadrature "
                                           << "points the area Jacobian is " << ratio << " times that of its vertex "
                                           << "triangle (it must be positive; a mid-side node lies far outside the "
                                           << "triangle?); fix the mesh");
}

}  // namespace

std::vector<BlockSection> block_sections(const std::map<std::string, materials::BlockParams>& blocks,
                                         const std::map<std::string, materials::MaterialParams>& materials,
                                         const std::vector<std::string>& block_names) {
  std::vector<BlockSection> out;
  for (const auto& name : block_names) {
    const auto& block = blocks.at(name);
    out.push_back({block.thickness, materials.at(block.material)});
  }
  return out;
}

std::string ShellModel::element_name(GlobalId gid) const {
  if (!file_ids) return mesh::element_label(gid, gid + 1);
  // The rank that owns it knows its file id; the others contribute 0 (file ids are positive).
  std::int64_t mine = 0, id = 0;
  for (LocalId le = 0; le < owned && mine == 0; ++le)
    if (dm.element_gid(le) == gid) mine = owned_file_ids[static_cast<std::size_t>(le)];
  SHELLFRAC_REQUIRE(MPI_Allreduce(&mine, &id, 1, MPI_INT64_T, MPI_MAX, dm.comm()) == MPI_SUCCESS,
                    "MPI_Allreduce of an element's file id failed");
  return mesh::element_label(gid, id > 0 ? id : gid + 1);
}

ShellModel::ShellModel(const decomposition::DistributedMesh& d, const ModelParams& params,
                       const std::vector<BlockSection>& s)
    : dm(d), owned(d.num_owned()), overlap(d.num_overlap()), sections(s), file_ids(!params.element_ids.empty()) {
  SHELLFRAC_REQUIRE(dm.nodes_per_element() == 6, "the DG shell needs TRI6 elements");
  if (file_ids)
    for (LocalId le = 0; le < owned; ++le)
      owned_file_ids.push_back(params.element_ids.ids.at(static_cast<std::size_t>(dm.element_gid(le))));
  check_not_folded(*this, params.mesh_label);
  X = PositionRowsView(dm.node_coords_data(), overlap);
  // Point laws of the blocks.
  block_elastic.resize(sections.size()), block_plastic.resize(sections.size()), block_is_plastic.assign(sections.size(), 0);
  for (std::size_t b = 0; b < sections.size(); ++b) {
    const auto& m = sections[b].material;
    const double h = sections[b].thickness;
    block_elastic[b] = materials::make_elastic_section(m.youngs_modulus, m.poissons_ratio, h);
    if (!m.plastic()) continue;
    block_is_plastic[b] = 1;
    block_plastic[b] = materials::make_plastic_section(m.youngs_modulus, m.poissons_ratio, h, m.yield_stress,
                                                       m.hardening_modulus, m.shear_in_yield);
  }
  for (LocalId le = 0; le < owned; ++le) any_plastic = any_plastic || is_plastic(le);
  any_plastic = parallel::any(any_plastic, dm.comm());  // the same on every rank (collectives depend on it)
  // Non-manifold interfaces are penalized but not lifted (a kink has no single neighbour).
  std::set<std::pair<LocalId, int>> not_lifted;
  for (const auto& fc : dm.interfaces())
    if (fc.non_manifold) not_lifted.insert({fc.minus, fc.minus_edge}), not_lifted.insert({fc.plus, fc.plus_edge});
  // Element reference data, lifted edges, masses (selectively scaled), the stable step.
  element_refs.resize(owned), lifted.resize(owned), mass.assign(owned), inertia.assign(owned);
  MassScalingTally scaling;
  TimeStepTally steps;
  const double rotary_scale = params.time.rotary_inertia_scale;
  stable_dt = std::numeric_limits<double>::max();
  for (LocalId le = 0; le < owned; ++le) {
    double Xe[6][3], Te[3][3];
    reference_nodes(dm, le, Xe, Te);
    bool same[3];
    for (int k = 0; k < 3; ++k) {
      const LocalId nb = dm.neighbor(le, k);
      lifted[le][k] = nb >= 0 && !not_lifted.count({le, k});
      same[k] = nb >= 0 && same_edge_direction(dm, le, k, nb, dm.neighbor_edge(le, k));
    }
    const BlockSection& sc = sections.at(dm.element_block(le));
    const auto& m = sc.material;
    const double h = sc.thickness;
    const auto& discretization = params.discretization;
    disc::build_dg_element_ref(Xe, Te, same, element_refs[le], discretization.strains,
                               discretization.membrane_remainder(Xe, h));
    disc::StableStepParams sp{m.youngs_modulus, m.poissons_ratio, m.density, h};
    sp.cx = params.discretization.cx, sp.cT = params.discretization.cT, sp.rotary_scale = rotary_scale;
    const double dt_e = disc::element_stable_dt(sp, disc::characteristic_length(Xe));
    const double factor = density_factor(params.time, dt_e);
    steps.add(le, dt_e);
    disc::hrz_lumped_mass(Xe, m.density * h, mass.at(le));
    disc::hrz_rotary_inertia(Xe, rotary_scale * m.density * h * h * h / 12, inertia.at(le));
    scaling.add(le, factor, mass.at(le));
    if (factor != 1.0) {  // every frequency scales as 1/sqrt(density)
      for (int A = 0; A < position_nodes; ++A) *mass.at(le, A) *= factor;
      for (int b = 0; b < director_nodes; ++b) *inertia.at(le, b) *= factor;
    }
    stable_dt = std::min(stable_dt, dt_e * std::sqrt(factor));
  }
  stable_dt = -parallel::max(-stable_dt, dm.comm());  // global minimum (exact, rank-count independent)
  mass_scaling = scaling.global_result(dm);
  time_step_survey = steps.global_result(dm);
  check_added_mass(params, mass_scaling, *this);
  build_interfaces(params.discretization);
}

// Interfaces: reference edge data of the minus side, built with the same routine as the elements' own data;
// the penalty constants of paper eq. 42 (sides of different blocks use the mean of their constants, a choice
// the paper leaves open).
void ShellModel::build_interfaces(const DiscretizationParams& discretization) {
  const auto& ifs = dm.interfaces();
  const auto beta = [&](LocalId le, bool director) {
    const BlockSection& sc = sections.at(dm.element_block(le));
    const double E = sc.material.youngs_modulus, h = sc.thickness;
    return director ? discretization.cT * E * h * h * h / 12 : discretization.cx * E * h;
  };
  interface_refs.resize(ifs.size()), interface_beta_x.resize(ifs.size()), interface_beta_t.resize(ifs.size());
  incident.offset.assign(std::size_t(owned) + 1, 0);
  for (const auto& fc : ifs) {
    if (fc.minus < owned) ++incident.offset[std::size_t(fc.minus) + 1];
    if (fc.plus < owned) ++incident.offset[std::size_t(fc.plus) + 1];
  }
  for (LocalId le = 0; le < owned; ++le) incident.offset[std::size_t(le) + 1] += incident.offset[std::size_t(le)];
  incident.entries.resize(std::size_t(incident.offset.back()));
  std::vector<int> filled(incident.offset.begin(), incident.offset.end() - 1);
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    const auto& fc = ifs[i];
    double Xe[6][3], Te[3][3];
    reference_nodes(dm, fc.minus, Xe, Te);
    bool same[3] = {false, false, false};
    same[fc.minus_edge] = same_edge_direction(dm, fc.minus, fc.minus_edge, fc.plus, fc.plus_edge);
    disc::DgElementRef r;
    disc::build_dg_element_ref(Xe, Te, same, r);
    disc::build_dg_interface_ref(r.edge[fc.minus_edge], interface_refs[i]);
    interface_beta_x[i] = 0.5 * (beta(fc.minus, false) + beta(fc.plus, false));
    interface_beta_t[i] = 0.5 * (beta(fc.minus, true) + beta(fc.plus, true));
    if (fc.minus < owned) incident.entries[std::size_t(filled[std::size_t(fc.minus)]++)] = {int(i), 0};
    if (fc.plus < owned) incident.entries[std::size_t(filled[std::size_t(fc.plus)]++)] = {int(i), 1};
  }
}

const materials::ElasticSection& ShellModel::elastic(LocalId le) const { return block_elastic[dm.element_block(le)]; }
bool ShellModel::is_plastic(LocalId le) const { return block_is_plastic[dm.element_block(le)] != 0; }

double ShellModel::bytes() const {
  return sizeof(disc::DgElementRef) * double(element_refs.size()) +
         sizeof(double) * double(mass.size() + inertia.size()) +
         sizeof(disc::DgInterfaceRef) * double(interface_refs.size());
}

}  // namespace shellfrac::solver
