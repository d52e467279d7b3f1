/// \file fuzz_deck.cpp
/// libFuzzer target: the XML input deck through solver::Deck::read, exactly as `shellfrac` reads it:
/// params::read_deck (Teuchos XML, read on rank 0 and broadcast), then the validation of every sublist by its
/// owner's from_parameters() (params::validate + conversion). The mesh itself is not read (that is fuzz_gmsh /
/// fuzz_exodus). Seeds: tests/fuzz_corpus/deck/.
/// MPI is initialised once (1 rank) in LLVMFuzzerInitialize; Kokkos is not needed to read a deck.
/// Build and run (docs/hostile_input.md):
///   cmake --build build-fuzz --target fuzz_deck
///   build-fuzz/fuzz/fuzz_deck -max_total_time=600 -rss_limit_mb=4096 /tmp/corpus_deck tests/fuzz_corpus/deck
/// Expected outcome of every input: a validated deck, or a shellfrac::InputError naming the file
/// (fuzz_common.hpp).

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_common.hpp"
#include "shellfrac/solver/simulation.hpp"

/// Open MPI's start-up allocations that it never frees (reported by LeakSanitizer at exit; not ours). Only
/// stacks through Open MPI and its helpers are suppressed (vasprintf: called from an MPI plugin).
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libmpi.so\nleak:libopen-pal.so\nleak:libopen-rte.so\nleak:libhwloc.so\nleak:libpmix.so\n"
         "leak:libevent\nleak:/openmpi/lib/\nleak:__vasprintf_internal\n";
}

/// No leak check at exit: Open MPI unloads the plugins it does not select during MPI_Init, and what they leaked
/// cannot be matched to a library any more. libFuzzer's own leak check after each input (an input whose run
/// allocates more than it frees) is unaffected.
extern "C" const char* __asan_default_options() { return "leak_check_at_exit=0"; }

/// MPI stays initialised until the process exits (MPI_Finalize would unload every plugin, see above).
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) MPI_Init(argc, argv);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = shellfrac::fuzz::write_input("deck.xml", data, size);
  shellfrac::fuzz::run_reader(path, [](const std::string& p) { shellfrac::solver::Deck::read(p, MPI_COMM_WORLD); });
  return 0;
}
