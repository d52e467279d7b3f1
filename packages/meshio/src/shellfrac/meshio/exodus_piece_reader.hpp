#pragma once
/// \file exodus_piece_reader.hpp
/// An Exodus II shell mesh read in pieces by all ranks at once: no rank reads or holds more than its share
/// (docs/parallel.md, "Distributed set-up").
///
/// Of N elements and M nodes on P ranks, rank r reads
///  * the connectivity of the elements [r W, (r + 1) W), W = ceil(N / P), in file order (the numbering of
///    read_exodus_mesh), with their blocks;
///  * the coordinates of the nodes [r B, (r + 1) B), B = ceil(M / P), and sends each rank the coordinates of the
///    nodes its elements use;
///  * the r-th of P equal slices of every node, side and element set, and sends each entry to the rank that holds
///    its element, or that holds its node's coordinates (which passes it on with the coordinates).
/// The piece is the one mesh::element_range_piece gives of the whole mesh: the same values, bit for bit.
///
/// The file's element id map comes with the elements (ElementPiece::element_file_ids; dropped when it is the
/// identity). The file is checked as read_exodus_mesh checks it, with the same message for a file with one error
/// (a file with several may be refused for another of them first), with two differences: the
/// node id map is not read, so messages number nodes by their positions in the file and a bad node id map is not
/// seen; and a node no element uses is not checked.
#include <mpi.h>

#include <string>

#include "shellfrac/mesh/mesh_piece.hpp"

namespace shellfrac::meshio {

/// This rank's piece of the Exodus mesh `path` (see above); piece.source = outline.source = path. InputError on
/// every rank for what read_exodus_mesh refuses. Collective.
mesh::MeshPiece read_exodus_piece(const std::string& path, MPI_Comm comm);

}  // namespace shellfrac::meshio
