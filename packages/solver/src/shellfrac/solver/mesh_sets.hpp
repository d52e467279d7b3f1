#pragma once
/// \file mesh_sets.hpp
/// The sets of the mesh that a deck names: 'all', element sets, blocks, node sets and side sets. Every name
/// is resolved here, so every unknown name gives the same kind of message: an InputError naming the deck,
/// the entry that refers to the set, and the sets of that kind the mesh has.
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}

namespace shellfrac::solver {

/// Name resolution against one mesh. `what` in each call names the referring entry for messages, e.g.
/// "boundary condition 'left' (Elements)".
class MeshSets {
 public:
  MeshSets(const mesh::SerialMesh& mesh, std::string deck_file);

  /// A flag per mesh element: every element for 'all', else the union of the element sets and blocks called
  /// `name`. InputError if there is none.
  std::vector<char> elements(const std::string& what, const std::string& name) const;
  /// A flag per mesh node: the nodes of elements(what, name).
  std::vector<char> nodes_of_elements(const std::string& what, const std::string& name) const;
  /// A flag per mesh node: the node set `name`, or every node for 'all' when `allow_all`. InputError if the
  /// mesh has no such node set.
  std::vector<char> node_set(const std::string& what, const std::string& name, bool allow_all) const;
  /// The (element, local edge) pairs of the side set `name`. InputError if the mesh has none of that name.
  std::set<std::pair<GlobalId, int>> side_set(const std::string& what, const std::string& name) const;

 private:
  const mesh::SerialMesh& mesh_;
  std::string file_;
};

}  // namespace shellfrac::solver
