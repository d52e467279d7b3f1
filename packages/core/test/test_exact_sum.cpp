// ExactSum: an order-independent, rank-count independent sum of doubles.
// References: exact arithmetic on values whose double sum loses digits (1e16 + 1 - 1e16 = 1 exactly, whereas the
// naive left-to-right sum gives 0); the exact sum of k 2^-1074 (denormals) and of huge values; a shuffled order and
// a split over ranks give the same bits; the result is the correctly rounded exact sum for sums that fit in 64
// bits (compared with integer arithmetic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"

using shellfrac::ExactSum;

namespace {
double exact_sum(const std::vector<double>& v) {
  ExactSum s;
  for (double x : v) s.add(x);
  return s.value();
}
}  // namespace

TEST(ExactSum, CancellationIsExact) {
  EXPECT_EQ(exact_sum({1e16, 1.0, -1e16}), 1.0);
  EXPECT_EQ(exact_sum({1e300, 1e-300, -1e300}), 1e-300);
  EXPECT_EQ(exact_sum({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));  // the doubles' exact sum (Python: Fraction)
  EXPECT_EQ(exact_sum({}), 0.0);
  EXPECT_EQ(exact_sum({-2.5}), -2.5);
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact_sum({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(exact_sum({std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 7.0}), 7.0);
  EXPECT_TRUE(std::isnan(exact_sum({1.0, std::numeric_limits<double>::infinity()})));
}

TEST(ExactSum, MatchesIntegerArithmetic) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> pick(-(std::int64_t(1) << 40), std::int64_t(1) << 40);
  std::vector<double> v;
  std::int64_t sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const std::int64_t k = pick(rng);
    v.push_back(std::ldexp(double(k), -20));  // exact binary fractions
    sum += k;
  }
  EXPECT_EQ(exact_sum(v), std::ldexp(double(sum), -20));  // double(sum) is the correctly rounded sum
}

TEST(ExactSum, OrderIndependent) {
  std::mt19937_64 rng(11);
  std::lognormal_distribution<double> mag(0.0, 20.0);
  std::vector<double> v;
  for (int i = 0; i < 20000; ++i) v.push_back((i % 3 ? 1 : -1) * mag(rng));
  const double a = exact_sum(v);
  std::shuffle(v.begin(), v.end(), rng);
  EXPECT_EQ(exact_sum(v), a);
  std::reverse(v.begin(), v.end());
  ExactSum left, right;
  for (std::size_t i = 0; i < v.size(); ++i) (i < v.size() / 3 ? left : right).add(v[i]);
  left += right;
  EXPECT_EQ(left.value(), a);
}

TEST(ExactSum, RankCountIndependent) {
  // The same 10000 values, dealt to the ranks round robin: every rank count gives the single-rank sum.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> val(0.0, 1e6);
  std::vector<double> v(10000);
  for (double& x : v) x = val(rng);
  const double serial = exact_sum(v);
  const int rank = shellfrac::parallel::rank(), size = shellfrac::parallel::size();
  ExactSum s;
  for (std::size_t i = rank; i < v.size(); i += size) s.add(v[i]);
  s.allreduce(MPI_COMM_WORLD);
  EXPECT_EQ(s.value(), serial);
}

TEST(ExactSum, BatchAllreduceEqualsSingleOnes) {
  // Three sums reduced together give the bits of each reduced alone, non-finite flags included.
  const int rank = shellfrac::parallel::rank();
  std::vector<ExactSum> batch(3);
  ExactSum a, b, c;
  for (int i = 0; i < 100; ++i) {
    const double x = std::ldexp(1.0 + rank + i, -i), y = -1e20 * (rank + 1) + i, z = i == 50 && rank == 0 ? NAN : 1.0;
    batch[0].add(x), batch[1].add(y), batch[2].add(z), a.add(x), b.add(y), c.add(z);
  }
  ExactSum::allreduce(batch, MPI_COMM_WORLD);
  a.allreduce(MPI_COMM_WORLD), b.allreduce(MPI_COMM_WORLD), c.allreduce(MPI_COMM_WORLD);
  EXPECT_EQ(batch[0].value(), a.value());
  EXPECT_EQ(batch[1].value(), b.value());
  EXPECT_TRUE(std::isnan(batch[2].value()));
  EXPECT_TRUE(std::isnan(c.value()));
}

// Packed partial sums (as the fragment table sends them) add up to the same bits as one sum of all values;
// reference: the cancellation values above, split into three parts.
TEST(ExactSum, PackedPartsAddUpExactly) {
  const std::vector<double> values = {1e16, 0.1, 1e-300, -1e16, 0.2, 1e300, -0.3, -1e300, 1.0};
  ExactSum whole;
  shellfrac::parallel::ByteWriter w;
  for (int part = 0; part < 3; ++part) {
    ExactSum s;
    for (int k = part; k < int(values.size()); k += 3) s.add(values[k]), whole.add(values[k]);
    s.pack(w);
  }
  ExactSum sum, empty;
  shellfrac::parallel::ByteReader r(w.buffer());
  while (!r.done()) sum += ExactSum::unpack(r);
  EXPECT_EQ(sum.value(), whole.value());
  EXPECT_EQ(sum.value(), 1.0 + 1e-300 + std::ldexp(1.0, -55));
  shellfrac::parallel::ByteWriter w0;
  empty.pack(w0);
  shellfrac::parallel::ByteReader r0(w0.buffer());
  EXPECT_EQ(ExactSum::unpack(r0).value(), 0.0);
  EXPECT_TRUE(r0.done());
}
