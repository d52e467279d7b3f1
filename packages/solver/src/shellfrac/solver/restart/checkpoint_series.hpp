#pragma once
/// \file checkpoint_series.hpp
/// The checkpoints a run writes (docs/output.md, "Checkpoints and restart"): one file per checkpoint,
/// <File without .h5>_step<N>.h5, the newest `Checkpoint->Keep` of them kept (older ones of this run are
/// removed). A run never writes, replaces or removes the checkpoint it restarted from, and removes only files it
/// wrote itself.
#include <mpi.h>

#include <deque>
#include <string>

#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/solver/restart/restart_fingerprint.hpp"

namespace shellfrac::solver {

struct CheckpointParams;

/// The stem of the series named by Checkpoint->File: the name without ".h5".
std::string checkpoint_stem(const std::string& file);

class CheckpointSeries {
 public:
  /// `restart_file`: the checkpoint the run started from ("" if none).
  CheckpointSeries(const CheckpointParams& params, const std::string& restart_file, RestartFingerprint fingerprint,
                   MPI_Comm comm);
  /// The file of the checkpoint at `step`.
  std::string path(long step) const;
  /// Whether `path` is the checkpoint the run started from.
  bool is_restart_file(const std::string& path) const;
  /// Writes `state` (its scalar "step" names the file) with the fingerprint, then removes this run's
  /// checkpoints beyond Keep. Returns the file. Collective; OutputError if the write fails.
  std::string write(io::CheckpointData state);
  /// The last checkpoint this run wrote ("" if none).
  std::string last() const { return written_.empty() ? std::string() : written_.back(); }

 private:
  std::string stem_, restart_file_;
  int keep_;
  RestartFingerprint fingerprint_;
  MPI_Comm comm_;
  std::deque<std::string> written_;
};

}  // namespace shellfrac::solver
