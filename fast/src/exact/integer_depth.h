// integer_depth.h — internal to fast/src: a candidate direction's classification, depth D and
// n.n (definitions §3–§4: delta² = D²/(n.n)) exactly in machine integers, on a pair's integer
// frame (integer_heights.h), and the exact order of two candidates' delta².
//
// Input:  an IntegerFrame of the pair (usable()), an edge pair (a, b) or a candidate's label.
// Output: classify_edge_pair_framed: the edge pair's kind and orientation rule
//         (exact_predicates.h's classify_edge_pair_exact).
//         framed_depth: the label's oriented normal n (eB × eA for an edge pair, or the common
//         perpendicular (e.e) w − (w.e) e of parallel edges, w = r_x − s_u; oriented by the rule;
//         a face's outward normal, −outward for VF), its depth D = max_i n.s_i − min_j n.r_j
//         and n.n, all exact; false for a colinear edge pair (no direction).
//         compare_framed_delta2: sign(delta²_p − delta²_q) = sign(D_p² n_q.n_q − D_q² n_p.n_p).
//         framed_delta2: delta² as a double with a root bound (value_bounds.h).
//
// The same polynomials as exact_predicates.cpp's expansions (term for term: face_normal_out_of,
// edge_pair_normal, side_rule, depth_parts_exact, compare_delta2_exact), evaluated over
// integers. In units of the frame (2^e), with coordinate differences below 2^61:
//   faces and generic edge pairs: |n_k| < 2^123, heights n.(p − s0) < 2^186 (IntegerFrame::dot),
//     |D| < 2^187 (units 2^(3e)), n.n < 2^248 (2^(4e));
//   parallel edge pairs (degree 3 in the differences): e.e, w.e < 2^124, |n_k| < 2^186,
//     heights < 2^249, |D| < 2^250 (2^(4e)), n.n < 2^374 (2^(6e));
// delta² = D²/(n.n) is in units 2^(2e) either way, so any two candidates compare as integers:
// D² n.n < 2^(500 + 374), fourteen 64-bit limbs. The products are GMP's mpn functions on limbs
// on the stack (mpz allocates); a parallel pair's heights are signed 256-bit integers of four
// words (integer_depth.cpp's I256: two 128 x 128-bit products a height), its n.n the product
// (e.e) |e × w|^2 of its edge e and offset w (Lagrange's identity). Written here rather than on
// expansions (expansion.h) because a comparison is then ~100 limb products instead of thousands
// of two_products; the callers keep the expansions where the pair has no frame.
#pragma once

#include <gmp.h>

#include "exact/exact_predicates.h"
#include "exact/integer_heights.h"
#include "pdd/direction_label.h"

namespace pdd::fast::detail {

// The edge pair's kind and orientation rule, exactly. Precondition: f.usable().
EdgePairClass classify_edge_pair_framed(const IntegerFrame& f, int a, int b);

struct FramedDepth {
  mp_limb_t D[4] = {};   // |D|, least significant limb first, units 2^(3e) (2^(4e): parallel)
  mp_limb_t nn[6] = {};  // n.n, units 2^(4e) (2^(6e): parallel)
  int D_sign = 0;        // sign of D
  bool parallel = false; // a parallel edge pair (the units above)
  bool has_normal = false;    // n below is the label's oriented normal (not for a parallel pair)
  __int128 n[3] = {0, 0, 0};  // units 2^(2e)
};

// The label's exact depth and n.n (header); false for a colinear edge pair. Precondition:
// f.usable().
bool framed_depth(const IntegerFrame& f, const DirectionLabel& label, FramedDepth& out);

// The sign of the label's D, exactly (−1, 0, +1): framed_depth's D_sign, the whole depth kept in
// its per-pair memo (a depth sign the candidate set cannot decide in doubles is a contender's,
// whose depth the refinement asks next); 2 for a colinear edge pair. Precondition: f.usable().
int framed_depth_sign(const IntegerFrame& f, const DirectionLabel& label);

// A label's exact oriented normal n (framed_depth's: a face's outward normal, −outward for VF,
// eB × eA for an edge pair, or the common perpendicular of parallel edges, oriented as the label
// says) and the heights n.(x_i − o) of the eight vertices (0..3 A's, 4..7 B's), each rounded
// once to a double in the pair's units (n in 2^(2e), heights in 2^(3e); parallel: 2^(3e) and
// 2^(4e)), with |n~_k − n_k| <= e_n and |h~_i − h_i| <= e[i] (each a few u of its own value, 0
// where the value is 0). The origin o: the face's first vertex for FV and VF (the face's three
// heights exactly 0, as compensated_heights.h has them), else s_t, A's vertex highest along n
// (the first in ties). Relative to it the vertices at a shallow contact's plane have heights
// ~|n| depth, so their errors are ~u of that rather than of the pair's size (a resting contact
// 1e-9 deep: intervals ~1e-7 wide relative to s_u, ~1e-13 here). An edge pair's A edge's two
// heights are equal exactly (n is normal to it), and so are B's. For compensated_heights.h's
// expansion_heights, which takes the same quantities by expansions where the pair has no frame
// (edge pairs only). False for a colinear edge pair, or a value that is not 0 and does not round
// to a normal double. Precondition: f.usable().
struct FramedHeights {
  double n[3] = {0, 0, 0}, e_n = 0;
  double h[8] = {}, e[8] = {};
};
bool framed_heights(const IntegerFrame& f, const DirectionLabel& label, FramedHeights& out);

// sign(delta²_p − delta²_q), exactly (both from one frame).
int compare_framed_delta2(const FramedDepth& p, const FramedDepth& q);

// The position in l[0..n) of the first least exact delta², exact ties to the earliest
// (exact_predicates.h's first_least_delta2_exact, over integers); −1 when a label has no
// direction (a colinear edge pair) or n = 0. Precondition: f.usable().
int first_least_delta2_framed(const IntegerFrame& f, const DirectionLabel* l, int n);

// delta² = D²/(n.n) as a double v with a root bound r (the exact value lies in
// [lower_of(v, r), upper_of(v, r)], value_bounds.h); false when D = 0 or v is not a normal
// double. Each part is converted from its K limbs with a relative error below (2K − 1) u < 12u
// (non-negative terms), taken as rho = 16u each; then as delta2_by_expansions:
// r = 1.02 (rho_D + rho_n + 4u).
bool framed_delta2(const IntegerFrame& f, const FramedDepth& p, double& v, double& r);

}  // namespace pdd::fast::detail
