#include "shellfrac/meshio/exodus_mesh_io.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/exodus/exodus_api.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"

namespace shellfrac::meshio {


namespace {

/// Largest entity count accepted from a file before allocating (a hostile header must not exhaust memory).
constexpr std::int64_t max_count = std::int64_t{1} << 31;

/// Per-block facts the reader needs after the block loop.
struct BlockInfo {
  std::int64_t id = 0;
  std::int64_t count = 0;
  bool shell = false;  ///< TRISHELL*: side numbers 3,4,5 are the edges
};

/// Nodes per element implied by an Exodus triangle type name, 0 if the type is not a supported triangle,
/// -1 if the name does not fix it (TRI, TRIANGLE, TRISHELL). Sets `shell`.
int triangle_type_nodes(const std::string& type, bool& shell) {
  const std::string t = exodus::upper(type);
  shell = t.rfind("TRISHELL", 0) == 0;
  if (t == "TRI3" || t == "TRISHELL3" || t == "TRIANGLE3") return 3;
  if (t == "TRI6" || t == "TRISHELL6" || t == "TRIANGLE6") return 6;
  if (t == "TRI" || t == "TRIANGLE" || t == "TRISHELL") return -1;
  return 0;
}

/// Reads an entity count header value and checks it is sane.
std::int64_t checked_count(std::int64_t n, const std::string& path, const char* what) {
  SHELLFRAC_INPUT_REQUIRE(n >= 0 && n < max_count, path << ": invalid " << what << " count " << n);
  return n;
}

/// In a netCDF classic file (no compression) every declared entity is stored: n entities of at least
/// `bytes_each` bytes must fit in the file's `file_bytes` (0 = no such bound: netCDF-4 / HDF5 file). Guards
/// the allocations sized by header values against a hostile header.
void check_stored(std::int64_t n, std::uint64_t bytes_each, std::uint64_t file_bytes, const std::string& path,
                  const std::string& what) {
  SHELLFRAC_INPUT_REQUIRE(file_bytes == 0 || static_cast<std::uint64_t>(n) <= file_bytes / bytes_each,
                          path << ": the file declares " << n << " " << what << ", more than its " << file_bytes
                               << " bytes can hold (truncated or corrupt file)");
}

/// Exodus entity id -> SerialMesh id (positive int).
int checked_id(std::int64_t id, const std::string& path, const char* what) {
  SHELLFRAC_INPUT_REQUIRE(id > 0 && id <= exodus::max_stored_int,
                          path << ": " << what << " has id " << id << "; ids must be positive 32-bit integers");
  return static_cast<int>(id);
}

std::string default_name(const std::string& name, const char* prefix, std::int64_t id) {
  return name.empty() ? std::string(prefix) + "_" + std::to_string(id) : name;
}

/// Ids of all entities of `type` (count from the header).
std::vector<std::int64_t> get_ids(int exo_id, ex_entity_type type, std::int64_t count, const std::string& path,
                                  const char* what) {
  std::vector<std::int64_t> ids(static_cast<std::size_t>(count));
  if (count > 0) SHELLFRAC_EXO_INPUT_CHECK(ex_get_ids(exo_id, type, ids.data()), path << ": cannot read " << what << " ids");
  return ids;
}

/// Reads one set's entries (and extra list for side sets) as 1-based file values.
void get_set(int exo_id, ex_entity_type type, std::int64_t id, std::vector<std::int64_t>& entries,
             std::vector<std::int64_t>* extra, const std::string& path, const std::string& what,
             std::uint64_t file_bytes) {
  std::int64_t n = 0, ndf = 0;
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_set_param(exo_id, type, id, &n, &ndf), path << ": cannot read " << what);
  checked_count(n, path, what.c_str());
  check_stored(n, extra ? 8 : 4, file_bytes, path, "entries in " + what);
  entries.assign(static_cast<std::size_t>(n), 0);
  if (extra) extra->assign(static_cast<std::size_t>(n), 0);
  if (n > 0)
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_set(exo_id, type, id, entries.data(), extra ? extra->data() : nullptr),
                              path << ": cannot read the entries of " << what);
}

/// 1-based file indices -> sorted, unique 0-based indices; each must be in [1, n].
std::vector<GlobalId> to_sorted_indices(const std::vector<std::int64_t>& v, std::int64_t n, const std::string& path,
                                        const std::string& what, const char* entity) {
  std::vector<GlobalId> out;
  out.reserve(v.size());
  for (auto x : v) {
    SHELLFRAC_INPUT_REQUIRE(x >= 1 && x <= n, path << ": " << what << " refers to " << entity << " " << x
                                                   << ", but the file has " << n << " " << entity << "s");
    out.push_back(x - 1);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Big-endian reader over the header of a netCDF classic file, bounds-checked against the file size.
class NetcdfHeader {
 public:
  NetcdfHeader(const std::string& path, std::uintmax_t size) : path_(path), in_(path, std::ios::binary), size_(size) {}

  std::uint64_t remaining() const { return size_ - pos_; }
  std::uint64_t position() const { return pos_; }

  /// Reads an n-byte (4 or 8) unsigned big-endian integer.
  std::uint64_t get(int n, const char* what) {
    SHELLFRAC_INPUT_REQUIRE(remaining() >= static_cast<std::uint64_t>(n),
                            path_ << ": truncated netCDF header at byte " << pos_ << " (reading " << what << ")");
    unsigned char b[8] = {};
    in_.read(reinterpret_cast<char*>(b), n);
    SHELLFRAC_INPUT_REQUIRE(in_.gcount() == n, path_ << ": cannot read the netCDF header at byte " << pos_);
    pos_ += static_cast<std::uint64_t>(n);
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 8) | b[i];
    return v;
  }
  /// Reads n bytes (which must be in the file) as a string.
  std::string text(std::uint64_t n, const char* what) {
    SHELLFRAC_INPUT_REQUIRE(n <= remaining(), path_ << ": truncated netCDF header at byte " << pos_ << " (" << what
                                                    << " of " << n << " bytes)");
    std::string s(static_cast<std::size_t>(n), '\0');
    in_.read(s.data(), static_cast<std::streamsize>(n));
    SHELLFRAC_INPUT_REQUIRE(in_.gcount() == static_cast<std::streamsize>(n),
                            path_ << ": cannot read the netCDF header at byte " << pos_);
    pos_ += n;
    return s;
  }
  /// Skips n bytes (which must be in the file).
  void skip(std::uint64_t n, const char* what) {
    SHELLFRAC_INPUT_REQUIRE(n <= remaining(), path_ << ": truncated netCDF header at byte " << pos_ << " (" << what
                                                    << " of " << n << " bytes)");
    in_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
    pos_ += n;
  }
  /// A count of items of at least min_bytes each that must fit in the rest of the file.
  std::uint64_t count(int n, std::uint64_t min_bytes, const char* what) {
    const std::uint64_t c = get(n, what);
    SHELLFRAC_INPUT_REQUIRE(c <= remaining() / min_bytes,
                            path_ << ": corrupt or truncated netCDF header: " << what << " " << c << " at byte " << pos_ - n
                                  << " is more than the " << size_ << "-byte file can hold");
    return c;
  }

 private:
  const std::string& path_;
  std::ifstream in_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
};

/// Checks the header of a netCDF classic file (CDF-1, CDF-2 or CDF-5; "NetCDF Classic Format Specification")
/// before the netCDF library parses it: every count must fit in the file, every type and dimension id must be
/// valid. libnetcdf allocates what a header declares before checking it against the file: a 2.6 kB file
/// declaring a variable with 822083584 dimensions made it allocate and touch 6.5 GB. Then the data of every
/// fixed-size variable must lie inside the file (the library writes files to their full size; reading past
/// the end of a truncated file gives zeros, hence misleading messages). Returns false when the file is not a
/// netCDF classic file (netCDF-4 / HDF5 files are left to the library).
bool check_netcdf_classic_header(const std::string& path, std::uintmax_t size) {
  NetcdfHeader h(path, size);
  if (size < 4) return false;
  const std::uint64_t magic = h.get(4, "the magic number");
  if ((magic >> 8) != 0x434446u) return false;  // "CDF"
  const int version = static_cast<int>(magic & 0xffu);
  SHELLFRAC_INPUT_REQUIRE(version == 1 || version == 2 || version == 5,
                          path << ": netCDF classic file of unknown version " << version);
  const int nn = version == 5 ? 8 : 4;  // size of counts, lengths and (CDF-5) dimension ids
  constexpr std::uint64_t tag_dimension = 10, tag_variable = 11, tag_attribute = 12;
  h.get(nn, "the record count");
  // A list is ABSENT (two zeros) or tag + count; `tag` is the expected tag.
  auto list_count = [&](std::uint64_t tag, std::uint64_t min_bytes, const char* what) -> std::uint64_t {
    const std::uint64_t t = h.get(4, what);
    if (t == 0) {
      SHELLFRAC_INPUT_REQUIRE(h.get(nn, what) == 0, path << ": corrupt netCDF header: absent " << what
                                                         << " with a non-zero count");
      return 0;
    }
    SHELLFRAC_INPUT_REQUIRE(t == tag, path << ": corrupt netCDF header: bad tag " << t << " for the " << what
                                           << " at byte " << h.position() - 4);
    return h.count(nn, min_bytes, what);
  };
  auto name = [&](const char* what) {
    const std::uint64_t n = h.count(nn, 1, what);
    std::string text = h.text(n, what);
    h.skip((n + 3) / 4 * 4 - n, what);
    return text;
  };
  auto type_size = [&](std::uint64_t type) -> std::uint64_t {
    switch (type) {
      case 1: case 2: case 7: return 1;  // byte, char, ubyte
      case 3: case 8: return 2;          // short, ushort
      case 4: case 5: case 9: return 4;  // int, float, uint
      case 6: case 10: case 11: return 8;  // double, int64, uint64
      default: break;
    }
    SHELLFRAC_INPUT_REQUIRE(false, path << ": corrupt netCDF header: unknown data type " << type << " at byte "
                                        << h.position() - 4);
    return 0;
  };
  auto attributes = [&](const char* what) {
    const std::uint64_t n = list_count(tag_attribute, static_cast<std::uint64_t>(2 * nn + 4), what);
    for (std::uint64_t i = 0; i < n; ++i) {
      name("attribute name length");
      const std::uint64_t bytes = type_size(h.get(4, "attribute type"));
      const std::uint64_t values = h.count(nn, bytes, "attribute value count");
      h.skip((values * bytes + 3) / 4 * 4, "attribute values");
    }
  };
  const std::uint64_t num_dims = list_count(tag_dimension, static_cast<std::uint64_t>(2 * nn), "dimension list");
  std::vector<std::uint64_t> dim_length(static_cast<std::size_t>(num_dims));
  for (auto& len : dim_length) {
    name("dimension name length");
    len = h.get(nn, "dimension length");  // 0: the record (unlimited) dimension
  }
  attributes("global attribute list");
  const int offset_size = version == 1 ? 4 : 8;
  const std::uint64_t num_vars =
      list_count(tag_variable, static_cast<std::uint64_t>(3 * nn + 4 + 4 + nn + offset_size), "variable list");
  constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();
  for (std::uint64_t i = 0; i < num_vars; ++i) {
    const std::string var = name("variable name length");
    const std::uint64_t rank = h.count(nn, static_cast<std::uint64_t>(nn), "variable dimension count");
    bool record = false;
    std::uint64_t values = 1;
    for (std::uint64_t k = 0; k < rank; ++k) {
      const std::uint64_t dim = h.get(nn, "dimension id");
      SHELLFRAC_INPUT_REQUIRE(dim < num_dims, path << ": corrupt netCDF header: variable '" << var
                                                   << "' refers to dimension id " << dim << " beyond the " << num_dims
                                                   << " dimensions");
      const std::uint64_t len = dim_length[static_cast<std::size_t>(dim)];
      if (k == 0 && len == 0) record = true;
      values = len == 0 || values <= saturated / len ? values * len : saturated;
    }
    attributes("variable attribute list");
    const std::uint64_t bytes_each = type_size(h.get(4, "variable type"));
    h.get(nn, "variable size");
    const std::uint64_t begin = h.get(offset_size, "variable offset");
    if (record || values == 0) continue;  // record variables grow with the file; empty ones store nothing
    const std::uint64_t bytes = values <= saturated / bytes_each ? values * bytes_each : saturated;
    const std::uint64_t end = begin <= saturated - bytes ? begin + bytes : saturated;
    SHELLFRAC_INPUT_REQUIRE(end <= size, path << ": truncated file: the data of variable '" << var << "' end at byte "
                                              << end << ", but the file has " << size << " bytes");
  }
  return true;
}

/// An open netCDF id, closed on destruction.
struct NetcdfFile {
  int id = -1;
  ~NetcdfFile() {
    if (id >= 0) nc_close(id);
  }
};

/// Checks the parts of the file's netCDF structure that libexodusII (6.02) trusts when it reads into buffers
/// sized from other parts, before any Exodus call. Each of these was a buffer overflow in the library (heap or
/// stack; crashes or silent memory corruption), found with fuzz_exodus, valgrind and ASan
/// (docs/hostile_input.md):
///  * variables it reads whole (nc_get_var) into buffers sized by the Exodus dimensions: coordinates,
///    connectivity, id and status arrays, set entries; each must have exactly the size of its dimensions;
///  * global attributes it reads into a single number (version, word size, ...): exactly one value;
///  * the element type attribute of a block, read into a 33-character buffer: at most 32 characters.
/// Files that netCDF cannot open are left to ex_open (which reports them).
void check_exodus_structure(const std::string& path) {
  NetcdfFile nc;
  if (nc_open(path.c_str(), NC_NOWRITE, &nc.id) != NC_NOERR) {
    nc.id = -1;
    return;
  }
  for (const char* att : {"api_version", "api version", "version", "floating_point_word_size",
                          "floating point word size", "file_size", "int64_status", "maximum_name_length"}) {
    std::size_t len = 0;
    if (nc_inq_attlen(nc.id, NC_GLOBAL, att, &len) == NC_NOERR)
      SHELLFRAC_INPUT_REQUIRE(len == 1, path << ": corrupt Exodus file: global attribute '" << att << "' has " << len
                                             << " values instead of one");
  }
  // Length of a dimension by name (0 if absent: Exodus then has no data of that kind).
  auto dim_length = [&](const std::string& name) -> std::uint64_t {
    int dim = -1;
    std::size_t len = 0;
    if (nc_inq_dimid(nc.id, name.c_str(), &dim) != NC_NOERR || nc_inq_dimlen(nc.id, dim, &len) != NC_NOERR) return 0;
    return len;
  };
  // a * b, saturated (dimension lengths come from the file).
  auto times = [](std::uint64_t a, std::uint64_t b) {
    return a == 0 || b <= std::numeric_limits<std::uint64_t>::max() / a ? a * b
                                                                        : std::numeric_limits<std::uint64_t>::max();
  };
  // Expected number of values of a variable that Exodus reads whole; nullopt if it is not one of those.
  auto expected_size = [&](const std::string& var) -> std::optional<std::uint64_t> {
    std::string k;
    auto numbered = [&](const char* prefix) {
      const std::size_t n = std::strlen(prefix);
      if (var.size() <= n || var.compare(0, n, prefix) != 0) return false;
      k = var.substr(n);
      return std::all_of(k.begin(), k.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (var == "coordx" || var == "coordy" || var == "coordz") return dim_length("num_nodes");
    if (var == "coord") return times(dim_length("num_dim"), dim_length("num_nodes"));
    if (var == "eb_status" || numbered("eb_prop")) return dim_length("num_el_blk");
    if (var == "ns_status" || numbered("ns_prop")) return dim_length("num_node_sets");
    if (var == "ss_status" || numbered("ss_prop")) return dim_length("num_side_sets");
    if (var == "els_status" || numbered("els_prop")) return dim_length("num_elem_sets");
    if (numbered("connect")) return times(dim_length("num_el_in_blk" + k), dim_length("num_nod_per_el" + k));
    if (numbered("node_ns")) return dim_length("num_nod_ns" + k);
    if (numbered("elem_ss") || numbered("side_ss")) return dim_length("num_side_ss" + k);
    if (numbered("elem_els")) return dim_length("num_ele_els" + k);
    return std::nullopt;
  };
  int num_vars = 0;
  SHELLFRAC_INPUT_REQUIRE(nc_inq_nvars(nc.id, &num_vars) == NC_NOERR, path << ": cannot read the netCDF variables");
  for (int v = 0; v < num_vars; ++v) {
    char name_buf[NC_MAX_NAME + 1] = {};
    int ndims = 0;
    if (nc_inq_varname(nc.id, v, name_buf) != NC_NOERR || nc_inq_varndims(nc.id, v, &ndims) != NC_NOERR) continue;
    const std::string name = name_buf;
    const std::optional<std::uint64_t> expected = expected_size(name);
    if (expected) {
      std::vector<int> dims(static_cast<std::size_t>(std::max(ndims, 0)));
      SHELLFRAC_INPUT_REQUIRE(nc_inq_vardimid(nc.id, v, dims.data()) == NC_NOERR,
                              path << ": cannot read the dimensions of variable '" << name << "'");
      std::uint64_t size = 1;
      for (int d : dims) {
        std::size_t len = 0;
        SHELLFRAC_INPUT_REQUIRE(nc_inq_dimlen(nc.id, d, &len) == NC_NOERR,
                                path << ": cannot read the dimensions of variable '" << name << "'");
        size = times(size, len);
      }
      SHELLFRAC_INPUT_REQUIRE(size == *expected, path << ": corrupt Exodus file: variable '" << name << "' has "
                                                      << size << " values, but its Exodus dimensions give "
                                                      << *expected);
    }
    std::size_t len = 0;
    if (name.rfind("connect", 0) == 0 && nc_inq_attlen(nc.id, v, "elem_type", &len) == NC_NOERR)
      SHELLFRAC_INPUT_REQUIRE(len <= MAX_STR_LENGTH, path << ": corrupt Exodus file: the element type of variable '"
                                                          << name << "' is " << len << " characters long (at most "
                                                          << MAX_STR_LENGTH << ")");
  }
}

mesh::SerialMesh read_exodus_impl(const std::string& path) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(std::filesystem::is_regular_file(path, ec), path << ": Exodus file not found");
  const std::uintmax_t file_size = std::filesystem::file_size(path, ec);
  SHELLFRAC_INPUT_REQUIRE(!ec, path << ": cannot read the file size (" << ec.message() << ")");
  // Upper bound for counts read from the header (0 = none: netCDF-4 files may be compressed).
  const std::uint64_t stored_bytes = check_netcdf_classic_header(path, file_size) ? file_size : 0;
  check_exodus_structure(path);
  exodus::File file = exodus::open_read(path);
  SHELLFRAC_INPUT_REQUIRE(file.is_open(), path << ": cannot open as an Exodus II file (" << exodus::last_error() << ")");
  const int id = file.id();

  ex_init_params p{};
  SHELLFRAC_EXO_INPUT_CHECK(ex_get_init_ext(id, &p), path << ": cannot read the Exodus header");
  SHELLFRAC_INPUT_REQUIRE(p.num_dim == 2 || p.num_dim == 3,
                          path << ": " << p.num_dim << "-dimensional coordinates; a shell mesh needs 2 or 3");
  const std::int64_t num_nodes = checked_count(p.num_nodes, path, "node");
  const std::int64_t num_elem = checked_count(p.num_elem, path, "element");
  checked_count(p.num_elem_blk, path, "element block");
  checked_count(p.num_node_sets, path, "node set");
  checked_count(p.num_side_sets, path, "side set");
  checked_count(p.num_elem_sets, path, "element set");
  SHELLFRAC_INPUT_REQUIRE(num_elem > 0 && p.num_elem_blk > 0, path << ": the file has no elements");
  check_stored(num_nodes, 4 * static_cast<std::uint64_t>(p.num_dim), stored_bytes, path, "nodes");
  check_stored(num_elem, 3 * 4, stored_bytes, path, "elements");
  check_stored(p.num_elem_blk, 4, stored_bytes, path, "element blocks");
  check_stored(p.num_node_sets, 4, stored_bytes, path, "node sets");
  check_stored(p.num_side_sets, 4, stored_bytes, path, "side sets");
  check_stored(p.num_elem_sets, 4, stored_bytes, path, "element sets");

  mesh::SerialMesh m;
  m.source = path;

  // The file's element and node ids (its id maps; 1..n without them). shellfrac numbers elements and nodes by their
  // position in the file, so two entities with one id would be two things under one name: refused. Messages name
  // them by these ids (mesh::FileIds), kept when they are not the positions.
  for (const auto& [type, count, what] : {std::tuple<ex_entity_type, std::int64_t, const char*>{EX_ELEM_MAP, num_elem,
                                                                                               "element"},
                                          std::tuple<ex_entity_type, std::int64_t, const char*>{EX_NODE_MAP, num_nodes,
                                                                                               "node"}}) {
    std::vector<std::int64_t> ids(static_cast<std::size_t>(count));
    if (count > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_id_map(id, type, ids.data()), path << ": cannot read the " << what << " id map");
    std::vector<std::pair<std::int64_t, std::size_t>> sorted;
    sorted.reserve(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(ids[i] > 0, path << ": " << what << " " << i + 1 << " has the id " << ids[i]
                                               << " in the file's " << what << " id map; ids must be positive");
      sorted.emplace_back(ids[i], i);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t k = 1; k < sorted.size(); ++k)
      SHELLFRAC_INPUT_REQUIRE(sorted[k].first != sorted[k - 1].first,
                              path << ": the " << what << " id " << sorted[k].first << " is given to " << what << "s "
                                   << sorted[k - 1].second + 1 << " and " << sorted[k].second + 1
                                   << " (positions in the file) by its " << what << " id map; ids must be unique");
    bool positions = true;
    for (std::size_t i = 0; i < ids.size() && positions; ++i) positions = ids[i] == static_cast<std::int64_t>(i) + 1;
    if (!positions) (type == EX_ELEM_MAP ? m.element_ids : m.node_ids).ids = std::move(ids);
  }

  // Coordinates.
  {
    std::vector<double> x(static_cast<std::size_t>(num_nodes)), y(x.size()), z(x.size(), 0.0);
    if (num_nodes > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_coord(id, x.data(), y.data(), p.num_dim == 3 ? z.data() : nullptr),
                                path << ": cannot read the node coordinates");
    m.coords.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) m.coords[i] = {x[i], y[i], z[i]};
  }

  // Element blocks, in file order; elements are numbered in that order.
  const auto block_ids = get_ids(id, EX_ELEM_BLOCK, p.num_elem_blk, path, "element block");
  const auto block_names = exodus::get_names(id, EX_ELEM_BLOCK, p.num_elem_blk, path);
  std::vector<BlockInfo> blocks;
  std::int64_t total = 0;
  std::size_t first_block_with_elements = 0;
  m.nodes_per_element = 0;
  for (std::size_t b = 0; b < block_ids.size(); ++b) {
    const std::string name = default_name(block_names[b], "block", block_ids[b]);
    const std::string what = "element block " + std::to_string(block_ids[b]) + " ('" + name + "')";
    ex_block blk{};
    blk.id = block_ids[b];
    blk.type = EX_ELEM_BLOCK;
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_block_param(id, &blk), path << ": cannot read " << what);
    blk.topology[MAX_STR_LENGTH] = '\0';
    const std::string type = blk.topology;
    checked_count(blk.num_entry, path, what.c_str());
    check_stored(blk.num_entry, 3 * 4, stored_bytes, path, "elements in " + what);
    bool shell = false;
    int npe = triangle_type_nodes(type, shell);
    if (blk.num_entry == 0) {  // Exodus stores empty blocks with type "NULL" and 0 nodes per element
      m.blocks.push_back({name, checked_id(block_ids[b], path, what.c_str())});
      blocks.push_back({block_ids[b], 0, shell});
      continue;
    }
    if (npe == -1 && (blk.num_nodes_per_entry == 3 || blk.num_nodes_per_entry == 6))
      npe = static_cast<int>(blk.num_nodes_per_entry);
    SHELLFRAC_INPUT_REQUIRE(npe > 0 && npe == blk.num_nodes_per_entry,
                            path << ": " << what << " has unsupported element type '" << type << "' with "
                                 << blk.num_nodes_per_entry
                                 << " nodes per element; shell meshes need TRI3/TRISHELL3 or TRI6/TRISHELL6");
    if (blk.num_entry > 0) {
      if (m.nodes_per_element == 0) {
        m.nodes_per_element = npe;
        first_block_with_elements = b;
      }
      SHELLFRAC_INPUT_REQUIRE(npe == m.nodes_per_element,
                              path << ": " << what << " has " << npe << "-node elements but element block "
                                   << block_ids[first_block_with_elements] << " has " << m.nodes_per_element
                                   << "-node elements; mixed TRI3/TRI6 blocks are not supported");
    }
    total += blk.num_entry;
    SHELLFRAC_INPUT_REQUIRE(total <= num_elem, path << ": the element blocks hold more elements than the header's "
                                                    << num_elem);
    const int block_index = static_cast<int>(m.blocks.size());
    m.blocks.push_back({name, checked_id(block_ids[b], path, what.c_str())});
    blocks.push_back({block_ids[b], blk.num_entry, shell});
    if (blk.num_entry == 0) continue;
    std::vector<std::int64_t> conn(static_cast<std::size_t>(blk.num_entry * npe));
    SHELLFRAC_EXO_INPUT_CHECK(ex_get_conn(id, EX_ELEM_BLOCK, blk.id, conn.data(), nullptr, nullptr),
                              path << ": cannot read the connectivity of " << what);
    for (std::size_t k = 0; k < conn.size(); ++k) {
      SHELLFRAC_INPUT_REQUIRE(conn[k] >= 1 && conn[k] <= num_nodes,
                              path << ": " << what << ", element " << k / npe + 1 << " of the block refers to node "
                                   << conn[k] << ", but the file has " << num_nodes << " nodes");
      m.connectivity.push_back(conn[k] - 1);
    }
    m.element_block.insert(m.element_block.end(), static_cast<std::size_t>(blk.num_entry), block_index);
  }
  SHELLFRAC_INPUT_REQUIRE(total == num_elem, path << ": the element blocks hold " << total
                                                  << " elements but the header says " << num_elem);

  // Per element: does side s of a TRISHELL element (3,4,5) or a TRI element (1,2,3) map to an edge?
  std::vector<char> elem_is_shell;
  elem_is_shell.reserve(static_cast<std::size_t>(num_elem));
  for (const auto& b : blocks) elem_is_shell.insert(elem_is_shell.end(), static_cast<std::size_t>(b.count), b.shell);

  // Node sets.
  {
    const auto ids = get_ids(id, EX_NODE_SET, p.num_node_sets, path, "node set");
    const auto names = exodus::get_names(id, EX_NODE_SET, p.num_node_sets, path);
    std::vector<std::int64_t> entries;
    for (std::size_t s = 0; s < ids.size(); ++s) {
      mesh::NodeSet ns;
      ns.name = default_name(names[s], "nodeset", ids[s]);
      const std::string what = "node set " + std::to_string(ids[s]) + " ('" + ns.name + "')";
      ns.id = checked_id(ids[s], path, what.c_str());
      get_set(id, EX_NODE_SET, ids[s], entries, nullptr, path, what, stored_bytes);
      ns.nodes = to_sorted_indices(entries, num_nodes, path, what, "node");
      m.node_sets.push_back(std::move(ns));
    }
  }

  // Side sets.
  {
    const auto ids = get_ids(id, EX_SIDE_SET, p.num_side_sets, path, "side set");
    const auto names = exodus::get_names(id, EX_SIDE_SET, p.num_side_sets, path);
    std::vector<std::int64_t> elems, sides;
    for (std::size_t s = 0; s < ids.size(); ++s) {
      mesh::SideSet ss;
      ss.name = default_name(names[s], "sideset", ids[s]);
      const std::string what = "side set " + std::to_string(ids[s]) + " ('" + ss.name + "')";
      ss.id = checked_id(ids[s], path, what.c_str());
      get_set(id, EX_SIDE_SET, ids[s], elems, &sides, path, what, stored_bytes);
      for (std::size_t k = 0; k < elems.size(); ++k) {
        const std::int64_t e = elems[k];
        SHELLFRAC_INPUT_REQUIRE(e >= 1 && e <= num_elem, path << ": " << what << " refers to element " << e
                                                              << ", but the file has " << num_elem << " elements");
        const bool shell = elem_is_shell[static_cast<std::size_t>(e - 1)] != 0;
        const std::int64_t first = shell ? 3 : 1;
        SHELLFRAC_INPUT_REQUIRE(!(shell && (sides[k] == 1 || sides[k] == 2)),
                                path << ": " << what << ", element " << e << ": side " << sides[k]
                                     << " is a face of a shell element; side sets of shells must use edge sides 3, 4, 5");
        SHELLFRAC_INPUT_REQUIRE(sides[k] >= first && sides[k] < first + 3,
                                path << ": " << what << ", element " << e << ": invalid side number " << sides[k]
                                     << " (expected " << first << ".." << first + 2 << ")");
        ss.elements.push_back(e - 1);
        ss.local_edges.push_back(static_cast<int>(sides[k] - first));
      }
      m.side_sets.push_back(std::move(ss));
    }
  }

  // Element sets.
  {
    const auto ids = get_ids(id, EX_ELEM_SET, p.num_elem_sets, path, "element set");
    const auto names = exodus::get_names(id, EX_ELEM_SET, p.num_elem_sets, path);
    std::vector<std::int64_t> entries;
    for (std::size_t s = 0; s < ids.size(); ++s) {
      mesh::ElementSet es;
      es.name = default_name(names[s], "elemset", ids[s]);
      const std::string what = "element set " + std::to_string(ids[s]) + " ('" + es.name + "')";
      es.id = checked_id(ids[s], path, what.c_str());
      get_set(id, EX_ELEM_SET, ids[s], entries, nullptr, path, what, stored_bytes);
      es.elements = to_sorted_indices(entries, num_elem, path, what, "element");
      m.element_sets.push_back(std::move(es));
    }
  }
  return m;
}

/// Writes one set of `type` with 1-based entries (and optional side numbers).
void put_set(int exo_id, ex_entity_type type, int set_id, const std::vector<std::int64_t>& entries,
             const std::vector<std::int64_t>* extra, const std::string& path) {
  SHELLFRAC_EXO_CHECK(ex_put_set_param(exo_id, type, set_id, static_cast<std::int64_t>(entries.size()), 0),
                      path << ": set " << set_id);
  if (!entries.empty())
    SHELLFRAC_EXO_CHECK(ex_put_set(exo_id, type, set_id, entries.data(), extra ? extra->data() : nullptr),
                        path << ": set " << set_id);
}

template <class Set>
std::vector<std::string> names_of(const std::vector<Set>& sets) {
  std::vector<std::string> out;
  for (const auto& s : sets) out.push_back(s.name);
  return out;
}

}  // namespace

mesh::SerialMesh read_exodus_mesh(const std::string& path) {
  mesh::SerialMesh m;
  try {
    m = read_exodus_impl(path);
  } catch (const std::bad_alloc&) {
    SHELLFRAC_INPUT_REQUIRE(false, path << ": the Exodus file declares more data than fits in memory");
  } catch (const std::length_error&) {
    SHELLFRAC_INPUT_REQUIRE(false, path << ": the Exodus file declares more data than fits in memory");
  }
  mesh::check_mesh(m);
  return m;
}

void write_exodus_mesh(const mesh::SerialMesh& mesh, const std::string& path) {
  const int npe = mesh.nodes_per_element;
  SHELLFRAC_REQUIRE(npe == 3 || npe == 6, path << ": nodes_per_element is " << npe);
  SHELLFRAC_REQUIRE(mesh.connectivity.size() == mesh.element_block.size() * static_cast<std::size_t>(npe),
                    path << ": connectivity size does not match the element count");
  SHELLFRAC_REQUIRE(mesh.num_nodes() < exodus::max_stored_int && mesh.num_elements() < exodus::max_stored_int,
                    path << ": mesh too large for 32-bit Exodus integers");
  exodus::check_name_lengths(names_of(mesh.blocks), "element block", path);
  exodus::check_name_lengths(names_of(mesh.node_sets), "node set", path);
  exodus::check_name_lengths(names_of(mesh.side_sets), "side set", path);
  exodus::check_name_lengths(names_of(mesh.element_sets), "element set", path);

  // Exodus numbers elements block by block: file element k is mesh element order[k].
  const std::size_t ne = mesh.element_block.size();
  std::vector<std::size_t> order(ne);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return mesh.element_block[a] < mesh.element_block[b]; });
  std::vector<std::int64_t> file_number(ne);  // 1-based file element number of each mesh element
  for (std::size_t k = 0; k < ne; ++k) file_number[order[k]] = static_cast<std::int64_t>(k) + 1;

  exodus::File file = exodus::create(path);
  if (!file.is_open()) throw OutputError(path + ": cannot create the Exodus file: " + exodus::last_error());
  const int id = file.id();

  ex_init_params p{};
  const std::string title = "shellfrac mesh from " + mesh.source;
  title.copy(p.title, MAX_LINE_LENGTH);
  p.num_dim = 3;
  p.num_nodes = mesh.num_nodes();
  p.num_elem = mesh.num_elements();
  p.num_elem_blk = static_cast<std::int64_t>(mesh.blocks.size());
  p.num_node_sets = static_cast<std::int64_t>(mesh.node_sets.size());
  p.num_side_sets = static_cast<std::int64_t>(mesh.side_sets.size());
  p.num_elem_sets = static_cast<std::int64_t>(mesh.element_sets.size());
  SHELLFRAC_EXO_CHECK(ex_put_init_ext(id, &p), path);

  if (!mesh.coords.empty()) {
    std::vector<double> x, y, z;
    for (const auto& c : mesh.coords) {
      x.push_back(c[0]);
      y.push_back(c[1]);
      z.push_back(c[2]);
    }
    SHELLFRAC_EXO_CHECK(ex_put_coord(id, x.data(), y.data(), z.data()), path);
  }

  const char* type = npe == 3 ? "TRISHELL3" : "TRISHELL6";
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    std::vector<std::int64_t> conn;
    for (std::size_t e : order)
      if (mesh.element_block[e] == static_cast<int>(b))
        for (int a = 0; a < npe; ++a) conn.push_back(mesh.connectivity[e * npe + a] + 1);
    const std::int64_t count = static_cast<std::int64_t>(conn.size()) / npe;
    SHELLFRAC_EXO_CHECK(ex_put_block(id, EX_ELEM_BLOCK, mesh.blocks[b].id, type, count, npe, 0, 0, 0),
                        path << ": element block " << mesh.blocks[b].id);
    if (count > 0)
      SHELLFRAC_EXO_CHECK(ex_put_conn(id, EX_ELEM_BLOCK, mesh.blocks[b].id, conn.data(), nullptr, nullptr),
                          path << ": element block " << mesh.blocks[b].id);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_BLOCK, names_of(mesh.blocks)), path);

  for (const auto& ns : mesh.node_sets) {
    std::vector<std::int64_t> entries;
    for (GlobalId n : ns.nodes) entries.push_back(n + 1);
    put_set(id, EX_NODE_SET, ns.id, entries, nullptr, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_NODE_SET, names_of(mesh.node_sets)), path);

  for (const auto& ss : mesh.side_sets) {
    SHELLFRAC_REQUIRE(ss.elements.size() == ss.local_edges.size(), path << ": side set '" << ss.name << "' sizes differ");
    std::vector<std::int64_t> elems, sides;
    for (std::size_t k = 0; k < ss.elements.size(); ++k) {
      elems.push_back(file_number.at(static_cast<std::size_t>(ss.elements[k])));
      sides.push_back(ss.local_edges[k] + 3);  // TRISHELL: sides 3,4,5 are edges 0,1,2
    }
    put_set(id, EX_SIDE_SET, ss.id, elems, &sides, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_SIDE_SET, names_of(mesh.side_sets)), path);

  for (const auto& es : mesh.element_sets) {
    std::vector<std::int64_t> entries;
    for (GlobalId e : es.elements) entries.push_back(file_number.at(static_cast<std::size_t>(e)));
    std::sort(entries.begin(), entries.end());
    put_set(id, EX_ELEM_SET, es.id, entries, nullptr, path);
  }
  SHELLFRAC_EXO_CHECK(exodus::put_names(id, EX_ELEM_SET, names_of(mesh.element_sets)), path);

  SHELLFRAC_EXO_CHECK(file.close(), path);
}

mesh::SerialMesh read_mesh_file(const std::string& path) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(std::filesystem::exists(path, ec), path << ": mesh file not found");
  files::require_regular_input(path, "the mesh file");  // a FIFO would block in open(), a device never end
  std::string ext = exodus::upper(std::filesystem::path(path).extension().string());
  if (ext == ".MSH") return read_gmsh(path);
  if (ext == ".EXO" || ext == ".E" || ext == ".G" || ext == ".GEN" || ext == ".EX2") return read_exodus_mesh(path);
  SHELLFRAC_INPUT_REQUIRE(false, path << ": unknown mesh file extension '"
                                      << std::filesystem::path(path).extension().string()
                                      << "' (expected .msh for Gmsh, or .exo .e .g .gen .ex2 for Exodus II)");
  return {};
}

}  // namespace shellfrac::meshio
