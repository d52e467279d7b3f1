#include "shellfrac/solver/step/force_assembly.hpp"

#include <utility>

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/solver/fracture/cohesive_interface.hpp"
#include "shellfrac/solver/model/element_inputs.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

namespace {

constexpr int nq = disc::num_area_points;
constexpr int nx = position_values, nt = director_values;
constexpr int flux_width = Rows<3, 15>::width;
constexpr int edge_traction_width = int(sizeof(disc::EdgeTractions) / sizeof(double));
constexpr int state_channel = 0, flux_channel = 1;

/// Adds an edge's 15 force values (3 position nodes x 3, then 2 director nodes x 3, edge-local order) to the
/// element rows f, g of element le on its local edge k.
KOKKOS_INLINE_FUNCTION void add_edge_forces(const double* in, LocalId le, int k, const KernelView<double>& f,
                                            const KernelView<double>& g) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) f(le * nx + disc::edge_node(k, j) * 3 + c) += in[j * 3 + c];
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) g(le * nt + disc::edge_node(k, j) * 3 + c) += in[9 + j * 3 + c];
}

/// The edge nodes (positions 3, directors 2, edge-local order) of local edge k of element le.
KOKKOS_INLINE_FUNCTION void edge_nodes(const KernelView<const double>& xp, const KernelView<const double>& tp,
                                       LocalId le, int k, double xk[3][3], double tk[2][3]) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) xk[j][c] = xp(le * nx + disc::edge_node(k, j) * 3 + c);
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) tk[j][c] = tp(le * nt + disc::edge_node(k, j) * 3 + c);
}

}  // namespace

ForceAssembly::ForceAssembly(const ShellModel& model, bool edge_tractions, PhaseTimes& times)
    : model_(model),
      times_(times),
      exchange_(model.dm, {nx + nt, flux_width + (edge_tractions ? edge_traction_width : 0)}) {
  flux_.assign(model.overlap);
  if (edge_tractions) edge_tractions_.assign(model.overlap, disc::EdgeTractions{});
  interface_force_.assign(static_cast<LocalId>(model.dm.interfaces().size()));
  plastic_work_increment_.assign(model.owned, 0.0), return_failed_.assign(model.owned, 0);
}

void ForceAssembly::exchange_state(ShellState& s) {
  ScopedTimer timer(times_.exchange);
  exchange_.import_ghost_rows(state_channel, {{s.x.data(), nx}, {s.t.data(), nt}});
}

void ForceAssembly::compute_forces(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive) {
  element_kernel(s);
  {
    ScopedTimer timer(times_.exchange);
    if (edge_tractions_.empty())
      exchange_.import_ghost_rows(flux_channel, {{flux_.data(), flux_width}});
    else
      exchange_.import_ghost_rows(flux_channel, {{flux_.data(), flux_width},
                                                 {&edge_tractions_[0].at[0][0][0], edge_traction_width}});
  }
  interface_kernel(s, cohesive);
  gather(s);
}

void ForceAssembly::element_kernel(ShellState& s) {
  ScopedTimer timer(times_.element);
  const KernelView<const double> xp = kernel_view(std::as_const(s.x)), tp = kernel_view(std::as_const(s.t));
  const KernelView<double> fp = kernel_view(s.internal_force), gp = kernel_view(s.director_force);
  const KernelView<double> ep = kernel_view(s.strain_energy), flp = kernel_view(flux_);
  const KernelView<disc::EdgeTractions> etp = kernel_view(edge_tractions_);
  const bool edge_tractions = !edge_tractions_.empty();
  const auto rp = kernel_view(model_.element_refs);
  const auto lp = kernel_view(model_.lifted);
  const auto block = kernel_view(model_.dm.element_blocks());
  const auto sp = kernel_view(model_.block_elastic);
  const auto psp = kernel_view(model_.block_plastic);
  const auto plp = kernel_view(model_.block_is_plastic);
  const auto plastic = kernel_view(s.plastic);
  const auto pwp = kernel_view(plastic_work_increment_);
  const auto failp = kernel_view(return_failed_);
  const NeighborViews nb(model_.dm);
  Kokkos::parallel_for("shellfrac::ShellElementForces", KernelRange(0, model_.owned), [=](const LocalId le) {
    double xe[6][3], te[3][3], xn[3][3][3] = {}, tn[3][2][3] = {}, fe[6][3], ge[3][3], fk[3][3][3], gk[3][2][3];
    bool lf[3];
    element_inputs(nb, xp, tp, lp(le), le, xe, te, lf, xn, tn);
    disc::EdgeTractions* edge = edge_tractions ? &etp(le) : nullptr;
    const disc::DgElementRef& R = rp(le);
    const int blk = block(le);
    if (plp(blk)) {
      // Resultant plasticity: the return map at area point q from the state of the last step to the new one,
      // in place (each element reads and writes only its own points).
      const materials::PlasticSection ps = psp(blk);
      int failed = 0;
      double work = 0;
      auto law = [&](int q, const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                     double M[3]) {
        materials::PlasticState& st = plastic(le * nq + q);
        const auto r = materials::resultant_return_map(ps, eps, gam, rho, st, st, N, Q, M);
        work += R.wj0[q] * r.plastic_work;
        failed |= r.converged ? 0 : 1;
        return materials::elastic_energy(ps.elastic, eps, gam, rho, st.eps_p, st.gam_p, st.rho_p);
      };
      ep(le) = disc::dg_element_forces(R, xe, te, lf, xn, tn, law, fe, ge, fk, gk, edge);
      pwp(le) = work, failp(le) = failed;
    } else {
      const materials::ElasticSection sc = sp(blk);
      auto law = [&sc](int, const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                       double M[3]) {
        materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
        return materials::elastic_energy(sc, eps, gam, rho);
      };
      ep(le) = disc::dg_element_forces(R, xe, te, lf, xn, tn, law, fe, ge, fk, gk, edge);
    }
    for (int i = 0; i < nx; ++i) fp(le * nx + i) = fe[i / 3][i % 3];
    for (int i = 0; i < nt; ++i) gp(le * nt + i) = ge[i / 3][i % 3];
    for (int k = 0; k < 3; ++k) {
      const LocalId out = le * flux_width + k * 15;
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) flp(out + j * 3 + c) = fk[k][j][c];
      for (int j = 0; j < 2; ++j)
        for (int c = 0; c < 3; ++c) flp(out + 9 + j * 3 + c) = gk[k][j][c];
    }
  });
}

void ForceAssembly::interface_kernel(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive) {
  ScopedTimer timer(times_.interface);
  const auto ip = kernel_view(model_.dm.interfaces());
  const auto irp = kernel_view(model_.interface_refs);
  const KernelView<const double> xp = kernel_view(std::as_const(s.x)), tp = kernel_view(std::as_const(s.t));
  const auto bx = kernel_view(model_.interface_beta_x), bt = kernel_view(model_.interface_beta_t);
  const KernelView<double> fip = kernel_view(interface_force_), eip = kernel_view(s.penalty_energy);
  const auto mode = kernel_view(s.mode);
  const auto cpp = kernel_view(cohesive);
  const KernelView<double> dmp = kernel_view(s.delta_max), cnp = kernel_view(s.conormal);
  const KernelView<const double> jap = kernel_view(std::as_const(s.activation_offset));
  const KernelView<double> ucp = kernel_view(s.cohesive_energy), dcp = kernel_view(s.cohesive_dissipation);
  Kokkos::parallel_for("shellfrac::InterfaceForces", KernelRange(0, LocalId(ip.extent(0))), [=](const LocalId i) {
    const auto& fc = ip(i);
    double xm[3][3], tm[2][3], xq[3][3], tq[2][3], fm[3][3], gm[2][3], fq[3][3], gq[2][3];
    edge_nodes(xp, tp, fc.minus, fc.minus_edge, xm, tm);
    edge_nodes(xp, tp, fc.plus, fc.plus_edge, xq, tq);
    if (mode(i) == intact) {
      eip(i) = disc::dg_penalty_forces(irp(i), bx(i), bt(i), xm, tm, xq, tq, fm, gm, fq, gq);
    } else {
      // Activated: the cohesive law replaces the penalty (paper eqs. 53-54); a separated interface still
      // evaluates it (zero tractions) so that its energies stay current.
      eip(i) = 0;
      double(*nu)[3] = reinterpret_cast<double(*)[3]>(&cnp(i * 9));  // the 3 edge points' co-normals
      const auto* offset = reinterpret_cast<const double(*)[6]>(&jap(i * 18));  // their offsets fixed at activation
      const auto r =
          cohesive_interface_forces(irp(i), cpp(i), xm, tm, xq, tq, offset, &dmp(i * 3), nu, fm, gm, fq, gq);
      ucp(i) = r.stored, dcp(i) = r.dissipated;
      if (r.separated) mode(i) = separated;
    }
    const LocalId out = i * 30;
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) fip(out + j * 3 + c) = fm[j][c], fip(out + 15 + j * 3 + c) = fq[j][c];
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) fip(out + 9 + j * 3 + c) = gm[j][c], fip(out + 15 + 9 + j * 3 + c) = gq[j][c];
  });
}

void ForceAssembly::gather(ShellState& s) {
  ScopedTimer timer(times_.gather);
  const KernelView<double> fp = kernel_view(s.internal_force), gp = kernel_view(s.director_force);
  const KernelView<const double> flp = kernel_view(std::as_const(flux_)), fip = kernel_view(std::as_const(interface_force_));
  const auto lp = kernel_view(model_.lifted);
  const auto offset = kernel_view(model_.incident.offset);
  const auto incident = kernel_view(model_.incident.entries);
  const auto ip = kernel_view(model_.dm.interfaces());
  const NeighborViews nb(model_.dm);
  Kokkos::parallel_for("shellfrac::GatherForces", KernelRange(0, model_.owned), [=](const LocalId le) {
    for (int k = 0; k < 3; ++k)
      if (lp(le)[k]) add_edge_forces(&flp(nb.element(le * 3 + k) * flux_width + nb.edge(le * 3 + k) * 15), le, k, fp, gp);
    for (int e = offset(le); e < offset(le + 1); ++e) {
      const auto [i, side] = incident(e);
      add_edge_forces(&fip(i * 30 + side * 15), le, side == 0 ? ip(i).minus_edge : ip(i).plus_edge, fp, gp);
    }
  });
}

double ForceAssembly::bytes() const {
  return sizeof(double) * double(flux_.size() + interface_force_.size() + plastic_work_increment_.size()) +
         sizeof(disc::EdgeTractions) * double(edge_tractions_.size()) + exchange_.bytes();
}

}  // namespace shellfrac::solver
