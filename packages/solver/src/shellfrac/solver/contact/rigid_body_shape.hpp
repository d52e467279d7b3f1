#pragma once
/// \file rigid_body_shape.hpp
/// The surface of a rigid body (input/contact_params.hpp RigidBody; docs/theory.md §12.4) as a signed distance:
/// how far a point is outside the body (negative inside) and the outward normal at the nearest surface point.
/// Every shape is axisymmetric and convex, so the distance is computed in the plane of the axis and the point:
/// (a, r) with a the axial coordinate from Point (positive towards the nose) and r the distance from the axis.
/// The profile there is made of straight pieces (the back face, the side, a flat or conical nose) and, for a
/// sphere or a hemispherical nose, a circular arc.
#include "shellfrac/core/types.hpp"
#include "shellfrac/solver/input/contact_params.hpp"

namespace shellfrac::solver {

struct SurfaceDistance {
  double distance = 0;  ///< signed: > 0 outside the body, < 0 inside
  Vec3 normal{0, 0, 1};  ///< unit outward normal of the body at its surface point nearest to the point
};

/// The signed distance of x from body b whose Point is at `point` (it translates without turning).
SurfaceDistance surface_distance(const RigidBody& b, const Vec3& point, const Vec3& x);

/// A sphere that holds body b: its centre is Point + offset * axis, and every point of the body is within radius of it
/// (a point farther than radius + h/2 from the centre is not in contact: no distance to compute).
struct BoundingSphere {
  double offset = 0, radius = 0;
};
BoundingSphere bounding_sphere(const RigidBody& b);

}  // namespace shellfrac::solver
