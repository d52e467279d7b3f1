#include "shellfrac/core/application.hpp"

#include <mpi.h>

#include <cstdio>
#include <exception>
#include <iostream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac {

int run_guarded(const char* program_name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    // Input errors are detected collectively: every rank has the same message and exits normally.
    if (parallel::rank() == 0) std::cerr << program_name << ": error: " << e.what() << "\n";
    return 1;
  } catch (const OutputError& e) {
    // Output errors are agreed by all ranks too (the writer checks every write).
    if (parallel::rank() == 0) std::cerr << program_name << ": error: " << e.what() << "\n";
    return 6;
  } catch (const NumericalError& e) {
    // A blow-up is found by a reduction over all ranks and thrown on every rank: the physics, not a bug.
    if (parallel::rank() == 0) std::cerr << program_name << ": error: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << program_name << ": internal error on rank " << parallel::rank() << ": " << e.what() << "\n";
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 3);
    return 3;
  }
}

}  // namespace shellfrac
