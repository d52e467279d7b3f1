#include "shellfrac/solver/step/force_assembly.hpp"

#include <type_traits>
#include <utility>

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/dg_interface.hpp"
#include "shellfrac/disc/element_lanes.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/solver/fracture/cohesive_interface.hpp"
#include "shellfrac/solver/model/element_inputs.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

namespace {

constexpr int nq = disc::num_area_points;
constexpr int state_channel = 0, flux_channel = 1;

/// The doubles of rows that are structs of doubles only, as the ghost exchange sends them, and how many a row has.
template <class Row>
double* values_of(std::vector<Row>& rows) {
  static_assert(std::is_trivially_copyable_v<Row> && sizeof(Row) % sizeof(double) == 0, "a row of doubles only");
  return reinterpret_cast<double*>(rows.data());
}
template <class Row>
constexpr int values_per_row = int(sizeof(Row) / sizeof(double));

/// Adds forces on the nodes of local edge k of element le (edge-local order) to its force rows f, g.
KOKKOS_INLINE_FUNCTION void add_edge_forces(const disc::EdgeForces& in, LocalId le, int k, const PositionView& f,
                                            const DirectorView& g) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) f(le, disc::edge_node(k, j), c) += in.f[j][c];
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) g(le, disc::edge_node(k, j), c) += in.g[j][c];
}

}  // namespace

ForceAssembly::ForceAssembly(const ShellModel& model, bool edge_tractions, PhaseTimes& times)
    : model_(model),
      times_(times),
      exchange_(model.dm, {PositionRows::width + DirectorRows::width,
                           values_per_row<LiftingFluxes> + (edge_tractions ? values_per_row<disc::EdgeTractions> : 0)}) {
  flux_.assign(std::size_t(model.overlap), LiftingFluxes{});
  if (edge_tractions) edge_tractions_.assign(model.overlap, disc::EdgeTractions{});
  interface_force_.assign(model.dm.interfaces().size(), InterfaceForces{});
  plastic_work_increment_.assign(model.owned, 0.0), return_failed_.assign(model.owned, 0);
}

void ForceAssembly::exchange_state(ShellState& s) {
  ScopedTimer timer(times_.exchange);
  exchange_.import_ghost_rows(state_channel, {{s.x.data(), PositionRows::width}, {s.t.data(), DirectorRows::width}});
}

void ForceAssembly::compute_forces(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive) {
  element_kernel(s);
  {
    ScopedTimer timer(times_.exchange);
    if (edge_tractions_.empty())
      exchange_.import_ghost_rows(flux_channel, {{values_of(flux_), values_per_row<LiftingFluxes>}});
    else
      exchange_.import_ghost_rows(flux_channel, {{values_of(flux_), values_per_row<LiftingFluxes>},
                                                 {values_of(edge_tractions_), values_per_row<disc::EdgeTractions>}});
  }
  interface_kernel(s, cohesive);
  gather(s);
}

namespace {

using disc::Batch;
namespace lanes = disc::lanes;

/// Lane `lane` of a batch's elastic sections <- an element's.
KOKKOS_INLINE_FUNCTION void load_lane(materials::ElasticSectionOf<Batch>& b, const materials::ElasticSection& s,
                                      int lane) {
  b.Dn.set(lane, s.Dn), b.Dm.set(lane, s.Dm), b.Ds.set(lane, s.Ds), b.nu.set(lane, s.nu);
}

/// The element kernel (docs/theory.md §5.4) over the owned elements, batch_width consecutive elements at a time in
/// lock-step (disc/lanes.hpp; docs/performance.md, "The batched element kernel"). A batch runs the same templated
/// code as one element, on Batch numbers: each element's arithmetic is the same sequence of IEEE operations in a
/// batch as on its own, so the results do not depend on which elements share a batch (that is, on the
/// partition). The last, incomplete batch and a batch whose elements differ in their membrane treatment run
/// element by element. A batch of plastic elements tests its trial states at once and runs the return map lane by
/// lane only where a point yields; a batch that mixes elastic and plastic elements calls each lane's own law.
struct ElementForcesKernel {
  ConstPositionView x;
  ConstDirectorView t;
  PositionView f;
  DirectorView g;
  ViewOf<Scalars> strain_energy;
  KernelView<LiftingFluxes> fluxes;
  KernelView<disc::EdgeTractions> tractions;
  bool edge_tractions;
  KernelView<const disc::DgElementRef> refs;
  KernelView<const std::array<bool, 3>> lifted;
  KernelView<const int> block;
  KernelView<const materials::ElasticSection> elastic_section;
  KernelView<const materials::PlasticSection> plastic_section;
  KernelView<const char> block_is_plastic;
  KernelView<materials::PlasticState> plastic;
  KernelView<double> plastic_work;
  KernelView<int> return_failed;
  NeighborViews nb;
  LocalId owned;

  /// The point law of element le at area point q: elastic, or the return map of resultant plasticity from the
  /// state of the last step to the new one in place (each element reads and writes only its own points), adding
  /// its plastic work to `work` and a failed return to `failed`. Returns the stored energy per unit area.
  KOKKOS_INLINE_FUNCTION double point_law(LocalId le, int q, const double eps[3], const double gam[2],
                                          const double rho[3], double N[3], double Q[2], double M[3], double& work,
                                          int& failed) const {
    const int blk = block(le);
    if (!block_is_plastic(blk)) {
      const materials::ElasticSection& sc = elastic_section(blk);
      materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
      return materials::elastic_energy(sc, eps, gam, rho);
    }
    const materials::PlasticSection& ps = plastic_section(blk);
    materials::PlasticState& st = plastic(le * nq + q);
    const auto r = materials::resultant_return_map(ps, eps, gam, rho, st, st, N, Q, M);
    work += refs(le).wj0[q] * r.plastic_work;
    failed |= r.converged ? 0 : 1;
    return materials::elastic_energy(ps.elastic, eps, gam, rho, st.eps_p, st.gam_p, st.rho_p);
  }

  /// Writes the plastic work and the return-map flag of element le (plastic blocks only).
  KOKKOS_INLINE_FUNCTION void store_plastic(LocalId le, double work, int failed) const {
    if (block_is_plastic(block(le))) plastic_work(le) = work, return_failed(le) = failed;
  }

  /// Writes element le's forces on its own nodes and its lifting fluxes.
  KOKKOS_INLINE_FUNCTION void store_forces(LocalId le, const disc::DgElementForces& out) const {
    for (int A = 0; A < position_nodes; ++A)
      for (int c = 0; c < 3; ++c) f(le, A, c) = out.f[A][c];
    for (int a = 0; a < director_nodes; ++a)
      for (int c = 0; c < 3; ++c) g(le, a, c) = out.g[a][c];
    for (int k = 0; k < 3; ++k) fluxes(le).across[k] = out.neighbour[k];
  }

  /// One element on its own.
  KOKKOS_INLINE_FUNCTION void one_element(LocalId le) const {
    disc::DgElementNodes in;
    element_inputs(nb, x, t, lifted(le), le, in);
    disc::DgElementForces out;
    double work = 0;
    int failed = 0;
    auto law = [&](int q, const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                   double M[3]) { return point_law(le, q, eps, gam, rho, N, Q, M, work, failed); };
    strain_energy(le) = disc::dg_element_forces(refs(le), in, law, out, edge_tractions ? &tractions(le) : nullptr);
    store_forces(le, out);
    store_plastic(le, work, failed);
  }

  /// The sections of a batch's elements, lane by lane.
  struct BatchSections {
    materials::ElasticSectionOf<Batch> elastic;  ///< elastic lanes: the section; plastic: its elastic part
    Batch a_n, a_m, a_q, Y0, H;                  ///< plastic lanes: the yield function and the hardening
  };

  /// Loads the batch_width elements from `first` into their lanes; returns how many are plastic.
  KOKKOS_INLINE_FUNCTION int load_batch(LocalId first, disc::DgElementRefOf<Batch>& R,
                                        disc::DgElementNodesOf<Batch>& in, BatchSections& sc) const {
    int plastic_lanes = 0;
    for (int i = 0; i < disc::batch_width; ++i) {
      const LocalId le = first + i;
      lanes::load(R, refs(le), i);
      disc::DgElementNodes one;
      element_inputs(nb, x, t, lifted(le), le, one);
      lanes::load(in, one, i);
      const int blk = block(le);
      if (block_is_plastic(blk)) {
        const materials::PlasticSection& ps = plastic_section(blk);
        ++plastic_lanes;
        load_lane(sc.elastic, ps.elastic, i);
        sc.a_n.set(i, ps.a_n), sc.a_m.set(i, ps.a_m), sc.a_q.set(i, ps.a_q), sc.Y0.set(i, ps.Y0), sc.H.set(i, ps.H);
      } else {
        load_lane(sc.elastic, elastic_section(blk), i);
      }
    }
    return plastic_lanes;
  }

  /// The batch_width elements from `first` in lock-step.
  KOKKOS_INLINE_FUNCTION void batch(LocalId first) const {
    constexpr int W = disc::batch_width;
    disc::DgElementRefOf<Batch> R;
    disc::DgElementNodesOf<Batch> in;
    BatchSections sections;
    const int plastic_lanes = load_batch(first, R, in, sections);
    const materials::ElasticSectionOf<Batch>& sc = sections.elastic;
    disc::DgElementForcesOf<Batch> out;
    disc::EdgeTractionsOf<Batch> at;
    disc::EdgeTractionsOf<Batch>* at_or_null = edge_tractions ? &at : nullptr;
    double work[W] = {};
    int failed[W] = {};
    // Each lane's own point law (elastic, or the whole return map of its block).
    auto lane_by_lane = [&](int q, const Batch eps[3], const Batch gam[2], const Batch rho[3], Batch N[3],
                            Batch Q[2], Batch M[3]) {
      Batch w;
      for (int i = 0; i < W; ++i) {
        double e[3], gm[2], r[3], n[3], qs[2], m[3];
        for (int c = 0; c < 3; ++c) e[c] = eps[c][i], r[c] = rho[c][i];
        for (int c = 0; c < 2; ++c) gm[c] = gam[c][i];
        w.set(i, point_law(first + i, q, e, gm, r, n, qs, m, work[i], failed[i]));
        for (int c = 0; c < 3; ++c) N[c].set(i, n[c]), M[c].set(i, m[c]);
        for (int c = 0; c < 2; ++c) Q[c].set(i, qs[c]);
      }
      return w;
    };
    Batch energy;
    if (plastic_lanes == 0) {
      auto law = [&sc](int, const Batch eps[3], const Batch gam[2], const Batch rho[3], Batch N[3], Batch Q[2],
                       Batch M[3]) {
        materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
        return materials::elastic_energy(sc, eps, gam, rho);
      };
      energy = disc::dg_element_forces(R, in, law, out, at_or_null);
    } else if (plastic_lanes == W) {
      // The trial states of the batch at once (materials::trial_equivalent_stress); where every lane's is inside
      // its yield surface, the return map's elastic outcome: the trial resultants, the plastic state unchanged,
      // no plastic work (added as w j0 * 0, as the return map's result adds it). Otherwise lane by lane.
      auto law = [&](int q, const Batch eps[3], const Batch gam[2], const Batch rho[3], Batch N[3], Batch Q[2],
                     Batch M[3]) {
        Batch eps_p[3] = {0.0, 0.0, 0.0}, gam_p[2] = {0.0, 0.0}, rho_p[3] = {0.0, 0.0, 0.0}, alpha = 0.0;
        for (int i = 0; i < W; ++i) {
          const materials::PlasticState& st = plastic((first + i) * nq + q);
          for (int c = 0; c < 3; ++c) eps_p[c].set(i, st.eps_p[c]), rho_p[c].set(i, st.rho_p[c]);
          for (int c = 0; c < 2; ++c) gam_p[c].set(i, st.gam_p[c]);
          alpha.set(i, st.alpha);
        }
        Batch w[materials::detail::num_modes];
        const Batch F0 =
            materials::trial_equivalent_stress(sc, sections.a_n, sections.a_m, sections.a_q, eps, gam, rho, eps_p,
                                               gam_p, rho_p, N, Q, M, w);
        const Batch sy_n = sections.Y0 + sections.H * alpha;
        bool elastic = true;
        for (int i = 0; i < W; ++i) elastic = elastic && !(F0[i] > sy_n[i]);
        if (!elastic) return lane_by_lane(q, eps, gam, rho, N, Q, M);
        for (int i = 0; i < W; ++i) work[i] += refs(first + i).wj0[q] * 0.0;
        return materials::elastic_energy(sc, eps, gam, rho, eps_p, gam_p, rho_p);
      };
      energy = disc::dg_element_forces(R, in, law, out, at_or_null);
    } else {
      energy = disc::dg_element_forces(R, in, lane_by_lane, out, at_or_null);
    }
    for (int i = 0; i < W; ++i) {
      const LocalId le = first + i;
      strain_energy(le) = energy[i];
      disc::DgElementForces one;
      lanes::store(out, one, i);
      store_forces(le, one);
      if (edge_tractions) lanes::store(at, tractions(le), i);
      store_plastic(le, work[i], failed[i]);
    }
  }

  /// Batch b: the elements b * batch_width ... (b + 1) * batch_width - 1 that are owned.
  KOKKOS_INLINE_FUNCTION void operator()(LocalId b) const {
    const LocalId first = b * disc::batch_width;
    const LocalId end = first + disc::batch_width;
    bool same_strains = end <= owned;
    for (LocalId le = first + 1; same_strains && le < end; ++le)
      same_strains = refs(le).strains == refs(first).strains;
    if (same_strains)
      batch(first);
    else
      for (LocalId le = first; le < end && le < owned; ++le) one_element(le);
  }
};

}  // namespace

void ForceAssembly::element_kernel(ShellState& s) {
  ScopedTimer timer(times_.element);
  const ElementForcesKernel kernel{kernel_view(std::as_const(s.x)),
                                  kernel_view(std::as_const(s.t)),
                                  kernel_view(s.internal_force),
                                  kernel_view(s.director_force),
                                  kernel_view(s.strain_energy),
                                  kernel_view(flux_),
                                  kernel_view(edge_tractions_),
                                  !edge_tractions_.empty(),
                                  kernel_view(model_.element_refs),
                                  kernel_view(model_.lifted),
                                  kernel_view(model_.dm.element_blocks()),
                                  kernel_view(model_.block_elastic),
                                  kernel_view(model_.block_plastic),
                                  kernel_view(model_.block_is_plastic),
                                  kernel_view(s.plastic),
                                  kernel_view(plastic_work_increment_),
                                  kernel_view(return_failed_),
                                  NeighborViews(model_.dm),
                                  model_.owned};
  const LocalId batches = (model_.owned + disc::batch_width - 1) / disc::batch_width;
  static const std::string label_shell_element_forces("shellfrac::ShellElementForces");
  Kokkos::parallel_for(label_shell_element_forces, KernelRange(0, batches), kernel);
}

void ForceAssembly::interface_kernel(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive) {
  ScopedTimer timer(times_.interface);
  const auto interfaces = kernel_view(model_.dm.interfaces());
  const auto refs = kernel_view(model_.interface_refs);
  const ConstPositionView x = kernel_view(std::as_const(s.x));
  const ConstDirectorView t = kernel_view(std::as_const(s.t));
  const auto beta_x = kernel_view(model_.interface_beta_x), beta_t = kernel_view(model_.interface_beta_t);
  const KernelView<InterfaceForces> forces = kernel_view(interface_force_);
  const auto penalty_energy = kernel_view(s.penalty_energy);
  const auto mode = kernel_view(s.mode);
  const auto law = kernel_view(cohesive);
  const auto delta_max = kernel_view(s.delta_max);
  const auto conormal = kernel_view(s.conormal);
  const auto offset = kernel_view(std::as_const(s.activation_offset));
  const auto cohesive_energy = kernel_view(s.cohesive_energy), cohesive_dissipation = kernel_view(s.cohesive_dissipation);
  static const std::string label_interface_forces("shellfrac::InterfaceForces");
  const LocalId count = LocalId(interfaces.extent(0));
  Kokkos::parallel_for(label_interface_forces, KernelRange(0, count), [=](const LocalId i) {
    if (const LocalId ahead = i + prefetch_distance; ahead < count)  // the two sides' rows, scattered (a hint)
      for (const LocalId le : {interfaces(ahead).minus, interfaces(ahead).plus}) {
        prefetch_bytes(x.at(le), sizeof(double) * PositionRows::width);
        prefetch_bytes(t.at(le), sizeof(double) * DirectorRows::width);
      }
    const auto& fc = interfaces(i);
    disc::EdgeNodes minus, plus;
    edge_nodes_of(x, t, fc.minus, fc.minus_edge, minus);
    edge_nodes_of(x, t, fc.plus, fc.plus_edge, plus);
    disc::EdgeForces on_minus, on_plus;
    if (mode(i) == intact) {
      penalty_energy(i) = disc::dg_penalty_forces(refs(i), beta_x(i), beta_t(i), minus, plus, on_minus, on_plus);
    } else {
      // Activated: the cohesive law replaces the penalty (paper eqs. 53-54); a separated interface still
      // evaluates it (zero tractions) so that its energies stay current. The co-normals and the offsets fixed at
      // activation are per edge point.
      penalty_energy(i) = 0;
      const auto r = cohesive_interface_forces(refs(i), law(i), minus, plus, offset.points_of(i), delta_max.at(i),
                                               conormal.points_of(i), on_minus, on_plus);
      cohesive_energy(i) = r.stored, cohesive_dissipation(i) = r.dissipated;
      if (r.separated) mode(i) = separated;
    }
    forces(i).side[0] = on_minus, forces(i).side[1] = on_plus;
  });
}

void ForceAssembly::gather(ShellState& s) {
  ScopedTimer timer(times_.gather);
  const PositionView f = kernel_view(s.internal_force);
  const DirectorView g = kernel_view(s.director_force);
  const KernelView<const LiftingFluxes> fluxes = kernel_view(std::as_const(flux_));
  const KernelView<const InterfaceForces> forces = kernel_view(std::as_const(interface_force_));
  const auto lifted = kernel_view(model_.lifted);
  const auto offset = kernel_view(model_.incident.offset);
  const auto incident = kernel_view(model_.incident.entries);
  const auto interfaces = kernel_view(model_.dm.interfaces());
  const NeighborViews nb(model_.dm);
  static const std::string label_gather_forces("shellfrac::GatherForces");
  const LocalId owned = model_.owned;
  Kokkos::parallel_for(label_gather_forces, KernelRange(0, model_.owned), [=](const LocalId le) {
    // The rows this loop reads are scattered (neighbours, interfaces): ask for those of a later element now, so
    // that they arrive while this one adds (a hint only: no effect on the results).
    if (const LocalId ahead = le + prefetch_distance; ahead < owned) {
      for (int k = 0; k < 3; ++k)
        if (lifted(ahead)[k]) prefetch(fluxes(nb.element_across(ahead, k)).across[nb.edge_across(ahead, k)]);
      for (int e = offset(ahead); e < offset(ahead + 1); ++e)
        prefetch(forces(incident(e).interface).side[incident(e).side]);
    }
    for (int k = 0; k < 3; ++k)
      if (lifted(le)[k]) add_edge_forces(fluxes(nb.element_across(le, k)).across[nb.edge_across(le, k)], le, k, f, g);
    for (int e = offset(le); e < offset(le + 1); ++e) {
      const auto [i, side] = incident(e);
      add_edge_forces(forces(i).side[side], le, side == 0 ? interfaces(i).minus_edge : interfaces(i).plus_edge, f, g);
    }
  });
}

double ForceAssembly::bytes() const {
  return sizeof(LiftingFluxes) * double(flux_.size()) + sizeof(InterfaceForces) * double(interface_force_.size()) +
         sizeof(double) * double(plastic_work_increment_.size()) +
         sizeof(disc::EdgeTractions) * double(edge_tractions_.size()) + exchange_.bytes();
}

}  // namespace shellfrac::solver
