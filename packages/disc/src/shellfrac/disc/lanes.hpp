#pragma once
/// \file lanes.hpp
/// A batch of elements computed in lock-step (docs/performance.md, "The batched element kernel"): `Batch` holds
/// one double per element of a batch of `batch_width` elements, in one vector register of the machine (GCC's
/// vector extension; 4 doubles = one AVX register). Every arithmetic operator is the IEEE operation on each lane,
/// exactly the operation the same expression performs on a double (the build never contracts multiply-adds and
/// never reassociates), so a function templated on its number type gives on each lane of a Batch bit for bit
/// what it gives on a double. `BatchMask` holds one flag per lane; `select` takes per lane one of two values
/// (both are computed), `any` says whether a flag is set on some lane. The same names on double and bool make a
/// template read the same for both.
#include <Kokkos_Macros.hpp>

namespace shellfrac::disc {

constexpr int batch_width = 4;  ///< elements per batch: one 256-bit register of doubles

/// One flag per lane (all bits set = true), the result of a comparison of two Batch values.
struct BatchMask {
  typedef long long Bits __attribute__((vector_size(batch_width * sizeof(long long))));
  Bits m;
  BatchMask() = default;
  KOKKOS_INLINE_FUNCTION explicit BatchMask(Bits bits) : m(bits) {}
  KOKKOS_INLINE_FUNCTION void set(int lane, bool value) { m[lane] = value ? -1 : 0; }
  KOKKOS_INLINE_FUNCTION bool operator[](int lane) const { return m[lane] != 0; }
};

/// One double per lane.
struct Batch {
  typedef double Values __attribute__((vector_size(batch_width * sizeof(double))));
  Values v;
  Batch() = default;
  /// The same value on every lane (exactly s, also for -0 and NaN).
  KOKKOS_INLINE_FUNCTION Batch(double s) {  // NOLINT(google-explicit-constructor): a double used as a Batch
    for (int i = 0; i < batch_width; ++i) v[i] = s;
  }
  KOKKOS_INLINE_FUNCTION explicit Batch(Values values) : v(values) {}
  KOKKOS_INLINE_FUNCTION double operator[](int lane) const { return v[lane]; }
  KOKKOS_INLINE_FUNCTION void set(int lane, double value) { v[lane] = value; }

  KOKKOS_INLINE_FUNCTION friend Batch operator+(Batch a, Batch b) { return Batch(a.v + b.v); }
  KOKKOS_INLINE_FUNCTION friend Batch operator-(Batch a, Batch b) { return Batch(a.v - b.v); }
  KOKKOS_INLINE_FUNCTION friend Batch operator*(Batch a, Batch b) { return Batch(a.v * b.v); }
  KOKKOS_INLINE_FUNCTION friend Batch operator/(Batch a, Batch b) { return Batch(a.v / b.v); }
  KOKKOS_INLINE_FUNCTION friend Batch operator-(Batch a) { return Batch(-a.v); }
  KOKKOS_INLINE_FUNCTION Batch& operator+=(Batch b) { v = v + b.v; return *this; }
  KOKKOS_INLINE_FUNCTION Batch& operator-=(Batch b) { v = v - b.v; return *this; }
  KOKKOS_INLINE_FUNCTION Batch& operator*=(Batch b) { v = v * b.v; return *this; }
  KOKKOS_INLINE_FUNCTION Batch& operator/=(Batch b) { v = v / b.v; return *this; }
  KOKKOS_INLINE_FUNCTION friend BatchMask operator<(Batch a, Batch b) { return BatchMask(a.v < b.v); }
};

/// Per lane: a where the flag is set, else b.
KOKKOS_INLINE_FUNCTION Batch select(BatchMask m, Batch a, Batch b) { return Batch(m.m ? a.v : b.v); }
KOKKOS_INLINE_FUNCTION double select(bool m, double a, double b) { return m ? a : b; }

/// The correctly rounded square root on each lane (the same as std::sqrt of a double).
KOKKOS_INLINE_FUNCTION Batch sqrt(Batch a) {
  Batch r;
  for (int i = 0; i < batch_width; ++i) r.v[i] = __builtin_sqrt(a.v[i]);
  return r;
}

/// Whether the flag is set on some lane.
KOKKOS_INLINE_FUNCTION bool any(const BatchMask& m) {
  bool r = false;
  for (int i = 0; i < batch_width; ++i) r = r || m.m[i] != 0;
  return r;
}
KOKKOS_INLINE_FUNCTION bool any(bool m) { return m; }

/// The flag type of a number type: bool for double, BatchMask for Batch.
template <class T>
using MaskOf = decltype(T{} < T{});

}  // namespace shellfrac::disc
