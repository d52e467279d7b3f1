// shellfrac_meshtool: small mesh tool.
//   shellfrac_meshtool info FILE                         counts, blocks, sets, edges, bounding box, quality
//   shellfrac_meshtool convert IN OUT.exo [--p2] [--refine N]
//                                                    Gmsh/Exodus -> Exodus (optionally TRI3 -> TRI6, refined)
//   shellfrac_meshtool refine IN OUT.exo N               N uniform refinements (each triangle -> 4)
// Exit codes: 0 ok, 1 input error (message names the file), 2 usage error.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/memory_release.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"

namespace {

using namespace shellfrac;

const char* usage =
    "usage: shellfrac_meshtool info FILE\n"
    "       shellfrac_meshtool convert IN OUT.exo [--p2] [--refine N]\n"
    "       shellfrac_meshtool refine IN OUT.exo N\n"
    "IN is an Exodus II (.exo .e .g .gen) or Gmsh (.msh 2.2/4.1) triangle mesh; OUT is written as Exodus II.\n";

int parse_count(const std::string& s) {
  std::size_t used = 0;
  int n = -1;
  try {
    n = std::stoi(s, &used);
  } catch (const std::exception&) {
  }
  SHELLFRAC_INPUT_REQUIRE(used == s.size() && n >= 0 && n <= 10, "refinement count '" << s << "' must be 0..10");
  return n;
}

void info(const mesh::SerialMesh& m) {
  const auto topo = mesh::build_edge_topology(m, mesh::NonManifoldPolicy::Star);
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& x : m.coords)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], x[c]), hi[c] = std::max(hi[c], x[c]);
  double hmin = std::numeric_limits<double>::max(), hmax = 0, worst_aspect = 0;
  for (GlobalId e = 0; e < m.num_elements(); ++e) {
    double lmin = std::numeric_limits<double>::max(), lmax = 0;
    for (int k = 0; k < 3; ++k) {
      const double l = mesh::norm(mesh::sub(m.coords[m.node(e, edge_vertex[k][1])], m.coords[m.node(e, edge_vertex[k][0])]));
      lmin = std::min(lmin, l), lmax = std::max(lmax, l);
    }
    hmin = std::min(hmin, lmin), hmax = std::max(hmax, lmax);
    // aspect = longest edge / (2 sqrt(3) inradius); 1 for an equilateral triangle
    const double area = mesh::vertex_area(m, e);
    double perimeter = 0;
    for (int k = 0; k < 3; ++k)
      perimeter += mesh::norm(mesh::sub(m.coords[m.node(e, edge_vertex[k][1])], m.coords[m.node(e, edge_vertex[k][0])]));
    worst_aspect = std::max(worst_aspect, lmax * perimeter / (4 * std::sqrt(3.0) * area));
  }
  GlobalId flipped = 0;
  for (const auto& f : topo.interfaces) flipped += f.same_orientation && !f.non_manifold;
  std::cout << m.source << ":\n"
            << "  elements: " << m.num_elements() << " TRI" << m.nodes_per_element << ", nodes: " << m.num_nodes() << "\n"
            << "  edges: " << topo.num_edges() << " (" << topo.interfaces.size() << " interfaces, " << topo.boundary.size()
            << " boundary, " << topo.num_non_manifold_edges << " non-manifold)\n"
            << "  inconsistently oriented neighbour pairs: " << flipped << "\n"
            << "  edge length: " << hmin << " .. " << hmax << ", worst aspect ratio " << worst_aspect << "\n"
            << "  bounding box: [" << lo[0] << ", " << hi[0] << "] x [" << lo[1] << ", " << hi[1] << "] x [" << lo[2]
            << ", " << hi[2] << "]\n";
  std::vector<GlobalId> per_block(m.blocks.size(), 0);
  for (int b : m.element_block) ++per_block[b];
  for (std::size_t b = 0; b < m.blocks.size(); ++b)
    std::cout << "  block " << m.blocks[b].id << " '" << m.blocks[b].name << "': " << per_block[b] << " elements\n";
  for (const auto& s : m.node_sets) std::cout << "  node set " << s.id << " '" << s.name << "': " << s.nodes.size() << " nodes\n";
  for (const auto& s : m.side_sets)
    std::cout << "  side set " << s.id << " '" << s.name << "': " << s.elements.size() << " edges\n";
  for (const auto& s : m.element_sets)
    std::cout << "  element set " << s.id << " '" << s.name << "': " << s.elements.size() << " elements\n";
}

int run(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << usage;
    return args.empty() ? 2 : 0;
  }
  const std::string& cmd = args[0];
  if (cmd == "info" && args.size() == 2) {
    info(meshio::read_mesh_file(args[1]));
    return 0;
  }
  // The output replaces a file of its name, never the input (read whole first, but a failed write would lose it).
  if ((cmd == "convert" || cmd == "refine") && args.size() >= 3) {
    std::error_code ec;
    if (std::filesystem::equivalent(args[1], args[2], ec)) {
      std::cerr << "shellfrac_meshtool: error: the output " << args[2] << " is the input mesh " << args[1]
                << "; name another output file\n";
      return 2;
    }
  }
  if (cmd == "convert" && args.size() >= 3) {
    bool p2 = false;
    int refine = 0;
    for (std::size_t i = 3; i < args.size(); ++i) {
      if (args[i] == "--p2") {
        p2 = true;
      } else if (args[i] == "--refine" && i + 1 < args.size()) {
        refine = parse_count(args[++i]);
      } else {
        std::cerr << "shellfrac_meshtool: error: unknown option '" << args[i] << "'\n" << usage;
        return 2;
      }
    }
    auto m = meshio::read_mesh_file(args[1]);
    if (p2) mesh::promote_to_p2(m);
    for (int i = 0; i < refine; ++i) mesh::refine_uniform(m);
    meshio::write_exodus_mesh(m, args[2]);
    std::cout << "wrote " << args[2] << ": " << m.num_elements() << " TRI" << m.nodes_per_element << " elements\n";
    return 0;
  }
  if (cmd == "refine" && args.size() == 4) {
    const int n = parse_count(args[3]);
    auto m = meshio::read_mesh_file(args[1]);
    for (int i = 0; i < n; ++i) mesh::refine_uniform(m);
    meshio::write_exodus_mesh(m, args[2]);
    std::cout << "wrote " << args[2] << ": " << m.num_elements() << " TRI" << m.nodes_per_element << " elements\n";
    return 0;
  }
  std::cerr << "shellfrac_meshtool: error: bad arguments\n" << usage;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  shellfrac::release_freed_memory_promptly();
  MPI_Init(&argc, &argv);  // the mesh library's broadcast helpers expect MPI; the tool itself is serial
  int code = 0;
  try {
    code = run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const shellfrac::InputError& e) {
    std::cerr << "shellfrac_meshtool: error: " << e.what() << "\n";
    code = 1;
  } catch (const std::exception& e) {
    std::cerr << "shellfrac_meshtool: internal error: " << e.what() << "\n";
    code = 3;
  }
  MPI_Finalize();
  return code;
}
