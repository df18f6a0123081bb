// candidate_directions.h — the candidate separating directions of a pair (SPEC §3, paper eq. 6).
//
// Input:  tetrahedra A (s0..s3) and B (r0..r3), raw doubles.
// Output: CandidateSet: the oriented directions in canonical order (FV:0..3, VF:0..3, EE:a:b with
//         ':+' before ':-'), each with
//           n      unnormalised vector pointing from A to B,
//           nn     = n.n,
//           hA,hB  heights H = n.(x − o) of the 8 vertices (o: a point of the candidate's own
//                  choosing; only differences of heights are ever used),
//           conA,conB  bit masks of the constrained vertices C_A, C_B,
//           depth  D = max_i hA_i − min_j hB_j, so delta(n) = D/|n| (SPEC §4),
//         and `intersecting` = (every D > 0), i.e. min delta > 0.
// Every combinatorial decision — orientation of A and B (sign of the volume, also the validity
// test), parallel edges (n == 0), colinear edges, the signs of g_k (keep / flip / undecidable),
// and the sign of each D (intersection) — is exact: a floating-point value is trusted only when
// it exceeds the static bound of filter_bounds.h, otherwise exact_predicates.h decides.
// Constrained vertices of one tetrahedron share one height by construction (they are exactly
// coplanar with the plane orthogonal to n), so the solver sees exactly equal values.
// No heap allocation: the set is a fixed-capacity array.
#pragma once

#include <cstdint>

#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

// 8 face directions + 36 edge pairs, each edge pair at most twice (undecidable).
inline constexpr int kMaxCandidates = 8 + 2 * 36;

struct Candidate {
  DirectionLabel label;
  double n[3];
  double nn;
  double depth;
  double hA[4], hB[4];
  std::uint8_t conA, conB;
};

struct CandidateSet {
  int count = 0;
  bool intersecting = false;  // valid only when build_candidates returned Ok
  Candidate c[kMaxCandidates];
};

enum class BuildStatus { Ok, NonFiniteA, NonFiniteB, DegenerateA, DegenerateB };

// Fills `out`. When the pair does not intersect the set may be left incomplete (the scan stops
// at the first exactly separating candidate): only `intersecting == false` is then meaningful.
BuildStatus build_candidates(const TetVertices& A, const TetVertices& B, CandidateSet& out);

}  // namespace pdd::fast
