#include "shellfrac/solver/outputs/results_series.hpp"

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"
#include "shellfrac/io/results_reader.hpp"
#include "shellfrac/io/results_writer.hpp"

namespace shellfrac::solver {

namespace fs = std::filesystem;

namespace {

std::string regex_escaped(const std::string& text) {
  return std::regex_replace(text, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)");
}

fs::path directory_of(const std::string& path) {
  const fs::path p(path);
  return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

/// The files beside `exodus` whose names match `pattern`, sorted, named as `exodus` is (with its directory, if it
/// has one).
std::vector<std::string> matching(const std::string& exodus, const std::regex& pattern) {
  std::vector<std::string> out;
  const fs::path parent = fs::path(exodus).parent_path();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_of(exodus), ec)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, pattern)) out.push_back(parent.empty() ? name : (parent / name).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string with_time(double t) {
  std::ostringstream os;
  os.precision(6);
  os << t;
  return os.str();
}

}  // namespace

std::string restart_member(const std::string& exodus, long step) { return exodus + "-s." + std::to_string(step); }

void remove_restart_members(const std::string& exodus) {
  const std::string name = regex_escaped(fs::path(exodus).filename().string());
  for (const auto& file : matching(exodus, std::regex(name + R"(-s\.[0-9]+(\.[0-9]+\.[0-9]+)?)"))) {
    files::require_result_path(file);
    files::remove_result(file);
  }
}

std::vector<LaterFrames> frames_after(const std::string& exodus, const std::string& own, int np, double time) {
  const std::string name = regex_escaped(fs::path(exodus).filename().string());
  const std::string layout = np > 1 ? R"(\.)" + std::to_string(np) + R"(\.0)" : std::string();
  const std::string own_file = np > 1 ? io::rank_file_name(own, np, 0) : own;
  std::vector<LaterFrames> out;
  for (const auto& file : matching(exodus, std::regex(name + R"((-s\.[0-9]+)?)" + layout))) {
    if (fs::path(file).filename() == fs::path(own_file).filename()) continue;
    std::vector<double> times;
    try {
      times = io::read_result_times(file);
    } catch (const InputError&) {
      continue;  // not results ParaView could show either
    }
    LaterFrames later{file, {}};
    for (double t : times)
      if (t > time) later.times.push_back(t);
    if (!later.times.empty()) out.push_back(std::move(later));
  }
  return out;
}

bool only_other_layouts(const std::string& exodus, int np) {
  const std::string name = regex_escaped(fs::path(exodus).filename().string());
  const std::string member = name + R"((-s\.[0-9]+)?)";
  const std::string layout = np > 1 ? R"(\.)" + std::to_string(np) + R"(\.[0-9]+)" : std::string();
  if (!matching(exodus, std::regex(member + layout)).empty()) return false;
  return !matching(exodus, std::regex(member + R"((\.[0-9]+\.[0-9]+)?)")).empty();
}

std::vector<std::string> interleaving_notices(const std::vector<LaterFrames>& later, const std::vector<double>& own_times,
                                              const std::string& own, double restart_time) {
  std::vector<std::string> notices;
  for (const auto& member : later) {
    std::size_t stray = 0;
    for (double t : member.times)
      if (!std::binary_search(own_times.begin(), own_times.end(), t)) ++stray;
    if (stray == 0) continue;
    notices.push_back(member.file + " holds " + std::to_string(stray) + " frame(s) after t = " +
                      with_time(restart_time) +
                      " (this restart's time) at times this run wrote no frame (its time step or output times are "
                      "not those of the run before): ParaView's IOSS reader opens the run and its restarts as one "
                      "series and shows them between this run's frames; to see this run alone, open " + own +
                      " with the reader's 'Scan For Related Files' off");
  }
  return notices;
}

}  // namespace shellfrac::solver
