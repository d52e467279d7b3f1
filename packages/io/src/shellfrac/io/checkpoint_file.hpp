#pragma once
/// \file checkpoint_file.hpp
/// One checkpoint file, HDF5, written or read on one rank one table at a time (docs/output.md, "Checkpoints"):
/// the header (scalars, strings), the tables in chunks with Fletcher32 checksums, and a checksum over everything.
/// checkpoint.cpp gathers the ranks' rows to it and scatters them from it. Internal to io; checkpoint_file.cpp is
/// the only file that includes hdf5.h.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint.hpp"

namespace shellfrac::io {

/// Rows of a table that rank 0 gathers and writes (or reads and sends) at a time, whole chunks of the file: what
/// bounds its memory.
extern const std::size_t checkpoint_rows_per_block;

/// The scalars and strings in a fixed order (maps are sorted), then the number of tables: the broadcast buffer of
/// a read and the first item of the checksum.
parallel::ByteWriter serialize_header(const CheckpointData& d, std::size_t num_tables);
/// Reads what serialize_header wrote into d; returns the number of tables.
std::int64_t deserialize_header(parallel::ByteReader& r, CheckpointData& d);

/// Writes a checkpoint file: `<path>.tmp` (made anew, never through a link), renamed to `<path>` by finish().
/// OutputError naming the file for any failed write.
class CheckpointFileWriter {
 public:
  CheckpointFileWriter(const std::string& path, const CheckpointData& header, std::size_t num_tables);
  ~CheckpointFileWriter();
  CheckpointFileWriter(const CheckpointFileWriter&) = delete;
  CheckpointFileWriter& operator=(const CheckpointFileWriter&) = delete;
  /// Starts table `name` of `width` values per row for the sorted `ids`; its rows follow by write_rows.
  void begin_table(const std::string& name, int width, const std::vector<GlobalId>& ids);
  /// The next n rows of the table (n * width values).
  void write_rows(const double* values, std::size_t n);
  /// The checksum, then flush, close and rename.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a checkpoint file: the header at once, then one table at a time. InputError naming the file for anything
/// that is not a complete, intact checkpoint.
class CheckpointFileReader {
 public:
  explicit CheckpointFileReader(const std::string& path);
  ~CheckpointFileReader();
  CheckpointFileReader(const CheckpointFileReader&) = delete;
  CheckpointFileReader& operator=(const CheckpointFileReader&) = delete;
  const CheckpointData& header() const;
  const std::vector<std::string>& table_names() const;
  /// Table `name`'s width and ids (no values); its rows follow by read_rows.
  CheckpointTable begin_table(const std::string& name);
  /// The next n rows of the table into out (n * width values).
  void read_rows(std::size_t n, double* out);
  /// InputError unless the checksum over everything read matches the file's.
  void verify() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellfrac::io
