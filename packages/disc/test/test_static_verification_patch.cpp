// Static verification of the DG shell operator (theory.md §5, §5.8) on the assembled serial model
// of dg_test_model.hpp. Each test states its reference and tolerance:
//  * MembranePatchTestOnUnstructuredMesh / BendingPatchTestOnUnstructuredMesh: patch tests on a genuinely
//    unstructured Delaunay mesh (tests/data/gmsh/patch_unstructured.{geo,msh}: 62 triangles on [0,2]x[0,1],
//    vertex valences 2..7, promoted to P2), every interior edge lifted. A continuous affine (membrane) or
//    uniform-curvature (bending) state is represented exactly, the DG derivative of a continuous field is the
//    classical one, so the resultants at EVERY area point equal the exact constant values, the DG copies of
//    interior nodes are in equilibrium and the boundary nodes carry exactly the consistent nodal loads of
//    the exact boundary tractions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dg_test_model.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;
using shellfrac::disc::test::AreaPointState;
using shellfrac::disc::test::Model;

namespace {

// ----------------------------------------------------------------------------------------------------------
// Patch tests on the unstructured mesh
// ----------------------------------------------------------------------------------------------------------

/// The committed unstructured mesh (Gmsh Delaunay, P1, see its .geo), promoted to P2 (straight edges).
mesh::SerialMesh unstructured_patch() {
  auto m = meshio::read_gmsh(std::string(SHELLFRAC_SOURCE_DIR) + "/tests/data/gmsh/patch_unstructured.msh");
  mesh::promote_to_p2(m);
  return m;
}

/// Local components S_ij = e_i . S e_j of an in-plane global tensor S (2x2, xy components; e_i in z = 0),
/// returned in Voigt form [S11, S22, S12] (tensor components; multiply the last by 2 for engineering strain).
void to_local(const double S[2][2], const double e1[3], const double e2[3], double out[3]) {
  const double* e[2] = {e1, e2};
  double L[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      L[i][j] = 0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) L[i][j] += e[i][a] * S[a][b] * e[j][b];
    }
  out[0] = L[0][0], out[1] = L[1][1], out[2] = L[0][1];
}

/// Checks the common properties of the unstructured patch model: flat, t0 = e3, every interior edge lifted.
/// Returns the number of lifted (element, edge) sides.
int check_patch_model(const Model& model) {
  int lifted = 0;
  for (std::size_t i = 0; i < model.T0.size() / 3; ++i) EXPECT_EQ(model.T0[3 * i + 2], 1.0);
  for (std::size_t i = 0; i < model.X.size() / 3; ++i) EXPECT_EQ(model.X[3 * i + 2], 0.0);
  for (GlobalId e = 0; e < model.mesh.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const bool has_nbr = model.topo.neighbor[e][k].element >= 0;
      EXPECT_EQ(model.lift[e][k], has_nbr) << "element " << e << " edge " << k;
      lifted += model.lift[e][k];
    }
  EXPECT_EQ(lifted, static_cast<int>(2 * model.topo.interfaces.size()));
  EXPECT_EQ(model.topo.num_non_manifold_edges, 0);
  return lifted;
}

/// Consistent nodal loads of a traction that is constant on each boundary edge: `traction(nu)` gives the
/// force (3-vector) per unit reference length on a boundary edge with outward unit normal nu (in z = 0).
/// P2 positions: 1/6, 1/6, 2/3 of traction x length to (vertex, vertex, mid-side); P1 directors: 1/2, 1/2.
template <class Traction>
std::vector<double> boundary_nodal_loads(const Model& model, bool p2, const Traction& traction) {
  const auto& m = model.mesh;
  std::vector<double> f(m.num_nodes() * 3, 0.0);
  for (const auto& b : model.topo.boundary) {
    const GlobalId e = b.element;
    const int k = b.local_edge;
    const Vec3& P0 = m.coords[m.node(e, edge_node(k, 0))];
    const Vec3& P1 = m.coords[m.node(e, edge_node(k, 1))];
    const double dx = P1[0] - P0[0], dy = P1[1] - P0[1], len = std::hypot(dx, dy);
    const double nu[2] = {dy / len, -dx / len};  // outward for a counter-clockwise element
    double tr[3];
    traction(nu, tr);
    const double w[3] = {p2 ? 1.0 / 6 : 0.5, p2 ? 1.0 / 6 : 0.5, p2 ? 2.0 / 3 : 0.0};
    for (int j = 0; j < (p2 ? 3 : 2); ++j)
      for (int c = 0; c < 3; ++c) f[m.node(e, edge_node(k, j)) * 3 + c] += w[j] * len * tr[c];
  }
  return f;
}

}  // namespace

// Reference: membrane patch test. x = Fm X (general in-plane Fm, not symmetric), t = e3 on an unstructured
// flat P2 mesh is continuous and exactly represented; the DG derivative (liftings active on every interior
// edge) equals the classical one, so at every area point a_i = Fm e_i and, in the element's local frame
// {e1, e2}, eps = R^T E R with the exact Green-Lagrange strain E = 1/2 (Fm^T Fm - 1) and N = D_n C0 eps,
// Q = 0, M = 0 exactly. Tolerances: N to 1e-10 of max|N| (round-off: strains ~1e-3 computed as
// 1/2 (a.a - 1) from O(1) vectors lose ~1e-13 relative); Q and M are exactly zero (t = e3 and d = 0 exactly,
// z-components of a exactly zero). Forces: the nodal sums over DG copies equal the consistent nodal loads
// of the exact traction P nu = Fm S nu on boundary edges (zero at interior nodes) to 1e-10 of the boundary
// nodal load scale; director moments vanish on every copy; Pi_h = 1/2 S:E |S|.
TEST(StaticVerification, MembranePatchTestOnUnstructuredMesh) {
  const double E = 1.0e3, nu = 0.3, h = 0.05, area = 2.0;
  Model model(unstructured_patch(), E, nu, h);
  const int lifted = check_patch_model(model);
  const double s = 1e-3, r = -4e-4, g12 = 2e-4, g21 = -3e-4;
  const double Fm[3][3] = {{1 + s, g12, 0}, {g21, 1 + r, 0}, {0, 0, 1}};
  test::set_affine_state(model, Fm);
  // Exact Green-Lagrange strain and second Piola-Kirchhoff resultant (global xy components).
  double Eg[2][2], S[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) Eg[i][j] = 0.5 * (Fm[0][i] * Fm[0][j] + Fm[1][i] * Fm[1][j] - (i == j ? 1 : 0));
  const double Dn = model.section.Dn;
  S[0][0] = Dn * (Eg[0][0] + nu * Eg[1][1]);
  S[1][1] = Dn * (Eg[1][1] + nu * Eg[0][0]);
  S[0][1] = S[1][0] = Dn * (1 - nu) * Eg[0][1];
  const double Smax = std::max({std::abs(S[0][0]), std::abs(S[1][1]), std::abs(S[0][1])});
  // Resultants at every area point.
  double errN = 0, errEps = 0, maxQ = 0, maxM = 0;
  int points = 0;
  for (GlobalId e = 0; e < model.mesh.num_elements(); ++e) {
    AreaPointState st[num_area_points];
    test::area_point_states(model, e, st);
    for (const auto& p : st) {
      double Nl[3], El[3];
      to_local(S, p.e1, p.e2, Nl);
      to_local(Eg, p.e1, p.e2, El);
      El[2] *= 2;  // engineering shear
      for (int c = 0; c < 3; ++c) {
        errN = std::max(errN, std::abs(p.N[c] - Nl[c]));
        errEps = std::max(errEps, std::abs(p.eps[c] - El[c]));
        maxM = std::max(maxM, std::abs(p.M[c]));
      }
      maxQ = std::max({maxQ, std::abs(p.Q[0]), std::abs(p.Q[1])});
      ++points;
    }
  }
  std::printf("membrane patch (%d elements, %d lifted sides, %d area points): max |N - N_exact| / max|N| = %.2e, "
              "max |eps - eps_exact| = %.2e, max |Q| = %.1e, max |M| = %.1e\n",
              static_cast<int>(model.mesh.num_elements()), lifted, points, errN / Smax, errEps, maxQ, maxM);
  EXPECT_LT(errN, 1e-10 * Smax);
  EXPECT_LT(errEps, 1e-13);
  EXPECT_EQ(maxQ, 0.0);
  EXPECT_EQ(maxM, 0.0);
  // Energy and forces.
  std::vector<double> F, G;
  const double energy = model.energy_and_forces(F, G);
  const double exact_energy = 0.5 * (S[0][0] * Eg[0][0] + S[1][1] * Eg[1][1] + 2 * S[0][1] * Eg[0][1]) * area;
  EXPECT_NEAR(energy, exact_energy, 1e-10 * exact_energy);
  EXPECT_EQ(test::max_abs(G), 0.0);  // no director moments anywhere (M = Q = 0, directors continuous)
  const auto node_f = test::sum_position_copies(model, F);
  // Traction on an edge with outward normal nu: P nu = Fm S nu (first Piola-Kirchhoff resultant).
  const auto expect_f = boundary_nodal_loads(model, true, [&](const double n[2], double tr[3]) {
    const double Sn[2] = {S[0][0] * n[0] + S[0][1] * n[1], S[1][0] * n[0] + S[1][1] * n[1]};
    for (int c = 0; c < 3; ++c) tr[c] = Fm[c][0] * Sn[0] + Fm[c][1] * Sn[1];
  });
  const double fscale = test::max_abs(expect_f);
  double err_nodes = 0, rx2 = 0, rx2_exact = 0;
  for (GlobalId n = 0; n < model.mesh.num_nodes(); ++n) {
    for (int c = 0; c < 3; ++c) err_nodes = std::max(err_nodes, std::abs(node_f[n * 3 + c] - expect_f[n * 3 + c]));
    if (model.mesh.coords[n][0] > 2 - 1e-12) rx2 += node_f[n * 3], rx2_exact += expect_f[n * 3];
  }
  std::printf("membrane patch: Pi_h rel. error %.2e; max nodal |f - f_consistent| = %.2e (scale %.2e); "
              "x-reaction on x = 2: %.12e (consistent loads %.12e)\n",
              (energy - exact_energy) / exact_energy, err_nodes, fscale, rx2, rx2_exact);
  EXPECT_LT(err_nodes, 1e-10 * fscale);
  // The resultant x-force on the x = 2 side (its corners also carry a share of the y = 0, 1 tractions).
  EXPECT_NEAR(rx2, rx2_exact, 1e-10 * std::abs(rx2_exact));
}

// Reference: bending patch test (the state of DgVerification.UniformBendingPatchTest, helper
// test::set_uniform_bending_state) on the unstructured mesh. x = X + kappa X^2/2 e3, t = (-kappa X, 0, 1) are
// exactly P2 / P1 and continuous, so with every interior edge lifted d^DG = d and, for EVERY kappa,
// rho = -kappa e1 (x) e1 and gamma = 0 exactly (global frame), eps = kappa^2 X^2/2 e1 (x) e1. At every area
// point, in the local frame: M = D_m C0 rho_local exactly (tolerance 1e-10 of D_m kappa: M is computed from
// a.d products of O(1) and O(kappa) vectors, round-off ~1e-15 relative), Q = 0 (to 1e-13 of D_s kappa:
// gamma = a_1.t cancels kappa X - kappa X in floating point), and N = D_n C0 eps_local(X_q) (checked at
// kappa = 0.2, where eps ~ 1e-2 is far above round-off; at kappa = 1e-6 eps ~ 1e-12 is at round-off level).
// Forces at first order in kappa (central difference in kappa = 1e-6, which removes the O(kappa^2) membrane
// parts): position forces vanish on every DG copy (1e-9 of D_n x element size, per unit kappa), the director
// moments of the DG copies of interior nodes sum to zero and boundary nodes carry the consistent P1 loads of
// the moment traction M nu = (-D_m nu_x, -nu D_m nu_y, 0) kappa (1e-10 of D_m x element size).
TEST(StaticVerification, BendingPatchTestOnUnstructuredMesh) {
  const double E = 1.0e3, nu = 0.3, h = 0.05;
  Model model(unstructured_patch(), E, nu, h);
  std::printf("bending patch: %d lifted element sides\n", check_patch_model(model));
  const double Dm = model.section.Dm, Dn = model.section.Dn, Ds = model.section.Ds;
  for (const double kappa : {1e-6, 0.2}) {
    test::set_uniform_bending_state(model, kappa);
    const double rho_g[2][2] = {{-kappa, 0}, {0, 0}};
    double errM = 0, errN = 0, maxQ = 0, maxN = 0;
    for (GlobalId e = 0; e < model.mesh.num_elements(); ++e) {
      AreaPointState st[num_area_points];
      test::area_point_states(model, e, st);
      for (const auto& p : st) {
        double rl[3], el[3];
        to_local(rho_g, p.e1, p.e2, rl);
        rl[2] *= 2;  // engineering (Voigt) form
        const double eps_g[2][2] = {{0.5 * kappa * kappa * p.X[0] * p.X[0], 0}, {0, 0}};
        to_local(eps_g, p.e1, p.e2, el);
        el[2] *= 2;
        const double Mx[3] = {Dm * (rl[0] + nu * rl[1]), Dm * (nu * rl[0] + rl[1]), Dm * (1 - nu) / 2 * rl[2]};
        const double Nx[3] = {Dn * (el[0] + nu * el[1]), Dn * (nu * el[0] + el[1]), Dn * (1 - nu) / 2 * el[2]};
        for (int c = 0; c < 3; ++c) {
          errM = std::max(errM, std::abs(p.M[c] - Mx[c]));
          errN = std::max(errN, std::abs(p.N[c] - Nx[c]));
          maxN = std::max(maxN, std::abs(Nx[c]));
        }
        maxQ = std::max({maxQ, std::abs(p.Q[0]), std::abs(p.Q[1])});
      }
    }
    std::printf("bending patch, kappa = %g: max |M - M_exact| / (Dm kappa) = %.2e, max |Q| / (Ds kappa) = %.2e, "
                "max |N - N_exact| / max|N_exact| = %.2e\n",
                kappa, errM / (Dm * kappa), maxQ / (Ds * kappa), errN / maxN);
    EXPECT_LT(errM, 1e-10 * Dm * kappa);
    EXPECT_LT(maxQ, 1e-13 * Ds * kappa);
    if (kappa > 0.1) {
      EXPECT_LT(errN, 1e-10 * maxN);
    }
  }
  // First-order forces per unit kappa.
  const double kappa = 1e-6;
  std::vector<double> Fp, Gp, Fm, Gm;
  test::set_uniform_bending_state(model, kappa);
  model.energy_and_forces(Fp, Gp);
  test::set_uniform_bending_state(model, -kappa);
  model.energy_and_forces(Fm, Gm);
  std::vector<double> F1(Fp.size()), G1(Gp.size());
  for (std::size_t i = 0; i < Fp.size(); ++i) F1[i] = (Fp[i] - Fm[i]) / (2 * kappa);
  for (std::size_t i = 0; i < Gp.size(); ++i) G1[i] = (Gp[i] - Gm[i]) / (2 * kappa);
  const double lE = 0.3;  // typical element size of the mesh (sizes 0.22 .. 0.45)
  std::printf("bending patch: max |dF/dkappa| on a DG copy = %.2e (scale Dn lE = %.2e)\n", test::max_abs(F1), Dn * lE);
  EXPECT_LT(test::max_abs(F1), 1e-9 * Dn * lE);
  const auto node_g = test::sum_director_copies(model, G1);
  const auto expect_g = boundary_nodal_loads(model, false, [&](const double n[2], double tr[3]) {
    tr[0] = -Dm * n[0], tr[1] = -nu * Dm * n[1], tr[2] = 0;  // M nu per unit kappa, M = Dm C0 (-1, 0, 0)
  });
  double err_nodes = 0, interior_max = 0;
  std::vector<char> on_boundary(model.mesh.num_nodes(), 0);
  for (const auto& b : model.topo.boundary)
    for (int j = 0; j < 3; ++j) on_boundary[model.mesh.node(b.element, edge_node(b.local_edge, j))] = 1;
  for (GlobalId n = 0; n < model.mesh.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      err_nodes = std::max(err_nodes, std::abs(node_g[n * 3 + c] - expect_g[n * 3 + c]));
      if (!on_boundary[n]) interior_max = std::max(interior_max, std::abs(node_g[n * 3 + c]));
    }
  std::printf("bending patch: max interior director-moment sum %.2e, max nodal |g - g_consistent| %.2e (Dm lE %.2e)\n",
              interior_max, err_nodes, Dm * lE);
  EXPECT_LT(err_nodes, 1e-10 * Dm * lE);  // includes the interior nodes (expected 0)
}
