#pragma once
/// \file dg_test_model.hpp
/// Test helper shared by the DG operator tests: a serial DG model in which every element owns copies of
/// its nodes, assembled by gather exactly as described in theory.md §5.4 (own forces, neighbours' lifting
/// fluxes written to per-(element, edge) buffers and gathered by the owner, then interface penalties).
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/dg_interface.hpp"
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
    auto law = [&](int, const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                   double M[3]) {
      materials::elastic_resultants(section, eps, gam, rho, N, Q, M);
      return materials::elastic_energy(section, eps, gam, rho);
    };
    std::vector<double> fn(ne * 27), gn(ne * 18);
    double total = 0;
    for (GlobalId e = 0; e < ne; ++e) {
      DgElementForces out;
      total += dg_element_forces(refs[e], element_nodes(e), law, out);
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) F[e * 18 + A * 3 + c] += out.f[A][c];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) G[e * 9 + a * 3 + c] += out.g[a][c];
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) {
            fn[e * 27 + k * 9 + j * 3 + c] = out.neighbour[k].f[j][c];
            if (j < 2) gn[e * 18 + k * 6 + j * 3 + c] = out.neighbour[k].g[j][c];
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
      EdgeForces on_minus, on_plus;
      total += dg_penalty_forces(iref[i], beta_x, beta_t, edge_nodes(f.minus.element, f.minus.local_edge),
                                 edge_nodes(f.plus.element, f.plus.local_edge), on_minus, on_plus);
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) {
          F[f.minus.element * 18 + edge_node(f.minus.local_edge, j) * 3 + c] += on_minus.f[j][c];
          F[f.plus.element * 18 + edge_node(f.plus.local_edge, j) * 3 + c] += on_plus.f[j][c];
          if (j < 2) {
            G[f.minus.element * 9 + edge_node(f.minus.local_edge, j) * 3 + c] += on_minus.g[j][c];
            G[f.plus.element * 9 + edge_node(f.plus.local_edge, j) * 3 + c] += on_plus.g[j][c];
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
  DgElementNodes element_nodes(GlobalId e) const {
    DgElementNodes in{};
    load(e, in.x, in.t);
    for (int k = 0; k < 3; ++k) {
      in.lift[k] = lift[e][k];
      if (in.lift[k]) in.neighbour[k] = edge_nodes(topo.neighbor[e][k].element, topo.neighbor[e][k].local_edge);
    }
    return in;
  }

  /// The nodes of local edge k of element e, in its edge-local order.
  EdgeNodes edge_nodes(GlobalId e, int k) const {
    double xe[6][3], te[3][3];
    load(e, xe, te);
    EdgeNodes out;
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) {
        out.x[j][c] = xe[edge_node(k, j)][c];
        if (j < 2) out.t[j][c] = te[edge_node(k, j)][c];
      }
    return out;
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

// ---------------------------------------------------------------------------------------------------------
// Helpers for patch tests and linearized statics (test_static_verification_patch and _cantilever; usable by any DG operator test).
namespace shellfrac::disc::test {

/// Affine state x = Fm X on every DG copy (Fm a 3x3 matrix acting on the reference positions), directors
/// reset to the reference directors T0. On a flat patch with Fm mapping the plane into itself this is a
/// uniform membrane state (the membrane patch test).
inline void set_affine_state(Model& model, const double Fm[3][3]) {
  for (std::size_t i = 0; i < model.X.size() / 3; ++i)
    for (int r = 0; r < 3; ++r)
      model.x[3 * i + r] = Fm[r][0] * model.X[3 * i] + Fm[r][1] * model.X[3 * i + 1] + Fm[r][2] * model.X[3 * i + 2];
  model.t = model.T0;
}

/// The exact uniform-bending state of DgVerification.UniformBendingPatchTest on a flat patch in a plane
/// z = const with reference directors t0 = e3: x = X + w(X) e3 with w = kappa X^2/2 (exactly P2) and the
/// linear (not normalized) director field t = (-kappa X, 0, 1) (exactly P1), on every DG copy. Exactly:
/// a_1 = e1 + kappa X e3, a_2 = e2, d_1 = (-kappa, 0, 0), d_2 = 0, hence gamma = 0, rho = (-kappa, 0, 0)
/// (global frame, for every kappa) and eps = (kappa^2 X^2/2, 0, 0).
inline void set_uniform_bending_state(Model& model, double kappa) {
  model.x = model.X;
  model.t = model.T0;
  for (std::size_t i = 0; i < model.X.size() / 3; ++i) {
    const double X0 = model.X[3 * i];
    model.x[3 * i + 2] = model.X[3 * i + 2] + 0.5 * kappa * X0 * X0;
  }
  for (std::size_t i = 0; i < model.T0.size() / 3; ++i) model.t[3 * i] = -kappa * model.X[(i / 3) * 18 + (i % 3) * 3];
}

/// State of one area point of an element: reference position, local Cartesian basis, strains and resultants.
struct AreaPointState {
  double X[3];           ///< reference position of the area point (P2 map)
  double e1[3], e2[3];   ///< local Cartesian reference basis (element_geometry.hpp)
  double wj0;            ///< w_q j0_q
  double eps[3], gam[2], rho[3];
  double N[3], Q[2], M[3];
};

/// Strains and elastic resultants at the area points of element e in the model's current state, along the
/// code path of dg_element_forces: dg_kinematics (with the element's lift flags and its neighbours' edge
/// nodes), compute_strains, materials::elastic_resultants.
inline void area_point_states(const Model& model, GlobalId e, AreaPointState out[num_area_points]) {
  double Xe[6][3];
  for (int A = 0; A < 6; ++A)
    for (int c = 0; c < 3; ++c) Xe[A][c] = model.X[e * 18 + A * 3 + c];
  ShellKinematics kin[num_area_points];
  dg_kinematics(model.refs[e], model.element_nodes(e), kin);
  for (int q = 0; q < num_area_points; ++q) {
    AreaPointState& s = out[q];
    const double xi1 = tri6_rule.xi[q][0], xi2 = tri6_rule.xi[q][1];
    AreaPointGeometry geo;
    area_point_geometry(Xe, xi1, xi2, tri6_rule.w[q], geo);
    double N[6], dN[6][2];
    p2_shape(xi1, xi2, N, dN);
    for (int c = 0; c < 3; ++c) {
      s.X[c] = 0;
      for (int A = 0; A < 6; ++A) s.X[c] += N[A] * Xe[A][c];
      s.e1[c] = geo.e1[c], s.e2[c] = geo.e2[c];
    }
    s.wj0 = geo.wj0;
    compute_strains(kin[q], model.refs[e].ref[q], s.eps, s.gam, s.rho);
    materials::elastic_resultants(model.section, s.eps, s.gam, s.rho, s.N, s.Q, s.M);
  }
}

/// Sums over the DG copies of every mesh node: positions (3 components per mesh node, from F[E][A][c]) and
/// directors (3 components per mesh node, from G[E][a][c]; zero at mid-side nodes).
inline std::vector<double> sum_position_copies(const Model& model, const std::vector<double>& F) {
  std::vector<double> s(model.mesh.num_nodes() * 3, 0.0);
  for (GlobalId e = 0; e < model.mesh.num_elements(); ++e)
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) s[model.mesh.node(e, A) * 3 + c] += F[e * 18 + A * 3 + c];
  return s;
}

inline std::vector<double> sum_director_copies(const Model& model, const std::vector<double>& G) {
  std::vector<double> s(model.mesh.num_nodes() * 3, 0.0);
  for (GlobalId e = 0; e < model.mesh.num_elements(); ++e)
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) s[model.mesh.node(e, a) * 3 + c] += G[e * 9 + a * 3 + c];
  return s;
}

}  // namespace shellfrac::disc::test
