// Loads, prescribed motions and symmetry planes (issue: elastic dynamics, item 5), each with its reference:
//  * follower pressure on a free flat plate: the energy balance K + U - W_ext = 0 (theory.md §9.7) holds to
//    0.1 % of the work done, and the work is positive;
//  * a strip pulled at both ends at V (cosine ramp): before the reflected waves return, the end reaction is
//    the bar-wave force rho c0 V h b (c0 = sqrt(E/rho), one-dimensional wave theory), and the energy balance
//    K + U - W_react = 0 holds to 0.1 %;
//  * symmetry: half of a mirror-symmetric cantilever plate with a symmetry plane gives the first frequency of
//    the full plate to 0.1 % (the full mesh is mirror-symmetric and the uniform kick excites only symmetric
//    modes).
#include <gtest/gtest.h>

#include <cmath>

#include "deck_test_util.hpp"
#include "shellfrac/solver/simulation.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {
std::vector<std::vector<double>> run(const std::string& dir, const std::string& name,
                                     const Teuchos::ParameterList& deck, std::vector<std::string>& header) {
  write_deck(dir + "/" + name + ".xml", deck);
  solver::Simulation sim(dir + "/" + name + ".xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  return read_history(sim.history_path(), header);
}
}  // namespace

TEST(Loads, PressureWorkBalancesEnergy) {
  const auto dir = work_dir("pressure");
  auto deck = base_deck({}, dir);
  set_rectangle(*deck, 1.0, 1.0, 4, 4);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 0.02), time.set("History Interval", 50);
  auto& blast = deck->sublist("Loads").sublist("blast");
  blast.set("Type", std::string("Pressure")), blast.set("Elements", std::string("all"));
  blast.set("Function", std::string("Exponential")), blast.set("Pressure", 50.0), blast.set("Decay Time", 0.005);
  set_probes(*deck, {"corners"});
  std::vector<std::string> h;
  const auto rows = run(dir, "pressure", *deck, h);
  if (parallel::rank() != 0) return;
  const auto w = column(h, "external_work"), err = column(h, "energy_balance_error");
  double wmax = 0;
  for (const auto& r : rows) wmax = std::max(wmax, std::abs(r[w]));
  EXPECT_GT(rows.back()[w], 0.0);
  for (const auto& r : rows) EXPECT_LE(std::abs(r[err]), 1e-3 * wmax) << "step " << r[0];
}

TEST(Constraints, PulledStripReactionAndEnergy) {
  const auto dir = work_dir("pulled");
  const double V = 1.0, E = 2.1e6, rho = 1.0, h = 0.1, b = 0.2;
  ShellSection section;
  section.poisson = 0.0;  // no lateral contraction: the strip is a one-dimensional bar exactly
  auto deck = base_deck(section, dir);
  set_rectangle(*deck, 2.0, b, 40, 4);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 1.2e-3), time.set("History Interval", 5);
  auto& left = boundary_condition(*deck, "left", "Prescribed Velocity", "x_min");
  left.set("Velocity", vec3(-1.0, 0.0, 0.0)), left.set("Ramp Time", 1e-4);
  auto& right = boundary_condition(*deck, "right", "Prescribed Velocity", "x_max");
  right.set("Velocity", vec3(1.0, 0.0, 0.0)), right.set("Ramp Time", 1e-4);
  set_probes(*deck, {"x_max"});
  std::vector<std::string> hd;
  const auto rows = run(dir, "pulled", *deck, hd);
  if (parallel::rank() != 0) return;
  const auto rx = column(hd, "right_reaction_x"), t = column(hd, "time"), err = column(hd, "energy_balance_error");
  const auto wr = column(hd, "reaction_work");
  ASSERT_LT(rx, hd.size());
  // Waves leave both ends at t = 0 and meet at the centre at L/c0 = 1/c0 = 6.9e-4; the reflection reaches the
  // ends at 2/c0 = 1.38e-3. Between the end of the ramp (1e-4) plus the ramp's rise and 1.2e-3 the reaction
  // is rho c0 V h b.
  const double c0 = std::sqrt(E / rho), expected = rho * c0 * V * h * b;
  double wmax = 0;
  for (const auto& r : rows) {
    wmax = std::max(wmax, std::abs(r[wr]));
    if (r[t] > 3e-4 && r[t] < 1.2e-3) {
      EXPECT_NEAR(r[rx], expected, 0.03 * expected) << "t = " << r[t];
    }
  }
  for (const auto& r : rows) EXPECT_LE(std::abs(r[err]), 1e-3 * wmax) << "t = " << r[t];
}

// Prescribed Velocity on some components only (Components = "z"): a strip clamped at x = 0 whose end x = L is
// lifted at V in z (cosine ramp). References: the lifted end follows the exact integral of the velocity program
// in z; its x and y motion is free, so the condition's reaction in x and y is exactly zero while the end moves
// in x (the strip is no longer held at its length); the energy balance K + U - W_react - W_ext = 0 holds to 0.1 %
// of the reaction work (a free component integrated wrongly, or a missing reaction, would break it). The same
// deck with all components prescribed keeps x exactly and needs a reaction in x.
TEST(Constraints, PartlyPrescribedVelocityLeavesOtherComponentsFree) {
  const auto dir = work_dir("partly_prescribed");
  const double V = 1.0, tr = 2e-4, t_end = 1.5e-3;
  const auto strip = [&](const std::string& components) {
    auto deck = base_deck({}, dir);
    set_rectangle(*deck, 2.0, 0.2, 20, 2);
    auto& time = deck->sublist("Time Integration");
    time.set("End Time", t_end), time.set("History Interval", 5);
    boundary_condition(*deck, "root", "Clamped", "x_min");
    auto& lift = boundary_condition(*deck, "lift", "Prescribed Velocity", "x_max");
    lift.set("Velocity", vec3(0.0, 0.0, 1.0)), lift.set("Components", components), lift.set("Ramp Time", tr);
    set_probes(*deck, {"x_max"});
    return deck;
  };
  std::vector<std::string> hz, ha;
  const auto rz = run(dir, "z_only", *strip("z"), hz);
  const auto ra = run(dir, "all", *strip("xyz"), ha);
  if (parallel::rank() != 0) return;
  const auto& last = rz.back();
  const double t = last[column(hz, "time")], u_exact = V * (t - 0.5 * tr);
  EXPECT_NEAR(last[column(hz, "x_max_displ_z")], u_exact, 1e-12 * u_exact);
  EXPECT_NE(last[column(hz, "x_max_displ_x")], 0.0) << "the end must be free to move along x";
  double wmax = 0;
  for (const auto& r : rz) wmax = std::max(wmax, std::abs(r[column(hz, "reaction_work")]));
  EXPECT_GT(wmax, 0.0);
  for (const auto& r : rz) {
    EXPECT_EQ(r[column(hz, "lift_reaction_x")], 0.0);
    EXPECT_EQ(r[column(hz, "lift_reaction_y")], 0.0);
    EXPECT_LE(std::abs(r[column(hz, "energy_balance_error")]), 1e-3 * wmax) << "t = " << r[column(hz, "time")];
  }
  EXPECT_EQ(ra.back()[column(ha, "x_max_displ_x")], 0.0);
  EXPECT_NE(ra.back()[column(ha, "lift_reaction_x")], 0.0);
}

TEST(Constraints, SymmetryPlaneHalfModelMatchesFullModel) {
  const auto dir = work_dir("symmetry");
  // The clamped plate 1.0 x 1.5 (8 x 12 cells) or its half x <= 0.5 (4 x 12) with a mirror on x_max.
  const auto plate = [&](bool half) {
    auto deck = base_deck({}, dir);
    set_rectangle(*deck, half ? 0.5 : 1.0, 1.5, half ? 4 : 8, 12);
    auto& time = deck->sublist("Time Integration");
    time.set("End Time", 0.2), time.set("History Interval", 10);
    boundary_condition(*deck, "root", "Clamped", "y_min");
    if (half) boundary_condition(*deck, "mirror", "Symmetry", "x_max").set("Normal", vec3(1.0, 0.0, 0.0));
    initial_velocity(*deck, "kick", "all", vec3(0.0, 0.0, 1.0));
    set_probes(*deck, {"y_max"});
    return deck;
  };
  std::vector<std::string> hf, hh;
  const auto full = run(dir, "full", *plate(false), hf);
  const auto half = run(dir, "half", *plate(true), hh);
  if (parallel::rank() != 0) return;
  const auto cf = upward_crossings(full, column(hf, "y_max_displ_z"));
  const auto ch = upward_crossings(half, column(hh, "y_max_displ_z"));
  ASSERT_GE(cf.size(), 2u);
  ASSERT_EQ(cf.size(), ch.size());
  const double pf = (cf.back() - cf.front()) / (cf.size() - 1), ph = (ch.back() - ch.front()) / (ch.size() - 1);
  EXPECT_NEAR(ph, pf, 1e-3 * pf) << "half-model period " << ph << " vs full " << pf;
  // The half has exactly half the (mirror-symmetric) mass, so half the initial kinetic energy. Later values
  // are not identical: in the full DG model the centre line is an interior edge where symmetry holds only
  // weakly (through the jump penalty), while the half model enforces u.n = 0 strongly on the plane; the two
  // discretizations differ at the discretization-error level (measured: < 1 % in kinetic energy here).
  const auto kf = column(hf, "kinetic_energy"), kh = column(hh, "kinetic_energy");
  EXPECT_NEAR(2 * half[0][kh], full[0][kf], 1e-12 * full[0][kf]);
}
