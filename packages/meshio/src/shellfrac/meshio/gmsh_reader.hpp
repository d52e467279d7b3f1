#pragma once
/// \file gmsh_reader.hpp
/// Reads Gmsh .msh files, formats 2.2 and 4.1, ASCII and binary (either endianness marker checked).
/// Mapping (docs/mesh_input.md):
///  * 3-node and 6-node triangles (Gmsh types 2, 9) are the shell elements; all must have the same order.
///  * Physical surfaces (dim 2) -> element blocks (name from $PhysicalNames, else "block_<tag>"; id = tag).
///    Triangles with no physical group go to block "block_1" (only possible when the file has no groups or
///    was saved with SaveAll). A triangle in several physical surfaces: block = lowest tag, and it is also
///    put in an element set per extra surface group.
///  * Physical curves (dim 1) -> a side set (line elements matched to triangle edges by their end vertices)
///    and a node set (all nodes of the lines, mid-side nodes included), both with the group's name and tag.
///  * Physical points (dim 0) -> node sets.
///  * Nodes are renumbered 0.. in increasing Gmsh tag order; unused nodes are dropped. Triangles are numbered
///    in increasing element tag order. The tags are kept for messages (mesh.element_ids, mesh.node_ids) when
///    they are not the positions 1..n.
///  * Gmsh numbers physical groups per dimension, so a curve and a point may share a tag: the later set gets
///    the next free id (and "_<id>" appended to a clashing name). Unnamed groups are "curve_<tag>",
///    "point_<tag>", "block_<tag>".
///  * A physical line on an interior edge is listed in the side set for both adjacent triangles; a line3 must
///    match the triangle edge including its mid-side node.
///  * Points outside any physical group are ignored (SaveAll writes construction points such as arc centres).
/// Errors (InputError naming the file and, where it applies, the line or element tag): unreadable file,
/// unsupported version, quadrilaterals or volume elements, a line element that is not an edge of any
/// triangle, truncated or malformed sections, unknown node tags.
#include <string>

#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::meshio {

/// Reads a Gmsh mesh file; mesh.source = path.
mesh::SerialMesh read_gmsh(const std::string& path);

}  // namespace shellfrac::meshio
