#pragma once
/// \file kernel_views.hpp
/// What the per-element kernels run over (docs/parallel.md, "Threads"): Kokkos::Views of the host arrays of the
/// state and the model, unmanaged (the arrays keep their owners), and the execution space of the kernels. A
/// kernel captures views and plain values only, never an object or a container, so each iteration touches
/// nothing but the rows its index names. Include only in the kernel sources (Kokkos_Core.hpp is heavy).
#include <Kokkos_Core.hpp>
#include <vector>

#include "shellfrac/solver/model/prefetch.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

/// The kernels' execution space: the host's (threads with a Kokkos OpenMP build), where the arrays live.
/// (A kernel is launched with a label made once, `static const std::string`: Kokkos 3.4 takes the label as a
/// std::string, so a string literal would be a heap allocation at every launch.)
using KernelSpace = Kokkos::DefaultHostExecutionSpace;
using KernelRange = Kokkos::RangePolicy<KernelSpace>;

/// A 1-D view of n values of T in host memory, not owning them.
template <class T>
using KernelView = Kokkos::View<T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

template <class T>
KernelView<T> kernel_view(std::vector<T>& v) {
  return KernelView<T>(v.data(), v.size());
}
template <class T>
KernelView<const T> kernel_view(const std::vector<T>& v) {
  return KernelView<const T>(v.data(), v.size());
}
/// A row array (Rows) as the kernels see it: row r (an element or an interface, as Over says), point p, value c.
/// The widths come from the type, so a kernel names what it reads (x(le, A, c), rotation.point(j)) and never
/// computes an offset by hand.
template <class Over, int P, int V, class T>
class RowsView {
 public:
  using over = Over;
  static constexpr int points = P, values = V, width = P * V;
  RowsView() = default;
  RowsView(T* data, std::size_t rows) : v_(data, rows * width) {}
  /// Value c of point p of row r.
  KOKKOS_INLINE_FUNCTION T& operator()(LocalId r, int p, int c) const { return v_((r * P + p) * V + c); }
  /// The `width` values of row r, point after point.
  KOKKOS_INLINE_FUNCTION T* at(LocalId r) const { return &v_(r * width); }
  /// The V values of point i = r * P + p.
  KOKKOS_INLINE_FUNCTION T* point(LocalId i) const { return &v_(i * V); }
  /// The value of point i = r * P + p of a one-value array (V = 1).
  KOKKOS_INLINE_FUNCTION T& operator()(LocalId i) const {
    static_assert(V == 1, "one value per point: index a wider array by (row, point, value) or point()");
    return v_(i);
  }
  /// Row r as P points of V values (an argument `T values[][V]` of a point-wise function).
  KOKKOS_INLINE_FUNCTION T (*points_of(LocalId r) const)[V] { return reinterpret_cast<T(*)[V]>(at(r)); }

 private:
  KernelView<T> v_;
};

template <class O, int P, int V>
RowsView<O, P, V, double> kernel_view(Rows<O, P, V>& r) {
  return RowsView<O, P, V, double>(r.data(), std::size_t(r.rows()));
}
template <class O, int P, int V>
RowsView<O, P, V, const double> kernel_view(const Rows<O, P, V>& r) {
  return RowsView<O, P, V, const double>(r.data(), std::size_t(r.rows()));
}
inline RowsView<PerElement, position_nodes, 3, const double> kernel_view(const PositionRowsView& r) {
  return {r.data(), std::size_t(r.rows())};
}

/// The kernels' view of a row array type: ViewOf<PositionRows> writes, ConstViewOf<PositionRows> reads.
template <class R>
using ViewOf = RowsView<typename R::over, R::points, R::values, double>;
template <class R>
using ConstViewOf = RowsView<typename R::over, R::points, R::values, const double>;
using PositionView = ViewOf<PositionRows>;
using ConstPositionView = ConstViewOf<PositionRows>;
using DirectorView = ViewOf<DirectorRows>;
using ConstDirectorView = ConstViewOf<DirectorRows>;

}  // namespace shellfrac::solver
