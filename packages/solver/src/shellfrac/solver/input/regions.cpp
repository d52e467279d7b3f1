#include "shellfrac/solver/input/regions.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_Tuple.hpp>
#include <cmath>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Teuchos::Array<double> triple(double x, double y, double z) {
  return Teuchos::Array<double>(Teuchos::tuple<double>(x, y, z));
}
}  // namespace

bool Region::contains(const Vec3& p) const {
  switch (shape) {
    case Shape::Box: {
      double size = 0;
      for (int c = 0; c < 3; ++c) size = std::max(size, max[c] - min[c]);
      const double tol = 1e-9 * size;
      for (int c = 0; c < 3; ++c)
        if (p[c] < min[c] - tol || p[c] > max[c] + tol) return false;
      return true;
    }
    case Shape::Sphere: {
      const Vec3 d{p[0] - center[0], p[1] - center[1], p[2] - center[2]};
      return std::sqrt(dot(d, d)) <= radius * (1 + 1e-9);
    }
    case Shape::CylinderSector: {
      const Vec3 d{p[0] - center[0], p[1] - center[1], p[2] - center[2]};
      const double a = dot(d, axis);
      const Vec3 r{d[0] - a * axis[0], d[1] - a * axis[1], d[2] - a * axis[2]};
      const double rho = std::sqrt(dot(r, r));
      const double tol = 1e-9 * std::max({axial_max - axial_min, radius_max, 1e-300});
      if (a < axial_min - tol || a > axial_max + tol || rho < radius_min - tol || rho > radius_max + tol) return false;
      if (rho <= tol) return angle_max - angle_min >= 360;  // on the axis: only a full sector holds it
      const Vec3 b{axis[1] * reference[2] - axis[2] * reference[1], axis[2] * reference[0] - axis[0] * reference[2],
                   axis[0] * reference[1] - axis[1] * reference[0]};  // angle 90 degrees
      double theta = std::atan2(dot(r, b), dot(r, reference)) * 180 / M_PI;  // in (-180, 180]
      while (theta < angle_min - 1e-9) theta += 360;
      return theta <= angle_max + 1e-9;
    }
  }
  return false;
}

Teuchos::RCP<const Teuchos::ParameterList> Region::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<region name>"));
  params::set_choice(*pl, "Shape", "Box",
                     "Box: Min <= x <= Max; Sphere: |x - Center| <= Radius; Cylinder Sector: the points at axial "
                     "position (x - Center) . Axis in Axial Range, distance from the axis in Radius Range and angle "
                     "about Axis from Reference Direction in Angle Range. An element belongs to the region when its "
                     "centroid does, a node when it lies in it, an edge when its mid-side node does",
                     {"Box", "Sphere", "Cylinder Sector"});
  pl->set("Min", triple(0, 0, 0), "Box: lower corner {x, y, z} [length]");
  pl->set("Max", triple(0, 0, 0), "Box: upper corner {x, y, z} [length]");
  pl->set("Center", triple(0, 0, 0), "Sphere: centre; Cylinder Sector: a point on the axis {x, y, z} [length]");
  pl->set("Radius", 0.0, "Sphere: radius [length]", params::non_negative_double());
  pl->set("Axis", triple(0, 0, 1), "Cylinder Sector: axis direction {ax, ay, az}");
  pl->set("Reference Direction", triple(1, 0, 0),
          "Cylinder Sector: the direction of angle 0 {x, y, z} (its part normal to the axis is used)");
  pl->set("Angle Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 360.0)),
          "Cylinder Sector: {from, to} [degrees], counter-clockwise about Axis from Reference Direction; to - from "
          "in (0, 360]");
  pl->set("Axial Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0)),
          "Cylinder Sector: {from, to} of (x - Center) . Axis [length]");
  pl->set("Radius Range", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0)),
          "Cylinder Sector: {from, to} of the distance from the axis [length]");
  return pl;
}

Region Region::from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  Region r;
  r.name = name;
  const std::string shape = pl.get<std::string>("Shape");
  r.shape = shape == "Sphere" ? Shape::Sphere : shape == "Cylinder Sector" ? Shape::CylinderSector : Shape::Box;
  const auto array = [&](const char* what, std::size_t n) { return params::fixed_array(pl, what, n, ctx); };
  const auto vec = [&](const char* what) {
    const auto v = array(what, 3);
    return Vec3{v[0], v[1], v[2]};
  };
  r.min = vec("Min"), r.max = vec("Max"), r.center = vec("Center"), r.radius = pl.get<double>("Radius");
  const auto angles = array("Angle Range", 2), axial = array("Axial Range", 2), radii = array("Radius Range", 2);
  r.angle_min = angles[0], r.angle_max = angles[1], r.axial_min = axial[0], r.axial_max = axial[1];
  r.radius_min = radii[0], r.radius_max = radii[1];
  const std::string where = ctx.file + ": '" + ctx.path + "'";
  if (r.shape == Shape::Box)
    for (int c = 0; c < 3; ++c) SHELLFRAC_INPUT_REQUIRE(r.min[c] <= r.max[c], where << ": Min must not exceed Max");
  if (r.shape == Shape::Sphere) SHELLFRAC_INPUT_REQUIRE(r.radius > 0, where << ": a Sphere needs a Radius > 0");
  if (r.shape == Shape::CylinderSector) {
    Vec3 a = vec("Axis"), e = vec("Reference Direction");
    const double na = std::sqrt(dot(a, a));
    SHELLFRAC_INPUT_REQUIRE(na > 0, where << ": Axis is zero");
    for (double& c : a) c /= na;
    const double ea = dot(e, a);
    for (int c = 0; c < 3; ++c) e[c] -= ea * a[c];
    const double ne = std::sqrt(dot(e, e));
    SHELLFRAC_INPUT_REQUIRE(ne > 1e-12, where << ": Reference Direction must not be parallel to Axis");
    for (double& c : e) c /= ne;
    r.axis = a, r.reference = e;
    SHELLFRAC_INPUT_REQUIRE(r.angle_max > r.angle_min && r.angle_max - r.angle_min <= 360,
                            where << ": Angle Range {from, to} needs from < to <= from + 360");
    SHELLFRAC_INPUT_REQUIRE(r.axial_max >= r.axial_min, where << ": Axial Range {from, to} needs from <= to");
    SHELLFRAC_INPUT_REQUIRE(r.radius_min >= 0 && r.radius_max > r.radius_min,
                            where << ": Radius Range {from, to} needs 0 <= from < to");
  }
  return r;
}

}  // namespace shellfrac::solver
