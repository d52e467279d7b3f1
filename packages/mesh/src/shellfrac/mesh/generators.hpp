#pragma once
/// \file generators.hpp
/// Built-in structured triangle meshes (TRI3; promote with promote_to_p2 for P2, which places the new
/// nodes on the exact surface recorded in mesh.surface). Each generator makes one element block
/// (id 1, name `block_name`), node sets and side sets for its boundary edges, and documents them below.
#include <string>

#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::mesh {

/// Diagonal pattern of a structured rectangle: each cell of the nx x ny grid is split into two right
/// triangles along the diagonal from (i,j) to (i+1,j+1) ("Right"), along (i+1,j)-(i,j+1) ("Left"), or
/// alternating like a chessboard ("Alternating"). The paper's 200 x 40 cantilever uses a structured right
/// triangular mesh (§6.4): "Right".
enum class DiagonalPattern { Right, Left, Alternating };

/// Rectangle [x0, x0+lx] x [y0, y0+ly] in the plane z = 0, nx x ny cells, 2 nx ny triangles.
/// Node sets / side sets: "x_min", "x_max", "y_min", "y_max" (edges at x = x0, x = x0+lx, y = y0, y = y0+ly),
/// plus node set "corners". Counter-clockwise triangles (normal +z).
SerialMesh make_rectangle(double lx, double ly, int nx, int ny, DiagonalPattern pattern = DiagonalPattern::Right,
                          double x0 = 0, double y0 = 0, const std::string& block_name = "shell");

/// Cylindrical panel: radius r, axial length l along x in [0, l], opening angle `angle` (radians) centred on
/// the +z axis: points (x, r sin(theta), r cos(theta)), theta in [-angle/2, angle/2]. n_axial x n_circ cells.
/// Sets: "x_min", "x_max" (the curved ends), "theta_min", "theta_max" (the straight edges). Normals point
/// outward (away from the axis). mesh.surface = the cylinder.
SerialMesh make_cylindrical_panel(double r, double l, double angle, int n_axial, int n_circ,
                                  DiagonalPattern pattern = DiagonalPattern::Right,
                                  const std::string& block_name = "shell");

/// Closed cylinder (tube): radius r, axis x in [0, l], n_axial x n_circ cells (n_circ >= 3), periodic in
/// theta (no seam: nodes at theta = 0 and 2 pi are the same). Sets: "x_min", "x_max". Outward normals.
SerialMesh make_cylinder(double r, double l, int n_axial, int n_circ, DiagonalPattern pattern = DiagonalPattern::Right,
                         const std::string& block_name = "shell");

/// Outward unit normal of the exact vertex normals averaged over elements (theory.md §1.5): for each mesh
/// vertex, the normalized sum over the elements that use it of the element's unit normal at that vertex
/// (P2 geometry if TRI6). Entries of non-vertex (mid-side) nodes are zero.
std::vector<Vec3> reference_vertex_normals(const SerialMesh& mesh);
/// One element's term of that sum: its unit normal at vertex a (0..2) from its node coordinates x[0..npe) (P2
/// geometry if TRI6). False for a zero Jacobian there.
bool vertex_normal_term(int nodes_per_element, const Vec3* x, int a, Vec3& term);
/// v / |v|, or v itself when it is zero (the last step of the average).
Vec3 unit_or_zero(const Vec3& v);

}  // namespace shellfrac::mesh
