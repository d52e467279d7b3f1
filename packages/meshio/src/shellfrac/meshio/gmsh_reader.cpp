/// \file gmsh_reader.cpp
/// Gmsh .msh reader (formats 2.2 and 4.1, ASCII and binary). The whole file is read into memory and parsed
/// with a bounds-checked cursor: every count read from the file is checked against the bytes that remain
/// before anything is allocated, so a truncated or hostile file gives an InputError, never a crash.
/// Parsing produces a raw list of nodes and elements (Gmsh tags, physical groups); the SerialMesh is then
/// assembled from it by one format-independent routine, so all four variants give the same mesh.
#include "shellfrac/meshio/gmsh_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"

namespace shellfrac::meshio {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Element types

constexpr int type_line2 = 1;
constexpr int type_tri3 = 2;
constexpr int type_line3 = 8;
constexpr int type_tri6 = 9;
constexpr int type_point = 15;
constexpr int max_element_nodes = 6;  ///< largest supported element (triangle6)

/// Number of nodes of a supported Gmsh element type, 0 for any other type.
int supported_num_nodes(int type) {
  switch (type) {
    case type_line2: return 2;
    case type_tri3: return 3;
    case type_line3: return 3;
    case type_tri6: return 6;
    case type_point: return 1;
    default: return 0;
  }
}

/// Topological dimension of a supported element type.
int element_dim(int type) {
  switch (type) {
    case type_point: return 0;
    case type_line2:
    case type_line3: return 1;
    default: return 2;
  }
}

/// Human-readable name of a Gmsh element type, for messages about unsupported types (Gmsh manual §9.1).
const char* element_type_name(int type) {
  switch (type) {
    case 3: return "4-node quadrangle";
    case 10: return "9-node quadrangle";
    case 16: return "8-node quadrangle";
    case 4: case 11: case 29: case 30: case 31: return "tetrahedron";
    case 5: case 12: case 17: case 92: case 93: return "hexahedron";
    case 6: case 13: case 18: return "prism";
    case 7: case 14: case 19: return "pyramid";
    case 20: case 21: case 22: case 23: case 24: case 25: return "triangle of order > 2";
    case 26: case 27: case 28: return "line of order > 2";
    default: return "unknown element type";
  }
}

// ---------------------------------------------------------------------------------------------------------
// Raw file content

/// A node as read: Gmsh tag and coordinates.
struct RawNode {
  std::int64_t tag = 0;
  Vec3 x{0, 0, 0};
};

/// An element as read. Its physical groups are either a list index (groups) or, for 4.1 before the
/// $Entities lookup, the entity (entity_dim, entity_tag).
struct RawElement {
  std::int64_t tag = 0;
  int type = 0;
  int entity_dim = 0;
  int entity_tag = 0;
  int groups = 0;  ///< index into RawFile::group_lists (sorted physical tags of this element's dimension)
  std::array<std::int64_t, max_element_nodes> nodes{};
};

/// Everything the reader keeps from the file.
struct RawFile {
  bool v41 = false;
  bool binary = false;
  bool swap = false;  ///< binary data of the other endianness
  std::map<std::pair<int, int>, std::string> physical_names;  ///< (dim, tag) -> name
  bool has_entities = false;
  std::map<std::pair<int, int>, std::vector<int>> entity_groups;  ///< (dim, entity tag) -> physical tags
  bool has_nodes = false;
  bool has_elements = false;
  std::vector<RawNode> nodes;
  std::vector<RawElement> elements;
  std::vector<std::vector<int>> group_lists{{}};  ///< interned sorted lists; [0] = no group
  std::map<std::vector<int>, int> group_index{{{}, 0}};

  /// Index of the (interned) sorted, unique list of physical tags.
  int intern(std::vector<int> tags) {
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
    auto it = group_index.find(tags);
    if (it != group_index.end()) return it->second;
    const int index = static_cast<int>(group_lists.size());
    group_lists.push_back(tags);
    group_index.emplace(std::move(tags), index);
    return index;
  }
};

// ---------------------------------------------------------------------------------------------------------
// Cursor

/// Bounds-checked reader over the file content: ASCII tokens and lines, and raw binary values.
class Cursor {
 public:
  Cursor(const std::string& path, const std::string& data) : path_(path), data_(data) {}

  /// Where the cursor is, for messages: the line of the last token in ASCII files, the byte offset in
  /// binary files (line numbers are meaningless once binary data has been crossed).
  std::string where() const {
    return binary_ ? "byte " + std::to_string(token_pos_) : "line " + std::to_string(token_line_);
  }
  void set_binary(bool binary) { binary_ = binary; }
  void set_swap(bool swap) { swap_ = swap; }
  std::size_t remaining() const { return data_.size() - pos_; }
  /// " (truncated file?)" when the cursor is at the end of the file: a malformed last token is then most
  /// likely a cut, not a typo.
  const char* eof_hint() const { return pos_ >= data_.size() ? " (truncated file?)" : ""; }
  std::size_t position() const { return pos_; }

  /// Skips white space; true if the end of the file is reached.
  bool at_end() {
    skip_space();
    return pos_ >= data_.size();
  }

  /// Next white-space separated token; `what` names what was expected, for the message.
  std::string_view token(const char* what) {
    skip_space();
    token_pos_ = pos_;
    token_line_ = line_;
    SHELLFRAC_INPUT_REQUIRE(pos_ < data_.size(),
                            path_ << ": unexpected end of file (truncated?) while reading " << what);
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    return std::string_view(data_).substr(start, pos_ - start);
  }

  /// Next token as an integer in [lo, hi].
  std::int64_t integer(const char* what, std::int64_t lo = std::numeric_limits<std::int64_t>::min(),
                       std::int64_t hi = std::numeric_limits<std::int64_t>::max()) {
    const std::string_view t = token(what);
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    SHELLFRAC_INPUT_REQUIRE(ec == std::errc() && end == t.data() + t.size(),
                            path_ << ": " << where() << ": expected an integer (" << what << "), found '"
                                  << shorten(t) << "'" << eof_hint());
    SHELLFRAC_INPUT_REQUIRE(value >= lo && value <= hi, path_ << ": " << where() << ": " << what << " "
                                                              << value << " is out of range [" << lo << ", "
                                                              << hi << "]");
    return value;
  }

  /// Next token as a count, bounded so that `count * min_bytes_each` fits in what remains of the file
  /// (guards the allocations that follow against hostile counts).
  std::size_t count(const char* what, std::size_t min_bytes_each) {
    const std::int64_t n = integer(what, 0);
    check_count(static_cast<std::uint64_t>(n), min_bytes_each, what);
    return static_cast<std::size_t>(n);
  }

  /// Next token as a finite double.
  double real(const char* what) {
    const std::string_view t = token(what);
    double value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    SHELLFRAC_INPUT_REQUIRE(ec == std::errc() && end == t.data() + t.size() && std::isfinite(value),
                            path_ << ": " << where() << ": expected a finite number (" << what << "), found '"
                                  << shorten(t) << "'" << eof_hint());
    return value;
  }

  /// The rest of the current line (without the newline), consumed.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    const std::string_view line = std::string_view(data_).substr(start, pos_ - start);
    if (pos_ < data_.size()) {
      ++pos_;
      ++line_;
    }
    return line;
  }

  /// Consumes blanks up to and including the end of the line; binary data starts right after it.
  void end_of_line(const char* after) {
    while (pos_ < data_.size() && (data_[pos_] == ' ' || data_[pos_] == '\t' || data_[pos_] == '\r')) ++pos_;
    SHELLFRAC_INPUT_REQUIRE(pos_ < data_.size() && data_[pos_] == '\n',
                            path_ << ": " << where() << ": expected the end of the line after " << after
                                  << eof_hint());
    ++pos_;
    ++line_;
  }

  /// Requires the next token to be `expected` (e.g. "$EndNodes").
  void expect(std::string_view expected, const char* context) {
    const std::string_view t = token(context);
    SHELLFRAC_INPUT_REQUIRE(t == expected, path_ << ": " << where() << ": expected '" << expected << "' "
                                                 << context << ", found '" << shorten(t) << "'"
                                                 << eof_hint());
  }

  /// Throws unless `n` items of at least `min_bytes_each` bytes fit in the rest of the file.
  void check_count(std::uint64_t n, std::size_t min_bytes_each, const char* what) const {
    SHELLFRAC_INPUT_REQUIRE(n <= remaining() / std::max<std::size_t>(min_bytes_each, 1),
                            path_ << ": " << where() << ": " << what << " " << n
                                  << " is larger than the rest of the file can hold (truncated or corrupt file)");
  }

  /// Reads one binary value of type T (int32, uint64 or double), swapping bytes if needed.
  template <class T>
  T binary(const char* what) {
    token_pos_ = pos_;
    SHELLFRAC_INPUT_REQUIRE(remaining() >= sizeof(T), path_ << ": unexpected end of file (truncated?) at byte "
                                                            << pos_ << " while reading " << what);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (swap_) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Binary int32 in [lo, hi].
  int binary_int(const char* what, int lo = std::numeric_limits<int>::min(),
                 int hi = std::numeric_limits<int>::max()) {
    const std::int32_t v = binary<std::int32_t>(what);
    SHELLFRAC_INPUT_REQUIRE(v >= lo && v <= hi, path_ << ": " << where() << ": " << what << " " << v
                                                      << " is out of range [" << lo << ", " << hi << "]");
    return v;
  }

  /// Binary size_t (8 bytes in 4.1 files) as a non-negative int64.
  std::int64_t binary_size(const char* what) {
    const std::uint64_t v = binary<std::uint64_t>(what);
    SHELLFRAC_INPUT_REQUIRE(v <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()),
                            path_ << ": " << where() << ": " << what << " " << v << " is out of range");
    return static_cast<std::int64_t>(v);
  }

  /// Binary size_t used as a count, bounded like count().
  std::size_t binary_count(const char* what, std::size_t min_bytes_each) {
    const std::uint64_t n = binary<std::uint64_t>(what);
    check_count(n, min_bytes_each, what);
    return static_cast<std::size_t>(n);
  }

  /// Binary finite double.
  double binary_real(const char* what) {
    const double v = binary<double>(what);
    SHELLFRAC_INPUT_REQUIRE(std::isfinite(v), path_ << ": " << where() << ": " << what << " is not finite");
    return v;
  }

  /// Skips to just after the line "$End<name>" (sections this reader does not use); returns what it skipped
  /// before that line (the section's body).
  std::string_view skip_section(std::string_view name) {
    const std::string end = "$End" + std::string(name);
    const std::size_t start = pos_;
    std::size_t at = pos_;
    for (;;) {
      at = data_.find(end, at);
      SHELLFRAC_INPUT_REQUIRE(at != std::string::npos, path_ << ": " << where() << ": section $" << name
                                                             << " has no " << end << " (truncated file?)");
      const std::size_t after = at + end.size();
      // Must be a whole token at the start of a line: "$EndNode" must not match "$EndNodeData".
      if ((at == 0 || data_[at - 1] == '\n') && (after == data_.size() || is_space(data_[after]))) {
        line_ += static_cast<std::size_t>(std::count(data_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                                     data_.begin() + static_cast<std::ptrdiff_t>(after), '\n'));
        pos_ = after;
        return std::string_view(data_).substr(start, at - start);
      }
      at = after;
    }
  }

  static std::string shorten(std::string_view t) {
    std::string s(t.substr(0, 40));
    for (char& c : s)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return t.size() > 40 ? s + "..." : s;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_space() {
    while (pos_ < data_.size() && is_space(data_[pos_])) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  const std::string& path_;
  const std::string& data_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t token_pos_ = 0;
  std::size_t token_line_ = 1;
  bool binary_ = false;
  bool swap_ = false;
};

// ---------------------------------------------------------------------------------------------------------
// Section parsers

/// Throws for element types other than the supported ones; returns the node count.
int check_element_type(const std::string& path, const Cursor& in, int type) {
  const int n = supported_num_nodes(type);
  SHELLFRAC_INPUT_REQUIRE(n > 0, path << ": " << in.where() << ": element type " << type << " ("
                                      << element_type_name(type)
                                      << ") is not supported; shellfrac reads 3- and 6-node triangles, "
                                         "2- and 3-node lines and points only (no quadrilaterals or volume "
                                         "elements)");
  return n;
}

/// $MeshFormat: version, file type, data size and, in binary files, the endianness marker.
void read_mesh_format(const std::string& path, Cursor& in, RawFile& raw) {
  SHELLFRAC_INPUT_REQUIRE(!in.at_end(), path << ": empty file (not a Gmsh mesh)");
  const std::string_view first = in.token("$MeshFormat");
  SHELLFRAC_INPUT_REQUIRE(first == "$MeshFormat",
                          path << ": not a Gmsh .msh file (it does not start with $MeshFormat)");
  const std::string_view version = in.token("the format version");
  SHELLFRAC_INPUT_REQUIRE(version == "2.2" || version == "4.1",
                          path << ": " << in.where() << ": unsupported Gmsh file format version '"
                               << Cursor::shorten(version)
                               << "'; supported versions are 2.2 and 4.1 (gmsh -format msh22 or msh41)");
  raw.v41 = version == "4.1";
  raw.binary = in.integer("the file type (0 ASCII, 1 binary)", 0, 1) == 1;
  const std::int64_t data_size = in.integer("the data size");
  if (raw.binary) {
    // Binary data is read as 8-byte doubles and size_t; other sizes are not written by Gmsh on 64-bit systems.
    SHELLFRAC_INPUT_REQUIRE(data_size == 8, path << ": " << in.where() << ": binary data size " << data_size
                                                 << " is not supported (must be 8)");
    in.end_of_line("the $MeshFormat line");
    in.set_binary(true);
    const std::int32_t one = in.binary<std::int32_t>("the endianness marker");
    std::int32_t swapped = 0;
    {
      unsigned char b[4];
      std::memcpy(b, &one, 4);
      std::reverse(b, b + 4);
      std::memcpy(&swapped, b, 4);
    }
    SHELLFRAC_INPUT_REQUIRE(one == 1 || swapped == 1, path << ": bad endianness marker in binary $MeshFormat "
                                                              "(expected the integer 1)");
    raw.swap = one != 1;
    in.set_swap(raw.swap);
  }
  in.expect("$EndMeshFormat", "to close $MeshFormat");
}

/// $PhysicalNames (ASCII in every variant): dim tag "name".
void read_physical_names(const std::string& /*path*/, Cursor& in, RawFile& raw) {
  const std::size_t n = in.count("number of physical names", 6);
  for (std::size_t i = 0; i < n; ++i) {
    const int dim = static_cast<int>(in.integer("physical group dimension", 0, 3));
    const int tag = static_cast<int>(in.integer("physical tag", std::numeric_limits<int>::min() + 1,
                                                std::numeric_limits<int>::max()));
    std::string_view name = in.rest_of_line();
    while (!name.empty() && (name.front() == ' ' || name.front() == '\t')) name.remove_prefix(1);
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t' || name.back() == '\r')) name.remove_suffix(1);
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    if (!name.empty()) raw.physical_names[{dim, std::abs(tag)}] = std::string(name);
  }
  in.expect("$EndPhysicalNames", "to close $PhysicalNames");
}

/// $Entities (4.1): keeps entity -> physical tags, skips bounding boxes and bounding entities.
void read_entities(const std::string& /*path*/, Cursor& in, RawFile& raw) {
  raw.has_entities = true;
  std::size_t num[4];
  if (raw.binary) {
    in.end_of_line("$Entities");
    for (std::size_t& n : num) n = in.binary_count("number of entities", 4 + 3 * 8 + 8);
  } else {
    for (std::size_t& n : num) n = in.count("number of entities", 8);
  }
  for (int dim = 0; dim < 4; ++dim) {
    for (std::size_t i = 0; i < num[dim]; ++i) {
      const int num_coords = dim == 0 ? 3 : 6;  // point: x y z; others: bounding box
      int tag = 0;
      std::vector<int> groups;
      if (raw.binary) {
        tag = in.binary_int("entity tag");
        for (int c = 0; c < num_coords; ++c) in.binary<double>("entity coordinates");
        const std::size_t np = in.binary_count("number of physical tags", 4);
        for (std::size_t k = 0; k < np; ++k)
          groups.push_back(std::abs(in.binary_int("physical tag", -std::numeric_limits<int>::max())));
        if (dim > 0) {
          const std::size_t nb = in.binary_count("number of bounding entities", 4);
          for (std::size_t k = 0; k < nb; ++k) in.binary<std::int32_t>("bounding entity tag");
        }
      } else {
        tag = static_cast<int>(
            in.integer("entity tag", std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
        for (int c = 0; c < num_coords; ++c) in.real("entity coordinates");
        const std::size_t np = in.count("number of physical tags", 2);
        for (std::size_t k = 0; k < np; ++k)
          groups.push_back(static_cast<int>(std::abs(in.integer("physical tag", -std::numeric_limits<int>::max(),
                                                                std::numeric_limits<int>::max()))));
        if (dim > 0) {
          const std::size_t nb = in.count("number of bounding entities", 2);
          for (std::size_t k = 0; k < nb; ++k) in.integer("bounding entity tag");
        }
      }
      groups.erase(std::remove(groups.begin(), groups.end(), 0), groups.end());  // 0 = no group
      raw.entity_groups[{dim, tag}] = std::move(groups);
    }
  }
  in.expect("$EndEntities", "to close $Entities");
}

/// $Nodes, format 2.2: n, then n x (tag x y z).
void read_nodes_22(const std::string& path, Cursor& in, RawFile& raw) {
  const std::size_t n = in.count("number of nodes", raw.binary ? 4 + 3 * 8 : 8);
  if (raw.binary) in.end_of_line("the number of nodes");
  raw.nodes.reserve(raw.nodes.size() + n);
  for (std::size_t i = 0; i < n; ++i) {
    RawNode node;
    if (raw.binary) {
      node.tag = in.binary_int("node tag");
      for (double& c : node.x) c = in.binary_real("node coordinate");
    } else {
      node.tag = in.integer("node tag");
      for (double& c : node.x) c = in.real("node coordinate");
    }
    SHELLFRAC_INPUT_REQUIRE(node.tag > 0, path << ": " << in.where() << ": node tag " << node.tag
                                               << " is not positive");
    raw.nodes.push_back(node);
  }
  in.expect("$EndNodes", "to close $Nodes (wrong node count?)");
}

/// $Nodes, format 4.1: header, then per entity block: dim tag parametric n, n tags, n coordinate tuples.
void read_nodes_41(const std::string& path, Cursor& in, RawFile& raw) {
  std::size_t num_blocks = 0, num_nodes = 0;
  if (raw.binary) {
    in.end_of_line("$Nodes");
    num_blocks = in.binary_count("number of node blocks", 3 * 4 + 8);
    num_nodes = in.binary_count("number of nodes", 8 + 3 * 8);
    in.binary_size("minimum node tag");
    in.binary_size("maximum node tag");
  } else {
    num_blocks = in.count("number of node blocks", 8);
    num_nodes = in.count("number of nodes", 8);
    in.integer("minimum node tag");
    in.integer("maximum node tag");
  }
  raw.nodes.reserve(raw.nodes.size() + num_nodes);
  std::size_t total = 0;
  for (std::size_t b = 0; b < num_blocks; ++b) {
    int dim = 0;
    bool parametric = false;
    std::size_t n = 0;
    if (raw.binary) {
      dim = in.binary_int("node block entity dimension", 0, 3);
      in.binary_int("node block entity tag");
      parametric = in.binary_int("node block parametric flag", 0, 1) == 1;
      n = in.binary_count("number of nodes in block", 8 + 3 * 8);
    } else {
      dim = static_cast<int>(in.integer("node block entity dimension", 0, 3));
      in.integer("node block entity tag");
      parametric = in.integer("node block parametric flag", 0, 1) == 1;
      n = in.count("number of nodes in block", 4);
    }
    total += n;
    SHELLFRAC_INPUT_REQUIRE(total <= num_nodes, path << ": " << in.where() << ": node blocks hold more than the "
                                                     << num_nodes << " nodes announced in the $Nodes header");
    // Parametric coordinates (u, v, w as far as the entity dimension) follow x y z; they are skipped.
    const int num_values = 3 + (parametric ? dim : 0);
    const std::size_t first = raw.nodes.size();
    for (std::size_t i = 0; i < n; ++i) {
      RawNode node;
      node.tag = raw.binary ? in.binary_size("node tag") : in.integer("node tag");
      SHELLFRAC_INPUT_REQUIRE(node.tag > 0, path << ": " << in.where() << ": node tag " << node.tag
                                                 << " is not positive");
      raw.nodes.push_back(node);
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < num_values; ++c) {
        const double v = raw.binary ? in.binary_real("node coordinate") : in.real("node coordinate");
        if (c < 3) raw.nodes[first + i].x[static_cast<std::size_t>(c)] = v;
      }
    }
  }
  SHELLFRAC_INPUT_REQUIRE(total == num_nodes, path << ": " << in.where() << ": node blocks hold " << total
                                                   << " nodes, the $Nodes header announces " << num_nodes);
  in.expect("$EndNodes", "to close $Nodes (wrong node count?)");
}

/// $Elements, format 2.2. ASCII: tag type ntags tags... nodes...; binary: blocks of (type, count, ntags)
/// followed by count int records (tag, tags..., nodes...). The physical tag is the first tag (0 = none).
void read_elements_22(const std::string& path, Cursor& in, RawFile& raw) {
  const std::size_t n = in.count("number of elements", raw.binary ? 4 * 2 : 8);
  if (raw.binary) in.end_of_line("the number of elements");
  raw.elements.reserve(raw.elements.size() + n);
  std::size_t done = 0;
  while (done < n) {
    if (raw.binary) {
      const int type = in.binary_int("element type");
      const int nn = check_element_type(path, in, type);
      const int count = in.binary_int("number of elements in block", 1);
      const int ntags = in.binary_int("number of element tags", 0);
      SHELLFRAC_INPUT_REQUIRE(static_cast<std::size_t>(count) <= n - done,
                              path << ": " << in.where() << ": element blocks hold more than the " << n
                                   << " elements announced");
      in.check_count(static_cast<std::uint64_t>(count), 4 * (1 + static_cast<std::size_t>(ntags) + nn),
                     "number of elements in block");
      for (int e = 0; e < count; ++e) {
        RawElement el;
        el.type = type;
        el.tag = in.binary_int("element tag");
        int physical = 0;
        for (int t = 0; t < ntags; ++t) {
          const int v = in.binary_int("element tag list", -std::numeric_limits<int>::max());
          if (t == 0) physical = std::abs(v);
        }
        for (int a = 0; a < nn; ++a) el.nodes[static_cast<std::size_t>(a)] = in.binary_int("element node tag");
        el.groups = physical == 0 ? 0 : raw.intern({physical});
        raw.elements.push_back(el);
      }
      done += static_cast<std::size_t>(count);
    } else {
      RawElement el;
      el.tag = in.integer("element tag");
      el.type = static_cast<int>(in.integer("element type", 0, std::numeric_limits<int>::max()));
      const int nn = check_element_type(path, in, el.type);
      const std::int64_t ntags = in.integer("number of element tags", 0, 1000);
      int physical = 0;
      for (std::int64_t t = 0; t < ntags; ++t) {
        const std::int64_t v = in.integer("element tag list", -std::numeric_limits<int>::max(),
                                          std::numeric_limits<int>::max());
        if (t == 0) physical = static_cast<int>(std::abs(v));
      }
      for (int a = 0; a < nn; ++a) el.nodes[static_cast<std::size_t>(a)] = in.integer("element node tag");
      el.groups = physical == 0 ? 0 : raw.intern({physical});
      raw.elements.push_back(el);
      ++done;
    }
  }
  in.expect("$EndElements", "to close $Elements (wrong element or node count?)");
}

/// $Elements, format 4.1: header, then per entity block: dim tag type n, then n x (tag nodes...).
/// Physical groups come from the block's entity ($Entities), looked up after the whole file is read.
void read_elements_41(const std::string& path, Cursor& in, RawFile& raw) {
  std::size_t num_blocks = 0, num_elements = 0;
  if (raw.binary) {
    in.end_of_line("$Elements");
    num_blocks = in.binary_count("number of element blocks", 3 * 4 + 8);
    num_elements = in.binary_count("number of elements", 2 * 8);
    in.binary_size("minimum element tag");
    in.binary_size("maximum element tag");
  } else {
    num_blocks = in.count("number of element blocks", 8);
    num_elements = in.count("number of elements", 4);
    in.integer("minimum element tag");
    in.integer("maximum element tag");
  }
  raw.elements.reserve(raw.elements.size() + num_elements);
  std::size_t total = 0;
  for (std::size_t b = 0; b < num_blocks; ++b) {
    int dim = 0, entity = 0, type = 0;
    std::size_t n = 0;
    if (raw.binary) {
      dim = in.binary_int("element block entity dimension", 0, 3);
      entity = in.binary_int("element block entity tag");
      type = in.binary_int("element type");
    } else {
      dim = static_cast<int>(in.integer("element block entity dimension", 0, 3));
      entity = static_cast<int>(in.integer("element block entity tag", std::numeric_limits<int>::min(),
                                           std::numeric_limits<int>::max()));
      type = static_cast<int>(in.integer("element type", 0, std::numeric_limits<int>::max()));
    }
    const int nn = check_element_type(path, in, type);
    SHELLFRAC_INPUT_REQUIRE(element_dim(type) == dim, path << ": " << in.where() << ": element block of type "
                                                           << type << " belongs to an entity of dimension " << dim);
    n = raw.binary ? in.binary_count("number of elements in block", 8 * (1 + static_cast<std::size_t>(nn)))
                   : in.count("number of elements in block", 2 * (1 + static_cast<std::size_t>(nn)));
    total += n;
    SHELLFRAC_INPUT_REQUIRE(total <= num_elements, path << ": " << in.where()
                                                        << ": element blocks hold more than the " << num_elements
                                                        << " elements announced in the $Elements header");
    for (std::size_t e = 0; e < n; ++e) {
      RawElement el;
      el.type = type;
      el.entity_dim = dim;
      el.entity_tag = entity;
      el.groups = -1;  // resolved from $Entities later
      el.tag = raw.binary ? in.binary_size("element tag") : in.integer("element tag");
      for (int a = 0; a < nn; ++a)
        el.nodes[static_cast<std::size_t>(a)] =
            raw.binary ? in.binary_size("element node tag") : in.integer("element node tag");
      raw.elements.push_back(el);
    }
  }
  SHELLFRAC_INPUT_REQUIRE(total == num_elements, path << ": " << in.where() << ": element blocks hold " << total
                                                      << " elements, the $Elements header announces "
                                                      << num_elements);
  in.expect("$EndElements", "to close $Elements (wrong element or node count?)");
}

/// Reads the whole file into memory.
std::string read_file(const std::string& path) {
  std::error_code ec;
  SHELLFRAC_INPUT_REQUIRE(std::filesystem::is_regular_file(path, ec),
                          path << ": cannot open mesh file (" << (std::filesystem::exists(path, ec)
                                                                      ? "not a regular file"
                                                                      : "no such file")
                               << ")");
  std::ifstream file(path, std::ios::binary);
  SHELLFRAC_INPUT_REQUIRE(file, path << ": cannot open mesh file (" << std::strerror(errno) << ")");
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  SHELLFRAC_INPUT_REQUIRE(size >= 0, path << ": cannot read mesh file");
  file.seekg(0, std::ios::beg);
  std::string data(static_cast<std::size_t>(size), '\0');
  file.read(data.data(), size);
  SHELLFRAC_INPUT_REQUIRE(file.gcount() == size, path << ": cannot read mesh file (read " << file.gcount()
                                                      << " of " << size << " bytes)");
  return data;
}

/// Parses every section of the file into `raw`.
RawFile parse(const std::string& path, const std::string& data) {
  RawFile raw;
  Cursor in(path, data);
  read_mesh_format(path, in, raw);
  while (!in.at_end()) {
    const std::string_view header = in.token("a section header");
    SHELLFRAC_INPUT_REQUIRE(header.size() > 1 && header.front() == '$' && header.substr(0, 4) != "$End",
                            path << ": " << in.where() << ": expected a section header ($Name), found '"
                                 << Cursor::shorten(header) << "'" << in.eof_hint());
    const std::string_view name = header.substr(1);
    if (name == "PhysicalNames") {
      read_physical_names(path, in, raw);
    } else if (name == "Entities" && raw.v41) {
      SHELLFRAC_INPUT_REQUIRE(!raw.has_entities, path << ": " << in.where() << ": second $Entities section");
      read_entities(path, in, raw);
    } else if (name == "Nodes") {
      SHELLFRAC_INPUT_REQUIRE(!raw.has_nodes, path << ": " << in.where() << ": second $Nodes section");
      raw.has_nodes = true;
      raw.v41 ? read_nodes_41(path, in, raw) : read_nodes_22(path, in, raw);
    } else if (name == "Elements") {
      SHELLFRAC_INPUT_REQUIRE(!raw.has_elements, path << ": " << in.where() << ": second $Elements section");
      raw.has_elements = true;
      raw.v41 ? read_elements_41(path, in, raw) : read_elements_22(path, in, raw);
    } else if (name == "Periodic") {
      // Gmsh writes an empty section (a count of 0: "0" in ASCII, zero bytes in binary) when nothing is periodic.
      const std::string where = in.where();
      const std::string_view body = in.skip_section(name);
      SHELLFRAC_INPUT_REQUIRE(body.find_first_not_of(std::string_view(" \t\r\n0\0", 7)) == std::string_view::npos,
                              path << ": " << where << ": $Periodic (periodic node correspondences) is not "
                                   << "supported: the periodic boundaries would be free edges; mesh without "
                                   << "Periodic constraints");
    } else if (name == "PartitionedEntities" || name == "GhostElements") {
      SHELLFRAC_INPUT_REQUIRE(false, path << ": " << in.where() << ": $" << name << ": the mesh was partitioned by "
                                          << "Gmsh, which is not supported; save it unpartitioned (shellfrac "
                                          << "partitions the mesh itself: Partitioning sublist)");
    } else {
      // $Comments, $Parametrizations, $NodeData, $ElementData, ... carry nothing shellfrac uses
      in.skip_section(name);
    }
  }
  SHELLFRAC_INPUT_REQUIRE(raw.has_nodes, path << ": no $Nodes section (truncated file?)");
  SHELLFRAC_INPUT_REQUIRE(raw.has_elements, path << ": no $Elements section (truncated file?)");
  return raw;
}

// ---------------------------------------------------------------------------------------------------------
// Assembly of the SerialMesh

/// Resolves 4.1 element groups from $Entities and merges 2.2 duplicates (Gmsh 2.2 writes an element once
/// per physical group it belongs to, with the same tag). Returns the elements sorted by tag, unique.
std::vector<RawElement> merge_elements(const std::string& path, RawFile& raw) {
  std::vector<RawElement>& elements = raw.elements;
  if (raw.v41) {
    for (RawElement& el : elements) {
      std::vector<int> groups;
      if (raw.has_entities) {
        const auto it = raw.entity_groups.find({el.entity_dim, el.entity_tag});
        SHELLFRAC_INPUT_REQUIRE(it != raw.entity_groups.end(),
                                path << ": element " << el.tag << " belongs to entity (dimension "
                                     << el.entity_dim << ", tag " << el.entity_tag
                                     << ") that is not in $Entities");
        groups = it->second;
      }
      el.groups = raw.intern(groups);
    }
  }
  std::stable_sort(elements.begin(), elements.end(),
                   [](const RawElement& a, const RawElement& b) { return a.tag < b.tag; });
  std::vector<RawElement> merged;
  merged.reserve(elements.size());
  for (const RawElement& el : elements) {
    if (!merged.empty() && merged.back().tag == el.tag) {
      RawElement& prev = merged.back();
      SHELLFRAC_INPUT_REQUIRE(!raw.v41 && prev.type == el.type && prev.nodes == el.nodes,
                              path << ": element tag " << el.tag << " is used by two different elements");
      std::vector<int> groups = raw.group_lists[static_cast<std::size_t>(prev.groups)];
      const std::vector<int>& more = raw.group_lists[static_cast<std::size_t>(el.groups)];
      groups.insert(groups.end(), more.begin(), more.end());
      prev.groups = raw.intern(std::move(groups));
    } else {
      merged.push_back(el);
    }
  }
  elements.clear();
  elements.shrink_to_fit();
  return merged;
}

/// Makes `name` unique among `taken` (appends _<id>, then a counter) and records it.
std::string unique_name(std::string name, int id, std::vector<std::string>& taken) {
  auto is_taken = [&](const std::string& s) { return std::find(taken.begin(), taken.end(), s) != taken.end(); };
  if (is_taken(name)) {
    const std::string base = name + "_" + std::to_string(id);
    name = base;
    for (int k = 2; is_taken(name); ++k) name = base + "_" + std::to_string(k);
  }
  taken.push_back(name);
  return name;
}

/// `wanted` if it is positive and not in `taken`, else one more than the largest taken id (or, when that
/// largest id is INT_MAX, the smallest free positive id); recorded.
int unique_id(int wanted, std::vector<int>& taken) {
  auto is_taken = [&](int id) { return std::find(taken.begin(), taken.end(), id) != taken.end(); };
  int id = wanted;
  if (id <= 0 || is_taken(id)) {
    const int largest = taken.empty() ? 0 : *std::max_element(taken.begin(), taken.end());
    if (largest < std::numeric_limits<int>::max()) {
      id = std::max(largest, 0) + 1;
    } else {  // a physical tag of 2147483647 is legal in Gmsh: no "next" id, take a free one
      for (id = 1; is_taken(id); ++id) {
      }
    }
  }
  taken.push_back(id);
  return id;
}

mesh::SerialMesh assemble(const std::string& path, RawFile& raw) {
  // Nodes sorted by tag: the new (0-based) numbering follows increasing Gmsh tag order.
  std::vector<RawNode>& nodes = raw.nodes;
  std::sort(nodes.begin(), nodes.end(), [](const RawNode& a, const RawNode& b) { return a.tag < b.tag; });
  for (std::size_t i = 1; i < nodes.size(); ++i)
    SHELLFRAC_INPUT_REQUIRE(nodes[i].tag != nodes[i - 1].tag, path << ": node tag " << nodes[i].tag
                                                                   << " is defined twice");
  auto node_index = [&](std::int64_t tag, std::int64_t element) -> std::size_t {
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), tag,
                                     [](const RawNode& n, std::int64_t t) { return n.tag < t; });
    SHELLFRAC_INPUT_REQUIRE(it != nodes.end() && it->tag == tag,
                            path << ": element " << element << " references unknown node " << tag);
    return static_cast<std::size_t>(it - nodes.begin());
  };

  const std::vector<RawElement> elements = merge_elements(path, raw);
  auto groups_of = [&](const RawElement& el) -> const std::vector<int>& {
    return raw.group_lists[static_cast<std::size_t>(el.groups)];
  };

  // Triangles (in increasing element tag order) and their order.
  std::vector<const RawElement*> triangles;
  for (const RawElement& el : elements)
    if (element_dim(el.type) == 2) triangles.push_back(&el);
  SHELLFRAC_INPUT_REQUIRE(!triangles.empty(), path << ": the mesh has no triangles (Gmsh types 2 or 9); "
                                                      "is the surface in a physical group?");
  const int type = triangles.front()->type;
  for (const RawElement* t : triangles)
    SHELLFRAC_INPUT_REQUIRE(t->type == type, path << ": triangles " << triangles.front()->tag << " and " << t->tag
                                                  << " have different orders (mixed 3- and 6-node triangles)");

  mesh::SerialMesh m;
  m.source = path;
  m.nodes_per_element = type == type_tri6 ? num_nodes_tri6 : num_nodes_tri3;
  const int npe = m.nodes_per_element;

  // Connectivity in raw node indices first; nodes not used by a triangle are dropped afterwards.
  std::vector<std::size_t> raw_conn;
  raw_conn.reserve(triangles.size() * static_cast<std::size_t>(npe));
  std::vector<char> used(nodes.size(), 0);
  for (const RawElement* t : triangles) {
    for (int a = 0; a < npe; ++a) {
      const std::size_t i = node_index(t->nodes[static_cast<std::size_t>(a)], t->tag);
      for (int b = 0; b < a; ++b)
        SHELLFRAC_INPUT_REQUIRE(t->nodes[static_cast<std::size_t>(b)] != t->nodes[static_cast<std::size_t>(a)],
                                path << ": element " << t->tag << " uses node " << t->nodes[static_cast<std::size_t>(a)]
                                     << " twice");
      raw_conn.push_back(i);
      used[i] = 1;
    }
  }
  std::vector<GlobalId> new_index(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!used[i]) continue;
    new_index[i] = static_cast<GlobalId>(m.coords.size());
    m.coords.push_back(nodes[i].x);
  }
  m.connectivity.reserve(raw_conn.size());
  for (std::size_t i : raw_conn) m.connectivity.push_back(new_index[i]);
  /// New index of a node referenced by a line or point; it must be a node of some triangle.
  auto mesh_node = [&](std::int64_t tag, const RawElement& el, const char* kind) -> GlobalId {
    const GlobalId i = new_index[node_index(tag, el.tag)];
    SHELLFRAC_INPUT_REQUIRE(i >= 0, path << ": " << kind << " element " << el.tag << ": node " << tag
                                         << " is not a node of any triangle");
    return i;
  };

  // Blocks: lowest physical surface tag of each triangle; extra surface groups -> element sets.
  std::map<int, std::vector<GlobalId>> block_members, surface_members;
  std::map<int, bool> surface_is_extra;
  bool has_unassigned = false;
  for (std::size_t e = 0; e < triangles.size(); ++e) {
    const std::vector<int>& g = groups_of(*triangles[e]);
    if (g.empty()) {
      has_unassigned = true;
      continue;
    }
    block_members[g.front()].push_back(static_cast<GlobalId>(e));
    for (std::size_t k = 0; k < g.size(); ++k) {
      surface_members[g[k]].push_back(static_cast<GlobalId>(e));
      if (k > 0) surface_is_extra[g[k]] = true;
    }
  }
  auto group_name = [&](int dim, int tag, const char* prefix) {
    const auto it = raw.physical_names.find({dim, tag});
    return it != raw.physical_names.end() ? it->second : prefix + std::to_string(tag);
  };
  {
    std::vector<int> ids;
    std::vector<std::string> names;
    m.element_block.assign(triangles.size(), -1);
    for (const auto& [tag, members] : block_members) {
      ids.push_back(tag);
      names.push_back(group_name(2, tag, "block_"));
    }
    for (std::size_t b = 0; b < ids.size(); ++b) {
      m.blocks.push_back({names[b], ids[b]});
      for (GlobalId e : block_members[ids[b]]) m.element_block[static_cast<std::size_t>(e)] = static_cast<int>(b);
    }
    if (has_unassigned) {
      // Triangles outside every physical surface: block "block_1" (another id if 1 is a physical tag).
      const int id = unique_id(1, ids);
      std::vector<std::string> taken = names;
      const std::string name = unique_name("block_" + std::to_string(id), id, taken);
      const int b = static_cast<int>(m.blocks.size());
      m.blocks.push_back({name, id});
      for (int& eb : m.element_block)
        if (eb < 0) eb = b;
    }
    std::vector<int> set_ids;
    std::vector<std::string> set_names;
    for (const auto& [tag, extra] : surface_is_extra) {
      mesh::ElementSet set;
      set.id = unique_id(tag, set_ids);
      set.name = unique_name(group_name(2, tag, "block_"), set.id, set_names);
      set.elements = surface_members[tag];  // increasing by construction
      m.element_sets.push_back(std::move(set));
    }
  }

  // Edge table: (low vertex, high vertex) -> (element, local edge), sorted for binary search.
  struct EdgeRef {
    GlobalId lo, hi, element;
    int edge;
  };
  std::vector<EdgeRef> edges;
  edges.reserve(triangles.size() * 3);
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const GlobalId a = m.node(e, edge_vertex[k][0]), b = m.node(e, edge_vertex[k][1]);
      edges.push_back({std::min(a, b), std::max(a, b), e, k});
    }
  auto edge_less = [](const EdgeRef& x, const EdgeRef& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.element < y.element;
  };
  std::sort(edges.begin(), edges.end(), edge_less);

  // Lines -> side sets and node sets (per physical curve); points -> node sets (per physical point).
  std::map<int, std::vector<std::pair<GlobalId, int>>> curve_sides;
  std::map<int, std::vector<GlobalId>> curve_nodes, point_nodes;
  for (const RawElement& el : elements) {
    const int dim = element_dim(el.type);
    if (dim == 1) {
      const GlobalId a = mesh_node(el.nodes[0], el, "line");
      const GlobalId b = mesh_node(el.nodes[1], el, "line");
      const EdgeRef key{std::min(a, b), std::max(a, b), -1, 0};
      auto it = std::lower_bound(edges.begin(), edges.end(), key, edge_less);
      SHELLFRAC_INPUT_REQUIRE(it != edges.end() && it->lo == key.lo && it->hi == key.hi,
                              path << ": line element " << el.tag << " (nodes " << el.nodes[0] << ", "
                                   << el.nodes[1] << ") is not an edge of any triangle");
      if (el.type == type_line3) {
        SHELLFRAC_INPUT_REQUIRE(npe == num_nodes_tri6, path << ": 3-node line element " << el.tag
                                                            << " in a mesh of 3-node triangles");
        const GlobalId mid = mesh_node(el.nodes[2], el, "line");
        SHELLFRAC_INPUT_REQUIRE(mid == m.node(it->element, 3 + it->edge),
                                path << ": line element " << el.tag << ": mid node " << el.nodes[2]
                                     << " is not the mid-side node of the triangle edge it lies on");
      }
      for (; it != edges.end() && it->lo == key.lo && it->hi == key.hi; ++it) {
        // An interior edge in a physical curve (e.g. a crack path) is listed on both sides.
        for (int g : groups_of(el)) {
          curve_sides[g].emplace_back(it->element, it->edge);
          std::vector<GlobalId>& ns = curve_nodes[g];
          ns.push_back(a);
          ns.push_back(b);
          if (npe == num_nodes_tri6) ns.push_back(m.node(it->element, 3 + it->edge));
        }
      }
    } else if (dim == 0 && !groups_of(el).empty()) {
      // Points outside physical groups are skipped: with SaveAll Gmsh writes construction points (arc
      // centres) that are not mesh nodes.
      const GlobalId a = mesh_node(el.nodes[0], el, "point");
      for (int g : groups_of(el)) point_nodes[g].push_back(a);
    }
  }
  auto sort_unique = [](std::vector<GlobalId>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  {
    std::vector<int> ids;
    std::vector<std::string> names;
    for (auto& [tag, sides] : curve_sides) {
      std::sort(sides.begin(), sides.end());
      sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
      mesh::SideSet set;
      set.id = unique_id(tag, ids);
      set.name = unique_name(group_name(1, tag, "curve_"), set.id, names);
      for (const auto& [e, k] : sides) {
        set.elements.push_back(e);
        set.local_edges.push_back(k);
      }
      m.side_sets.push_back(std::move(set));
    }
  }
  {
    // Curves first, then points: on an id or name clash between a curve and a point group, the point
    // group's node set is the one renamed / renumbered.
    std::vector<int> ids;
    std::vector<std::string> names;
    for (auto& [tag, ns] : curve_nodes) {
      mesh::NodeSet set;
      set.id = unique_id(tag, ids);
      set.name = unique_name(group_name(1, tag, "curve_"), set.id, names);
      sort_unique(ns);
      set.nodes = std::move(ns);
      m.node_sets.push_back(std::move(set));
    }
    for (auto& [tag, ns] : point_nodes) {
      mesh::NodeSet set;
      set.id = unique_id(tag, ids);
      set.name = unique_name(group_name(0, tag, "point_"), set.id, names);
      sort_unique(ns);
      set.nodes = std::move(ns);
      m.node_sets.push_back(std::move(set));
    }
  }
  return m;
}

}  // namespace

mesh::SerialMesh read_gmsh(const std::string& path) {
  mesh::SerialMesh m;
  {
    // The file content and the raw lists are released before check_mesh.
    const std::string data = read_file(path);
    RawFile raw = parse(path, data);
    m = assemble(path, raw);
  }
  mesh::check_mesh(m);
  return m;
}

}  // namespace shellfrac::meshio
