// Contact between the shells (docs/theory.md §12.5; solver/contact/shell_contact.hpp, bin_grid.hpp,
// closest_point.hpp).
//
// 1. The broad phase against brute force: random boxes, every query's overlapping boxes, ascending (exact).
// 2. The nearest point of a triangle against a fine sampling of it: no sampled point is nearer (exact up to
//    round-off), the weights are a point of the triangle.
// 3. Two identical free elastic plates (1 x 1, h = 0.1, 4 x 4 cells each, parallel, 0.02 apart) meet head-on at
//    +-V (test (a) of the contact issue). The references: the total momentum is zero at every step (the contact forces
//    are pairs: a node's force and its face's reactions sum to zero), to round-off, 1e-12 M V; each plate's momentum
//    after the contact is that of a 1-D elastic impact of two equal bodies, which exchanges the velocities: -+V, within
//    1 % (the discrete switch in and out of contact of the central-difference recurrence: 0.6 % for the wall, theory.md
//    §12.3; measured here +0.02 %); the energy balance (the contact's work is external work, §12.5) closes to 1e-3 of
//    the kinetic energy (the acceptance of the contact issue; measured 1e-16); the plates never interpenetrate: their
//    mid-surfaces stay more than h/2 apart (the penetration at this speed is about V dt / sqrt(s) ~ 0.01 h).
// 4. The same run on 1, 2 and 3 ranks: bitwise the same history and results (test (e)); also with friction.
// 5. The input: an unknown block is refused naming it.
// 6., 7.: friction and restart, below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <vector>

#include "deck_test_util.hpp"
#include "in_memory_model.hpp"
#include "serial_compare.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/contact/bin_grid.hpp"
#include "shellfrac/solver/contact/closest_point.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/step/energy_accounts.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

TEST(BinGrid, FindsWhatBruteForceFinds) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-5, 5), size(0, 0.8);
  std::vector<solver::Box> boxes(500);
  for (auto& b : boxes)
    for (int c = 0; c < 3; ++c) b.lo[c] = pos(rng), b.hi[c] = b.lo[c] + size(rng);
  const solver::BinGrid grid(boxes, 0.1);
  for (int n = 0; n < 300; ++n) {
    solver::Box q;
    for (int c = 0; c < 3; ++c) q.lo[c] = pos(rng), q.hi[c] = q.lo[c] + 2 * size(rng);
    std::vector<int> brute;
    for (int i = 0; i < int(boxes.size()); ++i)
      if (boxes[std::size_t(i)].overlaps(q)) brute.push_back(i);
    EXPECT_EQ(grid.overlapping(q), brute) << "query " << n;
  }
}

TEST(ClosestPoint, NoPointOfTheTriangleIsNearer) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 0; n < 200; ++n) {
    double a[3], b[3], c[3], p[3];
    for (int i = 0; i < 3; ++i) a[i] = u(rng), b[i] = u(rng), c[i] = u(rng), p[i] = 2 * u(rng);
    const auto t = solver::closest_point_on_triangle(p, a, b, c);
    ASSERT_GE(std::min({t.w[0], t.w[1], t.w[2]}), 0.0);
    ASSERT_NEAR(t.w[0] + t.w[1] + t.w[2], 1.0, 1e-14);
    auto dist2 = [&](double w0, double w1, double w2) {
      double d = 0;
      for (int i = 0; i < 3; ++i) {
        const double y = w0 * a[i] + w1 * b[i] + w2 * c[i];
        d += (p[i] - y) * (p[i] - y);
      }
      return d;
    };
    const double best = dist2(t.w[0], t.w[1], t.w[2]);
    const int m = 60;
    for (int i = 0; i <= m; ++i)
      for (int j = 0; i + j <= m; ++j) {
        const double w1 = double(i) / m, w2 = double(j) / m;
        ASSERT_LE(best, dist2(1 - w1 - w2, w1, w2) * (1 + 1e-12) + 1e-15) << "triangle " << n;
      }
  }
}

namespace {

constexpr double h = 0.1, V = 10.0, gap0 = 0.02;  // plates 1 x 1, density 1: each of mass 0.1
constexpr int cells = 4;

/// Writes (rank 0) a Gmsh 2.2 mesh of two parallel unit squares, "lower" at z = -(h + gap0)/2 and "upper" at
/// z = +(h + gap0)/2, cells x cells each, two triangles per cell. Collective.
std::string write_two_plates(const std::string& dir) {
  const std::string path = dir + "/two_plates.msh";
  if (parallel::rank() == 0) {
    std::ofstream out(path);
    const int n = cells + 1;
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"lower\"\n2 2 \"upper\"\n$EndPhysicalNames\n";
    out << "$Nodes\n" << 2 * n * n << "\n";
    for (int p = 0; p < 2; ++p)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          out << 1 + p * n * n + j * n + i << " " << double(i) / cells << " " << double(j) / cells << " "
              << (p == 0 ? -0.5 : 0.5) * (h + gap0) << "\n";
    out << "$EndNodes\n$Elements\n" << 2 * 2 * cells * cells << "\n";
    int id = 1;
    for (int p = 0; p < 2; ++p)
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
          const int v = 1 + p * n * n + j * n + i;
          out << id++ << " 2 2 " << p + 1 << " " << p + 1 << " " << v << " " << v + 1 << " " << v + n + 1 << "\n";
          out << id++ << " 2 2 " << p + 1 << " " << p + 1 << " " << v << " " << v + n + 1 << " " << v + n << "\n";
        }
    out << "$EndElements\n";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}

Teuchos::RCP<Teuchos::ParameterList> two_plates_deck(const std::string& dir) {
  auto deck = base_deck({}, dir);
  deck->sublist("Blocks").remove("shell");
  for (const char* b : {"lower", "upper"}) {
    auto& block = deck->sublist("Blocks").sublist(b);
    block.set("Thickness", h), block.set("Material", std::string("m"));
  }
  write_two_plates(dir);
  set_mesh_file(*deck, "two_plates.msh");  // beside the deck
  initial_velocity(*deck, "up", "lower", vec3(0, 0, V));
  initial_velocity(*deck, "down", "upper", vec3(0, 0, -V));
  deck->sublist("Contact").sublist("Shells").set("Blocks", Teuchos::Array<std::string>(1, "all"));
  return deck;
}

/// Per block (lower, upper): the z-momentum and the mass, and the lowest z of the upper plate less the highest of
/// the lower one over the DG position nodes, over all ranks. Collective.
struct Plates {
  double momentum[2], mass[2], clearance;
};

Plates plates(const solver::ShellDynamics& dyn) {
  const auto& model = dyn.model();
  const auto& s = dyn.state();
  std::vector<ExactSum> sums(4);
  double top_of_lower = -1e300, bottom_of_upper = 1e300;
  for (LocalId le = 0; le < model.owned; ++le) {
    const int b = model.dm.element_block(le);  // the Gmsh physical names sort as "lower", "upper"
    for (int A = 0; A < solver::position_nodes; ++A) {
      const double m = *model.mass.at(le, A);
      sums[std::size_t(b)].add(m * s.v.at(le, A)[2]);
      sums[2 + std::size_t(b)].add(m);
      const double z = s.x.at(le, A)[2];
      if (b == 0) top_of_lower = std::max(top_of_lower, z);
      else bottom_of_upper = std::min(bottom_of_upper, z);
    }
  }
  ExactSum::allreduce(sums, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &top_of_lower, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &bottom_of_upper, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return {{sums[0].value(), sums[1].value()}, {sums[2].value(), sums[3].value()}, bottom_of_upper - top_of_lower};
}

}  // namespace

TEST(ShellContact, TwoPlatesMeetingHeadOnExchangeTheirVelocities) {
  const auto dir = work_dir("shell_contact_plates");
  auto model = build_model(two_plates_deck(dir), dir + "/plates.xml");
  ASSERT_EQ(model.block_names, (std::vector<std::string>{"lower", "upper"}));
  auto& dyn = *model.dynamics;
  const Plates p0 = plates(dyn);
  const double M = p0.mass[0], e0 = dyn.record().kinetic;
  ASSERT_NEAR(M, 0.1, 1e-12);
  EXPECT_NEAR(p0.momentum[0], M * V, 1e-12 * M * V);
  double min_clearance = p0.clearance;
  bool touched = false, separated = false;
  int steps = 0;
  for (; steps < 2000 && !separated; ++steps) {
    dyn.step();
    const Plates p = plates(dyn);
    EXPECT_NEAR(p.momentum[0] + p.momentum[1], 0.0, 1e-12 * M * V) << "step " << steps;
    min_clearance = std::min(min_clearance, p.clearance);
    touched = touched || p.momentum[0] < 0.5 * M * V;
    separated = touched && p.clearance > h + 0.5 * gap0;
  }
  ASSERT_TRUE(separated) << "the plates have not come apart after " << steps << " steps";
  const Plates p = plates(dyn);
  const auto r = dyn.record();
  RecordProperty("steps", steps);
  RecordProperty("rebound_lower_over_V", std::to_string(-p.momentum[0] / (M * V)));
  RecordProperty("rebound_upper_over_V", std::to_string(p.momentum[1] / (M * V)));
  RecordProperty("min_clearance_over_h", std::to_string(min_clearance / h));
  RecordProperty("balance_error_over_e0", std::to_string(solver::energy_balance_error(r, e0) / e0));
  EXPECT_NEAR(p.momentum[0], -M * V, 0.01 * M * V);
  EXPECT_NEAR(p.momentum[1], -p.momentum[0], 1e-12 * M * V);
  EXPECT_GT(min_clearance, 0.5 * h);
  EXPECT_LT(std::abs(solver::energy_balance_error(r, e0)), 1e-3 * e0);
}

// 6. Friction between the shells (theory.md §12.6): the plates of 3 meet head-on while the upper one also slides along
// x at U = 2 V, with mu = 0.2 (static = dynamic). The contact is short and the slip far from being stopped (the
// friction can take at most 2 mu (2 M V) of the relative tangential momentum M U), so every node slides throughout
// and Coulomb's law of impact holds for the impulses: each plate's tangential momentum changes by mu times the
// normal impulse 2 M V (Routh's rough-body impact; Stronge, Impact Mechanics, 2000, §3.2), within 1 % (nodes near
// the plates' edges, where the nearest point lies on an edge and the normal tilts). The tangential momentum is
// conserved to round-off (the reactions are the node forces' opposites); the energy balance closes to 1e-3 of the
// initial kinetic energy (measured 2.5e-5), and the energy friction took in the history's friction_dissipation is the
// loss of kinetic and strain energy within 3 %: the dissipation is booked as -f^{n+1} . v_slip^{n+1/2} dt, the
// external work by the trapezoidal rule, and the two differ by (1/2) sum (f^{n+1} - f^n) . dx_slip, which is not
// zero when the normal force rises while the slip is fast and falls when it is slower (measured 1.1 % over this
// contact of 28 steps at the default penalty; theory.md §12.6).
TEST(ShellContact, FrictionTakesMuTimesTheNormalImpulse) {
  const auto dir = work_dir("shell_contact_friction");
  auto deck = two_plates_deck(dir);
  const double U = 2 * V, mu = 0.2;
  deck->sublist("Initial Conditions").sublist("down").set("Velocity", vec3(U, 0, -V));
  deck->sublist("Contact").sublist("Shells").set("Friction Coefficient", mu);
  auto model = build_model(deck, dir + "/plates.xml");
  auto& dyn = *model.dynamics;
  ASSERT_EQ(dyn.contact_columns().back(), "friction_dissipation");
  const Plates p0 = plates(dyn);
  const double M = p0.mass[0], e0 = dyn.record().kinetic;
  const auto tangential = [&] {  // the lower and the upper plate's x-momenta
    std::vector<ExactSum> sums(2);
    for (LocalId le = 0; le < dyn.model().owned; ++le)
      for (int A = 0; A < solver::position_nodes; ++A)
        sums[std::size_t(dyn.model().dm.element_block(le))].add(*dyn.model().mass.at(le, A) * dyn.state().v.at(le, A)[0]);
    ExactSum::allreduce(sums, MPI_COMM_WORLD);
    return std::pair{sums[0].value(), sums[1].value()};
  };
  bool touched = false, separated = false;
  int steps = 0, contact_steps = 0;
  for (; steps < 2000 && !separated; ++steps) {
    dyn.step();
    const Plates p = plates(dyn);
    const auto [lower, upper] = tangential();
    contact_steps += dyn.contact_values().at(1) > 0;
    EXPECT_NEAR(lower + upper, M * U, 1e-12 * M * U) << "step " << steps;
    touched = touched || p.momentum[0] < 0.5 * M * V;
    separated = touched && p.clearance > h + 0.5 * gap0;
  }
  ASSERT_TRUE(separated) << "the plates have not come apart after " << steps << " steps";
  const Plates p = plates(dyn);
  const auto [lower, upper] = tangential();
  const double normal_impulse = M * V - p.momentum[0];  // the one the lower plate took (along -z): about 2 M V
  RecordProperty("normal_impulse_over_MV", std::to_string(normal_impulse / (M * V)));
  RecordProperty("tangential_impulse_over_mu_normal", std::to_string(lower / (mu * normal_impulse)));
  EXPECT_NEAR(lower, mu * std::abs(normal_impulse), 0.01 * mu * std::abs(normal_impulse));
  EXPECT_NEAR(upper, M * U - lower, 1e-12 * M * U);
  const auto r = dyn.record();
  const double dissipated = dyn.contact_values().back();
  RecordProperty("dissipated_over_e0", std::to_string(dissipated / e0));
  RecordProperty("dissipated_over_energy_lost", std::to_string(dissipated / (e0 - r.kinetic - r.strain - r.penalty)));
  RecordProperty("contact_steps", contact_steps);
  RecordProperty("balance_error_over_e0", std::to_string(solver::energy_balance_error(r, e0) / e0));
  EXPECT_LT(std::abs(solver::energy_balance_error(r, e0)), 1e-3 * e0);
  EXPECT_NEAR(dissipated, e0 - r.kinetic - r.strain - r.penalty, 0.03 * dissipated);
}

namespace {

/// Runs the plates' deck to 4 ms in `dir`, checks that its results are those of the serial run bitwise, and returns
/// each history column's largest value (by column name). Collective.
std::map<std::string, double> same_as_serial(Teuchos::ParameterList& deck, const std::string& dir) {
  deck.sublist("Time Integration").set("End Time", 4e-3);
  deck.sublist("Time Integration").set("Output Interval", 1e-3);
  write_deck(dir + "/plates.xml", deck);
  solver::Simulation sim(dir + "/plates.xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  std::vector<std::string> header;
  const auto rows = read_history(sim.history_path(), header);
  std::map<std::string, double> peak;
  for (const auto& row : rows)
    for (std::size_t c = 0; c < header.size(); ++c) peak[header[c]] = std::max(peak[header[c]], row[c]);
  expect_same_as_serial(sim, deck, dir, "plates");
  return peak;
}

}  // namespace

TEST(ShellContact, SameResultsOnAnyRankCount) {
  const auto dir = work_dir("shell_contact_ranks");
  auto deck = two_plates_deck(dir);
  EXPECT_GT(same_as_serial(*deck, dir)["shell_contact_nodes"], 0) << "the plates never touched";
}

// The same with friction while the plates slide (6.): the ghost faces' velocities enter the slip.
TEST(ShellContact, SameResultsOnAnyRankCountWithFriction) {
  const auto dir = work_dir("shell_contact_ranks_friction");
  auto deck = two_plates_deck(dir);
  deck->sublist("Initial Conditions").sublist("down").set("Velocity", vec3(2 * V, V, -V));
  deck->sublist("Contact").sublist("Shells").set("Friction Coefficient", 0.2);
  EXPECT_GT(same_as_serial(*deck, dir)["friction_dissipation"], 0) << "no friction";
}

// 7. Restart during a contact with friction (the contact state is a function of the positions and velocities, which
// the checkpoint holds; the candidate lists are rebuilt and the face chosen does not depend on them, §12.5): the
// sliding plates of 6 are run to 2 ms without a break, and again to the middle of their contact with a checkpoint,
// then restarted to 2 ms — also from 3 ranks to 2. The restarted run's history equals the continuous one's bitwise.
TEST(ShellContact, RestartDuringAContactWithFrictionIsBitwise) {
  const auto root = work_dir("shell_contact_restart");
  const auto deck_to = [&](const std::string& dir, double end) {
    if (parallel::rank() == 0) std::filesystem::create_directories(dir);
    MPI_Barrier(MPI_COMM_WORLD);
    auto deck = two_plates_deck(dir);
    deck->sublist("Initial Conditions").sublist("down").set("Velocity", vec3(2 * V, 0, -V));
    deck->sublist("Contact").sublist("Shells").set("Friction Coefficient", 0.2);
    deck->sublist("Contact").sublist("Shells").set("Static Friction Coefficient", 0.3);
    auto& time = deck->sublist("Time Integration");
    time.set("End Time", end), time.set("Output Interval", 1e-3), time.set("History Interval", 1);
    deck->sublist("Checkpoint").set("Step Interval", 100000);
    write_deck(dir + "/run.xml", *deck);
    return dir + "/run.xml";
  };
  const std::string reference = root + "/continuous";
  solver::Simulation continuous(deck_to(reference, 2e-3));
  continuous.run();
  MPI_Barrier(MPI_COMM_WORLD);
  // The split: the middle of the contact (the rows with nodes in contact), read on every rank.
  std::vector<std::string> header;
  const auto rows = read_history(continuous.history_path(), header);
  std::vector<double> touching;
  for (const auto& row : rows)
    if (row[column(header, "shell_contact_nodes")] > 0) touching.push_back(row[column(header, "time")]);
  ASSERT_GE(touching.size(), 5u) << "the plates never touched";
  const double split = touching[touching.size() / 2];
  const auto broken = [&](const std::string& dir, MPI_Comm first, MPI_Comm second) {
    if (first != MPI_COMM_NULL) solver::Simulation(deck_to(dir, split), first).run();
    MPI_Barrier(MPI_COMM_WORLD);
    std::string checkpoint;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".h5") checkpoint = e.path().string();
    ASSERT_FALSE(checkpoint.empty()) << "no checkpoint in " << dir;
    const std::string deck = deck_to(dir, 2e-3);
    if (second != MPI_COMM_NULL) {
      solver::Simulation sim(deck, second, checkpoint);
      EXPECT_GT(sim.summary().restart_step, 0);
      sim.run();
    }
    MPI_Barrier(MPI_COMM_WORLD);
    if (parallel::rank() == 0) {
      EXPECT_EQ(slurp(continuous.history_path()), slurp(dir + "/run_history.csv")) << dir;
    }
  };
  broken(root + "/same_ranks", MPI_COMM_WORLD, MPI_COMM_WORLD);
  if (parallel::size() == 3) {
    MPI_Comm two;
    MPI_Comm_split(MPI_COMM_WORLD, parallel::rank() < 2 ? 0 : MPI_UNDEFINED, parallel::rank(), &two);
    broken(root + "/three_to_two", MPI_COMM_WORLD, two);
    if (two != MPI_COMM_NULL) MPI_Comm_free(&two);
  }
}

TEST(ShellContact, UnknownBlockRefused) {
  const auto dir = work_dir("shell_contact_input");
  auto deck = two_plates_deck(dir);
  deck->sublist("Contact").sublist("Shells").set("Blocks", Teuchos::Array<std::string>(1, "middle"));
  const std::string e = input_error(deck, dir + "/plates.xml");
  EXPECT_NE(e.find("/plates.xml: 'Contact->Shells->Blocks' names the block 'middle', which the mesh does not have"),
            std::string::npos)
      << e;
}
