// Serial mesh: generators, P2 promotion, uniform refinement, edge topology and the interface map P.
// References are exact combinatorial counts of structured meshes (derived in each test), Euler's formula
// V - E + F = chi (1 for a disc-like surface, 0 for an open tube), and exact areas of flat/cylindrical
// surfaces.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/triangle_basis.hpp"
#include "shellfrac/disc/quadrature.hpp"
#include "shellfrac/mesh/coincident_nodes.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"

using namespace shellfrac;
using namespace shellfrac::mesh;

namespace {

/// Area of the (P1 or P2) mesh surface with the 6-point rule.
double surface_area(const SerialMesh& m) {
  const int order = m.nodes_per_element == 6 ? 2 : 1;
  double area = 0;
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int q = 0; q < disc::tri6_rule.num_points; ++q) {
      double N[6], dN[6][2];
      shellfrac::shape(order, disc::tri6_rule.xi[q][0], disc::tri6_rule.xi[q][1], N, dN);
      Vec3 g1{0, 0, 0}, g2{0, 0, 0};
      for (int a = 0; a < m.nodes_per_element; ++a) {
        g1 = add(g1, scale(dN[a][0], m.coords[m.node(e, a)]));
        g2 = add(g2, scale(dN[a][1], m.coords[m.node(e, a)]));
      }
      area += disc::tri6_rule.w[q] * norm(cross(g1, g2));
    }
  return area;
}

const NodeSet& node_set(const SerialMesh& m, const std::string& name) {
  for (const auto& s : m.node_sets)
    if (s.name == name) return s;
  throw std::runtime_error("no node set " + name);
}
const SideSet& side_set(const SerialMesh& m, const std::string& name) {
  for (const auto& s : m.side_sets)
    if (s.name == name) return s;
  throw std::runtime_error("no side set " + name);
}

}  // namespace

TEST(Generators, RectangleCountsSetsAndOrientation) {
  for (auto pattern : {DiagonalPattern::Right, DiagonalPattern::Left, DiagonalPattern::Alternating}) {
    const int nx = 5, ny = 3;
    auto m = make_rectangle(2.0, 1.0, nx, ny, pattern);
    check_mesh(m);
    EXPECT_EQ(m.num_elements(), 2 * nx * ny);
    EXPECT_EQ(m.num_nodes(), (nx + 1) * (ny + 1));
    EXPECT_EQ(node_set(m, "x_min").nodes.size(), std::size_t(ny + 1));
    EXPECT_EQ(side_set(m, "x_min").elements.size(), std::size_t(ny));
    EXPECT_EQ(side_set(m, "y_max").elements.size(), std::size_t(nx));
    EXPECT_EQ(node_set(m, "corners").nodes.size(), 4u);
    for (GlobalId e = 0; e < m.num_elements(); ++e) {
      // counter-clockwise seen from +z: positive z component of (b - a) x (c - a)
      const auto& a = m.coords[m.node(e, 0)];
      const auto& b = m.coords[m.node(e, 1)];
      const auto& c = m.coords[m.node(e, 2)];
      EXPECT_GT(cross(sub(b, a), sub(c, a))[2], 0.0);
    }
    EXPECT_NEAR(surface_area(m), 2.0, 1e-13);
    // side set x_max edges lie on x = 2
    const auto& ss = side_set(m, "x_max");
    for (std::size_t i = 0; i < ss.elements.size(); ++i)
      for (int v : edge_vertex[ss.local_edges[i]]) EXPECT_DOUBLE_EQ(m.coords[m.node(ss.elements[i], v)][0], 2.0);
  }
}

TEST(Generators, PaperCantileverPattern200x40) {
  // Paper §6.4: 200 x 40 structured right-triangle mesh = 16 000 elements, 24 DOFs each = 384e3 DOFs.
  auto m = make_rectangle(10.0, 2.0, 200, 40);
  EXPECT_EQ(m.num_elements(), 16000);
  EXPECT_EQ(24 * m.num_elements(), 384000);
}

TEST(Generators, CylindricalPanelOnSurfaceWithExactArea) {
  const double r = 2.9375, l = 12.56, angle = 2 * M_PI / 3;  // paper §6.1 panel
  auto m = make_cylindrical_panel(r, l, angle, 16, 6);
  check_mesh(m);
  promote_to_p2(m);
  check_mesh(m);
  EXPECT_EQ(m.nodes_per_element, 6);
  for (const auto& x : m.coords) EXPECT_NEAR(std::hypot(x[1], x[2]), r, 1e-12 * r);
  // P2 surface area converges to r*angle*l at O(h^4) or better; 1e-4 relative is met with margin on 16x6.
  EXPECT_NEAR(surface_area(m), r * angle * l, 1e-4 * r * angle * l);
  // Outward normals: the reference vertex normal at each vertex equals the radial direction.
  auto n = reference_vertex_normals(m);
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int a = 0; a < 3; ++a) {
      const auto& x = m.coords[m.node(e, a)];
      const Vec3 radial{0, x[1] / r, x[2] / r};
      EXPECT_NEAR(dot(n[m.node(e, a)], radial), 1.0, 1e-3);  // P2 normal at vertices, h/R ~ 0.4
    }
  EXPECT_EQ(node_set(m, "theta_min").nodes.size(), std::size_t(2 * 16 + 1));  // vertices + mid-sides
}

TEST(Generators, ClosedCylinderIsPeriodic) {
  auto m = make_cylinder(1.0, 3.0, 4, 8);
  check_mesh(m);
  EXPECT_EQ(m.num_nodes(), 5 * 8);
  auto t = build_edge_topology(m);
  // Open tube: V - E + F = 0; boundary edges only at the two ends.
  EXPECT_EQ(m.num_nodes() - t.num_edges() + m.num_elements(), 0);
  EXPECT_EQ(t.boundary.size(), std::size_t(2 * 8));
}

TEST(Topology, CountsAndInterfaceMapOnRectangle) {
  const int nx = 6, ny = 4;
  auto m = make_rectangle(3.0, 2.0, nx, ny, DiagonalPattern::Alternating);
  auto t = build_edge_topology(m);
  const GlobalId edges = nx * (ny + 1) + ny * (nx + 1) + nx * ny;  // horizontal + vertical + diagonals
  EXPECT_EQ(t.num_edges(), edges);
  EXPECT_EQ(t.boundary.size(), std::size_t(2 * (nx + ny)));
  EXPECT_EQ(t.interfaces.size(), std::size_t(edges - 2 * (nx + ny)));
  EXPECT_EQ(m.num_nodes() - t.num_edges() + m.num_elements(), 1);  // Euler, disc topology
  for (std::size_t i = 0; i < t.interfaces.size(); ++i) {
    const auto& f = t.interfaces[i];
    EXPECT_LT(f.minus.element, f.plus.element);
    EXPECT_FALSE(f.same_orientation);  // consistently oriented mesh: opposite traversal
    // P map: both sides name the same edge, with the same vertex pair
    EXPECT_EQ(t.element_edges[f.minus.element][f.minus.local_edge], f.edge);
    EXPECT_EQ(t.element_edges[f.plus.element][f.plus.local_edge], f.edge);
    EXPECT_EQ(t.element_interface[f.minus.element][f.minus.local_edge], GlobalId(i));
    EXPECT_EQ(t.neighbor[f.plus.element][f.plus.local_edge].element, f.minus.element);
    std::set<GlobalId> vm{m.node(f.minus.element, edge_vertex[f.minus.local_edge][0]),
                          m.node(f.minus.element, edge_vertex[f.minus.local_edge][1])};
    std::set<GlobalId> vp{m.node(f.plus.element, edge_vertex[f.plus.local_edge][0]),
                          m.node(f.plus.element, edge_vertex[f.plus.local_edge][1])};
    EXPECT_EQ(vm, vp);
  }
  // Boundary side-set membership: every boundary edge is in exactly one of x_min/x_max/y_min/y_max.
  for (const auto& s : t.boundary_side_sets) EXPECT_EQ(s.size(), 1u);
  std::vector<GlobalId> offsets, adjacency;
  dual_graph(t, m.num_elements(), offsets, adjacency);
  EXPECT_EQ(adjacency.size(), 2 * t.interfaces.size());
}

namespace {
/// Three triangles on the common edge (0,1): a T-joint (e.g. a stiffener on a skin).
SerialMesh t_joint() {
  SerialMesh m;
  m.source = "t_joint";
  m.coords = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  m.connectivity = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  m.element_block = {0, 0, 0};
  m.blocks = {{"shell", 1}};
  return m;
}
}  // namespace

TEST(Topology, NonManifoldPolicies) {
  auto m = t_joint();
  check_mesh(m);
  try {
    build_edge_topology(m, NonManifoldPolicy::Error);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("t_joint"), std::string::npos);
    EXPECT_NE(msg.find("shared by 3 elements (1, 2, 3)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Non-Manifold Edges"), std::string::npos);
  }
  auto star = build_edge_topology(m, NonManifoldPolicy::Star);
  EXPECT_EQ(star.num_non_manifold_edges, 1);
  ASSERT_EQ(star.interfaces.size(), 2u);  // element 0 coupled to 1 and to 2
  EXPECT_EQ(star.interfaces[0].minus.element, 0);
  EXPECT_EQ(star.interfaces[0].plus.element, 1);
  EXPECT_EQ(star.interfaces[1].plus.element, 2);
  EXPECT_TRUE(star.interfaces[1].non_manifold);
  auto free = build_edge_topology(m, NonManifoldPolicy::Free);
  EXPECT_TRUE(free.interfaces.empty());
  EXPECT_EQ(free.boundary.size(), 3u * 3u);  // every edge of every element is free
}

TEST(Refinement, CountsAreaSetsAndSurface) {
  // TRI3 rectangle: refine twice -> 16x elements; area exact; side set x_min gets 4x edges.
  auto m = make_rectangle(2.0, 1.0, 3, 2);
  const auto ne = m.num_elements();
  const auto nx_min = side_set(m, "x_min").elements.size();
  refine_uniform(m);
  refine_uniform(m);
  check_mesh(m);
  EXPECT_EQ(m.num_elements(), 16 * ne);
  EXPECT_EQ(m.num_nodes(), (4 * 3 + 1) * (4 * 2 + 1));  // same as a 12 x 8 structured grid
  EXPECT_NEAR(surface_area(m), 2.0, 1e-13);
  EXPECT_EQ(side_set(m, "x_min").elements.size(), 4 * nx_min);
  EXPECT_EQ(node_set(m, "x_min").nodes.size(), std::size_t(4 * 2 + 1));
  for (GlobalId n : node_set(m, "x_min").nodes) EXPECT_DOUBLE_EQ(m.coords[n][0], 0.0);
  auto t = build_edge_topology(m);
  EXPECT_EQ(m.num_nodes() - t.num_edges() + m.num_elements(), 1);
  for (const auto& f : t.interfaces) EXPECT_FALSE(f.same_orientation);

  // TRI6 cylinder: refined nodes stay on the exact surface; area converges towards r*2pi*l.
  auto c = make_cylinder(1.0, 2.0, 3, 6);
  promote_to_p2(c);
  const double a0 = std::abs(surface_area(c) - 2 * M_PI * 2.0);
  refine_uniform(c);
  check_mesh(c);
  for (const auto& x : c.coords) EXPECT_NEAR(std::hypot(x[1], x[2]), 1.0, 1e-12);
  const double a1 = std::abs(surface_area(c) - 2 * M_PI * 2.0);
  EXPECT_LT(a1, a0 / 8);  // P2 geometry error O(h^3) or better: halving h divides it by >= 8
  EXPECT_EQ(node_set(c, "x_min").nodes.size(), std::size_t(2 * 12));  // 12 vertices + 12 mid-sides
}

TEST(SerialMesh, PackUnpackRoundTrip) {
  auto m = make_cylindrical_panel(1.0, 2.0, 1.0, 3, 2);
  m.element_sets.push_back({"patch", 1, {0, 3, 5}});
  promote_to_p2(m);
  const auto u = unpack(pack(m));
  EXPECT_EQ(u.coords, m.coords);
  EXPECT_EQ(u.connectivity, m.connectivity);
  EXPECT_EQ(u.nodes_per_element, 6);
  EXPECT_EQ(u.node_sets.back().nodes, m.node_sets.back().nodes);
  EXPECT_EQ(u.side_sets[2].local_edges, m.side_sets[2].local_edges);
  EXPECT_EQ(u.element_sets[0].elements, m.element_sets[0].elements);
  EXPECT_EQ(u.surface.radius, 1.0);
  EXPECT_EQ(u.source, m.source);
}

TEST(SerialMesh, CheckMeshNamesTheProblem) {
  auto expect_error = [](SerialMesh m, const std::string& phrase) {
    try {
      check_mesh(m);
      FAIL() << "expected InputError containing '" << phrase << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("bad.exo:", 0), 0u) << e.what();
    }
  };
  auto base = make_rectangle(1, 1, 1, 1);
  base.source = "bad.exo";
  auto m = base;
  m.connectivity[4] = 99;
  expect_error(m, "refers to node 100");
  m = base;
  m.coords[m.node(0, 2)] = m.coords[m.node(0, 0)];  // collapse a triangle onto an edge
  m.coords[m.node(0, 2)][0] = 0.5 * (m.coords[m.node(0, 0)][0] + m.coords[m.node(0, 1)][0]);
  m.coords[m.node(0, 2)][1] = 0.5 * (m.coords[m.node(0, 0)][1] + m.coords[m.node(0, 1)][1]);
  expect_error(m, "degenerate");
  m = base;
  m.node_sets[1].id = m.node_sets[0].id;
  expect_error(m, "two node sets have id");
  m = base;
  m.side_sets[0].local_edges[0] = 3;
  expect_error(m, "invalid edge number");
  // Names end up in Exodus files and messages: Latin-1 and control bytes are refused (docs/hostile_input.md).
  m = base;
  m.blocks[0].name = "pl\xe4te";
  expect_error(m, "the name 'pl\\xe4te' of element block 1 has a byte that is not UTF-8 (0xe4) at position 3");
  m = base;
  m.node_sets[0].name = "left\n";
  expect_error(m, "has a control character (byte 0x0a) at position 5; names must be printable UTF-8");
}

// Separate nodes at one point (duplicates left by a mesher, or a seam on purpose) are counted; the generated
// meshes share their nodes, the closed cylinder included, and nodes that no element uses are ignored.
TEST(SerialMesh, CoincidentNodesAreCountedWithAnExample) {
  EXPECT_EQ(coincident_nodes(make_rectangle(2, 1, 4, 2)).count, 0);
  EXPECT_EQ(coincident_nodes(make_cylinder(1, 2, 3, 8)).count, 0);
  SerialMesh m;
  m.coords = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {0, 1, 0}};
  m.connectivity = {0, 1, 2, 5, 4, 3};  // two triangles of a square that do not share their diagonal
  m.element_block = {0, 0};
  m.blocks = {{"plate", 1}};
  const auto c = coincident_nodes(m);  // node 6 repeats node 3 but is not used
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.example, (Vec3{0, 0, 0}));
}
