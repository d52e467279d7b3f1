#pragma once
/// \file results_conventions.hpp
/// What the writer and the readers of DG results files agree on (docs/output.md): the suffixes of a nodal
/// vector's components and the Exodus side number of a shell edge. Internal to io.
namespace shellfrac::io {

/// Suffixes of the scalar components of a nodal vector.
constexpr const char* component_suffix[3] = {"_x", "_y", "_z"};

/// Exodus side number of local edge 0 of a shell triangle (sides 1 and 2 are its faces; edge k is side k + 3).
constexpr int first_edge_side = 3;

}  // namespace shellfrac::io
