#include "shellfrac/core/exact_sum.hpp"

#include "shellfrac/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "shellfrac/core/error.hpp"

namespace shellfrac {

// x = mantissa 2^(exponent - 1075) from its IEEE 754 fields (mantissa < 2^53 with the hidden bit; denormals
// have exponent field 0 and the weight of field 1), so the mantissa's last bit has weight 2^(bit - bias) with
// bit = exponent field + 52 >= 53.
void ExactSum::add(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int field = static_cast<int>((bits >> 52) & 0x7ff);
  if (field == 0x7ff) {
    nonfinite_ = true;
    return;
  }
  std::int64_t mantissa = static_cast<std::int64_t>(bits & ((std::uint64_t(1) << 52) - 1));
  if (mantissa == 0 && field == 0) return;  // +-0
  if (field != 0) mantissa |= std::int64_t(1) << 52;
  const int bit = (field == 0 ? 1 : field) - 1075 + bias;
  const int k = bit >> 5, shift = bit & 31;  // digit_bits = 32
  // mantissa 2^shift split into 32-bit digits: the low digit, then the rest (< 2^53) in two digits.
  const std::int64_t mask = (std::int64_t(1) << digit_bits) - 1;
  const std::int64_t low = (mantissa & ((std::int64_t(1) << (digit_bits - shift)) - 1)) << shift;
  const std::int64_t rest = mantissa >> (digit_bits - shift);
  const std::int64_t sign = -static_cast<std::int64_t>(bits >> 63);  // 0 or -1: negate without a branch
  digit_[k] += (low ^ sign) - sign;
  digit_[k + 1] += ((rest & mask) ^ sign) - sign;
  digit_[k + 2] += ((rest >> digit_bits) ^ sign) - sign;
  if (++pending_ >= (std::int64_t(1) << 29)) normalize();  // digits stay far below 2^63
}

ExactSum& ExactSum::operator+=(const ExactSum& o) {
  for (int k = 0; k < num_digits; ++k) digit_[k] += o.digit_[k];
  nonfinite_ = nonfinite_ || o.nonfinite_;
  pending_ += o.pending_ + 1;
  if (pending_ >= (std::int64_t(1) << 29)) normalize();
  return *this;
}

// Carries so that digits 0 .. num_digits - 2 lie in [0, 2^32); the top digit keeps the sign. This form of an
// integer is unique.
void ExactSum::normalize() {
  for (int k = 0; k + 1 < num_digits; ++k) {
    const std::int64_t carry = digit_[k] >> digit_bits;  // floor division (arithmetic shift)
    digit_[k] -= carry * (std::int64_t(1) << digit_bits);
    digit_[k + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::allreduce(MPI_Comm comm) {
  std::vector<ExactSum> one{*this};
  allreduce(one, comm);
  *this = one[0];
}

// Digits are normalized first, so that each lies in [0, 2^32) (the top one signed): summing them over up to
// 2^31 ranks cannot overflow. The non-finite flags travel as one more integer per sum.
void ExactSum::allreduce(std::vector<ExactSum>& sums, MPI_Comm comm) {
  if (sums.empty()) return;  // the same on every rank: the callers' lists have global lengths
  constexpr int width = num_digits + 1;
  std::vector<std::int64_t> mine(sums.size() * width), all(sums.size() * width);
  for (std::size_t i = 0; i < sums.size(); ++i) {
    sums[i].normalize();
    std::copy(sums[i].digit_.begin(), sums[i].digit_.end(), mine.begin() + i * width);
    mine[i * width + num_digits] = sums[i].nonfinite_ ? 1 : 0;
  }
  SHELLFRAC_REQUIRE(MPI_Allreduce(mine.data(), all.data(), static_cast<int>(all.size()), MPI_INT64_T, MPI_SUM,
                                  comm) == MPI_SUCCESS,
                    "MPI_Allreduce of exact sums failed");
  for (std::size_t i = 0; i < sums.size(); ++i) {
    std::copy(all.begin() + i * width, all.begin() + i * width + num_digits, sums[i].digit_.begin());
    sums[i].nonfinite_ = all[i * width + num_digits] != 0;
    sums[i].pending_ = 0;
    sums[i].normalize();
  }
}

double ExactSum::value() const {
  if (nonfinite_) return std::numeric_limits<double>::quiet_NaN();
  ExactSum s = *this;
  s.normalize();
  const bool negative = s.digit_[num_digits - 1] < 0;
  if (negative) {
    for (auto& d : s.digit_) d = -d;
    s.normalize();
  }
  int top = num_digits - 1;
  while (top >= 0 && s.digit_[top] == 0) --top;
  if (top < 0) return 0.0;
  // The top three digits (96 bits, more than a long double's 64) carry the value; the rest only the last bit.
  long double v = 0;
  for (int k = top; k >= top - 2 && k >= 0; --k) v = v * 4294967296.0L + static_cast<long double>(s.digit_[k]);
  const int low = top - 2 > 0 ? top - 2 : 0;
  const double r = static_cast<double>(std::ldexp(v, low * digit_bits - bias));
  return negative ? -r : r;
}

void ExactSum::pack(parallel::ByteWriter& w) const {
  int lo = 0, hi = num_digits;
  while (lo < hi && digit_[lo] == 0) ++lo;
  while (hi > lo && digit_[hi - 1] == 0) --hi;
  w.put(std::int32_t(lo)), w.put(std::int32_t(hi)), w.put(pending_), w.put(std::int8_t(nonfinite_ ? 1 : 0));
  for (int k = lo; k < hi; ++k) w.put(digit_[k]);
}

ExactSum ExactSum::unpack(parallel::ByteReader& r) {
  ExactSum s;
  const int lo = r.get<std::int32_t>(), hi = r.get<std::int32_t>();
  SHELLFRAC_REQUIRE(0 <= lo && lo <= hi && hi <= num_digits, "a packed exact sum has digits " << lo << ".." << hi);
  s.pending_ = r.get<std::int64_t>();
  s.nonfinite_ = r.get<std::int8_t>() != 0;
  for (int k = lo; k < hi; ++k) s.digit_[k] = r.get<std::int64_t>();
  return s;
}

}  // namespace shellfrac
