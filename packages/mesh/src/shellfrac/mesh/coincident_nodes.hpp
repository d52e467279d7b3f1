#pragma once
/// \file coincident_nodes.hpp
/// Separate mesh nodes at one point. The elements around them are not connected there: a seam or a pre-cracked
/// line if the user meant it, otherwise duplicate nodes left by a mesher, which split the shell silently.
#include "shellfrac/core/types.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::mesh {

struct CoincidentNodes {
  GlobalId count = 0;     ///< nodes of elements at exactly the position of another node of elements
  Vec3 example{0, 0, 0};  ///< one such position (the smallest in x, then y, then z)
};

/// The nodes used by elements whose coordinates equal those of another such node. Nodes no element uses are
/// ignored.
CoincidentNodes coincident_nodes(const SerialMesh& mesh);

}  // namespace shellfrac::mesh
