#include "shellfrac/mesh/serial_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/core/printable_text.hpp"
#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/mesh/edge_incidence.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"

namespace shellfrac::mesh {

Vec3 ExactSurface::project(const Vec3& x) const {
  if (kind == Kind::None) return x;
  const Vec3 d = sub(x, axis_point);
  const double along = dot(d, axis_direction);
  const Vec3 radial = sub(d, scale(along, axis_direction));
  const double r = norm(radial);
  if (r == 0.0) return x;
  return add(add(axis_point, scale(along, axis_direction)), scale(radius / r, radial));
}

double vertex_area(const SerialMesh& mesh, GlobalId e) {
  const Vec3& a = mesh.coords[mesh.node(e, 0)];
  const Vec3& b = mesh.coords[mesh.node(e, 1)];
  const Vec3& c = mesh.coords[mesh.node(e, 2)];
  return 0.5 * norm(cross(sub(b, a), sub(c, a)));
}

namespace {

template <class Set>
void check_labels_of(const std::vector<Set>& sets, const char* kind, const std::string& source) {
  std::vector<std::pair<int, std::string>> ids_and_names;
  for (const auto& s : sets) ids_and_names.emplace_back(s.id, s.name);
  check_ids_and_names(ids_and_names, kind, source);
}

template <class T>
void check_sorted_in_range(const std::vector<T>& v, GlobalId n, const char* kind, const std::string& name,
                           const char* what, const std::string& source) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    SHELLFRAC_INPUT_REQUIRE(v[i] >= 0 && v[i] < n, source << ": " << kind << " '" << name << "' refers to " << what
                                                          << " " << v[i] << ", but the mesh has " << n << " " << what
                                                          << "s");
    SHELLFRAC_INPUT_REQUIRE(i == 0 || v[i - 1] < v[i],
                            source << ": " << kind << " '" << name << "' is not sorted/unique at entry " << i);
  }
}

/// Node-set membership of a node created on the edge (a, b) (rule documented in serial_mesh.hpp).
/// `uses[first, last)` are the uses of that edge; third(e, k) is the vertex of e opposite local edge k.
template <class ThirdFn>
bool joins_set(const std::vector<char>& member, GlobalId a, GlobalId b, const std::vector<detail::EdgeUse>& uses,
               std::size_t first, std::size_t last, ThirdFn third) {
  if (!member[a] || !member[b]) return false;
  if (last - first == 1) return true;  // boundary edge
  for (std::size_t u = first; u < last; ++u)
    if (member[third(uses[u].element, uses[u].local_edge)]) return false;
  return true;
}

/// Adds the created edge nodes to node sets. edge_nodes[g] = node made on the g-th edge group of `uses`.
template <class ThirdFn>
void extend_node_sets(SerialMesh& mesh, GlobalId num_nodes_before, const std::vector<detail::EdgeUse>& uses,
                      const std::vector<GlobalId>& edge_nodes, ThirdFn third) {
  for (auto& ns : mesh.node_sets) {
    std::vector<char> member(mesh.coords.size(), 0);
    for (GlobalId n : ns.nodes) member[n] = 1;
    std::size_t g = 0;
    detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
      if (joins_set(member, uses[first].a, uses[first].b, uses, first, last, third)) ns.nodes.push_back(edge_nodes[g]);
      ++g;
    });
    std::sort(ns.nodes.begin(), ns.nodes.end());
  }
  (void)num_nodes_before;
}

/// Children of a refined triangle, as indices into the parent's 6 P2 node positions (vertices 0,1,2,
/// mid-sides 3,4,5): corner children at vertices 1, 2, 3, then the centre one. All counter-clockwise.
constexpr int child_nodes[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {4, 5, 3}};

/// Maps sets to the children: parent edge k -> (child k, edge k) and (child (k+1)%3, edge k).
void refine_sets(SerialMesh& mesh) {
  for (auto& ss : mesh.side_sets) {
    std::vector<std::pair<GlobalId, int>> out;
    for (std::size_t i = 0; i < ss.elements.size(); ++i) {
      const GlobalId e = ss.elements[i];
      const int k = ss.local_edges[i];
      out.push_back({4 * e + k, k});
      out.push_back({4 * e + (k + 1) % 3, k});
    }
    std::sort(out.begin(), out.end());
    ss.elements.clear();
    ss.local_edges.clear();
    for (auto& [e, k] : out) ss.elements.push_back(e), ss.local_edges.push_back(k);
  }
  for (auto& es : mesh.element_sets) {
    std::vector<GlobalId> out;
    for (GlobalId e : es.elements)
      for (int c = 0; c < 4; ++c) out.push_back(4 * e + c);
    es.elements = out;
  }
  std::vector<int> blocks(4 * mesh.element_block.size());
  for (std::size_t e = 0; e < mesh.element_block.size(); ++e)
    for (int c = 0; c < 4; ++c) blocks[4 * e + c] = mesh.element_block[e];
  mesh.element_block = blocks;
}

}  // namespace

std::string element_label(GlobalId e, std::int64_t file_id) {
  if (file_id == e + 1) return "element " + std::to_string(e + 1);
  return "element " + std::to_string(file_id) + " (" + std::to_string(e + 1) + " in the results)";
}

std::string FileIds::element(GlobalId e) const {
  return element_label(e, ids.empty() ? e + 1 : ids[static_cast<std::size_t>(e)]);
}

std::string FileIds::node(GlobalId n) const {
  if (ids.empty()) return "node " + std::to_string(n + 1);
  if (n >= static_cast<GlobalId>(ids.size())) return "mid-side node " + std::to_string(n + 1) + " (added by shellfrac)";
  return "node " + std::to_string(ids[static_cast<std::size_t>(n)]);
}

void check_ids_and_names(const std::vector<std::pair<int, std::string>>& ids_and_names, const char* kind,
                         const std::string& source) {
  std::set<int> ids;
  std::set<std::string> names;
  for (const auto& [id, name] : ids_and_names) {
    SHELLFRAC_INPUT_REQUIRE(id > 0, source << ": " << kind << " '" << name << "' has id " << id
                                           << "; ids must be positive");
    SHELLFRAC_INPUT_REQUIRE(ids.insert(id).second, source << ": two " << kind << "s have id " << id);
    SHELLFRAC_INPUT_REQUIRE(!name.empty(), source << ": " << kind << " " << id << " has an empty name");
    const std::string bad = params::unprintable_part(name);
    SHELLFRAC_INPUT_REQUIRE(bad.empty(), source << ": the name '" << params::escaped(name) << "' of " << kind << " "
                                                << id << " has " << bad << "; names must be printable UTF-8");
    SHELLFRAC_INPUT_REQUIRE(names.insert(name).second, source << ": two " << kind << "s are named '" << name << "'");
  }
}

void check_element_nodes(GlobalId e, std::int64_t element_file_id, const GlobalId* nodes, int nodes_per_element,
                         GlobalId num_nodes, const FileIds& node_ids, const std::string& source) {
  for (int a = 0; a < nodes_per_element; ++a) {
    const GlobalId n = nodes[a];
    SHELLFRAC_INPUT_REQUIRE(n >= 0 && n < num_nodes, source << ": " << element_label(e, element_file_id)
                                                            << " refers to node " << n + 1
                                                            << " (a position in the file), but the mesh has "
                                                            << num_nodes << " nodes");
    for (int c = 0; c < a; ++c)
      SHELLFRAC_INPUT_REQUIRE(nodes[c] != n, source << ": " << element_label(e, element_file_id) << " uses "
                                                    << node_ids.node(n) << " twice");
  }
}

void check_element_area(GlobalId e, std::int64_t element_file_id, const Vec3& a, const Vec3& b, const Vec3& c,
                        const std::string& source) {
  // Zero-area (collinear) triangles have no normal and no stable time step.
  const double h2 = std::max({norm2(sub(b, a)), norm2(sub(c, b)), norm2(sub(a, c))});
  SHELLFRAC_INPUT_REQUIRE(0.5 * norm(cross(sub(b, a), sub(c, a))) > 1e-12 * h2,
                          source << ": " << element_label(e, element_file_id)
                                 << " is degenerate (its vertices are collinear)");
}

void check_mesh(const SerialMesh& mesh) {
  const std::string& src = mesh.source;
  SHELLFRAC_INPUT_REQUIRE(mesh.nodes_per_element == 3 || mesh.nodes_per_element == 6,
                          src << ": elements must have 3 or 6 nodes, not " << mesh.nodes_per_element);
  const GlobalId ne = mesh.num_elements(), nn = mesh.num_nodes();
  SHELLFRAC_INPUT_REQUIRE(ne > 0, src << ": the mesh has no triangle elements");
  SHELLFRAC_INPUT_REQUIRE(static_cast<GlobalId>(mesh.connectivity.size()) == ne * mesh.nodes_per_element,
                          src << ": connectivity has " << mesh.connectivity.size() << " entries, expected "
                              << ne * mesh.nodes_per_element);
  SHELLFRAC_INPUT_REQUIRE(!mesh.blocks.empty(), src << ": the mesh has no element block");
  SHELLFRAC_INPUT_REQUIRE(mesh.element_ids.empty() || GlobalId(mesh.element_ids.ids.size()) == ne,
                          src << ": the element id map has " << mesh.element_ids.ids.size() << " entries for " << ne
                              << " elements");
  SHELLFRAC_INPUT_REQUIRE(GlobalId(mesh.node_ids.ids.size()) <= nn,
                          src << ": the node id map has " << mesh.node_ids.ids.size() << " entries for " << nn
                              << " nodes");
  const auto& element = mesh.element_ids;
  const auto& node = mesh.node_ids;
  check_labels_of(mesh.blocks, "element block", src);
  check_labels_of(mesh.node_sets, "node set", src);
  check_labels_of(mesh.side_sets, "side set", src);
  check_labels_of(mesh.element_sets, "element set", src);
  for (const auto& c : mesh.coords)
    SHELLFRAC_INPUT_REQUIRE(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]),
                            src << ": a node has a non-finite coordinate");
  for (GlobalId e = 0; e < ne; ++e) {
    const int b = mesh.element_block[e];
    SHELLFRAC_INPUT_REQUIRE(b >= 0 && b < static_cast<int>(mesh.blocks.size()),
                            src << ": " << element.element(e) << " has no valid block");
    const GlobalId* nodes = &mesh.connectivity[static_cast<std::size_t>(e * mesh.nodes_per_element)];
    const std::int64_t file_id = element.empty() ? e + 1 : element.ids[static_cast<std::size_t>(e)];
    check_element_nodes(e, file_id, nodes, mesh.nodes_per_element, nn, node, src);
    check_element_area(e, file_id, mesh.coords[nodes[0]], mesh.coords[nodes[1]], mesh.coords[nodes[2]], src);
  }
  for (const auto& s : mesh.node_sets) check_sorted_in_range(s.nodes, nn, "node set", s.name, "node", src);
  for (const auto& s : mesh.element_sets) check_sorted_in_range(s.elements, ne, "element set", s.name, "element", src);
  for (const auto& s : mesh.side_sets) {
    SHELLFRAC_INPUT_REQUIRE(s.elements.size() == s.local_edges.size(),
                            src << ": side set '" << s.name << "' has mismatched element/edge lists");
    for (std::size_t i = 0; i < s.elements.size(); ++i) {
      SHELLFRAC_INPUT_REQUIRE(s.elements[i] >= 0 && s.elements[i] < ne,
                              src << ": side set '" << s.name << "' refers to element " << s.elements[i] + 1
                                  << ", but the mesh has " << ne << " elements");
      SHELLFRAC_INPUT_REQUIRE(s.local_edges[i] >= 0 && s.local_edges[i] < 3,
                              src << ": side set '" << s.name << "' has an invalid edge number " << s.local_edges[i]);
    }
  }
}

std::vector<char> pack(const SerialMesh& m) {
  parallel::ByteWriter w;
  w.put(m.nodes_per_element);
  w.put_vector(m.coords);
  w.put_vector(m.connectivity);
  w.put_vector(m.element_block);
  w.put<std::uint64_t>(m.blocks.size());
  for (const auto& b : m.blocks) w.put_string(b.name), w.put(b.id);
  w.put<std::uint64_t>(m.node_sets.size());
  for (const auto& s : m.node_sets) w.put_string(s.name), w.put(s.id), w.put_vector(s.nodes);
  w.put<std::uint64_t>(m.side_sets.size());
  for (const auto& s : m.side_sets) w.put_string(s.name), w.put(s.id), w.put_vector(s.elements), w.put_vector(s.local_edges);
  w.put<std::uint64_t>(m.element_sets.size());
  for (const auto& s : m.element_sets) w.put_string(s.name), w.put(s.id), w.put_vector(s.elements);
  w.put(m.surface.kind);
  w.put(m.surface.axis_point);
  w.put(m.surface.axis_direction);
  w.put(m.surface.radius);
  w.put_string(m.source);
  w.put_vector(m.element_ids.ids);
  w.put_vector(m.node_ids.ids);
  return std::move(w.buffer());
}

SerialMesh unpack(const std::vector<char>& buffer) {
  parallel::ByteReader r(buffer);
  SerialMesh m;
  m.nodes_per_element = r.get<int>();
  m.coords = r.get_vector<Vec3>();
  m.connectivity = r.get_vector<GlobalId>();
  m.element_block = r.get_vector<int>();
  m.blocks.resize(r.get<std::uint64_t>());
  for (auto& b : m.blocks) b.name = r.get_string(), b.id = r.get<int>();
  m.node_sets.resize(r.get<std::uint64_t>());
  for (auto& s : m.node_sets) s.name = r.get_string(), s.id = r.get<int>(), s.nodes = r.get_vector<GlobalId>();
  m.side_sets.resize(r.get<std::uint64_t>());
  for (auto& s : m.side_sets) {
    s.name = r.get_string();
    s.id = r.get<int>();
    s.elements = r.get_vector<GlobalId>();
    s.local_edges = r.get_vector<int>();
  }
  m.element_sets.resize(r.get<std::uint64_t>());
  for (auto& s : m.element_sets) s.name = r.get_string(), s.id = r.get<int>(), s.elements = r.get_vector<GlobalId>();
  m.surface.kind = r.get<ExactSurface::Kind>();
  m.surface.axis_point = r.get<Vec3>();
  m.surface.axis_direction = r.get<Vec3>();
  m.surface.radius = r.get<double>();
  m.source = r.get_string();
  m.element_ids.ids = r.get_vector<std::int64_t>();
  m.node_ids.ids = r.get_vector<std::int64_t>();
  return m;
}

void broadcast(SerialMesh& mesh, int root, MPI_Comm comm) {
  std::vector<char> buf;
  if (parallel::rank(comm) == root) buf = pack(mesh);
  parallel::broadcast(buf, root, comm);
  if (parallel::rank(comm) != root) mesh = unpack(buf);
}

void promote_to_p2(SerialMesh& mesh) {
  if (mesh.nodes_per_element == 6) return;
  const GlobalId ne = mesh.num_elements();
  const auto& conn = mesh.connectivity;
  const auto uses = detail::edge_uses(ne, [&](GlobalId e, int i) { return conn[3 * e + i]; });
  std::vector<GlobalId> p2(6 * ne);
  for (GlobalId e = 0; e < ne; ++e)
    for (int i = 0; i < 3; ++i) p2[6 * e + i] = conn[3 * e + i];
  const GlobalId nn0 = mesh.num_nodes();
  std::vector<GlobalId> edge_nodes;
  detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
    const GlobalId m = mesh.num_nodes();
    mesh.coords.push_back(mesh.surface.project(scale(0.5, add(mesh.coords[uses[first].a], mesh.coords[uses[first].b]))));
    edge_nodes.push_back(m);
    for (std::size_t u = first; u < last; ++u) p2[6 * uses[u].element + 3 + uses[u].local_edge] = m;
  });
  extend_node_sets(mesh, nn0, uses, edge_nodes, [&](GlobalId e, int k) { return conn[3 * e + (k + 2) % 3]; });
  mesh.connectivity = std::move(p2);
  mesh.nodes_per_element = 6;
}

void refine_uniform(SerialMesh& mesh) {
  mesh.element_ids.ids.clear(), mesh.node_ids.ids.clear();  // new elements and nodes: numbered by position
  const GlobalId ne = mesh.num_elements();
  const int npe = mesh.nodes_per_element;
  const GlobalId nn0 = mesh.num_nodes();
  // parent_nodes[6e + i]: the parent's 6 P2 node positions (vertices, then edge mid-points).
  std::vector<GlobalId> parent_nodes(6 * ne);
  if (npe == 6) {
    parent_nodes = mesh.connectivity;
  } else {
    const auto& conn = mesh.connectivity;
    const auto uses = detail::edge_uses(ne, [&](GlobalId e, int i) { return conn[3 * e + i]; });
    std::vector<GlobalId> edge_nodes;
    detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
      const GlobalId m = mesh.num_nodes();
      mesh.coords.push_back(
          mesh.surface.project(scale(0.5, add(mesh.coords[uses[first].a], mesh.coords[uses[first].b]))));
      edge_nodes.push_back(m);
      for (std::size_t u = first; u < last; ++u) parent_nodes[6 * uses[u].element + 3 + uses[u].local_edge] = m;
    });
    for (GlobalId e = 0; e < ne; ++e)
      for (int i = 0; i < 3; ++i) parent_nodes[6 * e + i] = conn[3 * e + i];
    extend_node_sets(mesh, nn0, uses, edge_nodes, [&](GlobalId e, int k) { return conn[3 * e + (k + 2) % 3]; });
  }
  // Children's vertices.
  std::vector<GlobalId> child(4 * ne * npe);
  for (GlobalId e = 0; e < ne; ++e)
    for (int c = 0; c < 4; ++c)
      for (int i = 0; i < 3; ++i) child[(4 * e + c) * npe + i] = parent_nodes[6 * e + child_nodes[c][i]];
  if (npe == 6) {
    // New mid-side nodes of the children, on the parent's P2 map (then on the exact surface).
    const GlobalId nc = 4 * ne;
    const auto uses = detail::edge_uses(nc, [&](GlobalId c, int i) { return child[6 * c + i]; });
    const GlobalId nn1 = mesh.num_nodes();
    std::vector<GlobalId> edge_nodes;
    detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
      const GlobalId c = uses[first].element, p = c / 4;
      const int k = uses[first].local_edge;
      const int i0 = child_nodes[c % 4][edge_vertex[k][0]], i1 = child_nodes[c % 4][edge_vertex[k][1]];
      const double xi1 = 0.5 * (p2_node_xi[i0][0] + p2_node_xi[i1][0]);
      const double xi2 = 0.5 * (p2_node_xi[i0][1] + p2_node_xi[i1][1]);
      double N[6], dN[6][2];
      p2_shape(xi1, xi2, N, dN);
      Vec3 x{0, 0, 0};
      for (int a = 0; a < 6; ++a) x = add(x, scale(N[a], mesh.coords[parent_nodes[6 * p + a]]));
      const GlobalId m = mesh.num_nodes();
      mesh.coords.push_back(mesh.surface.project(x));
      edge_nodes.push_back(m);
      for (std::size_t u = first; u < last; ++u) child[6 * uses[u].element + 3 + uses[u].local_edge] = m;
    });
    extend_node_sets(mesh, nn1, uses, edge_nodes, [&](GlobalId c, int k) { return child[6 * c + (k + 2) % 3]; });
  }
  mesh.connectivity = std::move(child);
  refine_sets(mesh);
}

}  // namespace shellfrac::mesh
