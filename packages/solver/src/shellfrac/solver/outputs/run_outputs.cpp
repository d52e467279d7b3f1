#include "shellfrac/solver/outputs/run_outputs.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>

#include "shellfrac/core/digest.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/core/version.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/io/results_writer.hpp"
#include "shellfrac/io/history.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/fracture/fracture.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/input/units.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/outputs/results_series.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

namespace shellfrac::solver {

namespace {

/// The program, the deck's name, its units and the digest of its expanded text, then the expanded deck, as Exodus
/// information records (at most 80 characters each).
std::vector<std::string> info_records(const Teuchos::ParameterList& deck, const std::string& file,
                                      const std::string& units) {
  Teuchos::ParameterList pl = deck;
  params::strip_validators(pl);
  std::ostringstream os;
  Teuchos::writeParameterListToXmlOStream(pl, os);
  Digest digest;
  digest.add(os.str());
  std::vector<std::string> lines = {std::string("shellfrac ") + shellfrac::version, "deck: " + file,
                                    "units: " + unit_system(units).description(),
                                    "expanded deck digest: " + digest.hex()};
  std::istringstream is(os.str());
  for (std::string line; std::getline(is, line);)
    for (std::size_t i = 0; i < line.size() || i == 0; i += 80) lines.push_back(line.substr(i, 80));
  return lines;
}

/// Removes the result `file` of an earlier run; a link or anything but a regular file of that name is an
/// OutputError (core/files.hpp), as for every result.
void remove_stale_result(const std::string& file) {
  files::require_result_path(file);
  files::remove_result(file);
}

/// Removes `path` and the files of any per-rank set `path.<n>.<r>` (remove_stale_result).
void remove_stale_results(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const std::regex set_file(std::regex_replace(p.filename().string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                            R"(\.[0-9]+\.[0-9]+)");
  remove_stale_result(path);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (std::regex_match(entry.path().filename().string(), set_file)) remove_stale_result(entry.path().string());
}

}  // namespace

// A side set named like a node set (every region, and x_min ... of the generators) is written as <name>_edges
// (sideset_<id> if that is too long for Exodus): ParaView 5.11's IOSS reader fails on a file whose node and side
// sets share names once both are shown with displacements.
ResultsSets results_sets(const Deck& deck, const RunModel& model) {
  ResultsSets layout;
  const auto& dm = *model.distributed;
  const auto& mesh = *model.mesh;
  const GlobalId npe = dm.nodes_per_element();
  const MeshSets sets(mesh, deck.file, deck.regions);
  const std::string what = "the results' sets";
  const auto add_nodes = [&](const std::string& name, int id) {
    const auto member = sets.node_set(what, name, false);
    io::ResultsSet set{name, id, {}, {}};
    for (LocalId le = 0; le < dm.num_owned(); ++le)
      for (int a = 0; a < npe; ++a)
        if (member[dm.mesh_node(le, a)]) set.entries.push_back(dm.element_gid(le) * npe + a);
    layout.node_sets.push_back(std::move(set));
  };
  const auto add_sides = [&](const std::string& name, int id) {
    const auto sides = sets.side_set(what, name);
    const bool shared = std::any_of(layout.node_sets.begin(), layout.node_sets.end(),
                                    [&](const io::ResultsSet& n) { return n.name == name; });
    std::string file_name = shared ? name + "_edges" : name;
    if (file_name.size() > io::max_exodus_name_length) file_name = "sideset_" + std::to_string(id);
    io::ResultsSet set{file_name, id, {}, {}};
    for (LocalId le = 0; le < dm.num_owned(); ++le)
      for (int k = 0; k < 3; ++k)
        if (sides.count({dm.element_gid(le), k})) set.entries.push_back(dm.element_gid(le)), set.edges.push_back(k);
    layout.side_sets.push_back(std::move(set));
  };
  int node_id = 0, side_id = 0;
  for (const auto& s : mesh.node_sets) add_nodes(s.name, s.id), node_id = std::max(node_id, s.id);
  for (const auto& r : deck.regions) add_nodes(r.name, ++node_id);
  for (const auto& s : mesh.side_sets) add_sides(s.name, s.id), side_id = std::max(side_id, s.id);
  for (const auto& r : deck.regions) add_sides(r.name, ++side_id);
  return layout;
}

namespace {

/// Indices of the written fields among `candidates` (Output->Fields; empty: all), in candidate order.
std::vector<int> written(const std::vector<std::string>& candidates, const std::vector<std::string>& fields) {
  std::vector<int> out;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (fields.empty() || std::find(fields.begin(), fields.end(), candidates[i]) != fields.end())
      out.push_back(static_cast<int>(i));
  return out;
}

template <class T>
std::vector<T> pick(std::vector<T> all, const std::vector<int>& which) {
  std::vector<T> out;
  for (int i : which) out.push_back(std::move(all[i]));
  return out;
}

/// The Exodus layout of the owned elements: blocks, DG nodes, the nodal vectors and element fields, and the
/// history columns as global variables (names cut to the length Exodus readers take).
io::ResultsLayout results_layout(const Deck& deck, const RunModel& model, const ResultsSets& sets,
                                 const std::vector<std::string>& columns) {
  const auto& dm = *model.distributed;
  io::ResultsLayout layout;
  layout.title = "shellfrac: " + deck.file;
  layout.nodes_per_element = dm.nodes_per_element();
  layout.block_names = model.block_names, layout.block_ids = model.block_ids;
  layout.nodal_vectors = pick(nodal_result_names(), written(nodal_result_names(), deck.output.fields));
  layout.element_scalars = pick(element_result_names(), written(element_result_names(), deck.output.fields));
  layout.info = info_records(*deck.expanded, deck.file, deck.units);
  for (const auto& c : columns) layout.global_variables.push_back(c.substr(0, io::max_global_name_length));
  layout.element_gids.reserve(std::size_t(dm.num_owned())), layout.element_block.reserve(std::size_t(dm.num_owned()));
  layout.node_coords.reserve(std::size_t(dm.num_owned()) * std::size_t(dm.nodes_per_element()));
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    layout.element_gids.push_back(dm.element_gid(le));
    layout.element_block.push_back(dm.element_block(le));
    for (int a = 0; a < dm.nodes_per_element(); ++a) layout.node_coords.push_back(dm.node_coords(le, a));
  }
  layout.node_sets = sets.node_sets, layout.side_sets = sets.side_sets;
  return layout;
}

/// The keys of a CSV table's mark in a checkpoint's header.
std::string bytes_key(const std::string& table) { return table + " table bytes"; }
std::string digest_key(const std::string& table) { return table + " table digest"; }
std::string file_key(const std::string& table) { return table + " table file"; }

bool exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::symlink_status(path, ec).type() != std::filesystem::file_type::not_found;
}

}  // namespace

ResultPaths::ResultPaths(const Deck& deck)
    : checkpoint(deck.checkpoint.file), directory_(deck.output.directory), base_(deck.output.base_name) {
  name(deck.output.path(""));
}

std::string ResultPaths::in_directory(const std::string& file_name) const {
  return directory_.empty() ? file_name : directory_ + "/" + file_name;
}

bool ResultPaths::of_this_base(const std::string& file_name, const std::string& suffix) const {
  if (file_name == base_ + suffix) return true;
  const std::string restart = base_ + ".restart";
  if (file_name.size() <= restart.size() + suffix.size() || file_name.compare(0, restart.size(), restart) != 0 ||
      file_name.compare(file_name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string step = file_name.substr(restart.size(), file_name.size() - restart.size() - suffix.size());
  return step.find_first_not_of("0123456789") == std::string::npos;
}

void ResultPaths::name(const std::string& prefix) {
  prefix_ = prefix;
  exodus = prefix + ".exo", history = prefix + "_history.csv", fragments = prefix + "_fragments.csv";
  cracks = prefix + "_cracks.csv", lock = prefix + ".lock";
}

ResultPaths ResultPaths::restarted(long step) const {
  ResultPaths r = *this;
  r.name(prefix_ + ".restart" + std::to_string(step));
  r.exodus = restart_member(exodus, step);
  return r;
}

TableMarks table_marks(const io::CheckpointData& header) {
  TableMarks marks;
  for (const char* table : {"history", "fragments", "cracks"}) {
    const auto bytes = header.scalars.find(bytes_key(table));
    const auto digest = header.strings.find(digest_key(table));
    const auto file = header.strings.find(file_key(table));
    if (bytes != header.scalars.end() && digest != header.strings.end() && file != header.strings.end())
      marks[table] = {static_cast<long long>(bytes->second), digest->second, file->second};
  }
  return marks;
}

RunOutputs::RunOutputs(const Deck& deck, RunModel& model, const ResultsSets& sets, const HistoryPoints& points,
                       long restart_step, const TableMarks& marks, double e0, MPI_Comm comm)
    : deck_(deck),
      model_(model),
      points_(points),
      e0_(e0),
      nodal_written_(written(nodal_result_names(), deck.output.fields)),
      element_written_(written(element_result_names(), deck.output.fields)),
      comm_(comm) {
  const ResultPaths paths(deck);
  const bool restarted = restart_step >= 0;
  const ResultPaths restart_paths = paths.restarted(std::max(restart_step, 0L));
  exodus_path_ = restarted ? restart_paths.exodus : paths.exodus;
  parallel::on_root_then_agree([&] { prepare_result_files(paths, restarted); }, 0, comm);
  const auto& dm = *model.distributed;
  element_constant_.resize(2);
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    element_constant_[0].push_back(model.block_ids[std::size_t(dm.element_block(le))]);
    element_constant_[1].push_back(dm.rank());
  }
  HistoryGroups& g = history_groups_;
  g.probe_names = points.probe_names;
  for (const auto& bc : deck.boundary_conditions) g.condition_names.push_back(bc.name);
  g.contact_columns = model.dynamics->contact_columns();
  for (long long id : points.node_ids) g.node_names.push_back("node" + std::to_string(id));
  for (long long id : points.element_ids) g.element_names.push_back("element" + std::to_string(id));
  if (deck.output.block_energies) g.block_names = model.block_names;
  std::vector<std::string> columns;
  for (const auto& [name, value] : history_row({}, 0, g.names_only())) columns.push_back(name);
  exodus_ = std::make_unique<io::ExodusResultsWriter>(exodus_path_, results_layout(deck, model, sets, columns), comm);
  // A table: a new file, or after a restart the table the checkpoint names continued if it is this base's and
  // provably the checkpointed run's; else a new file (the table on disk is left as it is).
  const auto table = [&](const char* name, const std::string& suffix, const std::vector<std::string>& table_columns) {
    const std::string fresh = paths.prefix() + suffix;
    if (!restarted) return std::make_unique<io::HistoryWriter>(fresh, table_columns, comm);
    const auto mark = marks.find(name);
    const bool ours = mark != marks.end() && paths.of_this_base(mark->second.file, suffix);
    if (ours) {
      const std::string recorded = paths.in_directory(mark->second.file);
      if (auto resumed = io::HistoryWriter::resume(recorded, table_columns, mark->second, comm)) return resumed;
    }
    const std::string path = exists(fresh) ? restart_paths.prefix() + suffix : fresh;
    if (ours || mark == marks.end())
      notices_.push_back((ours ? paths.in_directory(mark->second.file) : fresh) +
                         " does not hold exactly the rows the checkpoint was written after (" +
                         (ours ? "missing, changed, or written by another run since"
                               : "the checkpoint does not record them") +
                         "): it is left as it is, and this run's " + name + " rows from step " +
                         std::to_string(restart_step) + " on go to " + path);
    return std::make_unique<io::HistoryWriter>(path, table_columns, comm);
  };
  const auto& dyn = *model.dynamics;
  history_ = table("history", "_history.csv", columns);
  if (!dyn.fracture()) return;
  const std::vector<std::string> fragment_columns = {"time",  "fragment_id", "elements",   "mass",       "com_x",
                                                     "com_y", "com_z",       "momentum_x", "momentum_y", "momentum_z"};
  fragments_ = table("fragments", "_fragments.csv", fragment_columns);
  cracks_ = table("cracks", "_cracks.csv", Fracture::crack_event_columns());
}

// Results of an earlier run with another rank count would sit beside ours and confuse ParaView (which opens a
// per-rank set from any of its files): remove <base>.exo and every <base>.exo.<n>.<r> first; a new run also removes
// the restarts of an earlier one (ParaView would open them as the continuation of ours). A restart looks at the
// series it continues instead (results_series.hpp).
void RunOutputs::prepare_result_files(const ResultPaths& paths, bool restarted) {
  const int np = parallel::size(comm_);
  remove_stale_results(exodus_path_);
  if (!restarted) {  // fragment and crack tables of an earlier run would mislead
    remove_restart_members(paths.exodus);
    remove_stale_result(paths.fragments);
    remove_stale_result(paths.cracks);
    return;
  }
  restart_time_ = model_.dynamics->time();
  later_frames_ = frames_after(paths.exodus, exodus_path_, np, restart_time_);
  if (only_other_layouts(paths.exodus, np))
    notices_.push_back("the results before this restart are not in this run's layout (" +
                       (np > 1 ? std::to_string(np) + " per-rank files" : std::string("one file")) +
                       "; another rank count, or joined): ParaView opens a run and its restarts as one series "
                       "only when all are in one layout; join each per-rank set of the series into one file "
                       "with shellfrac_exojoin (e.g. 'shellfrac_exojoin " + paths.exodus +
                       "'), then open " + paths.exodus);
}

RunOutputs::~RunOutputs() = default;

void RunOutputs::write_frame(bool fragment_rows) {
  auto& dyn = *model_.dynamics;
  if (fragments_ && fragment_rows)
    for (auto row : dyn.fragment_table()) {
      row.insert(row.begin(), dyn.time());
      fragments_->write_row(row);
    }
  // One nodal component at a time: a frame never holds a copy of the nodal state.
  const auto nodal = [&](std::size_t v, int c, double* out) { dyn.nodal_field_component(nodal_written_[v], c, out); };
  std::vector<std::vector<double>> fields;
  dyn.element_fields(fields);
  std::vector<std::vector<double>> element = element_constant_;
  element.insert(element.end(), fields.begin(), fields.end());
  exodus_->write_step(dyn.time(), nodal, pick(std::move(element), element_written_), history_values(nullptr));
  frame_times_.push_back(dyn.time());
}

std::vector<std::string> RunOutputs::series_notices() const {
  return interleaving_notices(later_frames_, frame_times_, exodus_path_, restart_time_);
}

std::vector<double> RunOutputs::history_values(StepRecord* record) {
  auto& dyn = *model_.dynamics;
  const StepRecord r = dyn.record();
  HistoryGroups& g = history_groups_;  // names set once; the values refreshed here
  g.probes = dyn.probes(points_.probe_members);
  g.reactions = dyn.reactions();
  g.contact_values = dyn.contact_values();
  g.nodes = dyn.node_histories(points_.nodes);
  g.elements = dyn.element_histories(points_.elements);
  if (!g.block_names.empty()) g.blocks = dyn.block_energies(g.block_names.size());
  std::vector<double> values;
  for (const auto& [name, value] : history_row(r, e0_, g)) values.push_back(value);
  if (record) *record = r;
  return values;
}

void RunOutputs::write_history() {
  auto& dyn = *model_.dynamics;
  StepRecord r;
  history_->write_row(history_values(&r));
  physics_.observe(r, e0_);
  if (cracks_ && r.cohesive_edges != cracks_logged_) {
    for (const auto& row : dyn.crack_events()) cracks_->write_row(row), physics_.observe_crack(row);
    cracks_logged_ = r.cohesive_edges;
  }
}

void RunOutputs::flush_crack_log() {
  if (!cracks_) return;
  const GlobalId activated = model_.dynamics->record().cohesive_edges;
  if (activated == cracks_logged_) return;
  for (const auto& row : model_.dynamics->crack_events()) cracks_->write_row(row), physics_.observe_crack(row);
  cracks_logged_ = activated;
}

const PhysicsSummary& RunOutputs::finish_physics() {
  const auto& dyn = *model_.dynamics;
  physics_.fracture = dyn.fracture(), physics_.plasticity = dyn.plasticity();
  if (physics_.fracture) physics_.observe_fragments(dyn.fragment_table());
  physics_.peak_plastic_strain = dyn.peak_plastic_strain();
  if (parallel::rank(comm_) == 0) write_whole_file(summary_path(), physics_.json(deck_.file, deck_.units, dyn.time()));
  return physics_;
}

std::string RunOutputs::summary_path() const {
  const std::string history = history_path();
  const std::string suffix = "_history.csv";
  return history.substr(0, history.size() - suffix.size()) + "_summary.json";
}

io::CheckpointData RunOutputs::checkpoint(io::CheckpointData state) const {
  state.scalars["e0"] = e0_;
  physics_.store(state.scalars);
  state.strings["deck"] = deck_.file;
  state.strings["results"] = files::resolved(deck_.output.path(""));  // <directory>/<base> of the run
  const auto mark = [&](const char* name, const std::unique_ptr<io::HistoryWriter>& table) {
    if (!table) return;
    const io::CsvMark m = table->mark();
    state.scalars[bytes_key(name)] = double(m.bytes);  // exact below 2^53 bytes
    state.strings[digest_key(name)] = m.digest;
    state.strings[file_key(name)] = m.file;
  };
  mark("history", history_), mark("fragments", fragments_), mark("cracks", cracks_);
  return state;
}

std::string RunOutputs::history_path() const { return history_->path(); }
std::string RunOutputs::fragments_path() const { return fragments_ ? fragments_->path() : std::string(); }
std::string RunOutputs::cracks_path() const { return cracks_ ? cracks_->path() : std::string(); }

}  // namespace shellfrac::solver
