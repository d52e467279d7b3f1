#pragma once
/// \file gmsh_file.hpp
/// A Gmsh .msh file as read (formats 2.2 and 4.1, ASCII and binary), before it becomes a mesh: the nodes and
/// elements with their Gmsh tags and physical groups (internal to meshio; gmsh_reader.cpp assembles the mesh).
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::meshio::gmsh {

// ---------------------------------------------------------------------------------------------------------
// Element types

constexpr int type_line2 = 1;
constexpr int type_tri3 = 2;
constexpr int type_line3 = 8;
constexpr int type_tri6 = 9;
constexpr int type_point = 15;
constexpr int max_element_nodes = 6;  ///< largest supported element (triangle6)

/// Number of nodes of a supported Gmsh element type, 0 for any other type.
inline int supported_num_nodes(int type) {
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
inline int element_dim(int type) {
  switch (type) {
    case type_point: return 0;
    case type_line2:
    case type_line3: return 1;
    default: return 2;
  }
}

/// Human-readable name of a Gmsh element type, for messages about unsupported types (Gmsh manual §9.1).
inline const char* element_type_name(int type) {
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

/// Reads and parses the whole file `path` (every count checked against the bytes that remain before anything is
/// allocated: a truncated or hostile file gives an InputError naming it, never a crash).
RawFile read_file_sections(const std::string& path);

}  // namespace shellfrac::meshio::gmsh
