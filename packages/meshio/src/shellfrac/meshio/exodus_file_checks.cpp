#include "shellfrac/meshio/exodus_file_checks.hpp"

#include <exodusII.h>
#include <netcdf.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

#include "shellfrac/core/error.hpp"

namespace shellfrac::meshio {

namespace {

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

/// The netCDF classic header check of check_netcdf_classic_header, as one pass over the header.
class ClassicHeaderCheck {
 public:
  ClassicHeaderCheck(const std::string& path, std::uintmax_t size) : path_(path), size_(size), h_(path, size) {}

  /// False when the file is not a netCDF classic file.
  bool run() {
    if (size_ < 4) return false;
    const std::uint64_t magic = h_.get(4, "the magic number");
    if ((magic >> 8) != 0x434446u) return false;  // "CDF"
    version_ = static_cast<int>(magic & 0xffu);
    SHELLFRAC_INPUT_REQUIRE(version_ == 1 || version_ == 2 || version_ == 5,
                            path_ << ": netCDF classic file of unknown version " << version_);
    nn_ = version_ == 5 ? 8 : 4;
    h_.get(nn_, "the record count");
    dimensions();
    attributes("global attribute list");
    variables();
    return true;
  }

 private:
  static constexpr std::uint64_t tag_dimension = 10, tag_variable = 11, tag_attribute = 12;
  static constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();

  /// A list is ABSENT (two zeros) or tag + count; `tag` is the expected tag.
  std::uint64_t list_count(std::uint64_t tag, std::uint64_t min_bytes, const char* what) {
    const std::uint64_t t = h_.get(4, what);
    if (t == 0) {
      SHELLFRAC_INPUT_REQUIRE(h_.get(nn_, what) == 0, path_ << ": corrupt netCDF header: absent " << what
                                                            << " with a non-zero count");
      return 0;
    }
    SHELLFRAC_INPUT_REQUIRE(t == tag, path_ << ": corrupt netCDF header: bad tag " << t << " for the " << what
                                            << " at byte " << h_.position() - 4);
    return h_.count(nn_, min_bytes, what);
  }

  std::string name(const char* what) {
    const std::uint64_t n = h_.count(nn_, 1, what);
    std::string text = h_.text(n, what);
    h_.skip((n + 3) / 4 * 4 - n, what);
    return text;
  }

  std::uint64_t type_size(std::uint64_t type) {
    switch (type) {
      case 1: case 2: case 7: return 1;  // byte, char, ubyte
      case 3: case 8: return 2;          // short, ushort
      case 4: case 5: case 9: return 4;  // int, float, uint
      case 6: case 10: case 11: return 8;  // double, int64, uint64
      default: break;
    }
    SHELLFRAC_INPUT_REQUIRE(false, path_ << ": corrupt netCDF header: unknown data type " << type << " at byte "
                                         << h_.position() - 4);
    return 0;
  }

  void attributes(const char* what) {
    const std::uint64_t n = list_count(tag_attribute, static_cast<std::uint64_t>(2 * nn_ + 4), what);
    for (std::uint64_t i = 0; i < n; ++i) {
      name("attribute name length");
      const std::uint64_t bytes = type_size(h_.get(4, "attribute type"));
      const std::uint64_t values = h_.count(nn_, bytes, "attribute value count");
      h_.skip((values * bytes + 3) / 4 * 4, "attribute values");
    }
  }

  void dimensions() {
    const std::uint64_t num_dims = list_count(tag_dimension, static_cast<std::uint64_t>(2 * nn_), "dimension list");
    dim_length_.assign(static_cast<std::size_t>(num_dims), 0);
    for (auto& len : dim_length_) {
      name("dimension name length");
      len = h_.get(nn_, "dimension length");  // 0: the record (unlimited) dimension
    }
  }

  /// Every fixed-size variable's data must lie inside the file.
  void variables() {
    const int offset_size = version_ == 1 ? 4 : 8;
    const std::uint64_t num_vars =
        list_count(tag_variable, static_cast<std::uint64_t>(3 * nn_ + 4 + 4 + nn_ + offset_size), "variable list");
    for (std::uint64_t i = 0; i < num_vars; ++i) {
      const std::string var = name("variable name length");
      bool record = false;
      const std::uint64_t values = variable_values(var, record);
      attributes("variable attribute list");
      const std::uint64_t bytes_each = type_size(h_.get(4, "variable type"));
      h_.get(nn_, "variable size");
      const std::uint64_t begin = h_.get(offset_size, "variable offset");
      if (record || values == 0) continue;  // record variables grow with the file; empty ones store nothing
      const std::uint64_t bytes = values <= saturated / bytes_each ? values * bytes_each : saturated;
      const std::uint64_t end = begin <= saturated - bytes ? begin + bytes : saturated;
      SHELLFRAC_INPUT_REQUIRE(end <= size_, path_ << ": truncated file: the data of variable '" << var
                                                  << "' end at byte " << end << ", but the file has " << size_
                                                  << " bytes");
    }
  }

  /// Reads a variable's dimension ids; its number of values (saturated), `record` if its first is the record one.
  std::uint64_t variable_values(const std::string& var, bool& record) {
    const std::uint64_t rank = h_.count(nn_, static_cast<std::uint64_t>(nn_), "variable dimension count");
    std::uint64_t values = 1;
    for (std::uint64_t k = 0; k < rank; ++k) {
      const std::uint64_t dim = h_.get(nn_, "dimension id");
      SHELLFRAC_INPUT_REQUIRE(dim < dim_length_.size(), path_ << ": corrupt netCDF header: variable '" << var
                                                              << "' refers to dimension id " << dim << " beyond the "
                                                              << dim_length_.size() << " dimensions");
      const std::uint64_t len = dim_length_[static_cast<std::size_t>(dim)];
      if (k == 0 && len == 0) record = true;
      values = len == 0 || values <= saturated / len ? values * len : saturated;
    }
    return values;
  }

  const std::string& path_;
  std::uintmax_t size_;
  NetcdfHeader h_;
  int version_ = 0;
  int nn_ = 4;  ///< size of counts, lengths and (CDF-5) dimension ids
  std::vector<std::uint64_t> dim_length_;
};

/// An open netCDF id, closed on destruction.
struct NetcdfFile {
  int id = -1;
  ~NetcdfFile() {
    if (id >= 0) nc_close(id);
  }
};

}  // namespace

bool check_netcdf_classic_header(const std::string& path, std::uintmax_t size) {
  return ClassicHeaderCheck(path, size).run();
}

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


}  // namespace shellfrac::meshio
