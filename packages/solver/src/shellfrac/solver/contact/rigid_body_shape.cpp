#include "shellfrac/solver/contact/rigid_body_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shellfrac::solver {

namespace {

/// A point of the profile plane (a: along the axis, r: from the axis).
struct Point2 {
  double a, r;
};

/// The nearest point of the profile's boundary found so far, and the outward normal of the piece it lies on.
struct Nearest {
  double squared = std::numeric_limits<double>::infinity();
  Point2 q{0, 0}, piece_normal{0, 0};
  void consider(Point2 p, Point2 q_new, Point2 n) {
    const double da = p.a - q_new.a, dr = p.r - q_new.r, d2 = da * da + dr * dr;
    if (d2 < squared) squared = d2, q = q_new, piece_normal = n;
  }
  /// The segment from s to e, whose outward normal is n.
  void segment(Point2 p, Point2 s, Point2 e, Point2 n) {
    const double ea = e.a - s.a, er = e.r - s.r, len2 = ea * ea + er * er;
    const double u = std::clamp(((p.a - s.a) * ea + (p.r - s.r) * er) / len2, 0.0, 1.0);
    consider(p, {s.a + u * ea, s.r + u * er}, n);
  }
  /// The arc of radius R about the origin from the axis (R, 0) to (0, R): the points with a, r >= 0.
  void quarter_circle(Point2 p, double R) {
    const double rho = std::hypot(p.a, p.r);
    if (p.a < 0 || rho == 0) return;  // the nearest arc point is an end, which a segment covers
    const Point2 n{p.a / rho, p.r / rho};
    consider(p, {R * n.a, R * n.r}, n);
  }
};

/// Signed distance and outward normal in the profile plane (p.r >= 0).
void profile_distance(const RigidBody& b, Point2 p, double& distance, Point2& normal) {
  const double R = b.radius;
  Nearest n;
  bool inside = false;
  if (b.shape == RigidBody::Shape::Sphere) {
    const double rho = std::hypot(p.a, p.r);
    distance = rho - R;
    normal = rho > 0 ? Point2{p.a / rho, p.r / rho} : Point2{1, 0};
    return;
  } else {
    const double L = b.length;
    n.segment(p, {-L, 0}, {-L, R}, {-1, 0});  // the back face
    n.segment(p, {-L, R}, {0, R}, {0, 1});    // the side
    inside = p.a >= -L && p.r <= R && p.a <= 0;
    switch (b.nose) {
      case RigidBody::Nose::Flat:
        n.segment(p, {0, R}, {0, 0}, {1, 0});
        break;
      case RigidBody::Nose::Hemispherical:
        n.quarter_circle(p, R);
        inside = inside || (p.a > 0 && p.a * p.a + p.r * p.r < R * R);
        break;
      case RigidBody::Nose::Conical: {
        const double tip = R / std::tan(b.half_angle);  // the nose's length
        const double len = std::hypot(tip, R);
        n.segment(p, {0, R}, {tip, 0}, {R / len, tip / len});
        inside = inside || (p.a > 0 && p.a < tip && p.r < R * (1 - p.a / tip));
        break;
      }
    }
  }
  const double d = std::sqrt(n.squared);
  distance = inside ? -d : d;
  if (d > 1e-12 * R) {
    const double s = inside ? -1 : 1;  // from the surface point towards p outside, away from it inside
    normal = {s * (p.a - n.q.a) / d, s * (p.r - n.q.r) / d};
  } else {
    normal = n.piece_normal;
  }
}

}  // namespace

BoundingSphere bounding_sphere(const RigidBody& b) {
  if (b.shape == RigidBody::Shape::Sphere) return {0, b.radius};
  const double nose = b.nose == RigidBody::Nose::Hemispherical ? b.radius
                      : b.nose == RigidBody::Nose::Conical     ? b.radius / std::tan(b.half_angle)
                                                               : 0.0;
  const double half = 0.5 * (nose + b.length);  // the body spans a = -length .. nose along its axis
  return {0.5 * (nose - b.length), std::hypot(half, b.radius)};
}

SurfaceDistance surface_distance(const RigidBody& b, const Vec3& point, const Vec3& x) {
  const Vec3 axis = b.shape == RigidBody::Shape::Sphere ? Vec3{0, 0, 1} : b.axis;
  const Vec3 d{x[0] - point[0], x[1] - point[1], x[2] - point[2]};
  const double a = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
  Vec3 radial{d[0] - a * axis[0], d[1] - a * axis[1], d[2] - a * axis[2]};
  const double r = std::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
  if (r > 0) {
    for (double& c : radial) c /= r;
  } else {  // on the axis: any direction normal to it (the normal's radial part is 0 there, or the point is inside)
    const Vec3 e = std::abs(axis[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const double ea = e[0] * axis[0] + e[1] * axis[1] + e[2] * axis[2];
    radial = {e[0] - ea * axis[0], e[1] - ea * axis[1], e[2] - ea * axis[2]};
    const double len = std::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
    for (double& c : radial) c /= len;
  }
  SurfaceDistance out;
  Point2 n{0, 0};
  profile_distance(b, {a, r}, out.distance, n);
  for (int c = 0; c < 3; ++c) out.normal[c] = n.a * axis[c] + n.r * radial[c];
  return out;
}

}  // namespace shellfrac::solver
