// geometry.h — the small vector arithmetic of the resolver (doubles, component-wise as
// written: every function rounds exactly as its one-line body says) and its stopwatch.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "pdd/mesh.h"
#include "../binary_scale.h"

namespace pdd::mesh::detail {

inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3d scaled(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline void add_to(Vec3d& a, const Vec3d& b) {
  for (int k = 0; k < 3; ++k) a[k] += b[k];
}
// p + s d, component-wise (one rounding per component).
inline Vec3d moved_by(const Vec3d& p, double s, const Vec3d& d) {
  return {p[0] + s * d[0], p[1] + s * d[1], p[2] + s * d[2]};
}
inline bool finite(const Vec3d& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }
// a / |a|, or nullopt when a is zero or not finite. Taken on a scaled by the power of two that
// brings its largest |component| into [1/2, 1): the same bits wherever a.a is a normal double,
// and a result where it is not (a cross product of edges ~L^2 has a.a ~L^4, out of the double
// range for a mesh of size L beyond ~1e+-77).
inline std::optional<Vec3d> unit(const Vec3d& a) {
  if (!finite(a)) return std::nullopt;
  const double m = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2])});
  if (!(m > 0)) return std::nullopt;
  const Vec3d b = scaled(a, std::ldexp(1.0, -binary_exponent(m)));
  return scaled(b, 1 / std::sqrt(dot(b, b)));
}
// The largest squared edge length of the two tetrahedra.
inline double longest_edge2(const TetVertices& A, const TetVertices& B) {
  double edge = 0;
  for (const auto& e : kEdges)
    edge = std::max({edge, dot(sub(A[e[1]], A[e[0]]), sub(A[e[1]], A[e[0]])),
                     dot(sub(B[e[1]], B[e[0]]), sub(B[e[1]], B[e[0]]))});
  return edge;
}

// How far B must move along the unit u for its projections to clear A's: max u.s - min u.r
// (negative when they are already apart).
inline double clearance(const Vec3d& u, const TetVertices& A, const TetVertices& B) {
  double hi = -HUGE_VAL, lo = HUGE_VAL;
  for (int i = 0; i < 4; ++i) {
    hi = std::max(hi, dot(u, A[i]));
    lo = std::min(lo, dot(u, B[i]));
  }
  return hi - lo;
}

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace pdd::mesh::detail
