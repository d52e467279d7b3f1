#include "shellfrac/solver/restart/checkpoint_series.hpp"

#include <filesystem>
#include <system_error>

#include "shellfrac/core/files.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/solver/input/deck.hpp"

namespace shellfrac::solver {

std::string checkpoint_stem(const std::string& file) {
  const std::string ext = ".h5";
  const bool has = file.size() > ext.size() && file.compare(file.size() - ext.size(), ext.size(), ext) == 0;
  return has ? file.substr(0, file.size() - ext.size()) : file;
}

CheckpointSeries::CheckpointSeries(const CheckpointParams& params, const std::string& restart_file,
                                   RestartFingerprint fingerprint, MPI_Comm comm)
    : stem_(checkpoint_stem(params.file)),
      restart_file_(restart_file),
      keep_(params.keep),
      fingerprint_(std::move(fingerprint)),
      comm_(comm) {}

std::string CheckpointSeries::path(long step) const { return stem_ + "_step" + std::to_string(step) + ".h5"; }

bool CheckpointSeries::is_restart_file(const std::string& p) const {
  if (restart_file_.empty()) return false;
  std::error_code ec;
  if (std::filesystem::equivalent(p, restart_file_, ec)) return true;
  return files::resolved(p) == files::resolved(restart_file_);
}

std::string CheckpointSeries::write(io::CheckpointData state) {
  const std::string file = path(static_cast<long>(state.scalars.at("step")));
  if (is_restart_file(file)) return file;  // the same state is already there, and is the user's
  fingerprint_.stamp(state);
  io::write_checkpoint(file, state, comm_);
  if (written_.empty() || written_.back() != file) written_.push_back(file);
  while (static_cast<int>(written_.size()) > keep_) {
    const std::string old = written_.front();
    written_.pop_front();
    if (parallel::rank(comm_) == 0) {
      std::error_code ec;  // a checkpoint that cannot be removed is left in place: no data is lost
      std::filesystem::remove(old, ec);
    }
  }
  return file;
}

}  // namespace shellfrac::solver
