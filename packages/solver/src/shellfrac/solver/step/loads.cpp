#include "shellfrac/solver/step/loads.hpp"

#include <algorithm>

#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/disc/small_tensor.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/shell_model.hpp"

namespace shellfrac::solver {

namespace {

/// The orthonormal frame of an edge at edge parameter s: tangent (along the edge), outward co-normal and director
/// (made orthogonal to the tangent), from the edge's 3 position nodes x and 2 vertex directors t.
void edge_frame(const double x[3][3], const double t[2][3], double s, double tau[3], double nu[3], double n[3]) {
  double dn[3];
  disc::edge_shape_p2_derivative(s, dn);
  for (int c = 0; c < 3; ++c) {
    tau[c] = dn[0] * x[0][c] + dn[1] * x[1][c] + dn[2] * x[2][c];
    n[c] = (1 - s) * t[0][c] + s * t[1][c];
  }
  disc::normalize3(tau);
  const double along = disc::dot3(n, tau);
  for (int c = 0; c < 3; ++c) n[c] -= along * tau[c];
  disc::normalize3(n);
  disc::cross3(tau, n, nu);  // outward for an element that traverses its edges counter-clockwise about n
}

/// The edge nodes (3 positions, 2 directors, edge-local order) of local edge k of element le.
void edge_nodes(const double* xe, const double* te, int k, double x[3][3], double t[2][3]) {
  for (int j = 0; j < 3; ++j) disc::copy3(xe + disc::edge_node(k, j) * 3, x[j]);
  for (int j = 0; j < 2; ++j) disc::copy3(te + disc::edge_node(k, j) * 3, t[j]);
}

/// Number of elements that contain each mesh node (its DG copies).
std::vector<int> copies_per_node(const mesh::SerialMesh& mesh) {
  std::vector<int> n(mesh.num_nodes(), 0);
  for (GlobalId e = 0; e < mesh.num_elements(); ++e)
    for (int A = 0; A < mesh.nodes_per_element; ++A) ++n[mesh.node(e, A)];
  return n;
}

}  // namespace

Loads::Loads(const std::vector<Load>& loads, const MeshSets& sets, const mesh::SerialMesh& mesh,
             const ShellModel& model)
    : model_(model), loads_(loads) {
  const auto& dm = model.dm;
  constant_force_.assign(model.owned, 0.0);
  const std::vector<int> copies = copies_per_node(mesh);
  for (const auto& load : loads_) {
    using T = Load::Type;
    const std::string what = "load '" + load.name + "'";
    elements_.emplace_back(), edges_.emplace_back(), scaled_force_.emplace_back();
    const bool varying = load.function != Load::Function::Constant;
    if (load.type == T::Gravity || load.type == T::NodalForce) {
      PositionRows& target = varying ? scaled_force_.back() : constant_force_;
      if (varying) target.assign(model.owned, 0.0);
      const auto member = load.type == T::Gravity ? sets.elements(what, load.elements)
                                                  : sets.node_set(what + " (Node Set)", load.node_set, false);
      sets.require_some(what, load.type == T::Gravity ? load.elements : load.node_set, member);
      for (LocalId le = 0; le < model.owned; ++le)
        for (int A = 0; A < 6; ++A) {
          if (load.type == T::Gravity && !member[dm.element_gid(le)]) continue;
          const GlobalId n = dm.mesh_node(le, A);
          if (load.type == T::NodalForce && !member[n]) continue;
          for (int c = 0; c < 3; ++c)
            target.at(le, A)[c] += load.type == T::Gravity ? *model.mass.at(le, A) * load.acceleration[c]
                                                           : load.force[c] / copies[n];
        }
    } else if (load.type == T::Pressure) {
      const auto member = sets.elements(what, load.elements);
      sets.require_some(what, load.elements, member);
      for (LocalId le = 0; le < model.owned; ++le)
        if (member[dm.element_gid(le)]) elements_.back().push_back(le);
    } else {
      const auto edges = sets.side_set(what + " (Side Set)", load.side_set);
      sets.require_some(what, load.side_set, edges);
      director_loads_ = director_loads_ || load.type == T::EdgeMoment;
      for (LocalId le = 0; le < model.owned; ++le)
        for (int k = 0; k < 3; ++k) {
          if (!edges.count({dm.element_gid(le), k})) continue;
          LoadedEdge e{le, k, {}};
          if (load.follower) {
            double x[3][3], t[2][3], tau[3], nu[3], n[3];
            double te[9];
            for (int a = 0; a < 3; ++a) disc::copy3(dm.reference_director(le, a).data(), te + 3 * a);
            edge_nodes(model.X.at(le), te, k, x, t);
            for (int g = 0; g < disc::num_edge_points; ++g) {
              edge_frame(x, t, disc::edge3_rule.s[g], tau, nu, n);
              e.local[g][0] = disc::dot3(load.force.data(), tau);
              e.local[g][1] = disc::dot3(load.force.data(), nu);
              e.local[g][2] = disc::dot3(load.force.data(), n);
            }
          }
          edges_.back().push_back(e);
        }
    }
  }
}

void Loads::external_forces(double t, const ShellState& s, PositionRows& fext, DirectorRows& gext) const {
  std::copy(constant_force_.vector().begin(), constant_force_.vector().end(), fext.vector().begin());
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    if (scaled_force_[l].size() == 0) continue;
    const double f = loads_[l].factor_at(t);
    for (std::size_t i = 0; i < scaled_force_[l].size(); ++i) fext.data()[i] += f * scaled_force_[l].data()[i];
  }
  if (director_loads_) std::fill(gext.vector().begin(), gext.vector().end(), 0.0);
  for (std::size_t l = 0; l < loads_.size(); ++l) {
    const auto& load = loads_[l];
    if (load.type == Load::Type::Pressure) add_pressure(load, l, t, s, fext);
    if (load.type == Load::Type::LineLoad) add_line_load(load, l, t, s, fext);
    if (load.type == Load::Type::EdgeMoment) add_edge_moment(load, l, t, s, gext);
  }
}

// Follower pressure (docs/theory.md §10.3): f_ext^A = p(t) sum_q w_q N^A(xi_q) (dphi/dxi1 x dphi/dxi2)(xi_q) on the
// current mid-surface, with the ordinary (not DG) element derivatives.
void Loads::add_pressure(const Load& load, std::size_t l, double t, const ShellState& s, PositionRows& fext) const {
  const double p = load.pressure_at(t);
  for (LocalId le : elements_[l])
    for (int q = 0; q < disc::tri6_rule.num_points; ++q) {
      double N[6], dN[6][2], g1[3] = {0, 0, 0}, g2[3] = {0, 0, 0}, n[3];
      p2_shape(disc::tri6_rule.xi[q][0], disc::tri6_rule.xi[q][1], N, dN);
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) g1[c] += dN[A][0] * s.x.at(le, A)[c], g2[c] += dN[A][1] * s.x.at(le, A)[c];
      disc::cross3(g1, g2, n);
      for (int A = 0; A < 6; ++A)
        for (int c = 0; c < 3; ++c) fext.at(le, A)[c] += p * disc::tri6_rule.w[q] * N[A] * n[c];
    }
}

// Line load (docs/theory.md §10.3): f_ext^j = sum_g omega_g N_j(s_g) q(s_g) on the edge's 3 position nodes, omega_g
// the reference arc-length weights; a follower load keeps its components in the edge's current frame.
void Loads::add_line_load(const Load& load, std::size_t l, double t, const ShellState& s, PositionRows& fext) const {
  const double f = load.factor_at(t);
  for (const LoadedEdge& e : edges_[l]) {
    const disc::DgEdgeRef& E = model_.element_refs[e.element].edge[e.edge];
    double x[3][3], tt[2][3];
    edge_nodes(s.x.at(e.element), s.t.at(e.element), e.edge, x, tt);
    for (int g = 0; g < disc::num_edge_points; ++g) {
      const double sg = disc::edge3_rule.s[g];
      double q[3], N[3];
      if (load.follower) {
        double tau[3], nu[3], n[3];
        edge_frame(x, tt, sg, tau, nu, n);
        for (int c = 0; c < 3; ++c) q[c] = e.local[g][0] * tau[c] + e.local[g][1] * nu[c] + e.local[g][2] * n[c];
      } else {
        disc::copy3(load.force.data(), q);
      }
      disc::edge_shape_p2(sg, N);
      for (int j = 0; j < 3; ++j)
        for (int c = 0; c < 3; ++c) fext.at(e.element, disc::edge_node(e.edge, j))[c] += f * E.omega[g] * N[j] * q[c];
    }
  }
}

// Edge moment (docs/theory.md §10.3): a couple m per unit length does the virtual work m . theta with
// delta t = theta x t, so the director nodes get g_ext^j = sum_g omega_g L_j(s_g) (m x t(s_g)).
void Loads::add_edge_moment(const Load& load, std::size_t l, double t, const ShellState& s, DirectorRows& gext) const {
  const double f = load.factor_at(t);
  for (const LoadedEdge& e : edges_[l]) {
    const disc::DgEdgeRef& E = model_.element_refs[e.element].edge[e.edge];
    const double* t0 = s.t.at(e.element, disc::edge_node(e.edge, 0));
    const double* t1 = s.t.at(e.element, disc::edge_node(e.edge, 1));
    for (int g = 0; g < disc::num_edge_points; ++g) {
      const double sg = disc::edge3_rule.s[g], L[2] = {1 - sg, sg};
      double tg[3], mt[3];
      for (int c = 0; c < 3; ++c) tg[c] = L[0] * t0[c] + L[1] * t1[c];
      disc::cross3(load.moment.data(), tg, mt);
      for (int j = 0; j < 2; ++j)
        for (int c = 0; c < 3; ++c) gext.at(e.element, disc::edge_node(e.edge, j))[c] += f * E.omega[g] * L[j] * mt[c];
    }
  }
}

}  // namespace shellfrac::solver
