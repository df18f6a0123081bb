// value_bounds.h — certified error bounds on the fast engine's values, and the definitions §8 test.
//
// Input:  one candidate as the engine computed it (heights H~, D~, n~, n~.n~, its degree class),
//         the pair's filter bounds (filter_bounds.h) and a computed value.
// Output: r, a bound on the relative error of sqrt(value) against the exact value of the exact
//         candidate:  |sqrt(v~) − sqrt(v)| <= r sqrt(v~); hence v lies in [v~(1−r)², v~(1+r)²].
//         certified_choice() turns such intervals into the definitions §8 verdict for a minimum.
//
// Every value is root(v) = Phi / |n| with Phi = |D| (rigid) or Phi = sqrt(F/20) (a QP, F its
// n-scaled cost, direction_qp.h), both functions of the unnormalised heights H = n.(x − o).
// ---- Heights. Of an edge pair: triple products (filter_bounds.h: error <= 48 u L³) or a sum of
//   two of them (<= 2·48 + 12 = 108 u L³); of a face: a triple product or −|det| (<= 48 u L³).
//   Constrained heights are set equal by construction and are exactly equal in exact arithmetic
//   (n ⟂ the constrained edge or face), so their common error is one error. Parallel edge pairs
//   (n = (e.e)w − (w.e)e, degree 3): heights of degree 4, error <= 270 u L⁴ (filter_bounds.h).
//   So every height has error <= e_h = E3/4 (E4/4 for a parallel pair).
//   Nearly parallel edge pairs (n~ below kExactNormalBelow E2, n exactly non-zero): n is taken
//   exactly (expansion.h) and rounded, n~_k within 3u|n_k| (a nonoverlapping expansion summed in
//   increasing order: its tail is below 2u of its largest term), and the heights are computed
//   along n~ (candidate_directions.cpp, near_parallel_normal): with L the pair's extent, each
//   difference within u of itself and <= L, the dot product within 3.01u |n~|_1 L, the change
//   from n to n~ within 3u(1 + 4u)|n~|_1 L: error <= 7.1 u |n~|_1 L <= e_h = 16 u |n~|_1 L, and
//   e_n = 4 u max|n~_k| (own_degree_bounds). These bounds are relative to |n|, where E2, E3
//   are absolute: they certify the direction that rounding noise dominates in doubles.
// ---- Direction. Components of n~ have error <= e_n = E2 (E3 for a parallel pair), so
//   | |n~| − |n| | <= sqrt(3) e_n and |n|/|n~| lies in 1 ± rho_n, rho_n = sqrt(3) e_n/|n~|.
// ---- Rigid. D = max hA − min hB (one rounding): |D~ − D| <= 2 e_h + u|D~|.
// ---- QP (Lipschitz in the heights, proof). Every variant's constraints read H_i + T_i <= C,
//   H_j + T_j >= C or with '=', with C free or (case 1) tied to A's heights. Given an optimum
//   (T, C) for heights H, and H' with |H'_i − H_i| <= e: (T − (H' − H), C) is feasible for H'
//   when C is free or tied to constrained heights (which move together); in case 1 with C_A
//   empty (VF) take C' = C + e and T'_j = T_j + e − (H'_j − H_j) (|shift| <= 2e). The cost is
//   a squared norm, F/20 = sum_tets (|T|² + (sum T)²)/20, and one tetrahedron's shift vector s
//   with |s_i| <= 2e has (|s|² + (sum s)²)/20 <= (16 + 64)e²/20 = 4e². So
//   |Phi(H') − Phi(H)| <= 2 e (one moving tetrahedron shifted by <= 2e, or two by <= e each:
//   sqrt(2) e). The same holds with H and H' exchanged.
// ---- QP (the closed form in doubles, src/qp/direction_qp_impl.h). With Hm = max |H~_i| (heights
//   relative to a vertex of the candidate), every sum P, X has at most 5 terms <= Hm, the root C
//   is an average of heights and every displacement T = C − H or −S is <= 2 Hm. Each is computed
//   with error <= 64 u Hm when every branch goes the exact way. A branch (breakpoint test) can go
//   the other way only when its exact test value is within its rounding error
//   (<= 10 u · 560 Hm) of 0; the solution is continuous across a breakpoint and the balance
//   function G(C) = S_A + S_B has slope >= 1/4 there, so the adjacent region's closed form
//   moves C by at most 2 · (5600 u Hm / 25) · 4 = 1792 u Hm and T by twice that. Hence every
//   T~ is within dT = 2^12 u Hm of the exact optimum's T for the heights H~.
//   Tight case: when every free vertex's KKT margin at the computed solution (C − H + S, whose
//   sign is its status) exceeds 2 dT, the exact solution's margins (within 2 dT of these) have
//   the same signs (and no branch went the other way: one that did leaves the flipped vertex's
//   margin within about 20 · 5600/25 = 4480 u Hm < 2 dT of zero), so the
//   statuses are the exact ones and only the fixed closed form of that
//   region is rounded. That closed form involves only the heights of the constrained and the
//   active free vertices (the final sums P are added afresh over them, not carried through the
//   walk: src/qp/direction_qp_impl.h), so with Ha = max(|C~|, those |H~|): P (<= 4 terms <= Ha,
//   one integer product) to 15 u Ha; the root C = (P_A(5 − m_B) + P_B(5 − m_A))/den (den >= 4)
//   to 60 u Ha; each C − H of an active vertex to 62 u Ha; the sums s1 (<= 5 terms <= 2 Ha)
//   to 350 u Ha, so S = s1/(5 − m) and every T to 360 u Ha: dT = 2^9 u Ha. Inactive vertices
//   (far from the plane) enter only through their margins, whose signs are certain.
//   (src/qp/deformable_depth.cpp decides which case applies and computes Ha.) Ha is about
//   |n| PD_d for a shallow contact while Hm is about |n| L, so the tight bound is what lets
//   shallow contacts (PD_d << L) be certified in doubles. In both cases, since
//   sqrt(F) is a weighted Euclidean norm of T (weights I + J, norm <= 5, 8 entries):
//   |Phi~ − Phi(H~)| <= sqrt(40/20) dT + 4 u Phi~  (the last term: rounding of the norm).
// ---- Value. root(v~) = Phi~/|n~| (1 ± 3u): with a = |Phi~ − Phi|/Phi~ and rho_n both <= 1/100,
//   |root(v~) − root(v)| <= 1.02 (a + rho_n + 4u) root(v~) (second-order terms absorbed).
//   A bound that is not below 1/100 returns +inf (the caller takes the exact path).
// These bounds assume the filter range of filter_bounds.h (no overflow, negligible underflow);
// the engine rescales every pair by a power of two into it (solve_pair.cpp) or takes the exact
// path. They are checked against the exact path by the differential fuzzer (fuzz/) and tests.
#pragma once

#include <cmath>
#include <limits>

#include "certification/filter_bounds.h"

namespace pdd::fast {

inline constexpr double kContractRel = 1e-9;  // definitions §8
// Certified values must sit in an interval of relative width kCertifyRel: the reported value
// v~ and the exact minimum then differ by <= kCertifyRel (1 + kCertifyRel) < kContractRel.
inline constexpr double kCertifyRel = 0.9e-9;
inline constexpr double kSolverDisplacementCoeff = 4096.0;  // dT = 2^12 u Hm, see above
inline constexpr double kSolverDisplacementCoeffTight = 512.0;  // dT = 2^9 u Ha, see above

struct DegreeBounds {
  double e_h;  // per-height error
  double e_n;  // per-component error of n
};
inline DegreeBounds degree_bounds(const FilterBounds& fb, bool parallel) {
  return parallel ? DegreeBounds{fb.deg4 / 4, fb.deg3} : DegreeBounds{fb.deg3 / 4, fb.deg2};
}
// A candidate's class: generic, parallel, or nearly parallel with its own bounds.
template <class C>
inline DegreeBounds degree_bounds_of(const FilterBounds& fb, const C& c) {
  return c.own_bounds ? DegreeBounds{c.own_eh, c.own_en} : degree_bounds(fb, c.parallel);
}

// Which edge pairs take their normal exactly (candidate_directions.cpp's near_parallel_normal,
// own_degree_bounds below): those whose computed n has every component <= kExactNormalBelow E2.
// With the filter bounds their direction would be off by rho = sqrt(3) E2 / |n~| >= 2^-34
// relative, beside definitions §8's 9e-10 budget for the whole value (kCertifyRel): such a pair
// could not be certified as the minimum, nor ordered against it (edges parallel up to a mesh
// generator's noise, ~1e-12, not the doubles' 1e-16). Random pairs meet one about once in 10^5
// (an angle below ~0.03 degrees between edges of the pair's size).
inline constexpr double kExactNormalBelow = 0x1p34;

// The nearly parallel edge pair's bounds (see above): n~ its rounded exact normal, L the extent.
inline DegreeBounds own_degree_bounds(const double* n, double L) {
  const double a0 = std::fabs(n[0]), a1 = std::fabs(n[1]), a2 = std::fabs(n[2]);
  const double mx = a0 > a1 ? (a0 > a2 ? a0 : a2) : (a1 > a2 ? a1 : a2);
  return DegreeBounds{16 * kUnitRoundoff * ((a0 + a1 + a2) * L), 4 * kUnitRoundoff * mx};
}

inline double finish_root_rel(double a, double nn, double e_n) {
  const double rho = std::sqrt(3.0) * e_n / std::sqrt(nn);
  if (!(a <= 0.01 && rho <= 0.01)) return std::numeric_limits<double>::infinity();
  return 1.02 * (a + rho + 4 * kUnitRoundoff);
}

// Rigid: v~ = D~²/(n~.n~).
inline double rigid_root_rel(double D, double nn, const DegreeBounds& b) {
  const double aD = std::fabs(D);
  return finish_root_rel((2 * b.e_h + kUnitRoundoff * aD) / aD, nn, b.e_n);
}

// A QP value v~ = F~/(20 n~.n~); (coeff, Hm): (kSolverDisplacementCoeff, Hm), or
// (kSolverDisplacementCoeffTight, Ha) when the solution's statuses are certain (see above).
inline double qp_root_rel(double F, double nn, double Hm, const DegreeBounds& b,
                          double coeff = kSolverDisplacementCoeff) {
  const double phi = std::sqrt(F / 20);
  const double dT = coeff * kUnitRoundoff * Hm;
  return finish_root_rel((2 * b.e_h + std::sqrt(2.0) * dT) / phi + 4 * kUnitRoundoff, nn, b.e_n);
}

// Cheap test, products only, for deferring qp_root_rel (two square roots, two divisions) and
// the solver bound it needs: true only when qp_root_rel(F, nn, H', b, coeff') is finite and
// < 0.0195 for every (coeff', H') with coeff' H' <= coeff H, so that
// lower_of(F/(20 nn), it) >= (1 − 0.0195)² (1 − 3u) v > 0.9613 v (three roundings). Proof:
// dT' = coeff' u H' <= dT (coeff', u powers of two: exact scalings). X = 2 e_h + 1.5 coeff u H
// (computed; >= the computed 2 e_h + sqrt(2) dT' up to 2u relative, as 1.5 > sqrt(2)(1 + 4u)) and
// X² · 222000 <= F give X²/(F/20) <= 20/222000, i.e. X/phi <= 0.009492 (phi = sqrt(F/20)); with
// the few roundings of qp_root_rel its a is <= 0.0095 < 0.01. 3 e_n² · 11100 <= nn gives
// rho = sqrt(3) e_n/sqrt(nn) <= 0.009492, computed <= 0.0095 < 0.01. So the bound is finite
// and 1.02 (a + rho + 4u)(1 + 3u) < 0.0195. (NaN F or nn: false.) kSmallQpLower · v
// (computed: <= 0.96 (1 + u) v < 0.9613 v) is then below lower_of(v, that bound).
// Used with the wide solver bound (coeff = kSolverDisplacementCoeff, H = Hm): the tight one
// has coeff' H' = 512 Ha <= 4096 Hm (Ha <= max(|C|, Hm) and the root C is a weighted average
// of heights, |C| <= Hm (1 + 20u)), so the test covers whichever of the two applies.
inline constexpr double kSmallQpLower = 0.96;
inline bool qp_root_rel_small(double F, double nn, double H, const DegreeBounds& b,
                              double coeff = kSolverDisplacementCoeff) {
  const double X = 2 * b.e_h + 1.5 * coeff * kUnitRoundoff * H;
  return (X * X * 222000.0 <= F) & (3 * b.e_n * b.e_n * 11100.0 <= nn);
}

// A products-only test that qp_root_rel, for any solver bound covered as above (coeff' H' <=
// coeff H), is <= kTinyQpRoot: for a single candidate's value where only its own interval
// matters (pdd2_accel(A, B, 1): certified_choice(upper_of(v, r), lower_of(v, r)) holds for r up to
// ~2.2e-10, and (1 + 1.1e-10)²/(1 − 1.1e-10)² < 1 + 4.5e-10), it saves the solver bound's
// loop and qp_root_rel's two square roots and two divisions. Proof (the notation of
// qp_root_rel_small, whose rounding argument it repeats): X = 2 e_h + 1.5 coeff u H (computed)
// >= the computed 2 e_h + sqrt(2) dT'. X² · 8.4e21 <= F (8.4e21 = 21·5^20·2^22 and 1.25e21 =
// 5^22·2^19 are exact doubles; three roundings) gives X/phi <= sqrt(20/8.4e21)(1 + 2u) =
// 4.8795e-11 (1 + 2u), so its a <= 4.8796e-11 after qp_root_rel's roundings; e_n² · 1.25e21 <=
// nn gives rho = sqrt(3) e_n/sqrt(nn) <= sqrt(3/1.25e21)(1 + 2u) = 4.8990e-11 (1 + 2u), computed
// <= 4.8991e-11. Both <= 0.01: r = 1.02 (a + rho + 4u) (three roundings)
// <= 1.02 · 9.7788e-11 (1 + 3u) < 9.975e-11 < kTinyQpRoot. lower_of and upper_of are monotone
// in r, so a verdict reached with kTinyQpRoot is one the exact bound reaches too; and with it
// the single-candidate verdict above always holds, so the verdict is the same. NaN: false.
// (No underflow: e_h², e_n² are normal on rescaled pairs, tie_and_certify_bits in
// superset_kernel.cpp.)
inline constexpr double kTinyQpRoot = 1.1e-10;
inline bool qp_root_rel_tiny(double F, double nn, double H, const DegreeBounds& b,
                             double coeff = kSolverDisplacementCoeff) {
  const double X = 2 * b.e_h + 1.5 * coeff * kUnitRoundoff * H;
  return (X * X * 8.4e21 <= F) & (b.e_n * b.e_n * 1.25e21 <= nn);
}

// Interval of the exact value from v~ and its root bound r.
inline double lower_of(double v, double r) { return r >= 1 ? 0.0 : v * (1 - r) * (1 - r); }
inline double upper_of(double v, double r) { return v * (1 + r) * (1 + r); }

// definitions §8 for a minimum over candidates: the reported candidate's exact value lies in
// [lo_k, hi_k] and every candidate's exact value is >= lo_min (lo_min <= lo_k). If
// hi_k <= (1 + kCertifyRel) lo_min, the reported v~ (lo_k <= v~ <= hi_k) and the exact minimum
// x* (lo_min <= x* <= hi_k) differ by <= kCertifyRel (1 + kCertifyRel) x*, and the reported
// label's exact value is within that of x*.
inline bool certified_choice(double hi_k, double lo_min) {
  return lo_min > 0 && hi_k <= (1 + kCertifyRel) * lo_min;
}

}  // namespace pdd::fast
