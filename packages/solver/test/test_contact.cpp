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
#include "shellfrac/solver/contact/rigid_body_shape.hpp"
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

// Coulomb friction at a wall (theory.md §12.6; contact/coulomb_friction.hpp): test (c) of the contact issue. The
// plate above rests on the fixed wall z = delta - h/2 under gravity g, where delta = g_n dt^2 / s is the penetration
// at which the penalty force k m delta = m g_n carries every node's weight from the start (g_n: gravity's part along
// the normal), so the plate neither bounces nor deforms and every node slides alike: it moves as a rigid block
// whose tangential velocity u follows the explicit Coulomb recurrence of eqs. 12.6a-b (each step: the half-step
// velocity u_h = u + dt/2 a; the trial slip w = u_h + dt g_t; stick, a = -w/dt + g_t, when |w|/dt <= mu_s g_n;
// slide, a = g_t - mu_d g_n sign(w), otherwise; u = u_h + dt/2 a). References: that recurrence (1e-9, as above);
// and its continuous limits:
//  * a block launched at V on a level wall slides at the constant deceleration mu_d g (a block on a table: any
//    text on Coulomb friction) and stops after V / (mu_d g) having slid V^2 / (2 mu_d g) (within a step's V dt);
//    then it stays stopped: static friction holds it (to round-off: the trial slip is zero); the energy friction took is
//    its kinetic energy (1e-3; the dissipation's midpoint sum over a decelerating slide is exact but for the last
//    step);
//  * on a wall tilted by theta (gravity turned instead): below the static angle, tan theta < mu_s, a block at rest
//    stays at rest (to round-off; the static force is exactly m g sin theta); above it, it slides at
//    g (sin theta - mu_d cos theta) — with mu_d < tan theta < mu_s the two coefficients are told apart.
namespace {

Teuchos::RCP<Teuchos::ParameterList> block_on_wall(double dt, double theta, double g, double mu_d, double mu_s,
                                                   double velocity) {
  const double s = 0.25, gn = g * std::cos(theta), gt = g * std::sin(theta);
  auto deck = falling_plate(s, gn * dt * dt / s - 0.5 * h);
  deck->sublist("Initial Conditions").sublist("fall").set("Velocity", vec3(velocity, 0, 0));
  auto& gravity = deck->sublist("Loads").sublist("gravity");
  gravity.set("Type", std::string("Gravity")), gravity.set("Acceleration", vec3(gt, 0, -gn));
  deck->sublist("Contact").set("Friction Coefficient", mu_d);
  deck->sublist("Contact").set("Static Friction Coefficient", mu_s);
  return deck;
}

/// The explicit Coulomb recurrence of the file comment for the block's tangential motion.
struct Block {
  double x = 0, u = 0, a = 0;
  void step(double dt, double gn, double gt, double mu_d, double mu_s) {
    x += dt * u + 0.5 * dt * dt * a;
    const double uh = u + 0.5 * dt * a, w = uh + dt * gt;
    a = std::abs(w) / dt <= mu_s * gn ? gt - w / dt : gt - mu_d * gn * (w > 0 ? 1 : -1);
    u = uh + 0.5 * dt * a;
  }
};

/// The plate's mean x-displacement and x-velocity over all its DG nodes.
std::pair<double, double> block_motion(const solver::RunModel& model) {
  const auto p = model.dynamics->probes({std::vector<char>(std::size_t(model.counts.nodes), 1)});
  return {p.at(0), p.at(3)};
}

}  // namespace

TEST(RigidWallFriction, BlockSlidesAtMuGAndStops) {
  const double dt = build_model(falling_plate(0.25, -1e3)).dynamics->time_step();
  const double V = 1.0, mu_d = 0.3, mu_s = 0.5, g = V / (mu_d * 200 * dt);  // it stops after 200 steps
  auto model = build_model(block_on_wall(dt, 0.0, g, mu_d, mu_s, V));
  auto& dyn = *model.dynamics;
  ASSERT_EQ(dyn.contact_columns().back(), "friction_dissipation");
  const double e0 = dyn.record().kinetic;
  Block b;
  b.u = V, b.a = -mu_d * g;  // the start: sliding
  for (int step = 1; step <= 260; ++step) {
    b.step(dt, g, 0.0, mu_d, mu_s);
    dyn.step();
    const auto [x, u] = block_motion(model);
    EXPECT_NEAR(u, b.u, 1e-9 * V) << "step " << step;
    EXPECT_NEAR(x, b.x, 1e-9 * V * dt * step) << "step " << step;
    const double t = step * dt;
    if (t < V / (mu_d * g) - dt) {
      EXPECT_NEAR(u, V - mu_d * g * t, 0.5 * mu_d * g * dt) << "step " << step;
    }
    if (t > V / (mu_d * g) + dt) {
      EXPECT_LT(std::abs(u), 1e-15 * V) << "step " << step;  // stuck (to round-off)
    }
  }
  const auto [x, u] = block_motion(model);
  EXPECT_NEAR(x, V * V / (2 * mu_d * g), V * dt);
  const double dissipated = dyn.contact_values().back();
  EXPECT_NEAR(dissipated, e0, 1e-3 * e0);
  // Friction's work is external work (trapezoidal): the balance is closed but for the trapezoidal rule's
  // (M dt^2 / 8) (a_end^2 - a_0^2) of the wall test, a_0 = mu_d g, a_end = 0.
  const double trapezoid = mass * dt * dt / 8 * (mu_d * g) * (mu_d * g);
  EXPECT_NEAR(std::abs(solver::energy_balance_error(dyn.record(), e0)), trapezoid, 1e-3 * trapezoid);
  EXPECT_LT(dyn.record().strain, 1e-12 * e0);
}

TEST(RigidWallFriction, StaticAndDynamicCoefficientsOnAnIncline) {
  const double dt = build_model(falling_plate(0.25, -1e3)).dynamics->time_step();
  const double mu_d = 0.3, mu_s = 0.5, g = 1e-6 / (dt * dt);  // it slides about 0.13 in 1000 steps
  for (const double tan_theta : {0.4, 0.45}) {  // between mu_d and mu_s: sticks
    const double theta = std::atan(tan_theta);
    auto model = build_model(block_on_wall(dt, theta, g, mu_d, mu_s, 0.0));
    for (int step = 0; step < 1000; ++step) model.dynamics->step();
    const auto [x, u] = block_motion(model);
    EXPECT_LT(std::abs(u), 1e-12 * g * dt) << "tan theta " << tan_theta;  // at rest: held by static friction
    EXPECT_LT(std::abs(x), 1e-12 * g * dt * dt) << "tan theta " << tan_theta;
  }
  const double theta = std::atan(0.6);  // above mu_s: slides at g (sin - mu_d cos)
  auto model = build_model(block_on_wall(dt, theta, g, mu_d, mu_s, 0.0));
  Block b;
  b.a = g * (std::sin(theta) - mu_d * std::cos(theta));  // the start: the trial slip dt g_t is beyond the cone
  for (int step = 1; step <= 1000; ++step) {
    b.step(dt, g * std::cos(theta), g * std::sin(theta), mu_d, mu_s);
    model.dynamics->step();
    const auto [x, u] = block_motion(model);
    EXPECT_NEAR(u, b.u, 1e-9 * g * dt * step) << "step " << step;
  }
  const double t = 1000 * dt, slope = g * (std::sin(theta) - mu_d * std::cos(theta));
  EXPECT_NEAR(block_motion(model).second, slope * t, 2 * g * dt);
}

TEST(RigidWallFriction, StaticBelowDynamicRefused) {
  auto deck = falling_plate(0.25, -1.0);
  deck->sublist("Contact").set("Friction Coefficient", 0.4);
  deck->sublist("Contact").set("Static Friction Coefficient", 0.2);
  const std::string e = input_error(deck, "wall.xml");
  EXPECT_NE(e.find("wall.xml: 'shellfrac->Contact->Static Friction Coefficient' = 0.2 is below the 'Friction "
                   "Coefficient' 0.4"),
            std::string::npos)
      << e;
}

// Rigid bodies (theory.md §12.4; contact/rigid_body_shape.hpp, contact/rigid_bodies.hpp).
//
// The shapes' signed distances, against values worked out by hand: a sphere of radius 2 about (1, 2, 3); a
// projectile of radius 1, 3 long behind its Point (0, 0, 0), pointing along -z, with a conical nose of half-angle
// 45 deg (tip at z = -1), a hemispherical one (tip at z = -1) or a flat one.
namespace {

solver::RigidBody projectile(solver::RigidBody::Nose nose) {
  solver::RigidBody b;
  b.shape = solver::RigidBody::Shape::Cylinder, b.nose = nose;
  b.radius = 1, b.length = 3, b.half_angle = std::acos(-1.0) / 4, b.axis = {0, 0, -1};
  return b;
}

void expect_distance(const solver::RigidBody& b, const Vec3& x, double distance, const Vec3& normal) {
  const auto d = solver::surface_distance(b, b.point, x);
  EXPECT_NEAR(d.distance, distance, 1e-14) << x[0] << " " << x[1] << " " << x[2];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.normal[c], normal[c], 1e-14) << "component " << c;
}

}  // namespace

TEST(RigidBody, SignedDistancesOfTheShapes) {
  solver::RigidBody sphere;
  sphere.radius = 2, sphere.point = {1, 2, 3};
  expect_distance(sphere, {1, 2, 6}, 1, {0, 0, 1});
  expect_distance(sphere, {1 + 0.6, 2 + 0.8, 3}, -1, {0.6, 0.8, 0});
  using Nose = solver::RigidBody::Nose;
  const double r2 = std::sqrt(0.5);
  const auto cone = projectile(Nose::Conical);
  expect_distance(cone, {0, 0, -3}, 2, {0, 0, -1});            // ahead of the tip, on the axis
  expect_distance(cone, {0, 0, -0.5}, -0.5 * r2, {r2, 0, -r2});  // inside on the axis: nearest the flank (radial x)
  expect_distance(cone, {1, 0, -1}, r2, {r2, 0, -r2});         // beside the tip region: off the flank
  expect_distance(cone, {0, 2, 1.5}, 1, {0, 1, 0});            // beside the side
  expect_distance(cone, {0, 0.5, 4}, 1, {0, 0, 1});            // behind the back face
  expect_distance(cone, {0, 0.9, 1.5}, -0.1, {0, 1, 0});       // inside, near the side
  const auto round = projectile(Nose::Hemispherical);
  expect_distance(round, {0, 0, -3}, 2, {0, 0, -1});
  expect_distance(round, {0, 0.6, -0.8}, 0, {0, 0.6, -0.8});  // on the hemisphere
  expect_distance(round, {0, 0, -0.5}, -0.5, {0, 0, -1});
  // The bounding spheres hold the body: its tip and its back rim lie on them (cone: tip 1 ahead, back 3 behind).
  for (const auto& [b, tip] : {std::pair{cone, 1.0}, std::pair{round, 1.0}, std::pair{projectile(Nose::Flat), 0.0}}) {
    const auto s = solver::bounding_sphere(b);
    EXPECT_NEAR(s.offset, 0.5 * (tip - 3), 1e-15);
    EXPECT_NEAR(s.radius, std::hypot(0.5 * (tip + 3), 1.0), 1e-15);
  }
  EXPECT_EQ(solver::bounding_sphere(sphere).radius, 2.0);
  const auto flat = projectile(Nose::Flat);
  expect_distance(flat, {0.3, 0.4, -0.25}, 0.25, {0, 0, -1});
  expect_distance(flat, {0.3, 0.4, 0.25}, -0.25, {0, 0, -1});  // inside, nearest the face
}

// A free body strikes a free plate (the plate of the wall test, mass m = 0.1, at rest) face-on: a cylinder of radius 2
// with a flat nose pointing along -z covers the whole plate, mass M = 2 m, at V = 1; its face starts 1.5 V dt above
// the plate's upper face. Every node has the same stiffness per unit mass, so the plate stays flat and moves as a
// rigid body, and plate and body follow the central-difference recurrence of two masses on a one-sided spring:
//   g = z_b - z_p - h/2,  a_p = -(s/dt^2) <-g>,  a_b = +(s/dt^2) (m/M) <-g>   (each body: z += dt v + dt^2/2 a, ...).
// References: that recurrence (tolerance 1e-9 as for the wall); the total momentum m v_p + M v_b = M V to round-off at
// every step (the body takes minus the exact sum of the forces on the nodes); after the contact, the velocities of a
// 1-D elastic collision, v_p = 2M/(M+m) V, v_b = (M-m)/(M+m) V, within 2 % (the discrete switch loses about 1 % of the
// energy, as for the wall). A body too light for the step (M = m/20: s (1 + m/M) + (2 S_f)^2 > 4) stops the run.
namespace {

Teuchos::RCP<Teuchos::ParameterList> struck_plate(double body_mass, double face_z) {
  ShellSection section;
  section.thickness = h;
  auto deck = base_deck(section);
  set_rectangle(*deck, 1.0, 1.0, 4, 4);
  auto& body = deck->sublist("Contact").sublist("Rigid Bodies").sublist("ram");
  body.set("Shape", std::string("Cylinder")), body.set("Nose", std::string("Flat"));
  body.set("Radius", 2.0), body.set("Length", 1.0), body.set("Axis", vec3(0, 0, -1));
  body.set("Point", vec3(0.5, 0.5, face_z)), body.set("Velocity", vec3(0, 0, -V)), body.set("Mass", body_mass);
  return deck;
}

}  // namespace

TEST(RigidBody, FreeBodyStrikesAFreePlateAsTwoMassesOnASpring) {
  const double s = 0.25, M = 2 * mass;
  const double dt = build_model(struck_plate(M, 1e3)).dynamics->time_step();
  const double face0 = 0.5 * h + 1.5 * V * dt;
  auto model = build_model(struck_plate(M, face0));
  auto& dyn = *model.dynamics;
  ASSERT_EQ(dyn.time_step(), dt);
  const auto columns = dyn.contact_columns();
  ASSERT_EQ(columns.size(), 10u);
  EXPECT_EQ(columns[2], "ram_z");
  EXPECT_EQ(columns[9], "ram_kinetic_energy");
  double zp = 0, vp = 0, ap = 0, zb = face0, vb = -V, ab = 0;
  const double k = s / (dt * dt);
  bool touched = false, left = false;
  for (int step = 1; step <= 60 && !left; ++step) {
    zp += dt * vp + 0.5 * dt * dt * ap, zb += dt * vb + 0.5 * dt * dt * ab;
    const double g = zb - zp - 0.5 * h, pen = std::max(0.0, -g);
    const double ap1 = -k * pen, ab1 = k * (mass / M) * pen;
    vp += 0.5 * dt * (ap + ap1), vb += 0.5 * dt * (ab + ab1), ap = ap1, ab = ab1;
    dyn.step();
    const auto values = dyn.contact_values();
    EXPECT_NEAR(values[2], zb, 1e-9 * V * dt) << "step " << step;
    EXPECT_NEAR(values[5], vb, 1e-9 * V) << "step " << step;
    EXPECT_NEAR(values[8], M * ab, 1e-9 * mass * k * V * dt) << "step " << step;
    EXPECT_NEAR(dyn.record().kinetic, 0.5 * mass * vp * vp, 1e-9 * 0.5 * M * V * V) << "step " << step;
    // momentum: the plate's (mean velocity of all its DG nodes, which move together) and the body's
    const double plate_v = dyn.probes({std::vector<char>(std::size_t(model.counts.nodes), 1)}).at(5);
    EXPECT_NEAR(plate_v, vp, 1e-9 * V) << "step " << step;
    EXPECT_NEAR(mass * plate_v + M * values[5], -M * V, 1e-12 * M * V) << "step " << step;
    touched = touched || pen > 0;
    left = touched && pen == 0;
  }
  ASSERT_TRUE(left) << "the body has not left the plate";
  EXPECT_NEAR(vp, -2 * M / (M + mass) * V, 0.02 * V);
  EXPECT_NEAR(vb, -(M - mass) / (M + mass) * V, 0.02 * V);
  EXPECT_LT(dyn.record().strain, 1e-12 * M * V * V);  // flat: no deformation

  auto light = build_model(struck_plate(mass / 20, face0));
  EXPECT_THROW(
      {
        try {
          for (int step = 0; step < 10; ++step) light.dynamics->step();
        } catch (const NumericalError& e) {
          EXPECT_NE(std::string(e.what()).find("rigid body 'ram': the shells in contact with it (mass"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      NumericalError);
}

// The same ram with its motion prescribed (Mass 0): it keeps V whatever the forces, and the plate follows the
// recurrence of a mass pushed by a one-sided spring whose other end moves at -V: z_b(t) = face0 - V t exactly.
TEST(RigidBody, PrescribedBodyKeepsItsVelocityAndPushesThePlate) {
  const double s = 0.25;
  const double dt = build_model(struck_plate(0.0, 1e3)).dynamics->time_step();
  const double face0 = 0.5 * h + 1.5 * V * dt;
  auto model = build_model(struck_plate(0.0, face0));
  auto& dyn = *model.dynamics;
  double zp = 0, vp = 0, ap = 0;
  const double k = s / (dt * dt);
  for (int step = 1; step <= 30; ++step) {
    const double t = step * dt;
    zp += dt * vp + 0.5 * dt * dt * ap;
    const double pen = std::max(0.0, -((face0 - V * t) - zp - 0.5 * h)), ap1 = -k * pen;
    vp += 0.5 * dt * (ap + ap1), ap = ap1;
    dyn.step();
    const auto values = dyn.contact_values();
    EXPECT_NEAR(values[2], face0 - V * t, 1e-14) << "step " << step;
    EXPECT_EQ(values[5], -V) << "step " << step;
    EXPECT_EQ(values[9], 0.0);  // a prescribed body has no kinetic energy of its own in the history
    EXPECT_NEAR(dyn.probes({std::vector<char>(std::size_t(model.counts.nodes), 1)}).at(5), vp, 1e-9 * V)
        << "step " << step;
  }
  EXPECT_LT(vp, -V);  // pushed ahead of the ram, faster than it (the spring's overshoot)
}
