#include "shellfrac/mesh/generators.hpp"

#include <cmath>
#include <functional>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/mesh/edge_incidence.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"

namespace shellfrac::mesh {

namespace {

/// A structured nx x ny grid of cells mapped to R^3 by position(i, j); periodic_j closes the grid in j
/// (node j = ny is node j = 0). Each cell gives two counter-clockwise triangles (in (i, j) space).
struct Grid {
  int nx, ny;
  bool periodic_j;
  GlobalId node(int i, int j) const { return static_cast<GlobalId>(periodic_j ? j % ny : j) * (nx + 1) + i; }
  int num_j_nodes() const { return periodic_j ? ny : ny + 1; }
};

SerialMesh make_grid(const Grid& g, DiagonalPattern pattern, const std::function<Vec3(int, int)>& position,
                     const std::string& block_name, const std::string& source) {
  SHELLFRAC_INPUT_REQUIRE(g.nx >= 1 && g.ny >= (g.periodic_j ? 3 : 1),
                          source << ": too few elements (" << g.nx << " x " << g.ny << ")");
  SerialMesh m;
  m.nodes_per_element = 3;
  m.source = source;
  m.blocks.push_back({block_name, 1});
  for (int j = 0; j < g.num_j_nodes(); ++j)
    for (int i = 0; i <= g.nx; ++i) m.coords.push_back(position(i, j));
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const GlobalId n00 = g.node(i, j), n10 = g.node(i + 1, j), n01 = g.node(i, j + 1), n11 = g.node(i + 1, j + 1);
      const bool right = pattern == DiagonalPattern::Right ||
                         (pattern == DiagonalPattern::Alternating && (i + j) % 2 == 0);
      const GlobalId tris[2][3] = {{n00, n10, right ? n11 : n01}, {right ? n00 : n10, n11, n01}};
      for (const auto& t : tris) {
        m.connectivity.insert(m.connectivity.end(), t, t + 3);
        m.element_block.push_back(0);
      }
    }
  return m;
}

/// Adds a node set and a side set named `name`: the nodes with on(i, j), and the boundary edges whose two
/// vertices are such nodes.
void add_boundary_sets(SerialMesh& m, const Grid& g, const std::string& name, const std::function<bool(int, int)>& on) {
  std::vector<char> member(m.coords.size(), 0);
  NodeSet ns{name, static_cast<int>(m.node_sets.size()) + 1, {}};
  for (int j = 0; j < g.num_j_nodes(); ++j)
    for (int i = 0; i <= g.nx; ++i)
      if (on(i, j)) member[g.node(i, j)] = 1;
  for (GlobalId n = 0; n < m.num_nodes(); ++n)
    if (member[n]) ns.nodes.push_back(n);
  m.node_sets.push_back(ns);
  SideSet ss{name, static_cast<int>(m.side_sets.size()) + 1, {}, {}};
  const auto uses = detail::edge_uses(m.num_elements(), [&](GlobalId e, int i) { return m.node(e, i); });
  std::vector<std::pair<GlobalId, int>> sides;
  detail::for_each_edge(uses, [&](std::size_t first, std::size_t last) {
    if (last - first == 1 && member[uses[first].a] && member[uses[first].b])
      sides.push_back({uses[first].element, uses[first].local_edge});
  });
  std::sort(sides.begin(), sides.end());
  for (auto& [e, k] : sides) ss.elements.push_back(e), ss.local_edges.push_back(k);
  m.side_sets.push_back(ss);
}

std::string describe(const char* what, std::initializer_list<double> values) {
  std::ostringstream os;
  os << what << "(";
  bool first = true;
  for (double v : values) os << (first ? "" : ", ") << v, first = false;
  os << ")";
  return os.str();
}

}  // namespace

SerialMesh make_rectangle(double lx, double ly, int nx, int ny, DiagonalPattern pattern, double x0, double y0,
                          const std::string& block_name) {
  const std::string src = describe("rectangle", {lx, ly, double(nx), double(ny)});
  SHELLFRAC_INPUT_REQUIRE(lx > 0 && ly > 0, src << ": lengths must be positive");
  const Grid g{nx, ny, false};
  auto m = make_grid(
      g, pattern, [&](int i, int j) { return Vec3{x0 + lx * i / nx, y0 + ly * j / ny, 0.0}; }, block_name, src);
  add_boundary_sets(m, g, "x_min", [](int i, int) { return i == 0; });
  add_boundary_sets(m, g, "x_max", [&](int i, int) { return i == nx; });
  add_boundary_sets(m, g, "y_min", [](int, int j) { return j == 0; });
  add_boundary_sets(m, g, "y_max", [&](int, int j) { return j == ny; });
  NodeSet corners{"corners", static_cast<int>(m.node_sets.size()) + 1,
                  {g.node(0, 0), g.node(nx, 0), g.node(0, ny), g.node(nx, ny)}};
  std::sort(corners.nodes.begin(), corners.nodes.end());
  m.node_sets.push_back(corners);
  return m;
}

SerialMesh make_cylindrical_panel(double r, double l, double angle, int n_axial, int n_circ, DiagonalPattern pattern,
                                  const std::string& block_name) {
  const std::string src = describe("cylindrical panel", {r, l, angle, double(n_axial), double(n_circ)});
  SHELLFRAC_INPUT_REQUIRE(r > 0 && l > 0, src << ": radius and length must be positive");
  SHELLFRAC_INPUT_REQUIRE(angle > 0 && angle < 2 * M_PI, src << ": the angle must be in (0, 2 pi) radians");
  const Grid g{n_axial, n_circ, false};
  auto m = make_grid(
      g, pattern,
      [&](int i, int j) {
        const double theta = -0.5 * angle + angle * j / n_circ;
        return Vec3{l * i / n_axial, r * std::sin(theta), r * std::cos(theta)};
      },
      block_name, src);
  m.surface = {ExactSurface::Kind::Cylinder, {0, 0, 0}, {1, 0, 0}, r};
  add_boundary_sets(m, g, "x_min", [](int i, int) { return i == 0; });
  add_boundary_sets(m, g, "x_max", [&](int i, int) { return i == n_axial; });
  add_boundary_sets(m, g, "theta_min", [](int, int j) { return j == 0; });
  add_boundary_sets(m, g, "theta_max", [&](int, int j) { return j == n_circ; });
  return m;
}

SerialMesh make_cylinder(double r, double l, int n_axial, int n_circ, DiagonalPattern pattern,
                         const std::string& block_name) {
  const std::string src = describe("cylinder", {r, l, double(n_axial), double(n_circ)});
  SHELLFRAC_INPUT_REQUIRE(r > 0 && l > 0, src << ": radius and length must be positive");
  const Grid g{n_axial, n_circ, true};
  auto m = make_grid(
      g, pattern,
      [&](int i, int j) {
        const double theta = 2 * M_PI * j / n_circ;
        return Vec3{l * i / n_axial, r * std::sin(theta), r * std::cos(theta)};
      },
      block_name, src);
  m.surface = {ExactSurface::Kind::Cylinder, {0, 0, 0}, {1, 0, 0}, r};
  add_boundary_sets(m, g, "x_min", [](int i, int) { return i == 0; });
  add_boundary_sets(m, g, "x_max", [&](int i, int) { return i == n_axial; });
  return m;
}

bool vertex_normal_term(int nodes_per_element, const Vec3* x, int a, Vec3& term) {
  const int order = nodes_per_element == 6 ? 2 : 1;
  double N[6], dN[6][2];
  shape(order, p2_node_xi[a][0], p2_node_xi[a][1], N, dN);
  Vec3 g1{0, 0, 0}, g2{0, 0, 0};
  for (int b = 0; b < nodes_per_element; ++b) {
    g1 = add(g1, scale(dN[b][0], x[b]));
    g2 = add(g2, scale(dN[b][1], x[b]));
  }
  const Vec3 c = cross(g1, g2);
  const double len = norm(c);
  if (!(len > 0)) return false;
  term = scale(1.0 / len, c);
  return true;
}

Vec3 unit_or_zero(const Vec3& v) {
  const double len = norm(v);
  return len > 0 ? scale(1.0 / len, v) : v;
}

std::vector<Vec3> reference_vertex_normals(const SerialMesh& mesh) {
  std::vector<Vec3> n(mesh.coords.size(), Vec3{0, 0, 0});
  const int npe = mesh.nodes_per_element;
  // Accumulate in element order (deterministic), then normalize.
  for (GlobalId e = 0; e < mesh.num_elements(); ++e) {
    Vec3 x[6];
    for (int b = 0; b < npe; ++b) x[b] = mesh.coords[mesh.node(e, b)];
    for (int a = 0; a < 3; ++a) {
      Vec3 term;
      SHELLFRAC_INPUT_REQUIRE(vertex_normal_term(npe, x, a, term),
                              mesh.source << ": element " << e + 1 << " has a zero Jacobian at vertex " << a + 1);
      const GlobalId v = mesh.node(e, a);
      n[v] = add(n[v], term);
    }
  }
  for (auto& v : n) v = unit_or_zero(v);
  return n;
}

}  // namespace shellfrac::mesh
