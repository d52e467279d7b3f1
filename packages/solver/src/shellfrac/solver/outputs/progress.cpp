#include "shellfrac/solver/outputs/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "shellfrac/solver/step/energy_accounts.hpp"

namespace shellfrac::solver {

namespace {

/// h:mm:ss of a duration in seconds.
std::string clock_time(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

/// A byte count with a binary-prefix unit (B, KiB, MiB, GiB, TiB).
std::string byte_size(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (bytes >= 1024 && u < 4) bytes /= 1024, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return buf;
}

}  // namespace

ProgressReport::ProgressReport(std::ostream* out, double interval, long start_step, double start_time,
                               double end_time, double dt, bool show_edges)
    : out_(out), interval_(interval), start_step_(start_step), start_time_(start_time), end_time_(end_time),
      dt_(dt), show_edges_(show_edges), start_(Clock::now()), last_(start_) {}

void ProgressReport::plan(double result_bytes) const {
  if (!out_) return;
  const long steps = std::lround(std::ceil((end_time_ - start_time_) / dt_ - 0.5));
  *out_ << "  planned: " << steps << " steps to t = " << end_time_ << ", results about " << byte_size(result_bytes)
        << "\n"
        << std::flush;
}

bool ProgressReport::due() const {
  return interval_ > 0 && std::chrono::duration<double>(Clock::now() - last_).count() >= interval_;
}

void ProgressReport::print(const StepRecord& r, double e0, double residual) {
  last_ = Clock::now();
  if (!out_) return;
  const double elapsed = std::chrono::duration<double>(last_ - start_).count();
  const double rate = elapsed > 0 ? double(r.step - start_step_) / elapsed : 0.0;
  const double remaining = std::max(0.0, (end_time_ - r.time) / dt_);
  const double done =
      end_time_ > start_time_ ? std::min(100.0, 100 * (r.time - start_time_) / (end_time_ - start_time_)) : 100.0;
  const double put_in = std::abs(e0) + std::abs(r.external_work) + std::abs(r.reaction_work);
  const double error = energy_balance_error(r, e0);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "  step %ld  t = %.6g  dt = %.4g  %.1f %%  %.0f steps/s  elapsed %s  ETA %s  balance error %.1e",
                r.step, r.time, r.dt, done, rate, clock_time(elapsed).c_str(),
                clock_time(rate > 0 ? remaining / rate : NAN).c_str(), put_in > 0 ? std::abs(error) / put_in : 0.0);
  *out_ << buf;
  if (!std::isnan(residual)) {
    std::snprintf(buf, sizeof buf, "  residual %.2e", residual);
    *out_ << buf;
  }
  if (show_edges_) *out_ << "  edges " << r.cohesive_edges << " activated, " << r.separated_edges << " separated";
  *out_ << "\n" << std::flush;
}

}  // namespace shellfrac::solver
