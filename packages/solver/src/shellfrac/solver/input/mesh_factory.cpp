#include "shellfrac/solver/input/mesh_factory.hpp"

#include <mpi.h>

#include <cmath>
#include <fstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"

namespace shellfrac::solver {

namespace {
const std::vector<std::string> sources = {"Rectangle", "Cylindrical Panel", "Cylinder", "File"};
const std::vector<std::string> patterns = {"Right", "Left", "Alternating"};

void add_pattern_and_block(Teuchos::ParameterList& pl) {
  params::set_choice(pl, "Diagonal Pattern", "Right",
                     "How each grid cell is split into two triangles: along the (i,j)-(i+1,j+1) diagonal (Right; "
                     "the paper's structured right-triangle mesh), the other diagonal (Left), or alternating",
                     patterns);
  pl.set("Block Name", "shell", "Name of the generated element block (a key of the Blocks sublist)");
}
}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> MeshParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Mesh"));
  params::set_choice(*pl, "Source", "Rectangle",
                     "Where the mesh comes from: a built-in generator (the sublist of the same name) or a file", sources);
  pl->set("File", "", "Mesh file (Source = File): Exodus II (.exo .e .g .gen) or Gmsh (.msh 2.2/4.1); relative "
                      "paths are relative to the deck's directory");
  pl->set("Uniform Refinements", 0, "Number of uniform refinements (each triangle -> 4) after reading/generating",
          params::int_range(0, 10));
  params::set_choice(*pl, "Non-Manifold Edges", "Star",
                     "Edges shared by 3+ elements (T-joints): couple the lowest-id element to each other one (Star), "
                     "leave them uncoupled (Free), or reject the mesh (Error)",
                     {"Star", "Free", "Error"});
  auto& r = pl->sublist("Rectangle", false, "Flat rectangle [0, Length] x [0, Width] in z = 0; sets x_min, x_max, "
                                            "y_min, y_max (node and side sets), corners (node set)");
  r.set("Length", 1.0, "Extent along x [length]", params::positive_double());
  r.set("Width", 1.0, "Extent along y [length]", params::positive_double());
  r.set("Elements Along Length", 10, "Grid cells along x (2 triangles per cell)", params::int_range(1, 1 << 20));
  r.set("Elements Along Width", 2, "Grid cells along y", params::int_range(1, 1 << 20));
  add_pattern_and_block(r);
  auto& p = pl->sublist("Cylindrical Panel", false,
                        "Open cylindrical panel: axis x in [0, Length], arc of Angle centred on +z; sets x_min, x_max "
                        "(curved ends), theta_min, theta_max (straight edges)");
  p.set("Radius", 1.0, "Mid-surface radius [length]", params::positive_double());
  p.set("Length", 1.0, "Axial length [length]", params::positive_double());
  p.set("Angle", 90.0, "Opening angle [degrees]", params::double_range(0.0, 360.0, true, true));
  p.set("Axial Elements", 8, "Grid cells along the axis", params::int_range(1, 1 << 20));
  p.set("Circumferential Elements", 4, "Grid cells along the arc", params::int_range(1, 1 << 20));
  add_pattern_and_block(p);
  auto& c = pl->sublist("Cylinder", false, "Closed cylinder (tube) with axis x in [0, Length]; sets x_min, x_max");
  c.set("Radius", 1.0, "Mid-surface radius [length]", params::positive_double());
  c.set("Length", 1.0, "Axial length [length]", params::positive_double());
  c.set("Axial Elements", 8, "Grid cells along the axis", params::int_range(1, 1 << 20));
  c.set("Circumferential Elements", 12, "Grid cells around the circumference", params::int_range(3, 1 << 20));
  add_pattern_and_block(c);
  return pl;
}

MeshParams MeshParams::from_parameters(Teuchos::ParameterList& pl, const params::Context& ctx,
                                       const std::string& deck_dir) {
  const auto valid = valid_parameters();
  params::validate(pl, *valid, ctx);
  MeshParams m;
  const std::string source = pl.get<std::string>("Source");
  m.source = static_cast<Source>(std::find(sources.begin(), sources.end(), source) - sources.begin());
  // Every generator sublist given is validated (a typo in one is reported even if another Source is
  // selected; the documented skeleton carries all of them); only the selected one is used.
  for (const std::string g : {"Rectangle", "Cylindrical Panel", "Cylinder"})
    if (pl.isSublist(g)) params::validate(pl.sublist(g), valid->sublist(g), ctx / g);
  m.refinements = pl.get<int>("Uniform Refinements");
  m.deck = ctx.file;
  const std::string nm = pl.get<std::string>("Non-Manifold Edges");
  m.non_manifold = nm == "Error"  ? mesh::NonManifoldPolicy::Error
                   : nm == "Free" ? mesh::NonManifoldPolicy::Free
                                  : mesh::NonManifoldPolicy::Star;
  if (m.source == Source::File) {
    const std::string file = pl.get<std::string>("File");
    SHELLFRAC_INPUT_REQUIRE(!file.empty(), ctx.file << ": '" << ctx.path << "->File' is required when Source = File");
    m.file = (file.front() == '/' || deck_dir.empty()) ? file : deck_dir + "/" + file;
    return m;
  }
  SHELLFRAC_INPUT_REQUIRE(pl.get<std::string>("File").empty(),
                          ctx.file << ": '" << ctx.path << "->File' is set but 'Source' is '" << source
                                   << "' (use Source = File to read a mesh file)");
  auto& g = pl.sublist(source);
  const std::string pattern = g.get<std::string>("Diagonal Pattern");
  m.pattern = static_cast<mesh::DiagonalPattern>(std::find(patterns.begin(), patterns.end(), pattern) - patterns.begin());
  m.block_name = g.get<std::string>("Block Name");
  SHELLFRAC_INPUT_REQUIRE(!m.block_name.empty(), ctx.file << ": '" << ctx.path << "->" << source << "->Block Name' is empty");
  m.length = g.get<double>("Length");
  if (m.source == Source::Rectangle) {
    m.width = g.get<double>("Width");
    m.n_length = g.get<int>("Elements Along Length");
    m.n_width = g.get<int>("Elements Along Width");
  } else {
    m.radius = g.get<double>("Radius");
    m.n_length = g.get<int>("Axial Elements");
    m.n_width = g.get<int>("Circumferential Elements");
    if (m.source == Source::CylindricalPanel) m.angle_degrees = g.get<double>("Angle");
  }
  const double cells = double(m.n_length) * m.n_width * std::pow(4.0, m.refinements);
  SHELLFRAC_INPUT_REQUIRE(2 * cells < 2e9, ctx.file << ": '" << ctx.path << "' asks for " << 2 * cells
                                                    << " elements, more than this version supports (2e9)");
  return m;
}

namespace {

/// Memory the run will need on one node [bytes]: per rank, the model's share of the elements, the mesh that
/// every rank holds during set-up, and the program itself (measured peaks of fracture runs with plasticity and
/// checkpoints: 5.7 kB per element over 2 ranks at 650 000 to 690 000 elements; docs/performance.md).
double estimated_node_bytes(double elements, int ranks, int ranks_on_node) {
  const double per_rank = elements * (6e3 / ranks + 0.25e3) + 60e6;
  return per_rank * ranks_on_node;
}

/// Available memory of this node [bytes] (MemAvailable of /proc/meminfo), or 0 if unknown.
double available_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  while (in >> key >> kib) {
    if (key == "MemAvailable:") return kib * 1024;
    in.ignore(256, '\n');
  }
  return 0;
}

/// Refuses a mesh whose run would not fit in the node's memory, before it is refined. On rank 0.
void check_memory(const MeshParams& p, GlobalId base_elements, int ranks, int ranks_on_node) {
  const double elements = double(base_elements) * std::pow(4.0, p.refinements);
  const double need = estimated_node_bytes(elements, ranks, ranks_on_node), have = available_bytes();
  SHELLFRAC_INPUT_REQUIRE(have == 0 || need <= have,
                          p.deck << ": the mesh would have " << elements << " elements (" << base_elements << " x 4^"
                                 << p.refinements << " Uniform Refinements); " << ranks_on_node << " rank(s) of "
                                 << ranks << " on this node would need about " << need / 1e9 << " GB, but the node "
                                 << "has " << have / 1e9 << " GB available; use fewer refinements or more nodes");
}

int ranks_on_this_node(MPI_Comm comm) {
  MPI_Comm node;
  SHELLFRAC_REQUIRE(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) == MPI_SUCCESS,
                    "MPI_Comm_split_type failed");
  const int n = parallel::size(node);
  MPI_Comm_free(&node);
  return n;
}

}  // namespace

mesh::SerialMesh build_mesh(const MeshParams& p, MPI_Comm comm) {
  mesh::SerialMesh m;
  const int ranks = parallel::size(comm), ranks_on_node = ranks_on_this_node(comm);
  parallel::on_root_then_agree(
      [&] {
        switch (p.source) {
          case MeshParams::Source::File: m = meshio::read_mesh_file(p.file); break;
          case MeshParams::Source::Rectangle:
            m = mesh::make_rectangle(p.length, p.width, p.n_length, p.n_width, p.pattern, 0, 0, p.block_name);
            break;
          case MeshParams::Source::CylindricalPanel:
            m = mesh::make_cylindrical_panel(p.radius, p.length, p.angle_degrees * M_PI / 180, p.n_length, p.n_width,
                                             p.pattern, p.block_name);
            break;
          case MeshParams::Source::Cylinder:
            m = mesh::make_cylinder(p.radius, p.length, p.n_length, p.n_width, p.pattern, p.block_name);
            break;
        }
        check_memory(p, m.num_elements(), ranks, ranks_on_node);
        mesh::promote_to_p2(m);  // the method uses P2 positions (paper §4.1)
        for (int i = 0; i < p.refinements; ++i) mesh::refine_uniform(m);
        mesh::check_mesh(m);
      },
      0, comm);
  mesh::broadcast(m, 0, comm);
  return m;
}

}  // namespace shellfrac::solver
