// Checkpoint/restart (issue #6), each check with its reference:
//  * ContinuesBitwiseThroughCrackActivation: a strip with one cohesive edge (the §5.2 problem of
//    test_fracture) is run to 14 us continuously, and to 10.5 us (after the edge activated at ~9.99 us, before
//    it separates at ~11.0 us) with a checkpoint, then restarted to 14 us: the resumed history file and the
//    final nodal and element fields must equal the continuous run's bitwise.
//  * On 3 ranks also across rank counts: written on 3 ranks and restarted on 2, written on 1 and restarted on 3;
//    on 4 ranks written on 4 (every rank writing its rows of the file) and restarted on 3 and on 1.
//  * ExactOutputTimesLandOnEveryFrameAndEndTime: with Exact Output Times and an Output Interval I = 2^-18 s (so
//    that its multiples are exact in binary), every frame is at k I exactly and the last at End Time (14 us, not a
//    multiple), though the time step divides neither; a run split at 3 I (an output time, where both runs land)
//    continues bitwise as above.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <functional>
#include <vector>
#include <sstream>
#include <string>
#include <utility>

#include "cracked_strip.hpp"
#include "deck_test_util.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/io/results_reader.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"
#include "shellfrac/solver/simulation.hpp"

using namespace shellfrac;
using namespace shellfrac::test;

namespace {

constexpr double h = strip_h;

/// The output settings of a run.
struct Frames {
  double interval = 3.5e-6;
  bool exact = false;  ///< Exact Output Times
  int history = 5;     ///< History Interval (a split run also writes a row at its last step)
  bool ball = false;   ///< a free rigid sphere strikes the strip at x = L/2 from 5 us on (theory.md §12.4)
};

/// The strip's deck (cracked_strip.hpp, mesh in the parent directory) run to `end_time` with checkpointing (Step
/// Interval 100 000), plasticity with shear yield (gam^p is state too) and the breakable edge; probe x_max.
Teuchos::RCP<Teuchos::ParameterList> strip_deck(const std::string& dir, double end_time, Frames frames = {}) {
  auto deck = pulled_strip_deck(dir, "../strip_mesh.exo", {h, 2693, 68.9e9, 0.0});
  auto& time = deck->sublist("Time Integration");
  time.set("End Time", end_time), time.set("History Interval", frames.history);
  time.set("Output Interval", frames.interval);
  time.set("Exact Output Times", frames.exact);
  deck->sublist("Checkpoint").set("Step Interval", 100000);
  auto& material = shell_material(*deck);
  material.set("Model", std::string("Resultant Plasticity")), material.set("Yield Stress", 280e6);
  material.set("Hardening Modulus", 20e9), material.set("Shear Yield", true);
  material.set("Cohesive Strength", 375e6), material.set("Fracture Energy", 10e3);
  set_probes(*deck, {"x_max"});
  if (frames.ball) {  // radius 5 mm, 1 g (3.7 times the strip), 50 m/s down; 0.25 mm above the strip's upper face
    auto& ball = deck->sublist("Contact").sublist("Rigid Bodies").sublist("ball");
    ball.set("Radius", 5e-3), ball.set("Mass", 1e-3), ball.set("Velocity", vec3(0, 0, -50));
    ball.set("Point", vec3(strip_L / 2, strip_b / 2, h / 2 + 0.25e-3 + 5e-3));
  }
  return deck;
}

/// Runs the strip to 14 us in `dir` on `comm` without a break (the reference).
void continuous(const std::string& dir, MPI_Comm comm, Frames frames = {}) {
  write_deck(dir + "/run.xml", *strip_deck(dir, 14e-6, frames), comm);
  solver::Simulation(dir + "/run.xml", comm).run();
}

/// The checkpoint of the first part of a broken run (the only run_checkpoint_step<N>.h5 in `dir`).
std::string checkpoint_in(const std::string& dir) {
  std::string found;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename();
    if (f.rfind("run_checkpoint_step", 0) == 0 && f.size() > 3 && f.substr(f.size() - 3) == ".h5") {
      EXPECT_TRUE(found.empty()) << "two checkpoints in " << dir;
      found = dir + "/" + f;
    }
  }
  EXPECT_FALSE(found.empty()) << "no checkpoint in " << dir;
  return found;
}

/// Runs to `split` (10.5 us) on `first`, then restarts the same deck to 14 us on `second` (either may be
/// MPI_COMM_NULL on ranks outside it). Collective over MPI_COMM_WORLD.
void broken_run(const std::string& dir, MPI_Comm first, MPI_Comm second, Frames frames = {}, double split = 10.5e-6) {
  write_deck(dir + "/run.xml", *strip_deck(dir, split, frames));
  if (first != MPI_COMM_NULL) {
    const auto s = solver::Simulation(dir + "/run.xml", first).run();
    EXPECT_EQ(s.restart_step, -1);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  write_deck(dir + "/run.xml", *strip_deck(dir, 14e-6, frames));
  if (second != MPI_COMM_NULL) {
    solver::Simulation sim(dir + "/run.xml", second, checkpoint_in(dir));
    EXPECT_GT(sim.summary().restart_step, 0);
    sim.run();
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

/// The broken run's history equals the continuous one's, and its last Exodus frame equals the continuous
/// run's last frame (nodal values, and element values except `rank`), bitwise.
void expect_same(const std::string& reference, const std::string& broken, const std::string& what) {
  if (parallel::rank() != 0) return;
  EXPECT_EQ(slurp(reference + "/run_history.csv"), slurp(broken + "/run_history.csv")) << what;
  EXPECT_EQ(slurp(reference + "/run_cracks.csv"), slurp(broken + "/run_cracks.csv")) << what << " (crack log)";
  EXPECT_NE(slurp(reference + "/run_cracks.csv").find('\n'), std::string::npos);
  // The results (a file, or the base of a per-rank set <name>.<np>.<rank>) whose name begins with `stem`.
  const auto find_results = [](const std::string& dir, const std::string& stem) {
    const std::regex rank_file(R"((.*)\.[0-9]+\.[0-9]+)");
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      std::string f = e.path().filename();
      if (f.rfind(stem, 0) != 0) continue;
      std::smatch m;
      if (std::regex_match(f, m, rank_file)) f = m[1];
      return dir + "/" + f;
    }
    return std::string();
  };
  const auto rc = io::read_results(find_results(reference, "run.exo"));
  const auto rb = io::read_results(find_results(broken, "run.exo-s."));
  ASSERT_FALSE(rc.times.empty());
  ASSERT_FALSE(rb.times.empty());
  EXPECT_EQ(rc.times.back(), rb.times.back()) << what;
  EXPECT_EQ(rc.nodal.back(), rb.nodal.back()) << what;
  ASSERT_EQ(rc.element_names, rb.element_names);
  for (std::size_t k = 0; k < rc.element_names.size(); ++k)
    if (rc.element_names[k] != "rank") {
      EXPECT_EQ(rc.element.back()[k], rb.element.back()[k]) << rc.element_names[k] << ", " << what;
    }
}

std::string fresh(const std::string& dir) {
  if (parallel::rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

/// The communicator of the first n ranks of MPI_COMM_WORLD (MPI_COMM_NULL on the others), freed with it.
class FirstRanks {
 public:
  explicit FirstRanks(int n) {
    MPI_Comm_split(MPI_COMM_WORLD, parallel::rank() < n ? 0 : MPI_UNDEFINED, parallel::rank(), &comm_);
  }
  ~FirstRanks() {
    if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
  }
  FirstRanks(const FirstRanks&) = delete;
  FirstRanks& operator=(const FirstRanks&) = delete;
  MPI_Comm comm() const { return comm_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
};

/// The rank counts (written on, restarted on) a test at this many ranks restarts across.
std::vector<std::pair<int, int>> rank_changes() {
  switch (parallel::size()) {
    case 3: return {{3, 2}, {1, 3}};
    case 4: return {{4, 3}, {4, 1}};
    default: return {};
  }
}

/// A run broken on `written` ranks and restarted on `restarted`, in root/<written>_to_<restarted>, equals the
/// reference run.
void expect_same_across(const std::string& root, const std::string& ref, int written, int restarted,
                        const Frames& frames, const std::string& what) {
  const FirstRanks first(written), second(restarted);
  const auto dir = fresh(root + "/" + std::to_string(written) + "_to_" + std::to_string(restarted));
  broken_run(dir, first.comm(), second.comm(), frames);
  expect_same(ref, dir,
              "written on " + std::to_string(written) + " ranks, restarted on " + std::to_string(restarted) + what);
}

}  // namespace

TEST(Restart, ContinuesBitwiseThroughCrackActivation) {
  const auto root = work_dir("restart");
  if (parallel::rank() == 0) write_cracked_strip(root + "/strip_mesh.exo");
  const auto ref = fresh(root + "/continuous"), same = fresh(root + "/same_ranks");
  continuous(ref, MPI_COMM_WORLD);
  broken_run(same, MPI_COMM_WORLD, MPI_COMM_WORLD);
  expect_same(ref, same, "restart on the same rank count");
  std::vector<std::string> hd;
  const auto rows = read_history(same + "/run_history.csv", hd);
  if (parallel::rank() == 0) {  // the restart point lies between activation and separation
    double t_act = 0;
    for (const auto& r : rows)
      if (t_act == 0 && r[column(hd, "num_cohesive_edges")] > 0) t_act = r[column(hd, "time")];
    EXPECT_GT(t_act, 0.0);
    EXPECT_LT(t_act, 10.5e-6);
    EXPECT_EQ(rows.back()[column(hd, "num_separated_edges")], 1.0);
  }
  for (const auto& [written, restarted] : rank_changes()) expect_same_across(root, ref, written, restarted, {}, "");
}

// A free rigid body's motion is state: the ball of Frames::ball is in contact with the strip from about 5 us, so
// the split at 10.5 us falls during the contact; the restarted run's history (the ball's position, velocity and
// force columns included) and last frame equal the continuous run's bitwise, also from 3 ranks to 2.
TEST(Restart, ContinuesBitwiseWithAFreeRigidBodyInContact) {
  const auto root = work_dir("restart_ball");
  if (parallel::rank() == 0) write_cracked_strip(root + "/strip_mesh.exo");
  Frames frames;
  frames.ball = true;
  const auto ref = fresh(root + "/continuous"), same = fresh(root + "/same_ranks");
  continuous(ref, MPI_COMM_WORLD, frames);
  broken_run(same, MPI_COMM_WORLD, MPI_COMM_WORLD, frames);
  expect_same(ref, same, "restart on the same rank count, ball in contact");
  std::vector<std::string> hd;
  const auto rows = read_history(ref + "/run_history.csv", hd);
  if (parallel::rank() == 0) {  // the ball touched before the split and was still pushing after it
    double first = 0, last = 0;
    for (const auto& r : rows)
      if (r[column(hd, "ball_force_z")] > 0) last = r[column(hd, "time")], first = first > 0 ? first : last;
    EXPECT_GT(first, 0.0);
    EXPECT_LT(first, 10.5e-6);
    EXPECT_GT(last, 10.5e-6);
  }
  if (parallel::size() == 3) expect_same_across(root, ref, 3, 2, frames, ", ball in contact");
}

TEST(Restart, ExactOutputTimesLandOnEveryFrameAndEndTime) {
  const auto root = work_dir("exact_output_times");
  if (parallel::rank() == 0) write_cracked_strip(root + "/strip_mesh.exo");
  const Frames frames{std::ldexp(1.0, -18), true, 1};  // I = 3.814697265625e-06 s: k I is exact in binary
  const auto ref = fresh(root + "/continuous"), split = fresh(root + "/split");
  continuous(ref, MPI_COMM_WORLD, frames);
  if (parallel::rank() == 0) {
    const auto r = io::read_results(ref + "/run.exo");  // one file, or the per-rank set
    ASSERT_EQ(r.times.size(), 5u);  // 0, I, 2I, 3I, End Time
    for (int k = 0; k < 4; ++k) EXPECT_EQ(r.times[std::size_t(k)], k * frames.interval) << "frame " << k;
    EXPECT_EQ(r.times.back(), 14e-6);
  }
  broken_run(split, MPI_COMM_WORLD, MPI_COMM_WORLD, frames, 3 * frames.interval);
  expect_same(ref, split, "Exact Output Times, split at an output time");
}


// A checkpoint whose checksum is valid but whose contents no run can have written (forged or written by another
// program) used to restart with exit 0: a negative or absurd step or time, a NaN, a zero director, a mode 7. Each
// is written with a valid checksum (io::write_checkpoint) and refused by the restart, naming the file and the value.
TEST(Restart, RefusesCheckpointValuesNoRunCanHaveWritten) {
  const auto root = work_dir("forged_checkpoints");
  if (parallel::rank() == 0) write_cracked_strip(root + "/strip_mesh.exo");
  const auto dir = fresh(root + "/run");
  write_deck(dir + "/run.xml", *strip_deck(dir, 10.5e-6));
  solver::Simulation(dir + "/run.xml", MPI_COMM_WORLD).run();
  const std::string good = checkpoint_in(dir);
  write_deck(dir + "/run.xml", *strip_deck(dir, 14e-6));
  const io::CheckpointData original = io::read_checkpoint(good, MPI_COMM_WORLD);
  const auto set_value = [](io::CheckpointData& d, const std::string& table, std::size_t index, double v) {
    ASSERT_TRUE(d.tables.count(table)) << table;
    ASSERT_LT(index, d.tables.at(table).values.size()) << table;
    d.tables.at(table).values[index] = v;
  };
  struct Forgery {
    std::string what, message;
    std::function<void(io::CheckpointData&)> change;
  };
  const std::vector<Forgery> forgeries = {
      {"negative step", "the checkpoint's step -3 is not a whole number >= 0",
       [](io::CheckpointData& d) { d.scalars["step"] = -3; }},
      {"absurd step", "the checkpoint's step 1e+300 is not a whole number >= 0",
       [](io::CheckpointData& d) { d.scalars["step"] = 1e300; }},
      {"time NaN", "the checkpoint's time nan at step",
       [](io::CheckpointData& d) { d.scalars["time"] = std::nan(""); }},
      {"negative time", "the checkpoint's time -1 at step", [](io::CheckpointData& d) { d.scalars["time"] = -1; }},
      {"velocity NaN", "its table 'element v' holds nan for element",
       [&](io::CheckpointData& d) { set_value(d, "element v", 4, std::nan("")); }},
      {"zero director", "its director 1 of element 1 has the length 0, not 1",
       [&](io::CheckpointData& d) {
         for (int c = 0; c < 3; ++c) set_value(d, "element t", std::size_t(c), 0.0);
       }},
      {"mode 7", "its table 'interface mode' holds the mode 7 for interface",
       [&](io::CheckpointData& d) { set_value(d, "interface mode", 0, 7.0); }},
  };
  for (const auto& f : forgeries) {
    io::CheckpointData forged = original;
    f.change(forged);
    const std::string file = dir + "/forged.h5";
    io::write_checkpoint(file, forged, MPI_COMM_WORLD);  // a valid checksum over the forged contents
    try {
      solver::Simulation sim(dir + "/run.xml", MPI_COMM_WORLD, file);
      ADD_FAILURE() << f.what << ": restarted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file + ": "), std::string::npos) << f.what << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find(f.message), std::string::npos) << f.what << ": " << e.what();
    }
  }
}

// A checkpoint written before a parameter existed does not record it. Such a parameter at its default is the same
// physics, so the restart goes on: here the lines of the Contact sublist and of a material's Weibull Modulus are
// taken out of the checkpoint's fingerprint, as a version without them wrote it. A non-default value of such a
// parameter, or a whole new entry of a user-named list (a rigid wall), is still refused.
TEST(Restart, AcceptsParametersAddedSinceAtTheirDefaultsOnly) {
  const auto root = work_dir("older_checkpoint");
  if (parallel::rank() == 0) write_cracked_strip(root + "/strip_mesh.exo");
  const auto dir = fresh(root + "/run");
  write_deck(dir + "/run.xml", *strip_deck(dir, 10.5e-6));
  solver::Simulation(dir + "/run.xml", MPI_COMM_WORLD).run();
  io::CheckpointData older = io::read_checkpoint(checkpoint_in(dir), MPI_COMM_WORLD);
  std::string kept, removed;
  std::istringstream lines(older.strings.at("fingerprint physics"));
  for (std::string line; std::getline(lines, line);)
    (line.rfind("Contact->", 0) == 0 || line.find("->Weibull Modulus = ") != std::string::npos ? removed : kept) +=
        line + "\n";
  ASSERT_NE(removed.find("Contact->Penalty Scale = 0.25"), std::string::npos) << removed;
  ASSERT_NE(removed.find("->Weibull Modulus = "), std::string::npos) << removed;
  older.strings["fingerprint physics"] = kept;
  const std::string file = dir + "/older.h5";
  io::write_checkpoint(file, older, MPI_COMM_WORLD);
  const auto restart_error = [&](const Teuchos::RCP<Teuchos::ParameterList>& deck) -> std::string {
    write_deck(dir + "/run.xml", *deck);
    try {
      solver::Simulation sim(dir + "/run.xml", MPI_COMM_WORLD, file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(restart_error(strip_deck(dir, 14e-6)), "");
  auto scaled = strip_deck(dir, 14e-6);
  scaled->sublist("Contact").set("Penalty Scale", 0.5);
  EXPECT_NE(restart_error(scaled).find("'Contact->Penalty Scale' = 0.5 is new"), std::string::npos);
  auto walled = strip_deck(dir, 14e-6);
  walled->sublist("Contact").sublist("Rigid Walls").sublist("floor").set("Point", vec3(0, 0, -1));
  EXPECT_NE(restart_error(walled).find("'Contact->Rigid Walls->floor->Normal' = {0, 0, 1} is new"), std::string::npos)
      << restart_error(walled);
}
