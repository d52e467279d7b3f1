#pragma once
/// \file time_step_survey.hpp
/// Where the stable time step comes from (docs/theory.md §8): the element with the smallest stable step and
/// the median element, so that a run can say when a few small or badly shaped elements (slivers) set the step
/// of the whole mesh, and which element gives an absurd step.
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

/// Global values (the same on every rank), before mass scaling and the safety factor.
struct TimeStepSurvey {
  double min_dt = 0;           ///< smallest element stable step
  GlobalId min_element = -1;   ///< the element with it (smallest id among equals)
  int min_block = -1;          ///< its block index
  Vec3 min_centroid{0, 0, 0};  ///< its vertex centroid
  double median_dt = 0;        ///< median element stable step (to 1 %: a histogram in 0.004-decade bins)
};

/// Collects the owned elements' stable steps; `global_result` combines them over the ranks (integer counts and
/// exact minima: the same result on any number of ranks).
class TimeStepTally {
 public:
  TimeStepTally();
  void add(LocalId le, double dt_e);
  TimeStepSurvey global_result(const decomposition::DistributedMesh& dm) const;

 private:
  std::vector<std::int64_t> counts_;
  double min_dt_;
  LocalId min_le_ = -1;
};

}  // namespace shellfrac::solver
