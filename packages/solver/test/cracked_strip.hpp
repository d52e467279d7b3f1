#pragma once
/// \file cracked_strip.hpp
/// The strip with one breakable edge shared by test_fracture and test_restart (docs/verification.md §5.2): the
/// Rectangle [0, 2L] x [0, b], 100 x 1 cells (1 mm), right diagonals, with node sets "crack" (x = L) and
/// "quarter" (x = L/2) and the side set "crack" (the edges at x = L, from the left elements), and the deck
/// that pulls both ends outward at V with only that side set breakable.
#include <cmath>
#include <string>

#include "deck_test_util.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"

namespace shellfrac::test {

constexpr double strip_L = 0.05, strip_b = 0.001, strip_h = 0.001;
constexpr int strip_cells = 100;  // along 2L: 1 mm elements

/// Writes the strip mesh (TRI6, Exodus) to `path`. Call on one rank.
inline void write_cracked_strip(const std::string& path) {
  const double L = strip_L;
  auto m = mesh::make_rectangle(2 * L, strip_b, strip_cells, 1, mesh::DiagonalPattern::Right);
  mesh::NodeSet crack{"crack", 10, {}}, quarter{"quarter", 11, {}};
  for (GlobalId n = 0; n < m.num_nodes(); ++n) {
    if (std::abs(m.coords[n][0] - L) < 1e-9) crack.nodes.push_back(n);
    if (std::abs(m.coords[n][0] - L / 2) < 1e-9) quarter.nodes.push_back(n);
  }
  mesh::SideSet edges{"crack", 10, {}, {}};
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const auto& a = m.coords[m.node(e, k)];
      const auto& c = m.coords[m.node(e, (k + 1) % 3)];
      const auto& o = m.coords[m.node(e, (k + 2) % 3)];
      if (std::abs(a[0] - L) < 1e-9 && std::abs(c[0] - L) < 1e-9 && o[0] < L) {
        edges.elements.push_back(e);
        edges.local_edges.push_back(k);
      }
    }
  m.node_sets.push_back(crack);
  m.node_sets.push_back(quarter);
  m.side_sets.push_back(edges);
  mesh::promote_to_p2(m);
  meshio::write_exodus_mesh(m, path);
}

/// The strip's deck: the mesh file `mesh_file` (relative to the deck's directory), the block "shell" of material
/// "m" with `section`, Fracture->Edges = crack, and both ends pulled outward at 20 m/s from t = 0; results written
/// to `out_dir`. Add the time integration, the probes and the material's fracture parameters.
inline Teuchos::RCP<Teuchos::ParameterList> pulled_strip_deck(const std::string& out_dir, const std::string& mesh_file,
                                                              const ShellSection& section) {
  auto deck = base_deck(section, out_dir);
  set_mesh_file(*deck, mesh_file);
  deck->sublist("Fracture").set("Edges", std::string("crack"));
  boundary_condition(*deck, "left", "Prescribed Velocity", "x_min").set("Velocity", vec3(-20.0, 0.0, 0.0));
  boundary_condition(*deck, "right", "Prescribed Velocity", "x_max").set("Velocity", vec3(20.0, 0.0, 0.0));
  return deck;
}

}  // namespace shellfrac::test
