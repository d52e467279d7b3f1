#pragma once
/// \file mesh_compare.hpp
/// Test helper shared by the mesh reader/writer tests: field-by-field comparison of two serial meshes.
#include <gtest/gtest.h>

#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::meshio::test {

using mesh::SerialMesh;

/// Field-by-field comparison. Coordinates: bitwise if coord_tol == 0, else |a - b| <= coord_tol.
inline void expect_same_mesh(const SerialMesh& a, const SerialMesh& b, double coord_tol = 0) {
  EXPECT_EQ(a.nodes_per_element, b.nodes_per_element);
  ASSERT_EQ(a.coords.size(), b.coords.size());
  for (std::size_t i = 0; i < a.coords.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      if (coord_tol == 0)
        EXPECT_EQ(a.coords[i][c], b.coords[i][c]) << "node " << i << " coordinate " << c;
      else
        EXPECT_NEAR(a.coords[i][c], b.coords[i][c], coord_tol) << "node " << i << " coordinate " << c;
    }
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
    EXPECT_EQ(a.node_sets[i].id, b.node_sets[i].id);
    EXPECT_EQ(a.node_sets[i].nodes, b.node_sets[i].nodes) << a.node_sets[i].name;
  }
  ASSERT_EQ(a.side_sets.size(), b.side_sets.size());
  for (std::size_t i = 0; i < a.side_sets.size(); ++i) {
    EXPECT_EQ(a.side_sets[i].name, b.side_sets[i].name);
    EXPECT_EQ(a.side_sets[i].id, b.side_sets[i].id);
    EXPECT_EQ(a.side_sets[i].elements, b.side_sets[i].elements) << a.side_sets[i].name;
    EXPECT_EQ(a.side_sets[i].local_edges, b.side_sets[i].local_edges) << a.side_sets[i].name;
  }
  ASSERT_EQ(a.element_sets.size(), b.element_sets.size());
  for (std::size_t i = 0; i < a.element_sets.size(); ++i) {
    EXPECT_EQ(a.element_sets[i].name, b.element_sets[i].name);
    EXPECT_EQ(a.element_sets[i].id, b.element_sets[i].id);
    EXPECT_EQ(a.element_sets[i].elements, b.element_sets[i].elements);
  }
}

}  // namespace shellfrac::meshio::test
