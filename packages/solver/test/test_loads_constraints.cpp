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
std::vector<std::vector<double>> run(const std::string& dir, const std::string& name, const std::string& text,
                                     std::vector<std::string>& header) {
  write_file(dir + "/" + name + ".xml", text);
  solver::Simulation sim(dir + "/" + name + ".xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  return read_history(sim.history_path(), header);
}
}  // namespace

TEST(Loads, PressureWorkBalancesEnergy) {
  const auto dir = work_dir("pressure");
  const std::string body =
      "<ParameterList name=\"Time Integration\"><Parameter name=\"End Time\" type=\"double\" value=\"0.02\"/>"
      "<Parameter name=\"History Interval\" type=\"int\" value=\"50\"/></ParameterList>\n"
      "<ParameterList name=\"Loads\"><ParameterList name=\"blast\"><Parameter name=\"Type\" type=\"string\" "
      "value=\"Pressure\"/><Parameter name=\"Elements\" type=\"string\" value=\"all\"/>"
      "<Parameter name=\"Function\" type=\"string\" value=\"Exponential\"/>"
      "<Parameter name=\"Pressure\" type=\"double\" value=\"50\"/>"
      "<Parameter name=\"Decay Time\" type=\"double\" value=\"0.005\"/></ParameterList></ParameterList>\n";
  std::vector<std::string> h;
  const auto rows = run(dir, "pressure", deck(rectangle_mesh(1.0, 1.0, 4, 4), body, dir, "{corners}"), h);
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
  const std::string body =
      "<ParameterList name=\"Time Integration\"><Parameter name=\"End Time\" type=\"double\" value=\"1.2e-3\"/>"
      "<Parameter name=\"History Interval\" type=\"int\" value=\"5\"/></ParameterList>\n"
      "<ParameterList name=\"Boundary Conditions\">"
      "<ParameterList name=\"left\"><Parameter name=\"Type\" type=\"string\" value=\"Prescribed Velocity\"/>"
      "<Parameter name=\"Node Set\" type=\"string\" value=\"x_min\"/>"
      "<Parameter name=\"Velocity\" type=\"Array(double)\" value=\"{-1.0, 0.0, 0.0}\"/>"
      "<Parameter name=\"Ramp Time\" type=\"double\" value=\"1e-4\"/></ParameterList>"
      "<ParameterList name=\"right\"><Parameter name=\"Type\" type=\"string\" value=\"Prescribed Velocity\"/>"
      "<Parameter name=\"Node Set\" type=\"string\" value=\"x_max\"/>"
      "<Parameter name=\"Velocity\" type=\"Array(double)\" value=\"{1.0, 0.0, 0.0}\"/>"
      "<Parameter name=\"Ramp Time\" type=\"double\" value=\"1e-4\"/></ParameterList></ParameterList>\n";
  std::vector<std::string> hd;
  ShellSection section;
  section.poisson = 0.0;  // no lateral contraction: the strip is a one-dimensional bar exactly
  const auto rows = run(dir, "pulled", deck(rectangle_mesh(2.0, b, 40, 4), body, dir, "{x_max}", section), hd);
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
  auto body = [&](const std::string& components) {
    return "<ParameterList name=\"Time Integration\"><Parameter name=\"End Time\" type=\"double\" value=\"" +
           xml_double(t_end) + "\"/><Parameter name=\"History Interval\" type=\"int\" value=\"5\"/></ParameterList>\n"
           "<ParameterList name=\"Boundary Conditions\">"
           "<ParameterList name=\"root\"><Parameter name=\"Type\" type=\"string\" value=\"Clamped\"/>"
           "<Parameter name=\"Node Set\" type=\"string\" value=\"x_min\"/></ParameterList>"
           "<ParameterList name=\"lift\"><Parameter name=\"Type\" type=\"string\" value=\"Prescribed Velocity\"/>"
           "<Parameter name=\"Node Set\" type=\"string\" value=\"x_max\"/>"
           "<Parameter name=\"Velocity\" type=\"Array(double)\" value=\"{0.0, 0.0, 1.0}\"/>"
           "<Parameter name=\"Components\" type=\"string\" value=\"" + components + "\"/>"
           "<Parameter name=\"Ramp Time\" type=\"double\" value=\"" + xml_double(tr) +
           "\"/></ParameterList></ParameterList>\n";
  };
  std::vector<std::string> hz, ha;
  const auto rz = run(dir, "z_only", deck(rectangle_mesh(2.0, 0.2, 20, 2), body("z"), dir, "{x_max}"), hz);
  const auto ra = run(dir, "all", deck(rectangle_mesh(2.0, 0.2, 20, 2), body("xyz"), dir, "{x_max}"), ha);
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
  const std::string time =
      "<ParameterList name=\"Time Integration\"><Parameter name=\"End Time\" type=\"double\" value=\"0.2\"/>"
      "<Parameter name=\"History Interval\" type=\"int\" value=\"10\"/></ParameterList>\n";
  const std::string kick =
      "<ParameterList name=\"Initial Conditions\"><ParameterList name=\"kick\">"
      "<Parameter name=\"Elements\" type=\"string\" value=\"all\"/>"
      "<Parameter name=\"Velocity\" type=\"Array(double)\" value=\"{0.0, 0.0, 1.0}\"/></ParameterList></ParameterList>\n";
  const std::string clamp =
      "<ParameterList name=\"root\"><Parameter name=\"Type\" type=\"string\" value=\"Clamped\"/>"
      "<Parameter name=\"Node Set\" type=\"string\" value=\"y_min\"/></ParameterList>";
  const std::string full_bc = "<ParameterList name=\"Boundary Conditions\">" + clamp + "</ParameterList>\n";
  const std::string half_bc = "<ParameterList name=\"Boundary Conditions\">" + clamp +
                              "<ParameterList name=\"mirror\"><Parameter name=\"Type\" type=\"string\" "
                              "value=\"Symmetry\"/><Parameter name=\"Node Set\" type=\"string\" value=\"x_max\"/>"
                              "<Parameter name=\"Normal\" type=\"Array(double)\" value=\"{1.0, 0.0, 0.0}\"/>"
                              "</ParameterList></ParameterList>\n";
  std::vector<std::string> hf, hh;
  const auto full = run(dir, "full", deck(rectangle_mesh(1.0, 1.5, 8, 12), time + full_bc + kick, dir), hf);
  const auto half = run(dir, "half", deck(rectangle_mesh(0.5, 1.5, 4, 12), time + half_bc + kick, dir), hh);
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
