#pragma once
/// \file nemesis_piece_reader.hpp
/// A mesh decomposed beforehand into one Exodus II file per rank (Nemesis I, as SEACAS nem_slice + nem_spread
/// write it: BASE.P.r, r zero-padded to the digits of P), each rank reading only its own file
/// (docs/parallel.md, "Distributed set-up").
///
/// Rank r reads BASE.P.r: its elements with their blocks, nodes, coordinates and set entries, numbered as in the
/// mesh that was decomposed (the files' element and node number maps give the positions in it), and the global
/// counts. The piece is the one mesh::piece_of_elements gives of that mesh for the same elements, bit for bit,
/// except that nem_spread does not carry element sets: a mesh read this way has none (name blocks or regions
/// instead). Checks and messages as for read_exodus_piece; in addition the files must be decomposed for the number
/// of ranks of the run, one rank per file, and every rank's file must list the blocks and sets of the mesh in the
/// same order.
#include <mpi.h>

#include <string>

#include "shellfrac/mesh/mesh_piece.hpp"

namespace shellfrac::meshio {

/// The name of rank r's file of a mesh decomposed for P ranks: BASE.P.r, r with as many digits as P (nem_spread).
std::string nemesis_file_name(const std::string& base, int P, int r);

/// This rank's piece of the decomposed mesh BASE (see above); piece.source and outline.source are BASE. InputError
/// on every rank for a missing file, a decomposition for another number of ranks, or what read_exodus_mesh
/// refuses. Collective.
mesh::MeshPiece read_nemesis_piece(const std::string& base, MPI_Comm comm);

}  // namespace shellfrac::meshio
