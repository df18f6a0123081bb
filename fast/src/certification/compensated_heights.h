// compensated_heights.h — internal to fast/src: the heights H*_i = n*.(x_i − o) of a candidate's
// EXACT direction n* (its face normal, or eB × eA for an edge pair), each rounded to a double
// with its own certified error bound e_i, in double-word arithmetic.
//
// Input:  a pair rescaled by power_scale.h (|coordinates| < 2) and one of its candidates c
//         (label, conA/conB). The orientation of n* is the label's (definitions §3), taken from
//         signs of double-word heights certain under the bound below: A's opposite vertex below
//         an FV face, B's above a VF one, and for a Decided edge pair the side of A's off-edge
//         vertices (Plus and Minus labels keep and flip eB × eA).
// Output: heights hA, hB (constrained vertices share one height: exactly 0 for a face's, one
//         computed value for B's edge of an edge pair), per-height bounds eA, eB with
//         |h~_i − H*_i| <= e_i, the normal n~ rounded with a per-component bound e_n
//         (|n~_k − n*_k| <= e_n), and false when not applicable (a parallel edge pair, whose
//         normal has another formula; an orientation sign within its bound; a non-finite or
//         vanishing value).
//
// Why: the double heights of the engine carry errors of the order u L³ (value_bounds.h:
// E3/4), which no bound can shrink: the normal itself is rounded. Along a shallow contact
// (depth ~1e-9 of the size) that is ~1e-7 of the value, and pdd2_accel1 went to rationals (~20
// us a pair, 9 in 10^4 of the paper's pairs). Here every height is within u|H*| plus a u²
// term of the exact one, so the heights that matter near the plane (value_bounds.h's tight
// case) are accurate to their own size. Written by hand: the bounds of the few double-word
// operations (double_word.h) through the normal and the heights, derived below.
//
// Double-word arithmetic (u = 2^-53): double_word.h, with each operation's error (mul 6.2 u²,
// add 4u² of the operands' magnitudes).
// The normal, componentwise n_z = e1x e2y − e1y e2x on differences taken exactly (two_sum):
//   two products (6.2 u² each of its magnitude) and an add (4u² (|p1| + |p2|)):
//   |n~_z − n*_z| <= 10.3 u² N_z, N_z = |e1x e2y| + |e1y e2x| (magnitudes from the high parts,
//   within (1 + u)² of the exact ones: absorbed in the rounding up to 10.5 below).
// A height h = n.d (d = x − o exact): three products, each off by 6.2 u² |n_k||d_k| plus
//   |n_k error| |d_k| <= 10.5 u² N_k |d_k|, and two adds (4u² of the running magnitudes each):
//   <= (6.2 + 10.5 + 8) u² M (1 + 2u) < 25 u² M, M = sum_k N_k |d_k| (|n_k| <= N_k (1 + O(u))).
//   Rounding the double word to its high part adds u |h~|. So e_i = u |h~_i| + 25 u² M_i,
//   computed with a factor (1 + 2^-40) over the few roundings of these products and sums, and
//   absolute terms for products that underflow (two_prod's error is then off by < 2^-1075):
//   2^-1040 for the height's own, and 2^-1066 sum_k |d_k| for the normal's (< 6 · 2^-1075 a
//   component, times |d_k|), which holds at any scale of the pair.
// The normal rounded to doubles: |n~_k − n*_k| <= u |n~_k| (1 + u) + 10.5 u² N_k (+ 2^-1070 for
//   underflowed products) =: <= e_n.
#pragma once

#include <optional>

#include "certification/double_word.h"
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

// The same where double words cannot give it: an edge pair's parallel edges (their normal,
// (e.e) w − (w.e) e, has degree 3) and nearly parallel ones (eB × eA cancels to ~u |e|², so
// its double word is off by ~10 u of itself, and so is every height along it), and any label
// whose depth lies below the double words' 25 u² M (a contact made by two roundings: depths
// ~1e-31 of the size, pdd2 ~1e-62). The exact normal n* and heights n*.(x − o), o a face
// label's first vertex (its face at 0, as above) or s_t, A's vertex highest along n* (at a
// shallow contact's plane the heights, and so their errors, are then ~|n*| depth, not |n*|
// size: the intervals of a resting contact 1e-9 deep ~1e-13 wide instead of ~1e-7): over the
// pair's integer frame where it has one (integer_depth.h's framed_heights: machine integers,
// each value rounded to nearest once, bound u of it), else, for an edge pair, by expansions
// (exact_predicates.h's oriented_normal_expansion: the label's orientation; expansion.h), each
// compressed and rounded once with approx_of's bound: every field within a few u of its own
// exact value, as above but without the u² term. For the contenders of a contact made by
// rounding (a grid against its copy shifted along a diagonal: edges parallel up to the rounding
// of the shift, depths ~1e-17 of the size), ~10 us a candidate less than the rationals; the
// frame's route ~4,000 instructions a candidate where the expansions take ~12,000. False for
// constrained sets other than the label's, a face label without a frame, outside the
// expansions' range or capacity, and on a non-finite or vanishing value.
bool expansion_heights(const TetVertices& A, const TetVertices& B, const Candidate& c, CompensatedHeights& out);

// The heights along a given double normal v instead of a candidate's (pdd2_global's normals,
// global_depth.h): n* = v exactly (e_n = 0), the origin A's vertex highest along v (so the
// vertices at a shallow plane have small heights, each within its own u), every other field
// as above; the products of a double-word difference by a double component err by less than
// the normal's share of the 25 u^2 M above. False on a zero or non-finite v or value.
// With `lo` (a normal in double words, n* = v + lo exactly, |lo_k| <= u |v_k|: a direction no
// double triple represents, global/shallow_certificate.h): the products are double word by
// double word (the same 6.2 u² bound, the normal exact), n~ = v with e_n = max |lo_k|.
bool compensated_heights_along(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                               CompensatedHeights& out, const std::array<double, 3>& lo = {0, 0, 0});

// The normal (p1 − p0) x (q1 − q0) of exact differences in double words (as above: each
// component within 10.5 u² N_k of the exact one), and the exact sign of its height n.(p − q)
// where the double words certify it (within 25 u² M of the exact value, as above): for exact
// tests that are most often not 0 by a rounding (an edge of a grid's shifted copy against a
// face plane of the grid). compensated_height_sign: true with the sign (+1 or −1); false where
// the bound does not decide it, or a value is not finite (an overflow at extreme coordinates;
// the bounds' absolute terms cover underflow at any scale): the exact sign is then an
// expansion's (exact_heights.h).
struct CompensatedNormal {
  dw::DW n[3];
  double N[3];
};
CompensatedNormal compensated_normal(const std::array<double, 3>& p1, const std::array<double, 3>& p0,
                                     const std::array<double, 3>& q1, const std::array<double, 3>& q0);
bool compensated_height_sign(const CompensatedNormal& n, const std::array<double, 3>& p,
                             const std::array<double, 3>& q, int& sign);

// The label's exact oriented normal n* and heights H*_i = n*.(x_i − o) in double words,
// unrounded (the header's, before their rounding to doubles), each with its bound: components
// |n~_k − n*_k| <= 10.5 u² N_k (en), heights the header's 25 u² M (eA, eB). The constrained
// vertices at their exact heights: 0 for the set through o (A's face or edge, B's face), one
// height for B's edge of an edge pair (n* is orthogonal to it). False where compensated_heights
// is not applicable (the orientation not certain; a parallel edge pair); a value that is not
// finite (an overflow) is passed on to the callers' own checks. For the comparisons of values a
// rounding apart (compensated_depth, compensated_displacements.h).
struct DoubleWordHeights {
  dw::DW n[3], hA[4], hB[4];
  double en[3], eA[4], eB[4];
};
bool double_word_heights(const TetVertices& A, const TetVertices& B, const DirectionLabel& l, DoubleWordHeights& out);

// A candidate's definitions §4 depth parts in double words, unrounded: D = max_i H*_A,i −
// min_j H*_B,j and n*.n* of its exact oriented normal (the heights above before their rounding
// to doubles), with certified absolute bounds |D~ − D*| <= eD, |nn~ − n*.n*| <= enn (derived in
// the .cpp). For ordering candidates whose delta² are a rounding apart (a grid against its copy
// shifted by a non-dyadic offset: directions parallel up to the rounding of the coordinates,
// depths ~1e-16 apart relative), which the rounded heights cannot and which expansions order at
// ~20 times the cost. False where compensated_heights is not applicable, D~ is not certainly
// positive, or a value is out of the range the comparison's bound covers.
struct CompensatedDepth {
  dw::DW D, nn;
  double eD = 0, enn = 0;
};
bool compensated_depth(const TetVertices& A, const TetVertices& B, const DirectionLabel& l, CompensatedDepth& out);

// sign(delta²_p − delta²_q) = sign(D_p² n_q.n_q − D_q² n_p.n_p) from compensated depths; nullopt
// where the bounds do not decide it (an exact tie among them).
std::optional<int> compare_delta2_compensated(const CompensatedDepth& p, const CompensatedDepth& q);

}  // namespace pdd::fast::detail
