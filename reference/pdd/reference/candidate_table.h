// candidate_table.h — every quantity of definitions §4–§5 evaluated on every candidate direction.
//
// Input : an exact pair and its candidates (candidate_directions), a QP formulation.
// Output: one row per candidate, in canonical order: the oriented depth (as its exact signed
//         square), eq. 11's overlap, and the per-direction QP optima of the three cases
//         (static is nullopt where the case-1 QP is infeasible). solve_exact takes minima over
//         these rows; audits and the paper experiment read them directly.
#pragma once

#include <optional>
#include <vector>

#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/direction_qp.h"

namespace pdd::reference {

struct CandidateRow {
  CandidateDirection direction;
  Rational depth;                 // D = max n.s_i − min n.r_j (n unnormalised), definitions §4
  Rational depth_signed_square;  // sign(delta) delta^2 = sign(D) D² / n.n
  std::optional<DirectionOptimum> static_case;  // paper case 1
  DirectionOptimum deformable;                  // paper case 2
  DirectionOptimum relaxed;                     // case 2, inequalities only
};

// The formulation of the case QPs (every row has all three solved).
struct CandidateTableOptions {
  QpFormulation formulation = QpFormulation::Full;
};

std::vector<CandidateRow> candidate_table(const ExactPair& pair,
                                          const std::vector<CandidateDirection>& candidates,
                                          const CandidateTableOptions& options);

// The row of the one candidate labelled `label` (computed alone, as candidate_table would);
// nullopt when the pair has no such candidate (e.g. the label of a colinear edge pair). For
// consumers that need a candidate the result does not name (the judge of a fast label, a
// figure), so that they ask the engine instead of re-deriving directions and re-solving QPs.
std::optional<CandidateRow> candidate_row(const ExactPair& pair, const DirectionLabel& label,
                                          const CandidateTableOptions& options);

// Candidate indices sorted by oriented depth ascending, stable in canonical order (case 3).
std::vector<std::size_t> depth_order(const std::vector<CandidateRow>& rows);

}  // namespace pdd::reference
