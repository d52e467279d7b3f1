#pragma once
/// \file symmetry_directors.hpp
/// The reference directors on symmetry planes (theory.md §10.1): a Symmetry condition holds the director in its
/// plane, so the reference director there must lie in it.
namespace shellfrac::mesh {
struct SerialMesh;
}
namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

struct Deck;

/// Puts the reference director of every DG copy that a Symmetry condition acts on into the condition's plane
/// (the component along the plane's normal removed, renormalized). On a curved mesh the averaged normal at a vertex
/// of the symmetry edge is tilted out of the plane by the discrete geometry (1e-3 on the Gmsh roof meshes), and the
/// condition would otherwise keep the director there at that tilt. A director more than `max_angle_degrees` out of
/// the plane is left as it is: there the plane is not a symmetry plane of the shell (a shell crossing it), and the
/// condition's reaction will show it. Returns the number of directors moved (this rank's owned and ghost copies).
long hold_reference_directors_in_symmetry_planes(const Deck& deck, const mesh::SerialMesh& mesh,
                                                 decomposition::DistributedMesh& dm, double max_angle_degrees = 5.0);

}  // namespace shellfrac::solver
