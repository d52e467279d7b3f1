#pragma once
/// \file closest_point.hpp
/// The point of a triangle nearest to a point, with its barycentric coordinates (docs/theory.md §12.5): the
/// contact law's distance from a DG node to another element's mid-surface. Face, edge and vertex regions are
/// told apart by the signs of the usual dot products (C. Ericson, Real-Time Collision Detection, 2005, §5.1.5),
/// so a point beyond an edge or a corner gets the nearest point on that edge or corner: the distance is continuous
/// everywhere and its gradient is continuous wherever the nearest point is unique.

namespace shellfrac::solver {

/// The nearest point y = w0 a + w1 b + w2 c of triangle (a, b, c) to p: its weights (w >= 0, sum 1).
struct TrianglePoint {
  double w[3];
};

inline TrianglePoint closest_point_on_triangle(const double* p, const double* a, const double* b, const double* c) {
  double ab[3], ac[3], ap[3];
  for (int i = 0; i < 3; ++i) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {{1, 0, 0}};  // vertex a
  double bp[3];
  for (int i = 0; i < 3; ++i) bp[i] = p[i] - b[i];
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {{0, 1, 0}};  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge ab
    const double v = d1 / (d1 - d3);
    return {{1 - v, v, 0}};
  }
  double cp[3];
  for (int i = 0; i < 3; ++i) cp[i] = p[i] - c[i];
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {{0, 0, 1}};  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge ac
    const double w = d2 / (d2 - d6);
    return {{1 - w, 0, w}};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge bc
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {{0, 1 - w, w}};
  }
  if (!(va + vb + vc > 0)) return {{1, 0, 0}};  // a degenerate (zero-area) triangle: its first vertex
  const double denom = 1 / (va + vb + vc);  // inside the face
  const double v = vb * denom, w = vc * denom;
  return {{1 - v - w, v, w}};
}

}  // namespace shellfrac::solver
