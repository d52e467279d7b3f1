#pragma once
/// \file contact_params.hpp
/// The deck's "Contact" sublist (docs/theory.md §12): rigid planar walls the shells bounce off, and the penalty
/// scale of the contact law.
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/types.hpp"

namespace shellfrac::solver {

/// "Contact->Rigid Walls-><name>": the plane through Point with unit Normal, moving at a constant Velocity. The
/// shells are on the side the normal points to; the wall pushes back any point of a shell's offset surface
/// (mid-surface - h/2 along the normal) that passes behind it.
struct RigidWall {
  std::string name;
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 0, 1};    ///< unit (normalized from the input)
  Vec3 velocity{0, 0, 0};  ///< of the plane [length/time]; its tangential part does nothing (frictionless)
  /// The wall's point at time t: point + velocity t.
  Vec3 point_at(double t) const {
    return {point[0] + velocity[0] * t, point[1] + velocity[1] * t, point[2] + velocity[2] * t};
  }
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static RigidWall from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Contact": the walls, and the penalty k = Penalty Scale m / dt^2 of each DG node of mass m (docs/theory.md
/// §12.2: with the default safety factor the step stays stable, which the set-up checks).
struct ContactParams {
  double penalty_scale = 0.25;
  std::vector<RigidWall> walls;
  /// The sublist without its user-named walls (those are validated one by one, RigidWall::valid_parameters).
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// The whole sublist, walls included. InputError for any problem.
  static ContactParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

}  // namespace shellfrac::solver
