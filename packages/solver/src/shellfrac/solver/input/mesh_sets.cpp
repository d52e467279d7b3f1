#include "shellfrac/solver/input/mesh_sets.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "shellfrac/core/error.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::solver {

namespace {
/// " 'a' 'b'" for the names of a list of sets.
template <class Sets>
std::string set_names(const Sets& sets) {
  std::string names;
  for (const auto& s : sets) names += " '" + s.name + "'";
  return names;
}

/// The mean of an element's vertices.
Vec3 vertex_centroid(const mesh::SerialMesh& m, GlobalId e) {
  Vec3 c{0, 0, 0};
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k) c[k] += m.coords[m.node(e, a)][k] / 3;
  return c;
}

/// The positions of `ids` among the entities numbered by `file_ids` (by position from 1 when it is empty; a file
/// with fewer ids than entities leaves the rest, the nodes shellfrac added, numbered by position), -1 where none.
std::vector<GlobalId> positions_of(const std::vector<long long>& ids, const mesh::FileIds& file_ids, GlobalId count) {
  std::vector<GlobalId> out;
  std::unordered_map<long long, GlobalId> position;
  for (GlobalId p = 0; p < GlobalId(file_ids.ids.size()); ++p) position.emplace(file_ids.ids[std::size_t(p)], p);
  for (long long id : ids) {
    const auto it = position.find(id);
    if (it != position.end()) out.push_back(it->second);
    else if (file_ids.empty() && id >= 1 && id <= count) out.push_back(GlobalId(id - 1));
    else out.push_back(-1);
  }
  return out;
}

/// " (ids 1 to n)" or " (the ids of its id map, a to b)" for the ids a mesh's nodes or elements have.
std::string id_range(const mesh::FileIds& file_ids, GlobalId count) {
  if (file_ids.empty()) return " (its ids run from 1 to " + std::to_string(count) + ")";
  const auto [lo, hi] = std::minmax_element(file_ids.ids.begin(), file_ids.ids.end());
  return " (its id map runs from " + std::to_string(*lo) + " to " + std::to_string(*hi) + ")";
}

}  // namespace

std::vector<GlobalId> MeshSets::nodes_by_id(const std::string& what, const std::vector<long long>& ids) const {
  const GlobalId count = GlobalId(mesh_.coords.size());
  std::vector<GlobalId> out = positions_of(ids, mesh_.node_ids, count);
  std::vector<char> used(std::size_t(count), 0);
  for (GlobalId n : mesh_.connectivity) used[std::size_t(n)] = 1;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    SHELLFRAC_INPUT_REQUIRE(out[k] >= 0, file_ << ": " << what << " names node " << ids[k] << ", which the mesh ("
                                              << mesh_.source << ") does not have" << id_range(mesh_.node_ids, count));
    SHELLFRAC_INPUT_REQUIRE(used[std::size_t(out[k])], file_ << ": " << what << " names node " << ids[k]
                                                             << ", which no element of the mesh (" << mesh_.source
                                                             << ") uses: it has no motion to record");
  }
  return out;
}

std::vector<GlobalId> MeshSets::elements_by_id(const std::string& what, const std::vector<long long>& ids) const {
  const GlobalId count = mesh_.num_elements();
  std::vector<GlobalId> out = positions_of(ids, mesh_.element_ids, count);
  for (std::size_t k = 0; k < ids.size(); ++k)
    SHELLFRAC_INPUT_REQUIRE(out[k] >= 0, file_ << ": " << what << " names element " << ids[k] << ", which the mesh ("
                                              << mesh_.source << ") does not have"
                                              << id_range(mesh_.element_ids, count));
  return out;
}

MeshSets::MeshSets(const mesh::SerialMesh& mesh, std::string deck_file, std::vector<Region> regions)
    : mesh_(mesh), file_(std::move(deck_file)), regions_(std::move(regions)) {
  for (const auto& r : regions_) {
    const auto named = [&](const auto& sets) {
      return std::any_of(sets.begin(), sets.end(), [&](const auto& s) { return s.name == r.name; });
    };
    SHELLFRAC_INPUT_REQUIRE(r.name != "all" && !named(mesh_.element_sets) && !named(mesh_.blocks) &&
                                !named(mesh_.node_sets) && !named(mesh_.side_sets),
                            file_ << ": region '" << r.name << "' has the name of a set or block of the mesh ("
                                  << mesh_.source << "); rename the region");
  }
}

const Region* MeshSets::region(const std::string& name) const {
  for (const auto& r : regions_)
    if (r.name == name) return &r;
  return nullptr;
}

void MeshSets::require_some(const std::string& what, const std::string& name, const std::vector<char>& member) const {
  if (std::find(member.begin(), member.end(), 1) == member.end()) refuse_empty(what, name);
}

void MeshSets::require_some(const std::string& what, const std::string& name,
                            const std::set<std::pair<GlobalId, int>>& edges) const {
  if (edges.empty()) refuse_empty(what, name);
}

void MeshSets::refuse_empty(const std::string& what, const std::string& name) const {
  SHELLFRAC_INPUT_REQUIRE(false, file_ << ": " << what << " acts on '" << name << "', which selects nothing in the "
                                       << "mesh (" << mesh_.source << "): a region outside the mesh, an empty set, or "
                                       << "a node set that none of its elements touch? It would act on nothing");
}

std::vector<MeshSets::RegionSize> MeshSets::region_sizes() const {
  std::vector<RegionSize> out;
  for (const auto& r : regions_) {
    const auto count = [](const std::vector<char>& v) { return GlobalId(std::count(v.begin(), v.end(), 1)); };
    out.push_back({r.name, count(elements("", r.name)), count(node_set("", r.name, false)),
                   GlobalId(side_set("", r.name).size())});
  }
  return out;
}

std::vector<char> MeshSets::elements(const std::string& what, const std::string& name) const {
  std::vector<char> member(mesh_.num_elements(), 0);
  bool found = name == "all";
  if (found) std::fill(member.begin(), member.end(), 1);
  for (const auto& es : mesh_.element_sets)
    if (es.name == name) {
      found = true;
      for (GlobalId e : es.elements) member[e] = 1;
    }
  for (std::size_t bl = 0; bl < mesh_.blocks.size(); ++bl)
    if (mesh_.blocks[bl].name == name) {
      found = true;
      for (GlobalId e = 0; e < mesh_.num_elements(); ++e)
        if (mesh_.element_block[e] == static_cast<int>(bl)) member[e] = 1;
    }
  if (const Region* r = region(name)) {
    found = true;
    for (GlobalId e = 0; e < mesh_.num_elements(); ++e)
      if (r->contains(vertex_centroid(mesh_, e))) member[e] = 1;
  }
  SHELLFRAC_INPUT_REQUIRE(found, file_ << ": " << what << " names '" << name
                                       << "', which is neither 'all' nor an element set or block of the mesh ("
                                       << mesh_.source << "); its element sets:" << set_names(mesh_.element_sets)
                                       << ", its blocks:" << set_names(mesh_.blocks));
  return member;
}

std::vector<char> MeshSets::nodes_of_elements(const std::string& what, const std::string& name) const {
  const auto in = elements(what, name);
  std::vector<char> member(mesh_.num_nodes(), 0);
  for (GlobalId e = 0; e < mesh_.num_elements(); ++e)
    if (in[e])
      for (int A = 0; A < mesh_.nodes_per_element; ++A) member[mesh_.node(e, A)] = 1;
  return member;
}

std::vector<char> MeshSets::node_set(const std::string& what, const std::string& name, bool allow_all) const {
  if (allow_all && name == "all") return std::vector<char>(mesh_.num_nodes(), 1);
  if (const Region* r = region(name)) {
    std::vector<char> member(mesh_.num_nodes(), 0);
    for (GlobalId n = 0; n < mesh_.num_nodes(); ++n) member[n] = r->contains(mesh_.coords[n]) ? 1 : 0;
    return member;
  }
  const auto it = std::find_if(mesh_.node_sets.begin(), mesh_.node_sets.end(),
                               [&](const auto& ns) { return ns.name == name; });
  SHELLFRAC_INPUT_REQUIRE(it != mesh_.node_sets.end(),
                          file_ << ": " << what << " names node set '" << name << "', which the mesh (" << mesh_.source
                                << ") does not have; its node sets:" << set_names(mesh_.node_sets)
                                << (allow_all ? " (or 'all')" : ""));
  std::vector<char> member(mesh_.num_nodes(), 0);
  for (GlobalId n : it->nodes) member[n] = 1;
  return member;
}

std::set<std::pair<GlobalId, int>> MeshSets::side_set(const std::string& what, const std::string& name) const {
  if (const Region* r = region(name)) {
    std::set<std::pair<GlobalId, int>> edges;
    for (GlobalId e = 0; e < mesh_.num_elements(); ++e)
      for (int k = 0; k < 3; ++k) {
        Vec3 mid;  // the mid-side node (TRI6), or the mean of the edge's vertices (TRI3)
        if (mesh_.nodes_per_element == 6) {
          mid = mesh_.coords[mesh_.node(e, 3 + k)];
        } else {
          for (int c = 0; c < 3; ++c)
            mid[c] = 0.5 * (mesh_.coords[mesh_.node(e, edge_vertex[k][0])][c] +
                            mesh_.coords[mesh_.node(e, edge_vertex[k][1])][c]);
        }
        if (r->contains(mid)) edges.insert({e, k});
      }
    return edges;
  }
  const auto it = std::find_if(mesh_.side_sets.begin(), mesh_.side_sets.end(),
                               [&](const auto& ss) { return ss.name == name; });
  SHELLFRAC_INPUT_REQUIRE(it != mesh_.side_sets.end(),
                          file_ << ": " << what << " names side set '" << name << "', which the mesh (" << mesh_.source
                                << ") does not have; its side sets:" << set_names(mesh_.side_sets));
  std::set<std::pair<GlobalId, int>> edges;
  for (std::size_t k = 0; k < it->elements.size(); ++k) edges.insert({it->elements[k], it->local_edges[k]});
  return edges;
}

}  // namespace shellfrac::solver
