#include "shellfrac/decomposition/element_migration.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::decomposition {

namespace {

/// (global id, value) pairs sorted by id, looked up by id.
struct SortedPairs {
  std::vector<std::pair<GlobalId, int>> pairs;
  void sort() { std::sort(pairs.begin(), pairs.end()); }
  /// The value of id, -1 if absent.
  int find(GlobalId id) const {
    const auto it = std::lower_bound(pairs.begin(), pairs.end(), std::pair<GlobalId, int>{id, -1});
    return it != pairs.end() && it->first == id ? it->second : -1;
  }
};

/// The ranks' shares of the element ids, each keeping the parts of its share: rank q holds [q width, (q+1) width).
class PartDirectory {
 public:
  /// Registers the parts of the piece's elements. Collective.
  PartDirectory(const ElementPiece& piece, const std::vector<int>& part, GlobalId num_elements, MPI_Comm comm)
      : comm_(comm), P_(parallel::size(comm)) {
    width_ = std::max<GlobalId>(1, (num_elements + P_ - 1) / P_);
    const GlobalId first = width_ * parallel::rank(comm);
    parts_.assign(std::size_t(std::max<GlobalId>(0, std::min(width_, num_elements - first))), -1);
    struct ElementPart {
      GlobalId gid;
      int part;
    };
    std::vector<std::vector<ElementPart>> send(static_cast<std::size_t>(P_));
    for (std::size_t i = 0; i < piece.elements.size(); ++i)
      send[std::size_t(home(piece.elements[i]))].push_back({piece.elements[i], part[i]});
    std::vector<int> counts;
    const auto given = parallel::exchange(std::move(send), counts, comm);
    parallel::on_all_then_agree(
        [&] {
          for (const ElementPart& g : given) {
            int& slot = parts_[std::size_t(g.gid - first)];
            SHELLFRAC_INPUT_REQUIRE(slot < 0, piece.source << ": element " << g.gid + 1 << " is given by two ranks");
            slot = g.part;
          }
        },
        comm);
  }
  /// The parts of `ids` (any rank's ids, in any order). Collective.
  std::vector<int> parts_of(const std::vector<GlobalId>& ids) const {
    std::vector<std::vector<GlobalId>> asked(static_cast<std::size_t>(P_));
    for (const GlobalId id : ids) asked[std::size_t(home(id))].push_back(id);
    // The replies come in the order of the questions, rank by rank.
    std::vector<std::size_t> next(static_cast<std::size_t>(P_), 0), start(static_cast<std::size_t>(P_), 0);
    for (int q = 1; q < P_; ++q) start[std::size_t(q)] = start[std::size_t(q - 1)] + asked[std::size_t(q - 1)].size();
    std::vector<int> counts;
    const auto questions = parallel::exchange(std::move(asked), counts, comm_);
    std::vector<std::vector<int>> answers(static_cast<std::size_t>(P_));
    const GlobalId first = width_ * parallel::rank(comm_);
    std::size_t k = 0;
    for (int q = 0; q < P_; ++q)
      for (int j = 0; j < counts[std::size_t(q)]; ++j, ++k)
        answers[std::size_t(q)].push_back(parts_[std::size_t(questions[k] - first)]);
    const auto replies = parallel::exchange(std::move(answers), counts, comm_);
    std::vector<int> out;
    out.reserve(ids.size());
    for (const GlobalId id : ids) {
      const std::size_t q = std::size_t(home(id));
      out.push_back(replies[start[q] + next[q]++]);
    }
    return out;
  }

 private:
  int home(GlobalId id) const { return static_cast<int>(std::min<GlobalId>(id / width_, P_ - 1)); }
  MPI_Comm comm_;
  int P_;
  GlobalId width_ = 1;
  std::vector<int> parts_;
};

/// Checks the piece on every rank (InputError on all ranks for any problem); returns the number of elements.
GlobalId checked_size(const ElementPiece& piece, const std::vector<int>& part, MPI_Comm comm) {
  const GlobalId n = parallel::sum(GlobalId(piece.elements.size()), comm);
  const int P = parallel::size(comm);
  int npe[2] = {-piece.nodes_per_element, piece.nodes_per_element}, extreme[2] = {0, 0};
  MPI_Allreduce(npe, extreme, 2, MPI_INT, MPI_MAX, comm);
  const bool file_ids = parallel::any(!piece.element_file_ids.empty(), comm);
  parallel::on_all_then_agree(
      [&] {
        const auto sorted = [](const auto& v, auto key) {
          return std::is_sorted(v.begin(), v.end(), [&](const auto& x, const auto& y) { return key(x) < key(y); });
        };
        const auto side_key = [](const SideEntry& x) { return std::tie(x.element, x.local_edge, x.side_set); };
        const auto member_key = [](const mesh::SetEntry& x) { return std::tie(x.member, x.set); };
        SHELLFRAC_REQUIRE(sorted(piece.side_entries, side_key) && sorted(piece.node_set_entries, member_key) &&
                              sorted(piece.element_set_entries, member_key),
                          piece.source << ": the set entries of the piece are not sorted (mesh::ElementPiece)");
        SHELLFRAC_REQUIRE(!file_ids || piece.element_file_ids.size() == piece.elements.size(),
                          piece.source << ": a piece of " << piece.elements.size() << " elements with "
                                       << piece.element_file_ids.size() << " file ids (another rank's piece has them)");
        SHELLFRAC_REQUIRE(-extreme[0] == extreme[1] && (extreme[1] == num_nodes_tri3 || extreme[1] == num_nodes_tri6),
                          piece.source << ": the ranks' pieces have " << -extreme[0] << " to " << extreme[1]
                                       << " nodes per element (3 or 6 on every rank)");
        const std::size_t m = piece.elements.size(), npe_here = std::size_t(piece.nodes_per_element);
        SHELLFRAC_REQUIRE(part.size() == m && piece.blocks.size() == m && piece.nodes.size() == m * npe_here &&
                              piece.coords.size() == m * npe_here,
                          piece.source << ": a piece of " << m << " elements with " << part.size() << " parts, "
                                       << piece.blocks.size() << " blocks, " << piece.nodes.size() << " nodes");
        for (std::size_t i = 0; i < m; ++i) {
          SHELLFRAC_INPUT_REQUIRE(piece.elements[i] >= 0 && piece.elements[i] < n,
                                  piece.source << ": element id " << piece.elements[i] + 1 << " is not in 1.." << n);
          SHELLFRAC_REQUIRE(part[i] >= 0 && part[i] < P, piece.source << ": element " << piece.elements[i] + 1
                                                                      << " has part " << part[i]
                                                                      << ", not a rank in [0, " << P << ")");
        }
      },
      comm);
  return n;
}

/// The part of every element of the piece and of every element across one of the piece's interfaces.
class KnownParts {
 public:
  /// Asks the directory for the far sides' parts. Collective.
  KnownParts(const ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part, GlobalId num_elements,
             MPI_Comm comm)
      : part_(part) {
    for (std::size_t i = 0; i < piece.elements.size(); ++i) here_.pairs.push_back({piece.elements[i], int(i)});
    here_.sort();
    const PartDirectory directory(piece, part, num_elements, comm);
    std::vector<GlobalId> others;  // the far sides of the piece's interfaces that other ranks hold
    for (const auto& f : topo.interfaces)
      for (const GlobalId e : {f.minus.element, f.plus.element})
        if (index(e) < 0) others.push_back(e);
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    const std::vector<int> far_parts = directory.parts_of(others);
    for (std::size_t i = 0; i < others.size(); ++i) far_.pairs.push_back({others[i], far_parts[i]});
  }
  /// The index of element e in the piece, -1 if another rank holds it.
  int index(GlobalId e) const { return here_.find(e); }
  int part_of(GlobalId e) const {
    const int i = here_.find(e);
    return i >= 0 ? part_[std::size_t(i)] : far_.find(e);
  }

 private:
  const std::vector<int>& part_;
  SortedPairs here_, far_;
};

/// The boundary entries of the owned elements: each goes from the rank of the piece that holds it to its element's
/// owner, with the side sets that name it (as (id, side set) pairs). Collective.
std::vector<MigratedBoundary> migrated_boundary(const ElementPiece& piece, const LocalTopology& topo,
                                                const KnownParts& parts, MPI_Comm comm) {
  const std::vector<SideEntry>& sides = piece.side_entries;  // by (element, local edge, set): checked_size
  struct BoundaryWire {
    GlobalId id;
    mesh::ElementEdge side;
    int side_set;  ///< -1: the entry itself
  };
  std::vector<std::vector<BoundaryWire>> boundary(static_cast<std::size_t>(parallel::size(comm)));
  for (std::size_t j = 0; j < topo.boundary.size(); ++j) {
    const auto& b = topo.boundary[j];
    auto& to = boundary[std::size_t(parts.part_of(b.element))];
    to.push_back({topo.boundary_ids[j], b, -1});
    auto it = std::lower_bound(sides.begin(), sides.end(), b, [](const SideEntry& s, const mesh::ElementEdge& x) {
      return std::tie(s.element, s.local_edge) < std::tie(x.element, x.local_edge);
    });
    for (; it != sides.end() && it->element == b.element && it->local_edge == b.local_edge; ++it)
      to.push_back({topo.boundary_ids[j], b, it->side_set});
  }
  std::vector<int> counts;
  auto wires = parallel::exchange(std::move(boundary), counts, comm);
  std::sort(wires.begin(), wires.end(), [](const BoundaryWire& x, const BoundaryWire& y) {
    return std::make_pair(x.id, x.side_set) < std::make_pair(y.id, y.side_set);
  });
  std::vector<MigratedBoundary> out;
  for (const BoundaryWire& w : wires)
    if (w.side_set < 0)
      out.push_back({w.id, w.side, {}});
    else
      out.back().side_sets.push_back(w.side_set);
  return out;
}

/// (element index in the piece, rank) for every element of the piece and every rank that holds it: its owner and each
/// rank that owns an element across one of its interfaces (the ghost layer). By element index, then rank.
std::vector<std::pair<int, int>> element_destinations(const ElementPiece& piece, const LocalTopology& topo,
                                                      const std::vector<int>& part, const KnownParts& parts) {
  std::vector<std::pair<int, int>> destinations;
  for (std::size_t i = 0; i < piece.elements.size(); ++i) destinations.push_back({int(i), part[i]});
  for (const auto& f : topo.interfaces) {
    const int m = parts.index(f.minus.element), p = parts.index(f.plus.element);
    if (m >= 0) destinations.push_back({m, parts.part_of(f.plus.element)});
    if (p >= 0) destinations.push_back({p, parts.part_of(f.minus.element)});
  }
  std::sort(destinations.begin(), destinations.end());
  destinations.erase(std::unique(destinations.begin(), destinations.end()), destinations.end());
  return destinations;
}

/// The entries of `entries` (sorted by key(entry)) whose key is k.
template <class Entry, class Key>
std::pair<typename std::vector<Entry>::const_iterator, typename std::vector<Entry>::const_iterator> entries_of(
    const std::vector<Entry>& entries, GlobalId k, Key key) {
  const auto lo =
      std::lower_bound(entries.begin(), entries.end(), k, [&](const Entry& x, GlobalId v) { return key(x) < v; });
  const auto hi = std::upper_bound(lo, entries.end(), k, [&](GlobalId v, const Entry& x) { return v < key(x); });
  return {lo, hi};
}

/// The set entries of every element of the piece go where the element goes (`destinations`): its side and element
/// set entries, and the node set entries of its nodes. What comes here: the set entries of this rank's overlap.
/// Collective.
mesh::SetEntries migrated_sets(const ElementPiece& piece, const std::vector<std::pair<int, int>>& destinations,
                               MPI_Comm comm) {
  const auto P = static_cast<std::size_t>(parallel::size(comm));
  const std::size_t npe = std::size_t(piece.nodes_per_element);
  std::vector<std::vector<SideEntry>> sides(P);
  std::vector<std::vector<mesh::SetEntry>> node_entries(P), element_entries(P);
  const auto side_key = [](const SideEntry& x) { return x.element; };
  const auto member_key = [](const mesh::SetEntry& x) { return x.member; };
  for (const auto& [i, rank] : destinations) {
    const GlobalId e = piece.elements[std::size_t(i)];
    const auto q = std::size_t(rank);
    const auto [s0, s1] = entries_of(piece.side_entries, e, side_key);
    sides[q].insert(sides[q].end(), s0, s1);
    const auto [e0, e1] = entries_of(piece.element_set_entries, e, member_key);
    element_entries[q].insert(element_entries[q].end(), e0, e1);
    for (std::size_t a = 0; a < npe; ++a) {
      const auto [n0, n1] = entries_of(piece.node_set_entries, piece.nodes[std::size_t(i) * npe + a], member_key);
      node_entries[q].insert(node_entries[q].end(), n0, n1);
    }
  }
  for (auto& entries : node_entries) mesh::sort_set_entries(entries);  // a node of several elements: once
  mesh::SetEntries out;
  std::vector<int> counts;
  out.side_entries = parallel::exchange(std::move(sides), counts, comm);
  out.node_set_entries = parallel::exchange(std::move(node_entries), counts, comm);
  out.element_set_entries = parallel::exchange(std::move(element_entries), counts, comm);
  mesh::sort_side_entries(out.side_entries);
  mesh::sort_set_entries(out.node_set_entries);
  mesh::sort_set_entries(out.element_set_entries);
  return out;
}

/// Every element of the piece where `destinations` sends it; what comes here, owned elements by id first, then the
/// ghosts by id. Collective.
std::vector<MigratedElement> migrated_elements(const ElementPiece& piece, const LocalTopology& topo,
                                               const std::vector<int>& part,
                                               const std::vector<std::pair<int, int>>& destinations, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  const std::size_t npe = std::size_t(piece.nodes_per_element);
  const std::vector<Vec3> directors =
      local_vertex_normals(piece.elements, piece.nodes_per_element, piece.nodes, piece.coords, piece.source, comm);
  std::vector<std::vector<MigratedElement>> send(static_cast<std::size_t>(parallel::size(comm)));
  for (const auto& [i, rank] : destinations) {
    const std::size_t e = std::size_t(i);
    MigratedElement r;
    r.gid = piece.elements[e];
    r.file_id = piece.element_file_ids.empty() ? 0 : piece.element_file_ids[e];  // sizes: checked_size
    r.owner = part[e];
    r.block = piece.blocks[e];
    for (std::size_t a = 0; a < npe; ++a)
      r.nodes[a] = piece.nodes[e * npe + a], r.coords[a] = piece.coords[e * npe + a];
    for (std::size_t a = 0; a < 3; ++a) r.directors[a] = directors[3 * e + a], r.neighbor[a] = topo.neighbor[e][a];
    send[std::size_t(rank)].push_back(r);
  }
  std::vector<int> counts;
  auto elements = parallel::exchange(std::move(send), counts, comm);
  std::sort(elements.begin(), elements.end(), [me](const MigratedElement& x, const MigratedElement& y) {
    return std::make_pair(x.owner != me, x.gid) < std::make_pair(y.owner != me, y.gid);
  });
  return elements;
}

}  // namespace

MigratedPart migrate_elements(const ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part,
                              MPI_Comm comm) {
  MigratedPart out;
  out.nodes_per_element = piece.nodes_per_element;
  out.num_global_elements = checked_size(piece, part, comm);
  const int me = parallel::rank(comm);
  const KnownParts parts(piece, topo, part, out.num_global_elements, comm);
  const auto destinations = element_destinations(piece, topo, part, parts);
  out.elements = migrated_elements(piece, topo, part, destinations, comm);
  out.sets = migrated_sets(piece, destinations, comm);
  out.num_owned = LocalId(std::count_if(out.elements.begin(), out.elements.end(),
                                        [me](const MigratedElement& x) { return x.owner == me; }));
  // An interface goes from the rank that holds its minus side to the owners of its two sides.
  std::vector<std::vector<MigratedInterface>> interfaces(static_cast<std::size_t>(parallel::size(comm)));
  for (std::size_t j = 0; j < topo.interfaces.size(); ++j) {
    const auto& f = topo.interfaces[j];
    if (parts.index(f.minus.element) < 0) continue;
    const MigratedInterface r{topo.interface_ids[j], f, parts.part_of(f.minus.element), parts.part_of(f.plus.element)};
    interfaces[std::size_t(r.minus_owner)].push_back(r);
    if (r.plus_owner != r.minus_owner) interfaces[std::size_t(r.plus_owner)].push_back(r);
  }
  std::vector<int> counts;
  out.interfaces = parallel::exchange(std::move(interfaces), counts, comm);
  std::sort(out.interfaces.begin(), out.interfaces.end(),
            [](const MigratedInterface& x, const MigratedInterface& y) { return x.id < y.id; });
  out.boundary = migrated_boundary(piece, topo, parts, comm);
  return out;
}

}  // namespace shellfrac::decomposition
