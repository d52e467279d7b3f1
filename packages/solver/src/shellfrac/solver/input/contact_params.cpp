#include "shellfrac/solver/input/contact_params.hpp"

#include <cmath>
#include <set>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {

Vec3 vec3(const Teuchos::ParameterList& pl, const char* name, const params::Context& ctx) {
  const auto v = params::fixed_array(pl, name, 3, ctx);
  return {v[0], v[1], v[2]};
}

/// The vector parameter `name`, normalized; InputError if it is zero.
Vec3 unit_vec3(const Teuchos::ParameterList& pl, const char* name, const params::Context& ctx) {
  Vec3 v = vec3(pl, name, ctx);
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  SHELLFRAC_INPUT_REQUIRE(n > 0 && std::isfinite(n), ctx.file << ": '" << ctx.path << "->" << name << "' is zero");
  for (double& c : v) c /= n;
  return v;
}

/// The named sublists of `list` (one per wall or body), each read by `read`.
template <class T>
std::vector<T> named_entries(Teuchos::ParameterList& list, const char* what, const params::Context& ctx) {
  std::vector<T> out;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    SHELLFRAC_INPUT_REQUIRE(list.entry(it).isList(), ctx.file << ": '" << ctx.path << "->" << name
                                                              << "' must be a sublist (" << what << ")");
    out.push_back(T::from_parameters(name, list.sublist(name), ctx / name));
  }
  return out;
}

}  // namespace

void FrictionParams::add_valid_parameters(Teuchos::ParameterList& pl) {
  pl.set("Friction Coefficient", 0.0,
         "Coulomb coefficient mu_d of sliding contacts (theory.md §12.6); 0: frictionless", params::non_negative_double());
  pl.set("Static Friction Coefficient", -1.0,
         "Coulomb coefficient mu_s >= mu_d up to which a contact sticks (theory.md §12.6); -1: the Friction "
         "Coefficient");
}

FrictionParams FrictionParams::from_parameters(const Teuchos::ParameterList& pl, const params::Context& ctx) {
  FrictionParams f;
  f.dynamic_coefficient = pl.get<double>("Friction Coefficient");
  const double mu_s = pl.get<double>("Static Friction Coefficient");
  f.static_coefficient = mu_s == -1 ? f.dynamic_coefficient : mu_s;
  SHELLFRAC_INPUT_REQUIRE(std::isfinite(f.static_coefficient) && f.static_coefficient >= f.dynamic_coefficient,
                          ctx.file << ": '" << ctx.path << "->Static Friction Coefficient' = " << mu_s
                                   << " is below the 'Friction Coefficient' " << f.dynamic_coefficient
                                   << " (static friction is at least the sliding one; -1: the same)");
  return f;
}

Teuchos::RCP<const Teuchos::ParameterList> RigidWall::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<wall name>"));
  pl->set("Point", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)), "A point of the plane {x, y, z} at t = 0");
  pl->set("Normal", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 1.0)),
          "Normal of the plane, pointing to the side the shells are on {nx, ny, nz} (normalized)");
  pl->set("Velocity", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Velocity of the plane {vx, vy, vz} [length/time] (constant; its tangential part drags the shells only "
          "with friction)");
  return pl;
}

RigidWall RigidWall::from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  RigidWall w;
  w.name = name;
  w.point = vec3(pl, "Point", ctx);
  w.normal = vec3(pl, "Normal", ctx);
  w.velocity = vec3(pl, "Velocity", ctx);
  w.normal = unit_vec3(pl, "Normal", ctx);
  return w;
}

Teuchos::RCP<const Teuchos::ParameterList> RigidBody::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<body name>"));
  params::set_choice(*pl, "Shape", "Sphere",
                     "Sphere (centre Point, Radius), or Cylinder (Radius, Length, Axis, Nose): a projectile whose nose "
                     "ends its cylindrical part at Point and points along Axis",
                     {"Sphere", "Cylinder"});
  pl->set("Radius", 0.01, "Radius of the sphere or of the cylinder [length]", params::positive_double());
  pl->set("Point", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "At t = 0: the sphere's centre, or the centre of the cylinder's nose base {x, y, z}");
  pl->set("Axis", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, -1.0)),
          "Cylinder: the way its nose points {ax, ay, az} (normalized)");
  pl->set("Length", 0.05, "Cylinder: length of the cylindrical part behind Point [length]", params::positive_double());
  params::set_choice(*pl, "Nose", "Hemispherical",
                     "Cylinder: the nose's shape (a hemisphere of the cylinder's radius, a cone of Nose Half-Angle, or "
                     "flat)",
                     {"Hemispherical", "Conical", "Flat"});
  pl->set("Nose Half-Angle", 30.0, "Cylinder, Conical nose: the cone's half-angle at its tip [degrees]",
          params::double_range(1, 89));
  pl->set("Velocity", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Velocity {vx, vy, vz} [length/time]: the initial one of a free body (Mass > 0), else the prescribed, "
          "constant one");
  pl->set("Mass", 0.0,
          "Mass of a free rigid body [mass], moved by the contact forces; 0: the motion is prescribed (Velocity)",
          params::non_negative_double());
  return pl;
}

RigidBody RigidBody::from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  RigidBody b;
  b.name = name;
  b.shape = pl.get<std::string>("Shape") == "Sphere" ? Shape::Sphere : Shape::Cylinder;
  const std::string nose = pl.get<std::string>("Nose");
  b.nose = nose == "Hemispherical" ? Nose::Hemispherical : nose == "Conical" ? Nose::Conical : Nose::Flat;
  params::refuse_inapplicable(pl, *valid_parameters(), "a '" + pl.get<std::string>("Shape") + "' rigid body",
                              [&](const std::string& p) {
                                if (p == "Axis" || p == "Length" || p == "Nose") return b.shape == Shape::Cylinder;
                                if (p == "Nose Half-Angle") return b.shape == Shape::Cylinder && b.nose == Nose::Conical;
                                return true;
                              },
                              ctx);
  b.radius = pl.get<double>("Radius");
  b.length = pl.get<double>("Length");
  b.half_angle = pl.get<double>("Nose Half-Angle") * std::acos(-1.0) / 180;
  b.point = vec3(pl, "Point", ctx);
  b.axis = unit_vec3(pl, "Axis", ctx);
  b.velocity = vec3(pl, "Velocity", ctx);
  b.mass = pl.get<double>("Mass");
  return b;
}

Teuchos::RCP<const Teuchos::ParameterList> ShellContactParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Shells"));
  pl->set("Blocks", Teuchos::Array<std::string>(),
          "The blocks whose shells contact each other (and themselves): block names, or {all}; empty: none");
  pl->set("Penalty Scale", 0.01,
          "A node of mass m_A has the stiffness Penalty Scale m_A mbar_F / ((mbar_A + mbar_F) dt^2) against another "
          "element (mbar: the two elements' mean node masses; theory.md §12.5)",
          params::positive_double());
  pl->set("Search Margin", 0.0,
          "Margin of the contact candidate lists [length]; they are rebuilt when a node has moved half of it. "
          "0: the largest thickness of the blocks in contact",
          params::non_negative_double());
  FrictionParams::add_valid_parameters(*pl);
  return pl;
}

ShellContactParams ShellContactParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  ShellContactParams c;
  for (const auto& b : pl.get<Teuchos::Array<std::string>>("Blocks")) c.blocks.push_back(b);
  c.penalty_scale = pl.get<double>("Penalty Scale");
  c.search_margin = pl.get<double>("Search Margin");
  c.friction = FrictionParams::from_parameters(pl, ctx);
  return c;
}

Teuchos::RCP<const Teuchos::ParameterList> ContactParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Contact"));
  pl->set("Penalty Scale", 0.25,
          "The contact stiffness of a DG node of mass m is Penalty Scale m / dt^2 (theory.md §12.2); at most "
          "4 (1 - S_f^2) with S_f = dt / the stable step, so that contact does not make the step unstable",
          params::positive_double());
  FrictionParams::add_valid_parameters(*pl);
  pl->sublist("Rigid Walls", false, "One sublist per planar rigid wall, named freely");
  pl->sublist("Rigid Bodies", false, "One sublist per rigid body (sphere or projectile), named freely");
  pl->set("Shells", *ShellContactParams::valid_parameters(), "Contact between the shells (theory.md §12.5)");
  return pl;
}

ContactParams ContactParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  ContactParams c;
  c.penalty_scale = pl.get<double>("Penalty Scale");
  c.friction = FrictionParams::from_parameters(pl, ctx);
  c.walls = named_entries<RigidWall>(pl.sublist("Rigid Walls"), "Point, Normal, Velocity", ctx / "Rigid Walls");
  c.bodies = named_entries<RigidBody>(pl.sublist("Rigid Bodies"), "Shape, Radius, Point, ...", ctx / "Rigid Bodies");
  c.shells = ShellContactParams::from_parameters(pl.sublist("Shells"), ctx / "Shells");
  std::set<std::string> names;
  for (const auto& w : c.walls) names.insert(w.name);
  for (const auto& b : c.bodies)
    SHELLFRAC_INPUT_REQUIRE(names.insert(b.name).second, ctx.file << ": '" << ctx.path << "->Rigid Bodies->" << b.name
                                                                  << "' has the name of a rigid wall; name them "
                                                                     "apart (they name history columns)");
  return c;
}

}  // namespace shellfrac::solver
