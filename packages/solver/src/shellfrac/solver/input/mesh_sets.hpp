#pragma once
/// \file mesh_sets.hpp
/// The sets of the mesh that a deck names: 'all', element sets, blocks, node sets, side sets, and the deck's
/// regions (regions.hpp), which serve as any of these. Every name is resolved here, so every unknown name gives
/// the same kind of message: an InputError naming the deck, the entry that refers to the set, and the sets of
/// that kind the mesh has.
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/solver/input/regions.hpp"

namespace shellfrac::mesh {
struct SerialMesh;
}

namespace shellfrac::solver {

/// Name resolution against one mesh. `what` in each call names the referring entry for messages, e.g.
/// "boundary condition 'left' (Elements)".
class MeshSets {
 public:
  /// InputError if a region has the name of a set or block of the mesh.
  MeshSets(const mesh::SerialMesh& mesh, std::string deck_file, std::vector<Region> regions = {});

  /// A flag per mesh element: every element for 'all', else the union of the element sets and blocks called
  /// `name`, or the elements whose vertex centroid lies in the region `name`. InputError if there is none.
  std::vector<char> elements(const std::string& what, const std::string& name) const;
  /// A flag per mesh node: the nodes of elements(what, name).
  std::vector<char> nodes_of_elements(const std::string& what, const std::string& name) const;
  /// A flag per mesh node: the node set `name`, the nodes in the region `name`, or every node for 'all' when
  /// `allow_all`. InputError if the mesh has no such node set.
  std::vector<char> node_set(const std::string& what, const std::string& name, bool allow_all) const;
  /// The (element, local edge) pairs of the side set `name`, or of the edges whose mid-side node lies in the
  /// region `name`. InputError if there is none of that name.
  std::set<std::pair<GlobalId, int>> side_set(const std::string& what, const std::string& name) const;

  /// The positions of the mesh nodes (elements) whose ids in the mesh file are `ids`, in their order (a file
  /// without ids numbers by position from 1). InputError naming `what` and the id if the mesh has no such node
  /// (element), or no element uses the node.
  std::vector<GlobalId> nodes_by_id(const std::string& what, const std::vector<long long>& ids) const;
  std::vector<GlobalId> elements_by_id(const std::string& what, const std::vector<long long>& ids) const;

  /// InputError unless `member` (a flag per node or element, from the calls above) or `edges` selects something:
  /// `what` names the entry that acts on it, `name` the set (a region outside the mesh, an empty set in the file,
  /// or a node set disjoint from the entry's elements would make the entry act on nothing, silently).
  void require_some(const std::string& what, const std::string& name, const std::vector<char>& member) const;
  void require_some(const std::string& what, const std::string& name,
                    const std::set<std::pair<GlobalId, int>>& edges) const;

  /// Per region, in deck order: its name and how many elements, nodes and edges it holds.
  struct RegionSize {
    std::string name;
    GlobalId elements, nodes, edges;
  };
  std::vector<RegionSize> region_sizes() const;

 private:
  const Region* region(const std::string& name) const;
  [[noreturn]] void refuse_empty(const std::string& what, const std::string& name) const;
  const mesh::SerialMesh& mesh_;
  std::string file_;
  std::vector<Region> regions_;
};

}  // namespace shellfrac::solver
