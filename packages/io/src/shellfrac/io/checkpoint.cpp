#include "shellfrac/io/checkpoint.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "shellfrac/core/digest.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::io {

namespace {

constexpr const char* format_tag = "shellfrac checkpoint 3";

/// Rows per HDF5 chunk of a table (chunked storage carries the Fletcher32 checksum of every chunk).
constexpr hsize_t rows_per_chunk = 4096;

/// Closes an HDF5 handle at scope exit.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  ~Handle() {
    if (id >= 0) close(id);
  }
  Handle(Handle&& o) noexcept : id(o.id), close(o.close) { o.id = -1; }
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

/// Every scalar, string and table in a fixed order (maps are sorted): the broadcast buffer and the checksummed text.
parallel::ByteWriter serialize(const CheckpointData& d) {
  parallel::ByteWriter w;
  w.put(std::int64_t(d.scalars.size()));
  for (const auto& [k, v] : d.scalars) w.put_string(k), w.put(v);
  w.put(std::int64_t(d.strings.size()));
  for (const auto& [k, v] : d.strings) w.put_string(k), w.put_string(v);
  w.put(std::int64_t(d.tables.size()));
  for (const auto& [k, t] : d.tables)
    w.put_string(k), w.put(std::int64_t(t.width)), w.put_vector(t.ids), w.put_vector(t.values);
  return w;
}

CheckpointData deserialize(const std::vector<char>& buffer) {
  CheckpointData d;
  parallel::ByteReader r(buffer);
  for (auto n = r.get<std::int64_t>(); n > 0; --n) {
    const auto k = r.get_string();
    d.scalars[k] = r.get<double>();
  }
  for (auto n = r.get<std::int64_t>(); n > 0; --n) {
    const auto k = r.get_string();
    d.strings[k] = r.get_string();
  }
  for (auto n = r.get<std::int64_t>(); n > 0; --n) {
    const auto k = r.get_string();
    CheckpointTable& t = d.tables[k];
    t.width = static_cast<int>(r.get<std::int64_t>());
    t.ids = r.get_vector<GlobalId>();
    t.values = r.get_vector<double>();
  }
  return d;
}

std::string checksum(parallel::ByteWriter serialized) {
  Digest digest;
  digest.add_bytes(serialized.buffer().data(), serialized.buffer().size());
  return digest.hex();
}

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

void write_file(const std::string& path, const CheckpointData& d) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
  const std::string tmp = path + ".tmp";
  // The 1.10 file format: the superblock and object headers (which hold the attributes) carry checksums too.
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_libver_bounds(fapl.id, H5F_LIBVER_V110, H5F_LIBVER_LATEST);
  Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id), H5Fclose);
  check(file.id >= 0, tmp, "cannot create the checkpoint file");
  write_string_attribute(file.id, "format", format_tag, tmp);
  write_string_attribute(file.id, "checksum", checksum(serialize(d)), tmp);
  {
    Handle g(H5Gcreate2(file.id, "scalars", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    for (const auto& [name, v] : d.scalars) {
      Handle space(H5Screate(H5S_SCALAR), H5Sclose);
      Handle attr(H5Acreate2(g.id, name.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
      check(attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &v) >= 0, tmp, "cannot write scalar " + name);
    }
  }
  {
    Handle g(H5Gcreate2(file.id, "strings", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    for (const auto& [name, v] : d.strings) write_string_attribute(g.id, name, v, tmp);
  }
  Handle tables(H5Gcreate2(file.id, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  for (const auto& [name, t] : d.tables) {
    Handle g(H5Gcreate2(tables.id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    check(g.id >= 0, tmp, "cannot create table " + name);
    const hsize_t rows = t.ids.size(), dims[2] = {rows, hsize_t(t.width)};
    {
      Handle space(H5Screate_simple(1, &rows, nullptr), H5Sclose);
      const Handle dcpl = dataset_properties(1, &rows);
      Handle ds(H5Dcreate2(g.id, "ids", H5T_NATIVE_INT64, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose);
      check(ds.id >= 0 && (rows == 0 || H5Dwrite(ds.id, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                   t.ids.data()) >= 0),
            tmp, "cannot write table " + name);
    }
    Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
    const Handle dcpl = dataset_properties(2, dims);
    Handle ds(H5Dcreate2(g.id, "values", H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT, dcpl.id, H5P_DEFAULT), H5Dclose);
    check(ds.id >= 0 && (t.values.empty() || H5Dwrite(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                                         t.values.data()) >= 0),
          tmp, "cannot write table " + name);
  }
  H5Gclose(tables.id);
  tables.id = -1;
  check(H5Fflush(file.id, H5F_SCOPE_GLOBAL) >= 0, tmp, "cannot flush the checkpoint file");
  H5Fclose(file.id);
  file.id = -1;
  check(std::rename(tmp.c_str(), path.c_str()) == 0, path, "cannot rename " + tmp + " to it");
}

CheckpointData read_file(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors are reported by us, not printed by HDF5
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file.id < 0) throw InputError(path + ": cannot open the checkpoint (missing, or not an HDF5 file)");
  const auto root_string = [&](const char* name) {
    Handle attr(H5Aopen(file.id, name, H5P_DEFAULT), H5Aclose);
    return attr.id < 0 ? std::string() : read_string_attribute(attr.id, path);
  };
  if (root_string("format") != format_tag)
    throw InputError(path + ": not a checkpoint of this version of shellfrac (no '" + std::string(format_tag) +
                     "' format tag; checkpoints of other versions or other programs are not read)");
  const std::string stored_checksum = root_string("checksum");
  CheckpointData d;
  {
    Handle g(H5Gopen2(file.id, "scalars", H5P_DEFAULT), H5Gclose);
    if (g.id < 0) throw InputError(path + ": checkpoint without /scalars");
    for (const auto& name : attribute_names(g.id)) {
      Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
      double v = 0;
      if (H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) < 0) throw InputError(path + ": unreadable scalar " + name);
      d.scalars[name] = v;
    }
  }
  {
    Handle g(H5Gopen2(file.id, "strings", H5P_DEFAULT), H5Gclose);
    if (g.id < 0) throw InputError(path + ": checkpoint without /strings");
    for (const auto& name : attribute_names(g.id)) {
      Handle attr(H5Aopen(g.id, name.c_str(), H5P_DEFAULT), H5Aclose);
      d.strings[name] = read_string_attribute(attr.id, path);
    }
  }
  Handle tables(H5Gopen2(file.id, "tables", H5P_DEFAULT), H5Gclose);
  if (tables.id < 0) throw InputError(path + ": checkpoint without /tables");
  for (const auto& name : member_names(tables.id)) {
    Handle g(H5Gopen2(tables.id, name.c_str(), H5P_DEFAULT), H5Gclose);
    Handle ids(H5Dopen2(g.id, "ids", H5P_DEFAULT), H5Dclose);
    Handle vals(H5Dopen2(g.id, "values", H5P_DEFAULT), H5Dclose);
    if (ids.id < 0 || vals.id < 0) throw InputError(path + ": table " + name + " lacks ids or values");
    Handle s1(H5Dget_space(ids.id), H5Sclose), s2(H5Dget_space(vals.id), H5Sclose);
    hsize_t n = 0, dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(s1.id) != 1 || H5Sget_simple_extent_ndims(s2.id) != 2)
      throw InputError(path + ": table " + name + " has the wrong shape");
    H5Sget_simple_extent_dims(s1.id, &n, nullptr);
    H5Sget_simple_extent_dims(s2.id, dims, nullptr);
    if (dims[0] != n) throw InputError(path + ": table " + name + ": ids and values differ in length");
    CheckpointTable t;
    t.width = static_cast<int>(dims[1]);
    t.ids.resize(n), t.values.resize(n * dims[1]);
    if ((n > 0 && H5Dread(ids.id, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.ids.data()) < 0) ||
        (!t.values.empty() && H5Dread(vals.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.values.data()) < 0))
      throw InputError(path + ": unreadable table " + name + " (a chunk fails its checksum: the file is corrupt)");
    if (!std::is_sorted(t.ids.begin(), t.ids.end())) throw InputError(path + ": table " + name + " is not sorted");
    d.tables[name] = std::move(t);
  }
  if (checksum(serialize(d)) != stored_checksum)
    throw InputError(path + ": the checkpoint's contents do not match its checksum: the file is corrupt (a damaged "
                     "copy or disk?); restart from another checkpoint");
  return d;
}

}  // namespace

const double* CheckpointTable::row(GlobalId id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return nullptr;
  return values.data() + (it - ids.begin()) * width;
}

void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm) {
  // Merge every table on rank 0, sorted by id.
  CheckpointData merged;
  merged.scalars = local.scalars, merged.strings = local.strings;
  for (const auto& [name, t] : local.tables) {
    const auto ids = parallel::all_gather(t.ids, comm);  // small compared to the values; keeps the code simple
    const auto values = parallel::all_gather(t.values, comm);
    const int width = static_cast<int>(parallel::max(double(t.width), comm));
    CheckpointTable& out = merged.tables[name];
    out.width = width;
    std::vector<std::size_t> order(ids.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
    for (std::size_t i : order) {
      if (!out.ids.empty() && out.ids.back() == ids[i]) continue;  // the same row from two ranks
      out.ids.push_back(ids[i]);
      out.values.insert(out.values.end(), values.begin() + i * width, values.begin() + (i + 1) * width);
    }
  }
  parallel::on_root_then_agree([&] { write_file(path, merged); }, 0, comm);
}

CheckpointData read_checkpoint(const std::string& path, MPI_Comm comm) {
  CheckpointData d;
  std::string error;
  if (parallel::rank(comm) == 0) {
    try {
      d = read_file(path);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  parallel::broadcast(error, 0, comm);
  if (!error.empty()) throw InputError(error);
  // Broadcast: scalars, strings, tables.
  parallel::ByteWriter w;
  if (parallel::rank(comm) == 0) w = serialize(d);
  parallel::broadcast(w.buffer(), 0, comm);
  if (parallel::rank(comm) != 0) d = deserialize(w.buffer());
  return d;
}

}  // namespace shellfrac::io
