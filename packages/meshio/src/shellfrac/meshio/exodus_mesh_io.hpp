#pragma once
/// \file exodus_mesh_io.hpp
/// Exodus II shell meshes in and out (conforming, shared nodes; results files are in shellfrac/io).
/// Read: element blocks of type TRI3/TRI6/TRISHELL3/TRISHELL6 (also TRI, TRIANGLE, TRISHELL with 3 or 6
/// nodes); all blocks must have the same number of nodes per element. 2-D files get z = 0. Node sets,
/// side sets and element sets with their names (default "nodeset_<id>", "sideset_<id>", "elemset_<id>",
/// "block_<id>"). Side numbering: TRI*: sides 1,2,3 = edges 0,1,2; TRISHELL*: sides 3,4,5 = edges 0,1,2
/// (sides 1, 2 are the shell faces and are rejected in a side set). Elements are numbered in file order.
/// Write: TRISHELL3/TRISHELL6 blocks, 3-D coordinates, all sets with names; side sets as sides 3,4,5.
/// Errors: InputError naming the file (and block/set) for unreadable files, unsupported element types,
/// mixed orders, out-of-range ids.
#include <string>

#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::meshio {

/// Reads an Exodus II shell mesh; mesh.source = path.
mesh::SerialMesh read_exodus_mesh(const std::string& path);

/// Writes `mesh` as an Exodus II file (overwrites). Throws Error if the file cannot be written.
void write_exodus_mesh(const mesh::SerialMesh& mesh, const std::string& path);

/// Reads a mesh file by its extension: .msh -> Gmsh; .exo .e .g .gen .ex2 -> Exodus. Other extensions and
/// missing files are an InputError naming the file.
mesh::SerialMesh read_mesh_file(const std::string& path);

}  // namespace shellfrac::meshio
