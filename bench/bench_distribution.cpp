// shellfrac_distribution_bench: build the distributed mesh of a generated closed cylinder of about E elements, from
// the whole mesh on every rank or from pieces (each rank makes only its slice of the elements), and print per rank
// the peak memory the set-up took beyond what the rank held before it, and the time of each phase. Not a test.
//   mpiexec -np P shellfrac_distribution_bench [--elements E] [--path whole|pieces|file] [--mesh F.exo]
// whole: mesh::make_cylinder, mesh::build_edge_topology and DistributedMesh(mesh, topology, part), as the set-up does
// today (without the partitioner: both paths use the same part, element e to rank e P / N, axial strips).
// pieces: rank r makes the elements [r N / P, (r + 1) N / P) of the same mesh (same ids, nodes and coordinates),
// then build_local_topology and DistributedMesh(piece, topology, part).
// file: the same mesh read from the Exodus file F (default cylinder_<E>.exo; rank 0 writes it first when it is not
// there) by meshio::read_exodus_piece, then as pieces. Memory: VmHWM minus the VmRSS before the set-up, from
// /proc/self (after MPI_Init and the libraries are in; the peak is reset there). Output: one line per rank, then
// key=value lines.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "process_memory.hpp"
#include "shellfrac/core/memory_release.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/decomposition/distributed_topology.hpp"
#include "shellfrac/decomposition/element_migration.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/meshio/exodus_piece_reader.hpp"

using namespace shellfrac;
using bench::status_bytes;

namespace {

/// The cylinder of mesh::make_cylinder (radius 1, length 4, pattern Right) with nx x ny cells.
struct Cylinder {
  int nx, ny;
  GlobalId num_elements() const { return 2 * GlobalId(nx) * ny; }
  GlobalId node(int i, int j) const { return GlobalId(j % ny) * (nx + 1) + i; }
  Vec3 position(GlobalId n) const {
    const int i = int(n % (nx + 1)), j = int(n / (nx + 1));
    const double theta = 2 * M_PI * j / ny;
    return Vec3{4.0 * i / nx, std::sin(theta), std::cos(theta)};
  }
  std::array<GlobalId, 3> nodes(GlobalId e) const {
    const GlobalId cell = e / 2;
    const int i = int(cell % nx), j = int(cell / nx);
    const GlobalId n00 = node(i, j), n10 = node(i + 1, j), n01 = node(i, j + 1), n11 = node(i + 1, j + 1);
    return e % 2 == 0 ? std::array<GlobalId, 3>{n00, n10, n11} : std::array<GlobalId, 3>{n00, n11, n01};
  }
};

int part_of(GlobalId e, GlobalId ne, int P) { return int(e * P / ne); }

}  // namespace

int main(int argc, char** argv) {
  release_freed_memory_promptly();  // as the shellfrac executable does
  MPI_Init(&argc, &argv);
  GlobalId wanted = 500000;
  std::string path = "pieces", file;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a];
    if (k == "--elements") wanted = std::stoll(argv[a + 1]);
    if (k == "--path") path = argv[a + 1];
    if (k == "--mesh") file = argv[a + 1];
  }
  const int P = parallel::size(), me = parallel::rank();
  const int n = std::max(3, int(std::lround(std::sqrt(double(wanted) / 2))));
  const Cylinder c{n, n};
  const GlobalId ne = c.num_elements();
  if (file.empty()) file = "cylinder_" + std::to_string(ne) + ".exo";
  if (path == "file" && me == 0 && !std::filesystem::exists(file))
    meshio::write_exodus_mesh(mesh::make_cylinder(1.0, 4.0, n, n), file);
  MPI_Barrier(MPI_COMM_WORLD);
  const double before = bench::reset_peak();
  std::vector<std::pair<std::string, double>> phases;
  auto last = std::chrono::steady_clock::now();
  const auto lap = [&](const char* name) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto now = std::chrono::steady_clock::now();
    phases.push_back({name, std::chrono::duration<double>(now - last).count()});
    last = now;
  };
  LocalId owned = 0, overlap = 0;
  if (path == "whole") {
    auto m = mesh::make_cylinder(1.0, 4.0, n, n);
    lap("mesh");
    const auto topo = mesh::build_edge_topology(m);
    lap("topology");
    std::vector<int> part(static_cast<std::size_t>(ne));
    for (GlobalId e = 0; e < ne; ++e) part[std::size_t(e)] = part_of(e, ne, P);
    const decomposition::DistributedMesh dm(m, topo, part);
    lap("distribution");
    owned = dm.num_owned(), overlap = dm.num_overlap();
  } else {
    mesh::MeshPiece read;     // path file
    mesh::ElementPiece made;  // path pieces
    if (path == "file") {
      read = meshio::read_exodus_piece(file, MPI_COMM_WORLD);
    } else {
      made.source = "cylinder";
      for (GlobalId e = me * ne / P; e < (me + 1) * ne / P; ++e) {
        made.elements.push_back(e);
        made.blocks.push_back(0);
        for (const GlobalId v : c.nodes(e)) made.nodes.push_back(v), made.coords.push_back(c.position(v));
      }
    }
    const mesh::ElementPiece& piece = path == "file" ? read.piece : made;
    const auto npe = static_cast<std::size_t>(piece.nodes_per_element);
    std::vector<std::array<GlobalId, 3>> vertices(piece.elements.size());
    for (std::size_t i = 0; i < vertices.size(); ++i)
      for (std::size_t a = 0; a < 3; ++a) vertices[i][a] = piece.nodes[npe * i + a];
    lap("mesh");
    const auto topo = decomposition::build_local_topology(piece.elements, vertices, mesh::NonManifoldPolicy::Star,
                                                          piece.source, MPI_COMM_WORLD);
    lap("topology");
    std::vector<int> part;
    for (const GlobalId e : piece.elements) part.push_back(part_of(e, ne, P));
    const decomposition::DistributedMesh dm(piece, topo, part);
    lap("distribution");
    owned = dm.num_owned(), overlap = dm.num_overlap();
  }
  const double extra = status_bytes("VmHWM:") - before;
  const auto extras = parallel::all_gather(std::vector<double>{extra});
  const auto counts = parallel::all_gather(std::vector<std::int64_t>{owned, overlap});
  if (me == 0) {
    for (int r = 0; r < P; ++r)
      std::printf("rank %d: +%.1f MiB, %lld owned, %lld overlap\n", r, extras[std::size_t(r)] / 1048576.0,
                  (long long)counts[2 * std::size_t(r)], (long long)counts[2 * std::size_t(r) + 1]);
    const double largest = *std::max_element(extras.begin(), extras.end());
    std::printf(
        "path=%s\nranks=%d\nelements=%lld\npeak_extra_bytes_max=%.0f\npeak_extra_bytes_max_per_global_element=%.2f\n",
        path.c_str(), P, (long long)ne, largest, largest / double(ne));
    for (const auto& [name, s] : phases) std::printf("%s_s=%.3f\n", name.c_str(), s);
  }
  MPI_Finalize();
  return 0;
}
