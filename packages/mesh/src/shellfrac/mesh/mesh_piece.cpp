#include "shellfrac/mesh/mesh_piece.hpp"

#include <algorithm>
#include <tuple>

namespace shellfrac::mesh {

namespace {

template <class Set>
std::vector<SetLabel> labels_of(const std::vector<Set>& sets) {
  std::vector<SetLabel> out;
  out.reserve(sets.size());
  for (const auto& s : sets) out.push_back({s.name, s.id});
  return out;
}

}  // namespace

MeshOutline outline_of(const SerialMesh& mesh) {
  MeshOutline o;
  o.nodes_per_element = mesh.nodes_per_element;
  o.num_elements = mesh.num_elements();
  o.num_nodes = mesh.num_nodes();
  o.blocks = mesh.blocks;
  o.node_sets = labels_of(mesh.node_sets);
  o.side_sets = labels_of(mesh.side_sets);
  o.element_sets = labels_of(mesh.element_sets);
  o.source = mesh.source;
  return o;
}

ElementPiece element_range_piece(const SerialMesh& mesh, GlobalId first, GlobalId end) {
  std::vector<GlobalId> elements;
  for (GlobalId e = first; e < end; ++e) elements.push_back(e);
  return piece_of_elements(mesh, elements);
}

ElementPiece piece_of_elements(const SerialMesh& mesh, const std::vector<GlobalId>& elements) {
  ElementPiece p;
  const int npe = mesh.nodes_per_element;
  p.nodes_per_element = npe;
  p.source = mesh.source;
  p.elements = elements;
  for (GlobalId e : elements) {
    p.blocks.push_back(mesh.element_block[static_cast<std::size_t>(e)]);
    for (int a = 0; a < npe; ++a) {
      p.nodes.push_back(mesh.node(e, a));
      p.coords.push_back(mesh.coords[static_cast<std::size_t>(mesh.node(e, a))]);
    }
  }
  if (!mesh.element_ids.empty())
    for (GlobalId e : elements) p.element_file_ids.push_back(mesh.element_ids.ids[static_cast<std::size_t>(e)]);
  SetEntries sets = set_entries_of(mesh, elements);
  p.side_entries = std::move(sets.side_entries);
  p.node_set_entries = std::move(sets.node_set_entries);
  p.element_set_entries = std::move(sets.element_set_entries);
  return p;
}

SetEntries set_entries_of(const SerialMesh& mesh, const std::vector<GlobalId>& elements) {
  SetEntries out;
  std::vector<GlobalId> mine = elements;
  std::sort(mine.begin(), mine.end());
  const auto here = [&](GlobalId e) { return std::binary_search(mine.begin(), mine.end(), e); };
  for (std::size_t s = 0; s < mesh.side_sets.size(); ++s) {
    const SideSet& ss = mesh.side_sets[s];
    for (std::size_t k = 0; k < ss.elements.size(); ++k)
      if (here(ss.elements[k])) out.side_entries.push_back({ss.elements[k], ss.local_edges[k], static_cast<int>(s)});
  }
  for (std::size_t s = 0; s < mesh.element_sets.size(); ++s)
    for (GlobalId e : mesh.element_sets[s].elements)
      if (here(e)) out.element_set_entries.push_back({e, static_cast<int>(s)});
  std::vector<GlobalId> used;
  for (GlobalId e : mine)
    for (int a = 0; a < mesh.nodes_per_element; ++a) used.push_back(mesh.node(e, a));
  std::sort(used.begin(), used.end());
  for (std::size_t s = 0; s < mesh.node_sets.size(); ++s)
    for (GlobalId n : mesh.node_sets[s].nodes)
      if (std::binary_search(used.begin(), used.end(), n)) out.node_set_entries.push_back({n, static_cast<int>(s)});
  sort_side_entries(out.side_entries);
  sort_set_entries(out.node_set_entries);
  sort_set_entries(out.element_set_entries);
  return out;
}

void check_piece_elements(const ElementPiece& piece, GlobalId num_nodes) {
  const int npe = piece.nodes_per_element;
  const FileIds positions;
  for (std::size_t i = 0; i < piece.elements.size(); ++i) {
    const std::size_t at = i * static_cast<std::size_t>(npe);
    const GlobalId e = piece.elements[i];
    const std::int64_t file_id = piece.element_file_ids.empty() ? e + 1 : piece.element_file_ids[i];
    check_element_nodes(e, file_id, &piece.nodes[at], npe, num_nodes, positions, piece.source);
    check_element_area(e, file_id, piece.coords[at], piece.coords[at + 1], piece.coords[at + 2], piece.source);
  }
}

void sort_set_entries(std::vector<SetEntry>& entries) {
  const auto key = [](const SetEntry& x) { return std::tie(x.member, x.set); };
  std::sort(entries.begin(), entries.end(), [&](const SetEntry& x, const SetEntry& y) { return key(x) < key(y); });
  entries.erase(std::unique(entries.begin(), entries.end(),
                            [&](const SetEntry& x, const SetEntry& y) { return key(x) == key(y); }),
                entries.end());
}

void sort_side_entries(std::vector<SideEntry>& entries) {
  const auto key = [](const SideEntry& x) { return std::tie(x.element, x.local_edge, x.side_set); };
  std::sort(entries.begin(), entries.end(), [&](const SideEntry& x, const SideEntry& y) { return key(x) < key(y); });
}

}  // namespace shellfrac::mesh
