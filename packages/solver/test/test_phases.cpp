// The phases of a step, on models built in memory (no deck file, no output file): the start-up accelerations,
// the constraint projections of the predictor and corrector, and the support reactions when two conditions act
// on one node set. References:
//  * a free plate in its stress-free reference state (docs/theory.md §5: forces vanish there to round-off) under
//    gravity g, with a uniform initial velocity v0 and mass damping alpha, starts with a = g - alpha v0 at every
//    node (paper eq. 49 with the damping force alpha m v) and T-ddot = 0;
//  * held nodes stay at X and keep t0, components under a velocity program follow its exact integral, and no
//    motion crosses a symmetry plane; the director of a node on a symmetry plane stays in it (docs/theory.md §10.1);
//  * at rest under gravity, a symmetry plane with normal n pushes each of its nodes with n (f - f_ext) . n, so two
//    orthogonal planes on one node set carry the two components of the set's weight and together the whole load
//    on the set's normal plane, as a clamp of the same set does.
#include <gtest/gtest.h>

#include <cmath>

#include "deck_test_util.hpp"
#include "in_memory_model.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/model/shell_state.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

/// A 2 x 1 plate, 4 x 2 cells, steel-like section (deck_test_util.hpp), built in memory.
Teuchos::RCP<Teuchos::ParameterList> plate_deck() {
  auto deck = base_deck();
  set_rectangle(*deck, 2.0, 1.0, 4, 2);
  return deck;
}

/// Flag per mesh node: member of node set `name`.
std::vector<char> node_set(const mesh::SerialMesh& mesh, const std::string& name) {
  std::vector<char> member(mesh.num_nodes(), 0);
  for (const auto& ns : mesh.node_sets)
    if (ns.name == name)
      for (GlobalId n : ns.nodes) member[n] = 1;
  return member;
}

}  // namespace

TEST(Phases, StartUpAccelerationIsGravityMinusDamping) {
  const double g = -9.81, alpha = 5.0, v0 = 2.0;
  auto deck = plate_deck();
  deck->sublist("Time Integration").set("Mass Damping", alpha);
  auto& gravity = deck->sublist("Loads").sublist("gravity");
  gravity.set("Type", std::string("Gravity")), gravity.set("Acceleration", vec3(0, 0, g));
  deck->sublist("Initial Conditions").sublist("kick").set("Velocity", vec3(0, 0, v0));
  const auto model = build_model(deck);
  const auto& s = model.dynamics->state();
  const double expected = g - alpha * v0, tol = 1e-9 * std::abs(expected);
  for (LocalId le = 0; le < model.distributed->num_owned(); ++le) {
    for (int A = 0; A < 6; ++A) {
      EXPECT_NEAR(s.a.at(le, A)[0], 0.0, tol);
      EXPECT_NEAR(s.a.at(le, A)[1], 0.0, tol);
      EXPECT_NEAR(s.a.at(le, A)[2], expected, tol) << "element " << le << " node " << A;
    }
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 2; ++c) EXPECT_NEAR(s.director_acceleration.at(le, b)[c], 0.0, 1e-6);
  }
}

TEST(Phases, ConstraintsHoldProjectAndPrescribe) {
  const double V = 0.1, ramp = 2e-4;
  auto deck = plate_deck();
  boundary_condition(*deck, "clamp", "Clamped", "y_min");
  boundary_condition(*deck, "mirror", "Symmetry", "x_min").set("Normal", vec3(1, 0, 0));
  auto& lift = boundary_condition(*deck, "lift", "Prescribed Velocity", "x_max");
  lift.set("Velocity", vec3(0, 0, V)), lift.set("Components", std::string("z")), lift.set("Ramp Time", ramp);
  deck->sublist("Initial Conditions").sublist("kick").set("Velocity", vec3(0.3, 0.2, 1.0));
  auto& gravity = deck->sublist("Loads").sublist("gravity");
  gravity.set("Type", std::string("Gravity")), gravity.set("Acceleration", vec3(1.0, 2.0, -9.81));
  auto model = build_model(deck);
  auto& dyn = *model.dynamics;
  for (int k = 0; k < 60; ++k) dyn.step();
  const auto& s = dyn.state();
  const auto& X = dyn.model().X;
  const auto& dm = *model.distributed;
  const auto clamp = node_set(*model.mesh, "y_min"), mirror = node_set(*model.mesh, "x_min"),
             lifted = node_set(*model.mesh, "x_max");
  // The exact integral of the cosine ramp (docs/theory.md §10.2) at the current time.
  const double t = dyn.time(), tr = ramp;
  const double uz = t < tr ? V * (0.5 * t - tr / (2 * M_PI) * std::sin(M_PI * t / tr)) : V * (t - 0.5 * tr);
  int moved_freely = 0, held = 0, mirrored = 0, driven = 0;
  for (LocalId le = 0; le < dm.num_owned(); ++le)
    for (int A = 0; A < 6; ++A) {
      const GlobalId n = dm.mesh_node(le, A);
      const double *x = s.x.at(le, A), *x0 = X.at(le, A), *v = s.v.at(le, A);
      held += clamp[n], mirrored += mirror[n] && !clamp[n], driven += lifted[n] && !clamp[n];
      if (clamp[n]) {  // held, whatever else acts on the node
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(x[c], x0[c]);
          EXPECT_EQ(v[c], 0.0);
        }
        if (A < 3) {
          EXPECT_EQ(s.t.at(le, A)[2], 1.0);
        }
        continue;
      }
      if (lifted[n]) {
        EXPECT_NEAR(x[2] - x0[2], uz, 1e-15) << "the z program of node " << n;
        moved_freely += std::abs(x[0] - x0[0]) > 1e-6;  // x is free
      } else if (mirror[n]) {
        EXPECT_NEAR(x[0] - x0[0], 0.0, 1e-15) << "node " << n << " crossed the symmetry plane";
        EXPECT_NEAR(v[0], 0.0, 1e-12);
        if (A < 3) {
          EXPECT_NEAR(s.t.at(le, A)[0], 0.0, 1e-14) << "director of node " << n << " left the plane";
        }
      }
    }
  if (parallel::size() == 1) {
    EXPECT_GT(moved_freely, 0);
    EXPECT_GT(held, 0);
    EXPECT_GT(mirrored, 0);
    EXPECT_GT(driven, 0);
  }
}

TEST(Phases, TwoConditionsOnOneNodeSetShareItsReaction) {
  const double gy = -3.0, gz = -9.81;
  auto deck = plate_deck();
  boundary_condition(*deck, "floor", "Symmetry", "y_min").set("Normal", vec3(0, 0, 1));
  boundary_condition(*deck, "wall", "Symmetry", "y_min").set("Normal", vec3(0, 1, 0));
  auto& gravity = deck->sublist("Loads").sublist("gravity");
  gravity.set("Type", std::string("Gravity")), gravity.set("Acceleration", vec3(0, gy, gz));
  const auto model = build_model(deck);
  const auto r = model.dynamics->reactions();  // floor: force (3), couple (3); wall: force (3), couple (3)
  // Mass of every DG copy of the set's nodes.
  const auto member = node_set(*model.mesh, "y_min");
  const auto& dm = *model.distributed;
  double m = 0;
  for (LocalId le = 0; le < dm.num_owned(); ++le)
    for (int A = 0; A < 6; ++A)
      if (member[dm.mesh_node(le, A)]) m += *model.dynamics->model().mass.at(le, A);
  double m_all = 0;
  MPI_Allreduce(&m, &m_all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  ASSERT_GT(m_all, 0);
  const double tol = 1e-9 * m_all * std::abs(gz);
  // The floor carries z only, the wall y only.
  EXPECT_NEAR(r[0], 0.0, tol);
  EXPECT_NEAR(r[1], 0.0, tol);
  EXPECT_NEAR(r[2], -m_all * gz, tol);
  EXPECT_NEAR(r[6], 0.0, tol);
  EXPECT_NEAR(r[7], -m_all * gy, tol);
  EXPECT_NEAR(r[8], 0.0, tol);
  // A clamp of the same set carries the same total.
  auto clamped = plate_deck();
  boundary_condition(*clamped, "clamp", "Clamped", "y_min");
  auto& g2 = clamped->sublist("Loads").sublist("gravity");
  g2.set("Type", std::string("Gravity")), g2.set("Acceleration", vec3(0, gy, gz));
  const auto rc = build_model(clamped).dynamics->reactions();
  EXPECT_NEAR(rc[1], r[1] + r[7], tol);
  EXPECT_NEAR(rc[2], r[2] + r[8], tol);
}
