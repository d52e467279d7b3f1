#pragma once
/// \file element_lanes.hpp
/// The element functions' data for a batch of elements in lock-step (lanes.hpp; docs/performance.md, "The
/// batched element kernel"): lane i of each batched struct is element i of the batch. Loading copies an element's
/// struct into its lane, storing copies a lane out to the element's struct; the copies are exact, so a lane
/// holds bit for bit what the element's own struct holds.
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/lanes.hpp"

namespace shellfrac::disc::lanes {

/// Lane `lane` of the n batched values b <- the n values s.
KOKKOS_INLINE_FUNCTION void load(Batch* b, const double* s, int n, int lane) {
  for (int i = 0; i < n; ++i) b[i].set(lane, s[i]);
}
/// The n values s <- lane `lane` of the n batched values b.
KOKKOS_INLINE_FUNCTION void store(const Batch* b, double* s, int n, int lane) {
  for (int i = 0; i < n; ++i) s[i] = b[i][lane];
}

/// Number of doubles in an array (of any rank) of doubles, and its first value.
template <class A>
constexpr int count_of(const A& a) {
  return int(sizeof(a) / sizeof(double));
}
template <class A>
KOKKOS_INLINE_FUNCTION const double* first_of(const A& a) {
  return reinterpret_cast<const double*>(&a);
}
template <class A>
KOKKOS_INLINE_FUNCTION double* first_of(A& a) {
  return reinterpret_cast<double*>(&a);
}
template <class A>
KOKKOS_INLINE_FUNCTION Batch* batches_of(A& a) {
  return reinterpret_cast<Batch*>(&a);
}
template <class A>
KOKKOS_INLINE_FUNCTION const Batch* batches_of(const A& a) {
  return reinterpret_cast<const Batch*>(&a);
}

/// Lane `lane` of batched array b <- array s of the same shape in double.
template <class B, class S>
KOKKOS_INLINE_FUNCTION void load_array(B& b, const S& s, int lane) {
  static_assert(sizeof(B) == sizeof(S) * batch_width, "arrays of the same shape");
  load(batches_of(b), first_of(s), count_of(s), lane);
}
template <class B, class S>
KOKKOS_INLINE_FUNCTION void store_array(const B& b, S& s, int lane) {
  static_assert(sizeof(B) == sizeof(S) * batch_width, "arrays of the same shape");
  store(batches_of(b), first_of(s), count_of(s), lane);
}

KOKKOS_INLINE_FUNCTION void load(DgElementRefOf<Batch>& b, const DgElementRef& r, int lane) {
  load_array(b.wj0, r.wj0, lane);
  load_array(b.Jinv, r.Jinv, lane);
  for (int q = 0; q < num_area_points; ++q) {
    load_array(b.ref[q].gam0, r.ref[q].gam0, lane);
    load_array(b.ref[q].rho0, r.ref[q].rho0, lane);
  }
  for (int k = 0; k < 3; ++k) {
    load_array(b.edge[k].omega, r.edge[k].omega, lane);
    load_array(b.edge[k].nu_cov, r.edge[k].nu_cov, lane);
    b.edge[k].nbr_same_direction.set(lane, r.edge[k].nbr_same_direction);
  }
  b.area.set(lane, r.area);
  load_array(b.Minv, r.Minv, lane);
  b.strains = r.strains;  // the same on every lane (the caller checks)
  b.membrane_remainder.set(lane, r.membrane_remainder);
}

KOKKOS_INLINE_FUNCTION void load(EdgeNodesOf<Batch>& b, const EdgeNodes& e, int lane) {
  load_array(b.x, e.x, lane);
  load_array(b.t, e.t, lane);
}

KOKKOS_INLINE_FUNCTION void load(DgElementNodesOf<Batch>& b, const DgElementNodes& e, int lane) {
  load_array(b.x, e.x, lane);
  load_array(b.t, e.t, lane);
  for (int k = 0; k < 3; ++k) {
    b.lift[k].set(lane, e.lift[k]);
    load(b.neighbour[k], e.neighbour[k], lane);
  }
}

KOKKOS_INLINE_FUNCTION void store(const EdgeForcesOf<Batch>& b, EdgeForces& e, int lane) {
  store_array(b.f, e.f, lane);
  store_array(b.g, e.g, lane);
}

KOKKOS_INLINE_FUNCTION void store(const EdgeTractionsOf<Batch>& b, EdgeTractions& e, int lane) {
  store_array(b.at, e.at, lane);
}

KOKKOS_INLINE_FUNCTION void store(const DgElementForcesOf<Batch>& b, DgElementForces& e, int lane) {
  store_array(b.f, e.f, lane);
  store_array(b.g, e.g, lane);
  for (int k = 0; k < 3; ++k) store(b.neighbour[k], e.neighbour[k], lane);
}

}  // namespace shellfrac::disc::lanes
