#include "shellfrac/solver/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <optional>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/io/results_writer.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/mesh_sets.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/outputs/progress.hpp"
#include "shellfrac/solver/outputs/run_outputs.hpp"
#include "shellfrac/solver/restart/checkpoint_series.hpp"
#include "shellfrac/solver/setup/stop_signals.hpp"

namespace shellfrac::solver {

namespace {

/// Exodus frames every Output Interval (0: the first and the last state only). A frame is due when the time is
/// within half a step of the next output time.
class OutputSchedule {
 public:
  /// Outputs every `interval` of time up to `end`.
  OutputSchedule(double interval, double end) : interval_(interval), end_(end), next_(interval) {}
  bool due(double t, double dt) const { return t >= next_ - 0.5 * dt; }
  /// Where a step from t of the time step dt must end to land on the next output time or on End Time (Exact
  /// Output Times), or 0 if a whole step passes neither. An output time within 1e-6 dt of End Time is End Time
  /// (no sliver of a step between them); a step that ends within 1e-9 dt of a target lands on it.
  double landing(double t, double dt) const {
    const double target = next_ < end_ - 1e-6 * dt ? next_ : end_;
    return t + dt * (1 + 1e-9) >= target ? target : 0.0;
  }
  /// Moves the next output time past t (the same sums whether the run started at 0 or restarted). An interval
  /// far below the time step gives a frame at every step instead of a loop that (almost) never ends.
  void pass(double t, double dt) {
    const double now = t + 0.5 * dt;
    if (next_ <= now && (now - next_) / interval_ > 1e6) next_ = std::nextafter(now, HUGE_VAL);
    while (next_ <= now) {
      const double next = next_ + interval_;
      next_ = next > next_ ? next : std::nextafter(now, HUGE_VAL);
    }
  }

 private:
  double interval_, end_, next_;
};

/// When history rows are due: every History Interval steps, or with a History Time Interval at the first step at or
/// past each multiple of it.
class HistorySchedule {
 public:
  explicit HistorySchedule(const TimeParams& tp)
      : steps_(tp.history_interval),
        by_time_(tp.history_time_interval > 0),
        times_(by_time_ ? tp.history_time_interval : tp.end_time, tp.end_time) {}
  /// Whether a row is due at the end of the step to (step, t) of the time step dt; moves past it if so.
  bool due(long step, double t, double dt) {
    if (!by_time_) return step % steps_ == 0;
    if (!times_.due(t, dt)) return false;
    times_.pass(t, dt);
    return true;
  }
  /// A restarted run: its first row (the checkpoint's) is written; the next one is after t.
  void pass(double t, double dt) { times_.pass(t, dt); }

 private:
  int steps_;
  bool by_time_;
  OutputSchedule times_;
};

/// The energy the balance starts from: kinetic, strain and penalty energy of the initial state.
double energy_of_the_state(const StepRecord& r) { return r.kinetic + r.strain + r.penalty; }

enum class CheckpointAction { none, write, write_and_stop };

/// What the signals and the wall clock ask for after a step, agreed by all ranks with one reduction: a checkpoint
/// every Step Interval steps, every Wall Interval minutes (any rank's clock decides) and at SIGUSR1; a checkpoint
/// and a stop at SIGTERM or SIGUSR2 (a signal seen by any rank counts for all; the reduction's maximum of the
/// signal numbers puts a stop signal before SIGUSR1); a progress line when it is due.
class StepEvents {
 public:
  StepEvents(const CheckpointParams& p, ProgressReport& progress, MPI_Comm comm)
      : params_(p), progress_(progress), comm_(comm), last_(std::chrono::steady_clock::now()) {}
  struct Due {
    CheckpointAction checkpoint;
    bool progress;
    int signal;  ///< the signal acted on (0: none)
  };
  /// After step `step`. Collective.
  Due after_step(long step) {
    const auto now = std::chrono::steady_clock::now();
    const bool wall_due =
        params_.wall_minutes > 0 && std::chrono::duration<double>(now - last_).count() >= 60 * params_.wall_minutes;
    int mine[3] = {received_stop_signal(), wall_due ? 1 : 0, progress_.due() ? 1 : 0}, all[3];
    SHELLFRAC_REQUIRE(MPI_Allreduce(mine, all, 3, MPI_INT, MPI_MAX, comm_) == MPI_SUCCESS,
                      "MPI_Allreduce of the step events failed");
    const int signal = all[0];
    static_assert(SIGTERM > SIGUSR1 && SIGUSR2 > SIGUSR1, "a stop signal must win the maximum over SIGUSR1");
    Due due{CheckpointAction::none, all[2] != 0, signal};
    if (!((params_.step_interval > 0 && step % params_.step_interval == 0) || signal != 0 || all[1] != 0)) return due;
    last_ = now;
    if (signal == SIGUSR1) clear_checkpoint_signal();
    due.checkpoint = is_stop_signal(signal) ? CheckpointAction::write_and_stop : CheckpointAction::write;
    return due;
  }

 private:
  const CheckpointParams& params_;
  ProgressReport& progress_;
  MPI_Comm comm_;
  std::chrono::steady_clock::time_point last_;
};

/// Estimated size of the results of a run of `steps` steps from time t on `elements` elements [bytes]: the Exodus
/// frames (coordinates and connectivity of the DG copies once, then per frame three nodal vectors per DG node and
/// the element fields), and the history rows as text.
double estimated_result_bytes(const Deck& deck, GlobalId elements, long steps, double t) {
  const auto& tp = deck.time;
  const double frames =
      std::min(double(steps), tp.output_interval > 0 ? std::floor((tp.end_time - t) / tp.output_interval) : 0) + 2;
  const double dg_nodes = 6.0 * double(elements);
  const double fixed = dg_nodes * 3 * 8 + dg_nodes * 4;
  const auto& fields = deck.output.fields;
  const auto nodal = nodal_result_names();
  const double vectors = fields.empty() ? double(nodal.size()) : double(std::count_if(fields.begin(), fields.end(), [&](const auto& f) {
    return std::find(nodal.begin(), nodal.end(), f) != nodal.end();
  }));
  const double scalars = fields.empty() ? double(element_result_names().size()) : double(fields.size()) - vectors;
  const double per_frame = dg_nodes * 3 * 8 * vectors + double(elements) * scalars * 8;
  const double columns = 30 + 6 * double(deck.output.probes.size() + deck.boundary_conditions.size()) +
                        9 * double(deck.output.history_nodes.size()) + 10 * double(deck.output.history_elements.size()) +
                        (deck.output.block_energies ? 3 * double(deck.blocks.size()) : 0);
  const double rows = (tp.history_time_interval > 0
                           ? std::min(double(steps), std::floor((tp.end_time - t) / tp.history_time_interval))
                           : double(steps) / tp.history_interval) + 2;
  return fixed + frames * per_frame + rows * columns * 16;
}

/// A checkpoint on disk: its file, step and time.
struct CheckpointOnDisk {
  std::string file;
  long step = -1;
  double time = 0;
};

/// The message of a blow-up that names the last good state on disk: `last_good` if the run kept a copy in memory
/// (written now as a checkpoint), else the last checkpoint written or started from (`on_disk`; none if the run
/// blew up before its first checkpoint).
std::string stop_at_blow_up(const NumericalError& e, CheckpointSeries& checkpoints,
                            const std::optional<io::CheckpointData>& last_good, const CheckpointOnDisk& on_disk) {
  CheckpointOnDisk good = on_disk;
  if (last_good) {
    good.file = checkpoints.write(*last_good);
    good.step = long(last_good->scalars.at("step")), good.time = last_good->scalars.at("time");
  }
  std::ostringstream os;
  os << e.what() << ". ";
  if (good.file.empty()) {
    os << "No checkpoint was written before the blow-up; rerun with a smaller Time Step or Safety Factor";
    return os.str();
  }
  os << "The last good state (step " << good.step << ", time " << good.time << ") is in " << good.file
     << (checkpoints.is_restart_file(good.file) ? " (the checkpoint this run started from)" : "")
     << "; restart from it (--restart) with a smaller Time Step or Safety Factor";
  return os.str();
}

/// Whether `file` is one of the checkpoints of the series <stem>_step<N>.h5.
bool in_series(const std::string& file, const std::string& stem) {
  const std::string f = files::resolved(file), s = files::resolved(stem) + "_step";
  return f.compare(0, s.size(), s) == 0;
}

/// The locks of a run (core/files.hpp): its output base and, if Checkpoint->File names another series, that
/// series. Taken on rank 0 before anything is written, released when the run ends. Collective.
class RunLocks {
 public:
  RunLocks(const Deck& deck, MPI_Comm comm) {
    parallel::on_root_then_agree(
        [&] {
          const ResultPaths paths(deck);
          const std::string base = deck.output.path("");
          locks_.push_back(std::make_unique<files::RunLock>(paths.lock, base, deck.file));
          const std::string stem = checkpoint_stem(deck.checkpoint.file);
          if (files::resolved(stem) != files::resolved(base + "_checkpoint"))
            locks_.push_back(std::make_unique<files::RunLock>(stem + ".lock", deck.checkpoint.file, deck.file));
        },
        0, comm);
  }

 private:
  std::vector<std::unique_ptr<files::RunLock>> locks_;
};

}  // namespace

Simulation::Simulation(const std::string& deck_file, MPI_Comm comm, const std::string& restart_file,
                       bool allow_physics_change)
    : signals_(std::make_unique<SignalGuard>()),
      comm_(comm),
      deck_(Deck::read(deck_file, comm)),
      allow_physics_change_(allow_physics_change) {
  if (!restart_file.empty()) deck_.checkpoint.restart_from = restart_file;
  stop_if_terminated("reading the deck", comm);
  model_ = build_run_model(deck_, comm);
  fingerprint_ = RestartFingerprint::of(deck_, *model_.distributed, *model_.mesh);
  progress_interval_ = deck_.output.progress_interval;
  resolve_history_points();
  results_sets_ = results_sets(deck_, model_);
  summarize();
  model_.release_global_mesh();  // from here on a rank holds only its part of the mesh
  if (!deck_.checkpoint.restart_from.empty()) restart_from_checkpoint();
  check_time_step();
  stop_if_terminated("the set-up", comm);
}

Simulation::~Simulation() = default;

// The checkpoint is read and checked against this deck and mesh before any output is written.
void Simulation::restart_from_checkpoint() {
  const std::string& file = deck_.checkpoint.restart_from;
  files::require_regular_input(file, "the checkpoint to restart from");  // a FIFO would block in open()
  auto& dyn = *model_.dynamics;
  dyn.restore(file, [&](const io::CheckpointData& header) {  // before any table is read into the state
    const auto e0 = header.scalars.find("e0");
    SHELLFRAC_INPUT_REQUIRE(e0 != header.scalars.end(), file << ": not a checkpoint of a shellfrac run (no 'e0')");
    fingerprint_.check(header, file, allow_physics_change_);
    refuse_changed_physics_over_its_origin(header);
    restart_e0_ = e0->second;
    restart_marks_ = table_marks(header);
    restart_physics_ = PhysicsSummary::restored(header.scalars);
    const auto results = header.strings.find("results");
    if (results != header.strings.end()) restart_origin_ = results->second;
  });
  SHELLFRAC_INPUT_REQUIRE(dyn.time() + 0.5 * dyn.time_step() < deck_.time.end_time,
                          deck_.file << ": 'Time Integration->End Time' = " << deck_.time.end_time
                                     << " is not after the time " << dyn.time() << " of the checkpoint " << file
                                     << " (step " << dyn.step_count() << "): nothing to run; raise End Time");
  summary_.restart_step = dyn.step_count();
}

// A restart with other physics is another run: its results and checkpoints must not continue (and so cut or
// replace) those of the run it starts from. Known by the output base the checkpoint records, and by the checkpoint
// series the restart file belongs to.
void Simulation::refuse_changed_physics_over_its_origin(const io::CheckpointData& header) const {
  if (fingerprint_.physics_differences(header).empty()) return;
  const auto results = header.strings.find("results");
  const std::string& file = deck_.checkpoint.restart_from;
  const bool same_results = results != header.strings.end() && results->second == files::resolved(deck_.output.path(""));
  const bool same_series = in_series(file, checkpoint_stem(deck_.checkpoint.file));
  SHELLFRAC_INPUT_REQUIRE(!same_results && !same_series,
                          deck_.file << ": this restart changes the physics (--allow-physics-change) but would write "
                                     << (same_results ? "its results under the same 'Output->Base Name' and "
                                                        "'Output->Directory'"
                                                      : "its checkpoints into the series '" + deck_.checkpoint.file + "'")
                                     << " as the run that wrote " << file
                                     << ", cutting and replacing that run's results and later checkpoints; give this "
                                        "run another 'Output->Base Name' (or 'Output->Directory') and, if set, "
                                        "another 'Checkpoint->File'");
}

void Simulation::resolve_history_points() {
  const MeshSets sets(*model_.mesh, deck_.file, deck_.regions);
  summary_.regions = sets.region_sizes();
  HistoryPoints& h = history_points_;
  for (const auto& name : deck_.output.probes) {
    h.probe_members.push_back(sets.node_set("'Output->Probes'", name, false));
    sets.require_some("'Output->Probes'", name, h.probe_members.back());
    h.probe_names.push_back(name);
  }
  h.node_ids = deck_.output.history_nodes, h.element_ids = deck_.output.history_elements;
  h.nodes = sets.nodes_by_id("'Output->History Nodes'", h.node_ids);
  h.elements = sets.elements_by_id("'Output->History Elements'", h.element_ids);
}

void Simulation::summarize() {
  const auto& dm = *model_.distributed;
  summary_.stable_dt = model_.dynamics->stable_time_step();
  summary_.mass_scaling = model_.dynamics->model().mass_scaling;
  summary_.strengths = model_.dynamics->strengths();
  summary_.seed = deck_.fracture.seed;
  summary_.dt = model_.dynamics->time_step();
  const MeshCounts& c = model_.counts;
  summary_.elements = c.elements, summary_.nodes = c.nodes, summary_.edges = c.edges;
  summary_.interfaces = c.interfaces, summary_.boundary_edges = c.boundary_edges;
  summary_.non_manifold_edges = c.non_manifold_edges;
  summary_.max_owned = static_cast<GlobalId>(parallel::max(double(dm.num_owned()), comm_));
  summary_.min_owned = -static_cast<GlobalId>(parallel::max(-double(dm.num_owned()), comm_));
  summary_.max_ghosts = static_cast<GlobalId>(parallel::max(double(dm.num_ghosts()), comm_));
  summary_.min_ghosts = -static_cast<GlobalId>(parallel::max(-double(dm.num_ghosts()), comm_));
}

std::string Simulation::element_description(GlobalId element, int block) const {
  const std::string& name = model_.block_names.at(std::size_t(block));
  const auto& section = deck_.blocks.at(name);
  const auto& m = deck_.materials.at(section.material);
  std::ostringstream os;
  os << model_.dynamics->model().element_name(element) << " of block '" << name << "' (material '" << section.material
     << "': Young's Modulus " << m.youngs_modulus << ", Density " << m.density << "; Thickness " << section.thickness
     << ")";
  return os.str();
}

// A time step that is zero, denormal or gives an absurd number of steps is refused (also by --check), naming the
// element that sets it; a step set by a few elements far below the median is reported (warnings()).
void Simulation::check_time_step() {
  const auto& dyn = *model_.dynamics;
  const auto& survey = dyn.model().time_step_survey;
  const auto& tp = deck_.time;
  const std::string setter = element_description(survey.min_element, survey.min_block);
  const double dt = dyn.time_step();
  SHELLFRAC_INPUT_REQUIRE(std::isnormal(dt), deck_.file << ": the time step " << dt << " is zero or below the "
                                                        << "smallest normal number: " << setter << " has the stable "
                                                        << "step " << survey.min_dt << "; check the units");
  SHELLFRAC_INPUT_REQUIRE(!tp.exact_output_times || tp.output_interval == 0 || tp.output_interval >= dt,
                          deck_.file << ": 'Time Integration->Exact Output Times' with an Output Interval of "
                                     << tp.output_interval << ", below the time step " << dt
                                     << ", would shorten every step to the interval; raise the Output Interval or "
                                        "turn Exact Output Times off");
  const double planned = (tp.end_time - dyn.time()) / dt;
  SHELLFRAC_INPUT_REQUIRE(planned <= tp.maximum_steps,
                          deck_.file << ": the run would take " << planned << " steps (End Time " << tp.end_time
                                     << ", time step " << dt << "), more than 'Time Integration->Maximum Steps' = "
                                     << tp.maximum_steps << "; the step is set by " << setter
                                     << "; check the units, remesh or use Target Time Step, or raise Maximum Steps");
  // Reported below 0.3 of the median: on the A319 skin at 100 mm (h = 1.5 mm) the CAD slivers give 0.21 of the
  // median element, whose step the thickness (director limit) sets; a run then takes 5 times more steps.
  constexpr double far_below_median = 0.3;
  if (tp.target_time_step > 0 || tp.time_step > 0 || survey.min_dt >= far_below_median * survey.median_dt) return;
  std::ostringstream os;
  const auto& c = survey.min_centroid;
  os << setter << ", centroid (" << c[0] << ", " << c[1] << ", " << c[2] << "), has the smallest stable step "
     << survey.min_dt << ", " << survey.min_dt / survey.median_dt << " of the median element's " << survey.median_dt
     << ": it sets the time step of the whole mesh (a sliver, or a locally refined region?); remesh it, or use "
        "'Time Integration->Target Time Step' (selective mass scaling, docs/theory.md §8.1)";
  model_.warnings.push_back(os.str());
}

// Peak resident memory of each rank so far: the largest, its rank, and the sum.
void Simulation::record_peak_memory() {
  const std::vector<double> all = parallel::peak_resident_bytes(comm_);
  const auto largest = std::max_element(all.begin(), all.end());
  summary_.peak_memory_max = *largest, summary_.peak_memory_rank = int(largest - all.begin());
  summary_.peak_memory_sum = 0;
  for (const double m : all) summary_.peak_memory_sum += m;
}

std::string Simulation::exodus_path() const { return ResultPaths(deck_).exodus; }
std::string Simulation::history_path() const { return ResultPaths(deck_).history; }
std::string Simulation::fragments_path() const { return ResultPaths(deck_).fragments; }
std::string Simulation::cracks_path() const { return ResultPaths(deck_).cracks; }

RunSummary Simulation::run() {
  auto& dyn = *model_.dynamics;
  const bool restarted = summary_.restart_step >= 0;
  const double e0 = restarted ? restart_e0_ : energy_of_the_state(dyn.record());
  const RunLocks locks(deck_, comm_);  // before anything is written
  RunOutputs out(deck_, model_, results_sets_, history_points_, summary_.restart_step, restart_marks_, e0,
                 comm_);
  print_notices(start_notices(out));
  if (restarted) out.resume_physics(restart_physics_);
  const auto& tp = deck_.time;
  OutputSchedule frames(tp.output_interval > 0 ? tp.output_interval : tp.end_time, tp.end_time);
  HistorySchedule rows(tp);
  if (restarted) {
    out.write_frame(false);  // the restart state opens the new Exodus set; history and fragments already have it
    frames.pass(dyn.time(), dyn.time_step());
    rows.pass(dyn.time(), dyn.time_step());
  } else {
    out.write_frame();
    out.write_history();
  }
  const auto start = std::chrono::steady_clock::now();
  bool frame_written = true, history_written = true;
  CheckpointSeries checkpoints(deck_.checkpoint, deck_.checkpoint.restart_from, fingerprint_, comm_);
  CheckpointOnDisk on_disk;
  if (restarted) on_disk = {deck_.checkpoint.restart_from, dyn.step_count(), dyn.time()};
  const auto write_checkpoint = [&] {
    out.flush_crack_log();  // complete through the checkpoint's step (a restart keeps those rows)
    on_disk = {checkpoints.write(out.checkpoint(dyn.checkpoint())), dyn.step_count(), dyn.time()};
  };
  ProgressReport progress(parallel::rank(comm_) == 0 ? &std::cout : nullptr, progress_interval_, dyn.step_count(),
                          dyn.time(), tp.end_time, dyn.time_step(), dyn.fracture());
  const long planned = std::lround(std::ceil((tp.end_time - dyn.time()) / dyn.time_step() - 0.5));
  progress.plan(estimated_result_bytes(deck_, summary_.elements, planned, dyn.time()));
  StepEvents events(deck_.checkpoint, progress, comm_);
  // The last good state if the run blows up: with a checkpoint schedule, the last checkpoint; without one, a copy
  // of the state kept in memory every 50 steps (as large as the state: docs/performance.md), written then.
  const bool checkpointing = deck_.checkpoint.step_interval > 0 || deck_.checkpoint.wall_minutes > 0;
  std::optional<io::CheckpointData> last_good;
  // The copy carries the marks of the CSV tables as they stand at its step (the crack log completed through it).
  const auto keep_last_good = [&] {
    out.flush_crack_log();
    last_good.reset();  // one copy at a time
    last_good = io::built(out.checkpoint(dyn.checkpoint()));
  };
  if (!checkpointing) keep_last_good();
  // Stop when the next step would overshoot the end time by more than half a step; with Exact Output Times the
  // steps that would pass an output time or End Time are shortened to end on it.
  const bool exact = tp.exact_output_times;
  while (exact ? dyn.time() < tp.end_time : dyn.time() + 0.5 * dyn.time_step() < tp.end_time) {
    try {
      const double land = exact ? frames.landing(dyn.time(), dyn.time_step()) : 0.0;
      if (land > 0)
        dyn.step_to(land);
      else
        dyn.step();
    } catch (const NumericalError& e) {
      throw NumericalError(stop_at_blow_up(e, checkpoints, last_good, on_disk));
    }
    if (last_good && dyn.step_count() % 50 == 0) keep_last_good();
    history_written = rows.due(dyn.step_count(), dyn.time(), dyn.time_step());
    if (history_written) out.write_history();
    frame_written = frames.due(dyn.time(), dyn.time_step());
    if (frame_written) out.write_frame(), frames.pass(dyn.time(), dyn.time_step());
    const auto due = events.after_step(dyn.step_count());
    if (due.progress) progress.print(dyn.record(), e0, dyn.relaxation_residual());
    if (due.checkpoint != CheckpointAction::none) write_checkpoint();
    if (due.checkpoint == CheckpointAction::write_and_stop) {
      summary_.stopped_by_signal = true, summary_.stop_signal = signal_name(due.signal);
      break;
    }
    if (dyn.relaxed() || dyn.relaxation_stalled()) break;  // the static state, or no way to it (Static Relaxation)
  }
  if (!history_written) out.write_history();
  if (!frame_written) out.write_frame();
  if (checkpointing && !summary_.stopped_by_signal) write_checkpoint();  // to continue later
  print_notices(out.series_notices());
  complete_summary(out, checkpoints.last(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return summary_;
}

// What the user must know about the files at the start: RunOutputs' notices, and for a restart under another output
// base than the run that wrote the checkpoint, where the steps before it are.
std::vector<std::string> Simulation::start_notices(const RunOutputs& out) const {
  std::vector<std::string> notices = out.notices();
  const std::string base = deck_.output.path("");
  if (summary_.restart_step < 0 || restart_origin_.empty() || restart_origin_ == files::resolved(base)) return notices;
  std::ostringstream os;
  os << "this restart writes its results under " << base << ", not under " << restart_origin_
     << " as the run that wrote " << deck_.checkpoint.restart_from << ": its history and Exodus series begin at step "
     << summary_.restart_step << " (t = " << model_.dynamics->time() << "), the steps before are in "
     << restart_origin_ << "*; to continue that run's files, restart with its 'Output->Base Name' and "
     << "'Output->Directory'";
  notices.push_back(os.str());
  return notices;
}

void Simulation::print_notices(const std::vector<std::string>& notices) const {
  if (parallel::rank(comm_) == 0)
    for (const auto& notice : notices) std::cerr << "shellfrac: notice: " << notice << "\n";
}

// The run's end in the summary: how the static relaxation ended, peak memory, steps and wall time, the files written.
void Simulation::complete_summary(RunOutputs& out, const std::string& last_checkpoint, double wall_seconds) {
  const auto& dyn = *model_.dynamics;
  summary_.static_relaxation = deck_.time.static_relaxation;
  summary_.relaxed = dyn.relaxed(), summary_.residual = dyn.relaxation_residual();
  summary_.stalled = dyn.relaxation_stalled(), summary_.best_residual = dyn.best_relaxation_residual();
  summary_.at_floor = dyn.relaxed_at_floor(), summary_.displacement_change = dyn.relaxation_displacement_change();
  record_peak_memory();
  summary_.steps = dyn.step_count() - std::max(summary_.restart_step, 0L);
  summary_.wall_seconds = wall_seconds;
  const int np = parallel::size(comm_);
  summary_.files = {np == 1 ? out.exodus_path()
                            : io::rank_file_name(out.exodus_path(), np, 0) + " ... (" + std::to_string(np) + " files)",
                    out.history_path()};
  summary_.physics = out.finish_physics();
  summary_.files.push_back(out.summary_path());
  summary_.checkpoint = last_checkpoint;
  if (!summary_.checkpoint.empty()) summary_.files.push_back(summary_.checkpoint);
  if (dyn.fracture()) {
    out.flush_crack_log();
    summary_.files.push_back(out.fragments_path());
    summary_.files.push_back(out.cracks_path());
  }
}

}  // namespace shellfrac::solver
