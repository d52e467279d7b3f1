#include "shellfrac/solver/input/deck.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/printable_text.hpp"
#include "shellfrac/decomposition/partitioner.hpp"
#include "shellfrac/solver/input/element_fields.hpp"
#include "shellfrac/solver/input/units.hpp"

namespace shellfrac::solver {

namespace {

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

/// Calls make(name, sublist, context) for every child of the user-named sublist `list` in deck order; a child
/// that is a parameter instead of a sublist is an input error (`expect` says what belongs there).
template <class Make>
void for_each_named_sublist(Teuchos::ParameterList& deck, const char* list, const char* expect,
                            const params::Context& ctx, Make&& make) {
  auto& pl = deck.sublist(list);
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    SHELLFRAC_INPUT_REQUIRE(pl.entry(it).isList(),
                            ctx.file << ": '" << list << "->" << name << "' must be a sublist" << expect);
    make(name, pl.sublist(name), ctx / list / name);
  }
}

/// Blocks and Materials must both be present and non-empty.
void require_sections(Teuchos::ParameterList& pl, const params::Context& ctx) {
  for (const char* name : {"Blocks", "Materials"})
    SHELLFRAC_INPUT_REQUIRE(pl.isSublist(name) && pl.sublist(name).numParams() > 0,
                            ctx.file << ": the deck needs a '" << name << "' sublist with one entry per "
                                     << (std::string(name) == "Blocks" ? "element block (thickness, material)"
                                                                       : "material (density, elastic constants)"));
}

/// Blocks and Materials, and every block's material defined.
void read_sections(Teuchos::ParameterList& pl, const params::Context& ctx, Deck& d) {
  for_each_named_sublist(pl, "Blocks", " (Thickness, Material)", ctx, [&](const auto& name, auto& sub, const auto& c) {
    d.blocks[name] = materials::BlockParams::from_parameters(name, sub, c);
  });
  for_each_named_sublist(pl, "Materials", "", ctx, [&](const auto& name, auto& sub, const auto& c) {
    d.materials[name] = materials::MaterialParams::from_parameters(name, sub, c);
  });
  for (const auto& [name, b] : d.blocks) {
    if (d.materials.count(b.material)) continue;
    std::ostringstream os;
    for (const auto& [m, unused] : d.materials) os << " '" << m << "'";
    throw InputError(ctx.file + ": 'Blocks->" + name + "->Material' is '" + b.material +
                     "', which is not in Materials; defined materials:" + os.str());
  }
}

/// Boundary Conditions, Initial Conditions, Loads and Regions, in deck order.
void read_conditions(Teuchos::ParameterList& pl, const params::Context& ctx, Deck& d) {
  for_each_named_sublist(pl, "Boundary Conditions", " (Type, Node Set)", ctx,
                         [&](const auto& name, auto& sub, const auto& c) {
                           d.boundary_conditions.push_back(BoundaryCondition::from_parameters(name, sub, c));
                         });
  for_each_named_sublist(pl, "Initial Conditions", " (Elements, Velocity)", ctx,
                         [&](const auto& name, auto& sub, const auto& c) {
                           d.initial_velocities.push_back(InitialVelocity::from_parameters(name, sub, c));
                         });
  for_each_named_sublist(pl, "Loads", "", ctx, [&](const auto& name, auto& sub, const auto& c) {
    d.loads.push_back(Load::from_parameters(name, sub, c));
  });
  for_each_named_sublist(pl, "Regions", " (Shape, ...)", ctx, [&](const auto& name, auto& sub, const auto& c) {
    d.regions.push_back(Region::from_parameters(name, sub, c));
  });
}

/// Output and Checkpoint: result names, the output directory (must exist) and the checkpoint paths.
void read_output(Teuchos::ParameterList& pl, const params::Context& ctx, Deck& d) {
  const std::string& file = ctx.file;
  auto& out = pl.sublist("Output");
  params::validate(out, *OutputParams::valid_parameters(), ctx / "Output");
  d.output.base_name = out.get<std::string>("Base Name");
  if (d.output.base_name.empty()) d.output.base_name = stem_of(file);
  // A result name stays in the output directory: no directory part, no '.' or '..' of its own.
  const std::string& base = d.output.base_name;
  SHELLFRAC_INPUT_REQUIRE(base != "." && base != ".." && base.find('/') == std::string::npos &&
                              base.find('\0') == std::string::npos,
                          file << ": 'Output->Base Name' = '" << base << "' is not a file name: the results are "
                               << "written in 'Output->Directory' under names made of the base name, which must not "
                               << "contain '/' or be '.' or '..'; set the directory with 'Output->Directory'");
  d.output.directory = out.get<std::string>("Directory");
  for (const auto& p : out.get<Teuchos::Array<std::string>>("Probes")) {
    SHELLFRAC_INPUT_REQUIRE(std::find(d.output.probes.begin(), d.output.probes.end(), p) == d.output.probes.end(),
                            file << ": 'shellfrac->Output->Probes' names '" << p
                                 << "' twice; each probe gives its own history columns, so name each set once");
    d.output.probes.push_back(p);
  }
  const auto id_list = [&](const char* name) {
    std::vector<long long> ids;
    for (int id : out.get<Teuchos::Array<int>>(name)) {
      SHELLFRAC_INPUT_REQUIRE(id > 0, file << ": 'Output->" << name << "' names " << id
                                           << "; ids are the mesh file's, which are positive");
      SHELLFRAC_INPUT_REQUIRE(std::find(ids.begin(), ids.end(), id) == ids.end(),
                              file << ": 'Output->" << name << "' names " << id << " twice");
      ids.push_back(id);
    }
    return ids;
  };
  d.output.history_nodes = id_list("History Nodes");
  d.output.history_elements = id_list("History Elements");
  d.output.block_energies = out.get<bool>("Block Energies");
  d.output.progress_interval = out.get<double>("Progress Interval");
  auto valid = nodal_result_names();
  for (const auto& f : element_result_names()) valid.push_back(f);
  for (const auto& f : out.get<Teuchos::Array<std::string>>("Fields")) {
    SHELLFRAC_INPUT_REQUIRE(std::find(valid.begin(), valid.end(), f) != valid.end(),
                            file << ": 'Output->Fields' names '" << f << "', which is not a result field; the fields "
                                 << "are" << [&] {
                                      std::ostringstream os;
                                      for (const auto& v : valid) os << " '" << v << "'";
                                      return os.str();
                                    }());
    SHELLFRAC_INPUT_REQUIRE(std::find(d.output.fields.begin(), d.output.fields.end(), f) == d.output.fields.end(),
                            file << ": 'Output->Fields' names '" << f << "' twice");
    d.output.fields.push_back(f);
  }
  auto& ck = pl.sublist("Checkpoint");
  params::validate(ck, *CheckpointParams::valid_parameters(), ctx / "Checkpoint");
  d.checkpoint.step_interval = ck.get<int>("Step Interval");
  d.checkpoint.wall_minutes = ck.get<double>("Wall Interval");
  d.checkpoint.file = ck.get<std::string>("File");
  d.checkpoint.keep = ck.get<int>("Keep");
  if (d.checkpoint.file.empty()) d.checkpoint.file = d.output.path("_checkpoint.h5");
  d.checkpoint.restart_from = ck.get<std::string>("Restart From");
  if (!d.checkpoint.restart_from.empty() && d.checkpoint.restart_from.front() != '/')
    d.checkpoint.restart_from =
        (directory_of(file).empty() ? std::string() : directory_of(file) + "/") + d.checkpoint.restart_from;
  const auto require_writable_directory = [&](const std::string& dir, const std::string& parameter) {
    struct stat st {};
    SHELLFRAC_INPUT_REQUIRE(stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode),
                            file << ": " << parameter << " = '" << dir << "' is not an existing directory");
    SHELLFRAC_INPUT_REQUIRE(access(dir.c_str(), W_OK | X_OK) == 0,
                            file << ": " << parameter << " = '" << dir
                                 << "' is not writable (no permission, or a read-only file system)");
  };
  if (!d.output.directory.empty()) require_writable_directory(d.output.directory, "'Output->Directory'");
  // Checked now, not at the first checkpoint hours later.
  const std::string& series = d.checkpoint.file;
  SHELLFRAC_INPUT_REQUIRE(!series.empty() && series.back() != '/',
                          file << ": 'Checkpoint->File' = '" << series << "' names a directory, not a file");
  const std::string series_directory = directory_of(series);
  if (!series_directory.empty())
    require_writable_directory(series_directory, "the directory of 'Checkpoint->File' ('" + series + "')");
}

/// Velocities above the fastest elastic wave speed sqrt(E/rho) of the deck's materials strain the shell by more
/// than 100 % at once (a bar struck at speed v strains by v / c), and a pressure above the largest Young's
/// modulus compresses the thickness by more than that: both are mistakes that would blow up in the first step.
void check_magnitudes(const Deck& d, const params::Context& ctx) {
  double c = 0, E = 0;
  std::string fastest, stiffest;
  for (const auto& [name, m] : d.materials) {
    if (std::sqrt(m.youngs_modulus / m.density) > c) c = std::sqrt(m.youngs_modulus / m.density), fastest = name;
    if (m.youngs_modulus > E) E = m.youngs_modulus, stiffest = name;
  }
  const auto speed = [&](double v, const std::string& path) {
    SHELLFRAC_INPUT_REQUIRE(v <= c, ctx.file << ": '" << ctx.path << "->" << path << "' has the magnitude " << v
                                             << ", more than the elastic wave speed sqrt(E/rho) = " << c
                                             << " of material '" << fastest << "', the fastest of the deck; a "
                                             << "velocity above it strains the shell by more than 100 % at once");
  };
  const auto norm = [](const Vec3& v) { return std::hypot(v[0], v[1], v[2]); };
  for (const auto& iv : d.initial_velocities) {
    speed(norm(iv.velocity), "Initial Conditions->" + iv.name + "->Velocity");
    speed(std::abs(iv.normal_velocity), "Initial Conditions->" + iv.name + "->Normal Velocity");
  }
  for (const auto& bc : d.boundary_conditions)
    if (bc.type == BoundaryCondition::Type::PrescribedVelocity)
      speed(norm(bc.velocity), "Boundary Conditions->" + bc.name + "->Velocity");
  for (const auto& l : d.loads) {
    if (l.type != Load::Type::Pressure) continue;
    const bool table = l.function == Load::Function::Table;
    double p = std::abs(l.pressure);
    if (table)
      p = std::abs(*std::max_element(l.values.begin(), l.values.end(),
                                     [](double a, double b) { return std::abs(a) < std::abs(b); }));
    SHELLFRAC_INPUT_REQUIRE(p <= E, ctx.file << ": '" << ctx.path << "->Loads->" << l.name << "->"
                                             << (table ? "Values" : "Pressure") << "' reaches " << p
                                             << ", more than Young's Modulus " << E << " of material '" << stiffest
                                             << "', the stiffest of the deck; a pressure above it compresses the "
                                             << "shell by more than 100 %");
  }
}

}  // namespace

std::vector<std::string> nodal_result_names() { return {"displ", "velocity", "director"}; }

std::vector<std::string> element_result_names() {
  std::vector<std::string> names = {"block", "rank"};
  for (const auto& f : element_field_names()) names.push_back(f);
  return names;
}

std::string OutputParams::path(const std::string& suffix) const {
  return (directory.empty() ? std::string() : directory + "/") + base_name + suffix;
}

Teuchos::RCP<const Teuchos::ParameterList> OutputParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Output"));
  pl->set("Base Name", "", "Base name of the results: <Base Name>.exo (or the per-rank set <Base Name>.exo.<np>.<rank>) "
                           "and <Base Name>_history.csv; empty = the deck's file name without extension");
  pl->set("Directory", "", "Directory for the results (must exist); empty = the current directory");
  pl->set("Progress Interval", 10.0,
          "Seconds of wall time between progress lines on the console (rank 0): step, time, step size, percent "
          "done, steps per second, elapsed time, estimated time to the end, energy balance error relative to the "
          "energy put in, activated and separated edges; 0 = none (also shellfrac --quiet)",
          params::non_negative_double());
  pl->set("Fields", Teuchos::Array<std::string>(),
          "Exodus fields to write, e.g. {displ, damage, fragment_id}; empty = all: the nodal vectors displ, velocity, "
          "director and the element fields block, rank, eq_plastic_strain, membrane_force, bending_moment, "
          "shear_force, damage, fragment_id, edge_strength (docs/output.md). The history columns are always written as global "
          "variables");
  pl->set("Probes", Teuchos::Array<std::string>(), "Node sets whose mean displacement and velocity (over all DG "
                                                     "copies of their nodes) are history columns <set>_displ_x ... "
                                                     "<set>_vel_z, e.g. {tip, centre}");
  pl->set("History Nodes", Teuchos::Array<int>(),
          "Mesh nodes, by the mesh file's ids (positions from 1 when it has none), whose displacement, velocity and "
          "acceleration (mean over the node's DG copies) are history columns node<id>_displ_x ... node<id>_acc_z, "
          "e.g. {17, 2051}");
  pl->set("History Elements", Teuchos::Array<int>(),
          "Elements, by the mesh file's ids (positions from 1 when it has none), whose resultants N11 N22 N12 M11 "
          "M22 M12 Q1 Q2 (area means in the element's local basis), equivalent plastic strain and strain energy are "
          "history columns element<id>_N11 ... element<id>_strain_energy, e.g. {5, 1200}");
  pl->set("Block Energies", true,
          "History columns per element block: <block>_kinetic_energy, <block>_strain_energy and "
          "<block>_plastic_dissipation (they sum to the totals)");
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> CheckpointParams::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Checkpoint"));
  pl->set("Step Interval", 0, "Write a checkpoint every N steps (0 = not by step count)", params::int_range(0, 1 << 30));
  pl->set("Wall Interval", 0.0, "Write a checkpoint every M minutes of wall time (0 = not by time)",
          params::non_negative_double());
  pl->set("File", "", "Name of the checkpoint files (HDF5): a checkpoint at step N is <File without .h5>_step<N>.h5; "
                      "empty = <Output Directory>/<Base Name>_checkpoint.h5. Each file is written atomically and "
                      "carries checksums; SIGUSR1 writes one, SIGTERM or SIGUSR2 writes one and stops the run (exit code 4)");
  pl->set("Keep", 3, "How many of this run's checkpoints are kept (older ones are removed; the checkpoint a run "
                     "restarted from is never written, replaced or removed)", params::int_range(1, 1000000));
  pl->set("Restart From", "", "Continue from this checkpoint (relative paths: to the deck's directory); empty = "
                              "start at t = 0; the time step is the deck's. The command-line option restart (shellfrac --restart FILE DECK) overrides it");
  return pl;
}

namespace {

/// The top-level `Units` (units.hpp): one of the known systems, SI by default.
void set_units_parameter(Teuchos::ParameterList& pl) {
  std::vector<std::string> names;
  for (const auto& u : unit_systems()) names.push_back(u.name);
  params::set_choice(pl, "Units", "SI",
                     "The deck's consistent system of units, named in the results (Exodus information, "
                     "<base>_summary.json, the tools' labels): SI (m, kg, s; N, Pa, J), mm-t-s (mm, t, s; N, MPa, mJ), "
                     "mm-kg-ms (mm, kg, ms; kN, GPa, J), mm-g-ms (mm, g, ms; N, MPa, mJ), in-lbf-s (in, lbf s^2/in, "
                     "s; lbf, psi, in lbf), none (not declared). A density, modulus, strength, fracture energy or "
                     "thickness outside what real shells have in the declared system is warned about, naming it "
                     "(SI ranges: density 1 to 3e4 kg/m^3, Young's modulus 1e5 to 1.5e12 Pa, yield and cohesive "
                     "strength 1e5 to 1e11 Pa, fracture energy 0.01 to 1e7 J/m^2, thickness 1e-6 to 1 m); none: no "
                     "check, no unit labels",
                     names);
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> Deck::valid_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("shellfrac"));
  set_units_parameter(*pl);
  pl->set("Mesh", *MeshParams::valid_parameters(), "The mesh: a file or a built-in generator");
  auto& blocks = pl->sublist("Blocks", false, "One sublist per element block of the mesh, named as the block");
  blocks.set("shell", *materials::BlockParams::valid_parameters());
  auto& mats = pl->sublist("Materials", false, "One sublist per material, named freely; blocks refer to them");
  mats.set("steel", *materials::MaterialParams::valid_parameters());
  pl->set("Partitioning", *decomposition::PartitionParams::valid_parameters(), "Domain decomposition of the elements");
  pl->set("Output", *OutputParams::valid_parameters(), "Results files");
  pl->set("Checkpoint", *CheckpointParams::valid_parameters(), "Checkpoint files and restart");
  pl->set("Discretization", *DiscretizationParams::valid_parameters(), "DG stabilization constants");
  pl->set("Time Integration", *TimeParams::valid_parameters(), "Explicit central differences");
  pl->set("Fracture", *FractureParams::valid_parameters(), "Extrinsic cohesive fracture on element edges");
  pl->set("Contact", *ContactParams::valid_parameters(), "Contact with rigid walls (theory.md §12)");
  auto wall = *RigidWall::valid_parameters();  // an example wall, below the skeleton's plate
  wall.set("Point", Teuchos::Array<double>(Teuchos::tuple<double>(0.0, 0.0, -1.0)),
           RigidWall::valid_parameters()->getEntry("Point").docString());
  pl->sublist("Contact").sublist("Rigid Walls").set("floor", wall);
  auto& bcs = pl->sublist("Boundary Conditions", false, "One sublist per condition, named freely");
  bcs.set("clamped end", *BoundaryCondition::valid_parameters());
  auto& ics = pl->sublist("Initial Conditions", false, "One sublist per initial velocity, named freely");
  ics.set("initial velocity", *InitialVelocity::valid_parameters());
  auto& loads = pl->sublist("Loads", false, "One sublist per load, named freely");
  loads.set("pressure", *Load::valid_parameters());
  auto& regions = pl->sublist("Regions", false, "One sublist per region of space, named freely; a region's name "
                                                "serves as an element set, node set or side set");
  regions.set("patch", *Region::valid_parameters());
  return pl;
}

Deck Deck::read(const std::string& file, MPI_Comm comm) { return from_parameters(params::read_deck(file, comm), file); }

Deck Deck::from_parameters(const Teuchos::RCP<Teuchos::ParameterList>& deck, const std::string& file) {
  Deck d;
  d.file = file;
  d.expanded = deck;
  auto& pl = *d.expanded;
  const params::Context ctx{file, "shellfrac"};
  params::check_printable(pl, ctx);  // names and text go into result files and messages
  // Top level: only the known sublists; user-named children of Blocks/Materials are validated one by one.
  Teuchos::ParameterList top("shellfrac");
  set_units_parameter(top);
  for (const char* name : {"Mesh", "Blocks", "Materials", "Partitioning", "Output", "Checkpoint", "Discretization",
                           "Time Integration", "Fracture", "Contact", "Boundary Conditions", "Initial Conditions",
                           "Loads", "Regions"})
    top.sublist(name);
  params::validate(pl, top, ctx);
  require_sections(pl, ctx);
  d.units = pl.get<std::string>("Units");
  d.mesh = MeshParams::from_parameters(pl.sublist("Mesh"), ctx / "Mesh", directory_of(file));
  read_sections(pl, ctx, d);
  d.partition = std::make_shared<decomposition::PartitionParams>(
      decomposition::PartitionParams::from_parameters(pl.sublist("Partitioning"), ctx / "Partitioning"));
  d.discretization = DiscretizationParams::from_parameters(pl.sublist("Discretization"), ctx / "Discretization");
  d.time = TimeParams::from_parameters(pl.sublist("Time Integration"), ctx / "Time Integration");
  d.fracture = FractureParams::from_parameters(pl.sublist("Fracture"), ctx / "Fracture");
  d.contact = ContactParams::from_parameters(pl.sublist("Contact"), ctx / "Contact");
  read_conditions(pl, ctx, d);
  check_magnitudes(d, ctx);
  read_output(pl, ctx, d);
  return d;
}

}  // namespace shellfrac::solver
