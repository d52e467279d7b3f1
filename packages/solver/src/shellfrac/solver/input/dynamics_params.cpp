#include "shellfrac/solver/input/dynamics_params.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_Tuple.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {
/// The 3 components of a fixed_array as a vector.
Vec3 to_vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }
}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> DiscretizationParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Discretization"));
  pl->set("Position Penalty", 3.0, "c_x in beta_x = c_x E h (paper eq. 42; 3 in every example of the paper)",
          params::positive_double());
  pl->set("Director Penalty", 3.0, "c_T in beta_T = c_T E h^3/12 (paper eq. 42)", params::positive_double());
  params::set_choice(*pl, "Membrane Strain", "Stabilized P0",
                     "Stabilized P0: the element mean of the membrane strains plus a fraction of the remainder "
                     "(Membrane Stabilization); P1 Projection: their L2 projection on linear fields in each element; "
                     "Point Values: the strains at the area points as they are (theory.md §5.4)",
                     {"Stabilized P0", "P1 Projection", "Point Values"});
  pl->set("Membrane Stabilization", default_membrane_stabilization,
          "Stabilized P0: kappa, the fraction of the energy of the membrane strains' deviation from their element "
          "mean that a curved element keeps (theory.md eq. 5.4c; a flat one keeps all of it); small values free "
          "spurious membrane modes",
          params::double_range(1e-6, 1.0));
  params::set_choice(*pl, "Shear Strain", "P1 Projection",
                     "P1 Projection: the transverse shear strains through their L2 projection on linear fields in "
                     "each element; Point Values: at the area points as they are (theory.md §5.4)",
                     {"P1 Projection", "Point Values"});
  return pl;
}

double DiscretizationParams::membrane_remainder(const double X[6][3], double thickness) const {
  if (strains.membrane != disc::StrainSpace::p0) return 0;
  return disc::mean_membrane_remainder(disc::largest_edge_sagitta(X) / thickness, membrane_stabilization);
}

DiscretizationParams DiscretizationParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  const std::string membrane = pl.get<std::string>("Membrane Strain");
  disc::StrainTreatment strains;
  strains.membrane = membrane == "Stabilized P0"   ? disc::StrainSpace::p0
                     : membrane == "P1 Projection" ? disc::StrainSpace::p1
                                                   : disc::StrainSpace::point_values;
  strains.shear = pl.get<std::string>("Shear Strain") == "P1 Projection" ? disc::StrainSpace::p1
                                                                          : disc::StrainSpace::point_values;
  const bool stabilized = strains.membrane == disc::StrainSpace::p0;
  params::refuse_inapplicable(
      pl, *valid_parameters(), "'Membrane Strain' = '" + membrane + "'",
      [&](const std::string& name) { return name != "Membrane Stabilization" || stabilized; }, ctx);
  return {pl.get<double>("Position Penalty"), pl.get<double>("Director Penalty"), strains,
          pl.get<double>("Membrane Stabilization")};
}

Teuchos::RCP<const Teuchos::ParameterList> TimeParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Time Integration"));
  pl->set("End Time", 0.0, "Final time [time]; 0 writes the reference state without time stepping",
          params::non_negative_double());
  pl->set("Safety Factor", 0.8, "S_f: the time step is S_f times the stable estimate (theory.md §8; keep <= 0.9)",
          params::double_range(0.0, 1.0, true, false));
  pl->set("Time Step", 0.0, "Fixed time step [time]; 0 = Safety Factor x stable estimate", params::non_negative_double());
  pl->set("Force Time Step", false, "Run with a fixed Time Step even if it exceeds the stable estimate");
  pl->set("Target Time Step", 0.0,
          "Selective mass scaling (theory.md §8.1): the density of every element whose stable step (times the "
          "Safety Factor) is below this step is multiplied by the factor that brings it there, and the run uses "
          "this step; the added mass is reported. 0 = no mass scaling. Not together with Time Step",
          params::non_negative_double());
  pl->set("Maximum Added Mass Fraction", 0.05,
          "Target Time Step: the run is refused if the added mass exceeds this fraction of the total mass",
          params::non_negative_double());
  pl->set("Force Mass Scaling", false, "Target Time Step: accept any added mass");
  pl->set("Rotary Inertia Scale", 1.0, "s_I >= 1 multiplies the rotary inertia rho h^3/12 (raises the stable step of "
                                       "thin shells; changes the dynamics; reported when used)",
          params::double_range(1.0, 1e6));
  pl->set("Maximum Steps", 1e8,
          "The run (also --check) is refused if it would take more steps than this: a guard against absurd time "
          "steps from wrong units or tiny elements; raise it for a longer run",
          params::positive_double());
  pl->set("Output Interval", 0.0, "Time between Exodus outputs [time]; 0 = first and last step only",
          params::non_negative_double());
  pl->set("History Interval", 1, "Steps between rows of the history CSV", params::int_range(1, 1 << 30));
  pl->set("History Time Interval", 0.0,
          "Time between rows of the history CSV [time]: a row at the first step at or past each multiple (and the "
          "first and last steps); 0 = by History Interval (steps). Give one of the two",
          params::non_negative_double());
  pl->set("Exact Output Times", false,
          "Shorten the step that would pass an output time (a multiple of Output Interval, or End Time) so that it "
          "ends on it: frames at the exact output times and a last frame at End Time. The step sequence then depends "
          "on the output settings: a restart with another Output Interval does not continue bitwise like the "
          "uninterrupted run. false: frames at the step nearest each output time, a step sequence independent of the "
          "output");
  pl->set("Static Relaxation", false,
          "Find the static equilibrium by dynamic relaxation: all free velocities are set to zero at every peak of the "
          "kinetic energy (the removed energy is booked as damping), and the run stops, before End Time, once the "
          "loads and prescribed motions have reached their final values and the out-of-balance force of the free "
          "components is below Relaxation Tolerance times the force norm (loads, reactions, support couples); "
          "the run reports the residual. End Time is then the limit");
  pl->set("Relaxation Tolerance", 1e-6, "Static Relaxation: relative residual at which the run stops",
          params::double_range(0.0, 1.0, true, true));
  pl->set("Mass Damping", 0.0, "alpha of a mass-proportional damping force alpha m v [1/time], for dynamic relaxation "
                               "to static states; 0 = undamped",
          params::non_negative_double());
  return pl;
}

TimeParams TimeParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  TimeParams t;
  t.end_time = pl.get<double>("End Time");
  t.safety_factor = pl.get<double>("Safety Factor");
  t.time_step = pl.get<double>("Time Step");
  t.force_time_step = pl.get<bool>("Force Time Step");
  t.target_time_step = pl.get<double>("Target Time Step");
  t.max_added_mass_fraction = pl.get<double>("Maximum Added Mass Fraction");
  t.force_mass_scaling = pl.get<bool>("Force Mass Scaling");
  SHELLFRAC_INPUT_REQUIRE(t.target_time_step == 0 || t.time_step == 0,
                          ctx.file << ": '" << ctx.path << "': give either a Time Step or a Target Time Step (mass "
                                   << "scaling), not both");
  t.rotary_inertia_scale = pl.get<double>("Rotary Inertia Scale");
  t.maximum_steps = pl.get<double>("Maximum Steps");
  t.output_interval = pl.get<double>("Output Interval");
  t.history_interval = pl.get<int>("History Interval");
  t.history_time_interval = pl.get<double>("History Time Interval");
  SHELLFRAC_INPUT_REQUIRE(t.history_time_interval == 0 || t.history_interval == 1,
                          ctx.file << ": '" << ctx.path << "': give either a History Interval (steps) or a History "
                                   << "Time Interval, not both");
  t.exact_output_times = pl.get<bool>("Exact Output Times");
  t.mass_damping = pl.get<double>("Mass Damping");
  t.static_relaxation = pl.get<bool>("Static Relaxation");
  t.relaxation_tolerance = pl.get<double>("Relaxation Tolerance");
  return t;
}

Teuchos::RCP<const Teuchos::ParameterList> FractureParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Fracture"));
  pl->set("Edges", "all", "Interior edges that may break: 'all', or the name of a side set of the mesh (e.g. a "
                          "ligament); both sides' materials also need a Cohesive Strength > 0");
  pl->set("Alpha 1", 1.0, "alpha1: weight of the sliding jump in the effective opening (paper eq. 20)",
          params::positive_double());
  pl->set("Alpha 2", 1.0, "alpha2: weight of the normal director jump h theta_N (paper eq. 20)",
          params::positive_double());
  pl->set("Alpha 3", 1.0, "alpha3: weight of the tangential director jump h |theta_S| (paper eq. 20)",
          params::positive_double());
  pl->set("Activation Opening", 0.05,
          "delta0 / delta_f: the effective opening at which an activated edge's cohesive law starts, as a fraction of "
          "its softening length 2 Gamma / sigma_c; the law starts there carrying the edge's traction (continuous in "
          "time), so its initial secant S0/delta0 is resolved by the time step (theory.md §9.6). 0 = the rigid law "
          "of the paper, whose balance error grows with the opening rate",
          params::double_range(0.0, 1.0));
  pl->set("Seed", 0, "Key of the per-edge strength draws of materials with a Strength Distribution other than "
                     "Constant (docs/theory.md §9.8): each edge's strength is a hash of the seed and the edge's id, the "
                     "same on any rank or thread count and after a restart; another seed gives another, equally "
                     "likely pattern of flaws",
          params::int_range(0, std::numeric_limits<int>::max()));
  pl->set("Crack Face Contact", false,
          "Experimental (docs/theory.md §9.9): the faces of activated edges resist interpenetration with the stiffness "
          "of the intact penalty, a closing edge is not counted as opening and compression does not nucleate. Off by "
          "default: it is stable where faces close in a few places (a crack closed by a bending wave) but not yet in "
          "widespread fragmentation at high strain rates, where the compressed, partly broken mesh sheds single "
          "elements that tumble and blow up");
  return pl;
}

FractureParams FractureParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  FractureParams f;
  f.edges = pl.get<std::string>("Edges");
  f.alpha1 = pl.get<double>("Alpha 1");
  f.alpha2 = pl.get<double>("Alpha 2");
  f.alpha3 = pl.get<double>("Alpha 3");
  f.activation_opening = pl.get<double>("Activation Opening");
  f.seed = pl.get<int>("Seed");
  f.crack_face_contact = pl.get<bool>("Crack Face Contact");
  return f;
}

Teuchos::RCP<const Teuchos::ParameterList> BoundaryCondition::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<condition name>"));
  params::set_choice(*pl, "Type", "Clamped",
                     "Clamped: positions and directors fixed; Simply Supported: positions fixed, directors free; "
                     "Symmetry: no motion along Normal and the director stays in the plane; Rigid Diaphragm: no "
                     "motion in the plane normal to Normal (the motion along Normal is free) and no rotation of the "
                     "director about Normal (it may tilt out of the plane), the end support of a roof or a tube; "
                     "Prescribed Velocity: "
                     "velocity ramped smoothly to Velocity over Ramp Time, directors clamped; Prescribed Rotation: "
                     "directors rotated about Axis by an angle ramped smoothly to Angle over Ramp Time, positions free "
                     "(an end moment without drilling DOFs; theory.md §10.1-10.2)",
                     {"Clamped", "Simply Supported", "Symmetry", "Rigid Diaphragm", "Prescribed Velocity",
                      "Prescribed Rotation"});
  pl->set("Node Set", "x_min", "Name of a node set of the mesh, or 'all' (every node; with Elements: every node of "
                               "those elements)");
  pl->set("Elements", "all",
          "Element set or block: the condition acts only on the DG copies of the Node Set's nodes that belong to these "
          "elements; 'all' = every copy. A clamping fixture modelled as part of the mesh (its elements held, the "
          "edges at its border breakable): Node Set = all, Elements = the fixture's block");
  pl->set("Normal", Teuchos::Array<double>(Teuchos::tuple<double>(1.0, 0.0, 0.0)), "Symmetry, Rigid Diaphragm: normal of the plane {nx, ny, nz}");
  pl->set("Velocity", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Prescribed Velocity: final velocity {vx, vy, vz} [length/time]");
  pl->set("Components", "xyz",
          "Prescribed Velocity: the velocity components that are prescribed, a subset of 'xyz' (e.g. 'z': the nodes "
          "move freely along x and y, like a clamp that does not resist in-plane motion); the directors stay clamped");
  pl->set("Ramp Time", 0.0, "Prescribed Velocity/Rotation: duration of the cosine ramp from 0 to Velocity/Angle [time]",
          params::non_negative_double());
  pl->set("Axis", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 1.0, 0.0)),
          "Prescribed Rotation: rotation axis {ax, ay, az} (right-hand rule)");
  pl->set("Angle", 0.0, "Prescribed Rotation: final rotation angle [rad]", params::double_range(-100.0, 100.0));
  return pl;
}

BoundaryCondition BoundaryCondition::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                                     const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  BoundaryCondition bc;
  bc.name = name;
  const std::string type = pl.get<std::string>("Type");
  bc.type = type == "Clamped"            ? Type::Clamped
            : type == "Simply Supported" ? Type::SimplySupported
            : type == "Symmetry"         ? Type::Symmetry
            : type == "Rigid Diaphragm"  ? Type::RigidDiaphragm
            : type == "Prescribed Velocity" ? Type::PrescribedVelocity
                                            : Type::PrescribedRotation;
  params::refuse_inapplicable(pl, *valid_parameters(), "a '" + type + "' boundary condition",
                              [&](const std::string& p) {
                                if (p == "Type" || p == "Node Set" || p == "Elements") return true;
                                switch (bc.type) {
                                  case Type::Symmetry:
                                  case Type::RigidDiaphragm: return p == "Normal";
                                  case Type::PrescribedVelocity:
                                    return p == "Velocity" || p == "Components" || p == "Ramp Time";
                                  case Type::PrescribedRotation: return p == "Axis" || p == "Angle" || p == "Ramp Time";
                                  default: return false;
                                }
                              },
                              ctx);
  bc.node_set = pl.get<std::string>("Node Set");
  bc.elements = pl.get<std::string>("Elements");
  const auto vec3 = [&](const char* name) { return to_vec3(params::fixed_array(pl, name, 3, ctx)); };
  bc.normal = vec3("Normal");
  const double n = std::sqrt(bc.normal[0] * bc.normal[0] + bc.normal[1] * bc.normal[1] + bc.normal[2] * bc.normal[2]);
  SHELLFRAC_INPUT_REQUIRE((bc.type != Type::Symmetry && bc.type != Type::RigidDiaphragm) || n > 0,
                          ctx.file << ": '" << ctx.path << "->Normal' is zero");
  if (n > 0)
    for (double& c : bc.normal) c /= n;
  bc.velocity = vec3("Velocity");
  const std::string comps = pl.get<std::string>("Components");
  SHELLFRAC_INPUT_REQUIRE(!comps.empty() && comps.find_first_not_of("xyz") == std::string::npos,
                          ctx.file << ": '" << ctx.path << "->Components' is '" << comps
                                   << "'; it must be a non-empty subset of 'xyz'");
  for (int c = 0; c < 3; ++c) bc.components[c] = comps.find(char('x' + c)) != std::string::npos;
  bc.ramp_time = pl.get<double>("Ramp Time");
  bc.axis = vec3("Axis");
  const double na = std::sqrt(bc.axis[0] * bc.axis[0] + bc.axis[1] * bc.axis[1] + bc.axis[2] * bc.axis[2]);
  SHELLFRAC_INPUT_REQUIRE(bc.type != Type::PrescribedRotation || na > 0, ctx.file << ": '" << ctx.path << "->Axis' is zero");
  if (na > 0)
    for (double& c : bc.axis) c /= na;
  bc.angle = pl.get<double>("Angle");
  return bc;
}

Teuchos::RCP<const Teuchos::ParameterList> InitialVelocity::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<condition name>"));
  pl->set("Elements", "all", "Element set or block whose nodes get the velocity; 'all' for every element");
  Teuchos::Array<double> v(3, 0.0);
  pl->set("Velocity", v, "Initial velocity vector {vx, vy, vz} [length/time]");
  pl->set("Angular Velocity", v, "Rigid spin {wx, wy, wz} [1/time] added to Velocity: v = Velocity + w x (X - Center) "
                                  "and director rates w x t");
  pl->set("Center", v, "Centre of the spin {x, y, z} [length]");
  pl->set("Normal Velocity", 0.0, "Speed along the reference normal (the director t0; outward for the generators) "
                                  "added to the above [length/time]");
  return pl;
}

InitialVelocity InitialVelocity::from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                                 const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  InitialVelocity iv;
  iv.name = name;
  iv.elements = pl.get<std::string>("Elements");
  iv.velocity = to_vec3(params::fixed_array(pl, "Velocity", 3, ctx));
  iv.angular_velocity = to_vec3(params::fixed_array(pl, "Angular Velocity", 3, ctx));
  iv.center = to_vec3(params::fixed_array(pl, "Center", 3, ctx));
  iv.normal_velocity = pl.get<double>("Normal Velocity");
  return iv;
}

namespace {
/// Linear interpolation in a table, constant outside.
double table_value(const std::vector<double>& times, const std::vector<double>& values, double t) {
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const auto i = std::upper_bound(times.begin(), times.end(), t) - times.begin();
  const double w = (t - times[i - 1]) / (times[i] - times[i - 1]);
  return (1 - w) * values[i - 1] + w * values[i];
}
}  // namespace

double Load::pressure_at(double t) const {
  switch (function) {
    case Function::Constant: return pressure;
    case Function::Exponential: return pressure * std::exp(-t / decay_time) * (1 - t / decay_time);
    case Function::Table: return table_value(times, values, t);
  }
  return 0;
}

double Load::factor_at(double t) const {
  switch (function) {
    case Function::Constant: return 1.0;
    case Function::Exponential: return std::exp(-t / decay_time) * (1 - t / decay_time);
    case Function::Table: return table_value(times, values, t);
  }
  return 0;
}

Teuchos::RCP<const Teuchos::ParameterList> Load::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<load name>"));
  params::set_choice(*pl, "Type", "Pressure",
                     "Pressure: follower pressure normal to the current mid-surface (along G1 x G2 of each element; "
                     "theory.md §10.3); Gravity: uniform body acceleration on the lumped masses; Nodal Force: a force "
                     "at each mesh node of Node Set, shared equally by the node's DG copies; Line Load: a force per "
                     "unit length on the edges of Side Set, integrated along the quadratic edges; Edge Moment: a "
                     "couple per unit length on the directors of the edges of Side Set (its drilling part, along "
                     "the director, does no work)",
                     {"Pressure", "Gravity", "Nodal Force", "Line Load", "Edge Moment"});
  pl->set("Elements", "all", "Pressure, Gravity: element set or block carrying the load; 'all' for every element");
  pl->set("Node Set", "", "Nodal Force: node set whose mesh nodes carry the force");
  pl->set("Side Set", "", "Line Load, Edge Moment: side set whose edges carry the load");
  params::set_choice(*pl, "Function", "Constant",
                     "Time function: Constant; Exponential exp(-t/t_p)(1 - t/t_p) (paper §6.5); Table. A Pressure is "
                     "p0 times it (Table: the values are pressures); the other loads are their vector times it",
                     {"Constant", "Exponential", "Table"});
  pl->set("Pressure", 0.0, "p0 [force/length^2]");
  pl->set("Decay Time", 1.0, "t_p of the Exponential function [time]", params::positive_double());
  pl->set("Times", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 1.0)), "Table: increasing times [time]");
  pl->set("Values", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0)),
          "Table: pressures (Pressure) or factors (other loads) at Times");
  pl->set("Acceleration", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)), "Gravity: body acceleration {gx, gy, gz}");
  pl->set("Force", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Nodal Force: force per mesh node {fx, fy, fz} [force]");
  pl->set("Force Per Length", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Line Load: force per unit reference length {fx, fy, fz} [force/length]");
  pl->set("Follower", false, "Line Load: the force turns with the edge (its components in the edge's reference frame "
                             "of tangent, outward co-normal and director are kept); false: a fixed direction");
  pl->set("Moment Per Length", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Edge Moment: couple per unit reference length {mx, my, mz} [force length/length]");
  return pl;
}

Load Load::from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  Load l;
  l.name = name;
  const std::string type = pl.get<std::string>("Type");
  l.type = type == "Gravity"       ? Type::Gravity
           : type == "Nodal Force" ? Type::NodalForce
           : type == "Line Load"   ? Type::LineLoad
           : type == "Edge Moment" ? Type::EdgeMoment
                                   : Type::Pressure;
  const std::string f = pl.get<std::string>("Function");
  l.function = f == "Exponential" ? Function::Exponential : f == "Table" ? Function::Table : Function::Constant;
  params::refuse_inapplicable(pl, *valid_parameters(), "a '" + type + "' load with Function '" + f + "'",
                              [&](const std::string& p) {
                                if (p == "Type" || p == "Function") return true;
                                if (p == "Decay Time") return l.function == Function::Exponential;
                                if (p == "Times" || p == "Values") return l.function == Function::Table;
                                switch (l.type) {
                                  case Type::Pressure:  // a Table gives the pressures themselves
                                    return p == "Elements" || (p == "Pressure" && l.function != Function::Table);
                                  case Type::Gravity: return p == "Elements" || p == "Acceleration";
                                  case Type::NodalForce: return p == "Node Set" || p == "Force";
                                  case Type::LineLoad: return p == "Side Set" || p == "Force Per Length" || p == "Follower";
                                  default: return p == "Side Set" || p == "Moment Per Length";
                                }
                              },
                              ctx);
  l.elements = pl.get<std::string>("Elements");
  l.node_set = pl.get<std::string>("Node Set");
  l.side_set = pl.get<std::string>("Side Set");
  SHELLFRAC_INPUT_REQUIRE(l.type != Type::NodalForce || !l.node_set.empty(),
                          ctx.file << ": '" << ctx.path << "': a Nodal Force needs a 'Node Set'");
  SHELLFRAC_INPUT_REQUIRE((l.type != Type::LineLoad && l.type != Type::EdgeMoment) || !l.side_set.empty(),
                          ctx.file << ": '" << ctx.path << "': a " << type << " needs a 'Side Set'");
  l.pressure = pl.get<double>("Pressure");
  l.decay_time = pl.get<double>("Decay Time");
  const auto times = pl.get<Teuchos::Array<double>>("Times"), values = pl.get<Teuchos::Array<double>>("Values");
  l.times.assign(times.begin(), times.end());
  l.values.assign(values.begin(), values.end());
  if (l.function == Function::Table) {
    SHELLFRAC_INPUT_REQUIRE(!l.times.empty() && l.times.size() == l.values.size(),
                            ctx.file << ": '" << ctx.path << "': Times and Values must have the same, non-zero length");
    for (std::size_t i = 1; i < l.times.size(); ++i)
      SHELLFRAC_INPUT_REQUIRE(l.times[i] > l.times[i - 1], ctx.file << ": '" << ctx.path << "->Times' must increase");
  }
  const auto vec3 = [&](const char* what) { return to_vec3(params::fixed_array(pl, what, 3, ctx)); };
  l.acceleration = vec3("Acceleration");
  l.force = vec3(l.type == Type::LineLoad ? "Force Per Length" : "Force");
  l.moment = vec3("Moment Per Length");
  l.follower = pl.get<bool>("Follower");
  return l;
}

}  // namespace shellfrac::solver
