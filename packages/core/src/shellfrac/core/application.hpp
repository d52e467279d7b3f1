#pragma once
/// \file application.hpp
/// The exit-code contract of shellfrac's MPI executables, in one place:
///   0 success; 1 input error (InputError: printed once, by rank 0, as "<name>: error: <message>");
///   3 internal error (printed by the failing rank, then MPI_Abort so that no rank hangs).
/// Usage errors (exit 2) are the body's own business.
#include <functional>

namespace shellfrac {

/// Runs body() under the contract above; MPI must be initialised. Returns the exit code.
int run_guarded(const char* program_name, const std::function<int()>& body);

}  // namespace shellfrac
