#pragma once
/// \file digest.hpp
/// A 128-bit content digest (two independent 64-bit multiply-xorshift lanes) for checksums and fingerprints:
/// not cryptographic, but any change of the hashed bytes changes it with probability 1 - 2^-128 for accidental
/// corruption. Digests of independent items combine by `combine`, which is commutative: a sum over elements in
/// any order, on any number of ranks, gives the same value (docs/output.md, checkpoints).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shellfrac {

class Digest {
 public:
  Digest();
  /// Hashes n bytes (in 8-byte words; the tail is zero-padded, the length is hashed too).
  void add_bytes(const void* data, std::size_t n);
  void add(double v) { add_bytes(&v, sizeof v); }
  void add(std::int64_t v) { add_bytes(&v, sizeof v); }
  void add(const std::string& s) { add_bytes(s.data(), s.size()); }
  /// Order-independent combination: lane-wise sum modulo 2^64 of the finished lanes of `other`.
  void combine(const Digest& other);
  /// The finished lanes (after a final mixing), for sums across ranks.
  std::uint64_t lane(int i) const;
  /// A digest made of two given lanes (e.g. after an MPI sum of `lane` values).
  static Digest from_lanes(std::uint64_t a, std::uint64_t b);
  /// 32 lowercase hex digits of the finished lanes.
  std::string hex() const;

 private:
  void mix_word(std::uint64_t w);
  std::uint64_t h_[2];
  bool finished_ = false;  ///< from_lanes / combine: the lanes are already final
};

}  // namespace shellfrac
