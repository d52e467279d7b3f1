#pragma once
/// \file dg_test_model.hpp
/// Test helper shared by the DG operator tests: a serial DG model in which every element owns copies of
/// its nodes, assembled by gather exactly as described in math.md §5.4 (own forces, neighbours' lifting
/// fluxes written to per-(element, edge) buffers and gathered by the owner, then interface penalties).
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::disc::test {

/// A serial DG model: every element owns copies of its nodes.
struct Model {
  mesh::SerialMesh mesh;
  mesh::EdgeTopology topo;
  std::vector<DgElementRef> refs;
  std::vector<DgInterfaceRef> iref;
  std::vector<std::array<bool, 3>> lift;
  materials::ElasticSection section;
  double beta_x = 0, beta_t = 0;
  // state: positions [E][A][c], directors [E][a][c]
  std::vector<double> x, t;
  std::vector<double> X, T0;

  explicit Model(mesh::SerialMesh m, double E = 1.0e3, double nu = 0.3, double h = 0.05, double c = 3.0)
      : mesh(std::move(m)), topo(mesh::build_edge_topology(mesh)) {
    section = materials::make_elastic_section(E, nu, h);
    beta_x = c * E * h;
    beta_t = c * E * h * h * h / 12;
    const auto n0 = mesh::reference_vertex_normals(mesh);
    const auto ne = mesh.num_elements();
    X.resize(ne * 18), T0.resize(ne * 9);
    refs.resize(ne), lift.resize(ne);
    for (GlobalId e = 0; e < ne; ++e) {
      double Xe[6][3], Te[3][3];
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) Xe[A][c] = X[e * 18 + A * 3 + c] = mesh.coords[mesh.node(e, A)][c];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) Te[a][c] = T0[e * 9 + a * 3 + c] = n0[mesh.node(e, a)][c];
      bool same[3];
      for (int k = 0; k < 3; ++k) {
        const GlobalId f = topo.element_interface[e][k];
        same[k] = f >= 0 && topo.interfaces[f].same_orientation;
        lift[e][k] = f >= 0 && !topo.interfaces[f].non_manifold;
      }
      build_dg_element_ref(Xe, Te, same, refs[e]);
    }
    for (const auto& f : topo.interfaces) {
      DgInterfaceRef r;
      build_dg_interface_ref(refs[f.minus.element].edge[f.minus.local_edge], r);
      iref.push_back(r);
    }
    x = X, t = T0;
  }

  /// Total energy and forces F (positions), G (spatial director moments), assembled by gather.
  double energy_and_forces(std::vector<double>& F, std::vector<double>& G) const {
    const auto ne = mesh.num_elements();
    F.assign(ne * 18, 0), G.assign(ne * 9, 0);
    auto law = [&](const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                   double M[3]) {
      materials::elastic_resultants(section, eps, gam, rho, N, Q, M);
      return materials::elastic_energy(section, eps, gam, rho);
    };
    std::vector<double> fn(ne * 27), gn(ne * 18);
    double total = 0;
    for (GlobalId e = 0; e < ne; ++e) {
      double xe[6][3], te[3][3], xn[3][3][3], tn[3][2][3], f[6][3], g[3][3], fk[3][3][3], gk[3][2][3];
      bool lf[3];
      element_inputs(e, xe, te, lf, xn, tn);
      total += dg_element_forces(refs[e], xe, te, lf, xn, tn, law, f, g, fk, gk);
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) F[e * 18 + A * 3 + c] += f[A][c];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) G[e * 9 + a * 3 + c] += g[a][c];
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) {
            fn[e * 27 + k * 9 + j * 3 + c] = fk[k][j][c];
            if (j < 2) gn[e * 18 + k * 6 + j * 3 + c] = gk[k][j][c];
          }
    }
    // gather the neighbours' lifting fluxes: element e, edge k receives what its neighbour wrote for it
    for (GlobalId e = 0; e < ne; ++e)
      for (int k = 0; k < 3; ++k) {
        if (!lift[e][k]) continue;
        const auto nb = topo.neighbor[e][k];
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) {
            F[e * 18 + edge_node(k, j) * 3 + c] += fn[nb.element * 27 + nb.local_edge * 9 + j * 3 + c];
            if (j < 2) G[e * 9 + edge_node(k, j) * 3 + c] += gn[nb.element * 18 + nb.local_edge * 6 + j * 3 + c];
          }
      }
    for (std::size_t i = 0; i < topo.interfaces.size(); ++i) {
      const auto& f = topo.interfaces[i];
      double xa[6][3], ta[3][3], xb[6][3], tb[3][3], xm[3][3], tm[2][3], xp[3][3], tp[2][3];
      double fm[3][3], gm[2][3], fp[3][3], gp[2][3];
      load(f.minus.element, xa, ta);
      load(f.plus.element, xb, tb);
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) {
          xm[j][c] = xa[edge_node(f.minus.local_edge, j)][c];
          xp[j][c] = xb[edge_node(f.plus.local_edge, j)][c];
          if (j < 2) tm[j][c] = ta[edge_node(f.minus.local_edge, j)][c], tp[j][c] = tb[edge_node(f.plus.local_edge, j)][c];
        }
      total += dg_penalty_forces(iref[i], beta_x, beta_t, xm, tm, xp, tp, fm, gm, fp, gp);
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) {
          F[f.minus.element * 18 + edge_node(f.minus.local_edge, j) * 3 + c] += fm[j][c];
          F[f.plus.element * 18 + edge_node(f.plus.local_edge, j) * 3 + c] += fp[j][c];
          if (j < 2) {
            G[f.minus.element * 9 + edge_node(f.minus.local_edge, j) * 3 + c] += gm[j][c];
            G[f.plus.element * 9 + edge_node(f.plus.local_edge, j) * 3 + c] += gp[j][c];
          }
        }
    }
    return total;
  }

  double energy() const {
    std::vector<double> F, G;
    return energy_and_forces(F, G);
  }

  /// The inputs of dg_kinematics / dg_element_forces for element e: its own nodes, its lift flags and the
  /// neighbours' edge nodes (neighbour's edge-local order; zero where the edge is not lifted).
  void element_inputs(GlobalId e, double xe[6][3], double te[3][3], bool lf[3], double xn[3][3][3],
                      double tn[3][2][3]) const {
    load(e, xe, te);
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) xn[k][j][0] = xn[k][j][1] = xn[k][j][2] = 0;
      for (int j = 0; j < 2; ++j) tn[k][j][0] = tn[k][j][1] = tn[k][j][2] = 0;
      lf[k] = lift[e][k];
      if (!lf[k]) continue;
      const auto nb = topo.neighbor[e][k];
      double xo[6][3], to[3][3];
      load(nb.element, xo, to);
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) xn[k][j][c] = xo[edge_node(nb.local_edge, j)][c];
      for (int j = 0; j < 2; ++j)
        for (int c = 0; c < 3; ++c) tn[k][j][c] = to[edge_node(nb.local_edge, j)][c];
    }
  }

 private:
  void load(GlobalId e, double xe[6][3], double te[3][3]) const {
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) xe[A][c] = x[e * 18 + A * 3 + c];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) te[a][c] = t[e * 9 + a * 3 + c];
  }
};

inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double a : v) m = std::max(m, std::abs(a));
  return m;
}

}  // namespace shellfrac::disc::test
