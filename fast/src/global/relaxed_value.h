// relaxed_value.h — internal to fast/src/global: the relaxed value along one normal, in
// doubles with a certified error bound, or in rationals.
//
// Input : the pair (A, B), or its Problem (coordinates relative to A[0] rounded once, and about
//         the centroid), and a normal v (A -> B, any length).
// Output: relaxed_at: relaxed(v) = cost(h) / (20 v.v), cost the closed form of direction_qp.h
//         on the heights h_i = v.(x_i - A[0]) (its solution, max |h| and the heights on demand);
//         value_error: relaxed_at's certified relative error (value_bounds.h's QP bound);
//         relaxed_exact: the same closed form in rationals along the exact v;
//         evaluate_tight: relaxed(v) on heights relative to A's highest vertex along v, with a
//         tighter bound where the depth is far below the pair's size, and where that bound
//         still exceeds kGlobalRel, on compensated heights (relaxed_compensated,
//         deformable_depth.h); error +inf when both fail.
// kGlobalRel: the error budget of a reported pdd2_global (definitions §8's 1e-9, with room).
#pragma once

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

#include "exact/exact_candidate.h"
#include "exact/exact_geometry.h"
#include "global/vec3.h"
#include "pdd/tet_pair.h"
#include "qp/deformable_depth.h"
#include "qp/direction_qp.h"
#include "qp/direction_qp_impl.h"

namespace pdd::fast::global {

inline constexpr double kGlobalRel = 1e-10;  // value error budget (definitions §8's 1e-9, with room)

struct Problem {
  V3 relA[4], relB[4];  // x - A[0] (rounded once): heights for the evaluations
  V3 pA[4], pB[4];      // about the centroid: the enumeration's geometry
  double scale = 0;     // max |relA|, |relB| component
};

// The pair's Problem (each coordinate difference rounded once, the centroid in doubles).
inline Problem problem_of(const TetVertices& A, const TetVertices& B) {
  Problem P;
  V3 centroid{0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      P.relA[i][k] = A[i][k] - A[0][k], P.relB[i][k] = B[i][k] - A[0][k];
      P.scale = std::max({P.scale, std::fabs(P.relA[i][k]), std::fabs(P.relB[i][k])});
      centroid[k] += (P.relA[i][k] + P.relB[i][k]) / 8;
    }
  for (int i = 0; i < 4; ++i) P.pA[i] = sub(P.relA[i], centroid), P.pB[i] = sub(P.relB[i], centroid);
  return P;
}

// relaxed(v) = cost / (20 v.v) by direction_qp.h's closed form on heights relative to A[0].
// (hA, hB: the heights, when wanted.)
inline double relaxed_at(const Problem& P, const V3& v, DirectionSolution* sol = nullptr, double* hmax = nullptr,
                         double* hA_out = nullptr, double* hB_out = nullptr) {
  double local[8];
  double *hA = hA_out ? hA_out : local, *hB = hB_out ? hB_out : local + 4, hm = 0;
  for (int i = 0; i < 4; ++i) {
    hA[i] = dot(v, P.relA[i]), hB[i] = dot(v, P.relB[i]);
    hm = std::max({hm, std::fabs(hA[i]), std::fabs(hB[i])});
  }
  const DirectionSolution s = solve_relaxed(hA, hB);
  if (sol) *sol = s;
  if (hmax) *hmax = hm;
  return s.cost / (20.0 * dot(v, v));
}

// relaxed(v) in rationals (the exact closed form along the exact normal v), with its solution;
// v a double normal or a rational one (suspect_proof.h's witnesses).
using QNormal = std::array<detail::Q, 3>;
detail::Q relaxed_exact(const TetVertices& A, const TetVertices& B, const V3& v, detail::Q hA[4],
                        detail::Q hB[4], Solution<detail::Q>& s);
detail::Q relaxed_exact(const TetVertices& A, const TetVertices& B, const QNormal& v, detail::Q hA[4],
                        detail::Q hB[4], Solution<detail::Q>& s);

// The certified relative error of relaxed_at's value along v (value_bounds.h's QP bound):
// heights rel = x - A0 rounded (u |rel|) then a dot product (3 u sum |v_k rel_k|), so
// e_h <= 5 u |v|_1 scale; the closed form's T within dT = 2^12 u Hm; |Phi~ - Phi| <= 2 e_h +
// sqrt(2) dT + 4 u Phi~ with Phi = sqrt(cost / 20); the value Phi^2 / v.v (v.v to 3u) has
// relative error <= 2 r + 8u, r = |Phi~ - Phi| / Phi~. +inf when Phi~ = 0.
inline double value_error(const Problem& P, const V3& v, double cost, double hm) {
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double phi = std::sqrt(cost / 20.0);
  if (!(phi > 0)) return INFINITY;
  const double r = (2 * 5 * kU * vn1 * P.scale + std::sqrt(2.0) * 0x1p12 * kU * hm) / phi + 4 * kU;
  return 2 * r + 8 * kU;
}

// A certified upper bound on the exact relaxed value along v whatever value_error's relative
// bound (which is +inf at Phi~ = 0 and loses its meaning above 1/100): from value_error's
// chain, Phi <= Phi~ (1 + 4u) + 2 e_h + sqrt(2) dT, and the value Phi^2 / v.v with v.v computed
// to 3u. Phi_up below is that sum inflated by (1 + 16u) (its four roundings, and those of e_h
// and dT's products, each <= u); its square over the computed v.v, times (1 + 3u) for v.v and
// 2u for the square and the quotient, is covered by the final (1 + 8u) rounded up by one more
// rounding of the product (< u). For a depth far below the pair's size (Phi~ ~ the depth, e_h
// and dT ~ u times the size) the bound is ~(2^12 u size)^2: a depth bound, not the value.
// +inf where v.v, the square or the bound is below the normal range (their rounding would
// exceed the slack).
inline double value_upper(const Problem& P, const V3& v) {
  DirectionSolution s;
  double hm = 0;
  relaxed_at(P, v, &s, &hm);
  const double vn1 = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
  const double phi = std::sqrt(std::max(s.cost, 0.0) / 20.0);
  const double phi_up =
      (phi * (1 + 4 * kU) + 2 * 5 * kU * vn1 * P.scale + std::sqrt(2.0) * 0x1p12 * kU * hm) * (1 + 16 * kU);
  const double vv = dot(v, v), square = phi_up * phi_up;
  const double upper = square / vv * (1 + 8 * kU);
  return vv >= DBL_MIN && square >= DBL_MIN && upper >= DBL_MIN ? upper : INFINITY;
}

// The relaxed value along v (a double normal, A -> B) with a certified relative error bound,
// on heights relative to A's highest vertex along v (near the plane), so that value_bounds.h's
// tight case applies: when every vertex's KKT margin at the computed solution exceeds 2 dT,
// dT = 2^9 u Ha with Ha = max(|C|, |heights of the vertices at the plane|) ~ |v| depth, instead
// of value_error's 2^12 u max|H| ~ |v| size. Heights: x - o rounded (u |x - o| <= 2u scale per
// coordinate) then a dot product: e_h <= 10 u |v|_1 scale; then value_error's chain: r =
// (2 e_h + sqrt(2) dT) / Phi~ + 4u, error 2 r + 8u. error = +inf when a margin fails.
struct Evaluation {
  double value = INFINITY, error = INFINITY;
  DirectionSolution sol;
  double hA[4], hB[4];
};
Evaluation evaluate_tight(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v);
// evaluate_tight for a caller that keeps only values <= wanted (with error <= kGlobalRel): the
// double heights' path is skipped where its bound could certify no such value (a contact far
// shallower than the pair's size, where its error ~u size / depth exceeds kGlobalRel). Either
// path's result is certified; where the double one is skipped, only values the caller keeps
// could differ.
Evaluation evaluate_below(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v, double wanted);
// The same along the double-word normal v + lo (|lo_k| <= u |v_k|; lo = 0: evaluate_tight), on
// compensated heights only (the double heights cannot see lo).
Evaluation evaluate_tight(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v, const V3& lo);

}  // namespace pdd::fast::global
