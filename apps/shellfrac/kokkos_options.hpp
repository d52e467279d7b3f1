#pragma once
/// \file kokkos_options.hpp
/// The command-line options that Kokkos reads when the run starts (--kokkos-threads=N and the like). Kokkos
/// converts their values without checking them and aborts on a malformed one, so shellfrac checks them first
/// and answers with a usage error (exit code 2).
#include <string>
#include <vector>

namespace shellfrac::app {

/// The usage error for the first malformed or unknown Kokkos option in `args` (the arguments after the program
/// name), or an empty string if there is none. Integer options need a whole number >= 0 ("--kokkos-threads=4"),
/// --kokkos-num-devices one or two ("=2" or "=2,1"), the tool options a value, the switches none. Kokkos' older
/// spellings without the prefix (--threads=N, --numa=N, --device=N, --device-id=N, --num-devices=N,
/// --ndevices=N) are not shellfrac options and are refused as unknown.
std::string kokkos_option_error(const std::vector<std::string>& args);

}  // namespace shellfrac::app
