#pragma once
/// \file checkpoint.hpp
/// Checkpoint files (HDF5): the whole state of a run as tables keyed by rank-independent global ids, plus
/// scalars and strings, so that a run can be restarted on any number of ranks.
///
/// Layout of a file: group /tables/<name> with datasets "ids" (int64, sorted, unique) and "values" (double,
/// rows x width); group /scalars with one double attribute per scalar; group /strings with one variable-length
/// string attribute per string; root attribute "format" = "shellfrac checkpoint 6" and "checksum", a 128-bit
/// digest (core/digest.hpp) of the scalars, strings and each table's name, width and size, combined with the sum
/// over every row of a digest of (file row, id, values): the same whatever the number of ranks that wrote it. The
/// file uses the HDF5 1.10 format (checksummed superblock and object headers) and each table chunk carries a
/// Fletcher32 checksum: a damaged file is refused on reading, never restarted from.
///
/// Parallel: every rank opens the file (HDF5's MPI-IO driver) and writes or reads its own rows collectively.
/// Writing, rank r writes the rows of its P-th of a table's id range, sent to it by the ranks that hold them, in
/// rounds of about a block of rows; reading, it reads its P-th of the file's rows a block at a time and answers
/// the other ranks' requests for rows in it. Memory: a rank holds its own rows and a round's; rank 0 holds no more
/// (docs/parallel.md). Writing goes to `<path>.tmp`, renamed to `<path>`: a crash while writing never destroys the
/// previous checkpoint; a failed write on any rank is an OutputError naming the file, on every rank.
#include <mpi.h>

#include <functional>
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

/// A table read from what it was made from when the checkpoint is written, a block of rows at a time: valid while
/// that lives and is unchanged.
struct TableSource {
  int width = 0;
  /// The ids of the rows, sorted and unique (made when the table is written).
  std::function<std::vector<GlobalId>()> ids;
  /// The values of rows first .. first + count - 1 (in ids order) into out: count * width values.
  std::function<void(std::size_t first, std::size_t count, double* out)> rows;
};

/// The contents of a checkpoint.
struct CheckpointData {
  std::map<std::string, double> scalars;
  std::map<std::string, std::string> strings;
  std::map<std::string, CheckpointTable> tables;
  /// Tables never copied whole: written a block at a time from their sources (names distinct from those of
  /// `tables`); built() makes a snapshot.
  std::map<std::string, TableSource> table_sources;
};

/// `data` with every table source built into a table (a copy that outlives what the sources read).
CheckpointData built(CheckpointData data);

/// Writes `local` (each rank's own rows; scalars and strings from rank 0) atomically to `path`. Rows of all ranks
/// are merged and sorted by id; of an id given by two ranks, the lower rank's row is written. Throws OutputError
/// naming the file on failure (on every rank). Collective.
void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm);

/// Reads a checkpoint: every rank gets the scalars and strings, and of each table the rows of the ids it lists in
/// `wanted` (those the file has; sorted by id), or the whole table if `wanted` does not name it.
/// Throws InputError naming the file if it cannot be read or is not a shellfrac checkpoint of this format, or
/// fails a checksum. Collective.
CheckpointData read_checkpoint(const std::string& path, MPI_Comm comm,
                               const std::map<std::string, std::vector<GlobalId>>& wanted = {});

/// The rows a rank asks for in table `name` (sorted or not), or null for the whole table.
using WantedRows = std::function<const std::vector<GlobalId>*(const std::string& name)>;

/// The same without keeping the tables: `header` gets the scalars and strings first (no tables; it may throw on
/// every rank alike to refuse the file), then `rows` gets this rank's rows of each table (name order) a round at a
/// time, sorted by id within a call (one call per round, possibly without rows; the rounds of a table asked for
/// by rows are not in id order, those of a whole table are), and they are dropped: a rank holds a round of its
/// rows and the block it reads. The file's checksum is verified after the last table: if that throws (InputError),
/// what `rows` did must not be used. Collective.
void read_checkpoint(const std::string& path, MPI_Comm comm, const WantedRows& wanted,
                     const std::function<void(const CheckpointData& header)>& header,
                     const std::function<void(const std::string& name, const CheckpointTable& rows)>& rows);

}  // namespace shellfrac::io
