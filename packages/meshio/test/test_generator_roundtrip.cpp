// Generator -> Exodus -> reader round trip (issue: foundation, item 9). Reference: the generated mesh
// itself; Exodus stores doubles, so coordinates, connectivity, blocks and every set must come back exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"

using namespace shellfrac;

namespace {
void expect_same(const mesh::SerialMesh& a, const mesh::SerialMesh& b) {
  EXPECT_EQ(a.nodes_per_element, b.nodes_per_element);
  EXPECT_EQ(a.coords, b.coords);
  EXPECT_EQ(a.connectivity, b.connectivity);
  EXPECT_EQ(a.element_block, b.element_block);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    EXPECT_EQ(a.blocks[i].name, b.blocks[i].name);
    EXPECT_EQ(a.blocks[i].id, b.blocks[i].id);
  }
  ASSERT_EQ(a.node_sets.size(), b.node_sets.size());
  for (std::size_t i = 0; i < a.node_sets.size(); ++i) {
    EXPECT_EQ(a.node_sets[i].name, b.node_sets[i].name);
    EXPECT_EQ(a.node_sets[i].nodes, b.node_sets[i].nodes);
  }
  ASSERT_EQ(a.side_sets.size(), b.side_sets.size());
  for (std::size_t i = 0; i < a.side_sets.size(); ++i) {
    EXPECT_EQ(a.side_sets[i].name, b.side_sets[i].name);
    EXPECT_EQ(a.side_sets[i].elements, b.side_sets[i].elements);
    EXPECT_EQ(a.side_sets[i].local_edges, b.side_sets[i].local_edges);
  }
  ASSERT_EQ(a.element_sets.size(), b.element_sets.size());
  for (std::size_t i = 0; i < a.element_sets.size(); ++i) EXPECT_EQ(a.element_sets[i].elements, b.element_sets[i].elements);
}
}  // namespace

TEST(GeneratorRoundTrip, RectangleTri3AndTri6) {
  auto m = mesh::make_rectangle(2.0, 1.0, 8, 3, mesh::DiagonalPattern::Alternating);
  m.element_sets.push_back({"patch", 1, {0, 5, 7, 20}});
  meshio::write_exodus_mesh(m, "roundtrip_rect3.exo");
  expect_same(m, meshio::read_exodus_mesh("roundtrip_rect3.exo"));
  mesh::promote_to_p2(m);
  meshio::write_exodus_mesh(m, "roundtrip_rect6.exo");
  expect_same(m, meshio::read_exodus_mesh("roundtrip_rect6.exo"));
}

TEST(GeneratorRoundTrip, RefinedCylindricalPanelAndCylinder) {
  auto p = mesh::make_cylindrical_panel(2.9375, 12.56, 2 * M_PI / 3, 16, 6);
  mesh::promote_to_p2(p);
  mesh::refine_uniform(p);
  meshio::write_exodus_mesh(p, "roundtrip_panel.exo");
  const auto q = meshio::read_exodus_mesh("roundtrip_panel.exo");
  expect_same(p, q);
  EXPECT_EQ(q.num_elements(), 4 * 2 * 16 * 6);
  auto c = mesh::make_cylinder(1.0, 3.0, 4, 10);
  meshio::write_exodus_mesh(c, "roundtrip_cylinder.exo");
  expect_same(c, meshio::read_mesh_file("roundtrip_cylinder.exo"));
}
