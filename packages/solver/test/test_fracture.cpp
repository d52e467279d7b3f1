// Extrinsic cohesive fracture in the explicit solver (issue #5), each check with its reference:
//  * StripWithOneCohesiveEdge: docs/verification.md §5.2 (closed form, derived there). A strip x in [0, 2L]
//    (nu = 0, so the membrane wave speed is c = sqrt(E/rho) exactly) whose only breakable edge is at x = L
//    has both ends pulled outward at V from t = 0. The tension waves Z V (Z = rho c) meet at x = L at
//    t0 = L/c; with 2 Z V > sigma_c > Z V the edge activates then, and the cohesive law
//    T = sigma_c (1 - delta/delta_c) separates it completely at
//      t_sep = t0 + (Z delta_c / (2 sigma_c)) ln[2 Z V / (2 Z V - sigma_c)],  delta_c = 2 Gamma / sigma_c.
//    Asserted: activation and separation times within 2 % of the closed form (the tolerance, on the
//    times measured from t = 0), the dissipated energy of the separated edge = Gamma h b to 1e-6 relative
//    (theory.md §9.7), the energy balance within 1 % of the input work, and — no artificial compliance — the
//    history before activation is bitwise the history of the same strip that cannot break.
//  * SameBreaksOnAnyRankCount: a clamped 6061-T6 beam (paper §6.3 data, Gamma = 0) hit at 225 m/s shears off
//    at its supports within microseconds; on np ranks the history (edge and fragment counts, every energy)
//    and every Exodus value (fields incl. damage and fragment_id; not the rank) equal a serial run bitwise.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "deck_test_util.hpp"
#include "cracked_strip.hpp"
#include "serial_compare.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/solver/simulation.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

// the paper's Table 3 material (6061-T6) with Gamma = 10 kJ/m^2, V = 20 m/s: docs/verification.md §5.2 example
// (c0 = 5058 m/s, Z = 1.362e7 Pa s/m, 2 Z V = 545 MPa > sigma_c = 375 MPa, delta_c = 53.3 um, t_sep - t0 = 1.13 us).
constexpr double E = 68.9e9, rho = 2693, sigma_c = 375e6, Gamma = 10e3, V = 20;
constexpr double L = strip_L, b = strip_b, h = strip_h;

/// Writes the strip mesh on rank 0 (cracked_strip.hpp). Collective.
void write_strip(const std::string& path) {
  if (parallel::rank() == 0) write_cracked_strip(path);
  MPI_Barrier(MPI_COMM_WORLD);
}

/// The strip's deck (cracked_strip.hpp) run to 14 us with the cohesive strength `strength` (0: cannot break);
/// probes crack and quarter.
Teuchos::RCP<Teuchos::ParameterList> strip_deck(const std::string& dir, double strength) {
  auto deck = pulled_strip_deck(dir, "strip_mesh.exo", {h, rho, E, 0.0});
  deck->sublist("Time Integration").set("End Time", 14e-6);
  auto& material = shell_material(*deck);
  material.set("Cohesive Strength", strength), material.set("Fracture Energy", strength > 0 ? Gamma : 0.0);
  set_probes(*deck, {"crack", "quarter"});
  return deck;
}

/// A clamped 6061-T6 beam (paper §6.3 data, Gamma = 0), 0.2 x 0.025 on 40 x 5 cells, hit at 225 m/s; no probes.
Teuchos::RCP<Teuchos::ParameterList> clamped_beam_deck(const std::string& dir) {
  auto deck = base_deck({6.53e-3, 2693, 68.9e9, 0.343}, dir);
  set_rectangle(*deck, 0.2, 0.025, 40, 5);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 3e-5), time.set("History Interval", 5), time.set("Output Interval", 1e-5);
  boundary_condition(*deck, "left", "Clamped", "x_min");
  boundary_condition(*deck, "right", "Clamped", "x_max");
  initial_velocity(*deck, "impulse", "all", vec3(0.0, 0.0, -225.0));
  auto& material = shell_material(*deck);
  material.set("Model", std::string("Resultant Plasticity")), material.set("Yield Stress", 275e6);
  material.set("Hardening Modulus", 1.33e9), material.set("Cohesive Strength", 375e6);
  set_probes(*deck, {});
  return deck;
}

}  // namespace

TEST(Fracture, StripWithOneCohesiveEdge) {
  const auto dir = work_dir("fracture_strip");
  write_strip(dir + "/strip_mesh.exo");
  write_deck(dir + "/strip.xml", *strip_deck(dir, sigma_c));
  write_deck(dir + "/intact.xml", *strip_deck(dir, 0.0));
  solver::Simulation sim(dir + "/strip.xml");
  sim.run();
  solver::Simulation intact(dir + "/intact.xml");
  intact.run();
  std::vector<std::string> hd, hi;
  const auto rows = read_history(sim.history_path(), hd);
  const auto rows_intact = read_history(intact.history_path(), hi);
  const auto ct = column(hd, "time"), cc = column(hd, "num_cohesive_edges"), cs = column(hd, "num_separated_edges");
  ASSERT_LT(cs, hd.size());
  const double c = std::sqrt(E / rho), Z = rho * c, t0 = L / c, delta_c = 2 * Gamma / sigma_c;
  const double t_sep = t0 + Z * delta_c / (2 * sigma_c) * std::log(2 * Z * V / (2 * Z * V - sigma_c));
  double t_act = -1, t_broken = -1;
  for (const auto& r : rows) {
    if (t_act < 0 && r[cc] > 0) t_act = r[ct];
    if (t_broken < 0 && r[cs] > 0) t_broken = r[ct];
  }
  std::printf("activation at %.4g s (closed form %.4g), separation at %.4g s (closed form %.4g)\n", t_act, t0,
              t_broken, t_sep);
  ::testing::Test::RecordProperty("t_activation", std::to_string(t_act));
  ::testing::Test::RecordProperty("t_separation", std::to_string(t_broken));
  EXPECT_NEAR(t_act, t0, 0.02 * t0);
  EXPECT_NEAR(t_broken, t_sep, 0.02 * t_sep);
  // Only the one edge (1 cell across: one interface) breaks, into two fragments.
  EXPECT_EQ(rows.back()[cs], 1.0);
  EXPECT_EQ(rows.back()[column(hd, "num_fragments")], 2.0);
  EXPECT_NEAR(rows.back()[column(hd, "cohesive_dissipation")], Gamma * h * b, 1e-6 * Gamma * h * b);
  EXPECT_EQ(rows.back()[column(hd, "cohesive_energy")], 0.0);
  const double input = rows.back()[column(hd, "reaction_work")];
  for (const auto& r : rows) EXPECT_LE(std::abs(r[column(hd, "energy_balance_error")]), 0.01 * input) << "t = " << r[ct];
  // Fragment table at the last output: the two halves, each of mass rho h L b, moving apart symmetrically.
  std::vector<std::string> hf;
  const auto frags = read_history(sim.fragments_path(), hf);
  ASSERT_GE(frags.size(), 2u);
  const auto& f1 = frags[frags.size() - 2];
  const auto& f2 = frags.back();
  ASSERT_EQ(f1[0], f2[0]) << "the last two rows are the last output time";
  const double half = rho * h * L * b;
  EXPECT_NEAR(f1[column(hf, "mass")], half, 1e-12 * half);
  EXPECT_NEAR(f2[column(hf, "mass")], half, 1e-12 * half);
  EXPECT_NEAR(f1[column(hf, "com_x")] + f2[column(hf, "com_x")], 2 * L, 1e-9 * L);
  EXPECT_LT(f1[column(hf, "momentum_x")], 0.0);
  EXPECT_NEAR(f1[column(hf, "momentum_x")] + f2[column(hf, "momentum_x")], 0.0, 1e-9 * half * V);
  // Crack log: one row, the edge at mid-length, activated at t_act (the history records every step) by normal
  // opening (uniaxial tension across the edge). The other terms of n_eq^2 are not exactly zero: the P1 projections
  // of the two triangles' resultants carry a little in-plane shear near the wave front (measured share 6e-6).
  std::vector<std::string> hc;
  const auto cracks = read_history(sim.cracks_path(), hc);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_EQ(cracks[0][column(hc, "time")], t_act);
  EXPECT_NEAR(cracks[0][column(hc, "x")], L, 1e-3 * L);
  EXPECT_GE(cracks[0][column(hc, "fbar")], 0.0);
  EXPECT_GT(cracks[0][column(hc, "share_normal")], 1 - 1e-4);
  // No artificial compliance: until the edge activates, the run is the intact strip's, bitwise.
  ASSERT_EQ(hd, hi);
  std::size_t compared = 0;
  for (std::size_t k = 0; k < rows.size() && rows[k][ct] < t_act; ++k, ++compared)
    for (std::size_t j = 0; j < column(hd, "cohesive_energy"); ++j)
      EXPECT_EQ(rows[k][j], rows_intact[k][j]) << hd[j] << " at t = " << rows[k][ct];
  EXPECT_GT(compared, 50u);
}

TEST(Fracture, SameBreaksOnAnyRankCount) {
  const auto dir = work_dir("fracture_beam");
  const auto deck = clamped_beam_deck(dir);
  write_deck(dir + "/beam.xml", *deck);
  solver::Simulation sim(dir + "/beam.xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  std::vector<std::string> hd;
  const auto rows = read_history(sim.history_path(), hd);
  EXPECT_GT(rows.back()[column(hd, "num_separated_edges")], 4.0) << "the beam must shear off at its supports";
  EXPECT_GT(rows.back()[column(hd, "num_fragments")], 2.0);
  // The crack log has a row per activated edge, each with its five shares of n_eq^2 summing to 1.
  std::vector<std::string> hc;
  const auto cracks = read_history(sim.cracks_path(), hc);
  EXPECT_EQ(double(cracks.size()), rows.back()[column(hd, "num_cohesive_edges")]);
  for (const auto& r : cracks) {
    double sum = 0;
    for (std::size_t k = 0; k < hc.size(); ++k) sum += hc[k].rfind("share_", 0) == 0 ? r[k] : 0.0;
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  expect_same_as_serial(sim, *deck, dir, "beam");
}

namespace {

constexpr double fixture_length = 0.01, span = 0.2, width = 0.025, hb = 6.53e-3;  // 2 fixture cells of 5 mm each side

/// Writes on rank 0 the beam [0, span] x [0, width] (40 x 5 cells) with the fixture block "fixture" (2 cells of
/// 5 mm) beyond each end, P2. Collective.
void write_fixture_mesh(const std::string& path) {
  constexpr double lf = fixture_length;
  if (parallel::rank() == 0) {
    auto m = mesh::make_rectangle(span + 2 * lf, width, 44, 5, mesh::DiagonalPattern::Alternating, -lf);
    m.blocks.push_back({"fixture", 2});
    for (GlobalId e = 0; e < m.num_elements(); ++e) {
      double xc = 0;
      for (int k = 0; k < 3; ++k) xc += m.coords[m.node(e, k)][0] / 3;
      if (xc < 0 || xc > span) m.element_block[e] = 1;
    }
    mesh::promote_to_p2(m);
    meshio::write_exodus_mesh(m, path);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

/// The beam of fixture_mesh.exo hit at 225 m/s, its fixture (a second block of the same material) clamped; no probes.
Teuchos::RCP<Teuchos::ParameterList> fixture_deck(const std::string& dir) {
  auto deck = base_deck({hb, 2693, 68.9e9, 0.343}, dir);
  set_mesh_file(*deck, "fixture_mesh.exo");
  auto& fixture = deck->sublist("Blocks").sublist("fixture");
  fixture.set("Thickness", hb), fixture.set("Material", std::string("m"));
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 3e-6), time.set("Output Interval", 1e-6);
  boundary_condition(*deck, "fixture", "Clamped", "all").set("Elements", std::string("fixture"));
  initial_velocity(*deck, "impulse", "shell", vec3(0.0, 0.0, -225.0));
  shell_material(*deck).set("Cohesive Strength", 375e6);
  set_probes(*deck, {});
  return deck;
}

}  // namespace

// A clamping fixture that is part of the mesh (boundary condition with Elements = its block): only the
// fixture's DG copies of the border nodes are held, so the beam's copies move and the edges on the border are
// interior edges that can break. References: the definition of the option (docs/theory.md, "Conditions and
// loads"); the border edges are where the shear force of a suddenly stopped beam is largest, so at 225 m/s with
// an elastic shear force (docs/beam_blast.md: threshold sigma_c/(rho c_s') = 49 m/s) they break first.
TEST(Fracture, FixtureBorderEdgesBreak) {
  const auto dir = work_dir("fracture_fixture");
  write_fixture_mesh(dir + "/fixture_mesh.exo");
  write_deck(dir + "/fixture.xml", *fixture_deck(dir));
  solver::Simulation sim(dir + "/fixture.xml");
  sim.run();
  MPI_Barrier(MPI_COMM_WORLD);
  if (parallel::rank() == 0) {
    const auto res = io::read_results(sim.exodus_path());
    ASSERT_GE(res.times.size(), 2u);
    const auto dz = std::find(res.nodal_names.begin(), res.nodal_names.end(), "displ_z") - res.nodal_names.begin();
    ASSERT_LT(std::size_t(dz), res.nodal_names.size());
    const int npe = res.nodes_per_element;
    const auto& w = res.nodal.back()[dz];
    int held_copies = 0, free_border_copies = 0;
    for (std::size_t e = 0; e < res.element_gids.size(); ++e) {
      const bool fixture = res.element_block_ids[e] == 2;
      for (int a = 0; a < npe; ++a) {
        const double x = res.node_coords[e * npe + a][0];
        if (fixture && (x < 1e-9 || x > span - 1e-9)) {
          EXPECT_EQ(w[e * npe + a], 0.0) << "a held copy moved, x = " << x;
          ++held_copies;
        }
        if (!fixture && (std::abs(x) < 1e-9 || std::abs(x - span) < 1e-9)) {
          EXPECT_LT(w[e * npe + a], -1e-5) << "the beam's copy on the border must move";
          ++free_border_copies;
        }
      }
    }
    EXPECT_GT(held_copies, 0);
    EXPECT_GT(free_border_copies, 0);
    std::vector<std::string> hc;
    const auto cracks = read_history(sim.cracks_path(), hc);
    ASSERT_FALSE(cracks.empty());
    const double first_step = cracks.front()[column(hc, "step")];
    for (const auto& r : cracks) {
      if (r[column(hc, "step")] != first_step) break;
      const double x = r[column(hc, "x")];
      EXPECT_TRUE(std::abs(x) < 1e-3 || std::abs(x - span) < 1e-3) << "first edges broken at x = " << x;
      EXPECT_GT(r[column(hc, "share_transverse_shear")], 0.5);
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

// Crack-face contact (Fracture->Crack Face Contact, docs/theory.md §9.9). The strip of StripWithOneCohesiveEdge, free at both ends, its halves
// launched apart at V = 1 m/s and pulled back by opposite body accelerations g = 2.5e4 m/s^2 (Gravity on each
// half); the crack edge (Gamma = 0, sigma_c = 5 MPa < Z V = 13.6 MPa) separates at once, the halves stop after
// V/g = 40 us and meet again at about 2 V/g = 80 us at V. References:
//  * the contact of two elastic bars meeting at V each carries the stress Z V (Z = rho c), so the penalty
//    k_c = beta_x/h_e = c_x E h/b closes the faces by delta = Z V h b/(k_c b) = V b/(c_x c) = 6.6e-8 m
//    (c_x = 3, c = 5058 m/s); measured from the contact energy, the only energy of a separated edge:
//    U_c = 1/2 k_c b delta^2 over the edge's width b, delta = sqrt(2 U_c/(k_c b)). Asserted: the largest
//    penetration below 2 V b/(c_x c) (dynamic overshoot allowed); without contact the halves would pass through
//    each other by about V times the remaining time (0.03 mm);
//  * 1-D elastic impact of identical bars: they exchange velocities, so the halves bounce back after the contact
//    wave's round trip 2 L/c = 20 us; the left half's momentum goes from about +m V before the impact to about
//    -m V after it (the body force changes it by m g 2L/c = 0.5 m V meanwhile). Asserted: above +0.5 m V at one
//    frame and below -0.25 m V at a later one; without contact it would only grow;
//  * the energy balance closes to 1e-3 of the input (initial kinetic energy plus the body forces' work) at every
//    step: the contact is elastic and stores its energy in cohesive_energy.
TEST(Fracture, CrackFacesStopAtContact) {
  constexpr double Vc = 1.0, g = 2.5e4, sc = 5e6, cx = 3.0;
  const auto dir = work_dir("fracture_contact");
  write_strip(dir + "/strip_mesh.exo");
  auto deck = base_deck({h, rho, E, 0.0}, dir);
  set_mesh_file(*deck, "strip_mesh.exo");
  deck->sublist("Fracture").set("Edges", std::string("crack"));
  deck->sublist("Fracture").set("Crack Face Contact", true);
  auto& material = shell_material(*deck);
  material.set("Cohesive Strength", sc), material.set("Fracture Energy", 0.0);
  for (const auto& [name, lo, hi] : {std::tuple{"left", -1.0, L}, std::tuple{"right", L, 3 * L}}) {
    auto& r = deck->sublist("Regions").sublist(name);
    r.set("Shape", std::string("Box")), r.set("Min", vec3(lo, -1, -1)), r.set("Max", vec3(hi, 1, 1));
  }
  initial_velocity(*deck, "left", "left", vec3(-Vc, 0, 0));
  initial_velocity(*deck, "right", "right", vec3(Vc, 0, 0));
  for (const auto& [name, sign] : {std::pair{"left", 1.0}, std::pair{"right", -1.0}}) {
    auto& load = deck->sublist("Loads").sublist(std::string("pull ") + name);
    load.set("Type", std::string("Gravity")), load.set("Elements", std::string(name));
    load.set("Acceleration", vec3(sign * g, 0, 0));
  }
  deck->sublist("Time Integration").set("End Time", 1.1e-4);
  deck->sublist("Time Integration").set("Output Interval", 2e-6);
  set_probes(*deck, {});
  write_deck(dir + "/contact.xml", *deck);
  solver::Simulation sim(dir + "/contact.xml");
  sim.run();
  std::vector<std::string> hd;
  const auto rows = read_history(sim.history_path(), hd);
  const double c = std::sqrt(E / rho), kc = cx * E * h / b;
  double worst_penetration = 0, input = 0, worst_error = 0;
  for (const auto& r : rows) {
    worst_penetration = std::max(worst_penetration, std::sqrt(2 * r[column(hd, "cohesive_energy")] / (kc * b)));
    input = std::max(input, rows[0][column(hd, "kinetic_energy")] + r[column(hd, "external_work")]);
    worst_error = std::max(worst_error, std::abs(r[column(hd, "energy_balance_error")]));
  }
  std::printf("largest penetration %.3g m (bound %.3g m), worst balance error %.3g of the input %.3g J\n",
              worst_penetration, 2 * Vc * b / (cx * c), worst_error / input, input);
  EXPECT_EQ(rows.back()[column(hd, "num_separated_edges")], 1.0);
  EXPECT_GT(worst_penetration, 0.1 * Vc * b / (cx * c)) << "the faces must have met";
  EXPECT_LT(worst_penetration, 2 * Vc * b / (cx * c));
  EXPECT_LT(worst_error, 1e-3 * input);
  // The left half bounced: its momentum went from towards the right half to away from it.
  std::vector<std::string> hf;
  const auto frags = read_history(sim.fragments_path(), hf);
  const double mV = rho * h * L * b * Vc;
  double approach = -1, bounced = -1;  // the times of the first frame above +0.5 m V, and a later one below -0.25 m V
  for (const auto& f : frags) {
    if (f[column(hf, "com_x")] > L) continue;  // the right half
    const double p = f[column(hf, "momentum_x")], t = f[0];
    if (approach < 0 && p > 0.5 * mV) approach = t;
    if (approach > 0 && bounced < 0 && p < -0.25 * mV) bounced = t;
  }
  std::printf("left half: approaching at %g s, bounced back by %g s\n", approach, bounced);
  EXPECT_GT(approach, 0.0);
  EXPECT_GT(bounced, approach);
}
