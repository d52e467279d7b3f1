#pragma once
/// \file exact_sum.hpp
/// An exact, order-independent sum of doubles. Every value is added without rounding into a fixed-point
/// accumulator that covers the whole range of doubles (32-bit digits held in 64-bit integers), so the sum does
/// not depend on the order of the additions, nor on how the values are split over ranks or threads. One
/// MPI_Allreduce of integers combines the ranks. The result is the exact sum, rounded once to a double (the
/// rounding is deterministic: equal sums give equal doubles on any rank count).
#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace shellfrac {

namespace parallel {
class ByteWriter;
class ByteReader;
}  // namespace parallel

class ExactSum {
 public:
  /// Adds x exactly. A NaN or infinite x makes value() NaN.
  void add(double x);
  /// Adds another accumulator (a thread's or a block's partial sum).
  ExactSum& operator+=(const ExactSum& other);
  /// Replaces this rank's sum by the sum over all ranks of comm (the same on every rank). Collective.
  void allreduce(MPI_Comm comm);
  /// The same for every sum of `sums` at once, with one MPI_Allreduce. Collective.
  static void allreduce(std::vector<ExactSum>& sums, MPI_Comm comm);
  /// The sum rounded to a double.
  double value() const;
  /// Appends the accumulator to `w` compactly (its range of nonzero digits), for messages of many sums.
  void pack(parallel::ByteWriter& w) const;
  /// Reads an accumulator written by pack.
  static ExactSum unpack(parallel::ByteReader& r);

 private:
  static constexpr int digit_bits = 32;
  static constexpr int bias = 1127;  ///< bit 0 of the accumulator has weight 2^-bias (below the smallest denormal)
  static constexpr int num_digits = 70;  ///< 2240 bits: the double range, 2^53 mantissas and carry headroom
  void normalize();
  std::array<std::int64_t, num_digits> digit_{};
  std::int64_t pending_ = 0;  ///< additions since the last normalization
  bool nonfinite_ = false;
};

}  // namespace shellfrac
