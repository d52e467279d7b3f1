#pragma once
/// \file bin_grid.hpp
/// The broad phase of the contact search between shells (docs/theory.md §12.5): axis-aligned boxes sorted into a
/// uniform grid of cubic bins (a hash of the bin's integer coordinates), so that the boxes that overlap a query box
/// are found by visiting only the bins the query covers — O(N) to build, O(1) per query for boxes of about one
/// bin's size. The answer is the ascending list of box indices, whatever the order of the bins in the hash: the
/// search's results do not depend on the machine, the rank count or the thread count.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace shellfrac::solver {

/// An axis-aligned box [lo, hi] (closed).
struct Box {
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  /// The box around the points p[0..n) (3 doubles each).
  static Box around(const double* p, int n);
  /// This box grown by r on every side.
  Box inflated(double r) const;
  bool overlaps(const Box& b) const {
    for (int c = 0; c < 3; ++c)
      if (lo[c] > b.hi[c] || b.lo[c] > hi[c]) return false;
    return true;
  }
};

class BinGrid {
 public:
  /// Sorts `boxes` into bins whose edge is the largest extent of any box (at least `min_bin`, > 0).
  BinGrid(std::vector<Box> boxes, double min_bin);
  /// The indices of the boxes that overlap q, ascending. Safe to call from several threads at once.
  std::vector<int> overlapping(const Box& q) const;
  double bin_size() const { return bin_; }

 private:
  std::int64_t bin_index(double x) const;
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k);

  std::vector<Box> boxes_;
  double bin_ = 1;
  std::unordered_map<std::uint64_t, std::vector<int>> bins_;
};

}  // namespace shellfrac::solver
