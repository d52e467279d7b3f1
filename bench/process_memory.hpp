#pragma once
/// \file process_memory.hpp
/// The benchmarks' view of their own memory: fields of /proc/self/status, and a reset of the peak (Linux).
#include <fstream>
#include <string>

namespace shellfrac::bench {

/// A /proc/self/status field ("VmRSS:", "VmHWM:") [bytes].
inline double status_bytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field, 0) == 0) return 1024.0 * std::stod(line.substr(std::string(field).size()));
  return 0.0;
}

/// Resets the peak resident size (VmHWM) to the current one; returns the current one.
inline double reset_peak() {
  std::ofstream("/proc/self/clear_refs") << "5";
  return status_bytes("VmRSS:");
}

}  // namespace shellfrac::bench
