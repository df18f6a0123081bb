// compensated_heights.h — internal to fast/src: the heights H*_i = n*.(x_i − o) of a candidate's
// EXACT direction n* (its face normal, or eB × eA for an edge pair), each rounded to a double
// with its own certified error bound e_i, in double-word arithmetic.
//
// Input:  a pair rescaled by power_scale.h (|coordinates| < 2) and one of its candidates c
//         (label, conA/conB, and c.n: its rounded normal, which gives the orientation).
// Output: heights hA, hB (constrained vertices share one height: exactly 0 for a face's, one
//         computed value for B's edge of an edge pair), per-height bounds eA, eB with
//         |h~_i − H*_i| <= e_i, the normal n~ rounded with a per-component bound e_n
//         (|n~_k − n*_k| <= e_n), and false when not applicable (a parallel edge pair, whose
//         normal has another formula; a non-finite or vanishing value).
//
// Why: the double heights of the engine carry errors of the order u L³ (value_bounds.h:
// E3/4), which no bound can shrink: the normal itself is rounded. Along a shallow contact
// (depth ~1e-9 of the size) that is ~1e-7 of the value, and pdd2_accel1 went to rationals (~20
// us a pair, 9 in 10^4 of the paper's pairs). Here every height is within u|H*| plus a u²
// term of the exact one, so the heights that matter near the plane (value_bounds.h's tight
// case) are accurate to their own size. Written by hand: the few double-word operations
// below, not a library (no Debian package offers them), each with its bound derived here.
//
// Double-word arithmetic (u = 2^-53; x = xh + xl with |xl| <= u|xh|, "normalised"):
//   two_sum(a, b) = (s, e), s + e = a + b exactly (Knuth; no overflow at these magnitudes);
//   two_prod(a, b) = (p, e), p + e = a b exactly (e = fma(a, b, −p)) unless e underflows:
//     then off by <= 2^-1075, covered by an absolute 2^-1040 in every e_i (below);
//   mul(x, y): (ch, c1) = two_prod(xh, yh); t0 = xl yl; t1 = fma(xh, yl, t0);
//     c2 = fma(xl, yh, t1); c3 = c1 + c2; two_sum(ch, c3). Error <= 6.2u² |xh| |yh|:
//     |xl yl| <= u²|xh yh| (t0's rounding: u³); t1 errs by <= u |xh yl + t0| <= u²(1 + u)
//     |xh yh|; c2 by <= u |xl yh + t1| <= 2u²(1 + u) |xh yh|; c3 by <= u (|c1| + |c2|) <= u
//     (u + 2u(1 + u)) |xh yh| < 3.1 u² |xh yh|; two_sum exact: < 6.2 u² in all;
//   add(x, y): (sh, s1) = two_sum(xh, yh); v = xl + yl; w = s1 + v; two_sum(sh, w). Error
//     <= 4u² (|xh| + |yh|): v errs by <= u (|xl| + |yl|) <= u² (|xh| + |yh|), w by <= u (|s1|
//     + |v|) <= u (u |sh| + u (|xh| + |yh|)(1 + u)) <= 2.1 u² (|xh| + |yh|); two_sum exact.
//   Both results are normalised (two_sum's).
// The normal, componentwise n_z = e1x e2y − e1y e2x on differences taken exactly (two_sum):
//   two products (6.2 u² each of its magnitude) and an add (4u² (|p1| + |p2|)):
//   |n~_z − n*_z| <= 10.3 u² N_z, N_z = |e1x e2y| + |e1y e2x| (magnitudes from the high parts,
//   within (1 + u)² of the exact ones: absorbed in the rounding up to 10.5 below).
// A height h = n.d (d = x − o exact): three products, each off by 6.2 u² |n_k||d_k| plus
//   |n_k error| |d_k| <= 10.5 u² N_k |d_k|, and two adds (4u² of the running magnitudes each):
//   <= (6.2 + 10.5 + 8) u² M (1 + 2u) < 25 u² M, M = sum_k N_k |d_k| (|n_k| <= N_k (1 + O(u))).
//   Rounding the double word to its high part adds u |h~|. So e_i = u |h~_i| + 25 u² M_i,
//   computed with a factor (1 + 2^-40) over the few roundings of these products and sums, and
//   the absolute 2^-1040 (at most ~40 underflowed two_prod errors of 2^-1075, each multiplied
//   by factors < 8 at these magnitudes).
// The normal rounded to doubles: |n~_k − n*_k| <= u |n~_k| (1 + u) + 10.5 u² N_k =: <= e_n.
#pragma once

#include "kernel/candidate_directions.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

struct CompensatedHeights {
  double hA[4], hB[4];
  double eA[4], eB[4];
  double n[3], nn, e_n;
};

// false when not applicable (see above); c must be a candidate of (A, B) as given.
bool compensated_heights(const TetVertices& A, const TetVertices& B, const Candidate& c,
                         CompensatedHeights& out);

}  // namespace pdd::fast::detail
