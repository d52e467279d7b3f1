#pragma once
/// \file results_compare.hpp
/// Comparing two DG results data sets within tolerances (shellfrac_exocompare, the tests).
#include <cstddef>
#include <string>
#include <vector>

#include "shellfrac/io/results_reader.hpp"

namespace shellfrac::io {

/// Comparison tolerances: |a - b| <= max(abs, rel * max(|a|, |b|)) per variable; "coordinates" for coords.
struct CompareTolerances {
  double default_abs = 0.0, default_rel = 0.0;
  struct Entry {
    std::string name;
    double abs = 0, rel = 0;
  };
  std::vector<Entry> per_variable;
  /// Parses a tolerance file: lines "<variable|default|coordinates> [absolute A] [relative R]", '#' comments.
  static CompareTolerances from_file(const std::string& path);
};

/// Compares two data sets by element global id: same elements, blocks, times, variable names; coordinates and
/// values within tolerance. Returns a list of human-readable differences (empty = equal), at most max_report.
std::vector<std::string> compare_results(const ExodusResults& a, const ExodusResults& b,
                                         const CompareTolerances& tol, std::size_t max_report = 20);

}  // namespace shellfrac::io
