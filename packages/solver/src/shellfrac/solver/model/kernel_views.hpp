#pragma once
/// \file kernel_views.hpp
/// What the per-element kernels run over (docs/parallel.md, "Threads"): Kokkos::Views of the host arrays of the
/// state and the model, unmanaged (the arrays keep their owners), and the execution space of the kernels. A
/// kernel captures views and plain values only, never an object or a container, so each iteration touches
/// nothing but the rows its index names. Include only in the kernel sources (Kokkos_Core.hpp is heavy).
#include <Kokkos_Core.hpp>
#include <vector>

#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::solver {

/// The kernels' execution space: the host's (threads with a Kokkos OpenMP build), where the arrays live.
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
/// All values of a row array, row r point p value c at (r * P + p) * V + c.
template <int P, int V>
KernelView<double> kernel_view(Rows<P, V>& r) {
  return KernelView<double>(r.data(), r.size());
}
template <int P, int V>
KernelView<const double> kernel_view(const Rows<P, V>& r) {
  return KernelView<const double>(r.data(), r.size());
}
inline KernelView<const double> kernel_view(const PositionRowsView& r) {
  return KernelView<const double>(r.data(), r.size());
}

}  // namespace shellfrac::solver
