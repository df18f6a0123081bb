// quick_candidates.h — the candidate list of the hot path (definitions §3), when no exact decision
// is needed.
//
// Input:  tetrahedra A, B (raw doubles).
// Output: QuickCandidates: the same candidates as build_candidates (candidate_directions.h), in
//         the same canonical order, with bit-identical delta², n, n.n, D and heights — but no
//         label array (labels are derived on demand) and no exact fallback: quick_candidates
//         declines (returns false) whenever a filter verdict is unclear, the pair may not
//         intersect, or the input is invalid; callers then use build_candidates.
// Used by the convenience functions over raw tetrahedra (deformable_depth.h). The arithmetic is
// that of the superset kernel (src/kernel/superset_kernel.h, one vectorised pass that also writes the
// edge lanes), bit-identical to build_candidates' (tested).
#pragma once

#include "kernel/candidate_directions.h"

namespace pdd::fast {
namespace detail {
struct SupersetLanes;  // superset_kernel.h
}

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
  // quick_lanes(..., all_faces = true) only: the eight faces and the lanes are filled (the
  // orientations certain), some face's depth within its filter bound where count is 0.
  bool faces_filled = false;
};

// Fills `q` and returns true when the pair is valid, intersecting and every filter verdict
// clear; returns false otherwise (degenerate or near-degenerate input, non-intersecting or
// invalid pair) — then use build_candidates.
bool quick_candidates(const TetVertices& A, const TetVertices& B, QuickCandidates& q);

// quick_candidates in two steps: quick_lanes fills everything but the edge candidates (count =
// 8, the faces; the lanes and their verdicts are set) and declines as quick_candidates does;
// quick_edge_list then appends the edge candidates. Between the two, the lanes can be used
// directly by entry (below), as deformable_depth.cpp's lane sweeps do.
// `all_faces`: where a face's depth is within its filter bound, the other faces are still
// finished (faces_filled) for build_candidates(q), which decides that depth exactly.
// `kernel` (optional): where the superset kernel's lanes are kept (always filled, whatever is
// returned: superset_kernel(A, B, *kernel, ...)), for rigid_superset_of_kernel (superset_depth.h).
bool quick_lanes(const TetVertices& A, const TetVertices& B, QuickCandidates& q, bool all_faces = false,
                 detail::SupersetLanes* kernel = nullptr);
void quick_edge_list(QuickCandidates& q);

// An entry is a candidate's `src` (a face f < 8, or 8 + 2·lane + [oriented by −n]), usable
// before the list exists; which entries are candidates: the orientation rule on the lane's g
// signs (qp_lower_bound.cpp writes it as a mask). Its candidate and label:
Candidate entry_candidate(const QuickCandidates& q, int src);
LabelCode entry_label_code(const QuickCandidates& q, int src);

// Candidate k of a quick list (label included).
inline Candidate candidate(const QuickCandidates& q, int k) { return entry_candidate(q, q.src[k]); }
inline double delta2(const QuickCandidates& q, int k) { return q.delta_sq[k]; }
// (A quick list takes no exact depth: nothing known beyond its double bounds.)
inline double delta2_known_lower(const QuickCandidates&, int) { return 0.0; }
// No quick list holds an edge pair along a face of A (its g of 0 is within its filter bound).
inline int along_face_of_A(const QuickCandidates&, int) { return -1; }
inline LabelCode label_code(const QuickCandidates& q, int k) { return entry_label_code(q, q.src[k]); }

}  // namespace pdd::fast
