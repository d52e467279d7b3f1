#pragma once
/// \file contact_params.hpp
/// The deck's "Contact" sublist (docs/theory.md §12): rigid planar walls the shells bounce off, rigid bodies
/// (spheres and projectiles) that strike them, and the penalty scale of the contact law.
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/types.hpp"

namespace shellfrac::solver {

/// Coulomb friction of a contact (docs/theory.md §12.6): "Friction Coefficient" (mu_d, while sliding) and "Static
/// Friction Coefficient" (mu_s >= mu_d, the limit of sticking; by default mu_d), in "Contact" for the rigid walls and
/// bodies and in "Contact->Shells" for the shells.
struct FrictionParams {
  double dynamic_coefficient = 0;
  double static_coefficient = 0;
  bool enabled() const { return static_coefficient > 0; }
  /// Adds the two parameters to a sublist's valid parameters.
  static void add_valid_parameters(Teuchos::ParameterList& pl);
  /// Reads them from a validated sublist. InputError if mu_s < mu_d.
  static FrictionParams from_parameters(const Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Contact->Rigid Walls-><name>": the plane through Point with unit Normal, moving at a constant Velocity. The
/// shells are on the side the normal points to; the wall pushes back any point of a shell's offset surface
/// (mid-surface - h/2 along the normal) that passes behind it.
struct RigidWall {
  std::string name;
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 0, 1};    ///< unit (normalized from the input)
  Vec3 velocity{0, 0, 0};  ///< of the plane [length/time]; its tangential part drags the shells with friction
  /// The wall's point at time t: point + velocity t.
  Vec3 point_at(double t) const {
    return {point[0] + velocity[0] * t, point[1] + velocity[1] * t, point[2] + velocity[2] * t};
  }
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static RigidWall from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Contact->Rigid Bodies-><name>": a rigid, axisymmetric body (theory.md §12.4) that translates without
/// turning: a Sphere (centre Point, Radius), or a Cylinder of Radius whose nose of the chosen shape ends the
/// cylindrical part at Point and points along Axis (the body extends Length behind Point). With a Mass it is a
/// free body launched at Velocity, moved by the shells' contact forces; without one (Mass 0) it moves at the
/// constant Velocity whatever the forces.
struct RigidBody {
  enum class Shape { Sphere, Cylinder };
  enum class Nose { Hemispherical, Conical, Flat };
  std::string name;
  Shape shape = Shape::Sphere;
  Nose nose = Nose::Hemispherical;
  double radius = 0;
  double length = 0;      ///< of the cylindrical part, behind Point (Cylinder)
  double half_angle = 0;  ///< of a conical nose [rad] (Cylinder, Conical); the nose is radius / tan(half_angle) long
  Vec3 point{0, 0, 0};    ///< at t = 0: the sphere's centre, or the centre of the nose's base
  Vec3 axis{0, 0, 1};     ///< unit: the way the nose points (Cylinder)
  Vec3 velocity{0, 0, 0};
  double mass = 0;  ///< 0: the motion is prescribed (constant Velocity)
  bool free() const { return mass > 0; }
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static RigidBody from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Contact->Shells": contact between the shells themselves (docs/theory.md §12.5): every DG position node of a
/// listed block against the mid-surfaces of the other elements of the listed blocks, at the offset (h_A + h_B) / 2.
struct ShellContactParams {
  std::vector<std::string> blocks;  ///< the blocks in contact; {"all"}: every block; empty: no shell contact
  double penalty_scale = 0.01;      ///< s of a pair's stiffness s mu / dt^2 (theory.md §12.5)
  double search_margin = 0;         ///< of the candidate lists [length]; 0: the largest thickness in contact
  FrictionParams friction;          ///< between the shells
  bool enabled() const { return !blocks.empty(); }
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static ShellContactParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

/// "Contact": the walls and bodies, and the penalty k = Penalty Scale m / dt^2 of each DG node of mass m (docs/theory.md
/// §12.2: with the default safety factor the step stays stable, which the set-up checks).
struct ContactParams {
  double penalty_scale = 0.25;
  FrictionParams friction;  ///< between the shells and the walls and bodies
  std::vector<RigidWall> walls;
  std::vector<RigidBody> bodies;
  ShellContactParams shells;
  /// The sublist without its user-named walls (those are validated one by one, RigidWall::valid_parameters).
  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  /// The whole sublist, walls included. InputError for any problem.
  static ContactParams from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx);
};

}  // namespace shellfrac::solver
