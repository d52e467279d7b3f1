// Explicit DG shell dynamics (issue: elastic dynamics), each check with its reference:
//  * rigid translation of a free curved panel over 10 000 steps: strain + penalty energy <= 1e-10 of the
//    kinetic energy, kinetic energy conserved to 1e-6 (exact solution: uniform motion, no strain);
//  * the same deck on np ranks and serially (MPI_COMM_SELF) gives bitwise identical history files and final
//    Exodus fields (deterministic gather assembly, global-id-ordered sums);
//  * cantilever plate 1.0 x 1.5 clamped on a 1.0 edge, E = 2.1e6, nu = 0.3, rho = 1, t = 0.1: first
//    frequency within 2 % of 10.785 Hz (Blevins, Formulas for Dynamics, Acoustics and Vibration, Table 5.3
//    case 11; docs/verification.md §4), and total energy conserved to 0.1 % of the input energy.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "deck_test_util.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/results_reader.hpp"
#include "shellfrac/solver/simulation.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

/// The cantilever plate 1.0 x 1.5 on nx x ny cells (the default ShellSection) clamped on its edge y_min, every
/// element kicked at {0, 0, 1}; probe y_max. Add the time integration.
Teuchos::RCP<Teuchos::ParameterList> cantilever_deck(const std::string& dir, int nx, int ny) {
  auto deck = base_deck({}, dir);
  set_rectangle(*deck, 1.0, 1.5, nx, ny);
  boundary_condition(*deck, "root", "Clamped", "y_min");
  initial_velocity(*deck, "kick", "all", vec3(0.0, 0.0, 1.0));
  set_probes(*deck, {"y_max"});
  return deck;
}

/// Runs a free curved panel (fixed step 3e-5, below the stable estimate 3.48e-5) with the translation
/// {1, 2, -3} plus the spin `omega` for 10 000 steps; returns the history.
std::vector<std::vector<double>> spin_run(const std::string& name, const Teuchos::Array<double>& omega,
                                          std::vector<std::string>& h) {
  const auto dir = work_dir(name);
  auto deck = base_deck({}, dir);
  set_cylindrical_panel(*deck, 1.0, 1.5, 90, 4, 3);
  auto& time = deck->sublist("Time Integration");
  time.set("Time Step", 3e-5), time.set("End Time", 0.3), time.set("History Interval", 500);
  auto& spin = initial_velocity(*deck, "spin", "all", vec3(1.0, 2.0, -3.0));
  spin.set("Angular Velocity", omega), spin.set("Center", vec3(0.75, 0.0, 0.7));
  set_probes(*deck, {"x_max"});
  write_deck(dir + "/" + name + ".xml", *deck);
  solver::Simulation sim(dir + "/" + name + ".xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  return read_history(sim.history_path(), h);
}
}  // namespace

TEST(Dynamics, RigidTranslationOf10000Steps) {
  std::vector<std::string> header;
  const auto rows = spin_run("rigid", vec3(0.0, 0.0, 0.0), header);
  if (parallel::rank() != 0) return;
  ASSERT_EQ(header[3], "kinetic_energy");
  ASSERT_EQ(rows.back()[0], 10000);
  const double k0 = rows.front()[3];
  // 1/2 rho h |S| |v|^2 with the exact cylinder area; the lumped mass integrates the P2 surface, whose
  // area is O(h^4) smaller (7.7e-5 relative on this 4 x 3 mesh), hence the 5e-4 tolerance.
  EXPECT_NEAR(k0, 0.5 * 1.0 * 0.1 * (M_PI / 2 * 1.5) * 14.0, 5e-4 * k0);
  ASSERT_EQ(header[10], "x_max_displ_z");
  for (const auto& r : rows) {
    EXPECT_LE(r[4] + r[5], 1e-10 * k0) << "strain + penalty energy at step " << r[0];
    EXPECT_NEAR(r[3], k0, 1e-6 * k0) << "kinetic energy at step " << r[0];
    EXPECT_NEAR(r[10], -3.0 * r[1], 1e-9) << "probe z-displacement = vz t at step " << r[0];
  }
}


// A free body keeps its angular momentum (sum m x × v + sum I t × tdot about the origin) and its energy. A
// fast spin (|w| = 62 rad/s) also stretches the panel (centrifugal strain rho w^2 r^2 / E ~ 2e-3 with the
// test material), so only the conservation laws are exact: angular momentum to 1e-12 (measured ~1e-15) and
// K + U to 1e-6. A slow spin (|w| = 0.006 rad/s) added to the translation is rigid to within the
// centrifugal strain energy, which scales as w^4: strain + penalty <= 1e-10 of the kinetic energy.
TEST(Dynamics, SpinConservesAngularMomentumAndEnergy) {
  std::vector<std::string> h;
  const auto rows = spin_run("spin_fast", vec3(30.0, -20.0, 50.0), h);
  if (parallel::rank() == 0) {
    const auto kx = column(h, "angular_momentum_x"), k = column(h, "kinetic_energy");
    ASSERT_LT(kx + 2, h.size());
    const double l0 = std::sqrt(rows[0][kx] * rows[0][kx] + rows[0][kx + 1] * rows[0][kx + 1] +
                                rows[0][kx + 2] * rows[0][kx + 2]);
    const double e0 = rows[0][k] + rows[0][k + 1] + rows[0][k + 2];
    double max_strain = 0;
    for (const auto& r : rows) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[kx + c], rows[0][kx + c], 1e-12 * l0) << "step " << r[0];
      EXPECT_NEAR(r[k] + r[k + 1] + r[k + 2], e0, 1e-6 * e0) << "step " << r[0];
      max_strain = std::max(max_strain, r[k + 1] / e0);
    }
    EXPECT_GT(max_strain, 1e-4);  // the centrifugal stretching is really there
  }
  const auto slow = spin_run("spin_slow", vec3(0.003, -0.002, 0.005), h);
  if (parallel::rank() == 0) {
    const auto k = column(h, "kinetic_energy");
    for (const auto& r : slow) EXPECT_LE(r[k + 1] + r[k + 2], 1e-10 * r[k]) << "step " << r[0];
  }
}

// Initial velocity along the normal: every node of the panel moves at 2 along its reference normal (unit),
// so the initial kinetic energy is 1/2 rho h |S| 2^2 (P2 area within 5e-4, see the translation test), and on
// the curved end x_max the mean velocity has no axial component and points outward (+z): the normals are
// (0, sin th, cos th). (The probe weights each mesh node by its number of DG copies, which on this diagonal
// pattern is not symmetric in th, so the mean y-component is not zero.)
TEST(Dynamics, NormalInitialVelocity) {
  const auto dir = work_dir("normal_velocity");
  auto deck = base_deck({}, dir);
  set_cylindrical_panel(*deck, 1.0, 1.5, 90, 4, 4);
  auto& blast = deck->sublist("Initial Conditions").sublist("blast");
  blast.set("Elements", std::string("shell")), blast.set("Normal Velocity", 2.0);
  set_probes(*deck, {"x_max"});
  write_deck(dir + "/nv.xml", *deck);
  solver::Simulation sim(dir + "/nv.xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  if (parallel::rank() != 0) return;
  std::vector<std::string> h;
  const auto rows = read_history(sim.history_path(), h);
  const double k = rows[0][column(h, "kinetic_energy")], exact = 0.5 * 1.0 * 0.1 * (M_PI / 2 * 1.5) * 4.0;
  EXPECT_NEAR(k, exact, 5e-4 * exact);
  EXPECT_NEAR(rows[0][column(h, "x_max_vel_x")], 0.0, 1e-14);
  EXPECT_GT(rows[0][column(h, "x_max_vel_z")], 2.0 * std::cos(M_PI / 4));  // every node has cos(th) >= cos 45 deg
}

TEST(Dynamics, BitwiseIdenticalOnAnyRankCount) {
  const auto dir = work_dir("bitwise");
  const auto deck = cantilever_deck(dir, 4, 6);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 0.004), time.set("History Interval", 10), time.set("Output Interval", 0.002);
  write_deck(dir + "/par.xml", *deck);
  write_deck(dir + "/ser.xml", *deck);
  solver::Simulation par(dir + "/par.xml");
  par.run();
  MPI_Barrier(MPI_COMM_WORLD);
  if (parallel::rank() == 0) {
    solver::Simulation ser(dir + "/ser.xml", MPI_COMM_SELF);
    ser.run();
    const std::string hp = slurp(par.history_path()), hs = slurp(ser.history_path());
    EXPECT_GT(hp.size(), 1000u);
    EXPECT_EQ(hp, hs) << "histories differ between " << parallel::size() << " ranks and 1 rank";
    const auto rp = io::read_results(par.exodus_path()), rs = io::read_results(ser.exodus_path());
    EXPECT_EQ(rp.num_files, parallel::size());
    EXPECT_EQ(rp.times, rs.times);
    EXPECT_EQ(rp.nodal, rs.nodal);  // every nodal value of every output step, bitwise
    EXPECT_EQ(rp.element_gids, rs.element_gids);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

TEST(Dynamics, CantileverPlateFirstFrequencyAndEnergy) {
  if (parallel::size() > 1) GTEST_SKIP() << "serial verification (the rank-count independence is tested above)";
  const auto dir = work_dir("cantilever");
  const auto deck = cantilever_deck(dir, 8, 12);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 0.3), time.set("History Interval", 10);
  write_deck(dir + "/cantilever.xml", *deck);
  solver::Simulation sim(dir + "/cantilever.xml");
  sim.run();
  std::vector<std::string> header;
  const auto rows = read_history(sim.history_path(), header);
  ASSERT_EQ(header[10], "y_max_displ_z");
  // Mean-free tip deflection; period from the upward zero crossings (linear interpolation).
  const auto crossings = upward_crossings(rows, 10);
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double frequency = 1.0 / period;
  RecordProperty("first_frequency_hz", std::to_string(frequency));
  EXPECT_NEAR(frequency, 10.785, 0.02 * 10.785) << "first frequency " << frequency << " Hz";
  // Energy balance: |K + U - K0| <= 0.1 % of the input energy K0 over the whole run.
  const double k0 = rows.front()[3];
  for (const auto& r : rows) EXPECT_LE(std::abs(r[7]), 1e-3 * k0) << "energy balance error at step " << r[0];
}
