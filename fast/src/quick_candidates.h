// quick_candidates.h — the candidate list of the hot path (SPEC §3), when no exact decision is
// needed.
//
// Input:  tetrahedra A, B (raw doubles).
// Output: QuickCandidates: the same candidates as build_candidates (candidate_directions.h), in
//         the same canonical order, with bit-identical delta², n, n.n, D and heights — but no
//         label array (labels are derived on demand) and no exact fallback: quick_candidates
//         declines (returns false) whenever a filter verdict is unclear, the pair may not
//         intersect, or the input is invalid; callers then use build_candidates.
// Used by the convenience functions over raw tetrahedra (deformable_depth.h). The arithmetic is
// that of the superset kernel (src/superset_kernel.h, one vectorised pass that also writes the
// edge lanes), bit-identical to build_candidates' (tested).
#pragma once

#include "candidate_directions.h"

namespace pdd::fast {

// The candidate list of the hot path, when every filter verdict is clear (no exact fallback, no
// label array): the same candidates, in the same canonical order, with bit-identical delta²,
// heights, n and n.n as build_candidates. Candidate k is a face (src < 8) or an edge lane
// (src = 8 + 2·lane + [oriented by −n]).
struct QuickCandidates {
  int count = 0;
  double tie_kappa = 0.0;  // the pair's tie band (tie_tolerance.h)
  FilterBounds fb;         // the pair's error bounds (value_bounds.h)
  // The pair (refine.h); valid as long as the caller's pair lives (as CandidateSet's).
  const TetVertices* A = nullptr;
  const TetVertices* B = nullptr;
  double delta_sq[kMaxCandidates];
  double depth[kMaxCandidates], nn[kMaxCandidates];  // D and n.n of each candidate
  std::int16_t src[kMaxCandidates];
  DirectionGeometry faces[8];
  EdgeLanes edges;
};

// Fills `q` and returns true when the pair is valid, intersecting and every filter verdict
// clear; returns false otherwise (degenerate or near-degenerate input, non-intersecting or
// invalid pair) — then use build_candidates.
bool quick_candidates(const TetVertices& A, const TetVertices& B, QuickCandidates& q);

// Candidate k of a quick list (label included).
Candidate candidate(const QuickCandidates& q, int k);
inline double delta2(const QuickCandidates& q, int k) { return q.delta_sq[k]; }
LabelCode label_code(const QuickCandidates& q, int k);

}  // namespace pdd::fast
