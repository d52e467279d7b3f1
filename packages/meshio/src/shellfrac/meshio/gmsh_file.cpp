/// \file gmsh_file.cpp
/// Parsing a Gmsh .msh file (2.2 and 4.1, ASCII and binary) into its raw sections. The whole file is read into
/// memory and parsed with a bounds-checked cursor: every count read from the file is checked against the bytes
/// that remain before anything is allocated, so a truncated or hostile file gives an InputError, never a crash.
#include "shellfrac/meshio/gmsh_file.hpp"

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
#include "shellfrac/meshio/gmsh_cursor.hpp"

namespace shellfrac::meshio::gmsh {
namespace {

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

}  // namespace

RawFile read_file_sections(const std::string& path) {
  const std::string data = read_file(path);
  return parse(path, data);
}

}  // namespace shellfrac::meshio::gmsh
