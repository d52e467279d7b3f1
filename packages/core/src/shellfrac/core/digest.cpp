#include "shellfrac/core/digest.hpp"

#include <cstring>

namespace shellfrac {

namespace {

std::uint64_t finish(std::uint64_t x) {  // the splitmix64 finalizer: every input bit reaches every output bit
  x ^= x >> 30, x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27, x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

Digest::Digest() : h_{0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL} {}

void Digest::mix_word(std::uint64_t w) {
  h_[0] = (h_[0] ^ w) * 0x9e3779b97f4a7c15ULL, h_[0] ^= h_[0] >> 32;
  h_[1] = (h_[1] ^ (w + 0x632be59bd9b4e019ULL)) * 0xc2b2ae3d27d4eb4fULL, h_[1] ^= h_[1] >> 29;
}

void Digest::add_bytes(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    mix_word(w);
  }
  std::uint64_t tail = 0;
  std::memcpy(&tail, p + i, n - i);
  mix_word(tail);
  mix_word(static_cast<std::uint64_t>(n));
}

std::uint64_t Digest::lane(int i) const { return finished_ ? h_[i] : finish(h_[i] + std::uint64_t(i)); }

Digest Digest::from_lanes(std::uint64_t a, std::uint64_t b) {
  Digest d;
  d.h_[0] = a, d.h_[1] = b, d.finished_ = true;
  return d;
}

void Digest::combine(const Digest& other) {
  const std::uint64_t a = lane(0) + other.lane(0), b = lane(1) + other.lane(1);
  h_[0] = a, h_[1] = b, finished_ = true;
}

std::string Digest::hex() const {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (int i = 0; i < 2; ++i)
    for (int k = 60; k >= 0; k -= 4) s += digits[(lane(i) >> k) & 0xf];
  return s;
}

}  // namespace shellfrac
