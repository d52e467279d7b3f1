#include "shellfrac/decomposition/distributed_topology.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <tuple>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/mesh/edge_incidence.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"

namespace shellfrac::decomposition {

namespace {

/// The ranks' shares of the node ids: rank q holds [q width, (q + 1) width) (the last rank also what is above).
struct NodeShares {
  GlobalId width = 1;
  int num_ranks = 1;
  int home(GlobalId node) const { return static_cast<int>(std::min<GlobalId>(node / width, num_ranks - 1)); }
};

/// The shares for node ids up to the largest one any rank gives. Collective.
NodeShares node_shares(GlobalId largest_here, MPI_Comm comm) {
  GlobalId largest = -1;
  SHELLFRAC_REQUIRE(MPI_Allreduce(&largest_here, &largest, 1, MPI_INT64_T, MPI_MAX, comm) == MPI_SUCCESS,
                    "distributed topology: MPI_Allreduce of the node ids failed");
  NodeShares s;
  s.num_ranks = parallel::size(comm);
  s.width = std::max<GlobalId>(1, (largest + s.num_ranks) / s.num_ranks);  // ceil((largest + 1) / P)
  return s;
}

/// The exclusive prefix sums of n over the ranks (0 on rank 0). Collective.
std::array<GlobalId, 3> exclusive_scan(const std::array<GlobalId, 3>& n, MPI_Comm comm) {
  std::array<GlobalId, 3> before{0, 0, 0};
  SHELLFRAC_REQUIRE(MPI_Exscan(n.data(), before.data(), 3, MPI_INT64_T, MPI_SUM, comm) == MPI_SUCCESS,
                    "distributed topology: MPI_Exscan failed");
  if (parallel::rank(comm) == 0) before = {0, 0, 0};
  return before;
}

/// One use of an edge by an element of rank `rank`, where it is element number `index` of the rank's list.
struct EdgeUse {
  GlobalId a, b;  ///< vertex node ids, a < b
  GlobalId element;
  std::int32_t local_edge;
  std::int32_t rank, index;
  std::int32_t ascending;                   ///< the element traverses the edge from a to b
  bool operator<(const EdgeUse& o) const {  // the order of mesh/edge_incidence.hpp
    return std::tie(a, b, element, local_edge) < std::tie(o.a, o.b, o.element, o.local_edge);
  }
};

/// What the edge's home rank tells an element about one of its edges.
struct EdgeAnswer {
  std::int32_t index, local_edge;
  GlobalId edge, interface;
  mesh::ElementEdge neighbor;
};

struct InterfaceRecord {
  GlobalId id;
  mesh::Interface interface;
};

struct BoundaryRecord {
  GlobalId id;
  mesh::ElementEdge side;
};

/// The uses of the edges of this rank's elements, sent to the ranks of their lower vertices and sorted there.
std::vector<EdgeUse> uses_at_home(const std::vector<GlobalId>& elements,
                                  const std::vector<std::array<GlobalId, 3>>& vertices, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  GlobalId largest = -1;
  for (const auto& v : vertices) largest = std::max({largest, v[0], v[1], v[2]});
  const NodeShares shares = node_shares(largest, comm);
  std::vector<std::vector<EdgeUse>> send(std::size_t(shares.num_ranks));
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const GlobalId p = vertices[i][std::size_t(edge_vertex[k][0])], q = vertices[i][std::size_t(edge_vertex[k][1])];
      const EdgeUse u{std::min(p, q), std::max(p, q), elements[i], k, me, static_cast<std::int32_t>(i), p < q};
      send[std::size_t(shares.home(u.a))].push_back(u);
    }
  std::vector<int> counts;
  std::vector<EdgeUse> uses = parallel::exchange(std::move(send), counts, comm);
  std::sort(uses.begin(), uses.end());
  return uses;
}

using mesh::detail::for_each_edge;

/// The message of mesh::build_edge_topology for an edge of 3+ elements, with the elements' numbers in the results.
std::string non_manifold_message(const std::vector<EdgeUse>& uses, std::size_t first, std::size_t last,
                                 const std::string& source) {
  std::ostringstream os;
  os << source << ": edge between nodes " << uses[first].a + 1 << " and " << uses[first].b + 1 << " is shared by "
     << last - first << " elements (";
  for (std::size_t u = first; u < last; ++u) os << (u > first ? ", " : "") << uses[u].element + 1;
  os << " in the results): a T-joint or non-manifold edge. Set 'Mesh->Non-Manifold Edges' to 'Star' or 'Free' to "
        "accept it";
  return os.str();
}

/// The answers, interfaces and boundary entries of the edges at this rank, addressed to the ranks of their elements.
struct HomeRecords {
  std::vector<std::vector<EdgeAnswer>> answers;
  std::vector<std::vector<InterfaceRecord>> interfaces;
  std::vector<std::vector<BoundaryRecord>> boundary;
  std::array<GlobalId, 3> counts{0, 0, 0};  ///< edges, interfaces, boundary entries here
  GlobalId non_manifold = 0;
};

/// The serial rules of mesh::build_edge_topology applied to the sorted uses of this rank's edges. Collective (the
/// scan of the counts gives the global ids).
HomeRecords records_of_edges(const std::vector<EdgeUse>& uses, mesh::NonManifoldPolicy policy,
                             const std::string& source, MPI_Comm comm) {
  using mesh::NonManifoldPolicy;
  HomeRecords h;
  parallel::on_all_then_agree(
      [&] {
        for_each_edge(uses, [&](std::size_t first, std::size_t last) {
          const std::size_t count = last - first;
          if (count >= 3 && policy == NonManifoldPolicy::Error)
            throw InputError(non_manifold_message(uses, first, last, source));
          h.counts[0] += 1;
          h.non_manifold += count >= 3;
          const bool free = count == 1 || (count >= 3 && policy == NonManifoldPolicy::Free);
          h.counts[free ? 2 : 1] += free ? GlobalId(count) : GlobalId(count - 1);
        });
      },
      comm);
  const std::array<GlobalId, 3> before = exclusive_scan(h.counts, comm);
  const std::size_t P = std::size_t(parallel::size(comm));
  h.answers.resize(P), h.interfaces.resize(P), h.boundary.resize(P);
  GlobalId edge = before[0], interface = before[1], boundary = before[2];
  const auto side = [](const EdgeUse& u) { return mesh::ElementEdge{u.element, u.local_edge}; };
  for_each_edge(uses, [&](std::size_t first, std::size_t last) {
    const std::size_t count = last - first;
    const bool free = count == 1 || (count >= 3 && policy == NonManifoldPolicy::Free);
    std::vector<EdgeAnswer> answer;
    for (std::size_t u = first; u < last; ++u)
      answer.push_back({uses[u].index, uses[u].local_edge, edge, -1, mesh::ElementEdge{}});
    if (free) {
      // Free keeps the serial order of the boundary list: the other elements first, then the lowest.
      for (std::size_t k = 1; k <= count; ++k) {
        const EdgeUse& u = uses[first + (count == 1 ? 0 : k % count)];
        h.boundary[std::size_t(u.rank)].push_back({boundary++, side(u)});
      }
    } else {
      const EdgeUse& m = uses[first];
      for (std::size_t u = first + 1; u < last; ++u) {
        const EdgeUse& p = uses[u];
        const mesh::Interface f{edge, side(m), side(p), m.ascending == p.ascending, count >= 3};
        h.interfaces[std::size_t(m.rank)].push_back({interface, f});
        if (p.rank != m.rank) h.interfaces[std::size_t(p.rank)].push_back({interface, f});
        if (u == first + 1) answer[0].interface = interface, answer[0].neighbor = f.plus;
        answer[u - first].interface = interface, answer[u - first].neighbor = f.minus;
        ++interface;
      }
    }
    for (std::size_t u = first; u < last; ++u) h.answers[std::size_t(uses[u].rank)].push_back(answer[u - first]);
    ++edge;
  });
  return h;
}

}  // namespace

LocalTopology build_local_topology(const std::vector<GlobalId>& elements,
                                   const std::vector<std::array<GlobalId, 3>>& vertices, mesh::NonManifoldPolicy policy,
                                   const std::string& source, MPI_Comm comm) {
  SHELLFRAC_REQUIRE(elements.size() == vertices.size(), "build_local_topology: " << elements.size() << " elements with "
                                                                                 << vertices.size()
                                                                                 << " vertex triples");
  HomeRecords home = records_of_edges(uses_at_home(elements, vertices, comm), policy, source, comm);
  LocalTopology t;
  const std::size_t n = elements.size();
  t.element_edges.assign(n, {-1, -1, -1});
  t.element_interface.assign(n, {-1, -1, -1});
  t.neighbor.assign(n, {mesh::ElementEdge{}, mesh::ElementEdge{}, mesh::ElementEdge{}});
  std::vector<int> counts;
  for (const EdgeAnswer& a : parallel::exchange(std::move(home.answers), counts, comm)) {
    t.element_edges[std::size_t(a.index)][std::size_t(a.local_edge)] = a.edge;
    t.element_interface[std::size_t(a.index)][std::size_t(a.local_edge)] = a.interface;
    t.neighbor[std::size_t(a.index)][std::size_t(a.local_edge)] = a.neighbor;
  }
  auto interfaces = parallel::exchange(std::move(home.interfaces), counts, comm);
  std::sort(interfaces.begin(), interfaces.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
  for (const auto& r : interfaces) t.interface_ids.push_back(r.id), t.interfaces.push_back(r.interface);
  auto boundary = parallel::exchange(std::move(home.boundary), counts, comm);
  std::sort(boundary.begin(), boundary.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
  for (const auto& r : boundary) t.boundary_ids.push_back(r.id), t.boundary.push_back(r.side);
  std::array<GlobalId, 4> here{home.counts[0], home.counts[1], home.counts[2], home.non_manifold}, all{};
  SHELLFRAC_REQUIRE(MPI_Allreduce(here.data(), all.data(), 4, MPI_INT64_T, MPI_SUM, comm) == MPI_SUCCESS,
                    "build_local_topology: MPI_Allreduce of the counts failed");
  t.num_edges = all[0], t.num_interfaces = all[1], t.num_boundary = all[2], t.num_non_manifold_edges = all[3];
  return t;
}

namespace {

/// One element's term of the normal at one of its vertices, for the rank of the node's share.
struct NormalTerm {
  GlobalId node, element;
  std::int32_t rank, slot;  ///< the asking rank, and 3 index + vertex there
  Vec3 term;
};

struct NormalAnswer {
  std::int32_t slot;
  Vec3 normal;
};

}  // namespace

std::vector<Vec3> local_vertex_normals(const std::vector<GlobalId>& elements, int nodes_per_element,
                                       const std::vector<GlobalId>& nodes, const std::vector<Vec3>& coords,
                                       const std::string& source, MPI_Comm comm) {
  const std::size_t npe = std::size_t(nodes_per_element), n = elements.size();
  SHELLFRAC_REQUIRE(nodes.size() == n * npe && coords.size() == n * npe,
                    "local_vertex_normals: " << nodes.size() << " nodes and " << coords.size() << " coordinates for "
                                             << n << " elements of " << npe << " nodes");
  const int me = parallel::rank(comm);
  GlobalId largest = -1;
  for (const GlobalId v : nodes) largest = std::max(largest, v);
  const NodeShares shares = node_shares(largest, comm);
  std::vector<std::vector<NormalTerm>> send(std::size_t(shares.num_ranks));
  parallel::on_all_then_agree(
      [&] {
        for (std::size_t i = 0; i < n; ++i)
          for (int a = 0; a < 3; ++a) {
            NormalTerm t{nodes[i * npe + std::size_t(a)], elements[i], me, static_cast<std::int32_t>(3 * i) + a, {}};
            SHELLFRAC_INPUT_REQUIRE(
                mesh::vertex_normal_term(nodes_per_element, &coords[i * npe], a, t.term),
                source << ": element " << elements[i] + 1 << " has a zero Jacobian at vertex " << a + 1);
            send[std::size_t(shares.home(t.node))].push_back(t);
          }
      },
      comm);
  std::vector<int> counts;
  std::vector<NormalTerm> terms = parallel::exchange(std::move(send), counts, comm);
  // The serial sum runs in element order; a node is a vertex of an element at most once (mesh::check_mesh).
  std::sort(terms.begin(), terms.end(),
            [](const auto& x, const auto& y) { return std::tie(x.node, x.element) < std::tie(y.node, y.element); });
  std::vector<std::vector<NormalAnswer>> answers(std::size_t(shares.num_ranks));
  for (std::size_t i = 0; i < terms.size();) {
    std::size_t j = i;
    Vec3 sum{0, 0, 0};
    for (; j < terms.size() && terms[j].node == terms[i].node; ++j) sum = mesh::add(sum, terms[j].term);
    const Vec3 normal = mesh::unit_or_zero(sum);
    for (; i < j; ++i) answers[std::size_t(terms[i].rank)].push_back({terms[i].slot, normal});
  }
  std::vector<Vec3> normals(3 * n, Vec3{0, 0, 0});
  for (const NormalAnswer& a : parallel::exchange(std::move(answers), counts, comm))
    normals[std::size_t(a.slot)] = a.normal;
  return normals;
}

}  // namespace shellfrac::decomposition
