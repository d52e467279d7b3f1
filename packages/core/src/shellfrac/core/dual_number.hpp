#pragma once
/// \file dual_number.hpp
/// Forward-mode automatic differentiation: a value and its N partial derivatives, for kernels whose forces are the
/// gradient of an energy that is easy to write and tedious to differentiate by hand (the crack-face contact,
/// docs/theory.md §9.9). Kernel-safe: plain arrays, no allocation. Only the operations those energies use.
#include <Kokkos_Macros.hpp>

namespace shellfrac {

template <int N>
struct Dual {
  double v = 0;       ///< value
  double d[N] = {};   ///< partial derivatives

  KOKKOS_INLINE_FUNCTION Dual() = default;
  KOKKOS_INLINE_FUNCTION Dual(double value) : v(value) {}  // NOLINT: a constant converts implicitly
  /// The independent variable number i with value `value`.
  KOKKOS_INLINE_FUNCTION static Dual variable(double value, int i) {
    Dual x(value);
    x.d[i] = 1;
    return x;
  }
};

template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.v + b.v);
  for (int i = 0; i < N; ++i) r.d[i] = a.d[i] + b.d[i];
  return r;
}
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.v - b.v);
  for (int i = 0; i < N; ++i) r.d[i] = a.d[i] - b.d[i];
  return r;
}
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(const Dual<N>& a) {
  Dual<N> r(-a.v);
  for (int i = 0; i < N; ++i) r.d[i] = -a.d[i];
  return r;
}
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.v * b.v);
  for (int i = 0; i < N; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
  return r;
}
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
  const double inv = 1 / b.v;
  Dual<N> r(a.v * inv);
  for (int i = 0; i < N; ++i) r.d[i] = (a.d[i] - r.v * b.d[i]) * inv;
  return r;
}
/// The value of a double or a Dual (for decisions that are not differentiated: branches, gates, histories).
KOKKOS_INLINE_FUNCTION double value_of(double a) { return a; }
template <int N>
KOKKOS_INLINE_FUNCTION double value_of(const Dual<N>& a) {
  return a.v;
}

}  // namespace shellfrac
