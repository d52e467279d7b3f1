// Selective mass scaling (Time Integration->Target Time Step, docs/theory.md §8.1) on a strip with a row of
// slivers: the Rectangle 1 x 0.2 (10 x 2 cells, right diagonals, t = 0.01, rho = 1) whose node line x = 0.6 is
// moved to x = 0.501, so that the 4 triangles of the cells between x = 0.5 and 0.501 are 100 times thinner than
// the others and set the step dt0. References, exact from the construction:
//  * a target of 4 dt0 scales exactly those 4 elements, by (4)^2 (1 + 1e-12), so the added mass is
//    (16 (1 + 1e-12) - 1) rho t 0.001 x 0.2 and the step is the target (to the 1e-12 margin);
//  * the total of the lumped masses is the physical mass rho t 0.2 plus the added mass;
//  * the energy balance of a kicked cantilever over 400 steps closes as well as without scaling (both below 1e-6
//    of the input energy);
//  * a target that adds more than Maximum Added Mass Fraction is refused unless forced, and Time Step together
//    with Target Time Step is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "deck_test_util.hpp"
#include "in_memory_model.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/model/shell_state.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

constexpr double rho = 1.0, thickness = 0.01, sliver_width = 0.001, width = 0.2;

/// Writes the strip with the sliver row (once, rank 0) and returns its path.
std::string sliver_mesh() {
  const auto dir = work_dir("mass_scaling");
  const std::string path = dir + "/slivers.exo";
  if (parallel::rank() == 0) {
    auto m = mesh::make_rectangle(1.0, width, 10, 2, mesh::DiagonalPattern::Right);
    for (auto& x : m.coords)
      if (std::abs(x[0] - 0.6) < 1e-9) x[0] = 0.5 + sliver_width;
    mesh::promote_to_p2(m);
    meshio::write_exodus_mesh(m, path);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

Teuchos::RCP<Teuchos::ParameterList> sliver_deck(double target) {
  auto deck = base_deck(ShellSection{thickness, rho, 2.1e6, 0.3});
  set_mesh_file(*deck, sliver_mesh());
  boundary_condition(*deck, "root", "Clamped", "x_min");
  initial_velocity(*deck, "kick", "all", vec3(0, 0, 1.0));
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 1.0);
  if (target > 0) time.set("Target Time Step", target);
  return deck;
}

double total_mass(const solver::RunModel& model) {
  double m = 0;
  const auto& mass = model.dynamics->model().mass;
  for (std::size_t i = 0; i < mass.size(); ++i) m += mass.data()[i];
  double all = 0;
  MPI_Allreduce(&m, &all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

/// |energy balance error| / input energy after `steps` steps.
double balance_after(solver::RunModel& model, int steps) {
  auto& dyn = *model.dynamics;
  const auto r0 = dyn.record();
  const double e0 = r0.kinetic + r0.strain + r0.penalty;
  for (int i = 0; i < steps; ++i) dyn.step();
  return std::abs(solver::energy_balance_error(dyn.record(), e0)) / e0;
}

}  // namespace

TEST(MassScaling, SliversReachTheTargetStep) {
  auto plain = build_model(sliver_deck(0), "mass_scaling.xml");
  const double dt0 = plain.dynamics->time_step();
  EXPECT_EQ(plain.dynamics->model().mass_scaling.elements, 0);
  const double physical = rho * thickness * width;
  EXPECT_NEAR(total_mass(plain), physical, 1e-12 * physical);

  auto scaled = build_model(sliver_deck(4 * dt0), "mass_scaling.xml");
  const auto& ms = scaled.dynamics->model().mass_scaling;
  EXPECT_EQ(ms.elements, 4);
  EXPECT_NEAR(scaled.dynamics->time_step(), 4 * dt0, 1e-11 * dt0);
  const double added = (16 * (1 + 1e-12) - 1) * rho * thickness * sliver_width * width;
  EXPECT_NEAR(ms.added_mass, added, 1e-9 * added);
  EXPECT_NEAR(ms.physical_mass, physical, 1e-12 * physical);
  EXPECT_NEAR(total_mass(scaled), physical + added, 1e-12 * physical);
  EXPECT_NEAR(ms.max_factor, 16 * (1 + 1e-12), 1e-9);
  EXPECT_NEAR(ms.max_centroid[0], 0.5 + 2 * sliver_width / 3, 1e-3) << "a sliver (x in [0.5, 0.501])";

  const double plain_error = balance_after(plain, 400), scaled_error = balance_after(scaled, 400);
  EXPECT_LT(plain_error, 1e-6);
  EXPECT_LT(scaled_error, 1e-6);
  std::ostringstream os;
  os << plain_error << " " << scaled_error;
  ::testing::Test::RecordProperty("balance_plain_scaled", os.str());
}

TEST(MassScaling, TooMuchAddedMassIsRefusedUnlessForced) {
  const double dt0 = build_model(sliver_deck(0), "mass_scaling.xml").dynamics->time_step();
  auto deck = sliver_deck(20 * dt0);  // factor 400 on 1/1000 of the mass: 40 % added
  const std::string m = input_error(deck, "mass_scaling.xml");
  EXPECT_NE(m.find("mass_scaling.xml"), std::string::npos) << m;
  EXPECT_NE(m.find("Maximum Added Mass Fraction"), std::string::npos) << m;
  deck->sublist("Time Integration").set("Force Mass Scaling", true);
  EXPECT_EQ(input_error(deck, "mass_scaling.xml"), "");
  auto both = sliver_deck(4 * dt0);
  both->sublist("Time Integration").set("Time Step", dt0);
  EXPECT_NE(input_error(both, "mass_scaling.xml").find("not both"), std::string::npos)
      << input_error(both, "mass_scaling.xml");
}
