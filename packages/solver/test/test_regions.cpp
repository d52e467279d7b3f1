// Sets by region (the deck's Regions sublist, docs/input_reference.xml; solver/input/regions.hpp, solver/input/mesh_sets.hpp).
// Exact counts on structured meshes whose region boundaries lie between node lines, so that each count follows
// from the grid alone:
//  * a Cylinder Sector on a closed cylinder (R = 1, L = 4, 8 x 32 cells, cells 0.5 x 11.25 degrees) covering
//    4 axial x 10 circumferential cells: 80 elements; its P2 nodes form a 9 x 21 grid (189); each of the
//    189 - 5 x 11 = 134 non-vertex nodes is the mid-side node of one interior edge, i.e. 268 element sides;
//  * an Exponential pressure pulse on that patch: at t = 0 the resultant of the follower pressure is
//    p R L_patch (0, cos(th1) - cos(th2), sin(th2) - sin(th1)) over th in [th1, th2] (the outward normal of the
//    generator is (0, sin th, cos th)), to the P2 geometry's accuracy (1e-4);
//  * a Box and a Sphere on a rectangle, used as a support's node set, a load's element set, a probe and the
//    fracture edges, with the counts of the grid;
//  * bad regions are refused with the deck, the region and the problem named.
#include <gtest/gtest.h>

#include <cmath>

#include "deck_test_util.hpp"
#include "in_memory_model.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/model/shell_state.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

Teuchos::ParameterList& region(Teuchos::ParameterList& deck, const std::string& name, const std::string& shape) {
  auto& r = deck.sublist("Regions").sublist(name);
  r.set("Shape", shape);
  return r;
}

Teuchos::RCP<Teuchos::ParameterList> cylinder_patch_deck() {
  auto deck = base_deck();
  auto& mesh = deck->sublist("Mesh");
  mesh.set("Source", std::string("Cylinder"));
  auto& c = mesh.sublist("Cylinder");
  c.set("Radius", 1.0), c.set("Length", 4.0), c.set("Axial Elements", 8), c.set("Circumferential Elements", 32);
  c.set("Block Name", std::string("shell"));
  // Angles counter-clockwise about +x from +z: 19.7 to 137.8 degrees, i.e. the generator's angles -137.8 to
  // -19.7 (its points are (x, sin th, cos th)); the cells from -135 to -22.5 degrees. Axially 0.9 to 3.1.
  auto& patch = region(*deck, "patch", "Cylinder Sector");
  patch.set("Center", vec3(0, 0, 0)), patch.set("Axis", vec3(1, 0, 0)), patch.set("Reference Direction", vec3(0, 0, 1));
  patch.set("Angle Range", Teuchos::Array<double>(Teuchos::tuple<double>(19.7, 137.8)));
  patch.set("Axial Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.9, 3.1)));
  patch.set("Radius Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.9, 1.1)));
  auto& pulse = deck->sublist("Loads").sublist("pulse");
  pulse.set("Type", std::string("Pressure")), pulse.set("Elements", std::string("patch"));
  pulse.set("Pressure", 2.0), pulse.set("Function", std::string("Exponential")), pulse.set("Decay Time", 1e-3);
  deck->sublist("Time Integration").set("End Time", 1e-5);
  return deck;
}

long count(const std::vector<char>& flags) {
  long n = 0;
  for (char f : flags) n += f != 0;
  return n;
}

}  // namespace

TEST(Regions, CylinderSectorSelectsThePatch) {
  const auto deck = cylinder_patch_deck();
  const auto d = solver::Deck::from_parameters(deck, "regions.xml");
  const auto model = solver::build_run_model(d, MPI_COMM_WORLD);
  const solver::MeshSets sets(*model.mesh, d.file, d.regions);
  EXPECT_EQ(count(sets.elements("test", "patch")), 80);
  EXPECT_EQ(count(sets.node_set("test", "patch", false)), 189);
  EXPECT_EQ(static_cast<long>(sets.side_set("test", "patch").size()), 268);
  const auto sizes = sets.region_sizes();
  ASSERT_EQ(sizes.size(), 1u);
  EXPECT_EQ(sizes[0].name, "patch");
  EXPECT_EQ(sizes[0].elements, 80);
  EXPECT_EQ(sizes[0].nodes, 189);
  EXPECT_EQ(sizes[0].edges, 268);
}

TEST(Regions, PressurePulseOnACylinderSector) {
  if (parallel::size() > 1) GTEST_SKIP() << "serial: the resultant is summed over this rank's elements";
  const auto model = build_model(cylinder_patch_deck(), "regions.xml");
  const auto& f = model.dynamics->state().external_force;
  double F[3] = {0, 0, 0};
  for (std::size_t i = 0; i < f.size(); ++i) F[i % 3] += f.data()[i];
  const double p = 2.0, R = 1.0, L = 2.0, th1 = -135 * M_PI / 180, th2 = -22.5 * M_PI / 180;
  const double Fy = p * R * L * (std::cos(th1) - std::cos(th2)), Fz = p * R * L * (std::sin(th2) - std::sin(th1));
  const double scale = std::hypot(Fy, Fz);
  EXPECT_NEAR(F[0], 0.0, 1e-12 * scale);
  EXPECT_NEAR(F[1], Fy, 1e-4 * scale);
  EXPECT_NEAR(F[2], Fz, 1e-4 * scale);
}

TEST(Regions, BoxAndSphereServeAsEverySetKind) {
  // Rectangle 4 x 1 with 8 x 2 cells (0.5 x 0.5); P2 node spacing 0.25.
  auto deck = base_deck();
  set_rectangle(*deck, 4.0, 1.0, 8, 2);
  auto& left = region(*deck, "left end", "Box");  // the node line x = 0: 5 nodes
  left.set("Min", vec3(-0.1, -0.1, -0.1)), left.set("Max", vec3(0.1, 1.1, 0.1));
  auto& middle = region(*deck, "middle", "Box");  // the cells 1.5 < x < 2.5: 2 x 2 cells, 8 elements
  middle.set("Min", vec3(1.4, -0.1, -0.1)), middle.set("Max", vec3(2.6, 1.1, 0.1));
  auto& tip = region(*deck, "tip", "Sphere");  // the corner node (4, 1, 0) and nothing else (spacing 0.25)
  tip.set("Center", vec3(4, 1, 0)), tip.set("Radius", 0.1);
  boundary_condition(*deck, "root", "Clamped", "left end");
  auto& load = deck->sublist("Loads").sublist("weight");
  load.set("Type", std::string("Gravity")), load.set("Elements", std::string("middle"));
  load.set("Acceleration", vec3(0, 0, -1));
  set_probes(*deck, {"tip"});
  deck->sublist("Fracture").set("Edges", std::string("middle"));
  shell_material(*deck).set("Cohesive Strength", 1e5), shell_material(*deck).set("Fracture Energy", 1e3);
  const auto d = solver::Deck::from_parameters(deck, "regions.xml");
  const auto model = solver::build_run_model(d, MPI_COMM_WORLD);
  const solver::MeshSets sets(*model.mesh, d.file, d.regions);
  EXPECT_EQ(count(sets.node_set("test", "left end", false)), 5);
  EXPECT_EQ(count(sets.elements("test", "middle")), 8);
  EXPECT_EQ(count(sets.node_set("test", "tip", false)), 1);
  // Edges of "middle": P2 nodes with 1.5 <= x <= 2.5 form a 5 x 5 grid; its 25 - 9 non-vertex nodes are mid-side
  // nodes; the edges on y = 0 and y = 1 have one side, the 16 - 4 others two: 4 + 2 x 12 = 28 sides.
  EXPECT_EQ(static_cast<long>(sets.side_set("test", "middle").size()), 28);
  // The gravity load acts on the 8 elements only: total mass of 2 x 1 area x rho h = 1 x 1 x 0.1 (base_deck).
  double Fz = 0;
  const auto& f = model.dynamics->state().external_force;
  for (std::size_t i = 2; i < f.size(); i += 3) Fz += f.data()[i];
  if (parallel::size() == 1) {
    EXPECT_NEAR(Fz, -ShellSection{}.density * ShellSection{}.thickness * 1.0, 1e-12);
  }
}

TEST(Regions, BadRegionsAreRefused) {
  {
    auto deck = base_deck();
    set_rectangle(*deck, 4.0, 1.0, 8, 2);
    region(*deck, "x_min", "Sphere").set("Radius", 1.0);
    const std::string m = input_error(deck, "regions.xml");
    EXPECT_NE(m.find("regions.xml"), std::string::npos) << m;
    EXPECT_NE(m.find("'x_min' has the name of a set"), std::string::npos) << m;
  }
  {
    auto deck = base_deck();
    region(*deck, "ball", "Sphere");
    EXPECT_NE(input_error(deck, "regions.xml").find("a Sphere needs a Radius > 0"), std::string::npos)
        << input_error(deck, "regions.xml");
  }
  {
    auto deck = base_deck();
    auto& r = region(*deck, "sector", "Cylinder Sector");
    r.set("Angle Range", Teuchos::Array<double>(Teuchos::tuple<double>(90.0, 45.0)));
    r.set("Radius Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 1.0)));
    EXPECT_NE(input_error(deck, "regions.xml").find("Angle Range {from, to} needs from < to"), std::string::npos)
        << input_error(deck, "regions.xml");
  }
  {
    auto deck = base_deck();
    region(*deck, "box", "Box").set("Min", vec3(0, 0, std::nan("")));
    EXPECT_NE(input_error(deck, "regions.xml").find("is not finite"), std::string::npos)
        << input_error(deck, "regions.xml");
  }
  {
    auto deck = base_deck();
    set_rectangle(*deck, 4.0, 1.0, 8, 2);
    boundary_condition(*deck, "root", "Clamped", "nowhere");
    EXPECT_NE(input_error(deck, "regions.xml").find("'nowhere'"), std::string::npos)
        << input_error(deck, "regions.xml");
  }
}
