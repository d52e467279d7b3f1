#pragma once
/// \file contact_penalty.hpp
/// The contact penalty of every rigid partner (walls, bodies; docs/theory.md §12.2): k = Penalty Scale m / dt^2 per
/// DG node of mass m, and the set-up's check that it leaves the step stable.
#include <string>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

/// InputError naming `file` if a node in contact would make the step unstable: (2 S_f)^2 + Penalty Scale >= 4 with
/// S_f = dt / stable_dt.
inline void check_contact_penalty(double penalty_scale, double dt, double stable_dt, const std::string& file,
                                  const char* parameter = "Contact->Penalty Scale") {
  const double sf = dt / stable_dt;
  SHELLFRAC_INPUT_REQUIRE(4 * sf * sf + penalty_scale < 4,
                          file << ": '" << parameter << "' = " << penalty_scale << " with the time step " << dt
                               << " (" << sf << " of the stable step) makes the step unstable: a node in contact "
                               << "needs (2 S_f)^2 + Penalty Scale < 4 (theory.md §12.2); lower the scale or the "
                               << "'Time Integration->Safety Factor'");
}

}  // namespace shellfrac::solver
