// piece_screen.h — internal to fast/src: the double path of piece_enumeration.cpp prunes its 225
// pieces (active sets of the relaxed QP, global_depth.h) without an eigensolver.
//
// Input:  per active set S = (S_A, S_B), the piece's matrix as lanes; the pruning window
//         [lower, top) of consider_piece (piece_visit.h: an eigenpair can hold the minimiser
//         only if its exact eigenvalue lies there); the pair's centred vertices.
// Output: surviving_pieces: per row (S_A fixed, 15 lanes S_B), the pieces with an eigenvalue
//         possibly in the window; screen: of those, the ones whose in-window eigenvector may
//         satisfy the piece's sign conditions. Every other piece is certainly unable to hold
//         the minimiser (the arguments below); the survivors go to consider_piece.
// Both run as lane loops (the pieces side by side, branch-free) that GCC vectorises in its
// AVX-512 and AVX2 clones; on the paper's pairs (2000, seed 1) about 30 of the 225 pieces
// reach screen() and 1.5 reach consider_piece. The vectorisation is fragile: check
// `-fopt-info-vec` after any change (a chain of && on six comparisons once made GCC give up on
// the row loop: pdd2_global 13.4 us instead of 7.4), and that each clone ends with vzeroupper
// (objdump: without it the caller's SSE code runs with dirty upper registers: the caller's
// scalar pass over a row's lanes, piece_enumeration.cpp).
// Written by hand: no library counts a symmetric 3x3 matrix's eigenvalues in an interval with
// certified signs, or screens 8 lanes of them at once.
#pragma once

#include <algorithm>
#include <cmath>

namespace pdd::fast::detail {

inline constexpr double kScreenU = 0x1p-53;  // unit roundoff
// A sign condition l.v >= 0 (or <= 0) holds within tolerance kSign |l|_1 + floor (|l|_1 >=
// |l|_2: a wider tolerance, no square root; piece_visit.h's Conditions).
inline constexpr double kSign = 1e-6;
// screen()'s widening of the window for the other eigenvalues' gap, times tr N (one pair of
// counts: 2^-6 and 2^-14 together kept 18.8 pieces a pair on shallow contacts, 2^-10 alone 19.7).
inline constexpr double kClearWidening = 0x1p-10;
// ... computed only when some piece's window is narrower than this times its n_error: a wider
// window bounds sin t by ~3 n_error / (2^15 n_error) ~ 1e-4 on its own (mu mid-window), and
// pairs whose windows are all wide (the paper's: ~1e10 n_error) pay nothing for the counts.
inline constexpr double kNarrowWindow = 0x1p16;
// Bits of an active set (a subset of a tetrahedron's four vertices), and each vertex's sign
// condition in it: +1 active (l.v >= 0), -1 free (l.v <= 0). Tables: no branch per lane.
inline constexpr int kPopcount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
inline constexpr double kSignOf[16][4] = {
    {-1, -1, -1, -1}, {1, -1, -1, -1}, {-1, 1, -1, -1}, {1, 1, -1, -1}, {-1, -1, 1, -1}, {1, -1, 1, -1},
    {-1, 1, 1, -1},   {1, 1, 1, -1},   {-1, -1, -1, 1}, {1, -1, -1, 1}, {-1, 1, -1, 1}, {1, 1, -1, 1},
    {-1, -1, 1, 1},   {1, -1, 1, 1},   {-1, 1, 1, 1},   {1, 1, 1, 1}};

// The number of eigenvalues of the symmetric double matrix H = (h00 h01 h02 / h11 h12 / h22)
// (its exact eigenvalues) below t, or -1 when the doubles cannot decide it. eigenvalues_below's
// rule (Descartes on N = H - tI: the sign changes of (1, tr N, c1 N, det N)), each
// coefficient's sign certified: N's diagonal is rounded (relative u), off-diagonal entries
// exact. A sum of m products of d entries, each entry off by u relative and each product and
// sum rounded, is within ((d + d - 1 + m - 1) u + O(u^2)) of its value times the sum of its
// terms' magnitudes P (computed with the same roundings: within (1 + 8u) of the exact one):
// tr (d 1, m 3) 4u, c1 (d 2, m 6) 9u, det as written (d 3; two products, a subtraction, an
// outer product, two outer sums) 11u. Each is taken as 16u P: a coefficient within that of 0
// is undecided, and with it the count. Range: those relative bounds hold for normal results
// (each bound has >= 5u P to spare). A product that underflows errs by up to 2^-1075 absolute,
// and that error is multiplied by at most two more entries; with every entry of N - tI below
// 2^102 in magnitude (checked without a maximum: ptr <= 2^102 bounds the diagonal, pc1 <= 2^204
// the off-diagonal squares, each computed within a few u of its exact value), each of the <= 6
// terms errs by <= 2^-871 more, under 2^-868 in
// all, while the spare 5u P is >= 2^-851 when P >= 2^-800 (checked): a smaller P (a piece whose
// entries are ~1e-80, vertices ~1e-40 apart beside a vertex at 1) or a larger entry is
// undecided. (Without these checks a matrix whose products underflow gets a wrong count.)
// Overflow gives inf or NaN, which fail every comparison: undecided. Sums and
// differences are exact when subnormal. Branch-free (the lanes of surviving_pieces vectorise).
inline int eigenvalues_below_certain(double h00, double h01, double h02, double h11, double h12,
                                     double h22, double t) {
  const double a00 = h00 - t, a11 = h11 - t, a22 = h22 - t;
  const double tr = a00 + a11 + a22, ptr = std::fabs(a00) + std::fabs(a11) + std::fabs(a22);
  const double c1 = a00 * a11 - h01 * h01 + a00 * a22 - h02 * h02 + a11 * a22 - h12 * h12;
  const double pc1 = std::fabs(a00 * a11) + h01 * h01 + std::fabs(a00 * a22) + h02 * h02 +
                     std::fabs(a11 * a22) + h12 * h12;
  const double m0 = a11 * a22 - h12 * h12, m1 = h01 * a22 - h12 * h02, m2 = h01 * h12 - a11 * h02;
  const double det = a00 * m0 - h01 * m1 + h02 * m2;
  const double pdet = std::fabs(a00) * (std::fabs(a11 * a22) + h12 * h12) +
                      std::fabs(h01) * (std::fabs(h01 * a22) + std::fabs(h12 * h02)) +
                      std::fabs(h02) * (std::fabs(h01 * h12) + std::fabs(a11 * h02));
  // (& on ints, not &&: no branch, so that the lanes vectorise)
  const int decided = int(std::fabs(tr) > 16 * kScreenU * ptr) & int(std::fabs(c1) > 16 * kScreenU * pc1) &
                      int(std::fabs(det) > 16 * kScreenU * pdet) &  // false on NaN (and on inf)
                      int(pc1 >= 0x1p-800) & int(pdet >= 0x1p-800) &  // (range, above)
                      int(ptr <= 0x1p102) & int(pc1 <= 0x1p204);
  const int changes = int(tr < 0) + int((c1 < 0) != (tr < 0)) + int((det < 0) != (c1 < 0));
  return decided ? changes : -1;
}

// The double pieces of one row (A's active set fixed: its sums SA, QA (xx xy xz yy yz zz),
// max |QA| qa, size mA) against every B active set mb = 1..15 at once (lane mb; lane 0 is
// padding): bit mb of the result is set unless the piece is certainly outside the pruning
// window. The lanes hold N = 20 H, piece_enumeration.h's numerator (the same
// operations in the same order, without its final /20: no division per entry).
// N's error, entrywise, against the exact 20 H of the (centred, rounded) vertices: first order
// in u, with L the largest |coordinate| of the piece's active vertices, so that mag (the sum
// qa + qb + 2 |C| |S| + (mA + mB) |C|^2 + k |TA|^2 of max norms) >= qa + qb >= L^2 (a diagonal
// entry of QA or QB). SA, SB: <= 4 terms, |dS*| <= 12u L; QA, QB: 4 products summed, <= 16u
// L^2 each. The exact C is a convex combination of the active vertices' means, |C| <= L; its
// numerator's and r's roundings (wA, r, two products, a sum: <= 8u relative of a weighted mean
// <= L) give |dC| <= 12u L (wA + wB) r + 9u L <= 21u L ((wA + wB) r <= 1). TA = (mA C - SA) wA:
// |TA| <= 8L wA and |dTA| <= (mA 21 + 4 + 12 + 8 + 16) u L wA <= 124u L wA. S = SA + SB: |S| <=
// 8L, |dS| <= 32u L. Terms of 20 H: QA + QB 32u L^2; the two C S terms (21 8 + 32 + 16) u L^2
// each, 432u L^2; m C C (m <= 8) 2 8 21 = 336u L^2; k TA TA: 2 k |TA| |dTA| = 1984 k wA^2 u L^2
// with k wA^2 <= 5 (mA = 4: k <= 5, wA = 1; mA = 3, 2, 1: 6/4, 7/9, 8/16): 9920u L^2; each
// term's own roundings and the sum's, <= 9u mag. In all <= 10720u L^2 + 9u mag < 2^14 u mag:
// n_error = 2^-39 mag (2^14 u mag), second-order terms far inside the rest. (16u mag, the
// last expression's roundings alone, would leave out the inputs' own errors; measured errors
// stay below 0.3 of that.) So (Weyl, |E|_2 <= |E|_F <= 3 n_error) each exact eigenvalue of 20 H is
// within 3 n_error of one of the double N's own. The window of piece_visit.h's
// consider_piece, [lower, top) with top = best (1 - kPrune), becomes [20 lower, 20 top) for
// 20 H, and window_edges() widens it by 4 n_error (3 for Weyl, the rest and a relative 2^-40
// for the edges' own roundings, each <= u relative). When N has no eigenvalue between the
// edges, counted exactly (eigenvalues_below_certain), no exact eigenvalue of H lies in the
// window and the piece cannot hold the minimiser: it is skipped without its eigenpairs.
struct Edges {
  double lo, hi;
};
inline Edges window_edges(double top, double lower, double n_error) {  // top, lower >= 0
  return {20 * lower * (1 - 0x1p-40) - 4 * n_error, 20 * top * (1 + 0x1p-40) + 4 * n_error};
}
// B's active sets as lanes (structure of arrays): lane l holds the set mb[l] (0: padding, the
// empty set's zero sums), its sums, max |Q| q, size m, w = 1 / (5 - m) and, per A size mA = 1..4,
// r[mA][l] = 1 / (mA wA + m w) (kLaneR's values); lanes, a multiple of 4, are in use.
struct ColumnsB {
  double S[3][16], Q[6][16], q[16], m[16], w[16], r[5][16];
  unsigned char mb[16];
  int lanes;
};
// r = 1 / (mA wA + mB wB), w = 1 / (5 - m), per A size mA (1..4) and B set mb (mB its popcount):
// the lane loop's operations, folded at compile time instead of one vector division per 8
// lanes (the same bits: each operation correctly rounded, as at run time; no contraction).
struct LaneReciprocals {
  double r[5][16] = {};
  constexpr LaneReciprocals() {
    for (int mA = 1; mA <= 4; ++mA)
      for (int l = 0; l < 16; ++l) {
        const double wA = 1.0 / (5 - mA), dA = double(mA);
        const double wB = 1.0 / (5 - kPopcount[l]), mB = double(kPopcount[l]);
        r[mA][l] = 1.0 / (dA * wA + mB * wB);
      }
  }
};
inline constexpr LaneReciprocals kLaneR;
// One row's pieces as lanes (lane mb): N = 20 H (xx xy xz yy yz zz), n_error, c and T_A's
// vectors, and the number of N's eigenvalues below the window's bottom edge (parity: f's sign
// there, screen()) and below its top edge (-1: undecided).
// keep[l]: the piece is not certainly outside the pruning window (the caller gathers the bits).
struct RowLanes {
  double N[6][16], n_error[16], C[3][16], TA[3][16], below_low[16];
  int one[16];        // exactly one eigenvalue in the window, both counts decided
  int below_top[16];
  int keep[16];
};
// Lanes 0 .. `lanes` - 1 of b (4, 8, 12 or 16; RowLanes' lane l is b's lane l).
void surviving_pieces(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b, int lanes,
                      double top, double lower, RowLanes& out);
// The pieces that passed surviving_pieces with exactly one eigenvalue in the window (RowLanes'
// one), gathered as lanes for screen().
struct ScreenLanes {
  static constexpr int kMax = 232;  // 225 pieces, padded to whole 8-lane vectors
  int n = 0;
  double N[6][kMax], n_error[kMax], C[3][kMax], TA[3][kMax], below_low[kMax];  // as RowLanes
  double sign[8][kMax];  // each condition's sign (+1: active, l.v >= 0; -1: free, l.v <= 0)
  // RowLanes' one (1 on every lane gathered; read by screen(): without an int lane value first
  // in its verdict's chain of &, GCC 12 does not vectorise its last loop)
  int one[kMax];
  unsigned char ma[kMax], mb[kMax];
  int keep[kMax];
};

// The double path's screen of the pieces that passed surviving_pieces: keep[p] false when piece
// p certainly cannot hold the minimiser, decided without the eigensolver. It works on N = 20 H
// (the eigenvectors of H) and handles the common case only: exactly one eigenvalue mu of the
// double N between the window's edges [lo, hi) (window_edges; counted exactly by
// surviving_pieces; the other two lie outside), and its eigenvector certainly outside the
// piece's cone R_S in both orientations (a sign condition violated beyond its rounding floor).
// Every other piece (two or three eigenvalues in the window, a vector not resolved, a condition
// met or nearly met) is kept: consider_piece decides it. Lane loops (the pieces side by side)
// so that each step vectorises.
//  (H below: the lanes' N.)
//  - mu~: a root of f(x) = det(H - xI) = prod (lambda_i - x) in (lo, hi), where f changes
//    sign exactly once (f's sign is (-1)^(eigenvalues below x)); safeguarded Newton (a step
//    leaving the bracket, kept by f's computed signs, bisects), stopped at a step of 2^-24 of
//    the window or after kNewton steps: the test below needs sin t, about |mu~ - mu| / delta,
//    far below the conditions' violations, O(1) of |l| when they are violated. Its accuracy
//    is not relied on: the bound below takes mu~ as it is.
//  - v~: the largest cross product of two rows of M = H - mu~ I (M's null vector when mu~ is
//    exact), normalised.
//  - Residual bound (any shift rho), first for N itself: write v~ / |v~| = cos t v + sin t y
//    with v the unit eigenvector of mu and y a unit vector in the span of the other two
//    eigenvectors; then |(N - rho I) v~| / |v~| >= sin t |(N - rho I) y| >= sin t delta, delta
//    the distance from rho to the other eigenvalues. The residual w = M v~ is computed with
//    M's diagonal rounded (u relative) and a 3-term dot product per row: each component
//    within 4u of sum_c |m_rc| |v~_c|, so |w_exact| <= |w| (1 + 3u) + 5u sum_rc |m_rc| |v~_c|
//    (the 1-norm of the error vector bounds its 2-norm), and |v~| >= 1 - 5u: r, the bound.
//    Then for the exact 20 H = N + E (|E|_2 <= 3 n_error, surviving_pieces): its residual is
//    <= r + 3 n_error, and by Weyl its other two eigenvalues lie within 3 n_error of N's,
//    outside [lo', hi') (below): with rho = mu~ in (lo, hi), delta >= min(mu~ - lo', hi' -
//    mu~) - 3 n_error, required > 0. So the angle t to the exact piece's eigenvector (the one
//    whose eigenvalue is within 3 n_error of mu, the only one that can lie in the window) has
//    sin t <= (r + 3 n_error) / delta. (N's own angle is not the exact H's: their gap is ~u
//    mag / delta.) The relative bounds need normal results: decided only when the sum above
//    and |v~|'s square are >= 2^-900 (as for eigenvalues_below_certain).
//  - The other eigenvalues' gap: [lo', hi') = [lo - g, hi + g), g = kClearWidening tr N (a
//    scale only: N is positive semi-definite up to rounding, so tr N is about its largest
//    eigenvalue or more), where the exact counts at lo - g and hi + g (eigenvalues_below_certain,
//    at the computed ends) equal those at lo and hi: N's other two eigenvalues then lie outside
//    the widened interval, whatever g is; else [lo, hi) itself. A shallow contact's window (~1e-13 |N|) is far narrower than 3 n_error
//    (~2^-37 of the moments), so the window alone never gives delta > 0 there, while the other
//    eigenvalues of most of its pieces lie ~|N| away: on such pairs (depth 5e-7 of the size)
//    the pieces kept drop from 86 to 19 a pair (the rest have structural zero eigenvalues in
//    the window: two or three there, never `one`).
//  - For the orientation of v nearer v~ (angle t <= pi / 2), |v~ / |v~| - v| = 2 sin(t / 2) <=
//    sqrt(2) sin t. A condition's computed l.v~ is within 3u |l|_1 (1 + 4u) of the exact one,
//    and v~ / |v~| moves it by 4u |l|_2 more; |l|_2 <= |l|_1. So sign_k s l_k.v~ < -(floor +
//    |l_k|_1 (sqrt(2) sin t + 8u)) (computed) implies sign_k s l_k.v < -floor for the exact
//    unit eigenvector s v. The conditions' vectors l (d_i = (a_i - c) - T_A, e_j = (c - b_j) -
//    T_A) are computed as make_conditions computes them (same operations), each within its
//    rounding floor (Conditions: floor = 1e-12 of the pair's scale, far above the few roundings
//    of coordinates within the scale) of the exact one l*: so l*_k.(s v) < 0, s v lies outside
//    the cone R_S, for both orientations s = +1 and -1 (v~ may be near either). A piece holding
//    the minimiser u* has u* = +-v in R_S (global_depth.h: a stationary point of G is an
//    eigenvector of the S optimal there, in its cone): it is never dropped. consider_piece
//    offers more (every vector within kSign of its cone, a tolerance of its own that only costs
//    evaluations); the screen drops what it would not offer and the pieces it would offer in
//    vain, whose vectors lie outside their cones by less than kSign (shallow contacts, where
//    the conditions' values are of the order of the depth: at 5e-8 of the size the pieces kept
//    drop from 38 to a few a pair).
void screen(ScreenLanes& S, const double (&pA)[4][3], const double (&pB)[4][3], double floor, double top,
            double lower);

}  // namespace pdd::fast::detail
