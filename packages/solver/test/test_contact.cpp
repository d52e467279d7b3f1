// Contact with rigid walls (docs/theory.md §12; solver/contact/rigid_walls.hpp), on models built in memory.
//
// A free elastic plate (1 x 1 in z = 0, h = 0.1, density 1: mass M = 0.1; 4 x 4 cells) moves at V = 1 along -z
// toward a fixed wall whose plane is at z = -(h/2 + 1.5 V dt): its lower face reaches it during the second step.
// Every DG position node has the same contact stiffness per unit mass s / dt^2 (Penalty Scale s) and reaches the
// wall at the same time, so the plate stays flat and stress-free and moves as a rigid body; each node follows the
// central-difference recurrence of a mass on a one-sided spring:
//   x_{n+1} = x_n + dt v_n + dt^2/2 a_n,  a_{n+1} = -(s/dt^2) min(0, x_{n+1} - x_wall),  v_{n+1} = v_n + dt/2 (a_n + a_{n+1}).
// References, from that recurrence computed here (exact up to round-off; tolerance 1e-9 relative for the dozens
// of rounding steps the run adds):
//  * the kinetic energy at every step, the rebound velocity after the plate has left the wall (the wall returns all
//    the energy: frictionless, no vibration excited) and the wall's normal force (M times the node's |a|);
//  * the energy balance (§11: the wall's force counts in the external work, trapezoidal): after the rebound it is
//    closed to round-off, because the trapezoidal work of a one-sided spring differs from the kinetic-energy
//    change by (M dt^2 / 8) (a_{n+1}^2 - a_n^2), which sums to zero once the acceleration is zero again.
// And the input: a penalty that would make the step unstable ((2 S_f)^2 + s >= 4) and a zero normal are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "deck_test_util.hpp"
#include "in_memory_model.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

constexpr double h = 0.1, V = 1.0, mass = 0.1;  // plate 1 x 1, density 1

Teuchos::RCP<Teuchos::ParameterList> falling_plate(double penalty_scale, double wall_z) {
  ShellSection section;
  section.thickness = h;
  auto deck = base_deck(section);
  set_rectangle(*deck, 1.0, 1.0, 4, 4);
  deck->sublist("Initial Conditions").sublist("fall").set("Velocity", vec3(0, 0, -V));
  auto& contact = deck->sublist("Contact");
  contact.set("Penalty Scale", penalty_scale);
  auto& wall = contact.sublist("Rigid Walls").sublist("floor");
  wall.set("Point", vec3(0, 0, wall_z)), wall.set("Normal", vec3(0, 0, 2));  // normalized by the input
  return deck;
}

/// The recurrence of the file comment for one node: its z (from 0), velocity and acceleration after each step.
struct Node {
  double z = 0, v = -V, a = 0;
};

}  // namespace

TEST(RigidWall, PlateReboundsAsTheCentralDifferenceRecurrencePredicts) {
  const double s = 0.25;
  // The step does not depend on the wall: take it from the model without one, then place the wall.
  const double dt = build_model(falling_plate(s, -1e3)).dynamics->time_step();
  const double wall_face = -1.5 * V * dt;  // where the mid-surface touches: the wall's plane is h/2 below
  auto model = build_model(falling_plate(s, wall_face - 0.5 * h));
  auto& dyn = *model.dynamics;
  ASSERT_EQ(dyn.time_step(), dt);
  const double e0 = dyn.record().kinetic;
  EXPECT_NEAR(e0, 0.5 * mass * V * V, 1e-12 * e0);

  Node n;
  const double k = s / (dt * dt);
  bool touched = false, left = false;
  int contact_steps = 0;
  for (int step = 1; step <= 40 && !left; ++step) {
    const double z = n.z + dt * n.v + 0.5 * dt * dt * n.a;
    const double a = -k * std::min(0.0, z - wall_face);
    n.v += 0.5 * dt * (n.a + a), n.z = z, n.a = a;
    dyn.step();
    const auto r = dyn.record();
    const double expected_kinetic = 0.5 * mass * n.v * n.v;
    EXPECT_NEAR(r.kinetic, expected_kinetic, 1e-9 * e0) << "step " << step;
    EXPECT_NEAR(dyn.wall_forces().at(0), mass * n.a, 1e-9 * mass * k * V * dt) << "step " << step;
    touched = touched || a > 0;
    contact_steps += a > 0;
    left = touched && a == 0;
  }
  ASSERT_TRUE(left) << "the plate has not left the wall";
  // The contact lasts about half a period of the spring, pi / omega = pi dt / sqrt(s) = 6.3 steps.
  EXPECT_GE(contact_steps, 5);
  EXPECT_LE(contact_steps, 8);
  EXPECT_GT(n.v, 0.0);
  EXPECT_NEAR(n.v, V, 0.01 * V);  // the discrete rebound (0.994 V here) is close to the continuous one, V
  const auto r = dyn.record();
  EXPECT_NEAR(r.kinetic, 0.5 * mass * n.v * n.v, 1e-9 * e0);
  EXPECT_LT(std::abs(solver::energy_balance_error(r, e0)), 1e-9 * e0);
  EXPECT_LT(r.strain, 1e-12 * e0);  // flat: no deformation
}

TEST(RigidWall, UnstablePenaltyAndZeroNormalRefused) {
  auto deck = falling_plate(2.0, -1.0);  // (2 x 0.8)^2 + 2 = 4.56 >= 4
  const std::string unstable = input_error(deck, "wall.xml");
  EXPECT_NE(unstable.find("wall.xml: 'Contact->Penalty Scale' = 2"), std::string::npos) << unstable;
  EXPECT_NE(unstable.find("makes the step unstable"), std::string::npos) << unstable;
  deck = falling_plate(0.25, -1.0);
  deck->sublist("Contact").sublist("Rigid Walls").sublist("floor").set("Normal", vec3(0, 0, 0));
  const std::string zero = input_error(deck, "wall.xml");
  EXPECT_NE(zero.find("'shellfrac->Contact->Rigid Walls->floor->Normal' is zero"), std::string::npos) << zero;
}
