#include "shellfrac/solver/contact/bin_grid.hpp"

#include <algorithm>
#include <cmath>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

Box Box::around(const double* p, int n) {
  Box b;
  for (int c = 0; c < 3; ++c) b.lo[c] = b.hi[c] = p[c];
  for (int i = 1; i < n; ++i)
    for (int c = 0; c < 3; ++c) b.lo[c] = std::min(b.lo[c], p[3 * i + c]), b.hi[c] = std::max(b.hi[c], p[3 * i + c]);
  return b;
}

Box Box::inflated(double r) const {
  Box b = *this;
  for (int c = 0; c < 3; ++c) b.lo[c] -= r, b.hi[c] += r;
  return b;
}

BinGrid::BinGrid(std::vector<Box> boxes, double min_bin) : boxes_(std::move(boxes)), bin_(min_bin) {
  SHELLFRAC_REQUIRE(min_bin > 0 && std::isfinite(min_bin), "BinGrid: bin size " << min_bin);
  for (const Box& b : boxes_)
    for (int c = 0; c < 3; ++c) {
      SHELLFRAC_REQUIRE(std::isfinite(b.lo[c]) && std::isfinite(b.hi[c]), "BinGrid: a box is not finite");
      bin_ = std::max(bin_, b.hi[c] - b.lo[c]);
    }
  for (int n = 0; n < int(boxes_.size()); ++n) {
    const Box& b = boxes_[std::size_t(n)];
    const std::int64_t i0 = bin_index(b.lo[0]), i1 = bin_index(b.hi[0]), j0 = bin_index(b.lo[1]),
                       j1 = bin_index(b.hi[1]), k0 = bin_index(b.lo[2]), k1 = bin_index(b.hi[2]);
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) bins_[key(i, j, k)].push_back(n);
  }
}

std::int64_t BinGrid::bin_index(double x) const { return static_cast<std::int64_t>(std::floor(x / bin_)); }

std::uint64_t BinGrid::key(std::int64_t i, std::int64_t j, std::int64_t k) {
  // 21 bits per axis: bins -2^20 .. 2^20 - 1 around the origin; a model more than a million bins across wraps
  // (two far bins share a key), which costs a few false candidates, never a missed one.
  const std::uint64_t m = (1u << 21) - 1;
  return (std::uint64_t(i) & m) | ((std::uint64_t(j) & m) << 21) | ((std::uint64_t(k) & m) << 42);
}

std::vector<int> BinGrid::overlapping(const Box& q) const {
  std::vector<int> out;
  const std::int64_t i0 = bin_index(q.lo[0]), i1 = bin_index(q.hi[0]), j0 = bin_index(q.lo[1]),
                     j1 = bin_index(q.hi[1]), k0 = bin_index(q.lo[2]), k1 = bin_index(q.hi[2]);
  for (std::int64_t i = i0; i <= i1; ++i)
    for (std::int64_t j = j0; j <= j1; ++j)
      for (std::int64_t k = k0; k <= k1; ++k) {
        const auto it = bins_.find(key(i, j, k));
        if (it == bins_.end()) continue;
        for (int n : it->second)
          if (boxes_[std::size_t(n)].overlaps(q)) out.push_back(n);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace shellfrac::solver
