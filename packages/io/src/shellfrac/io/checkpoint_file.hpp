#pragma once
/// \file checkpoint_file.hpp
/// One checkpoint file, HDF5 with the MPI-IO driver, opened by every rank of a communicator (docs/output.md,
/// "Checkpoints"): the header (scalars, strings), the tables in chunks with Fletcher32 checksums, and a checksum
/// over everything that each rank computes over the rows it writes or reads and that the ranks combine.
/// checkpoint.cpp decides which rows each rank writes or reads. Every call is collective: a failure on any rank
/// is raised on every rank, with the same message. Internal to io; checkpoint_file.cpp is the only file that
/// includes hdf5.h.
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint.hpp"

namespace shellfrac::io {

/// Rows of a table that a rank writes or reads at a time (whole HDF5 chunks): what bounds its memory.
extern const std::size_t checkpoint_rows_per_block;

/// The scalars and strings in a fixed order (maps are sorted), then the number of tables: the broadcast buffer of
/// the header and the first item of the checksum.
parallel::ByteWriter serialize_header(const CheckpointData& d, std::size_t num_tables);
/// Reads what serialize_header wrote into d; returns the number of tables.
std::int64_t deserialize_header(parallel::ByteReader& r, CheckpointData& d);

/// Writes a checkpoint file: `<path>.tmp` (made anew by the first rank, never through a link), renamed to `<path>`
/// by finish(). OutputError naming the file for any failed write, on every rank. `header` must be the same on every
/// rank.
class CheckpointFileWriter {
 public:
  CheckpointFileWriter(const std::string& path, const CheckpointData& header, std::size_t num_tables, MPI_Comm comm);
  ~CheckpointFileWriter();
  CheckpointFileWriter(const CheckpointFileWriter&) = delete;
  CheckpointFileWriter& operator=(const CheckpointFileWriter&) = delete;
  /// Starts table `name` of `num_rows` rows of `width` values (the same on every rank).
  void begin_table(const std::string& name, int width, std::size_t num_rows);
  /// This rank's n rows from file row `first` on: their ids (sorted, above those of the rows before) and values
  /// (n * width). Every rank calls it the same number of times per table, possibly with n = 0.
  void write_rows(std::size_t first, const GlobalId* ids, const double* values, std::size_t n);
  /// The checksum, then flush, close and rename.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a checkpoint file: the header at once, then one table at a time. InputError naming the file, on every rank,
/// for anything that is not a complete, intact checkpoint.
class CheckpointFileReader {
 public:
  CheckpointFileReader(const std::string& path, MPI_Comm comm);
  ~CheckpointFileReader();
  CheckpointFileReader(const CheckpointFileReader&) = delete;
  CheckpointFileReader& operator=(const CheckpointFileReader&) = delete;
  const CheckpointData& header() const;
  const std::vector<std::string>& table_names() const;
  /// Starts table `name`: its width and number of rows, checked against what the file holds.
  void begin_table(const std::string& name, int& width, std::size_t& num_rows);
  /// This rank's n rows from file row `first` on into ids and values (resized), checked sorted after the rows this
  /// rank read before. Every rank calls it the same number of times per table, possibly with n = 0; each row of
  /// the file must be read by exactly one rank (the checksum counts every row read once).
  void read_rows(std::size_t first, std::size_t n, std::vector<GlobalId>& ids, std::vector<double>& values);
  /// InputError unless the checksum over everything read matches the file's.
  void verify() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellfrac::io
