#include "shellfrac/solver/model/time_step_survey.hpp"

#include <cmath>
#include <limits>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"

namespace shellfrac::solver {

namespace {

// Histogram of log10(dt_e) from 1e-30 to 1e10 (steps outside land in the end bins).
constexpr double log_min = -30, log_max = 10, bin_width = 0.004;
const int num_bins = static_cast<int>((log_max - log_min) / bin_width);

int bin_of(double dt) {
  const double x = dt > 0 ? (std::log10(dt) - log_min) / bin_width : 0;
  return std::isfinite(x) ? static_cast<int>(std::min(std::max(x, 0.0), double(num_bins - 1))) : 0;
}

}  // namespace

TimeStepTally::TimeStepTally() : counts_(num_bins, 0), min_dt_(std::numeric_limits<double>::max()) {}

void TimeStepTally::add(LocalId le, double dt_e) {
  ++counts_[bin_of(dt_e)];
  if (dt_e < min_dt_ || min_le_ < 0) min_dt_ = dt_e, min_le_ = le;
}

TimeStepSurvey TimeStepTally::global_result(const decomposition::DistributedMesh& dm) const {
  const MPI_Comm comm = dm.comm();
  TimeStepSurvey r;
  r.min_dt = -parallel::max(-min_dt_, comm);
  const bool mine = min_le_ >= 0 && min_dt_ == r.min_dt;
  const double gid = mine ? double(dm.element_gid(min_le_)) : std::numeric_limits<double>::max();
  r.min_element = static_cast<GlobalId>(-parallel::max(-gid, comm));
  double where[4] = {0, 0, 0, 0}, all[4];  // block, centroid: the owner of min_element contributes, others 0
  if (mine && dm.element_gid(min_le_) == r.min_element) {
    where[0] = dm.element_block(min_le_);
    for (int A = 0; A < 3; ++A)
      for (int k = 0; k < 3; ++k) where[1 + k] += dm.node_coords(min_le_, A)[k] / 3;
  }
  SHELLFRAC_REQUIRE(MPI_Allreduce(where, all, 4, MPI_DOUBLE, MPI_SUM, comm) == MPI_SUCCESS,
                    "MPI_Allreduce of the time step survey failed");
  r.min_block = static_cast<int>(all[0]);
  r.min_centroid = {all[1], all[2], all[3]};
  std::vector<std::int64_t> total(counts_.size());
  SHELLFRAC_REQUIRE(
      MPI_Allreduce(counts_.data(), total.data(), int(counts_.size()), MPI_INT64_T, MPI_SUM, comm) == MPI_SUCCESS,
      "MPI_Allreduce of the time step histogram failed");
  std::int64_t n = 0, seen = 0;
  for (auto c : total) n += c;
  for (int b = 0; b < num_bins; ++b) {
    seen += total[b];
    if (2 * seen >= n) {
      r.median_dt = std::pow(10.0, log_min + (b + 0.5) * bin_width);
      break;
    }
  }
  return r;
}

}  // namespace shellfrac::solver
