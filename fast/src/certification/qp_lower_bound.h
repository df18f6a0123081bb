// qp_lower_bound.h — internal to fast/src: certified lower bounds of the per-direction QP value
// (definitions §5, direction_qp.h) of every candidate of a quick list, from its heights alone, by
// weak duality. They prune the sweeps of deformable_depth.cpp: on the paper's pairs a sweep then
// solves ~1.7 QPs instead of ~8 (the plain bound coeff·delta² is the k = m = 1 case below).
//
// Input:  a quick list's lanes (quick_lanes, quick_candidates.h): the 8 faces' heights and the
//         36 edge pairs' lanes, every filter verdict clear (so no parallel pair).
// Output: for one case, per entry e (faces e = f < 8; edge lane i, orientation s: e = 8 + 2i +
//         [s = −1], the quick list's `src`, so entries ascend in canonical order),
//         lo[e] <= the EXACT value of that candidate's QP:
//           QpCase::Static      case 1 (A static); +inf on an undecidable edge pair (infeasible,
//                               definitions §5);
//           QpCase::Deformable  case 2 and the relaxed case 2 (the same bound serves both);
//         +inf for an entry that is not a candidate (the discarded orientation of a decided
//         edge pair, padding lanes); 0 when nothing can be certified (never NaN).
//
// ---- The bound (proof). Write F for the n-scaled cost of direction_qp.h, value = F/(20 n.n),
// M = I + J (4x4, F = sum over moving tetrahedra of T^T M T), M^-1 = I − J/5. Relaxed case 2:
// min F s.t. H_i + T_i <= C (A), H_j + T_j >= C (B). For multipliers l, m >= 0 with
// sum l = sum m (so that C drops out) the Lagrangian's minimum over (T, C) is the dual value
//     g(l, m) = l.H_A − m.H_B − (l^T M^-1 l + m^T M^-1 m)/4,   l^T M^-1 l = |l|² − (sum l)²/5,
// and weak duality gives F >= g for every such (l, m). Take l = s w_A, m = s w_B with weights
// w >= 0 of sum 1: g = s Δ − s² κ/4, Δ = w_A.H_A − w_B.H_B, κ = |w_A|² + |w_B|² − 2/5 > 0;
// the best s = 2Δ/κ gives F >= Δ²/κ (for Δ > 0). Uniform weights on A's k highest and B's m
// lowest vertices (any choice of index sets is valid, so choosing them by the computed heights
// is fine): Δ = mean of k − mean of m, κ = (5 − k)/(5k) + (5 − m)/(5m), and
//     value >= c_km Δ² / (n.n),   c_km = km / (4 (5(k + m) − 2km)),
// e.g. c_11 = 1/32 (deformable_depth.h's old bound), c_22 = 1/12, c_33 = 3/16. Case 2 with
// equality constraints, and the relaxed case 2 itself, have feasible sets inside the relaxed
// one, so the bound holds for both (pdd2 and pdd2_relaxed).
// Case 1 (A static): A does not move, C >= H_i (A); only B's term is quadratic, so with l on A's
// highest vertex a: F >= Δ²/κ_B, Δ = a − mean of m, κ_B = (5 − m)/(5m):
//     value >= c_m Δ² / (n.n),   c_m = m / (4 (5 − m)):  1/16, 1/6, 3/8, 1.
// (Case 1 with C tied to A's constrained vertices is again a subset of the relaxed problem.)
// We take k, m <= 3 in case 2 (on the paper's pairs k, m <= 4 evaluates 1.70 candidates per
// sweep, <= 3 1.76, <= 2 3.0) and m <= 4 in case 1 (1.68).
//
// ---- Rounding (proof that lo <= the exact value). value_bounds.h: every computed height is
// within e_h of the exact height of the exact candidate direction n, and |n|/|n~| lies in
// 1 ± rho_n, rho_n = sqrt(3) e_n / |n~|. Let Hm be the entry's largest |computed height|.
// A computed mean of k <= 4 heights (<= 3 additions: <= 3u·4Hm to first order, the slack below
// absorbing second order; then the product by the rounded 1/k: <= u·Hm more) is within 13 u Hm
// of the mean of the computed heights, which is within e_h of the exact heights' mean. We
// compute d = (mean_A − ε) − mean_B (case 1: mean_A = the highest computed A height): the first
// subtraction errs by <= u (Hm + ε), the second by u|d| (counted below as a relative rounding).
// With Δ the exact dual Δ of these index sets and d = d'(1 + δ), |δ| <= u:
//   d' <= Δ + (2 e_h + 26 u Hm) − ε + 1.01 u (Hm + ε)
//      = Δ + 2 e_h + 27.01 u Hm − (1 − 1.01u) ε <= Δ,
// because ε is computed as 2.0002 e_h + 32 u Hm (+ 2^-1000, below), >= 2.0001 e_h + 31.9 u Hm
// after its roundings.
// Hence when d > 0,  exact value >= c Δ²/(n.n) >= c d'² / (n~.n~ (1 + rho_n)²).
// When 3 e_n² · 2^23 <= n~.n~ (tested; else lo = 0), rho_n <= 2^-11.5 < 3.46e-4 and
// (1 + rho_n)^-2 >= 1 − 6.92e-4. The computed lo = fl(fl(c) fl(d²)) · fl(fl(0.999) / fl(n~.n~))
// carries 11 roundings beyond d: c's, the square's, the product's, the constant's, the
// division's, the last product's, d's own (1 + δ) squared, and the three of the dot product
// n~.n~ (its rounded value is also what the rho_n test sees: a relative 3u, absorbed as well):
// lo <= 0.999 (1 + 12u) c d'² / n~.n~ < (1 − 6.92e-4) c d'² / n~.n~ <= the exact value.
// (The largest lo / exact value measured on ~670k entries of adversarial families is
// 0.999000000: in the tight cases the safety factor is the whole margin.)
// Range: the quick list only exists on the rescaled pair (power_scale.h: |coordinates| < 2, so
// no overflow: heights < 2^10, n.n < 2^12). Underflow: ε also carries + 2^-1000, which covers
// every absolute error of a subnormal result in ε and in the means (each <= 2^-1075); and d is
// used only when d > 2^-500, so d², c d² (>= 2^-1005) and c d² / n.n (>= 2^-1017) are normal and
// the relative roundings above hold. A smaller d gives lo = 0.
// NaN anywhere gives lo = 0 (comparisons written so that NaN fails them).
// Written by hand: it is a closed form over eight numbers per lane, vectorised with the lanes.
#pragma once

#include "kernel/quick_candidates.h"

namespace pdd::fast::detail {

inline constexpr int kQpEntries = 8 + 2 * kLanes;  // faces, then (lane, ±n): the list's src
inline constexpr double kLowerSafety = 0.999;

enum class QpCase { Static, Deformable };  // case 1; case 2 and relaxed case 2

// lo[e] of entry e (faces, then lane i's +n at 8 + 2i and −n at 9 + 2i: canonical order).
struct QpLowerBounds {
  alignas(64) double lo[kQpEntries];
};

// Fills `out` for one case from q's faces and lanes (q from quick_lanes or quick_candidates).
void qp_lower_bounds(const QuickCandidates& q, QpCase which, QpLowerBounds& out);

// The entries' split at t, in one vectorised pass: how many have lo <= t, and the smallest lo
// above t (+inf when none).
struct QpSplit {
  int below;
  double above;
};
QpSplit split_at(const QpLowerBounds& b, double t);

}  // namespace pdd::fast::detail
