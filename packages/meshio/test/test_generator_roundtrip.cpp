// Generator -> Exodus -> reader round trip (issue: foundation, item 9). Reference: the generated mesh
// itself; Exodus stores doubles, so coordinates, connectivity, blocks and every set must come back exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "mesh_compare.hpp"

using namespace shellfrac;

using meshio::test::expect_same_mesh;

TEST(GeneratorRoundTrip, RectangleTri3AndTri6) {
  auto m = mesh::make_rectangle(2.0, 1.0, 8, 3, mesh::DiagonalPattern::Alternating);
  m.element_sets.push_back({"patch", 1, {0, 5, 7, 20}});
  meshio::write_exodus_mesh(m, "roundtrip_rect3.exo");
  expect_same_mesh(m, meshio::read_exodus_mesh("roundtrip_rect3.exo"));
  mesh::promote_to_p2(m);
  meshio::write_exodus_mesh(m, "roundtrip_rect6.exo");
  expect_same_mesh(m, meshio::read_exodus_mesh("roundtrip_rect6.exo"));
}

TEST(GeneratorRoundTrip, RefinedCylindricalPanelAndCylinder) {
  auto p = mesh::make_cylindrical_panel(2.9375, 12.56, 2 * M_PI / 3, 16, 6);
  mesh::promote_to_p2(p);
  mesh::refine_uniform(p);
  meshio::write_exodus_mesh(p, "roundtrip_panel.exo");
  const auto q = meshio::read_exodus_mesh("roundtrip_panel.exo");
  expect_same_mesh(p, q);
  EXPECT_EQ(q.num_elements(), 4 * 2 * 16 * 6);
  auto c = mesh::make_cylinder(1.0, 3.0, 4, 10);
  meshio::write_exodus_mesh(c, "roundtrip_cylinder.exo");
  expect_same_mesh(c, meshio::read_mesh_file("roundtrip_cylinder.exo"));
}
