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

}  // namespace pdd::fast::detail
