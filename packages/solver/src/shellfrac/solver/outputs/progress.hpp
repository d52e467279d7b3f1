#pragma once
/// \file progress.hpp
/// The console progress of a run (docs/output.md "Progress"): before the first step, the planned number of steps
/// and an estimate of the size of the results; then, at most every Output->Progress Interval seconds of wall
/// time, one line with the step, time, step size, percent done, steps per second, elapsed wall time, estimated
/// time to the end, the energy balance error relative to the energy put in, and the activated and separated
/// edges.
#include <chrono>
#include <cmath>
#include <iosfwd>

namespace shellfrac::solver {

struct StepRecord;

class ProgressReport {
 public:
  /// `out`: the console on rank 0, null on the other ranks (they only take part in the decisions). The run goes
  /// from (start_step, start_time) to end_time with steps of dt; interval 0 = no progress lines. `show_edges`:
  /// the run can fracture, so the lines count the activated and separated edges.
  ProgressReport(std::ostream* out, double interval, long start_step, double start_time, double end_time, double dt,
                 bool show_edges);
  /// The plan: the number of steps and the estimated size of the results [bytes].
  void plan(double result_bytes) const;
  /// Whether this rank's clock says a line is due (the ranks agree on it by a reduction).
  bool due() const;
  /// Prints the line for the record `r` (e0: the initial energy of the balance) and starts the next interval.
  /// `residual`: the static relaxation's relative residual (theory.md §7.5), shown unless NaN.
  void print(const StepRecord& r, double e0, double residual = NAN);

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream* out_;
  double interval_;
  long start_step_;
  double start_time_, end_time_, dt_;
  bool show_edges_;
  Clock::time_point start_, last_;
};

}  // namespace shellfrac::solver
