#include "shellfrac/solver/input/contact_params.hpp"

#include <cmath>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {

Vec3 vec3(const Teuchos::ParameterList& pl, const char* name, const params::Context& ctx) {
  const auto v = params::fixed_array(pl, name, 3, ctx);
  return {v[0], v[1], v[2]};
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> RigidWall::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<wall name>"));
  pl->set("Point", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)), "A point of the plane {x, y, z} at t = 0");
  pl->set("Normal", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 1.0)),
          "Normal of the plane, pointing to the side the shells are on {nx, ny, nz} (normalized)");
  pl->set("Velocity", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, 0.0)),
          "Velocity of the plane {vx, vy, vz} [length/time] (constant; its tangential part does nothing)");
  return pl;
}

RigidWall RigidWall::from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  RigidWall w;
  w.name = name;
  w.point = vec3(pl, "Point", ctx);
  w.normal = vec3(pl, "Normal", ctx);
  w.velocity = vec3(pl, "Velocity", ctx);
  const double n = std::sqrt(w.normal[0] * w.normal[0] + w.normal[1] * w.normal[1] + w.normal[2] * w.normal[2]);
  SHELLFRAC_INPUT_REQUIRE(n > 0 && std::isfinite(n), ctx.file << ": '" << ctx.path << "->Normal' is zero");
  for (double& c : w.normal) c /= n;
  return w;
}

Teuchos::RCP<const Teuchos::ParameterList> ContactParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Contact"));
  pl->set("Penalty Scale", 0.25,
          "The contact stiffness of a DG node of mass m is Penalty Scale m / dt^2 (theory.md §12.2); at most "
          "4 (1 - S_f^2) with S_f = dt / the stable step, so that contact does not make the step unstable",
          params::positive_double());
  pl->sublist("Rigid Walls", false, "One sublist per planar rigid wall, named freely");
  return pl;
}

ContactParams ContactParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx) {
  params::validate(pl, *valid_parameters(), ctx);
  ContactParams c;
  c.penalty_scale = pl.get<double>("Penalty Scale");
  auto& walls = pl.sublist("Rigid Walls");
  for (auto it = walls.begin(); it != walls.end(); ++it) {
    const std::string& name = walls.name(it);
    SHELLFRAC_INPUT_REQUIRE(walls.entry(it).isList(), ctx.file << ": '" << ctx.path << "->Rigid Walls->" << name
                                                               << "' must be a sublist (Point, Normal, Velocity)");
    c.walls.push_back(RigidWall::from_parameters(name, walls.sublist(name), ctx / "Rigid Walls" / name));
  }
  return c;
}

}  // namespace shellfrac::solver
