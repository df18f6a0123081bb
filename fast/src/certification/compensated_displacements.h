// compensated_displacements.h — internal to fast/src: case 2's optimal displacements for a
// verified status pattern, from double-word heights with certified bounds, for the deformed
// positions of a contact made by rounding (deformable_depth.cpp's compensated_positions).
//
// Input:  the pair, a candidate's label, the pattern of its exact optimum (the vertices at the
//         plane, constrained or active, as valued_on_heights in deformable_depth.cpp verifies it).
// Output: each vertex's displacement T*_i along the label's exact oriented normal n* (the
//         deformed vertex is x_i + T*_i n* / (n*.n*)), rounded to a double tA[i], tB[i] with a
//         bound eA[i], eB[i] on its distance to T*_i; false where double_word_heights
//         (compensated_heights.h) does not apply, n* may be 0 (parallel edges labelled ±: their
//         direction is not e1 x e2), the pattern has no vertex at the plane, or a value is not
//         finite.
// Closed form (direction_qp.h with the pattern fixed: displacement_below/above), on the heights
// h_i = n*.(x_i − o) of the double words (o a vertex of the constrained set: the value does not
// depend on it): m_A, m_B the counts at the plane, w_A = 5 − m_B, w_B = 5 − m_A, den = m_A w_A +
// m_B w_B and E = w_A sum_A h + w_B sum_B h, so that the plane's height is C* = E / den; at the
// plane T*_i = C* − h_i = d_i / den with d_i = E − den h_i, A's other vertices −S*_A and B's
// −S*_B, S*_X = (sum of X's d_i at the plane) / (den (5 − m_X)).
// Bounds: each operation's is Bounded's (double_word.h), so d_i and the sums carry certified
// bounds by construction; the rounding to a double adds the low part (|lo| <= u |hi|) and the
// division's rounding (u |t|), over den or den (5 − m_X), times 1 + 2^-40.
// Where the double solver's displacements carry 2^9 u Ha (value_bounds.h) and the contact is
// made by rounding (displacements ~1e-17 of the size), these carry ~u of themselves: the
// deformed positions within an ulp of the exact ones.
#pragma once

#include "certification/compensated_heights.h"
#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

struct AtPlane {
  unsigned atA = 0, atB = 0;  // bit i: vertex i at the plane (constrained or active)
};
struct CompensatedDisplacements {
  double tA[4], tB[4], eA[4], eB[4];
};
bool compensated_displacements(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               const AtPlane& pattern, CompensatedDisplacements& out);
// The same on given heights, each within its bound e_i of the exact height along the exact
// normal they were taken on (compensated_heights.h's expansion_heights: an edge pair's, which
// has no double words, each within a few u of itself): the displacements along that normal.
bool compensated_displacements(const CompensatedHeights& h, const AtPlane& pattern, CompensatedDisplacements& out);

}  // namespace pdd::fast::detail
