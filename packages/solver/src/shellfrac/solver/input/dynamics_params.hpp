#pragma once
/// \file dynamics_params.hpp
/// Deck sublists of the explicit shell dynamics (paper §4; theory.md §5-8, §10): discretization constants,
/// time integration, boundary conditions and initial conditions, as plain structs.
#include <array>
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/types.hpp"
#include "shellfrac/disc/strain_treatment.hpp"

namespace shellfrac::solver {

/// "Discretization": DG stabilization constants (paper eq. 42: beta_x = c_x E h, beta_T = c_T E h^3/12) and the
/// treatment of the membrane and shear strains (theory.md §5.4).
struct DiscretizationParams {
  double cx = 3.0, cT = 3.0;
  disc::StrainTreatment strains = {disc::StrainSpace::p0, disc::StrainSpace::p1};  ///< the deck's defaults
  double membrane_stabilization = default_membrane_stabilization;  ///< kappa (theory.md eq. 5.4c)
  static constexpr double default_membrane_stabilization = 0.1;
  /// The membrane remainder s of an element (theory.md eqs. 5.4a, 5.4c) of reference nodes X and thickness h.
  double membrane_remainder(const double X[6][3], double thickness) const;
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static DiscretizationParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Time Integration": explicit central differences (Newmark gamma = 1/2), theory.md §7-8.
struct TimeParams {
  double end_time = 0.0;         ///< 0: no time stepping, the run writes the reference state only
  double safety_factor = 0.8;    ///< S_f applied to the element-by-element stable estimate
  double time_step = 0.0;        ///< fixed Delta t; 0 = S_f x stable estimate
  bool force_time_step = false;  ///< allow a fixed Delta t above the stable estimate
  double target_time_step = 0.0;  ///< selective mass scaling to this Delta t (theory.md §8.1); 0 = none
  double max_added_mass_fraction = 0.05;  ///< refuse mass scaling that adds more (unless forced)
  bool force_mass_scaling = false;        ///< accept any added mass
  double rotary_inertia_scale = 1.0;  ///< s_I >= 1 scales the rotary inertia rho h^3/12 (mass scaling)
  double maximum_steps = 1e8;    ///< refuse a run planned longer (absurd time steps)
  double output_interval = 0.0;  ///< time between Exodus outputs; 0 = first and last step only
  bool exact_output_times = false;  ///< steps shortened to end on the output times and on End Time
  int history_interval = 1;      ///< steps between history rows
  double history_time_interval = 0;  ///< time between history rows (0: by history_interval)
  double mass_damping = 0.0;     ///< alpha of the damping force alpha m v (dynamic relaxation); 0 = none
  bool static_relaxation = false;  ///< find the static state: kinetic-energy peak resets, stop on the residual
  double relaxation_tolerance = 1e-6;  ///< stop when |residual| <= tolerance x |load| (static relaxation)
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static TimeParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Fracture": where edges may break and the weights of the effective opening (paper eq. 20, theory.md §9).
/// An interior edge can break when the materials of both sides have a Cohesive Strength > 0 and the edge
/// is in `edges` ("all", or the name of a side set of the mesh).
struct FractureParams {
  std::string edges = "all";
  double alpha1 = 1, alpha2 = 1, alpha3 = 1;
  double activation_opening = 0.05;  ///< delta0 / delta_f (docs/theory.md §9.6)
  long seed = 0;                      ///< key of the edges' strength draws (Strength Distribution, theory.md §9.8)
  bool crack_face_contact = false;    ///< activated edges' faces resist interpenetration (theory.md §9.9)
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static FractureParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// One entry of "Boundary Conditions": a condition on every DG copy of the nodes of a node set (theory.md §10.1,
/// §10.2).
struct BoundaryCondition {
  enum class Type { Clamped, SimplySupported, Symmetry, RigidDiaphragm, PrescribedVelocity, PrescribedRotation };
  std::string name;
  Type type = Type::Clamped;
  std::string node_set;
  std::string elements = "all";  ///< only the DG copies of the nodes that belong to these elements (set, block or all)
  Vec3 normal{0, 0, 1};    ///< Symmetry, Rigid Diaphragm: unit normal of the plane
  Vec3 velocity{0, 0, 0};  ///< Prescribed Velocity: final velocity V0 (directors clamped on the set)
  std::array<bool, 3> components{true, true, true};  ///< Prescribed Velocity: which of x, y, z are prescribed
  double ramp_time = 0;    ///< Prescribed Velocity/Rotation: cosine ramp duration t_r (0 = applied at once)
  Vec3 axis{0, 1, 0};      ///< Prescribed Rotation: unit rotation axis
  double angle = 0;        ///< Prescribed Rotation: final angle [rad] reached at the end of the ramp
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static BoundaryCondition from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                           const params::Context& ctx);
};

/// One entry of "Initial Conditions": a velocity on the nodes of an element set or block (theory.md §10.2).
struct InitialVelocity {
  std::string name;
  std::string elements;  ///< element set or block name; "all" for every element
  Vec3 velocity{0, 0, 0};
  Vec3 angular_velocity{0, 0, 0};  ///< rigid spin omega: v = velocity + omega x (X - center), tdot = omega x t
  Vec3 center{0, 0, 0};
  double normal_velocity = 0;  ///< speed along the reference director (outward normal), added to the above
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static InitialVelocity from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                         const params::Context& ctx);
};

/// One entry of "Loads" (theory.md §10.3). Every load follows its time function: a Pressure's magnitude is p(t)
/// (Table values are pressures), the other loads are their vector times the factor f(t) (Constant 1,
/// Exponential exp(-t/t_p)(1 - t/t_p), Table values are factors).
struct Load {
  enum class Type { Pressure, Gravity, NodalForce, LineLoad, EdgeMoment };
  enum class Function { Constant, Exponential, Table };
  std::string name;
  Type type = Type::Pressure;
  std::string elements;         ///< Pressure, Gravity: element set or block name, or "all"
  std::string node_set;         ///< Nodal Force: node set
  std::string side_set;         ///< Line Load, Edge Moment: side set
  Function function = Function::Constant;
  double pressure = 0;          ///< p0 [force/length^2]; positive along the element normal G1 x G2
  double decay_time = 0;        ///< t_p of p(t) = p0 exp(-t/t_p)(1 - t/t_p) (paper §6.5)
  std::vector<double> times, values;  ///< Table: p(t) or f(t) by linear interpolation, constant outside
  Vec3 acceleration{0, 0, 0};   ///< Gravity: body acceleration [length/time^2]
  Vec3 force{0, 0, 0};          ///< Nodal Force: force per mesh node; Line Load: force per unit reference length
  bool follower = false;        ///< Line Load: the force turns with the edge's frame (tangent, co-normal, director)
  Vec3 moment{0, 0, 0};         ///< Edge Moment: couple per unit reference length
  /// p(t) for a Pressure load.
  double pressure_at(double t) const;
  /// f(t) for the other loads.
  double factor_at(double t) const;
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static Load from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

}  // namespace shellfrac::solver
