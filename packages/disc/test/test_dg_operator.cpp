// The DG shell operator (theory.md §5) assembled serially over small meshes. References:
//  * rigid motions x = R X + b, t = R t0 produce zero strain energy and zero forces (objectivity, §2);
//  * the assembled forces are the exact gradient of the total discrete energy Pi_h (§5.6): checked by
//    central finite differences on a state with discontinuous (DG) perturbations, so that liftings and
//    penalties are all active; for each strain treatment (theory.md §5.4: point values, the P1 projection, the
//    stabilized mean membrane strains with projected shear strains);
//  * membrane patch test: a uniform stretch of a distorted flat mesh gives a uniform membrane state, so the
//    DG copies of every interior mesh node are in equilibrium and Pi_h = 1/2 N:eps |S|, for each treatment (a
//    uniform strain is its own projection).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dg_test_model.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;
using shellfrac::disc::test::max_abs;
using shellfrac::disc::test::Model;

namespace {

/// A strain treatment of theory.md §5.4 and the membrane remainder of every element.
struct Treatment {
  StrainTreatment spaces;
  double membrane_remainder;
};
/// The treatments the tests run through: point values, the P1 projection, the stabilized mean with projected shear.
const Treatment treatments[] = {{{}, 0}, {{StrainSpace::p1}, 0}, {{StrainSpace::p0, StrainSpace::p1}, 0.3}};

/// The treatment as text for failure messages.
std::string describe(const Treatment& t) {
  return "membrane space " + std::to_string(int(t.spaces.membrane)) + ", shear space " +
         std::to_string(int(t.spaces.shear)) + ", remainder " + std::to_string(t.membrane_remainder);
}

void apply(const Treatment& t, Model& model) {
  for (auto& r : model.refs) r.strains = t.spaces, r.membrane_remainder = t.membrane_remainder;
}

mesh::SerialMesh curved_mesh() {
  auto m = mesh::make_cylindrical_panel(1.0, 1.2, 1.0, 3, 2, mesh::DiagonalPattern::Alternating);
  mesh::promote_to_p2(m);
  return m;
}

/// Random rotation from a fixed-seed generator.
void random_rotation(std::mt19937& rng, double R[3][3]) {
  std::normal_distribution<double> n(0, 1);
  double q[4] = {n(rng), n(rng), n(rng), n(rng)};
  const double s = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& v : q) v /= s;
  const double w = q[0], a = q[1], b = q[2], c = q[3];
  const double M[3][3] = {{1 - 2 * (b * b + c * c), 2 * (a * b - c * w), 2 * (a * c + b * w)},
                          {2 * (a * b + c * w), 1 - 2 * (a * a + c * c), 2 * (b * c - a * w)},
                          {2 * (a * c - b * w), 2 * (b * c + a * w), 1 - 2 * (a * a + b * b)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = M[i][j];
}

}  // namespace

TEST(DgOperator, ReferenceStateIsStressFree) {
  Model model(curved_mesh());
  std::vector<double> F, G;
  EXPECT_NEAR(model.energy_and_forces(F, G), 0.0, 1e-18);
  EXPECT_LT(max_abs(F), 1e-11 * model.beta_x);
  EXPECT_LT(max_abs(G), 1e-11 * model.beta_x);
}

TEST(DgOperator, RigidMotionGivesZeroForces) {
  Model model(curved_mesh());
  std::mt19937 rng(7);
  double R[3][3];
  random_rotation(rng, R);
  const double b[3] = {0.3, -1.2, 2.0};
  for (std::size_t i = 0; i < model.X.size() / 3; ++i)
    for (int r = 0; r < 3; ++r)
      model.x[3 * i + r] = b[r] + R[r][0] * model.X[3 * i] + R[r][1] * model.X[3 * i + 1] + R[r][2] * model.X[3 * i + 2];
  for (std::size_t i = 0; i < model.T0.size() / 3; ++i)
    for (int r = 0; r < 3; ++r)
      model.t[3 * i + r] = R[r][0] * model.T0[3 * i] + R[r][1] * model.T0[3 * i + 1] + R[r][2] * model.T0[3 * i + 2];
  std::vector<double> F, G;
  // Scale: a unit strain would give energies ~ E h |S| = 50 and forces ~ beta_x = 150.
  EXPECT_LT(std::abs(model.energy_and_forces(F, G)), 1e-20 * 50 + 1e-22);
  EXPECT_LT(max_abs(F), 1e-11 * model.beta_x);
  EXPECT_LT(max_abs(G), 1e-11 * model.beta_x);
}

namespace {

void expect_forces_are_the_gradient(const Treatment& st) {
  SCOPED_TRACE(describe(st));
  Model model(curved_mesh());
  apply(st, model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  // A discontinuous state: every DG copy moved independently, directors perturbed off the sphere.
  for (double& v : model.x) v += 0.02 * u(rng);
  for (double& v : model.t) v += 0.05 * u(rng);
  std::vector<double> F, G;
  model.energy_and_forces(F, G);
  const double scale = std::max(max_abs(F), max_abs(G));
  ASSERT_GT(scale, 0.0);
  std::uniform_int_distribution<std::size_t> pick_x(0, model.x.size() - 1), pick_t(0, model.t.size() - 1);
  const double h = 1e-6;
  for (int trial = 0; trial < 60; ++trial) {
    const bool director = trial % 3 == 2;
    auto& v = director ? model.t : model.x;
    const std::size_t i = director ? pick_t(rng) : pick_x(rng);
    const double v0 = v[i];
    v[i] = v0 + h;
    const double ep = model.energy();
    v[i] = v0 - h;
    const double em = model.energy();
    v[i] = v0;
    const double fd = (ep - em) / (2 * h);
    const double an = director ? G[i] : F[i];
    EXPECT_NEAR(an, fd, 1e-6 * scale) << (director ? "director" : "position") << " dof " << i;
  }
}

void expect_membrane_patch_test(const Treatment& st) {
  SCOPED_TRACE(describe(st));
  // Flat unstructured patch: move interior vertices of a structured mesh (straight edges, affine elements).
  auto m = mesh::make_rectangle(2.0, 1.0, 4, 3, mesh::DiagonalPattern::Alternating);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.12, 0.12);
  for (auto& p : m.coords)
    if (p[0] > 1e-12 && p[0] < 2 - 1e-12 && p[1] > 1e-12 && p[1] < 1 - 1e-12) p[0] += u(rng), p[1] += u(rng);
  mesh::promote_to_p2(m);
  const double E = 1.0e3, nu = 0.3, h = 0.05;
  Model model(m, E, nu, h);
  apply(st, model);
  // x = F X with F = [[1+s, g, 0], [0, 1+r, 0], [0, 0, 1]], t = e3: uniform membrane strain.
  const double s = 1e-3, r = -4e-4, gsh = 2e-4;
  for (std::size_t i = 0; i < model.X.size() / 3; ++i) {
    const double X0 = model.X[3 * i], X1 = model.X[3 * i + 1];
    model.x[3 * i] = (1 + s) * X0 + gsh * X1;
    model.x[3 * i + 1] = (1 + r) * X1;
  }
  std::vector<double> F, G;
  const double energy = model.energy_and_forces(F, G);
  // Exact Green-Lagrange strain of the uniform deformation and its membrane energy.
  const double e11 = 0.5 * ((1 + s) * (1 + s) - 1), e22 = 0.5 * ((1 + r) * (1 + r) + gsh * gsh - 1);
  const double e12 = 0.5 * (1 + s) * gsh;
  const double Dn = E * h / (1 - nu * nu);
  const double N11 = Dn * (e11 + nu * e22), N22 = Dn * (e22 + nu * e11), N12 = Dn * (1 - nu) / 2 * 2 * e12;
  EXPECT_NEAR(energy, 0.5 * (N11 * e11 + N22 * e22 + N12 * 2 * e12) * 2.0, 1e-10 * std::abs(energy));
  // Equilibrium of interior mesh nodes: the forces on all DG copies of a node sum to zero.
  std::vector<double> node_force(m.num_nodes() * 3, 0.0);
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) node_force[m.node(e, A) * 3 + c] += F[e * 18 + A * 3 + c];
  const double fscale = std::abs(N11) * 0.5;  // a boundary node carries ~ N x edge length
  for (GlobalId n = 0; n < m.num_nodes(); ++n) {
    const auto& p = m.coords[n];
    const bool interior = p[0] > 1e-12 && p[0] < 2 - 1e-12 && p[1] > 1e-12 && p[1] < 1 - 1e-12;
    if (!interior) continue;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(node_force[n * 3 + c], 0.0, 1e-9 * fscale) << "node " << n;
  }
  // Total x-reaction on the x = 2 edge: the force per unit reference length is n^1 = N^{1j} a_j (theory.md
  // §3.2) with a_1 = F e1, a_2 = F e2; its x-component times the width 1.
  double rx = 0;
  for (GlobalId n = 0; n < m.num_nodes(); ++n)
    if (m.coords[n][0] > 2 - 1e-12) rx += node_force[n * 3];
  EXPECT_NEAR(rx, (N11 * (1 + s) + N12 * gsh) * 1.0, 1e-9 * std::abs(N11));
}

}  // namespace

TEST(DgOperator, ForcesAreTheExactGradientOfTheDiscreteEnergy) {
  for (const auto& st : treatments) expect_forces_are_the_gradient(st);
}

TEST(DgOperator, MembranePatchTestOnDistortedMesh) {
  for (const auto& st : treatments) expect_membrane_patch_test(st);
}
