#include "shellfrac/io/checkpoint_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "shellfrac/core/digest.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"

namespace shellfrac::io {

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

}  // namespace

const std::size_t checkpoint_rows_per_block = rows_per_block;

struct CheckpointFileWriter::Impl : FileWriter {
  using FileWriter::FileWriter;
};
CheckpointFileWriter::CheckpointFileWriter(const std::string& path, const CheckpointData& header,
                                           std::size_t num_tables)
    : impl_(std::make_unique<Impl>(path, header, num_tables)) {}
CheckpointFileWriter::~CheckpointFileWriter() = default;
void CheckpointFileWriter::begin_table(const std::string& name, int width, const std::vector<GlobalId>& ids) {
  impl_->begin_table(name, width, ids);
}
void CheckpointFileWriter::write_rows(const double* values, std::size_t n) { impl_->write_rows(values, n); }
void CheckpointFileWriter::finish() { impl_->finish(); }

struct CheckpointFileReader::Impl : FileReader {
  using FileReader::FileReader;
};
CheckpointFileReader::CheckpointFileReader(const std::string& path) : impl_(std::make_unique<Impl>(path)) {}
CheckpointFileReader::~CheckpointFileReader() = default;
const CheckpointData& CheckpointFileReader::header() const { return impl_->header(); }
const std::vector<std::string>& CheckpointFileReader::table_names() const { return impl_->table_names(); }
CheckpointTable CheckpointFileReader::begin_table(const std::string& name) { return impl_->begin_table(name); }
void CheckpointFileReader::read_rows(std::size_t n, double* out) { impl_->read_rows(n, out); }
void CheckpointFileReader::verify() const { impl_->verify(); }

}  // namespace shellfrac::io
