// Verification of the DG shell operator (theory.md §5) at the operator level (serial, no time stepping).
// Each test states its reference:
//  * LiftingJumpIdentity: theory.md §5.2 (one-sided lifting of a constant jump; the two halves
//    of the jump measure -[u] (x) nu delta_e), for the P1 position lifting and the P0 director lifting;
//  * ContinuousFieldsHaveClassicalDgDerivative: theory.md §5.2 "Consistency";
//  * ZeroEnergyModes*: theory.md §5.5: a free 3x3-square plate has exactly 6 zero modes with c > 0, and
//    114 with c = 0 (P1/P0 lifting);
//  * UniformBendingPatchTest: a uniform curvature state is represented exactly on a distorted flat mesh,
//    so the discrete energy is the exact 1/2 D_m kappa^2 |S| (+ a known O(kappa^4) membrane part) and the
//    DG copies of interior nodes are in equilibrium (the bending analogue of the membrane patch test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "dg_test_model.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;
using shellfrac::disc::test::Model;

namespace {

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Eigenvalues (ascending) of a dense symmetric n x n matrix (row-major) by the cyclic Jacobi method.
std::vector<double> symmetric_eigenvalues(std::vector<double> A, int n) {
  auto a = [&](int i, int j) -> double& { return A[static_cast<std::size_t>(i) * n + j]; };
  double total = 0;
  for (double v : A) total += v * v;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += a(p, q) * a(p, q);
    if (off <= 1e-30 * total) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a(p, q);
        if (std::abs(apq) <= 1e-300) continue;
        const double theta = (a(q, q) - a(p, p)) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c, tau = s / (1 + c);
        a(p, p) -= t * apq;
        a(q, q) += t * apq;
        a(p, q) = a(q, p) = 0;
        for (int r = 0; r < n; ++r) {
          if (r == p || r == q) continue;
          const double g = a(r, p), h = a(r, q);
          a(r, p) = a(p, r) = g - s * (h + g * tau);
          a(r, q) = a(q, r) = h + s * (g - h * tau);
        }
      }
  }
  std::vector<double> ev(n);
  for (int i = 0; i < n; ++i) ev[i] = a(i, i);
  std::sort(ev.begin(), ev.end());
  return ev;
}

/// Two flat affine P2 elements sharing one edge, in a tilted plane (generic quadrilateral split by a diagonal).
mesh::SerialMesh two_element_mesh() {
  auto m = mesh::make_rectangle(1.0, 1.0, 1, 1, mesh::DiagonalPattern::Right);
  for (auto& p : m.coords) {
    if (p[0] > 0.5 && p[1] > 0.5) p = {1.3, 0.9, 0.0};
    else if (p[0] > 0.5) p = {1.1, -0.2, 0.0};
    else if (p[1] > 0.5) p = {-0.1, 0.8, 0.0};
  }
  mesh::promote_to_p2(m);  // straight edges: mid-side nodes at the midpoints
  // Rigid rotation (about (1, 2, 3)/|.|, angle 0.7) and translation of the whole patch.
  const double ax[3] = {1 / std::sqrt(14.0), 2 / std::sqrt(14.0), 3 / std::sqrt(14.0)}, th = 0.7;
  const double c = std::cos(th), s = std::sin(th);
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0) + (1 - c) * ax[i] * ax[j];
  R[0][1] -= s * ax[2], R[0][2] += s * ax[1], R[1][0] += s * ax[2];
  R[1][2] -= s * ax[0], R[2][0] -= s * ax[1], R[2][1] += s * ax[0];
  for (auto& p : m.coords) {
    const Vec3 q = p;
    for (int i = 0; i < 3; ++i) p[i] = 0.4 * (i + 1) + R[i][0] * q[0] + R[i][1] * q[1] + R[i][2] * q[2];
  }
  return m;
}

}  // namespace

// Reference: theory.md §5.2. With u = c on E1 and u = 0 on E2 (nu the outward co-normal of E1
// on the shared edge e, |e| its length):  int_{E1} d^DG_i u dS0 = int_{E2} d^DG_i u dS0 = -1/2 c nu_i |e|
// (local Cartesian components i). For affine elements this is exact (J^-1 constant, 3-point Gauss exact on
// a straight edge). Also the P1 moments of the position lifting, int_E d^DG_i u L_b dS0 =
// -1/2 c nu_i int_e L_b ds = -1/2 c nu_i |e|/2 for the two vertices b of e and 0 for the third, and the P0
// director lifting is uniform: d^DG_i t = -1/2 c_t nu_i |e| / |E| at every area point.
TEST(DgVerification, LiftingJumpIdentity) {
  const Vec3 c = {0.3, -0.7, 0.45}, ct = {-0.2, 0.5, 0.35};
  double worst_int = 0, worst_moment = 0, worst_director = 0;
  for (GlobalId displaced = 0; displaced < 2; ++displaced) {  // both +/- labellings of E1
    Model model(two_element_mesh());
    ASSERT_EQ(model.mesh.num_elements(), 2);
    ASSERT_EQ(model.topo.interfaces.size(), 1u);
    const auto& f = model.topo.interfaces[0];
    auto local_edge = [&](GlobalId e) { return e == f.minus.element ? f.minus.local_edge : f.plus.local_edge; };
    const int k1 = local_edge(displaced);
    ASSERT_TRUE(model.lift[0][local_edge(0)] && model.lift[1][local_edge(1)]);
    // Independent geometry of the shared edge: end points, length, outward co-normal of E1 (in-plane,
    // perpendicular to e, pointing away from E1's third vertex).
    const Vec3 Va = model.mesh.coords[model.mesh.node(displaced, edge_node(k1, 0))];
    const Vec3 Vb = model.mesh.coords[model.mesh.node(displaced, edge_node(k1, 1))];
    const Vec3 Vc = model.mesh.coords[model.mesh.node(displaced, (k1 + 2) % 3)];
    Vec3 tau, d, nu;
    for (int i = 0; i < 3; ++i) tau[i] = Vb[i] - Va[i], d[i] = Vc[i] - Va[i];
    const double elen = std::sqrt(dot(tau, tau));
    for (double& v : tau) v /= elen;
    const double dt = dot(d, tau);
    for (int i = 0; i < 3; ++i) nu[i] = -(d[i] - dt * tau[i]);
    const double nn = std::sqrt(dot(nu, nu));
    for (double& v : nu) v /= nn;
    // DG copies of E1 displaced by c (positions) and ct (directors), E2 not.
    for (int A = 0; A < 6; ++A)
      for (int i = 0; i < 3; ++i) model.x[displaced * 18 + A * 3 + i] += c[i];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) model.t[displaced * 9 + a * 3 + i] += ct[i];
    for (GlobalId e = 0; e < 2; ++e) {
      double Xe[6][3];
      for (int A = 0; A < 6; ++A)
        for (int i = 0; i < 3; ++i) Xe[A][i] = model.X[e * 18 + A * 3 + i];
      ShellKinematics kin[num_area_points];
      dg_kinematics(model.refs[e], model.element_nodes(e), kin);
      const DgElementRef& R = model.refs[e];
      AreaPointShapes S;
      area_point_shapes(S);
      const int ke = local_edge(e);
      // Local Cartesian basis (constant on an affine element) and the components nu_i = nu . e_i.
      AreaPointGeometry geo;
      area_point_geometry(Xe, tri6_rule.xi[0][0], tri6_rule.xi[0][1], tri6_rule.w[0], geo);
      const double* ei[2] = {geo.e1, geo.e2};
      const double nui[2] = {nu[0] * geo.e1[0] + nu[1] * geo.e1[1] + nu[2] * geo.e1[2],
                             nu[0] * geo.e2[0] + nu[1] * geo.e2[1] + nu[2] * geo.e2[2]};
      EXPECT_NEAR(nui[0] * nui[0] + nui[1] * nui[1], 1.0, 1e-14);  // nu lies in the element's plane
      for (int i = 0; i < 2; ++i)
        for (int r = 0; r < 3; ++r) {
          double integral = 0, dintegral = 0, moment[3] = {0, 0, 0};
          for (int q = 0; q < num_area_points; ++q) {
            const double du = kin[q].a[i][r] - ei[i][r];  // d^DG_i (x - X), since d_i X = e_i
            integral += R.wj0[q] * du;
            for (int b = 0; b < 3; ++b) moment[b] += R.wj0[q] * du * S.L[q][b];
            dintegral += R.wj0[q] * kin[q].d[i][r];  // flat: d^DG t0 = 0
            // P0 director lifting: uniform derivative -1/2 ct_r nu_i |e| / |E|.
            worst_director = std::max(worst_director, std::abs(kin[q].d[i][r] + 0.5 * ct[r] * nui[i] * elen / R.area));
          }
          worst_int = std::max(worst_int, std::abs(integral + 0.5 * c[r] * nui[i] * elen));
          worst_director = std::max(worst_director, std::abs(dintegral + 0.5 * ct[r] * nui[i] * elen));
          for (int b = 0; b < 3; ++b) {
            const bool on_edge = b == edge_node(ke, 0) || b == edge_node(ke, 1);
            const double expect = on_edge ? -0.5 * c[r] * nui[i] * elen / 2 : 0.0;
            worst_moment = std::max(worst_moment, std::abs(moment[b] - expect));
          }
        }
    }
  }
  // The jumps are O(1) and |e| ~ 1: the identities must hold to round-off.
  std::printf("lifting identity: max error of int d^DG u %.2e, of its P1 moments %.2e, of d^DG t %.2e\n", worst_int,
              worst_moment, worst_director);
  EXPECT_LT(worst_int, 1e-13);
  EXPECT_LT(worst_moment, 1e-13);
  EXPECT_LT(worst_director, 1e-13);
}

// Reference: theory.md §5.2 "Consistency": if u is continuous, all jumps vanish and d^DG = d:
// random continuous P2 positions and P1 directors on a curved (cylindrical) P2 mesh; the DG kinematics with
// every interior edge lifted equal those with no edge lifted (the classical derivatives) to round-off.
TEST(DgVerification, ContinuousFieldsHaveClassicalDgDerivative) {
  auto m = mesh::make_cylindrical_panel(1.0, 1.2, 1.0, 3, 2, mesh::DiagonalPattern::Alternating);
  mesh::promote_to_p2(m);
  Model model(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> xnode(m.num_nodes()), tnode(m.num_nodes());
  for (auto& v : xnode) v = {u(rng), u(rng), u(rng)};
  for (auto& v : tnode) v = {u(rng), u(rng), u(rng)};
  for (GlobalId e = 0; e < m.num_elements(); ++e) {
    for (int A = 0; A < 6; ++A)
      for (int i = 0; i < 3; ++i) model.x[e * 18 + A * 3 + i] = model.X[e * 18 + A * 3 + i] + 0.1 * xnode[m.node(e, A)][i];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) model.t[e * 9 + a * 3 + i] = tnode[m.node(e, a)][i];
  }
  double worst = 0, scale = 0;
  int lifted = 0;
  for (GlobalId e = 0; e < m.num_elements(); ++e) {
    const DgElementNodes in = model.element_nodes(e);
    DgElementNodes unlifted = in;
    unlifted.lift[0] = unlifted.lift[1] = unlifted.lift[2] = false;
    lifted += in.lift[0] + in.lift[1] + in.lift[2];
    ShellKinematics kdg[num_area_points], kcl[num_area_points];
    dg_kinematics(model.refs[e], in, kdg);
    dg_kinematics(model.refs[e], unlifted, kcl);
    for (int q = 0; q < num_area_points; ++q)
      for (int i = 0; i < 2; ++i)
        for (int r = 0; r < 3; ++r) {
          worst = std::max({worst, std::abs(kdg[q].a[i][r] - kcl[q].a[i][r]), std::abs(kdg[q].d[i][r] - kcl[q].d[i][r])});
          scale = std::max({scale, std::abs(kcl[q].a[i][r]), std::abs(kcl[q].d[i][r])});
        }
  }
  ASSERT_GT(lifted, 0);
  std::printf("continuous fields: max |d^DG - d| = %.2e (max |d| = %.2e)\n", worst, scale);
  EXPECT_LT(worst, 1e-13 * scale);
}

namespace {

/// Free flat n x n unit square, alternating diagonals, P2 (the mesh of theory.md §5.5).
mesh::SerialMesh flat_square(int n) {
  auto m = mesh::make_rectangle(1.0, 1.0, n, n, mesh::DiagonalPattern::Alternating);
  mesh::promote_to_p2(m);
  return m;
}

/// Stiffness of the assembled operator at the reference state by central differences of the assembled
/// forces, in the generalized coordinates: all 18 position components of every element copy, then the 2
/// tangent components (e1, e2; t0 = e3 on the flat patch) of every director copy. Symmetrized; `asym`
/// returns max |K - K^T| / max |K|.
std::vector<double> fd_stiffness(Model& model, int& n, double& asym) {
  const GlobalId ne = model.mesh.num_elements();
  const int npos = static_cast<int>(ne * 18);
  n = static_cast<int>(ne * 24);
  auto dof = [&](int j) -> double& {
    if (j < npos) return model.x[j];
    const int k = j - npos;  // director copy k / 2, tangent component k % 2
    return model.t[(k / 2) * 3 + k % 2];
  };
  auto gen_forces = [&](std::vector<double>& out) {
    std::vector<double> F, G;
    model.energy_and_forces(F, G);
    out.assign(n, 0.0);
    for (int j = 0; j < npos; ++j) out[j] = F[j];
    for (int k = 0; k < n - npos; ++k) out[npos + k] = G[(k / 2) * 3 + k % 2];
  };
  const double h = 1e-6;
  std::vector<double> K(static_cast<std::size_t>(n) * n), fp, fm;
  for (int j = 0; j < n; ++j) {
    double& v = dof(j);
    const double v0 = v;
    v = v0 + h;
    gen_forces(fp);
    v = v0 - h;
    gen_forces(fm);
    v = v0;
    for (int i = 0; i < n; ++i) K[static_cast<std::size_t>(i) * n + j] = (fp[i] - fm[i]) / (2 * h);
  }
  double kmax = 0, amax = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      kmax = std::max(kmax, std::abs(K[i * n + j]));
      amax = std::max(amax, std::abs(K[i * n + j] - K[j * n + i]));
    }
  asym = amax / kmax;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) K[i * n + j] = K[j * n + i] = 0.5 * (K[i * n + j] + K[j * n + i]);
  return K;
}

struct ModeCount {
  int zero;        ///< eigenvalues below 1e-8 lambda_max
  double lam_max;  ///< largest eigenvalue
  double lam_gap;  ///< smallest eigenvalue above the threshold, relative to lambda_max
  double lam_zero; ///< largest |eigenvalue| below the threshold, relative to lambda_max
};

ModeCount count_zero_modes(int cells, double c) {
  Model model(flat_square(cells), 1.0e3, 0.3, 0.05, c);
  for (std::size_t i = 0; i < model.T0.size() / 3; ++i) {  // t0 = e3: the tangent directions are e1, e2
    EXPECT_NEAR(model.T0[3 * i + 2], 1.0, 1e-14);
  }
  int n = 0;
  double asym = 0;
  const auto K = fd_stiffness(model, n, asym);
  EXPECT_LT(asym, 1e-7);  // the assembled forces are a gradient: K is symmetric up to the FD error
  const auto ev = symmetric_eigenvalues(K, n);
  ModeCount r{0, ev.back(), 0, 0};
  for (double l : ev)
    if (std::abs(l) < 1e-8 * r.lam_max) ++r.zero, r.lam_zero = std::max(r.lam_zero, std::abs(l) / r.lam_max);
  r.lam_gap = r.zero < n ? ev[r.zero] / r.lam_max : 0;
  EXPECT_GT(ev.front(), -1e-8 * r.lam_max);  // positive semi-definite
  std::printf("%dx%d square, c_x = c_T = %g: %d dofs, asym %.1e, lambda_max %.3e, #zero %d (max %.1e), next %.2e\n",
              cells, cells, c, n, asym, r.lam_max, r.zero, r.lam_zero, r.lam_gap);
  return r;
}

}  // namespace

// Reference: theory.md §5.5: with c_x = c_T = 3 the only zero-energy modes of the linearized free
// flat patch are the 6 rigid-body modes (3 translations, 3 rotations; the drilling rotation is excluded by
// the 2-component director parametrization). Without penalty (c = 0) there are spurious modes.
TEST(DgVerification, ZeroEnergyModes2x2) {
  const auto stab = count_zero_modes(2, 3.0);
  EXPECT_EQ(stab.zero, 6);
  EXPECT_GT(stab.lam_gap, 1e3 * stab.lam_zero);  // a clear spectral gap above the rigid modes
  const auto free = count_zero_modes(2, 0.0);
  EXPECT_GT(free.zero, 6);
}

// Reference: theory.md §5.5: a free 3x3-square plate has exactly 6 zero modes with c > 0 and 114 with c = 0
// (P1/P0 lifting), counted independently on the linearized plate with the same DOFs as here (unit square,
// alternating diagonals, h = 0.05).
TEST(DgVerification, ZeroEnergyModes3x3MatchesTheIndependentCount) {
  const auto stab = count_zero_modes(3, 3.0);
  EXPECT_EQ(stab.zero, 6);
  EXPECT_GT(stab.lam_gap, 1e3 * stab.lam_zero);
  const auto free = count_zero_modes(3, 0.0);
  EXPECT_EQ(free.zero, 114);
}

// Reference: uniform bending patch test. On a flat distorted mesh of [0,2]x[0,1] (affine P2 elements), the
// state x = X + w(X) e3 with w = kappa X^2/2 (exactly P2) and the linear director field t = (-kappa X, 0, 1)
// (exactly P1, not normalized: the operator takes any t) is continuous, so no lifting or penalty acts, and
// exactly: a_1 = e1 + kappa X e3, a_2 = e2, d_1 = (-kappa, 0, 0), d_2 = 0, hence gamma = 0 (a_1 . t = 0),
// rho = (-kappa, 0, 0) uniform, eps = (kappa^2 X^2/2, 0, 0). Therefore
//   Pi_h = 1/2 D_m kappa^2 |S| + 1/2 D_n int (kappa^2 X^2/2)^2 dS = 1/2 D_m kappa^2 |S| + D_n kappa^4 (32/5)/8,
// the second term (O(kappa^2) relative: 3.8e-9 for kappa = 1e-6, h = 0.05) being the membrane contamination
// of the finite-amplitude state (integrated exactly by the degree-4 rule). At first order in kappa (central
// difference in kappa of the forces, which removes the O(kappa^2) non-uniform membrane and m^alpha . e3
// parts), the state is a uniform bending state: the position forces vanish, the director moments of the DG
// copies of every interior node sum to zero, and the boundary reactions are the edge moments
// sum g_x = M_11 * 1 = -D_m kappa on X = 2 (+D_m kappa on X = 0) and sum g_y = M_22 * 2 = -2 nu D_m kappa on
// Y = 1 (+ on Y = 0).
TEST(DgVerification, UniformBendingPatchTest) {
  auto m = mesh::make_rectangle(2.0, 1.0, 4, 3, mesh::DiagonalPattern::Alternating);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.12, 0.12);
  auto interior = [](const Vec3& p) { return p[0] > 1e-12 && p[0] < 2 - 1e-12 && p[1] > 1e-12 && p[1] < 1 - 1e-12; };
  for (auto& p : m.coords)
    if (interior(p)) p[0] += u(rng), p[1] += u(rng);
  mesh::promote_to_p2(m);
  const double E = 1.0e3, nu = 0.3, h = 0.05, area = 2.0;
  Model model(m, E, nu, h);
  for (std::size_t i = 0; i < model.T0.size() / 3; ++i) ASSERT_NEAR(model.T0[3 * i + 2], 1.0, 1e-14);
  const double Dm = model.section.Dm, Dn = model.section.Dn;
  auto set_state = [&](double kappa) {
    for (std::size_t i = 0; i < model.X.size() / 3; ++i) {
      const double X0 = model.X[3 * i];
      model.x[3 * i + 2] = model.X[3 * i + 2] + 0.5 * kappa * X0 * X0;
    }
    for (std::size_t i = 0; i < model.T0.size() / 3; ++i) model.t[3 * i] = -kappa * model.X[(i / 3) * 18 + (i % 3) * 3];
  };
  const double kappa = 1e-6;
  std::vector<double> Fp, Gp, Fm, Gm;
  set_state(kappa);
  const double energy = model.energy_and_forces(Fp, Gp);
  set_state(-kappa);
  model.energy_and_forces(Fm, Gm);
  // Energy: exact up to round-off (see above); the membrane part is 3.8e-9 of the total.
  const double Ub = 0.5 * Dm * kappa * kappa * area, Um = Dn * std::pow(kappa, 4) * (32.0 / 5.0) / 8.0;
  std::printf("bending patch: Pi_h = %.12e, 1/2 Dm k^2 |S| = %.12e, membrane part %.3e, rel. error %.2e\n", energy,
              Ub, Um, (energy - Ub - Um) / Ub);
  EXPECT_NEAR(energy, Ub + Um, 1e-10 * Ub);
  EXPECT_NEAR(energy, Ub, 1e-8 * Ub);  // membrane contamination Um / Ub = 3.8e-9 < 1e-8
  // First-order forces per unit kappa.
  const GlobalId ne = m.num_elements();
  std::vector<double> node_f(m.num_nodes() * 3, 0.0), node_g(m.num_nodes() * 3, 0.0);
  double fmax = 0;
  for (GlobalId e = 0; e < ne; ++e) {
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) {
        const double f1 = (Fp[e * 18 + A * 3 + c] - Fm[e * 18 + A * 3 + c]) / (2 * kappa);
        node_f[m.node(e, A) * 3 + c] += f1;
        fmax = std::max(fmax, std::abs(f1));
      }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) node_g[m.node(e, a) * 3 + c] += (Gp[e * 9 + a * 3 + c] - Gm[e * 9 + a * 3 + c]) / (2 * kappa);
  }
  // Position forces: zero at first order on every DG copy; scale of comparison: the nodal force of a membrane
  // strain of the same size kappa, D_n kappa * (element size 0.5).
  const double pos_scale = Dn * 0.5, mom_scale = Dm * 0.5;  // per unit kappa
  std::printf("bending patch: max |dF/dkappa| of a DG copy %.2e (scale %.2e)\n", fmax, pos_scale);
  EXPECT_LT(fmax, 1e-9 * pos_scale);
  double gint = 0;
  double rx0 = 0, rx2 = 0, ry0 = 0, ry1 = 0;
  for (GlobalId n = 0; n < m.num_nodes(); ++n) {
    const auto& p = m.coords[n];
    if (interior(p))
      for (int c = 0; c < 3; ++c) gint = std::max(gint, std::abs(node_g[n * 3 + c]));
    if (p[0] < 1e-12) rx0 += node_g[n * 3];
    if (p[0] > 2 - 1e-12) rx2 += node_g[n * 3];
    if (p[1] < 1e-12) ry0 += node_g[n * 3 + 1];
    if (p[1] > 1 - 1e-12) ry1 += node_g[n * 3 + 1];
  }
  std::printf("bending patch: max interior director-moment sum %.2e; reactions x: %.10e %.10e, y: %.10e %.10e (Dm %.10e)\n",
              gint, rx0, rx2, ry0, ry1, Dm);
  EXPECT_LT(gint, 1e-10 * mom_scale);
  EXPECT_NEAR(rx2, -Dm * 1.0, 1e-10 * Dm);
  EXPECT_NEAR(rx0, Dm * 1.0, 1e-10 * Dm);
  EXPECT_NEAR(ry1, -nu * Dm * 2.0, 1e-10 * Dm);
  EXPECT_NEAR(ry0, nu * Dm * 2.0, 1e-10 * Dm);
}
