#include "shellfrac/solver/setup/model_setup.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/decomposition/partitioner.hpp"
#include "shellfrac/io/results_writer.hpp"
#include "shellfrac/mesh/coincident_nodes.hpp"
#include "shellfrac/mesh/edge_topology.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/units.hpp"
#include "shellfrac/solver/model/symmetry_directors.hpp"
#include "shellfrac/solver/setup/stop_signals.hpp"

namespace shellfrac::solver {

RunModel::RunModel() = default;
RunModel::RunModel(RunModel&&) noexcept = default;
RunModel& RunModel::operator=(RunModel&&) noexcept = default;
RunModel::~RunModel() = default;

void check_deck_against_mesh(const Deck& deck, const mesh::SerialMesh& m) {
  for (const auto& b : m.blocks)
    SHELLFRAC_INPUT_REQUIRE(deck.blocks.count(b.name), deck.file << ": mesh block '" << b.name << "' (from " << m.source
                                                                 << ") has no entry in the Blocks sublist");
  for (const auto& section : deck.blocks) {
    const std::string& name = section.first;
    const bool found = std::any_of(m.blocks.begin(), m.blocks.end(), [&](const auto& b) { return b.name == name; });
    std::ostringstream os;
    for (const auto& b : m.blocks) os << " '" << b.name << "'";
    SHELLFRAC_INPUT_REQUIRE(found, deck.file << ": 'Blocks->" << name << "' names no block of the mesh (" << m.source
                                             << "); its blocks are:" << os.str());
  }
  // Results are Exodus files, whose names are limited: fail now, not after the run has started writing.
  for (const auto& b : m.blocks)
    SHELLFRAC_INPUT_REQUIRE(b.name.size() <= io::max_exodus_name_length,
                            m.source << ": block name '" << b.name << "' is longer than "
                                     << io::max_exodus_name_length << " characters (Exodus II limit)");
}

void check_orientation(const mesh::SerialMesh& m, const mesh::EdgeTopology& topo) {
  for (const auto& f : topo.interfaces)
    SHELLFRAC_INPUT_REQUIRE(!f.same_orientation || f.non_manifold,
                            m.source << ": " << m.element_ids.element(f.minus.element) << " and "
                                     << m.element_ids.element(f.plus.element) << " have opposite orientations (normals); orient the surface consistently "
                                        "(e.g. Gmsh: ReorientMesh / Reverse Surface)");
}

std::vector<std::string> mesh_warnings(const mesh::SerialMesh& m) {
  std::vector<std::string> out;
  if (const auto c = mesh::coincident_nodes(m); c.count > 0) {
    std::ostringstream os;
    os << m.source << ": " << c.count << " mesh node(s) lie at the position of another node without being shared "
       << "with it, e.g. at (" << c.example[0] << ", " << c.example[1] << ", " << c.example[2] << "); the elements "
       << "there are not connected: a seam or a crack if that is meant, otherwise merge the duplicate nodes";
    out.push_back(os.str());
  }
  return out;
}

/// Per block of the mesh, a thickness far above the block's median edge length: a shell thicker than its elements
/// are wide by this factor is a unit slip (10 m typed for 10 mm) or a solid, not a shell.
constexpr double thickness_per_edge_warned = 2.0;

std::vector<std::string> thickness_warnings(const Deck& deck, const mesh::SerialMesh& m) {
  std::vector<std::string> out;
  std::vector<std::vector<double>> edges(m.blocks.size());
  for (GlobalId e = 0; e < m.num_elements(); ++e)
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = m.coords[m.node(e, k)];
      const Vec3& b = m.coords[m.node(e, (k + 1) % 3)];
      edges[std::size_t(m.element_block[e])].push_back(
          std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
    }
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    auto& l = edges[b];
    const auto section = deck.blocks.find(m.blocks[b].name);
    if (l.empty() || section == deck.blocks.end()) continue;
    std::nth_element(l.begin(), l.begin() + std::ptrdiff_t(l.size() / 2), l.end());
    const double median = l[l.size() / 2], h = section->second.thickness;
    if (h <= thickness_per_edge_warned * median) continue;
    std::ostringstream os;
    os << deck.file << ": block '" << m.blocks[b].name << "' has the Thickness " << h << ", " << h / median
       << " times its median element edge " << median << ": a shell thicker than its elements are wide (the "
       << "thickness in other units than the mesh, or a solid meshed as a shell?)";
    out.push_back(os.str());
  }
  return out;
}

/// Fewer steps than this over the whole run: the waves cross an element only a few times in the run, which for a
/// dynamic problem means a modulus or density in other units than the mesh and End Time.
constexpr double few_steps = 10;

std::vector<std::string> model_warnings(const Deck& deck, const RunModel& r) {
  std::vector<std::string> out = implausible_constants(deck);
  for (auto& w : thickness_warnings(deck, *r.mesh)) out.push_back(std::move(w));
  const double dt = r.dynamics->time_step(), end = deck.time.end_time;
  if (end > 0 && end <= 0.5 * dt) {  // the time loop steps while t + dt/2 < End Time
    std::ostringstream os;
    os << deck.file << ": the time step " << dt << " is more than twice 'Time Integration->End Time' = " << end
       << ", so no step is taken and only the initial state is written (are Young's Modulus and Density right?)";
    out.push_back(os.str());
  } else if (end > 0 && end < few_steps * dt && !deck.time.static_relaxation) {
    std::ostringstream os;
    os << deck.file << ": the run takes only " << std::lround(std::ceil(end / dt - 0.5)) << " steps of " << dt
       << " to End Time " << end << ": a wave crosses an element only that often in the whole run (are Young's "
       << "Modulus and Density in the units of the mesh and End Time?)";
    out.push_back(os.str());
  }
  return out;
}

void RunModel::release_global_mesh() { mesh.reset(); }

RunModel build_run_model(const Deck& deck, MPI_Comm comm) {
  RunModel r;
  auto last = std::chrono::steady_clock::now();
  std::vector<double> seconds;
  // The end of each phase of the set-up: its time, and a prompt stop if SIGTERM or SIGUSR2 came (nothing is written yet).
  const auto lap = [&] {
    const auto now = std::chrono::steady_clock::now();
    seconds.push_back(std::chrono::duration<double>(now - last).count());
    last = now;
    static const char* const phases[] = {"reading the mesh", "the edge topology", "the partition",
                                         "the distribution", "the model"};
    stop_if_terminated(phases[std::min<std::size_t>(seconds.size(), 5) - 1], comm);
  };
  r.mesh = std::make_unique<mesh::SerialMesh>(build_mesh(deck.mesh, comm));
  check_deck_against_mesh(deck, *r.mesh);
  for (const auto& b : r.mesh->blocks) r.block_names.push_back(b.name), r.block_ids.push_back(b.id);
  r.warnings = mesh_warnings(*r.mesh);
  r.counts.elements = r.mesh->num_elements(), r.counts.nodes = r.mesh->num_nodes();
  lap();
  {  // the topology serves the partition and the distribution, then goes (the set-up's peak memory)
    const auto topology = mesh::build_edge_topology(*r.mesh, deck.mesh.non_manifold);
    check_orientation(*r.mesh, topology);
    r.counts.edges = topology.num_edges(), r.counts.interfaces = GlobalId(topology.interfaces.size());
    r.counts.boundary_edges = GlobalId(topology.boundary.size());
    r.counts.non_manifold_edges = topology.num_non_manifold_edges;
    lap();
    const auto part = decomposition::partition_elements(*r.mesh, topology, parallel::size(comm), *deck.partition, comm);
    lap();
    r.distributed = std::make_unique<decomposition::DistributedMesh>(*r.mesh, topology, part, comm);
    hold_reference_directors_in_symmetry_planes(deck, *r.mesh, *r.distributed);
    lap();
  }
  r.dynamics = std::make_unique<ShellDynamics>(*r.mesh, *r.distributed, deck);
  for (auto& w : model_warnings(deck, r)) r.warnings.push_back(std::move(w));
  lap();
  std::vector<double> slowest(seconds.size());
  SHELLFRAC_REQUIRE(MPI_Allreduce(seconds.data(), slowest.data(), int(seconds.size()), MPI_DOUBLE, MPI_MAX, comm) ==
                        MPI_SUCCESS,
                    "MPI_Allreduce of the set-up times failed");
  const char* phases[] = {"mesh", "topology", "partition", "distribution", "model"};
  for (std::size_t k = 0; k < slowest.size(); ++k) r.setup_seconds.push_back({phases[k], slowest[k]});
  return r;
}

}  // namespace shellfrac::solver
