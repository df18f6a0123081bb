// compensated_qp_order.h — internal to fast/src: the sign of value_p − value_q for two
// definitions §5 QP values whose optimal status patterns are known, from double-word heights
// with certified bounds: the filter in front of exact_qp_order.h's expansions in the QP sweeps'
// tie order (deformable_depth.cpp's first_least_qp_exact). On a grid against its copy shifted
// by whole cells of a decimal size (B's cells coincide with A's up to the rounding of k h + h
// against (k + 1) h) most near ties there are a rounding apart (~1e-16 relative), which double
// words separate at a few hundred instructions a candidate where the expansions take ~35,000.
//
// Input:  the pair, a candidate's label, its verified pattern (exact_qp_order.h's QpPattern:
//         the vertices at the plane, A's constrained ones) and the case (a_static: case 1).
// Output: parts F, Knn as Bounded double words (double_word.h: |v − x*| <= e) of
//         exact_qp_order.h's closed form, the candidate's exact value being F* / (20 Knn*);
//         false where double_word_heights does not apply or a value is not finite.
// Closed form: exact_qp_order.h's, on double_word_heights' heights (compensated_heights.h;
// their origin is a vertex of the constrained set: case 2's value does not depend on it, and
// case 1's C, a constrained height of A, is 0 there; A's highest when it has none, with the
// bound of `highest` in the .cpp). Each operation's bound is Bounded's, so the parts carry
// certified bounds by construction.
// compare_qp_compensated: sign(F_p Knn_q − F_q Knn_p) where the bound decides it; nullopt
// otherwise (an exact tie among them: the expansions decide).
#pragma once

#include <optional>

#include "certification/double_word.h"
#include "exact/exact_qp_order.h"
#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

struct CompensatedQpParts {
  dw::Bounded F, Knn;
};
bool compensated_qp_parts(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                          const QpPattern& pattern, bool a_static, CompensatedQpParts& out);
std::optional<int> compare_qp_compensated(const CompensatedQpParts& p, const CompensatedQpParts& q);

// Case 2's optimal displacements along the label's exact oriented normal n* for the verified
// pattern (the deformed vertex is x_i + T*_i n* / (n*.n*)): at the plane T*_i = C* − H*_i =
// d*_i / den, A's other vertices −S*_A and B's −S*_B, S*_X = (sum of X's d*_i at the plane) /
// (den (5 − m_X)) (the closed form above; direction_qp.h's displacement_below/above). Each
// rounded to a double tA[i], tB[i] with a bound eA[i], eB[i] on its distance to T*_i: the
// Bounded part's e, its low part (|lo| <= u |hi|) and the division's rounding (u |t|), over
// den or den (5 − m_X), times 1 + 2^-40. False where compensated_qp_parts' heights do not
// apply, n* may be 0 (parallel edges labelled ±: their direction is not e1 x e2), the pattern
// has no vertex at the plane, or a value is not finite.
// Where the double solver's displacements carry 2^9 u Ha (value_bounds.h) and the contact is
// made by rounding (displacements ~1e-17 of the size), these carry ~u of themselves: the
// deformed positions within an ulp of the exact ones (deformable_depth.cpp's
// compensated_positions).
struct CompensatedDisplacements {
  double tA[4], tB[4], eA[4], eB[4];
};
bool compensated_displacements(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               const QpPattern& pattern, CompensatedDisplacements& out);

}  // namespace pdd::fast::detail
