// candidate_directions.h — the candidate separating directions of paper Sec. IV-A (eq. 6 and
// its orientation rules), exactly as definitions §3 fixes them, in canonical order.
//
// Input : an exact pair (A = s0..s3, B = r0..r3).
// Output: every candidate direction n (exact, unnormalised, pointing from A to B) with its
//         label and its constrained/free vertex sets:
//   FV:i    n = (v1-v0) x (v2-v0) on A's face opposite s_i, oriented out of A;
//           C_A = the face, F_A = {s_i}, C_B = {}, F_B = all of B.
//   VF:j    the same on B's face opposite r_j, oriented into B;
//           C_A = {}, F_A = all of A, C_B = the face, F_B = {r_j}.
//   EE:a:b  n = (r_y - r_x) x (s_v - s_u); parallel edges: n = w - (w.e/e.e) e with
//           e = s_v - s_u, w = r_x - s_u (we store the positive multiple (e.e) w - (w.e) e,
//           same direction, dyadic); colinear edges: no direction. Orientation from
//           g_k = n.(s_k - s_u) over A's two other vertices: both <= 0 keep n, both >= 0 use
//           -n, otherwise undecidable: n (":+") then -n (":-").
//           C_A, C_B = the two edges; F_A, F_B = the other two vertices of each.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "pdd/direction_label.h"
#include "pdd/tet_tables.h"
#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {


struct CandidateDirection {
  DirectionLabel label;
  Vector n;                       // exact, unnormalised, A -> B
  std::array<bool, 4> constrained_A{};  // true: in C_A, false: in F_A
  std::array<bool, 4> constrained_B{};  // true: in C_B, false: in F_B
  std::optional<EdgePairKind> edge_kind;  // how an edge pair resolved (pdd/tet_tables.h); none for faces
};

// All candidates in canonical order (44 for a generic pair, +1 per undecidable edge pair,
// -1 per colinear edge pair).
std::vector<CandidateDirection> candidate_directions(const ExactPair& pair);

// The edge pairs that produce no direction (colinear edges), as (edge of A, edge of B).
std::vector<std::array<int, 2>> colinear_edge_pairs(const ExactPair& pair);

}  // namespace pdd::reference
