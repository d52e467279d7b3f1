#include "shellfrac/solver/dynamics_params.hpp"

#include <Teuchos_Array.hpp>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

Teuchos::RCP<const Teuchos::ParameterList> DiscretizationParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Discretization"));
  pl->set("Position Penalty", 3.0, "c_x in beta_x = c_x E h (paper eq. 42; 3 in every example of the paper)",
          params::positive_double());
  pl->set("Director Penalty", 3.0, "c_T in beta_T = c_T E h^3/12 (paper eq. 42)", params::positive_double());
  return pl;
}

DiscretizationParams DiscretizationParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  return {pl.get<double>("Position Penalty"), pl.get<double>("Director Penalty")};
}

Teuchos::RCP<const Teuchos::ParameterList> TimeParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Time Integration"));
  pl->set("End Time", 0.0, "Final time [time]; 0 writes the reference state without time stepping",
          params::non_negative_double());
  pl->set("Safety Factor", 0.8, "S_f: the time step is S_f times the stable estimate (math.md §8; keep <= 0.9)",
          params::double_range(0.0, 1.0, true, false));
  pl->set("Time Step", 0.0, "Fixed time step [time]; 0 = Safety Factor x stable estimate", params::non_negative_double());
  pl->set("Force Time Step", false, "Run with a fixed Time Step even if it exceeds the stable estimate");
  pl->set("Rotary Inertia Scale", 1.0, "s_I >= 1 multiplies the rotary inertia rho h^3/12 (raises the stable step of "
                                       "thin shells; changes the dynamics; reported when used)",
          params::double_range(1.0, 1e6));
  pl->set("Output Interval", 0.0, "Time between Exodus outputs [time]; 0 = first and last step only",
          params::non_negative_double());
  pl->set("History Interval", 1, "Steps between rows of the history CSV", params::int_range(1, 1 << 30));
  return pl;
}

TimeParams TimeParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  TimeParams t;
  t.end_time = pl.get<double>("End Time");
  t.safety_factor = pl.get<double>("Safety Factor");
  t.time_step = pl.get<double>("Time Step");
  t.force_time_step = pl.get<bool>("Force Time Step");
  t.rotary_inertia_scale = pl.get<double>("Rotary Inertia Scale");
  t.output_interval = pl.get<double>("Output Interval");
  t.history_interval = pl.get<int>("History Interval");
  return t;
}

Teuchos::RCP<const Teuchos::ParameterList> BoundaryCondition::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<condition name>"));
  params::set_choice(*pl, "Type", "Clamped",
                     "Clamped: positions and directors fixed; Simply Supported: positions fixed, directors free "
                     "(math.md §10.1)",
                     {"Clamped", "Simply Supported"});
  pl->set("Node Set", "x_min", "Name of a node set of the mesh");
  return pl;
}

BoundaryCondition BoundaryCondition::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                                     const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  BoundaryCondition bc;
  bc.name = name;
  bc.type = pl.get<std::string>("Type") == "Clamped" ? Type::Clamped : Type::SimplySupported;
  bc.node_set = pl.get<std::string>("Node Set");
  return bc;
}

Teuchos::RCP<const Teuchos::ParameterList> InitialVelocity::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<condition name>"));
  pl->set("Elements", "all", "Element set or block whose nodes get the velocity; 'all' for every element");
  Teuchos::Array<double> v(3, 0.0);
  pl->set("Velocity", v, "Initial velocity vector {vx, vy, vz} [length/time]");
  return pl;
}

InitialVelocity InitialVelocity::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                                 const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  InitialVelocity iv;
  iv.name = name;
  iv.elements = pl.get<std::string>("Elements");
  const auto v = pl.get<Teuchos::Array<double>>("Velocity");
  SHELLFRAC_INPUT_REQUIRE(v.size() == 3, ctx.file << ": '" << ctx.path << "->Velocity' must have 3 components, not "
                                                  << v.size());
  iv.velocity = {v[0], v[1], v[2]};
  return iv;
}

}  // namespace shellfrac::solver
