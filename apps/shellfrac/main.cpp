// shellfrac: DG / cohesive-zone simulation of shear-flexible shells (Talamini & Radovitzky, CMAME 2017).
//   shellfrac DECK.xml                     run the deck
//   shellfrac --check DECK.xml             validate the deck and build the mesh/partition; write nothing
//   shellfrac --quiet DECK.xml             run without progress lines
//   shellfrac --print-valid-parameters [F] documented XML skeleton of every parameter (stdout or file F)
//   shellfrac --help | --version
// Exit codes: 0 success, 1 input error (message names the file and parameter), 2 usage error,
// 3 numerical blow-up (one line) or internal error (all ranks aborted), 4 stopped by SIGTERM/SIGUSR2 (after a checkpoint;
// during the set-up: nothing written), 5 Static Relaxation not reached by End Time (results written), 6 a result
// file could not be written (named in the message).
#include <mpi.h>
#include <sys/stat.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "kokkos_options.hpp"
#include "shellfrac/core/application.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/core/memory_release.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/core/version.hpp"
#include "shellfrac/solver/setup/stop_signals.hpp"
#include "shellfrac/solver/simulation.hpp"
#include "shellfrac/solver/step/central_difference.hpp"

namespace {

const char* usage =
    "usage: shellfrac [options] DECK.xml\n"
    "Simulates deformation and fracture of shear-flexible shells (DG / cohesive zones).\n"
    "\n"
    "options:\n"
    "  --check                          validate the deck, build the mesh and partition, write nothing\n"
    "  --restart FILE                   continue from the checkpoint FILE (overrides Checkpoint->Restart From);\n"
    "                                   the mesh and the physics must be the checkpoint's\n"
    "  --allow-physics-change           with --restart: accept materials, loads, conditions etc. other than the\n"
    "                                   checkpoint's (the mesh must still be the same)\n"
    "  --quiet                          no progress lines during the run (Output->Progress Interval)\n"
    "  --print-valid-parameters [FILE]  write a documented XML deck with every parameter and its default\n"
    "  --help                           this text\n"
    "  --version                        version\n"
    "  --kokkos-threads=N, ...          Kokkos options (--kokkos-help lists them)\n"
    "\n"
    "Results go to the current directory unless the deck's Output sublist says otherwise:\n"
    "  <deck>.exo (np = 1) or the per-rank set <deck>.exo.<np>.<rank> (np > 1), and <deck>_history.csv.\n"
    "Run in parallel with: mpirun -np N shellfrac DECK.xml\n"
    "Input reference: docs/input_reference.xml (the output of --print-valid-parameters).\n"
    "Signals: SIGUSR1 writes a checkpoint and continues; SIGTERM or SIGUSR2 writes a checkpoint and the last\n"
    "results, then stops with exit code 4 (restart with --restart); during the set-up it stops at once, nothing\n"
    "written. Under mpirun send SIGUSR2 to mpirun (it kills the ranks 1 s after forwarding a SIGTERM).\n"
    "Exit codes: 0 done, 1 input error, 2 usage error, 3 numerical blow-up or internal error, 4 stopped by\n"
    "SIGTERM or SIGUSR2, 5 static equilibrium (Static Relaxation) not reached by End Time or the relaxation stalled,\n"
    "6 a result file could not be written (disk full?).\n";

/// The run's plan on rank 0: mesh, partition, time step, mass scaling, regions, then any warnings.
void print_summary(const shellfrac::solver::Simulation& sim, const std::string& deck) {
  const auto& s = sim.summary();
  std::cout << "shellfrac " << shellfrac::version << ": " << deck << " on " << shellfrac::parallel::size() << " rank(s)\n"
            << "  mesh: " << s.elements << " TRI6 elements, " << s.nodes << " nodes, " << s.edges << " edges ("
            << s.interfaces << " interfaces, " << s.boundary_edges << " boundary, " << s.non_manifold_edges
            << " non-manifold)\n"
            << "  partition: " << s.min_owned << ".." << s.max_owned << " elements and " << s.min_ghosts << ".."
            << s.max_ghosts << " ghosts per rank\n"
            << "  time step: " << s.dt << " (stable estimate " << s.stable_dt << ", docs/theory.md §8)\n";
  if (s.mass_scaling.elements > 0) {
    const auto& ms = s.mass_scaling;
    std::cout << "  mass scaling: " << ms.elements << " of " << s.elements << " elements scaled to reach the time "
              << "step; added mass " << ms.added_mass << " = " << 100 * ms.added_mass / ms.physical_mass << " % of "
              << ms.physical_mass << "; largest density factor " << ms.max_factor << " at element "
              << ms.max_element + 1 << " (centroid " << ms.max_centroid[0] << ", " << ms.max_centroid[1] << ", "
              << ms.max_centroid[2] << ")\n";
  }
  if (s.strengths.interfaces > 0) {
    const auto& st = s.strengths;
    std::cout << "  fracture: " << st.interfaces << " breakable interfaces, cohesive strength min " << st.min
              << ", mean " << st.mean << ", max " << st.max;
    if (st.scattered > 0) std::cout << " (" << st.scattered << " drawn with Fracture->Seed " << s.seed << ")";
    std::cout << "\n";
  }
  std::ostringstream setup;
  setup << std::fixed << std::setprecision(2) << "  set-up (slowest rank):";
  for (const auto& [phase, seconds] : sim.setup_seconds()) setup << " " << phase << " " << seconds << " s";
  std::cout << setup.str() << "\n";
  for (const auto& r : s.regions)
    std::cout << "  region '" << r.name << "': " << r.elements << " elements, " << r.nodes << " nodes, " << r.edges
              << " edges\n";
  for (const auto& w : sim.warnings()) std::cerr << "shellfrac: warning: " << w << "\n";
}

int run(int argc, char** argv) {
  const bool root = shellfrac::parallel::rank() == 0;
  std::vector<std::string> args(argv + 1, argv + argc);
  bool check = false, quiet = false, allow_physics_change = false;
  std::string deck, restart;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      if (root) std::cout << usage;
      return 0;
    } else if (a == "--version") {
      if (root) std::cout << "shellfrac " << shellfrac::version << "\n";
      return 0;
    } else if (a == "--print-valid-parameters") {
      if (!root) return 0;
      const auto valid = shellfrac::solver::Deck::valid_parameters();
      if (i + 1 < args.size()) {
        const std::string& file = args[i + 1];
        struct stat st {};
        if (::lstat(file.c_str(), &st) == 0) {  // a deck named after the option is never overwritten
          std::cerr << "shellfrac: error: --print-valid-parameters " << file << ": the file exists; this option "
                    << "writes a new file and never replaces one (name a file that does not exist, or omit it to "
                       "print to standard output)\n";
          return 2;
        }
        std::ostringstream text;
        shellfrac::params::write_documented_xml(text, *valid);
        shellfrac::files::OutputFile(file, shellfrac::files::OutputFile::Mode::create).write(text.str());
      } else {
        shellfrac::params::write_documented_xml(std::cout, *valid);
      }
      return 0;
    } else if (a == "--check") {
      check = true;
    } else if (a == "--quiet") {
      quiet = true;
    } else if (a == "--allow-physics-change") {
      allow_physics_change = true;
    } else if (a == "--restart") {
      if (i + 1 >= args.size()) {
        if (root) std::cerr << "shellfrac: error: --restart needs a checkpoint file\n\n" << usage;
        return 2;
      }
      restart = args[++i];
      if (restart.empty()) {
        if (root) std::cerr << "shellfrac: error: --restart was given an empty file name\n\n" << usage;
        return 2;
      }
    } else if (!a.empty() && a[0] == '-') {
      if (root) std::cerr << "shellfrac: error: unknown option '" << a << "'\n\n" << usage;
      return 2;
    } else if (deck.empty()) {
      deck = a;
    } else {
      if (root) std::cerr << "shellfrac: error: more than one deck given ('" << deck << "', '" << a << "')\n";
      return 2;
    }
  }
  if (deck.empty()) {
    if (root) std::cerr << "shellfrac: error: no input deck given\n\n" << usage;
    return 2;
  }
  std::unique_ptr<shellfrac::solver::Simulation> setup;
  try {
    setup = std::make_unique<shellfrac::solver::Simulation>(deck, MPI_COMM_WORLD, restart, allow_physics_change);
  } catch (const shellfrac::solver::StoppedDuringSetUp& e) {  // on every rank at once
    if (root) std::cout << "shellfrac: " << e.what() << std::endl;
    return 4;
  }
  shellfrac::solver::Simulation& sim = *setup;
  if (quiet) sim.set_quiet();
  if (root) print_summary(sim, deck);
  if (check) {
    if (root) std::cout << "  deck and mesh are valid (--check: nothing written)\n";
    return 0;
  }
  const auto out = sim.run();
  if (root) {
    if (out.steps > 0)
      std::cout << "  " << out.steps << " steps in " << out.wall_seconds << " s ("
                << 1e6 * out.wall_seconds / (double(out.steps) * double(out.elements)) << " us per element-step on "
                << shellfrac::parallel::size() << " rank(s))\n";
    std::cout << "  peak resident memory: " << out.peak_memory_max / (1024.0 * 1024 * 1024) << " GiB on rank "
              << out.peak_memory_rank << " (the largest), " << out.peak_memory_sum / 1024.0 / double(out.elements)
              << " kB per element over all ranks\n";
    std::cout << out.physics.text();
    for (const auto& f : out.files) std::cout << "  wrote " << f << "\n";
    if (out.stopped_by_signal)
      std::cout << "  stopped by " << out.stop_signal << " at step " << std::max(out.restart_step, 0L) + out.steps << "; continue with --restart "
                << out.checkpoint << "\n";
    const long run_steps = std::max(out.restart_step, 0L) + out.steps;  // the run's, across restarts
    const shellfrac::solver::CentralDifference::Relaxation relaxation;   // its stopping test's constants
    if (out.relaxed && out.at_floor)
      std::cout << "  static equilibrium reached after " << run_steps << " steps at the residual's round-off floor: "
                << "the relative residual stopped falling at " << out.best_residual << " (above 'Relaxation "
                << "Tolerance': the load is small against the stiffness) while the displacement changed by "
                << out.displacement_change << " of itself over " << relaxation.stall_peaks
                << " kinetic-energy peaks\n";
    else if (out.relaxed)
      std::cout << "  static equilibrium reached after " << run_steps << " steps: relative residual "
                << out.residual << "\n";
    else if (out.stalled)
      std::cerr << "shellfrac: warning: the static relaxation stalled at step " << run_steps
                << ": its relative residual has not fallen below " << relaxation.stall_drop
                << " of its smallest value " << out.best_residual << " over " << relaxation.stall_peaks
                << " kinetic-energy peaks while the displacement still changed by "
                << out.displacement_change << " of itself (no equilibrium: a mechanism, an instability, or a "
                << "tolerance below what the motion can settle to); the results are written; exit code 5\n";
    else if (out.static_relaxation && !out.stopped_by_signal)
      std::cerr << "shellfrac: warning: the static equilibrium was not reached by End Time (relative residual "
                << out.residual << " above 'Relaxation Tolerance'); the results are written; exit code 5\n";
  }
  if (out.stopped_by_signal) return 4;
  return out.static_relaxation && !out.relaxed ? 5 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  shellfrac::release_freed_memory_promptly();  // before the set-up allocates anything large
  shellfrac::solver::catch_stop_signals();  // before MPI and the set-up: a batch system's signal is never lost
  // A file beyond the size limit (ulimit -f, a batch system's file-size limit) fails its write (EFBIG), which is
  // reported naming the file with exit code 6, on every rank at once, instead of a kill by SIGXFSZ on one rank.
  std::signal(SIGXFSZ, SIG_IGN);
  // MPI first, so that only rank 0 reports a bad Kokkos option; Kokkos reads them in the ScopeGuard.
  MPI_Init(&argc, &argv);
  int code = 2;
  if (const auto bad = shellfrac::app::kokkos_option_error({argv + 1, argv + argc}); !bad.empty()) {
    if (shellfrac::parallel::rank() == 0) std::cerr << "shellfrac: error: " << bad << "\n\n" << usage;
  } else if (std::any_of(argv + 1, argv + argc, [](const char* a) { return !std::strcmp(a, "--help") || !std::strcmp(a, "-h"); })) {
    // shellfrac's own usage first, then Kokkos' options under a heading (Kokkos would print its own first).
    const bool root = shellfrac::parallel::rank() == 0;
    if (root) std::cout << usage << "\nKokkos options (shellfrac accepts them too):\n" << std::flush;
    char kokkos_help[] = "--kokkos-help";
    char* help_argv[] = {argv[0], kokkos_help, nullptr};
    int help_argc = root ? 2 : 1;
    char** help_args = help_argv;
    Tpetra::ScopeGuard scope(&help_argc, &help_args);
    code = 0;
  } else {
    Tpetra::ScopeGuard scope(&argc, &argv);
    code = shellfrac::run_guarded("shellfrac", [&] { return run(argc, argv); });
  }
  MPI_Finalize();
  return code;
}
