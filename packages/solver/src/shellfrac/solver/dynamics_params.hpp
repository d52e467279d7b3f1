#pragma once
/// \file dynamics_params.hpp
/// Deck sublists of the explicit shell dynamics (paper §4; math.md §5-8, §10): discretization constants,
/// time integration, boundary conditions and initial conditions, as plain structs.
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/types.hpp"

namespace shellfrac::solver {

/// "Discretization": DG stabilization constants (paper eq. 42: beta_x = c_x E h, beta_T = c_T E h^3/12).
struct DiscretizationParams {
  double cx = 3.0, cT = 3.0;
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static DiscretizationParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Time Integration": explicit central differences (Newmark gamma = 1/2), math.md §7-8.
struct TimeParams {
  double end_time = 0.0;         ///< 0: no time stepping, the run writes the reference state only
  double safety_factor = 0.8;    ///< S_f applied to the element-by-element stable estimate
  double time_step = 0.0;        ///< fixed Delta t; 0 = S_f x stable estimate
  bool force_time_step = false;  ///< allow a fixed Delta t above the stable estimate
  double rotary_inertia_scale = 1.0;  ///< s_I >= 1 scales the rotary inertia rho h^3/12 (mass scaling)
  double output_interval = 0.0;  ///< time between Exodus outputs; 0 = first and last step only
  int history_interval = 1;      ///< steps between history rows
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static TimeParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// One entry of "Boundary Conditions": a condition on every DG copy of the nodes of a node set (math.md §10.1).
struct BoundaryCondition {
  enum class Type { Clamped, SimplySupported };
  std::string name;
  Type type = Type::Clamped;
  std::string node_set;
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static BoundaryCondition from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                           const params::Context& ctx);
};

/// One entry of "Initial Conditions": a velocity on the nodes of an element set or block (math.md §10.2).
struct InitialVelocity {
  std::string name;
  std::string elements;  ///< element set or block name; "all" for every element
  Vec3 velocity{0, 0, 0};
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static InitialVelocity from_parameters(const std::string& name, Teuchos::ParameterList& pl,
                                         const params::Context& ctx);
};

}  // namespace shellfrac::solver
