// exact_qp_order.h — internal to fast/src: the exact order of two definitions §5 QP values
// whose optimal status patterns are known, by floating-point expansions (expansion.h), for
// the near ties of the QP sweeps that compensated intervals cannot separate
// (deformable_depth.cpp's tied_first). On coincident and symmetric aligned tetrahedra (a grid
// against its copy shifted by whole cells, blocks stacked a layer deep) the sweeps' minima are
// exact ties between different directions (a Kuhn cell's faces of equal value by the cell's
// symmetry); rationals take ~110k instructions a candidate there.
//
// Input:  the pair, with every non-zero |coordinate| in normal_for_degree_ten's range
//         (exact_predicates.h; checked here); a candidate's label and A's constrained vertices
//         conA; the pattern of its exact optimum: atA, atB the vertices at the plane
//         (constrained or active), as valued_on_heights (deformable_depth.cpp) verifies it.
// Output: QpParts {F, Knn}: the candidate's exact value is F / (20 Knn); ok = false outside
//         the range or past an expansion's capacity (the caller then takes rationals).
// Closed form (direction_qp.h with the pattern fixed; side_cost: sum d² + (sum d)² / (5 − m)
// per side), on the exact heights h_i = n.(x_i − o) of the label's exact oriented normal n, o
// a vertex at the plane:
//   case 2 and relaxed: m_A, m_B the counts at the plane, w_A = 5 − m_B, w_B = 5 − m_A,
//   den = m_A w_A + m_B w_B, C = E / den with E = w_A sum_A h + w_B sum_B h (an affine
//   combination: the value does not depend on the origin o). With d_i = E − den h_i
//   (= den (C − h_i)) and S_X the sum of X's d_i at the plane,
//     cost = (sum d_i² + S_A² / (5 − m_A) + S_B² / (5 − m_B)) / den²
//          = F / K,  F = w_A w_B sum d_i² + w_A S_A² + w_B S_B²,  K = den² w_A w_B;
//   case 1 (static): A does not move and C is the height its constrained vertices share (A's
//   highest when it has none: VF); d_i = C − h_i over B's vertices at the plane,
//     F = (5 − m_B) sum d_i² + S_B²,  K = 5 − m_B.
//   Knn = K n.n.
// Range: F has degree 6 in coordinate differences (8 for a parallel edge pair), Knn 4 (6), so
// each product F_p Knn_q of compare_qp_exact has degree 10 (14): depth_parts_exact's D² n.n
// argument (exact_predicates.cpp), whose granularity integer factors keep and whose magnitude
// bound they raise by less than 2^16 (den <= 12, w <= 5, at most 8 squares): far from overflow.
#pragma once

#include <optional>

#include "exact/expansion.h"
#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

struct QpPattern {
  unsigned atA = 0, atB = 0;  // bit i: vertex i at the plane (constrained or active)
  unsigned conA = 0;          // A's constrained vertices (case 1's C)
};
struct QpParts {
  detail::Expansion F, Knn;
  bool ok = false;
};
QpParts qp_parts_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                       const QpPattern& pattern, bool a_static);

// sign(value_p − value_q) = sign(F_p Knn_q − F_q Knn_p) (Knn > 0), exactly; nullopt past an
// expansion's capacity. Both parts from qp_parts_exact (ok).
std::optional<int> compare_qp_exact(const QpParts& p, const QpParts& q);

}  // namespace pdd::fast
