#pragma once
/// \file mass_scaling.hpp
/// What selective mass scaling (Time Integration->Target Time Step, docs/theory.md §8.1) added to a model.
#include "shellfrac/core/types.hpp"

namespace shellfrac::solver {

/// Global values (the same on every rank).
struct MassScaling {
  GlobalId elements = 0;          ///< elements whose density was scaled
  double physical_mass = 0;       ///< total mass of the mesh before scaling
  double added_mass = 0;          ///< mass added by the scaling
  double max_factor = 1;          ///< largest density factor
  GlobalId max_element = -1;      ///< the element with it (smallest id among equals)
  Vec3 max_centroid{0, 0, 0};     ///< its vertex centroid
};

}  // namespace shellfrac::solver
