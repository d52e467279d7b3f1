#include "shellfrac/solver/force_assembly.hpp"

#include <Kokkos_Core.hpp>

#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/solver/cohesive_interface.hpp"
#include "shellfrac/solver/shell_model.hpp"

namespace shellfrac::solver {

namespace {

using exec = Kokkos::DefaultExecutionSpace;
constexpr int nq = disc::num_area_points;
constexpr int nx = position_values, nt = director_values;
constexpr int flux_width = Rows<3, 15>::width;
constexpr int edge_traction_width = int(sizeof(disc::EdgeTractions) / sizeof(double));
constexpr int state_channel = 0, flux_channel = 1;

/// The inputs of the element kernel for owned element le (dg_element_forces / dg_kinematics): its nodes, its
/// lifted edges and, across each lifted edge, the neighbour's edge nodes in the neighbour's edge-local order.
KOKKOS_INLINE_FUNCTION void element_inputs(const decomposition::DistributedMesh& d, const double* xp, const double* tp,
                                           const std::array<bool, 3>& lift, LocalId le, double xe[6][3],
                                           double te[3][3], bool lf[3], double xn[3][3][3], double tn[3][2][3]) {
  for (int i = 0; i < nx; ++i) xe[i / 3][i % 3] = xp[le * nx + i];
  for (int i = 0; i < nt; ++i) te[i / 3][i % 3] = tp[le * nt + i];
  for (int k = 0; k < 3; ++k) {
    lf[k] = lift[k];
    if (!lf[k]) continue;
    const LocalId nb = d.neighbor(le, k);
    const int kk = d.neighbor_edge(le, k);
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) xn[k][j][c] = xp[nb * nx + disc::edge_node(kk, j) * 3 + c];
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) tn[k][j][c] = tp[nb * nt + disc::edge_node(kk, j) * 3 + c];
  }
}

/// Adds an edge's 15 force values (3 position nodes x 3, then 2 director nodes x 3, edge-local order) to the
/// element rows f, g of element le on its local edge k.
KOKKOS_INLINE_FUNCTION void add_edge_forces(const double* in, LocalId le, int k, double* f, double* g) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) f[le * nx + disc::edge_node(k, j) * 3 + c] += in[j * 3 + c];
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) g[le * nt + disc::edge_node(k, j) * 3 + c] += in[9 + j * 3 + c];
}

/// The edge nodes (positions 3, directors 2, edge-local order) of local edge k of element le.
KOKKOS_INLINE_FUNCTION void edge_nodes(const double* xp, const double* tp, LocalId le, int k, double xk[3][3],
                                       double tk[2][3]) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) xk[j][c] = xp[le * nx + disc::edge_node(k, j) * 3 + c];
  for (int j = 0; j < 2; ++j)
    for (int c = 0; c < 3; ++c) tk[j][c] = tp[le * nt + disc::edge_node(k, j) * 3 + c];
}

}  // namespace

ForceAssembly::ForceAssembly(const ShellModel& model, bool edge_tractions, PhaseTimes& times)
    : model_(model),
      times_(times),
      exchange_(model.dm, {nx + nt, flux_width + (edge_tractions ? edge_traction_width : 0)}) {
  flux_.assign(model.overlap);
  if (edge_tractions) edge_tractions_.assign(model.overlap, disc::EdgeTractions{});
  interface_force_.assign(static_cast<LocalId>(model.dm.interfaces().size()));
  plastic_trial_.assign(model.any_plastic ? model.owned * nq : 0, materials::PlasticState{});
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
  const double* xp = s.x.data();
  const double* tp = s.t.data();
  double* fp = s.internal_force.data();
  double* gp = s.director_force.data();
  double* ep = s.strain_energy.data();
  double* flp = flux_.data();
  disc::EdgeTractions* etp = edge_tractions_.empty() ? nullptr : edge_tractions_.data();
  const auto* rp = model_.element_refs.data();
  const auto* lp = model_.lifted.data();
  const auto* sp = model_.elastic.data();
  const auto* psp = model_.plastic.data();
  const char* plp = model_.is_plastic.data();
  const materials::PlasticState* pold = s.plastic.data();
  materials::PlasticState* pnew = plastic_trial_.data();
  double* pwp = plastic_work_increment_.data();
  int* failp = return_failed_.data();
  const decomposition::DistributedMesh* d = &model_.dm;
  Kokkos::parallel_for(
      "shellfrac::ShellElementForces", Kokkos::RangePolicy<exec>(0, model_.owned), [=](const int le) {
        double xe[6][3], te[3][3], xn[3][3][3] = {}, tn[3][2][3] = {}, fe[6][3], ge[3][3], fk[3][3][3], gk[3][2][3];
        bool lf[3];
        element_inputs(*d, xp, tp, lp[le], le, xe, te, lf, xn, tn);
        disc::EdgeTractions* edge = etp ? etp + le : nullptr;
        const disc::DgElementRef& R = rp[le];
        if (plp[le]) {
          // Resultant plasticity: the return map at area point q from the committed state to the trial state.
          const materials::PlasticSection ps = psp[le];
          int failed = 0;
          double work = 0;
          auto law = [&](int q, const double eps[3], const double gam[2], const double rho[3], double N[3],
                         double Q[2], double M[3]) {
            materials::PlasticState& st = pnew[le * nq + q];
            const auto r = materials::resultant_return_map(ps, eps, gam, rho, pold[le * nq + q], st, N, Q, M);
            work += R.wj0[q] * r.plastic_work;
            failed |= r.converged ? 0 : 1;
            return materials::elastic_energy(ps.elastic, eps, gam, rho, st.eps_p, st.gam_p, st.rho_p);
          };
          ep[le] = disc::dg_element_forces(R, xe, te, lf, xn, tn, law, fe, ge, fk, gk, edge);
          pwp[le] = work, failp[le] = failed;
        } else {
          const materials::ElasticSection sc = sp[le];
          auto law = [&sc](int, const double eps[3], const double gam[2], const double rho[3], double N[3],
                           double Q[2], double M[3]) {
            materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
            return materials::elastic_energy(sc, eps, gam, rho);
          };
          ep[le] = disc::dg_element_forces(R, xe, te, lf, xn, tn, law, fe, ge, fk, gk, edge);
        }
        for (int i = 0; i < nx; ++i) fp[le * nx + i] = fe[i / 3][i % 3];
        for (int i = 0; i < nt; ++i) gp[le * nt + i] = ge[i / 3][i % 3];
        for (int k = 0; k < 3; ++k) {
          double* out = flp + le * flux_width + k * 15;
          for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) out[j * 3 + c] = fk[k][j][c];
          for (int j = 0; j < 2; ++j)
            for (int c = 0; c < 3; ++c) out[9 + j * 3 + c] = gk[k][j][c];
        }
      });
}

void ForceAssembly::interface_kernel(ShellState& s, const std::vector<materials::CohesiveParams>& cohesive) {
  ScopedTimer timer(times_.interface);
  const auto& ifs = model_.dm.interfaces();
  const auto* ip = ifs.data();
  const auto* irp = model_.interface_refs.data();
  const double *xp = s.x.data(), *tp = s.t.data();
  const double *bx = model_.interface_beta_x.data(), *bt = model_.interface_beta_t.data();
  double* fip = interface_force_.data();
  double* eip = s.penalty_energy.data();
  int* mode = s.mode.data();
  const auto* cpp = cohesive.data();
  double *dmp = s.delta_max.data(), *cnp = s.conormal.data();
  const double* jap = s.activation_offset.data();
  double *ucp = s.cohesive_energy.data(), *dcp = s.cohesive_dissipation.data();
  Kokkos::parallel_for(
      "shellfrac::InterfaceForces", Kokkos::RangePolicy<exec>(0, static_cast<int>(ifs.size())), [=](const int i) {
        const auto& fc = ip[i];
        double xm[3][3], tm[2][3], xq[3][3], tq[2][3], fm[3][3], gm[2][3], fq[3][3], gq[2][3];
        edge_nodes(xp, tp, fc.minus, fc.minus_edge, xm, tm);
        edge_nodes(xp, tp, fc.plus, fc.plus_edge, xq, tq);
        if (mode[i] == intact) {
          eip[i] = disc::dg_penalty_forces(irp[i], bx[i], bt[i], xm, tm, xq, tq, fm, gm, fq, gq);
        } else {
          // Activated: the cohesive law replaces the penalty (paper eqs. 53-54); a separated interface still
          // evaluates it (zero tractions) so that its energies stay current.
          eip[i] = 0;
          double(*nu)[3] = reinterpret_cast<double(*)[3]>(cnp + i * 9);  // the 3 edge points' co-normals
          const auto* offset = reinterpret_cast<const double(*)[6]>(jap + i * 18);  // their offsets fixed at activation
          const auto r =
              cohesive_interface_forces(irp[i], cpp[i], xm, tm, xq, tq, offset, dmp + i * 3, nu, fm, gm, fq, gq);
          ucp[i] = r.stored, dcp[i] = r.dissipated;
          if (r.separated) mode[i] = separated;
        }
        double* out = fip + i * 30;
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) out[j * 3 + c] = fm[j][c], out[15 + j * 3 + c] = fq[j][c];
        for (int j = 0; j < 2; ++j)
          for (int c = 0; c < 3; ++c) out[9 + j * 3 + c] = gm[j][c], out[15 + 9 + j * 3 + c] = gq[j][c];
      });
}

void ForceAssembly::gather(ShellState& s) {
  ScopedTimer timer(times_.gather);
  double* fp = s.internal_force.data();
  double* gp = s.director_force.data();
  const double* flp = flux_.data();
  const double* fip = interface_force_.data();
  const auto* lp = model_.lifted.data();
  const auto* inc = model_.incident.data();
  const auto* ip = model_.dm.interfaces().data();
  const decomposition::DistributedMesh* d = &model_.dm;
  Kokkos::parallel_for("shellfrac::GatherForces", Kokkos::RangePolicy<exec>(0, model_.owned), [=](const int le) {
    for (int k = 0; k < 3; ++k)
      if (lp[le][k]) add_edge_forces(flp + d->neighbor(le, k) * flux_width + d->neighbor_edge(le, k) * 15, le, k, fp, gp);
    for (const auto& [i, side] : inc[le])
      add_edge_forces(fip + i * 30 + side * 15, le, side == 0 ? ip[i].minus_edge : ip[i].plus_edge, fp, gp);
  });
}

void ForceAssembly::element_strains(const ShellState& s, LocalId le, PointStrains out[nq]) const {
  double xe[6][3], te[3][3], xn[3][3][3] = {}, tn[3][2][3] = {};
  bool lf[3];
  element_inputs(model_.dm, s.x.data(), s.t.data(), model_.lifted[le], le, xe, te, lf, xn, tn);
  disc::ShellKinematics kin[nq];
  const disc::DgElementRef& R = model_.element_refs[le];
  disc::dg_kinematics(R, xe, te, lf, xn, tn, kin);
  double eps[nq][3], gam[nq][2], rho[nq][3];
  disc::dg_strains(R, kin, eps, gam, rho);
  for (int q = 0; q < nq; ++q) {
    out[q].weight = R.wj0[q];
    for (int c = 0; c < 3; ++c) out[q].eps[c] = eps[q][c], out[q].rho[c] = rho[q][c];
    for (int c = 0; c < 2; ++c) out[q].gam[c] = gam[q][c];
  }
}

double ForceAssembly::bytes() const {
  return sizeof(double) * double(flux_.size() + interface_force_.size() + plastic_work_increment_.size()) +
         sizeof(disc::EdgeTractions) * double(edge_tractions_.size()) +
         sizeof(materials::PlasticState) * double(plastic_trial_.size()) + exchange_.bytes();
}

}  // namespace shellfrac::solver
