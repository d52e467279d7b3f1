#pragma once
/// \file history.hpp
/// The run's CSV tables (history, fragments, crack log): files written by rank 0 (header line, then one row per
/// record; each row is written at once so a crashed run keeps its rows). Columns are fixed at construction. Values
/// are written with 17 significant digits so that tables compare bitwise across runs. Files are opened without
/// following links (core/files.hpp) and every write is checked.
///
/// A restart resumes a table only if the rows on disk are provably the ones its checkpoint was written after: the
/// checkpoint holds the table's mark (length and a digest of its lines, `mark()`), and `resume` accepts the file only
/// if its first mark.bytes bytes have that digest (docs/output.md, "Restarts").
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/digest.hpp"

namespace shellfrac::files {
class OutputFile;
}

namespace shellfrac::io {

/// How far a CSV table was written: its length in bytes and the digest of its lines (each with its '\n', hashed
/// one line at a time).
struct CsvMark {
  long long bytes = -1;  ///< -1: unknown (a checkpoint written before marks existed)
  std::string digest;
  std::string file;  ///< the file's name, without its directory
};

/// Rank-0 CSV writer for global time histories (energies, probes) and the other tables.
class HistoryWriter {
 public:
  /// Creates (replaces) `path` on rank 0 and writes the header. Throws OutputError naming the file on failure (on
  /// every rank; a symbolic link of that name is refused, not followed). Collective.
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm = MPI_COMM_WORLD);
  ~HistoryWriter();
  /// Resumes `path` after a restart if its header is `columns` and its first `mark.bytes` bytes are the lines
  /// `mark` was taken of: the file is cut there and rows are appended. Null (on every rank) if that cannot be
  /// proved: the file is missing, is not a regular file, is shorter, has other lines or columns, or the mark is
  /// unknown; the file is then left as it is. Collective.
  static std::unique_ptr<HistoryWriter> resume(const std::string& path, const std::vector<std::string>& columns,
                                               const CsvMark& mark, MPI_Comm comm);
  /// Appends a row; values.size() must equal the number of columns. Only rank 0's values are used. A failed
  /// write throws OutputError naming the file on every rank. Collective.
  void write_row(const std::vector<double>& values);
  const std::vector<std::string>& columns() const { return columns_; }
  const std::string& path() const { return path_; }
  /// The file's length and digest so far (rank 0's; the others get an unknown mark).
  CsvMark mark() const;

 private:
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm,
                std::unique_ptr<files::OutputFile> file, const Digest& digest, long long bytes);
  void append_line(const std::string& line);
  std::vector<std::string> columns_;
  std::string path_;
  MPI_Comm comm_;
  std::unique_ptr<files::OutputFile> file_;  // rank 0
  Digest digest_;
  long long bytes_ = 0;
};

}  // namespace shellfrac::io
