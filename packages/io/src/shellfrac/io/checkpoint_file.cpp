#include "shellfrac/io/checkpoint_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <functional>
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

constexpr const char* format_tag = "shellfrac checkpoint 6";

/// Rows per HDF5 chunk of a table (chunked storage carries the Fletcher32 checksum of every chunk).
constexpr hsize_t rows_per_chunk = 4096;
/// The widest table a checkpoint may hold (the widest written: the plastic state, 9 values per quadrature point).
constexpr hsize_t max_table_width = 1024;
/// Rows of a table that a rank writes or reads at a time (whole chunks): what bounds its memory.
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

/// File access through MPI-IO on `comm`, metadata read collectively (one rank reads, all get it), the HDF5 1.10
/// format (the superblock and object headers, which hold the attributes, carry checksums too).
Handle parallel_access(MPI_Comm comm) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fapl_mpio(fapl.id, comm, MPI_INFO_NULL);
  H5Pset_all_coll_metadata_ops(fapl.id, true);
  H5Pset_coll_metadata_write(fapl.id, true);
  H5Pset_libver_bounds(fapl.id, H5F_LIBVER_V110, H5F_LIBVER_LATEST);
  return fapl;
}

/// Collective transfers (what parallel writes of filtered, i.e. checksummed, chunks require).
Handle collective_transfer() {
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  H5Pset_dxpl_mpio(dxpl.id, H5FD_MPIO_COLLECTIVE);
  return dxpl;
}

/// The file and memory selections of n rows of `width` values from file row `first` (none when n = 0; every rank
/// takes part in a collective transfer).
struct RowSelection {
  Handle file, memory;
  RowSelection(hid_t dataset, int rank, std::size_t first, std::size_t n, hsize_t width)
      : file(H5Dget_space(dataset), H5Sclose), memory(-1, H5Sclose) {
    const hsize_t start[2] = {first, 0}, count[2] = {std::max<hsize_t>(n, 1), width};
    memory.id = H5Screate_simple(rank, count, nullptr);
    if (n == 0) {
      H5Sselect_none(file.id), H5Sselect_none(memory.id);
      return;
    }
    H5Sselect_hyperslab(file.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
  }
};

void write_string_attribute(hid_t loc, const std::string& name, const std::string& value, bool& ok) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id, H5T_VARIABLE);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(loc, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* c = value.c_str();
  ok = ok && attr.id >= 0 && H5Awrite(attr.id, type.id, &c) >= 0;
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

/// The checksum of a file, the same whatever the number of ranks that wrote or read it: a digest of the header
/// and of each table's name, width and number of rows (in name order), combined with the sum over the rows of
/// the file of a digest of (file row, id, values). Each rank adds the rows it writes or reads; the sums of the
/// ranks are added (modulo 2^64, exact: independent of the order).
class Checksum {
 public:
  void add_header(parallel::ByteWriter header) { meta_.add_bytes(header.buffer().data(), header.buffer().size()); }
  void add_table(const std::string& name, int width, std::size_t num_rows) {
    meta_.add(name), meta_.add(std::int64_t(width)), meta_.add(std::int64_t(num_rows));
  }
  void add_row(std::size_t row, GlobalId id, const double* values, int width) {
    Digest d;
    d.add(std::int64_t(row)), d.add(std::int64_t(id)), d.add_bytes(values, sizeof(double) * std::size_t(width));
    rows_.combine(d);
  }
  /// Collective: the checksum of the whole file.
  std::string hex(MPI_Comm comm) const {
    std::uint64_t mine[2] = {rows_.lane(0), rows_.lane(1)}, all[2] = {0, 0};
    MPI_Allreduce(mine, all, 2, MPI_UINT64_T, MPI_SUM, comm);
    Digest total = meta_;
    total.combine(Digest::from_lanes(all[0], all[1]));
    return total.hex();
  }

 private:
  Digest meta_;
  Digest rows_ = Digest::from_lanes(0, 0);
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

/// Writes a checkpoint file on every rank of `comm`, one table at a time: `<path>.tmp`, renamed to `<path>` by
/// finish().
class FileWriter {
 public:
  FileWriter(const std::string& path, const CheckpointData& header, std::size_t num_tables, MPI_Comm comm)
      : path_(path), comm_(comm), file_(-1, H5Fclose), tables_(-1, H5Gclose), transfer_(collective_transfer()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
    // Never through a link: the final name must be a file of its own (or absent); the temporary file is made anew,
    // exclusively, by the first rank, then opened by HDF5 on every rank (which truncates the empty file it finds).
    parallel::on_root_then_agree([&] { files::require_result_path(path_), tmp_ = files::fresh_temporary(path_); }, 0,
                                 comm_);
    made_ = true;
    parallel::broadcast(tmp_, 0, comm_);
    const Handle fapl = parallel_access(comm_);
    file_.id = H5Fcreate(tmp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id);
    check(file_.id >= 0, tmp_, "cannot create the checkpoint file");
    bool ok = true;
    write_string_attribute(file_.id, "format", format_tag, ok);
    checksum_.add_header(serialize_header(header, num_tables));
    {
      Handle g(H5Gcreate2(file_.id, "scalars", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      for (const auto& [name, v] : header.scalars) {
        Handle space(H5Screate(H5S_SCALAR), H5Sclose);
        Handle attr(H5Acreate2(g.id, name.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
        ok = ok && attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &v) >= 0;
      }
    }
    {
      Handle g(H5Gcreate2(file_.id, "strings", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      for (const auto& [name, v] : header.strings) write_string_attribute(g.id, name, v, ok);
    }
    check(ok, tmp_, "cannot write the scalars and strings");
    tables_.id = H5Gcreate2(file_.id, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    check(tables_.id >= 0, tmp_, "cannot create /tables");
  }
  ~FileWriter() {  // not finished: an error (raised on every rank, so every rank is here); the temporary file goes
    if (!made_) return;
    values_ = Handle(-1, H5Dclose), ids_ = Handle(-1, H5Dclose);
    if (tables_.id >= 0) H5Gclose(tables_.id), tables_.id = -1;
    if (file_.id >= 0) H5Fclose(file_.id), file_.id = -1;
    if (parallel::rank(comm_) == 0) ::unlink(tmp_.c_str());
  }
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  /// Starts a table of num_rows rows; its ids and values follow by write_rows.
  void begin_table(const std::string& name, int width, std::size_t num_rows) {
    values_ = Handle(-1, H5Dclose), ids_ = Handle(-1, H5Dclose);
    table_name_ = name, width_ = width, num_rows_ = num_rows;
    Handle g(H5Gcreate2(tables_.id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    check(g.id >= 0, tmp_, "cannot create table " + name);
    checksum_.add_table(name, width, num_rows);
    const hsize_t rows = num_rows, dims[2] = {rows, hsize_t(width)};
    Handle id_space(H5Screate_simple(1, &rows, nullptr), H5Sclose), space(H5Screate_simple(2, dims, nullptr), H5Sclose);
    const Handle id_dcpl = dataset_properties(1, &rows), dcpl = dataset_properties(2, dims);
    ids_.id = H5Dcreate2(g.id, "ids", H5T_NATIVE_INT64, id_space.id, H5P_DEFAULT, id_dcpl.id, H5P_DEFAULT);
    values_.id = H5Dcreate2(g.id, "values", H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT);
    check(ids_.id >= 0 && values_.id >= 0, tmp_, "cannot write table " + name);
  }
  /// This rank's n rows from file row `first` on (collective).
  void write_rows(std::size_t first, const GlobalId* ids, const double* values, std::size_t n) {
    if (num_rows_ == 0) return;  // nothing to transfer (the same on every rank)
    for (std::size_t i = 0; i < n; ++i) checksum_.add_row(first + i, ids[i], values + i * std::size_t(width_), width_);
    const GlobalId no_id = 0;
    const double no_value = 0;
    const RowSelection id_rows(ids_.id, 1, first, n, 1), value_rows(values_.id, 2, first, n, hsize_t(width_));
    const bool ok = H5Dwrite(ids_.id, H5T_NATIVE_INT64, id_rows.memory.id, id_rows.file.id, transfer_.id,
                             n ? ids : &no_id) >= 0 &&
                    (width_ == 0 || H5Dwrite(values_.id, H5T_NATIVE_DOUBLE, value_rows.memory.id, value_rows.file.id,
                                             transfer_.id, n ? values : &no_value) >= 0);
    check(ok, tmp_, "cannot write table " + table_name_);
  }

  /// The checksum, then flush, close and rename.
  void finish() {
    values_ = Handle(-1, H5Dclose), ids_ = Handle(-1, H5Dclose);
    bool ok = true;
    write_string_attribute(file_.id, "checksum", checksum_.hex(comm_), ok);
    check(ok, tmp_, "cannot write the checksum");
    H5Gclose(tables_.id), tables_.id = -1;
    check(H5Fflush(file_.id, H5F_SCOPE_GLOBAL) >= 0, tmp_, "cannot flush the checkpoint file");
    const bool closed = H5Fclose(file_.id) >= 0;
    file_.id = -1;
    check(closed, tmp_, "cannot close the checkpoint file");
    parallel::on_root_then_agree(
        [&] {
          files::require_result_path(path_);
          if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
            throw OutputError(path_ + ": cannot rename " + tmp_ + " to it (disk full, quota, or the directory is gone?)");
        },
        0, comm_);
    made_ = false;
  }

 private:
  /// A failed write on any rank names the file and stops the run on every rank with the output-error exit code
  /// (the previous checkpoint is untouched: the file being written is a temporary one). Collective.
  void check(bool ok, const std::string& file, const std::string& what) const {
    if (parallel::any(!ok, comm_)) throw OutputError(file + ": " + what + " (disk full, quota, or the directory is gone?)");
  }

  std::string path_, tmp_;
  MPI_Comm comm_;
  bool made_ = false;  ///< the temporary file exists and is ours
  Handle file_, tables_, transfer_;
  Checksum checksum_;
  Handle ids_{-1, H5Dclose}, values_{-1, H5Dclose};  // the table being written
  std::string table_name_;
  int width_ = 0;
  std::size_t num_rows_ = 0;
};

/// Reads a checkpoint file on every rank of `comm`: the header at once, then one table at a time.
class FileReader {
 public:
  FileReader(const std::string& path, MPI_Comm comm)
      : path_(path), comm_(comm), file_(-1, H5Fclose), tables_(-1, H5Gclose), transfer_(collective_transfer()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
    // HDF5 would open a file that is not HDF5 on some ranks only if they saw different files: asked of every rank.
    const bool exists = parallel::rank(comm_) != 0 || H5Fis_hdf5(path.c_str()) > 0;
    refuse(!exists, path + ": cannot open the checkpoint (missing, or not an HDF5 file)");
    const Handle fapl = parallel_access(comm_);
    file_.id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id);
    refuse(file_.id < 0, path + ": cannot open the checkpoint (missing, or not an HDF5 file)");
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
    read_header();
    tables_.id = H5Gopen2(file_.id, "tables", H5P_DEFAULT);
    if (tables_.id < 0) throw InputError(path + ": checkpoint without /tables");
    table_names_ = member_names(tables_.id);
    checksum_.add_header(serialize_header(header_, table_names_.size()));
  }
  const CheckpointData& header() const { return header_; }
  const std::vector<std::string>& table_names() const { return table_names_; }

  /// Starts reading table `name` (the names in table_names() order): its width and number of rows.
  void begin_table(const std::string& name, int& width, std::size_t& num_rows) {
    values_ = Handle(-1, H5Dclose), ids_ = Handle(-1, H5Dclose);
    table_name_ = name, have_last_ = false;
    Handle g(H5Gopen2(tables_.id, name.c_str(), H5P_DEFAULT), H5Gclose);
    ids_.id = H5Dopen2(g.id, "ids", H5P_DEFAULT);
    values_.id = H5Dopen2(g.id, "values", H5P_DEFAULT);
    if (ids_.id < 0 || values_.id < 0) throw InputError(path_ + ": table " + name + " lacks ids or values");
    Handle s1(H5Dget_space(ids_.id), H5Sclose), s2(H5Dget_space(values_.id), H5Sclose);
    hsize_t n = 0, dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(s1.id) != 1 || H5Sget_simple_extent_ndims(s2.id) != 2)
      throw InputError(path_ + ": table " + name + " has the wrong shape");
    H5Sget_simple_extent_dims(s1.id, &n, nullptr);
    H5Sget_simple_extent_dims(s2.id, dims, nullptr);
    if (dims[0] != n) throw InputError(path_ + ": table " + name + ": ids and values differ in length");
    // Sizes are believed only as far as the file holds the data: a damaged or forged header must not make us
    // allocate what the file does not contain.
    if (dims[1] > max_table_width || H5Dget_storage_size(ids_.id) < n * sizeof(GlobalId) ||
        H5Dget_storage_size(values_.id) < n * dims[1] * sizeof(double))
      throw InputError(path_ + ": table " + name + " declares " + std::to_string(n) + " rows of " +
                       std::to_string(dims[1]) + " values, more than the file holds: the file is corrupt");
    width = width_ = static_cast<int>(dims[1]);
    num_rows = num_rows_ = std::size_t(n);
    checksum_.add_table(name, width, num_rows);
  }
  /// This rank's n rows from file row `first` on (collective).
  void read_rows(std::size_t first, std::size_t n, std::vector<GlobalId>& ids, std::vector<double>& values) {
    ids.resize(n), values.resize(n * std::size_t(width_));
    if (num_rows_ == 0) return;  // nothing to transfer (the same on every rank)
    GlobalId no_id = 0;
    double no_value = 0;
    const RowSelection id_rows(ids_.id, 1, first, n, 1), value_rows(values_.id, 2, first, n, hsize_t(width_));
    const bool ok = H5Dread(ids_.id, H5T_NATIVE_INT64, id_rows.memory.id, id_rows.file.id, transfer_.id,
                            n ? ids.data() : &no_id) >= 0 &&
                    (width_ == 0 || H5Dread(values_.id, H5T_NATIVE_DOUBLE, value_rows.memory.id, value_rows.file.id,
                                            transfer_.id, n ? values.data() : &no_value) >= 0);
    refuse(!ok, path_ + ": unreadable table " + table_name_ + " (a chunk fails its checksum: the file is corrupt)");
    bool sorted = std::adjacent_find(ids.begin(), ids.end(), std::greater_equal<>()) == ids.end();
    if (n > 0 && have_last_) sorted = sorted && ids.front() > last_id_;
    if (n > 0) have_last_ = true, last_id_ = ids.back();
    refuse(!sorted, path_ + ": table " + table_name_ + " is not sorted");
    for (std::size_t i = 0; i < n; ++i) checksum_.add_row(first + i, ids[i], values.data() + i * std::size_t(width_), width_);
  }
  /// After every table: the contents against the stored checksum (collective).
  void verify() const {
    if (checksum_.hex(comm_) != stored_checksum_)
      throw InputError(path_ + ": the checkpoint's contents do not match its checksum: the file is corrupt (a "
                               "damaged copy or disk?); restart from another checkpoint");
  }

 private:
  /// InputError `message` on every rank if `bad` on any. Collective.
  void refuse(bool bad, const std::string& message) const {
    if (parallel::any(bad, comm_)) throw InputError(message);
  }
  void read_header() {
    {
      Handle g(H5Gopen2(file_.id, "scalars", H5P_DEFAULT), H5Gclose);
      if (g.id < 0) throw InputError(path_ + ": checkpoint without /scalars");
      for (const auto& name : attribute_names(g.id)) {
        Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
        double v = 0;
        if (H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) < 0) throw InputError(path_ + ": unreadable scalar " + name);
        header_.scalars[name] = v;
      }
    }
    Handle g(H5Gopen2(file_.id, "strings", H5P_DEFAULT), H5Gclose);
    if (g.id < 0) throw InputError(path_ + ": checkpoint without /strings");
    for (const auto& name : attribute_names(g.id)) {
      Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
      header_.strings[name] = read_string_attribute(attr.id, path_);
    }
  }

  std::string path_;
  MPI_Comm comm_;
  Handle file_, tables_, transfer_;
  std::string stored_checksum_;
  CheckpointData header_;
  std::vector<std::string> table_names_;
  Checksum checksum_;
  Handle ids_{-1, H5Dclose}, values_{-1, H5Dclose};  // the table being read
  std::string table_name_;
  int width_ = 0;
  std::size_t num_rows_ = 0;
  bool have_last_ = false;  ///< this rank has read rows of the table: last_id_ is the last id
  GlobalId last_id_ = 0;
};

}  // namespace

const std::size_t checkpoint_rows_per_block = rows_per_block;

struct CheckpointFileWriter::Impl : FileWriter {
  using FileWriter::FileWriter;
};
CheckpointFileWriter::CheckpointFileWriter(const std::string& path, const CheckpointData& header,
                                           std::size_t num_tables, MPI_Comm comm)
    : impl_(std::make_unique<Impl>(path, header, num_tables, comm)) {}
CheckpointFileWriter::~CheckpointFileWriter() = default;
void CheckpointFileWriter::begin_table(const std::string& name, int width, std::size_t num_rows) {
  impl_->begin_table(name, width, num_rows);
}
void CheckpointFileWriter::write_rows(std::size_t first, const GlobalId* ids, const double* values, std::size_t n) {
  impl_->write_rows(first, ids, values, n);
}
void CheckpointFileWriter::finish() { impl_->finish(); }

struct CheckpointFileReader::Impl : FileReader {
  using FileReader::FileReader;
};
CheckpointFileReader::CheckpointFileReader(const std::string& path, MPI_Comm comm)
    : impl_(std::make_unique<Impl>(path, comm)) {}
CheckpointFileReader::~CheckpointFileReader() = default;
const CheckpointData& CheckpointFileReader::header() const { return impl_->header(); }
const std::vector<std::string>& CheckpointFileReader::table_names() const { return impl_->table_names(); }
void CheckpointFileReader::begin_table(const std::string& name, int& width, std::size_t& num_rows) {
  impl_->begin_table(name, width, num_rows);
}
void CheckpointFileReader::read_rows(std::size_t first, std::size_t n, std::vector<GlobalId>& ids,
                                     std::vector<double>& values) {
  impl_->read_rows(first, n, ids, values);
}
void CheckpointFileReader::verify() const { impl_->verify(); }

}  // namespace shellfrac::io
