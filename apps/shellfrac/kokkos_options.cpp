#include "kokkos_options.hpp"

#include <algorithm>
#include <cctype>
#include <climits>

namespace shellfrac::app {

namespace {

/// True if `text` is a whole number in [0, INT_MAX] written with digits only.
bool is_count(const std::string& text) {
  if (text.empty() || text.size() > 10 ||
      !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
    return false;
  return std::stoll(text) <= INT_MAX;
}

/// The problem with the value of the Kokkos option `name` (given with '=' if has_value), or "" if it is fine;
/// "unknown" if `name` is not a Kokkos option.
std::string value_problem(const std::string& name, bool has_value, const std::string& value) {
  for (const char* n : {"--kokkos-threads", "--kokkos-numa", "--kokkos-device-id"})
    if (name == n) return has_value && is_count(value) ? "" : "needs a whole number >= 0 (" + name + "=N)";
  if (name == "--kokkos-num-devices" || name == "--kokkos-ndevices") {
    const auto comma = value.find(',');
    const bool ok = comma == std::string::npos ? is_count(value)
                                               : is_count(value.substr(0, comma)) && is_count(value.substr(comma + 1));
    return has_value && ok ? "" : "needs one or two whole numbers >= 0 (" + name + "=N or " + name + "=N,M)";
  }
  for (const char* n : {"--kokkos-tools-library", "--kokkos-tools-args"})
    if (name == n) return has_value ? "" : "needs a value (" + name + "=...)";
  for (const char* n : {"--kokkos-disable-warnings", "--kokkos-tune-internals", "--kokkos-help", "--kokkos-tools-help"})
    if (name == n) return has_value ? "takes no value" : "";
  return "unknown";
}

}  // namespace

std::string kokkos_option_error(const std::vector<std::string>& args) {
  for (const std::string& a : args) {
    const auto eq = a.find('=');
    const std::string name = a.substr(0, eq);
    for (const char* old : {"--threads", "--numa", "--device", "--device-id", "--num-devices", "--ndevices"})
      if (name == old) return "unknown option '" + a + "'";
    if (name.rfind("--kokkos-", 0) != 0) continue;
    const std::string problem =
        value_problem(name, eq != std::string::npos, eq == std::string::npos ? "" : a.substr(eq + 1));
    if (problem == "unknown") return "unknown option '" + a + "'";
    if (!problem.empty()) return "option '" + a + "' " + problem;
  }
  return "";
}

}  // namespace shellfrac::app
