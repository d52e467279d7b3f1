#pragma once
/// \file quadrature.hpp
/// Quadrature rules (theory.md §1.3). Triangle weights include the master area 1/2, so sum(w) = 1/2.
///  * tri6: 6-point degree-4 rule (Strang-Fix / Dunavant): full integration for P2 (mass matrix exact for
///    affine elements); the default area rule.
///  * tri7: 7-point degree-5 rule (Radon).
///  * edge3: 3-point Gauss-Legendre on s in [0, 1], exact to degree 5; weights sum to 1.
#include <Kokkos_Macros.hpp>

namespace shellfrac::disc {

/// A triangle rule: points xi[q] = {xi1, xi2} and weights w[q] (sum 1/2).
struct TriangleRule {
  int num_points;
  double xi[7][2];
  double w[7];
};

namespace detail {
constexpr double a6 = 0.445948490915965, wa6 = 0.223381589678011 / 2;
constexpr double b6 = 0.091576213509771, wb6 = 0.109951743655322 / 2;
constexpr double a7 = 0.470142064105115, wa7 = 0.132394152788506 / 2;
constexpr double b7 = 0.101286507323456, wb7 = 0.125939180544827 / 2;
}  // namespace detail

/// 6-point, degree-4 triangle rule.
constexpr TriangleRule tri6_rule{6,
                                 {{detail::a6, detail::a6},
                                  {1 - 2 * detail::a6, detail::a6},
                                  {detail::a6, 1 - 2 * detail::a6},
                                  {detail::b6, detail::b6},
                                  {1 - 2 * detail::b6, detail::b6},
                                  {detail::b6, 1 - 2 * detail::b6},
                                  {0, 0}},
                                 {detail::wa6, detail::wa6, detail::wa6, detail::wb6, detail::wb6, detail::wb6, 0}};

/// 7-point, degree-5 triangle rule.
constexpr TriangleRule tri7_rule{7,
                                 {{1.0 / 3, 1.0 / 3},
                                  {detail::a7, detail::a7},
                                  {1 - 2 * detail::a7, detail::a7},
                                  {detail::a7, 1 - 2 * detail::a7},
                                  {detail::b7, detail::b7},
                                  {1 - 2 * detail::b7, detail::b7},
                                  {detail::b7, 1 - 2 * detail::b7}},
                                 {0.225 / 2, detail::wa7, detail::wa7, detail::wa7, detail::wb7, detail::wb7,
                                  detail::wb7}};

/// 3-point Gauss-Legendre rule on [0, 1].
struct EdgeRule {
  int num_points;
  double s[3];
  double w[3];
};
/// sqrt(15)/10 = 0.3872983346207417
constexpr EdgeRule edge3_rule{3, {0.5 - 0.3872983346207417, 0.5, 0.5 + 0.3872983346207417}, {5.0 / 18, 8.0 / 18, 5.0 / 18}};

}  // namespace shellfrac::disc
