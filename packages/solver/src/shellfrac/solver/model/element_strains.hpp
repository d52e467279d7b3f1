#pragma once
/// \file element_strains.hpp
/// The strains of one owned element in the current state, with its current lifted edges (the element kernel's
/// kinematics, docs/theory.md §5.4): for the element output fields and the energy check of nucleation.
#include "shellfrac/core/types.hpp"
#include "shellfrac/disc/dg_element.hpp"

namespace shellfrac::solver {

struct ShellModel;
struct ShellState;

/// Strains at one area point, with the point's weight w_q j0_q (for diagnostics and energies).
struct PointStrains {
  double weight;
  double eps[3], gam[2], rho[3];
};

/// Strains at the area points of owned element le of `model` in state `s` (the ghosts must be current).
void element_strains(const ShellModel& model, const ShellState& s, LocalId le, PointStrains out[disc::num_area_points]);

}  // namespace shellfrac::solver
