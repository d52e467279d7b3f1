// The energy balance through fast fracture (docs/theory.md §9.6, docs/verification.md §5.1).
// A closed aluminium cylinder (R = 600 mm, L = 1200 mm, h = 1.5 mm, 12 x 38 cells, 912 TRI6; mm-t-s units:
// E = 72 000 MPa, nu = 0.34, rho = 2.7e-9 t/mm^3, sigma_c = 540 MPa, Gamma = 50 N/mm) is torn open by the
// exponential pressure pulse of the paper's §6.5 (3.37 MPa, decay 692 us) on a cylinder sector (22.5 to 135
// degrees from +z, x from 300 to 900 mm): about 50 edges activate and separate within 150 us, opening at
// several m/s. References, measured here and explained in theory.md §9.6:
//  * default activation opening (0.05 delta_f): the balance error stays within 1 % of the cohesive
//    dissipation (measured 0.02 %) at every history row, the level the issue sets for fast fracture;
//  * the paper's rigid law (Activation Opening 0): the error reaches more than 5 % of the cohesive dissipation
//    (measured 11.5 %): the defect the default removes, kept here so that a regression shows;
//  * both: at least 30 separated edges at the end, so the check is made through separation (measured 37 and 39
//    with the default membrane strains; 49 and 48 with Point Values, whose coarse curved elements, a sagitta of
//    1.4 thicknesses, are stiffer in bending: theory.md §5.4).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "deck_test_util.hpp"
#include "shellfrac/solver/simulation.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

/// The torn cylinder's deck with the given activation opening (negative: the default).
Teuchos::RCP<Teuchos::ParameterList> torn_cylinder_deck(const std::string& dir, double activation_opening) {
  auto deck = base_deck({1.5, 2.7e-9, 72000.0, 0.34}, dir);
  auto& mesh = deck->sublist("Mesh");
  mesh.set("Source", std::string("Cylinder"));
  auto& c = mesh.sublist("Cylinder");
  c.set("Radius", 600.0), c.set("Length", 1200.0), c.set("Axial Elements", 12), c.set("Circumferential Elements", 38);
  c.set("Block Name", std::string("shell"));
  auto& material = shell_material(*deck);
  material.set("Cohesive Strength", 540.0), material.set("Fracture Energy", 50.0);
  auto& patch = deck->sublist("Regions").sublist("patch");
  patch.set("Shape", std::string("Cylinder Sector"));
  patch.set("Center", vec3(0, 0, 0)), patch.set("Axis", vec3(1, 0, 0)), patch.set("Reference Direction", vec3(0, 0, 1));
  patch.set("Angle Range", Teuchos::Array<double>(Teuchos::tuple<double>(22.5, 135.0)));
  patch.set("Axial Range", Teuchos::Array<double>(Teuchos::tuple<double>(300.0, 900.0)));
  patch.set("Radius Range", Teuchos::Array<double>(Teuchos::tuple<double>(500.0, 700.0)));
  auto& pulse = deck->sublist("Loads").sublist("pulse");
  pulse.set("Type", std::string("Pressure")), pulse.set("Elements", std::string("patch"));
  pulse.set("Function", std::string("Exponential")), pulse.set("Pressure", 3.37), pulse.set("Decay Time", 6.92e-4);
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", 1.5e-4), time.set("History Interval", 10), time.set("Output Interval", 1.0);
  if (activation_opening >= 0) deck->sublist("Fracture").set("Activation Opening", activation_opening);
  set_probes(*deck, {});
  return deck;
}

struct BalanceSummary {
  double worst_error = 0;        ///< largest |energy_balance_error| over the rows
  double final_error = 0;        ///< energy_balance_error at the end
  double dissipation = 0;        ///< cohesive_dissipation at the end
  double separated = 0;          ///< num_separated_edges at the end
};

BalanceSummary run_torn_cylinder(const std::string& name, double activation_opening) {
  const auto dir = work_dir(name);
  write_deck(dir + "/torn.xml", *torn_cylinder_deck(dir, activation_opening));
  solver::Simulation sim(dir + "/torn.xml");
  sim.run();
  std::vector<std::string> hd;
  const auto rows = read_history(sim.history_path(), hd);
  const auto ce = column(hd, "energy_balance_error");
  BalanceSummary s;
  for (const auto& r : rows) s.worst_error = std::max(s.worst_error, std::abs(r[ce]));
  s.final_error = rows.back()[ce];
  s.dissipation = rows.back()[column(hd, "cohesive_dissipation")];
  s.separated = rows.back()[column(hd, "num_separated_edges")];
  std::printf("%s: %g separated edges, D_coh = %.6g, final error %.4g (%.3g %% of D_coh), worst %.4g\n", name.c_str(),
              s.separated, s.dissipation, s.final_error, 100 * s.final_error / s.dissipation, s.worst_error);
  return s;
}

}  // namespace

TEST(FastFracture, BalanceClosesWithTheDefaultActivationOpening) {
  const BalanceSummary s = run_torn_cylinder("fast_fracture_default", -1);
  EXPECT_GE(s.separated, 30);
  EXPECT_LE(s.worst_error, 0.01 * s.dissipation);
}

TEST(FastFracture, TheRigidLawLosesTheBalance) {
  const BalanceSummary s = run_torn_cylinder("fast_fracture_rigid", 0.0);
  EXPECT_GE(s.separated, 30);
  EXPECT_GE(s.final_error, 0.05 * s.dissipation);
}
