#pragma once
/// \file results_series.hpp
/// A run's Exodus results and those of its restarts as one time series (docs/output.md, "Checkpoints and
/// restart"). A run writes <base>.exo; a run restarted at step N writes <base>.exo-s.N (per-rank sets add
/// .<np>.<rank> to both), the names ParaView's IOSS reader opens together as one series when the sets have the
/// same number of files. The series is one run's when every restart continues the frames before it (the same
/// time step and output times: the frames after a restart's time coincide); otherwise the earlier files' later
/// frames show between the restart's, and the restart says so.
#include <string>
#include <vector>

namespace shellfrac::solver {

/// The results file of a run restarted at `step`: <exodus>-s.<step>.
std::string restart_member(const std::string& exodus, long step);

/// Removes the restart members <exodus>-s.<N> (and their per-rank files) an earlier run on this base left, so
/// that a new run's series holds its own files only. A link or anything but a regular file of such a name is an
/// OutputError (core/files.hpp). Rank 0.
void remove_restart_members(const std::string& exodus);

/// Frames of another member of the series after a restart's time.
struct LaterFrames {
  std::string file;           ///< the member's file as a run on np ranks names it (its .<np>.0 file for np > 1)
  std::vector<double> times;  ///< its frame times after the restart's time
};

/// The members of the series of `exodus` other than `own` that hold frames after `time`, in the layout of a
/// run on `np` ranks (<name> for np = 1, <name>.<np>.0 otherwise). Rank 0; an unreadable member is skipped.
std::vector<LaterFrames> frames_after(const std::string& exodus, const std::string& own, int np, double time);

/// Whether the series of `exodus` has results in another layout than that of np ranks (another rank count, or
/// one joined file against a per-rank set) and none in this one: ParaView then opens the restart as a series
/// of its own. Rank 0.
bool only_other_layouts(const std::string& exodus, int np);

/// What a restart that wrote frames at `own_times` tells about the earlier members' frames `later` that it did not
/// write at the same times (empty if none): ParaView shows them between its own.
std::vector<std::string> interleaving_notices(const std::vector<LaterFrames>& later, const std::vector<double>& own_times,
                                              const std::string& own, double restart_time);

}  // namespace shellfrac::solver
