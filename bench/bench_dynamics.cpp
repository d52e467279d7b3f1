// shellfrac_bench: time the explicit DG shell dynamics of a deck (default: the paper's §6.4 cantilever,
// 200 x 40 cells, 16 000 elements) and print microseconds per element-step by phase. Not a test.
//   shellfrac_bench [DECK.xml] [--steps N] [--warmup W]
// The model is built exactly as a shellfrac run builds it (deck -> mesh -> edge topology -> partition ->
// distributed mesh -> ShellDynamics); nothing is written. W warm-up steps (default 5) are taken first and
// not timed, then N steps (default 100) are timed. Every "us_per_element_step" value is
//   max over ranks (seconds on the rank) * 1e6 / (global elements * N),
// so ideal parallel speed-up lowers it. The last line is total_us_per_element_step=<value>, the wall time
// of the N steps; threads=<T> is the Kokkos execution space's concurrency on each rank; heap_allocations_per_step
// counts the C++ heap allocations of the timed steps (allocation_counter.hpp; max over ranks). Exit codes as
// shellfrac: 0 success, 1 input error, 2 usage error, 3 internal error.
#include <mpi.h>

#include <Kokkos_Core.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "shellfrac/core/application.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/memory_release.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/dynamics/shell_dynamics.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

namespace {

const char* usage =
    "usage: shellfrac_bench [DECK.xml] [--steps N] [--warmup W]\n"
    "Times N explicit steps (default 100, after W = 5 untimed warm-up steps) of the deck's model\n"
    "(default " SHELLFRAC_SOURCE_DIR "/xml/cantilever_200x40.xml) and prints microseconds per\n"
    "element-step by phase (max over ranks) and bytes of state per element. Writes no files.\n"
    "Run in parallel with: mpiexec -np N shellfrac_bench\n";

/// Parses a non-negative integer option value; false if it is not one.
bool parse_count(const std::string& s, long& out) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos || s.size() > 9) return false;
  out = std::strtol(s.c_str(), nullptr, 10);
  return true;
}

int run(int argc, char** argv) {
  using namespace shellfrac;
  MPI_Comm comm = MPI_COMM_WORLD;
  const bool root = parallel::rank(comm) == 0;
  const int np = parallel::size(comm);
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string deck_file;
  long steps = 100, warmup = 5;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      if (root) std::cout << usage;
      return 0;
    } else if (a == "--steps" || a == "--warmup") {
      long value = 0;
      if (i + 1 >= args.size() || !parse_count(args[i + 1], value) || (a == "--steps" && value == 0)) {
        if (root)
          std::cerr << "shellfrac_bench: error: " << a << " needs a " << (a == "--steps" ? "positive" : "non-negative")
                    << " integer\n\n"
                    << usage;
        return 2;
      }
      (a == "--steps" ? steps : warmup) = value;
      ++i;
    } else if (!a.empty() && a[0] == '-') {
      if (root) std::cerr << "shellfrac_bench: error: unknown option '" << a << "'\n\n" << usage;
      return 2;
    } else if (deck_file.empty()) {
      deck_file = a;
    } else {
      if (root) std::cerr << "shellfrac_bench: error: more than one deck given ('" << deck_file << "', '" << a << "')\n";
      return 2;
    }
  }
  if (deck_file.empty()) deck_file = std::string(SHELLFRAC_SOURCE_DIR) + "/xml/cantilever_200x40.xml";

  // The model of a shellfrac run, built as the run builds it.
  const auto deck = solver::Deck::read(deck_file, comm);
  const auto model = solver::build_run_model(deck, comm);
  const auto& dmesh = *model.distributed;
  auto& dyn = *model.dynamics;

  for (long s = 0; s < warmup; ++s) dyn.step();
  const solver::PhaseTimes before = dyn.phase_times();
  MPI_Barrier(comm);
  const long long allocations_before = heap_allocations();
  const auto start = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; ++s) dyn.step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double allocations = double(heap_allocations() - allocations_before);
  const solver::PhaseTimes& after = dyn.phase_times();

  const double element_steps = double(dmesh.num_global_elements()) * double(steps);
  auto per_element_step = [&](double local_seconds) {
    return parallel::max(local_seconds, comm) * 1e6 / element_steps;  // collective
  };
  const double element = per_element_step(after.element - before.element);
  const double interface = per_element_step(after.interface - before.interface);
  const double gather = per_element_step(after.gather - before.gather);
  const double exchange = per_element_step(after.exchange - before.exchange);
  const double update = per_element_step(after.update - before.update);
  const double nucleation = per_element_step(after.nucleation - before.nucleation);
  const double contact = per_element_step(after.contact - before.contact);
  const double total = per_element_step(wall);
  const double bytes = parallel::max(dyn.bytes_per_element(), comm);
  const double allocations_per_step = parallel::max(allocations, comm) / double(steps);
  const int threads = Kokkos::DefaultExecutionSpace().concurrency();
  const auto peaks = parallel::peak_resident_bytes(comm);
  double peak_sum = 0;
  for (const double p : peaks) peak_sum += p;
  if (root) {
    std::cout << "shellfrac_bench: " << deck_file << ", " << dmesh.num_global_elements() << " elements, " << np
              << " rank(s) x " << threads << " thread(s), " << steps << " steps (after " << warmup
              << " warm-up), dt = " << dyn.time_step() << "\n"
              << "threads=" << threads << "\n"
              << "element_kernel_us_per_element_step=" << element << "\n"
              << "interface_kernel_us_per_element_step=" << interface << "\n"
              << "gather_us_per_element_step=" << gather << "\n"
              << "communication_us_per_element_step=" << exchange << "\n"
              << "update_us_per_element_step=" << update << "\n"
              << "nucleation_check_us_per_element_step=" << nucleation << " (part of update)\n"
              << "shell_contact_us_per_element_step=" << contact << " (part of update)\n"
              << "bytes_per_element=" << bytes << "\n"
              << "heap_allocations_per_step=" << allocations_per_step << " (operator new, max over ranks)\n"
              << "peak_resident_bytes_max=" << *std::max_element(peaks.begin(), peaks.end()) << "\n"
              << "peak_resident_bytes_per_element=" << peak_sum / double(dmesh.num_global_elements()) << "\n"
              << "total_us_per_element_step=" << total << std::endl;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  shellfrac::release_freed_memory_promptly();  // as the shellfrac executable does
  Tpetra::ScopeGuard scope(&argc, &argv);
  return shellfrac::run_guarded("shellfrac_bench", [&] { return run(argc, argv); });
}
