#pragma once
/// \file checkpoint.hpp
/// Checkpoint files (HDF5): the whole state of a run as tables keyed by rank-independent global ids, plus
/// scalars and strings, so that a run can be restarted on any number of ranks.
///
/// Layout of a file: group /tables/<name> with datasets "ids" (int64, sorted, unique) and "values" (double,
/// rows x width); group /scalars with one double attribute per scalar; group /strings with one variable-length
/// string attribute per string; root attribute "format" = "shellfrac checkpoint 2" and "checksum", a 128-bit
/// digest (core/digest.hpp) of every scalar, string and table. The file uses the HDF5 1.10 format (checksummed
/// superblock and object headers) and each table chunk carries a Fletcher32 checksum: a damaged file is refused
/// on reading, never restarted from.
///
/// Writing gathers every table to rank 0 (memory O(global state) on rank 0, like the mesh; documented in
/// docs/parallel.md), which writes `<path>.tmp` and renames it to `<path>`: a crash while writing never
/// destroys the previous checkpoint; a failed write is an OutputError naming the file. Reading: rank 0 reads,
/// verifies the checksums and broadcasts.
#include <mpi.h>

#include <map>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::io {

/// One table: `width` values per id, rows in the order of `ids`.
struct CheckpointTable {
  int width = 0;
  std::vector<GlobalId> ids;
  std::vector<double> values;  ///< ids.size() * width
  /// Row of `id`, or nullptr if absent (ids must be sorted; after read_checkpoint they are).
  const double* row(GlobalId id) const;
};

/// The contents of a checkpoint.
struct CheckpointData {
  std::map<std::string, double> scalars;
  std::map<std::string, std::string> strings;
  std::map<std::string, CheckpointTable> tables;
};

/// Writes `local` (each rank's own rows; scalars and strings from rank 0) atomically to `path`. Rows of all ranks
/// are merged and sorted by id; an id given by two ranks must carry the same values. Throws OutputError naming
/// the file on failure (on every rank). Collective.
void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm);

/// Reads a checkpoint on rank 0 and broadcasts it. Throws InputError naming the file if it cannot be read or is
/// not a shellfrac checkpoint of this format, or fails a checksum. Collective.
CheckpointData read_checkpoint(const std::string& path, MPI_Comm comm);

}  // namespace shellfrac::io
