#include "shellfrac/solver/mesh_sets.hpp"

#include <algorithm>

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
}  // namespace

MeshSets::MeshSets(const mesh::SerialMesh& mesh, std::string deck_file) : mesh_(mesh), file_(std::move(deck_file)) {}

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
