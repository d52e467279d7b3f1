#include "shellfrac/io/checkpoint.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <queue>
#include <utility>

#include "shellfrac/core/digest.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::io {

namespace {

constexpr const char* format_tag = "shellfrac checkpoint 5";

/// Rows per HDF5 chunk of a table (chunked storage carries the Fletcher32 checksum of every chunk).
constexpr hsize_t rows_per_chunk = 4096;
/// The widest table a checkpoint may hold (the widest written: the plastic state, 9 values per quadrature point).
constexpr hsize_t max_table_width = 1024;
/// Rows of a table that rank 0 gathers and writes at a time (whole chunks): what bounds its memory.
constexpr std::size_t rows_per_block = 4 * rows_per_chunk;

/// Closes an HDF5 handle at scope exit.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~Handle() {
    if (id >= 0) close(id);
  }
  Handle(Handle&& o) noexcept : id(o.id), close(o.close) { o.id = -1; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      if (id >= 0) close(id);
      id = o.id, close = o.close, o.id = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
};

/// A failed write names the file and stops the run with the output-error exit code (the previous checkpoint is
/// untouched: the file being written is a temporary one).
void check(bool ok, const std::string& path, const std::string& what) {
  if (!ok) throw OutputError(path + ": " + what + " (disk full, quota, or the directory is gone?)");
}

void write_string_attribute(hid_t loc, const std::string& name, const std::string& value, const std::string& path) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id, H5T_VARIABLE);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(loc, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  check(attr.id >= 0, path, "cannot create attribute " + name);
  const char* c = value.c_str();
  check(H5Awrite(attr.id, type.id, &c) >= 0, path, "cannot write attribute " + name);
}

std::string read_string_attribute(hid_t attr, const std::string& path) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id, H5T_VARIABLE);
  char* c = nullptr;
  if (H5Aread(attr, type.id, &c) < 0 || !c) throw InputError(path + ": unreadable string attribute");
  std::string s(c);
  H5free_memory(c);
  return s;
}

std::vector<std::string> member_names(hid_t group) {
  std::vector<std::string> names;
  H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
             [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
               static_cast<std::vector<std::string>*>(data)->push_back(name);
               return 0;
             },
             &names);
  return names;
}

std::vector<std::string> attribute_names(hid_t loc) {
  std::vector<std::string> names;
  H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, nullptr,
              [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
                static_cast<std::vector<std::string>*>(data)->push_back(name);
                return 0;
              },
              &names);
  return names;
}

/// The scalars and strings in a fixed order (maps are sorted), then the number of tables: the broadcast buffer of
/// a read and the first item of the checksum.
parallel::ByteWriter serialize_header(const CheckpointData& d, std::size_t num_tables) {
  parallel::ByteWriter w;
  w.put(std::int64_t(d.scalars.size()));
  for (const auto& [k, v] : d.scalars) w.put_string(k), w.put(v);
  w.put(std::int64_t(d.strings.size()));
  for (const auto& [k, v] : d.strings) w.put_string(k), w.put_string(v);
  w.put(std::int64_t(num_tables));
  return w;
}

/// Reads what serialize_header wrote into d; returns the number of tables.
std::int64_t deserialize_header(parallel::ByteReader& r, CheckpointData& d) {
  for (auto n = r.get<std::int64_t>(); n > 0; --n) {
    const auto k = r.get_string();
    d.scalars[k] = r.get<double>();
  }
  for (auto n = r.get<std::int64_t>(); n > 0; --n) {
    const auto k = r.get_string();
    d.strings[k] = r.get_string();
  }
  return r.get<std::int64_t>();
}

/// The checksum of a file: the header, then each table in name order (its name, width and ids, then its values
/// in blocks of rows_per_chunk rows), so that writer and reader can add one table at a time.
class Checksum {
 public:
  void add_header(parallel::ByteWriter header) { d_.add_bytes(header.buffer().data(), header.buffer().size()); }
  void add_table(const std::string& name, int width, const std::vector<GlobalId>& ids) {
    d_.add(name), d_.add(std::int64_t(width)), d_.add_bytes(ids.data(), sizeof(GlobalId) * ids.size());
  }
  /// Rows of values, `rows` rows of `width`; called for consecutive blocks of at most rows_per_chunk rows.
  void add_rows(const double* values, std::size_t rows, int width) {
    d_.add_bytes(values, sizeof(double) * rows * std::size_t(width));
  }
  std::string hex() const { return d_.hex(); }

 private:
  Digest d_;
};

/// Creation properties of a table's dataset: chunked with a Fletcher32 checksum per chunk (empty tables are
/// contiguous: there is nothing to check).
Handle dataset_properties(int rank, const hsize_t* dims) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (dims[0] == 0 || (rank == 2 && dims[1] == 0)) return dcpl;
  const hsize_t chunk[2] = {std::min(dims[0], rows_per_chunk), rank == 2 ? dims[1] : 1};
  H5Pset_chunk(dcpl.id, rank, chunk);
  H5Pset_fletcher32(dcpl.id);
  return dcpl;
}

/// Writes a checkpoint file on one rank, one table at a time: `<path>.tmp`, renamed to `<path>` by finish().
class FileWriter {
 public:
  FileWriter(const std::string& path, const CheckpointData& header, std::size_t num_tables)
      : path_(path), fapl_(H5Pcreate(H5P_FILE_ACCESS), H5Pclose), file_(-1, H5Fclose), tables_(-1, H5Gclose) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
    // The 1.10 file format: the superblock and object headers (which hold the attributes) carry checksums too.
    H5Pset_libver_bounds(fapl_.id, H5F_LIBVER_V110, H5F_LIBVER_LATEST);
    // Never through a link: the final name must be a file of its own (or absent); the temporary file is made anew,
    // exclusively, then opened by HDF5 (which truncates the empty file it finds).
    files::require_result_path(path_);
    tmp_ = files::fresh_temporary(path_);
    file_.id = H5Fcreate(tmp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl_.id);
    check(file_.id >= 0, tmp_, "cannot create the checkpoint file");
    write_string_attribute(file_.id, "format", format_tag, tmp_);
    checksum_.add_header(serialize_header(header, num_tables));
    {
      Handle g(H5Gcreate2(file_.id, "scalars", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      for (const auto& [name, v] : header.scalars) {
        Handle space(H5Screate(H5S_SCALAR), H5Sclose);
        Handle attr(H5Acreate2(g.id, name.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
        check(attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &v) >= 0, tmp_, "cannot write scalar " + name);
      }
    }
    {
      Handle g(H5Gcreate2(file_.id, "strings", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      for (const auto& [name, v] : header.strings) write_string_attribute(g.id, name, v, tmp_);
    }
    tables_.id = H5Gcreate2(file_.id, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    check(tables_.id >= 0, tmp_, "cannot create /tables");
  }
  ~FileWriter() {  // not finished: an error; the temporary file goes
    if (file_.id < 0) return;
    values_ = Handle(-1, H5Dclose);
    H5Gclose(tables_.id), tables_.id = -1;
    H5Fclose(file_.id), file_.id = -1;
    ::unlink(tmp_.c_str());
  }
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  /// Starts a table: its ids (sorted and unique) are written; its values follow by write_rows, in id order.
  void begin_table(const std::string& name, int width, const std::vector<GlobalId>& ids) {
    values_ = Handle(-1, H5Dclose);
    table_name_ = name, width_ = width, rows_written_ = 0;
    Handle g(H5Gcreate2(tables_.id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    check(g.id >= 0, tmp_, "cannot create table " + name);
    checksum_.add_table(name, width, ids);
    const hsize_t rows = ids.size(), dims[2] = {rows, hsize_t(width)};
    {
      Handle space(H5Screate_simple(1, &rows, nullptr), H5Sclose);
      const Handle dcpl = dataset_properties(1, &rows);
      Handle ds(H5Dcreate2(g.id, "ids", H5T_NATIVE_INT64, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose);
      check(ds.id >= 0 && (rows == 0 || H5Dwrite(ds.id, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                   ids.data()) >= 0),
            tmp_, "cannot write table " + name);
    }
    Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
    const Handle dcpl = dataset_properties(2, dims);
    values_ = Handle(H5Dcreate2(g.id, "values", H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT),
                     H5Dclose);
    check(values_.id >= 0, tmp_, "cannot write table " + name);
  }
  /// The next `n` rows of the table begun last (n * width values); whole chunks except at the end.
  void write_rows(const double* values, std::size_t n) {
    if (width_ == 0 || n == 0) return;
    for (std::size_t r = 0; r < n; r += rows_per_chunk)
      checksum_.add_rows(values + r * std::size_t(width_), std::min<std::size_t>(rows_per_chunk, n - r), width_);
    const hsize_t start[2] = {rows_written_, 0}, count[2] = {n, hsize_t(width_)};
    Handle file_space(H5Dget_space(values_.id), H5Sclose);
    Handle memory(H5Screate_simple(2, count, nullptr), H5Sclose);
    check(H5Sselect_hyperslab(file_space.id, H5S_SELECT_SET, start, nullptr, count, nullptr) >= 0 &&
              H5Dwrite(values_.id, H5T_NATIVE_DOUBLE, memory.id, file_space.id, H5P_DEFAULT, values) >= 0,
          tmp_, "cannot write table " + table_name_);
    rows_written_ += n;
  }

  /// The checksum, then flush, close and rename.
  void finish() {
    values_ = Handle(-1, H5Dclose);
    write_string_attribute(file_.id, "checksum", checksum_.hex(), tmp_);
    H5Gclose(tables_.id), tables_.id = -1;
    check(H5Fflush(file_.id, H5F_SCOPE_GLOBAL) >= 0, tmp_, "cannot flush the checkpoint file");
    check(H5Fclose(file_.id) >= 0, tmp_, "cannot close the checkpoint file");
    file_.id = -1;
    files::require_result_path(path_);
    check(std::rename(tmp_.c_str(), path_.c_str()) == 0, path_, "cannot rename " + tmp_ + " to it");
  }

 private:
  std::string path_, tmp_;
  Handle fapl_, file_, tables_;
  Checksum checksum_;
  Handle values_{-1, H5Dclose};  // the values of the table being written
  std::string table_name_;
  int width_ = 0;
  hsize_t rows_written_ = 0;
};

/// Reads a checkpoint file on one rank: the header at once, then one table at a time.
class FileReader {
 public:
  explicit FileReader(const std::string& path) : path_(path), file_(-1, H5Fclose), tables_(-1, H5Gclose) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
    file_.id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_.id < 0) throw InputError(path + ": cannot open the checkpoint (missing, or not an HDF5 file)");
    const auto root_string = [&](const char* name) {
      Handle attr(H5Aopen(file_.id, name, H5P_DEFAULT), H5Aclose);
      return attr.id < 0 ? std::string() : read_string_attribute(attr.id, path);
    };
    const std::string format = root_string("format");
    if (format != format_tag)
      throw InputError(path + ": not a checkpoint of this version of shellfrac (" +
                       (format.rfind("shellfrac checkpoint", 0) == 0 ? "format '" + format + "', this version reads '" +
                                                                            std::string(format_tag) + "'"
                                                                      : "no '" + std::string(format_tag) + "' format tag") +
                       "; checkpoints of other versions or other programs are not read)");
    stored_checksum_ = root_string("checksum");
    {
      Handle g(H5Gopen2(file_.id, "scalars", H5P_DEFAULT), H5Gclose);
      if (g.id < 0) throw InputError(path + ": checkpoint without /scalars");
      for (const auto& name : attribute_names(g.id)) {
        Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
        double v = 0;
        if (H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) < 0) throw InputError(path + ": unreadable scalar " + name);
        header_.scalars[name] = v;
      }
    }
    {
      Handle g(H5Gopen2(file_.id, "strings", H5P_DEFAULT), H5Gclose);
      if (g.id < 0) throw InputError(path + ": checkpoint without /strings");
      for (const auto& name : attribute_names(g.id)) {
        Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
        header_.strings[name] = read_string_attribute(attr.id, path);
      }
    }
    tables_.id = H5Gopen2(file_.id, "tables", H5P_DEFAULT);
    if (tables_.id < 0) throw InputError(path + ": checkpoint without /tables");
    table_names_ = member_names(tables_.id);
    checksum_.add_header(serialize_header(header_, table_names_.size()));
  }
  const CheckpointData& header() const { return header_; }
  const std::vector<std::string>& table_names() const { return table_names_; }

  /// Starts reading table `name` (the names in table_names() order): its width and ids (the ids are also left in
  /// t.values empty); its values follow by read_rows, in order.
  CheckpointTable begin_table(const std::string& name) {
    values_ = Handle(-1, H5Dclose);
    table_name_ = name, rows_read_ = 0;
    Handle g(H5Gopen2(tables_.id, name.c_str(), H5P_DEFAULT), H5Gclose);
    Handle ids(H5Dopen2(g.id, "ids", H5P_DEFAULT), H5Dclose);
    values_ = Handle(H5Dopen2(g.id, "values", H5P_DEFAULT), H5Dclose);
    if (ids.id < 0 || values_.id < 0) throw InputError(path_ + ": table " + name + " lacks ids or values");
    Handle s1(H5Dget_space(ids.id), H5Sclose), s2(H5Dget_space(values_.id), H5Sclose);
    hsize_t n = 0, dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(s1.id) != 1 || H5Sget_simple_extent_ndims(s2.id) != 2)
      throw InputError(path_ + ": table " + name + " has the wrong shape");
    H5Sget_simple_extent_dims(s1.id, &n, nullptr);
    H5Sget_simple_extent_dims(s2.id, dims, nullptr);
    if (dims[0] != n) throw InputError(path_ + ": table " + name + ": ids and values differ in length");
    // Sizes are believed only as far as the file holds the data: a damaged or forged header must not make us
    // allocate what the file does not contain.
    if (dims[1] > max_table_width || H5Dget_storage_size(ids.id) < n * sizeof(GlobalId) ||
        H5Dget_storage_size(values_.id) < n * dims[1] * sizeof(double))
      throw InputError(path_ + ": table " + name + " declares " + std::to_string(n) + " rows of " +
                       std::to_string(dims[1]) + " values, more than the file holds: the file is corrupt");
    CheckpointTable t;
    t.width = width_ = static_cast<int>(dims[1]);
    t.ids.resize(n);
    if (n > 0 && H5Dread(ids.id, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.ids.data()) < 0)
      throw InputError(path_ + ": unreadable table " + name + " (a chunk fails its checksum: the file is corrupt)");
    if (!std::is_sorted(t.ids.begin(), t.ids.end())) throw InputError(path_ + ": table " + name + " is not sorted");
    checksum_.add_table(name, t.width, t.ids);
    return t;
  }
  /// The next `n` rows of the table begun last into out (n * width values); whole chunks except at the end.
  void read_rows(std::size_t n, double* out) {
    if (width_ == 0 || n == 0) return;
    const hsize_t start[2] = {rows_read_, 0}, count[2] = {n, hsize_t(width_)};
    Handle file_space(H5Dget_space(values_.id), H5Sclose);
    Handle memory(H5Screate_simple(2, count, nullptr), H5Sclose);
    if (H5Sselect_hyperslab(file_space.id, H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
        H5Dread(values_.id, H5T_NATIVE_DOUBLE, memory.id, file_space.id, H5P_DEFAULT, out) < 0)
      throw InputError(path_ + ": unreadable table " + table_name_ +
                       " (a chunk fails its checksum: the file is corrupt)");
    for (std::size_t r = 0; r < n; r += rows_per_chunk)
      checksum_.add_rows(out + r * std::size_t(width_), std::min<std::size_t>(rows_per_chunk, n - r), width_);
    rows_read_ += n;
  }
  /// After every table: the contents against the stored checksum.
  void verify() const {
    if (checksum_.hex() != stored_checksum_)
      throw InputError(path_ + ": the checkpoint's contents do not match its checksum: the file is corrupt (a "
                               "damaged copy or disk?); restart from another checkpoint");
  }

 private:
  std::string path_;
  Handle file_, tables_;
  std::string stored_checksum_;
  CheckpointData header_;
  std::vector<std::string> table_names_;
  Checksum checksum_;
  Handle values_{-1, H5Dclose};  // the values of the table being read
  std::string table_name_;
  int width_ = 0;
  hsize_t rows_read_ = 0;
};

// Point-to-point transfers of long vectors (MPI counts are int: sent in pieces of 2^27 values).
template <class T>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}
template <>
MPI_Datatype mpi_type<std::int64_t>() {
  return MPI_INT64_T;
}
constexpr std::size_t piece = std::size_t(1) << 27;

template <class T>
void send_vector(const std::vector<T>& v, int to, MPI_Comm comm) {
  std::uint64_t n = v.size();
  MPI_Send(&n, 1, MPI_UINT64_T, to, 0, comm);
  for (std::size_t off = 0; off < v.size(); off += piece)
    MPI_Send(v.data() + off, static_cast<int>(std::min(piece, v.size() - off)), mpi_type<T>(), to, 0, comm);
}

template <class T>
std::vector<T> receive_vector(int from, MPI_Comm comm) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 0, comm, MPI_STATUS_IGNORE);
  std::vector<T> v(n);
  for (std::size_t off = 0; off < v.size(); off += piece)
    MPI_Recv(v.data() + off, static_cast<int>(std::min(piece, v.size() - off)), mpi_type<T>(), from, 0, comm,
             MPI_STATUS_IGNORE);
  return v;
}

/// One table as a rank gives it: its ids, sorted, and a way to read a range of its rows in that order.
struct LocalRows {
  int width = 0;
  std::vector<GlobalId> ids;
  std::function<void(std::size_t first, std::size_t count, double* out)> rows;
};

/// Table `name` of `d`: a source as it is, a given table (ids in any order) through its sorting permutation.
LocalRows local_rows(const CheckpointData& d, const std::string& name) {
  const auto source = d.table_sources.find(name);
  if (source != d.table_sources.end()) return {source->second.width, source->second.ids(), source->second.rows};
  const CheckpointTable& t = d.tables.at(name);
  std::vector<std::size_t> order(t.ids.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t.ids[a] < t.ids[b]; });
  LocalRows r;
  r.width = t.width;
  for (const std::size_t i : order) r.ids.push_back(t.ids[i]);
  r.rows = [&t, order](std::size_t first, std::size_t count, double* out) {
    for (std::size_t i = 0; i < count; ++i)
      std::copy_n(t.values.data() + order[first + i] * std::size_t(t.width), t.width, out + i * std::size_t(t.width));
  };
  return r;
}

// The row requests of a table from rank 0 to rank r: (first, count) of r's rows, answered with their values; a
// request with count 0 ends the table.
std::vector<double> request_rows(int r, std::size_t first, std::size_t count, MPI_Comm comm) {
  const std::uint64_t request[2] = {first, count};
  MPI_Send(request, 2, MPI_UINT64_T, r, 0, comm);
  return receive_vector<double>(r, comm);
}
void end_row_requests(int r, MPI_Comm comm) {
  const std::uint64_t request[2] = {0, 0};
  MPI_Send(request, 2, MPI_UINT64_T, r, 0, comm);
}
void serve_row_requests(const LocalRows& t, MPI_Comm comm) {
  std::vector<double> values;
  for (;;) {
    std::uint64_t request[2] = {0, 0};
    MPI_Recv(request, 2, MPI_UINT64_T, 0, 0, comm, MPI_STATUS_IGNORE);
    if (request[1] == 0) return;
    const bool valid = request[0] + request[1] <= t.ids.size();
    values.assign(valid ? request[1] * std::size_t(t.width) : 0, 0.0);  // rank 0 reports a short answer
    if (valid) t.rows(request[0], request[1], values.data());
    send_vector(values, 0, comm);
  }
}

/// The ranks' sorted ids of a table merged in id order (an id several ranks give is taken from the lowest of them),
/// walked a block of rows at a time.
class RowMerge {
 public:
  /// ids[r]: rank r's ids, sorted (an id repeated within a rank is taken once).
  explicit RowMerge(const std::vector<std::vector<GlobalId>>& ids) : ids_(ids) {
    restart();
    std::vector<std::size_t> first, count;
    for (;;) {
      const auto& block = next_block(rows_per_block, first, count);
      if (block.empty()) break;
      for (const auto& [r, row] : block) sorted_.push_back(ids_[std::size_t(r)][row]);
    }
    size_ = sorted_.size();
    restart();
  }
  std::size_t size() const { return size_; }
  /// The merged ids (once: they are handed over).
  std::vector<GlobalId> take_sorted_ids() { return std::move(sorted_); }
  /// The next n rows: (rank, row) of each; first[r] and count[r] the range of rank r's rows the block passes
  /// (including repeats of a lower rank's ids, not taken).
  const std::vector<std::pair<int, std::size_t>>& next_block(std::size_t n, std::vector<std::size_t>& first,
                                                             std::vector<std::size_t>& count) {
    first = cursor_;
    block_.clear();
    while (block_.size() < n && !heads_.empty()) {
      const auto [id, r] = heads_.top();
      block_.emplace_back(r, cursor_[std::size_t(r)]);
      while (!heads_.empty() && heads_.top().first == id) {
        const int rr = heads_.top().second;
        heads_.pop();
        pass(rr, id);
      }
    }
    count.resize(cursor_.size());
    for (std::size_t r = 0; r < cursor_.size(); ++r) count[r] = cursor_[r] - first[r];
    return block_;
  }

 private:
  void restart() {
    cursor_.assign(ids_.size(), 0);
    heads_ = {};
    for (std::size_t r = 0; r < ids_.size(); ++r)
      if (!ids_[r].empty()) heads_.emplace(ids_[r][0], int(r));
  }
  /// Moves rank r past `id` and queues its next id.
  void pass(int r, GlobalId id) {
    const auto& mine = ids_[std::size_t(r)];
    std::size_t& c = cursor_[std::size_t(r)];
    while (c < mine.size() && mine[c] == id) ++c;
    if (c < mine.size()) heads_.emplace(mine[c], r);
  }

  const std::vector<std::vector<GlobalId>>& ids_;
  std::vector<std::size_t> cursor_;
  std::priority_queue<std::pair<GlobalId, int>, std::vector<std::pair<GlobalId, int>>, std::greater<>> heads_;
  std::vector<std::pair<int, std::size_t>> block_;
  std::vector<GlobalId> sorted_;
  std::size_t size_ = 0;
};

/// The names of the tables and table sources, sorted, the same on every rank (an internal error otherwise).
/// Collective.
std::vector<std::string> agreed_table_names(const CheckpointData& local, MPI_Comm comm) {
  std::vector<std::string> names;
  for (const auto& [name, t] : local.tables) names.push_back(name);
  for (const auto& [name, source] : local.table_sources) {
    SHELLFRAC_REQUIRE(!local.tables.count(name), "checkpoint: table " << name << " given twice");
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  std::string mine;
  for (const auto& name : names) mine += name + '\n';
  std::string roots = mine;
  parallel::broadcast(roots, 0, comm);
  SHELLFRAC_REQUIRE(!parallel::any(roots != mine, comm), "checkpoint: the ranks hold different tables");
  return names;
}

}  // namespace

CheckpointData built(CheckpointData data) {
  for (const auto& [name, source] : data.table_sources) {
    CheckpointTable& t = data.tables[name];
    t.width = source.width, t.ids = source.ids();
    t.values.resize(t.ids.size() * std::size_t(source.width));
    source.rows(0, t.ids.size(), t.values.data());
  }
  data.table_sources.clear();
  return data;
}

const double* CheckpointTable::row(GlobalId id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return nullptr;
  return values.data() + (it - ids.begin()) * width;
}

// Rank 0 writes, one table at a time and a block of rows_per_block rows at a time: it gathers every rank's ids of the
// table, merges them (sorted, a row given by two ranks taken from the lower), writes them, then asks each rank for
// the rows of each block and writes the block. No rank ever holds a table: rank 0 holds the ids and one block,
// the others build the rows of a block when asked. An error on rank 0 is raised on every rank after the last table.
void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  const auto names = agreed_table_names(local, comm);
  std::string error;
  int kind = 0;  // of the first error on rank 0: 1 InputError, 2 Error, 3 OutputError
  const auto attempt = [&](const auto& fn) {
    if (me != 0 || kind != 0) return;
    try {
      fn();
    } catch (const OutputError& e) {
      kind = 3, error = e.what();
    } catch (const InputError& e) {
      kind = 1, error = e.what();
    } catch (const std::exception& e) {
      kind = 2, error = e.what();
    }
  };
  std::unique_ptr<FileWriter> writer;
  attempt([&] { writer = std::make_unique<FileWriter>(path, local, names.size()); });
  for (const auto& name : names) {
    const LocalRows mine = local_rows(local, name);
    const int width = static_cast<int>(parallel::max(double(mine.width), comm));
    if (me != 0) {
      send_vector(std::vector<std::int64_t>{mine.width}, 0, comm), send_vector(mine.ids, 0, comm);
      serve_row_requests(mine, comm);
      continue;
    }
    std::vector<std::vector<GlobalId>> ids(static_cast<std::size_t>(np));
    std::vector<int> widths(static_cast<std::size_t>(np), mine.width);
    ids[0] = mine.ids;
    for (int r = 1; r < np; ++r) {
      widths[std::size_t(r)] = static_cast<int>(receive_vector<std::int64_t>(r, comm).at(0));
      ids[std::size_t(r)] = receive_vector<std::int64_t>(r, comm);
    }
    std::optional<RowMerge> merge;
    attempt([&] {
      for (int r = 0; r < np; ++r) {
        const auto& theirs = ids[std::size_t(r)];
        SHELLFRAC_REQUIRE(theirs.empty() || widths[std::size_t(r)] == width,
                          "checkpoint table " << name << ": rows of width " << widths[std::size_t(r)] << " from rank "
                                              << r << ", " << width << " from another");
        SHELLFRAC_REQUIRE(std::is_sorted(theirs.begin(), theirs.end()),
                          "checkpoint table " << name << ": the ids of rank " << r << " are not sorted");
      }
      merge.emplace(ids);
      writer->begin_table(name, width, merge->take_sorted_ids());
    });
    std::vector<double> block;
    std::vector<std::size_t> first(static_cast<std::size_t>(np)), count(static_cast<std::size_t>(np));
    std::vector<std::vector<double>> rows(static_cast<std::size_t>(np));
    for (std::size_t done = 0; kind == 0 && merge && done < merge->size(); done += rows_per_block) {
      const std::size_t n = std::min(rows_per_block, merge->size() - done);
      const auto& sources = merge->next_block(n, first, count);  // (rank, row) of each row of the block
      for (int r = 0; r < np; ++r) {
        auto& buffer = rows[std::size_t(r)];
        buffer.resize(count[std::size_t(r)] * std::size_t(width));
        if (count[std::size_t(r)] == 0) continue;
        if (r == 0)
          mine.rows(first[0], count[0], buffer.data());
        else
          buffer = request_rows(r, first[std::size_t(r)], count[std::size_t(r)], comm);
      }
      attempt([&] {
        block.resize(n * std::size_t(width));
        for (std::size_t i = 0; i < n; ++i) {
          const auto [r, row] = sources[i];
          const auto& buffer = rows[std::size_t(r)];
          SHELLFRAC_REQUIRE(buffer.size() == count[std::size_t(r)] * std::size_t(width),
                            "checkpoint table " << name << ": rank " << r << " sent " << buffer.size() << " values");
          std::copy_n(buffer.data() + (row - first[std::size_t(r)]) * std::size_t(width), width,
                      block.data() + i * std::size_t(width));
        }
        writer->write_rows(block.data(), n);
      });
    }
    for (int r = 1; r < np; ++r) end_row_requests(r, comm);
  }
  attempt([&] { writer->finish(); });
  writer.reset();
  MPI_Bcast(&kind, 1, MPI_INT, 0, comm);
  if (kind == 0) return;
  parallel::broadcast(error, 0, comm);
  if (kind == 1) throw InputError(error);
  if (kind == 3) throw OutputError(error);
  throw Error(error);
}

// Rank 0 reads one table at a time, a block of rows_per_block rows at a time, and sends every rank the rows of each
// block that it asks for (`wanted`; a table not asked for goes whole to every rank): no rank but rank 0 ever sees a
// row it did not ask for, and each rank holds one table of its rows at a time.
void read_checkpoint(const std::string& path, MPI_Comm comm, const WantedRows& wanted,
                     const std::function<void(const CheckpointData& header)>& header,
                     const std::function<void(const std::string& name, const CheckpointTable& rows)>& table) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  std::unique_ptr<FileReader> reader;
  CheckpointData d;
  std::vector<std::string> names;
  parallel::on_root_then_agree(
      [&] {
        reader = std::make_unique<FileReader>(path);
        d.scalars = reader->header().scalars, d.strings = reader->header().strings;
        names = reader->table_names();
      },
      0, comm);
  {  // scalars, strings and the table names to every rank
    parallel::ByteWriter w;
    if (me == 0) {
      w = serialize_header(d, names.size());
      for (const auto& n : names) w.put_string(n);
    }
    parallel::broadcast(w.buffer(), 0, comm);
    if (me != 0) {
      parallel::ByteReader r(w.buffer());
      for (auto n = deserialize_header(r, d); n > 0; --n) names.push_back(r.get_string());
    }
  }
  header(d);
  for (const auto& name : names) {
    // The ids each rank asks for, sorted and unique; a table nobody names goes whole to every rank.
    const std::vector<GlobalId>* ask = wanted(name);
    const bool whole = ask == nullptr;
    std::vector<GlobalId> mine_asked;
    if (!whole) {
      mine_asked = *ask;
      std::sort(mine_asked.begin(), mine_asked.end());
      mine_asked.erase(std::unique(mine_asked.begin(), mine_asked.end()), mine_asked.end());
    }
    SHELLFRAC_REQUIRE(!(parallel::any(whole, comm) && parallel::any(!whole, comm)),
                      "checkpoint " << path << ": table " << name << " is asked for by some ranks only");
    std::vector<std::vector<GlobalId>> asked(static_cast<std::size_t>(np));
    if (!whole) {
      if (me == 0) {
        asked[0] = std::move(mine_asked);
        for (int r = 1; r < np; ++r) asked[std::size_t(r)] = receive_vector<std::int64_t>(r, comm);
      } else {
        send_vector(mine_asked, 0, comm);
      }
    }
    CheckpointTable ids;  // rank 0: the file's ids and width
    parallel::on_root_then_agree([&] { ids = reader->begin_table(name); }, 0, comm);
    std::int64_t shape[2] = {ids.width, std::int64_t(ids.ids.size())};
    MPI_Bcast(shape, 2, MPI_INT64_T, 0, comm);
    CheckpointTable rows;  // this rank's rows of a block
    rows.width = static_cast<int>(shape[0]);
    const std::size_t num_rows = std::size_t(shape[1]), width = std::size_t(shape[0]);
    std::vector<std::size_t> cursor(static_cast<std::size_t>(np), 0);
    std::vector<double> block;
    std::vector<GlobalId> block_ids;
    for (std::size_t first = 0; first < num_rows; first += rows_per_block) {
      const std::size_t n = std::min(rows_per_block, num_rows - first);
      if (me == 0 || whole) block.resize(n * width);  // the other ranks get only their rows of a wanted table
      parallel::on_root_then_agree([&] { reader->read_rows(n, block.data()); }, 0, comm);
      rows.ids.clear(), rows.values.clear();
      if (whole) {  // every rank gets the block
        block_ids.assign(n, 0);
        if (me == 0) std::copy_n(ids.ids.begin() + std::ptrdiff_t(first), n, block_ids.begin());
        SHELLFRAC_REQUIRE(MPI_Bcast(block_ids.data(), int(n), MPI_INT64_T, 0, comm) == MPI_SUCCESS &&
                              MPI_Bcast(block.data(), int(n * width), MPI_DOUBLE, 0, comm) == MPI_SUCCESS,
                          "checkpoint: broadcast of table " << name << " failed");
        rows.ids = block_ids, rows.values = block;
        table(name, rows);
        continue;
      }
      if (me != 0) {  // this rank's rows of the block
        rows.ids = receive_vector<std::int64_t>(0, comm);
        rows.values = receive_vector<double>(0, comm);
        table(name, rows);
        continue;
      }
      // Rank 0: each rank's asked ids within the block (both sorted: one pass over each).
      const auto begin = ids.ids.begin() + std::ptrdiff_t(first), end = begin + std::ptrdiff_t(n);
      for (int r = 0; r < np; ++r) {
        const auto& want = asked[std::size_t(r)];
        std::size_t& c = cursor[std::size_t(r)];
        std::vector<GlobalId> out_ids;
        std::vector<double> out_values;
        auto at = begin;
        for (; c < want.size() && want[c] <= *(end - 1); ++c) {
          at = std::lower_bound(at, end, want[c]);
          if (at == end || *at != want[c]) continue;  // not in the file
          const std::size_t row = std::size_t(at - begin);
          out_ids.push_back(want[c]);
          out_values.insert(out_values.end(), block.begin() + std::ptrdiff_t(row * width),
                            block.begin() + std::ptrdiff_t((row + 1) * width));
        }
        if (r == 0)
          rows.ids = std::move(out_ids), rows.values = std::move(out_values);
        else
          send_vector(out_ids, r, comm), send_vector(out_values, r, comm);
      }
      table(name, rows);
    }
    if (num_rows == 0) table(name, rows);  // an empty table is still one
  }
  parallel::on_root_then_agree([&] { reader->verify(); }, 0, comm);
}

CheckpointData read_checkpoint(const std::string& path, MPI_Comm comm,
                               const std::map<std::string, std::vector<GlobalId>>& wanted) {
  CheckpointData d;
  const auto ask = [&](const std::string& name) -> const std::vector<GlobalId>* {
    const auto it = wanted.find(name);
    return it == wanted.end() ? nullptr : &it->second;
  };
  read_checkpoint(
      path, comm, ask, [&](const CheckpointData& header) { d = header; },
      [&](const std::string& name, const CheckpointTable& rows) {
        CheckpointTable& t = d.tables[name];
        t.width = rows.width;
        t.ids.insert(t.ids.end(), rows.ids.begin(), rows.ids.end());
        t.values.insert(t.values.end(), rows.values.begin(), rows.values.end());
      });
  return d;
}

}  // namespace shellfrac::io
