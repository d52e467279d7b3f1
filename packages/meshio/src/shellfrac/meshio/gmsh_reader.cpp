/// \file gmsh_reader.cpp
/// Gmsh .msh reader (formats 2.2 and 4.1, ASCII and binary). The whole file is read into memory and parsed
/// into its raw sections (gmsh_file.cpp: nodes and elements with their Gmsh tags and physical groups); the
/// SerialMesh is then assembled from them here by one format-independent routine, so all four variants give the
/// same mesh.
#include "shellfrac/meshio/gmsh_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/meshio/gmsh_file.hpp"

namespace shellfrac::meshio {
namespace {

using namespace gmsh;

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

/// An edge of a triangle, (low vertex, high vertex) -> (element, local edge); sorted for binary search.
struct EdgeRef {
  GlobalId lo, hi, element;
  int edge;
};
bool edge_less(const EdgeRef& x, const EdgeRef& y) {
  return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.element < y.element;
}

void sort_unique(std::vector<GlobalId>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

/// The SerialMesh of a raw file, built step by step: the triangles, the nodes they use (renumbered in increasing
/// Gmsh tag order), the blocks and element sets from the physical surfaces, and the side and node sets from the
/// physical curves and points.
class MeshAssembly {
 public:
  MeshAssembly(const std::string& path, RawFile& raw) : path_(path), raw_(raw), nodes_(raw.nodes) {}

  mesh::SerialMesh build() {
    sort_nodes();
    elements_ = merge_elements(path_, raw_);
    collect_triangles();
    number_nodes();
    assign_blocks();
    build_edge_table();
    collect_curves_and_points();
    make_side_sets();
    make_node_sets();
    return std::move(m_);
  }

 private:
  /// Nodes sorted by tag: the new (0-based) numbering follows increasing Gmsh tag order.
  void sort_nodes() {
    std::sort(nodes_.begin(), nodes_.end(), [](const RawNode& a, const RawNode& b) { return a.tag < b.tag; });
    for (std::size_t i = 1; i < nodes_.size(); ++i)
      SHELLFRAC_INPUT_REQUIRE(nodes_[i].tag != nodes_[i - 1].tag, path_ << ": node tag " << nodes_[i].tag
                                                                        << " is defined twice");
  }

  std::size_t node_index(std::int64_t tag, std::int64_t element) const {
    const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), tag,
                                     [](const RawNode& n, std::int64_t t) { return n.tag < t; });
    SHELLFRAC_INPUT_REQUIRE(it != nodes_.end() && it->tag == tag,
                            path_ << ": element " << element << " references unknown node " << tag);
    return static_cast<std::size_t>(it - nodes_.begin());
  }

  const std::vector<int>& groups_of(const RawElement& el) const {
    return raw_.group_lists[static_cast<std::size_t>(el.groups)];
  }

  /// New index of a node referenced by a line or point; it must be a node of some triangle.
  GlobalId mesh_node(std::int64_t tag, const RawElement& el, const char* kind) const {
    const GlobalId i = new_index_[node_index(tag, el.tag)];
    SHELLFRAC_INPUT_REQUIRE(i >= 0, path_ << ": " << kind << " element " << el.tag << ": node " << tag
                                          << " is not a node of any triangle");
    return i;
  }

  std::string group_name(int dim, int tag, const char* prefix) const {
    const auto it = raw_.physical_names.find({dim, tag});
    return it != raw_.physical_names.end() ? it->second : prefix + std::to_string(tag);
  }

  /// Triangles (in increasing element tag order), all of one order.
  void collect_triangles() {
    for (const RawElement& el : elements_)
      if (element_dim(el.type) == 2) triangles_.push_back(&el);
    SHELLFRAC_INPUT_REQUIRE(!triangles_.empty(), path_ << ": the mesh has no triangles (Gmsh types 2 or 9); "
                                                          "is the surface in a physical group?");
    const int type = triangles_.front()->type;
    for (const RawElement* t : triangles_)
      SHELLFRAC_INPUT_REQUIRE(t->type == type, path_ << ": triangles " << triangles_.front()->tag << " and "
                                                     << t->tag << " have different orders (mixed 3- and 6-node triangles)");
    m_.source = path_;
    m_.nodes_per_element = type == type_tri6 ? num_nodes_tri6 : num_nodes_tri3;
    // Messages name triangles by their Gmsh tags (mesh::FileIds), kept when they are not the positions.
    for (std::size_t e = 0; e < triangles_.size(); ++e) m_.element_ids.ids.push_back(triangles_[e]->tag);
    if (is_positions(m_.element_ids.ids)) m_.element_ids.ids.clear();
  }

  /// Whether ids[i] == i + 1 for every i (a file that numbers by position).
  static bool is_positions(const std::vector<std::int64_t>& ids) {
    for (std::size_t i = 0; i < ids.size(); ++i)
      if (ids[i] != static_cast<std::int64_t>(i) + 1) return false;
    return true;
  }

  /// Connectivity in raw node indices first; nodes not used by a triangle are dropped afterwards.
  void number_nodes() {
    const int npe = m_.nodes_per_element;
    std::vector<std::size_t> raw_conn;
    raw_conn.reserve(triangles_.size() * static_cast<std::size_t>(npe));
    std::vector<char> used(nodes_.size(), 0);
    for (const RawElement* t : triangles_) {
      for (int a = 0; a < npe; ++a) {
        const std::size_t i = node_index(t->nodes[static_cast<std::size_t>(a)], t->tag);
        for (int b = 0; b < a; ++b)
          SHELLFRAC_INPUT_REQUIRE(t->nodes[static_cast<std::size_t>(b)] != t->nodes[static_cast<std::size_t>(a)],
                                  path_ << ": element " << t->tag << " uses node "
                                        << t->nodes[static_cast<std::size_t>(a)] << " twice");
        raw_conn.push_back(i);
        used[i] = 1;
      }
    }
    new_index_.assign(nodes_.size(), -1);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      if (!used[i]) continue;
      new_index_[i] = static_cast<GlobalId>(m_.coords.size());
      m_.coords.push_back(nodes_[i].x);
      m_.node_ids.ids.push_back(nodes_[i].tag);
    }
    if (is_positions(m_.node_ids.ids)) m_.node_ids.ids.clear();
    m_.connectivity.reserve(raw_conn.size());
    for (std::size_t i : raw_conn) m_.connectivity.push_back(new_index_[i]);
  }

  /// Blocks: lowest physical surface tag of each triangle; extra surface groups -> element sets.
  void assign_blocks() {
    std::map<int, std::vector<GlobalId>> block_members, surface_members;
    std::map<int, bool> surface_is_extra;
    bool has_unassigned = false;
    for (std::size_t e = 0; e < triangles_.size(); ++e) {
      const std::vector<int>& g = groups_of(*triangles_[e]);
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
    std::vector<int> ids;
    std::vector<std::string> names;
    m_.element_block.assign(triangles_.size(), -1);
    for (const auto& [tag, members] : block_members) {
      ids.push_back(tag);
      names.push_back(group_name(2, tag, "block_"));
    }
    for (std::size_t b = 0; b < ids.size(); ++b) {
      m_.blocks.push_back({names[b], ids[b]});
      for (GlobalId e : block_members[ids[b]]) m_.element_block[static_cast<std::size_t>(e)] = static_cast<int>(b);
    }
    if (has_unassigned) {
      // Triangles outside every physical surface: block "block_1" (another id if 1 is a physical tag).
      const int id = unique_id(1, ids);
      std::vector<std::string> taken = names;
      const std::string name = unique_name("block_" + std::to_string(id), id, taken);
      const int b = static_cast<int>(m_.blocks.size());
      m_.blocks.push_back({name, id});
      for (int& eb : m_.element_block)
        if (eb < 0) eb = b;
    }
    std::vector<int> set_ids;
    std::vector<std::string> set_names;
    for (const auto& [tag, extra] : surface_is_extra) {
      mesh::ElementSet set;
      set.id = unique_id(tag, set_ids);
      set.name = unique_name(group_name(2, tag, "block_"), set.id, set_names);
      set.elements = surface_members[tag];  // increasing by construction
      m_.element_sets.push_back(std::move(set));
    }
  }

  void build_edge_table() {
    edges_.reserve(triangles_.size() * 3);
    for (GlobalId e = 0; e < m_.num_elements(); ++e)
      for (int k = 0; k < 3; ++k) {
        const GlobalId a = m_.node(e, edge_vertex[k][0]), b = m_.node(e, edge_vertex[k][1]);
        edges_.push_back({std::min(a, b), std::max(a, b), e, k});
      }
    std::sort(edges_.begin(), edges_.end(), edge_less);
  }

  /// Lines -> sides and nodes per physical curve; points -> nodes per physical point.
  void collect_curves_and_points() {
    for (const RawElement& el : elements_) {
      const int dim = element_dim(el.type);
      if (dim == 1) {
        add_line(el);
      } else if (dim == 0 && !groups_of(el).empty()) {
        // Points outside physical groups are skipped: with SaveAll Gmsh writes construction points (arc
        // centres) that are not mesh nodes.
        const GlobalId a = mesh_node(el.nodes[0], el, "point");
        for (int g : groups_of(el)) point_nodes_[g].push_back(a);
      }
    }
  }

  /// A line element: the triangle edges it lies on, for each of its physical curves.
  void add_line(const RawElement& el) {
    const int npe = m_.nodes_per_element;
    const GlobalId a = mesh_node(el.nodes[0], el, "line");
    const GlobalId b = mesh_node(el.nodes[1], el, "line");
    const EdgeRef key{std::min(a, b), std::max(a, b), -1, 0};
    auto it = std::lower_bound(edges_.begin(), edges_.end(), key, edge_less);
    SHELLFRAC_INPUT_REQUIRE(it != edges_.end() && it->lo == key.lo && it->hi == key.hi,
                            path_ << ": line element " << el.tag << " (nodes " << el.nodes[0] << ", " << el.nodes[1]
                                  << ") is not an edge of any triangle");
    if (el.type == type_line3) {
      SHELLFRAC_INPUT_REQUIRE(npe == num_nodes_tri6, path_ << ": 3-node line element " << el.tag
                                                           << " in a mesh of 3-node triangles");
      const GlobalId mid = mesh_node(el.nodes[2], el, "line");
      SHELLFRAC_INPUT_REQUIRE(mid == m_.node(it->element, 3 + it->edge),
                              path_ << ": line element " << el.tag << ": mid node " << el.nodes[2]
                                    << " is not the mid-side node of the triangle edge it lies on");
    }
    for (; it != edges_.end() && it->lo == key.lo && it->hi == key.hi; ++it) {
      // An interior edge in a physical curve (e.g. a crack path) is listed on both sides.
      for (int g : groups_of(el)) {
        curve_sides_[g].emplace_back(it->element, it->edge);
        std::vector<GlobalId>& ns = curve_nodes_[g];
        ns.push_back(a);
        ns.push_back(b);
        if (npe == num_nodes_tri6) ns.push_back(m_.node(it->element, 3 + it->edge));
      }
    }
  }

  void make_side_sets() {
    std::vector<int> ids;
    std::vector<std::string> names;
    for (auto& [tag, sides] : curve_sides_) {
      std::sort(sides.begin(), sides.end());
      sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
      mesh::SideSet set;
      set.id = unique_id(tag, ids);
      set.name = unique_name(group_name(1, tag, "curve_"), set.id, names);
      for (const auto& [e, k] : sides) {
        set.elements.push_back(e);
        set.local_edges.push_back(k);
      }
      m_.side_sets.push_back(std::move(set));
    }
  }

  /// Curves first, then points: on an id or name clash between a curve and a point group, the point group's node
  /// set is the one renamed / renumbered.
  void make_node_sets() {
    std::vector<int> ids;
    std::vector<std::string> names;
    const auto add = [&](std::map<int, std::vector<GlobalId>>& groups, int dim, const char* prefix) {
      for (auto& [tag, ns] : groups) {
        mesh::NodeSet set;
        set.id = unique_id(tag, ids);
        set.name = unique_name(group_name(dim, tag, prefix), set.id, names);
        sort_unique(ns);
        set.nodes = std::move(ns);
        m_.node_sets.push_back(std::move(set));
      }
    };
    add(curve_nodes_, 1, "curve_");
    add(point_nodes_, 0, "point_");
  }

  const std::string& path_;
  RawFile& raw_;
  std::vector<RawNode>& nodes_;
  std::vector<RawElement> elements_;            ///< merged, by increasing tag
  std::vector<const RawElement*> triangles_;    ///< in elements_, by increasing tag
  std::vector<GlobalId> new_index_;             ///< per raw node: its mesh node, -1 if no triangle uses it
  std::vector<EdgeRef> edges_;
  std::map<int, std::vector<std::pair<GlobalId, int>>> curve_sides_;
  std::map<int, std::vector<GlobalId>> curve_nodes_, point_nodes_;
  mesh::SerialMesh m_;
};

}  // namespace

mesh::SerialMesh read_gmsh(const std::string& path) {
  mesh::SerialMesh m;
  {
    // The file content and the raw lists are released before check_mesh.
    RawFile raw = read_file_sections(path);
    m = MeshAssembly(path, raw).build();
  }
  mesh::check_mesh(m);
  return m;
}

}  // namespace shellfrac::meshio
