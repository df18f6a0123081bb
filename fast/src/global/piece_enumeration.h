// piece_enumeration.h — internal to fast/src/global: the enumeration of the relaxed QP's
// pieces over one pair (global_depth.h's stationary points).
//
// Input : the pair's vertices (doubles about the centroid, or exact rationals relative to A[0]
//         scaled by 2^-unit), and the Search (the evaluations' problem, the best offer so far,
//         the lower bound on every G(u)).
// Output: every active set S = (S_A, S_B), both sides non-empty (15 x 15), is visited: the
//         pieces that certainly hold no stationary value in the window are dropped
//         (piece_screen.h in doubles; by certified eigenvalue counts on the exact path), and
//         each survivor's H_S and sign conditions go to consider_piece (piece_visit.h), whose
//         offers lower the best. H_S by moments:
//
// H_S by moments (enumerate_pieces): with S_A's sum SA and second moment QA = sum a a^T (and B's), the closed form's
//   20 H = sum_{S_A} (C - a)(C - a)^T + sum_{S_B} (C - b)(C - b)^T + k TA TA^T
//        = QA + QB - C (SA + SB)^T - (SA + SB) C^T + (mA + mB) C C^T + k TA TA^T,
// k = 2 + (4 - mA) + (4 - mB) (the free vertices' T_A^2 and T_B^2, and 2 T_A^2 for the centre),
// with the 16 subsets' sums and moments computed once. In doubles each entry of 20 H errs by
// at most 2^-39 mag, mag the sum of the terms' bounds (|QA| + |QB| + 2 |C| |SA + SB| +
// (mA + mB) |C|^2 + k |TA|^2, max norms): the derivation is piece_screen.h's (the inputs' own
// errors, C's and T_A's above all, included; 16u mag would count only the last expression's
// roundings). The /20 adds u relative, inside that bound's margin.
#pragma once

#include <array>

#include "exact/exact_geometry.h"
#include "global/piece_visit.h"

namespace pdd::fast::global {

template <class T>
using Corners = std::array<std::array<T, 3>, 4>;

// Doubles: positions about the centroid; H and the conditions in doubles with their errors.
void enumerate_pieces(const Corners<double>& pA, const Corners<double>& pB, const Search& search);
// Exact: positions relative to A[0] times 2^-unit; H and the conditions exact, each rounded to
// doubles once built (scaled by its own power of two), the suspects recorded.
void enumerate_pieces(const Corners<detail::Q>& pA, const Corners<detail::Q>& pB, const Search& search);

}  // namespace pdd::fast::global
