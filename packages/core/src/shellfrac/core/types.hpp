#pragma once
/// \file types.hpp
/// Index and scalar types used everywhere in shellfrac. Light header: no Tpetra, no Kokkos.
/// The Tpetra-facing aliases (map_type, ...) live in shellfrac/mesh/element_maps.hpp, which checks
/// that GlobalId matches Tpetra::Map<>::global_ordinal_type.
#include <array>
#include <cstdint>

namespace shellfrac {

/// Global (mesh-wide, rank-independent) id of an element, node, edge or interface. 0-based.
using GlobalId = std::int64_t;
/// Local (per-rank) index.
using LocalId = std::int32_t;
/// A point or vector in R^3.
using Vec3 = std::array<double, 3>;

constexpr int num_vertices_tri = 3;  ///< vertices (and edges) of a triangle
constexpr int num_nodes_tri3 = 3;    ///< linear triangle
constexpr int num_nodes_tri6 = 6;    ///< quadratic triangle: vertices 1,2,3 then mid-sides 4(1-2), 5(2-3), 6(3-1)

/// Local edge k of a triangle runs from vertex edge_vertices[k][0] to edge_vertices[k][1] (counter-clockwise);
/// its mid-side node (P2) is node 3 + k.  (theory.md §1.2; same as Exodus TRI6 and Gmsh triangle6 ordering)
constexpr int edge_vertex[3][2] = {{0, 1}, {1, 2}, {2, 0}};

}  // namespace shellfrac
