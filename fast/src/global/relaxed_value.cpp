// relaxed_value.cpp — see relaxed_value.h.
#include "global/relaxed_value.h"

#include <algorithm>
#include <cmath>

namespace pdd::fast::global {

detail::Q relaxed_exact(const TetVertices& A, const TetVertices& B, const V3& v, detail::Q hA[4],
                        detail::Q hB[4], Solution<detail::Q>& s) {
  return relaxed_exact(A, B, QNormal{detail::Q(v[0]), detail::Q(v[1]), detail::Q(v[2])}, hA, hB, s);
}

detail::Q relaxed_exact(const TetVertices& A, const TetVertices& B, const QNormal& v, detail::Q hA[4],
                        detail::Q hB[4], Solution<detail::Q>& s) {
  using detail::Q;
  const Q &v0 = v[0], &v1 = v[1], &v2 = v[2];
  for (int i = 0; i < 4; ++i) {
    hA[i] = v0 * (Q(A[i][0]) - Q(A[0][0])) + v1 * (Q(A[i][1]) - Q(A[0][1])) + v2 * (Q(A[i][2]) - Q(A[0][2]));
    hB[i] = v0 * (Q(B[i][0]) - Q(A[0][0])) + v1 * (Q(B[i][1]) - Q(A[0][1])) + v2 * (Q(B[i][2]) - Q(A[0][2]));
  }
  s = detail::solve_relaxed_heights(hA, hB);
  return s.cost / (20 * (v0 * v0 + v1 * v1 + v2 * v2));
}

namespace {

// evaluate_tight's second path: compensated heights, kept where they bound the value more
// tightly than `ev`'s error (ev: the double path's evaluation, or none).
Evaluation compensated_or(const TetVertices& A, const TetVertices& B, const V3& v, const Evaluation& ev) {
  // The heights' absolute error (~u |v| size) against a depth far below the size: compensated
  // heights (relaxed_compensated), whose error at the plane is the vertices' own u. The exact
  // value lies within v (1 +- r)^2 (value_bounds.h): relative error (2 + r) r, and 8u for the
  // roundings of these expressions.
  Evaluation tight;
  double rc = 1;
  if (relaxed_compensated(A, B, v, tight.value, rc, tight.sol, tight.hA, tight.hB) && rc < 1) {
    tight.error = (2 + rc) * rc + 8 * kU;
    if (tight.error < ev.error) return tight;
  }
  return ev;
}

}  // namespace

Evaluation evaluate_tight(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v) {
  Evaluation ev;
  int top = 0;
  for (int i = 1; i < 4; ++i)
    if (dot(v, P.relA[i]) > dot(v, P.relA[top])) top = i;
  for (int i = 0; i < 4; ++i) {
    V3 a, b;
    for (int k = 0; k < 3; ++k) a[k] = A[i][k] - A[top][k], b[k] = B[i][k] - A[top][k];
    ev.hA[i] = dot(v, a), ev.hB[i] = dot(v, b);
  }
  const DirectionSolution& sol = ev.sol = solve_relaxed(ev.hA, ev.hB);
  double Ha = std::fabs(sol.c);
  bool margins = true;
  double margin[8];
  for (int i = 0; i < 4; ++i) {
    margin[i] = sol.c - ev.hA[i] + sol.sumA;      // < 0: at the plane (active)
    margin[4 + i] = sol.c - ev.hB[i] + sol.sumB;  // > 0: at the plane (active)
    if (margin[i] < 0) Ha = std::max(Ha, std::fabs(ev.hA[i]));
    if (margin[4 + i] > 0) Ha = std::max(Ha, std::fabs(ev.hB[i]));
  }
  const double dT = 0x1p9 * kU * Ha;
  for (double m : margin) margins = margins && std::fabs(m) > 2 * dT;
  const double phi = std::sqrt(sol.cost / 20.0);
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double r = phi > 0 ? (2 * 10 * kU * vn1 * P.scale + std::sqrt(2.0) * dT) / phi + 4 * kU : INFINITY;
  ev.value = sol.cost / (20.0 * dot(v, v));
  if (margins) ev.error = 2 * r + 8 * kU;
  if (ev.error <= kGlobalRel) return ev;
  return compensated_or(A, B, v, ev);
}

Evaluation evaluate_below(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v, double wanted) {
  // The double path's error is 2 r + 8u with r >= 20 u |v|_1 scale / Phi~, and Phi~^2 =
  // value~ v.v (to a few u: 1 + 2^-40 covers it), so a value~ <= wanted that it certifies to
  // kGlobalRel has 40 u |v|_1 scale <= kGlobalRel sqrt(wanted v.v) (1 + 2^-40). Where that
  // fails, the double path would return no value the caller keeps: only the compensated one.
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double reach = kGlobalRel * std::sqrt(wanted * dot(v, v)) * (1 + 0x1p-40);
  if (!(40 * kU * vn1 * P.scale <= reach)) return compensated_or(A, B, v, Evaluation{});
  return evaluate_tight(A, B, P, v);
}

Evaluation evaluate_tight(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v, const V3& lo) {
  if (!nonzero(lo)) return evaluate_tight(A, B, P, v);
  Evaluation ev;
  double rc = 1;
  if (relaxed_compensated(A, B, v, ev.value, rc, ev.sol, ev.hA, ev.hB, lo) && rc < 1)
    ev.error = (2 + rc) * rc + 8 * kU;  // (as evaluate_tight's compensated branch)
  return ev;
}

}  // namespace pdd::fast::global
