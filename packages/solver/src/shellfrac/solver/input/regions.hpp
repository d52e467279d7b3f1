#pragma once
/// \file regions.hpp
/// Named regions of space ("Regions" sublist): a box, a sphere or a cylinder sector. A region's name can be used
/// wherever the deck names a set of the mesh: as an element set (the elements whose centroid lies inside), a node
/// set (the nodes inside) or a side set (the edges whose mid-side node lies inside). mesh_sets.hpp resolves them.
#include <string>
#include <vector>

#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/types.hpp"

namespace shellfrac::solver {

/// One entry of "Regions".
struct Region {
  enum class Shape { Box, Sphere, CylinderSector };
  std::string name;
  Shape shape = Shape::Box;
  Vec3 min{0, 0, 0}, max{0, 0, 0};      ///< Box: opposite corners
  Vec3 center{0, 0, 0};                  ///< Sphere: centre; Cylinder Sector: a point on the axis (the origin)
  double radius = 0;                     ///< Sphere
  Vec3 axis{0, 0, 1};                    ///< Cylinder Sector: unit axis
  Vec3 reference{1, 0, 0};               ///< Cylinder Sector: unit direction of angle 0, normal to the axis
  double angle_min = 0, angle_max = 360; ///< Cylinder Sector: angle range [degrees] about the axis from reference
  double axial_min = 0, axial_max = 0;   ///< Cylinder Sector: range of (x - origin) . axis
  double radius_min = 0, radius_max = 0; ///< Cylinder Sector: range of the distance from the axis
  /// Whether point p lies in the region (boundaries included, to a relative tolerance of 1e-9 of its size).
  bool contains(const Vec3& p) const;

  static Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();
  static Region from_parameters(const std::string& name, Teuchos::ParameterList& pl, const params::Context& ctx);
};

}  // namespace shellfrac::solver
