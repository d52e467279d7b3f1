#pragma once
/// \file phase_times.hpp
/// Wall time per phase of the time step on this rank, for the benchmark (docs/performance.md).
#include <chrono>

namespace shellfrac::solver {

/// Wall time spent in each phase of the steps taken so far, on this rank [s].
struct PhaseTimes {
  double element = 0;    ///< element kernel: DG derivatives, point laws, own forces, lifting fluxes, edge tractions
  double interface = 0;  ///< interface kernel: penalty forces of intact interfaces, cohesive forces of activated ones
  double gather = 0;     ///< gathering fluxes and interface forces into each element
  double exchange = 0;   ///< ghost exchange of positions/directors and of the flux buffers (incl. packing)
  double update = 0;     ///< predictor, director update, loads, accelerations, corrector, checks
  double nucleation = 0; ///< fracture: the nucleation check of intact edges and activation (part of update)
  double contact = 0;    ///< contact between the shells: search, ghost faces, forces (part of update)
};

/// Adds the wall time of its scope to a counter.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace shellfrac::solver
