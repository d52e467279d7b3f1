#pragma once
/// \file history.hpp
/// The run's history: a CSV file written by rank 0 (header line, then one row per recorded step; each row
/// is flushed so a crashed run keeps its history). Columns are fixed at construction. Values are written
/// with 17 significant digits so that histories compare bitwise across runs.
#include <mpi.h>

#include <fstream>
#include <string>
#include <vector>

namespace shellfrac::io {

/// Rank-0 CSV writer for global time histories (energies, probes).
class HistoryWriter {
 public:
  /// Creates (overwrites) `path` on rank 0 and writes the header. Throws Error naming the file on failure
  /// (on every rank). Collective.
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns, MPI_Comm comm = MPI_COMM_WORLD);
  /// Resumes an existing file (a restart): keeps its header (which must equal `columns`) and the rows whose first
  /// value is <= keep_through, drops the others, and appends after them. InputError naming the file if it is
  /// missing or has other columns. Collective.
  HistoryWriter(const std::string& path, const std::vector<std::string>& columns, double keep_through, MPI_Comm comm);
  /// Appends a row; values.size() must equal the number of columns. Only rank 0's values are used. A failed
  /// write (checked after each row) throws OutputError naming the file on every rank. Collective.
  void write_row(const std::vector<double>& values);
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::vector<std::string> columns_;
  std::string path_;
  MPI_Comm comm_;
  std::ofstream out_;
};

}  // namespace shellfrac::io
