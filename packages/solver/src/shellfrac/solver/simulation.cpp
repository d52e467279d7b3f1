#include "shellfrac/solver/simulation.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>
#include <sys/stat.h>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/dist/distributed_mesh.hpp"
#include "shellfrac/dist/partitioner.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/io/exodus_results.hpp"
#include "shellfrac/io/history.hpp"
#include "shellfrac/mesh/vec3_ops.hpp"
#include "shellfrac/solver/shell_dynamics.hpp"
#include <chrono>
#include <csignal>

namespace shellfrac::solver {

namespace {

/// Signal number received (SIGTERM / SIGUSR1), polled once per step by every rank.
volatile std::sig_atomic_t received_signal = 0;
extern "C" void on_signal(int sig) { received_signal = sig; }

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

std::string stem_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

/// The expanded deck as Exodus information records (at most 80 characters each).
std::vector<std::string> info_records(const Teuchos::ParameterList& deck) {
  Teuchos::ParameterList pl = deck;
  params::strip_validators(pl);
  std::ostringstream os;
  Teuchos::writeParameterListToXmlOStream(pl, os);
  std::vector<std::string> lines;
  std::istringstream is(os.str());
  for (std::string line; std::getline(is, line);)
    for (std::size_t i = 0; i < line.size() || i == 0; i += 80) lines.push_back(line.substr(i, 80));
  return lines;
}

/// Removes `path` and the files of any per-rank set `path.<n>.<r>`.
void remove_stale_results(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const std::regex set_file(std::regex_replace(p.filename().string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                            R"(\.[0-9]+\.[0-9]+)");
  std::error_code ec;
  fs::remove(p, ec);
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (std::regex_match(entry.path().filename().string(), set_file)) fs::remove(entry.path(), ec);
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> OutputParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Output"));
  pl->set("Base Name", "", "Base name of the results: <Base Name>.exo (or the per-rank set <Base Name>.exo.<np>.<rank>) "
                           "and <Base Name>_history.csv; empty = the deck's file name without extension");
  pl->set("Directory", "", "Directory for the results (must exist); empty = the current directory");
  pl->set("Probes", Teuchos::Array<std::string>(), "Node sets whose mean displacement and velocity (over all DG "
                                                     "copies of their nodes) are history columns <set>_displ_x ... "
                                                     "<set>_vel_z, e.g. {tip, centre}");
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> CheckpointParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Checkpoint"));
  pl->set("Step Interval", 0, "Write a checkpoint every N steps (0 = not by step count)", params::int_range(0, 1 << 30));
  pl->set("Wall Interval", 0.0, "Write a checkpoint every M minutes of wall time (0 = not by time)",
          params::non_negative_double());
  pl->set("File", "", "Checkpoint file (HDF5); empty = <Output Directory>/<Base Name>_checkpoint.h5. It is replaced "
                      "atomically; SIGUSR1 writes one, SIGTERM writes one and stops the run (exit code 4)");
  pl->set("Restart From", "", "Continue from this checkpoint (relative paths: to the deck's directory); empty = "
                              "start at t = 0; the time step is the deck's. The command-line option restart (shellfrac --restart FILE DECK) overrides it");
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> Deck::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("shellfrac"));
  pl->set("Mesh", *MeshParams::valid_parameters(), "The mesh: a file or a built-in generator");
  auto& blocks = pl->sublist("Blocks", false, "One sublist per element block of the mesh, named as the block");
  blocks.set("shell", *materials::BlockParams::valid_parameters());
  auto& mats = pl->sublist("Materials", false, "One sublist per material, named freely; blocks refer to them");
  mats.set("steel", *materials::MaterialParams::valid_parameters());
  pl->set("Partitioning", *dist::PartitionParams::valid_parameters(), "Domain decomposition of the elements");
  pl->set("Output", *OutputParams::valid_parameters(), "Results files");
  pl->set("Checkpoint", *CheckpointParams::valid_parameters(), "Checkpoint files and restart");
  pl->set("Discretization", *DiscretizationParams::valid_parameters(), "DG stabilization constants");
  pl->set("Time Integration", *TimeParams::valid_parameters(), "Explicit central differences");
  pl->set("Fracture", *FractureParams::valid_parameters(), "Extrinsic cohesive fracture on element edges");
  auto& bcs = pl->sublist("Boundary Conditions", false, "One sublist per condition, named freely");
  bcs.set("clamped end", *BoundaryCondition::valid_parameters());
  auto& ics = pl->sublist("Initial Conditions", false, "One sublist per initial velocity, named freely");
  ics.set("initial velocity", *InitialVelocity::valid_parameters());
  auto& loads = pl->sublist("Loads", false, "One sublist per load, named freely");
  loads.set("pressure", *Load::valid_parameters());
  return pl;
}

Deck Deck::read(const std::string& file, MPI_Comm comm) {
  Deck d;
  d.file = file;
  d.expanded = params::read_deck(file, comm);
  auto& pl = *d.expanded;
  const params::Context ctx{file, "shellfrac"};
  // Top level: only the known sublists; user-named children of Blocks/Materials are validated one by one.
  Teuchos::ParameterList top("shellfrac");
  for (const char* name : {"Mesh", "Blocks", "Materials", "Partitioning", "Output", "Checkpoint", "Discretization",
                           "Time Integration", "Fracture", "Boundary Conditions", "Initial Conditions", "Loads"})
    top.sublist(name);
  params::validate(pl, top, ctx);
  for (const char* name : {"Blocks", "Materials"})
    SHELLFRAC_INPUT_REQUIRE(pl.isSublist(name) && pl.sublist(name).numParams() > 0,
                            file << ": the deck needs a '" << name << "' sublist with one entry per "
                                 << (std::string(name) == "Blocks" ? "element block (thickness, material)"
                                                                   : "material (density, elastic constants)"));
  d.mesh = MeshParams::from_parameters(pl.sublist("Mesh"), ctx / "Mesh", directory_of(file));
  auto& blocks = pl.sublist("Blocks");
  for (auto it = blocks.begin(); it != blocks.end(); ++it) {
    const std::string& name = blocks.name(it);
    SHELLFRAC_INPUT_REQUIRE(blocks.entry(it).isList(),
                            file << ": 'Blocks->" << name << "' must be a sublist (Thickness, Material)");
    d.blocks[name] = materials::BlockParams::from_parameters(name, blocks.sublist(name), ctx / "Blocks" / name);
  }
  auto& mats = pl.sublist("Materials");
  for (auto it = mats.begin(); it != mats.end(); ++it) {
    const std::string& name = mats.name(it);
    SHELLFRAC_INPUT_REQUIRE(mats.entry(it).isList(), file << ": 'Materials->" << name << "' must be a sublist");
    d.materials[name] = materials::MaterialParams::from_parameters(name, mats.sublist(name), ctx / "Materials" / name);
  }
  for (const auto& [name, b] : d.blocks) {
    if (d.materials.count(b.material)) continue;
    std::ostringstream os;
    for (const auto& [m, unused] : d.materials) os << " '" << m << "'";
    throw InputError(file + ": 'Blocks->" + name + "->Material' is '" + b.material +
                     "', which is not in Materials; defined materials:" + os.str());
  }
  d.partition = std::make_shared<dist::PartitionParams>(
      dist::PartitionParams::from_parameters(pl.sublist("Partitioning"), ctx / "Partitioning"));
  d.discretization = DiscretizationParams::from_parameters(pl.sublist("Discretization"), ctx / "Discretization");
  d.time = TimeParams::from_parameters(pl.sublist("Time Integration"), ctx / "Time Integration");
  d.fracture = FractureParams::from_parameters(pl.sublist("Fracture"), ctx / "Fracture");
  auto& bcs = pl.sublist("Boundary Conditions");
  for (auto it = bcs.begin(); it != bcs.end(); ++it) {
    SHELLFRAC_INPUT_REQUIRE(bcs.entry(it).isList(), file << ": 'Boundary Conditions->" << bcs.name(it)
                                                         << "' must be a sublist (Type, Node Set)");
    d.boundary_conditions.push_back(BoundaryCondition::from_parameters(
        bcs.name(it), bcs.sublist(bcs.name(it)), ctx / "Boundary Conditions" / bcs.name(it)));
  }
  auto& ics = pl.sublist("Initial Conditions");
  for (auto it = ics.begin(); it != ics.end(); ++it) {
    SHELLFRAC_INPUT_REQUIRE(ics.entry(it).isList(), file << ": 'Initial Conditions->" << ics.name(it)
                                                         << "' must be a sublist (Elements, Velocity)");
    d.initial_velocities.push_back(InitialVelocity::from_parameters(
        ics.name(it), ics.sublist(ics.name(it)), ctx / "Initial Conditions" / ics.name(it)));
  }
  auto& loads = pl.sublist("Loads");
  for (auto it = loads.begin(); it != loads.end(); ++it) {
    SHELLFRAC_INPUT_REQUIRE(loads.entry(it).isList(), file << ": 'Loads->" << loads.name(it) << "' must be a sublist");
    d.loads.push_back(Load::from_parameters(loads.name(it), loads.sublist(loads.name(it)), ctx / "Loads" / loads.name(it)));
  }
  auto& out = pl.sublist("Output");
  params::validate(out, *OutputParams::valid_parameters(), ctx / "Output");
  d.output.base_name = out.get<std::string>("Base Name");
  if (d.output.base_name.empty()) d.output.base_name = stem_of(file);
  d.output.directory = out.get<std::string>("Directory");
  for (const auto& p : out.get<Teuchos::Array<std::string>>("Probes")) d.output.probes.push_back(p);
  auto& ck = pl.sublist("Checkpoint");
  params::validate(ck, *CheckpointParams::valid_parameters(), ctx / "Checkpoint");
  d.checkpoint.step_interval = ck.get<int>("Step Interval");
  d.checkpoint.wall_minutes = ck.get<double>("Wall Interval");
  d.checkpoint.file = ck.get<std::string>("File");
  if (d.checkpoint.file.empty())
    d.checkpoint.file = (d.output.directory.empty() ? std::string() : d.output.directory + "/") + d.output.base_name +
                        "_checkpoint.h5";
  d.checkpoint.restart_from = ck.get<std::string>("Restart From");
  if (!d.checkpoint.restart_from.empty() && d.checkpoint.restart_from.front() != '/')
    d.checkpoint.restart_from =
        (directory_of(file).empty() ? std::string() : directory_of(file) + "/") + d.checkpoint.restart_from;
  if (!d.output.directory.empty()) {
    struct stat st {};
    SHELLFRAC_INPUT_REQUIRE(stat(d.output.directory.c_str(), &st) == 0 && S_ISDIR(st.st_mode),
                            file << ": 'Output->Directory' = '" << d.output.directory << "' is not an existing directory");
  }
  return d;
}

DynamicsSetup make_dynamics_setup(const Deck& deck, const mesh::SerialMesh& mesh) {
  DynamicsSetup setup;
  for (const auto& b : mesh.blocks) {
    const auto& sec = deck.blocks.at(b.name);
    const auto& mat = deck.materials.at(sec.material);
    Section sc;
    sc.E = mat.youngs_modulus, sc.nu = mat.poissons_ratio, sc.rho = mat.density, sc.h = sec.thickness;
    sc.plastic = mat.plastic(), sc.Y0 = mat.yield_stress, sc.H = mat.hardening_modulus;
    sc.shear_yield = mat.shear_in_yield;
    sc.sigma_c = mat.cohesive_strength, sc.Gamma = mat.fracture_energy;
    setup.block_sections.push_back(sc);
  }
  setup.discretization = deck.discretization;
  setup.time = deck.time;
  setup.fracture = deck.fracture;
  setup.boundary_conditions = deck.boundary_conditions;
  setup.initial_velocities = deck.initial_velocities;
  setup.loads = deck.loads;
  setup.deck_file = deck.file;
  return setup;
}

Simulation::Simulation(const std::string& deck_file, MPI_Comm comm, const std::string& restart_file)
    : comm_(comm), deck_(Deck::read(deck_file, comm)) {
  if (!restart_file.empty()) deck_.checkpoint.restart_from = restart_file;
  mesh_ = std::make_unique<mesh::SerialMesh>(build_mesh(deck_.mesh, comm));
  const auto& m = *mesh_;
  // Every mesh block needs a section; every section must name a mesh block.
  for (const auto& b : m.blocks)
    SHELLFRAC_INPUT_REQUIRE(deck_.blocks.count(b.name), deck_.file << ": mesh block '" << b.name << "' (from " << m.source
                                                                   << ") has no entry in the Blocks sublist");
  for (const auto& section : deck_.blocks) {
    const std::string& name = section.first;  // not a structured binding: lambdas capture those only from C++20
    const bool found = std::any_of(m.blocks.begin(), m.blocks.end(), [&](const auto& b) { return b.name == name; });
    std::ostringstream os;
    for (const auto& b : m.blocks) os << " '" << b.name << "'";
    SHELLFRAC_INPUT_REQUIRE(found, deck_.file << ": 'Blocks->" << name << "' names no block of the mesh (" << m.source
                                              << "); its blocks are:" << os.str());
  }
  // Results are Exodus files, whose names are limited: fail now, not after the run has started writing.
  for (const auto& b : m.blocks)
    SHELLFRAC_INPUT_REQUIRE(b.name.size() <= io::max_exodus_name_length,
                            m.source << ": block name '" << b.name << "' is longer than "
                                     << io::max_exodus_name_length << " characters (Exodus II limit)");
  const auto topo = mesh::build_edge_topology(m, deck_.mesh.non_manifold);
  for (const auto& f : topo.interfaces)
    SHELLFRAC_INPUT_REQUIRE(!f.same_orientation || f.non_manifold,
                            m.source << ": elements " << f.minus.element + 1 << " and " << f.plus.element + 1
                                     << " have opposite orientations (normals); orient the surface consistently "
                                        "(e.g. Gmsh: ReorientMesh / Reverse Surface)");
  const int np = parallel::size(comm);
  const auto part = dist::partition_elements(m, topo, np, *deck_.partition, comm);
  dmesh_ = std::make_unique<dist::DistributedMesh>(m, topo, part, comm);

  dynamics_ = std::make_unique<ShellDynamics>(m, *dmesh_, make_dynamics_setup(deck_, m));
  // Restart: the checkpoint is read and checked against this model before any output is written.
  if (!deck_.checkpoint.restart_from.empty()) {
    const auto data = io::read_checkpoint(deck_.checkpoint.restart_from, comm_);
    const auto e0 = data.scalars.find("e0");
    SHELLFRAC_INPUT_REQUIRE(e0 != data.scalars.end(),
                            deck_.checkpoint.restart_from << ": not a checkpoint of a shellfrac run (no 'e0')");
    dynamics_->restore(data);
    restart_e0_ = e0->second;
    summary_.restart_step = dynamics_->step_count();
  }
  summary_.stable_dt = dynamics_->stable_time_step();
  for (const auto& name : deck_.output.probes) {
    const auto it = std::find_if(m.node_sets.begin(), m.node_sets.end(), [&](const auto& ns) { return ns.name == name; });
    std::string names;
    for (const auto& ns : m.node_sets) names += " '" + ns.name + "'";
    SHELLFRAC_INPUT_REQUIRE(it != m.node_sets.end(), deck_.file << ": 'Output->Probes' names node set '" << name
                                                                << "', which the mesh does not have; its node sets:"
                                                                << names);
    std::vector<char> member(m.num_nodes(), 0);
    for (GlobalId n : it->nodes) member[n] = 1;
    probe_names_.push_back(name);
    probe_members_.push_back(std::move(member));
  }
  summary_.dt = dynamics_->time_step();

  summary_.elements = m.num_elements();
  summary_.nodes = m.num_nodes();
  summary_.edges = topo.num_edges();
  summary_.interfaces = static_cast<GlobalId>(topo.interfaces.size());
  summary_.boundary_edges = static_cast<GlobalId>(topo.boundary.size());
  summary_.non_manifold_edges = topo.num_non_manifold_edges;
  summary_.max_owned = static_cast<GlobalId>(parallel::max(double(dmesh_->num_owned()), comm));
  summary_.min_owned = -static_cast<GlobalId>(parallel::max(-double(dmesh_->num_owned()), comm));
  summary_.max_ghosts = static_cast<GlobalId>(parallel::max(double(dmesh_->num_ghosts()), comm));
  summary_.min_ghosts = -static_cast<GlobalId>(parallel::max(-double(dmesh_->num_ghosts()), comm));
}

Simulation::~Simulation() = default;

std::string Simulation::exodus_path() const {
  const auto& o = deck_.output;
  return (o.directory.empty() ? std::string() : o.directory + "/") + o.base_name + ".exo";
}

std::string Simulation::checkpoint_path() const { return deck_.checkpoint.file; }

std::string Simulation::fragments_path() const {
  const auto& o = deck_.output;
  return (o.directory.empty() ? std::string() : o.directory + "/") + o.base_name + "_fragments.csv";
}

std::string Simulation::cracks_path() const {
  const auto& o = deck_.output;
  return (o.directory.empty() ? std::string() : o.directory + "/") + o.base_name + "_cracks.csv";
}

std::string Simulation::history_path() const {
  const auto& o = deck_.output;
  return (o.directory.empty() ? std::string() : o.directory + "/") + o.base_name + "_history.csv";
}

RunSummary Simulation::run() {
  const auto& dm = *dmesh_;
  const int npe = dm.nodes_per_element();
  io::ResultsLayout layout;
  layout.title = "shellfrac: " + deck_.file;
  layout.nodes_per_element = npe;
  for (const auto& b : mesh_->blocks) layout.block_names.push_back(b.name), layout.block_ids.push_back(b.id);
  layout.nodal_vectors = {"displ", "velocity", "director"};
  layout.element_scalars = {"block", "rank"};
  for (const auto& name : ShellDynamics::element_field_names()) layout.element_scalars.push_back(name);
  layout.info = info_records(*deck_.expanded);
  std::vector<std::vector<double>> element(2);
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    layout.element_gids.push_back(dm.element_gid(le));
    layout.element_block.push_back(dm.element_block(le));
    element[0].push_back(mesh_->blocks[dm.element_block(le)].id);
    element[1].push_back(dm.rank());
    for (int a = 0; a < npe; ++a) layout.node_coords.push_back(dm.node_coords(le, a));
  }
  // A restarted run writes its Exodus results to a new file set <base>.restart<step>.exo with continuous time,
  // and resumes the history and fragment tables after the restart point.
  const bool restarted = summary_.restart_step >= 0;
  const std::string exo_path =
      restarted ? exodus_path().substr(0, exodus_path().size() - 4) + ".restart" + std::to_string(summary_.restart_step) + ".exo"
                : exodus_path();
  // Results of an earlier run with another rank count would sit beside ours and confuse ParaView (which
  // opens a per-rank set from any of its files): remove <base>.exo and every <base>.exo.<n>.<r> first.
  parallel::on_root_then_agree(
      [&] {
        remove_stale_results(exo_path);
        if (!restarted) {  // fragment and crack tables of an earlier run would mislead
          std::filesystem::remove(fragments_path());
          std::filesystem::remove(cracks_path());
        }
      },
      0, comm_);
  io::ExodusResultsWriter exo(exo_path, layout, comm_);
  std::vector<std::string> columns = {"step",          "time",          "dt",
                                      "kinetic_energy", "strain_energy", "penalty_energy",
                                      "external_work",  "energy_balance_error"};
  for (const auto& p : probe_names_)
    for (const char* q : {"_displ_x", "_displ_y", "_displ_z", "_vel_x", "_vel_y", "_vel_z"}) columns.push_back(p + q);
  columns.push_back("reaction_work");
  columns.push_back("damping_dissipation");
  columns.push_back("plastic_dissipation");
  for (const char* c : {"cohesive_energy", "cohesive_dissipation", "activation_loss", "num_cohesive_edges",
                        "num_separated_edges", "num_fragments"})
    columns.push_back(c);
  for (const auto& bc : deck_.boundary_conditions)
    for (const char* q : {"_reaction_x", "_reaction_y", "_reaction_z", "_moment_x", "_moment_y", "_moment_z"})
      columns.push_back(bc.name + q);
  for (const char* q : {"angular_momentum_x", "angular_momentum_y", "angular_momentum_z"}) columns.push_back(q);
  auto& dyn = *dynamics_;
  auto history = restarted ? io::HistoryWriter(history_path(), columns, double(summary_.restart_step), comm_)
                           : io::HistoryWriter(history_path(), columns, comm_);
  std::vector<std::vector<Vec3>> nodal(3);
  std::vector<std::vector<double>> fields;
  // Fracture runs: a row per fragment at every output time.
  std::unique_ptr<io::HistoryWriter> fragment_csv;
  const std::vector<std::string> fragment_columns = {"time",  "fragment_id", "elements",   "mass",       "com_x",
                                                     "com_y", "com_z",       "momentum_x", "momentum_y", "momentum_z"};
  if (dyn.fracture())
    fragment_csv = restarted ? std::make_unique<io::HistoryWriter>(fragments_path(), fragment_columns, dyn.time(), comm_)
                             : std::make_unique<io::HistoryWriter>(fragments_path(), fragment_columns, comm_);
  // Fracture runs: a row per activated edge (the crack log), reported at history and checkpoint times.
  std::unique_ptr<io::HistoryWriter> crack_csv;
  if (dyn.fracture())
    crack_csv = restarted ? std::make_unique<io::HistoryWriter>(cracks_path(), ShellDynamics::crack_event_columns(),
                                                                double(summary_.restart_step), comm_)
                          : std::make_unique<io::HistoryWriter>(cracks_path(), ShellDynamics::crack_event_columns(), comm_);
  // The log is gathered only when the global count of activated edges has changed since it was last written (the
  // history record carries that count), so steps without activation cost no extra collective.
  GlobalId cracks_logged = -1;
  auto write_cracks = [&](GlobalId activated) {
    if (!crack_csv || activated == cracks_logged) return;
    for (const auto& row : dyn.crack_events()) crack_csv->write_row(row);
    cracks_logged = activated;
  };
  auto write_output = [&](bool fragment_rows = true) {
    if (fragment_csv && fragment_rows)
      for (auto row : dyn.fragment_table()) {
        row.insert(row.begin(), dyn.time());
        fragment_csv->write_row(row);
      }
    dyn.nodal_fields(nodal[0], nodal[1], nodal[2]);
    dyn.element_fields(fields);
    element.resize(2);
    element.insert(element.end(), fields.begin(), fields.end());
    exo.write_step(dyn.time(), nodal, element);
  };
  const StepRecord r0 = dyn.record();
  const double e0 = restarted ? restart_e0_ : r0.kinetic + r0.strain + r0.penalty;
  const auto& ck = deck_.checkpoint;
  const bool checkpointing = ck.step_interval > 0 || ck.wall_minutes > 0;
  auto write_checkpoint = [&] {
    write_cracks(dyn.record().cohesive_edges);  // complete through the checkpoint's step (a restart keeps those rows)
    auto data = dyn.checkpoint();
    data.scalars["e0"] = e0;
    data.strings["deck"] = deck_.file;
    io::write_checkpoint(checkpoint_path(), data, comm_);
  };
  auto write_history = [&] {
    const StepRecord r = dyn.record();
    // Energy balance (math.md §9.7, Check 2): K + U_el + U_stab + D_damp + W_p + U_coh + D_coh + D_act
    // - (K0 + U0) - W_ext - W_react.
    const double err = r.kinetic + r.strain + r.penalty + r.damping + r.plastic_work + r.cohesive_energy +
                       r.cohesive_dissipation + r.activation_loss - e0 - r.external_work - r.reaction_work;
    std::vector<double> row = {double(r.step), r.time, r.dt, r.kinetic, r.strain, r.penalty, r.external_work, err};
    for (double p : dyn.probes(probe_members_)) row.push_back(p);
    row.push_back(r.reaction_work);
    row.push_back(r.damping);
    row.push_back(r.plastic_work);
    for (double v : {r.cohesive_energy, r.cohesive_dissipation, r.activation_loss, double(r.cohesive_edges),
                     double(r.separated_edges), double(r.fragments)})
      row.push_back(v);
    for (double f : dyn.reactions()) row.push_back(f);
    for (double l : r.angular_momentum) row.push_back(l);
    history.write_row(row);
    write_cracks(r.cohesive_edges);
  };
  const auto& tp = deck_.time;
  const double output_step = tp.output_interval > 0 ? tp.output_interval : tp.end_time;
  double next_output = output_step;
  if (restarted) {
    write_output(false);  // the restart state opens the new Exodus set; history and fragments already have it
    while (next_output <= dyn.time() + 0.5 * dyn.time_step()) next_output += output_step;  // the same sums as a run from 0
  } else {
    write_output();
    write_history();
  }
  const auto start = std::chrono::steady_clock::now();
  auto last_checkpoint = start;
  bool last_written = true, last_recorded = true;
  received_signal = 0;
  const auto old_term = std::signal(SIGTERM, on_signal), old_usr1 = std::signal(SIGUSR1, on_signal);
  // The last good state: a copy of the state every 50 steps, written as the checkpoint if the run blows up.
  io::CheckpointData last_good = dyn.checkpoint();
  // Stop when the next step would overshoot the end time by more than half a step.
  while (dyn.time() + 0.5 * dyn.time_step() < tp.end_time) {
    try {
      dyn.step();
    } catch (const NumericalError& e) {
      last_good.scalars["e0"] = e0;
      last_good.strings["deck"] = deck_.file;
      io::write_checkpoint(checkpoint_path(), last_good, comm_);
      std::ostringstream os;
      os << e.what() << ". The last good state (step " << long(last_good.scalars["step"]) << ", time "
         << last_good.scalars["time"] << ") is in " << checkpoint_path()
         << "; restart from it (--restart) with a smaller Time Step or Safety Factor";
      throw NumericalError(os.str());
    }
    if (dyn.step_count() % 50 == 0) last_good = dyn.checkpoint();
    last_written = last_recorded = false;
    if (dyn.step_count() % tp.history_interval == 0) write_history(), last_recorded = true;
    if (dyn.time() >= next_output - 0.5 * dyn.time_step()) {
      write_output();
      last_written = true;
      while (next_output <= dyn.time() + 0.5 * dyn.time_step()) next_output += output_step;
    }
    // Checkpoints: every Step Interval steps, every Wall Interval minutes (rank 0's clock decides), at SIGUSR1;
    // SIGTERM writes one, closes the outputs and stops. A signal seen by any rank counts for all.
    const auto now = std::chrono::steady_clock::now();
    const bool wall_due = ck.wall_minutes > 0 &&
                          std::chrono::duration<double>(now - last_checkpoint).count() >= 60 * ck.wall_minutes;
    // One reduction: 2 x signal + wall flag (a signal on any rank, or any rank's clock, decides for all).
    const int code = static_cast<int>(parallel::max(double(2 * received_signal + (wall_due ? 1 : 0)), comm_));
    const int sig = code / 2;
    if ((ck.step_interval > 0 && dyn.step_count() % ck.step_interval == 0) || code != 0) {
      write_checkpoint();
      last_checkpoint = now;
      if (sig == SIGUSR1) received_signal = 0;
      if (sig == SIGTERM) {
        summary_.stopped_by_signal = true;
        break;
      }
    }
  }
  std::signal(SIGTERM, old_term), std::signal(SIGUSR1, old_usr1);
  if (!last_recorded) write_history();
  if (!last_written) write_output();
  if (checkpointing && !summary_.stopped_by_signal) write_checkpoint();  // the end state, to continue the run later
  summary_.steps = dyn.step_count() - std::max(summary_.restart_step, 0L);
  summary_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int np = parallel::size(comm_);
  summary_.files = {np == 1 ? exo_path : io::rank_file_name(exo_path, np, 0) + " ... (" + std::to_string(np) + " files)",
                    history_path()};
  if (checkpointing || summary_.stopped_by_signal) summary_.files.push_back(checkpoint_path());
  if (dynamics_->fracture()) {
    write_cracks(dyn.record().cohesive_edges);
    summary_.files.push_back(fragments_path());
    summary_.files.push_back(cracks_path());
  }
  return summary_;
}

}  // namespace shellfrac::solver
