// candidate_directions.h — the candidate separating directions of a pair (definitions §3,
// paper eq. 6).
//
// Input:  tetrahedra A (s0..s3) and B (r0..r3), raw doubles.
// Output: CandidateSet: the oriented directions in canonical order (FV:0..3, VF:0..3, EE:a:b with
//         ':+' before ':-'); per candidate k
//           label(set, k)  definitions §3 label,
//           depth[k]   D = max_i n.s_i − min_j n.r_j for the oriented unnormalised n, so that
//                      delta(n) = D/|n| (definitions §4),
//           nn[k]      n.n,   delta_sq[k] = D²/(n.n) (edge lanes: D²·(1/n.n)),
//         and, materialised on demand by candidate(set, k): n, the heights H = n.(x − o) of the 8
//         vertices (o a point of the candidate's own choosing; only height differences are used)
//         and the constrained masks C_A, C_B. `intersecting` = every D > 0 (min delta > 0).
// Every combinatorial decision — orientation of A and B (sign of the volume, also the validity
// test), parallel edges (n == 0), colinear edges, the signs of g_k (keep / flip / undecidable),
// and the sign of each D (intersection) — is exact: a floating-point value is trusted only when
// it exceeds the static bound of filter_bounds.h, otherwise exact_predicates.h decides.
// Constrained vertices of one tetrahedron share one height by construction (they are exactly
// on the plane orthogonal to n), so the solvers see exactly equal values.
// Layout: the 36 edge pairs are computed as structure-of-arrays "lanes" (lane = 8a + b), so the
// arithmetic vectorises; the set stores per candidate only its label, D, n.n and the lane.
// No heap allocation: fixed-capacity arrays.
#pragma once

#include <cstdint>

#include "certification/filter_bounds.h"
#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

// 8 face directions + 36 edge pairs, each edge pair at most twice (undecidable).
inline constexpr int kMaxCandidates = 8 + 2 * 36;
inline constexpr int kLaneStride = 8;  // lanes b = 6, 7 of each edge a are padding
inline constexpr int kLanes = 6 * kLaneStride;

// Geometry of one direction: everything the per-direction solvers need.
struct DirectionGeometry {
  double n[3];          // oriented A -> B, unnormalised
  double nn;            // n.n
  double depth;         // D
  double hA[4], hB[4];  // heights n.(x − o)
  std::uint8_t conA, conB;  // bit i: vertex i constrained (definitions §3)
};

struct Candidate : DirectionGeometry {
  DirectionLabel label;
  bool parallel = false;  // a parallel edge pair: n of degree 3, heights of degree 4
  // A nearly parallel edge pair: n rounded from its exact value, error bounds of its own
  // (value_bounds.h, own_degree_bounds): per-height own_eh, per-component own_en.
  bool own_bounds = false;
  double own_eh = 0.0, own_en = 0.0;
};

// A label packed in 16 bits (kind | a << 2 | b << 5 | orientation << 8): plain integers keep
// the set trivially constructible (DirectionLabel has member initialisers).
using LabelCode = std::uint16_t;
constexpr LabelCode pack_label(ContactKind k, int a, int b, EdgeOrientation o) {
  return LabelCode(int(k) | a << 2 | b << 5 | int(o) << 8);
}
inline DirectionLabel unpack_label(LabelCode c) {
  return {ContactKind(c & 3), (c >> 2) & 7, (c >> 5) & 7, EdgeOrientation((c >> 8) & 3)};
}

// Edge-pair lanes, unoriented n = eB × eA (definitions §3), heights relative to s_u:
// A: 0, 0, g1, g2 at (u, v, k1, k2); B: hx, hx, hx + q1, hx + q2 at (x, y, j1, j2), where
// (k1 < k2) are the vertices off edge a and (j1 < j2) those off edge b.
struct EdgeLanes {
  alignas(64) double n0[kLanes], n1[kLanes], n2[kLanes], nn[kLanes], hx[kLanes];
  alignas(64) double g1[kLanes], g2[kLanes], q1[kLanes], q2[kLanes];
  alignas(64) double dplus[kLanes], dminus[kLanes];  // D for +n and for −n
  alignas(64) double d2plus[kLanes], d2minus[kLanes];  // D²/(n.n) for +n and for −n
  // Filter verdicts of the lane (definitions §3 orientation rule on the signs of g1, g2):
  //   unclear = 1 when a sign of n, g1, g2 or of a used depth is within its filter bound (the
  //             lane then goes through the exact path), else 0;
  //   first   = delta² of the lane's first candidate (+n, or −n when both g > 0);
  //   second  = delta² of the ':-' candidate of an undecidable pair, +inf otherwise.
  alignas(64) double unclear[kLanes], first[kLanes], second[kLanes];
};

struct CandidateSet {
  int count = 0;
  bool intersecting = false;  // valid only when build_candidates returned Ok
  double tie_kappa = 0.0;     // the pair's tie band (tie_tolerance.h)
  FilterBounds fb;            // the pair's error bounds (filter_bounds.h, value_bounds.h)
  // The pair the set was built from (refine.h evaluates a few candidates exactly); valid as
  // long as the caller's pair lives (every user keeps both in one scope).
  const TetVertices* A = nullptr;
  const TetVertices* B = nullptr;
  LabelCode code[kMaxCandidates];  // label, see label(set, k)
  double depth[kMaxCandidates];
  double nn[kMaxCandidates];
  double delta_sq[kMaxCandidates];  // D²/(n.n) = delta(n)²
  // (16-bit, not 8-bit: char types alias everything and would pessimise the build loop)
  std::int16_t lane[kMaxCandidates];  // edge lane, or −1: stored in full in explicit_[k]
  std::int16_t sign[kMaxCandidates];  // orientation of a lane candidate: ±1
  // explicit candidates: 1 a parallel edge pair, 2 a nearly parallel one (its own bounds), else 0
  // (0 on lane candidates too: every entry written, in the build loop: 16-bit as lane and sign)
  std::int16_t parallel[kMaxCandidates];
  // Each candidate's degree bounds (value_bounds.h: per-height e_h, per-component e_n of n): its
  // class's (degree_bounds of fb) or, where parallel[k] == 2, its own (own_degree_bounds).
  // Stored, not chosen where read: on aligned pairs the classes interleave in the list, and a
  // choice by tests at every read mispredicted (~150 a pair on a Kuhn grid shifted a quarter cell
  // along (1, 1, 1), cachegrind's model).
  double e_h[kMaxCandidates], e_n[kMaxCandidates];
  // along_face[k] = f (0..3) where candidate k is an edge pair whose oriented direction is
  // exactly a positive multiple of FV:f's: edge a lies on A's face f and eB.N_f = 0 exactly (the
  // g of the face's third vertex is 0; the other g < 0 decides the orientation, out of face f).
  // Every variant's QP along it is >= FV:f's (deformable_depth.h, "Edge pairs along a face of
  // A"), and FV:f precedes it in canonical order: the sweeps leave it out; its depth has FV:f's
  // sign (build_candidates does not decide it again). Set on written lanes and on the decided
  // edge pairs edge_pair_general takes with a non-zero n (exactly parallel pairs: −1); −1
  // otherwise (no claim: such a pair is evaluated as any other).
  std::int16_t along_face[kMaxCandidates];
  // A certified lower bound of candidate k's exact delta², from its exact depth where the build
  // took it to decide the depth's sign (integer_depth.h's framed_delta2: a contact made by
  // rounding, whose near-normal candidates have delta² ~1e-34 of L², below the doubles' error,
  // so that their double bounds read 0); 0 elsewhere. The values' sweeps and rigid_pd2's
  // refinement prune with it. Written (all of it) only where some is known: delta_lower_known.
  bool delta_lower_known = false;
  double delta_lower[kMaxCandidates];
  EdgeLanes edges;
  DirectionGeometry explicit_[kMaxCandidates];  // faces, and exactly decided edge pairs
};

enum class BuildStatus { Ok, NonFiniteA, NonFiniteB, DegenerateA, DegenerateB };

// Fills `out`. When the pair does not intersect the set may be left incomplete (the scan stops
// at the first exactly separating candidate): only `intersecting == false` is then meaningful.
BuildStatus build_candidates(const TetVertices& A, const TetVertices& B, CandidateSet& out);

struct QuickCandidates;  // quick_candidates.h

// build_candidates on the faces and lanes of a quick list: one whose faces are all certain
// (q.count == 8: the pair's orientations and every face depth certain, declined on its lanes or
// not), or one filled by quick_lanes(..., all_faces = true) (faces_filled: orientations
// certain, some face depth within its bound, decided exactly here as build_candidates does).
// The lanes are build_candidates' own bit for bit (the superset kernel computes them with its
// verdicts, superset_kernel.h), and so are the faces, the filter bounds and the tie band, so
// only the exact decisions are left to do. The same set as build_candidates(*q.A, *q.B)
// (tested); Ok always (the orientations are certain).
BuildStatus build_candidates(const QuickCandidates& q, CandidateSet& out);

// build_candidates for callers that often ask for the same pair twice in a row on one thread
// (the depth stage: rigid_pd2 then pdd2_accel on the same rescaled pair), built into the
// thread's own set (no copy of its ~20 KB either way). The set returned stays valid until the
// thread's next call; an input equal to the last one bit for bit gets it again, with A, B
// pointing to the caller's pair. build_candidates is a function of the coordinates' bits, so the
// set is the one build_candidates would return. `status`: build_candidates' return value.
// `declined`: a quick list of the same A, B that declined on its lanes alone (above), to build
// from; else null.
const CandidateSet& build_candidates_reusing(const TetVertices& A, const TetVertices& B, BuildStatus& status,
                                             const QuickCandidates* declined = nullptr);

// The number of edge lanes of an intersecting set that took the exact path (edges.unclear set):
// where it is not 0, quick_lanes (quick_candidates.h), whose lanes are these bit for bit,
// declines on the same pair.
int exact_lanes(const CandidateSet& set);

// Candidate k of the set with its heights (cheap: a few loads and sign flips).
Candidate candidate(const CandidateSet& set, int k);

// definitions §3 label of candidate k.
inline DirectionLabel label(const CandidateSet& set, int k) { return unpack_label(set.code[k]); }

// The face f (FV:f, candidate f) when candidate k is an edge pair along it (along_face), else
// −1. Such a pair is never the first of its exact ties in delta² nor in any variant's QP
// value, FV:f coming first with the same delta² and a value at or below (deformable_depth.h):
// where the choice is not k itself, it is left out of the minimum of lower bounds and of the
// contenders.
inline int along_face_of_A(const CandidateSet& set, int k) { return set.along_face[k]; }

// delta(n)² of candidate k: D²/(n.n).
inline double delta2(const CandidateSet& set, int k) { return set.delta_sq[k]; }
// A certified lower bound of candidate k's exact delta² known without arithmetic
// (CandidateSet::delta_lower), or 0.
inline double delta2_known_lower(const CandidateSet& set, int k) {
  return set.delta_lower_known ? set.delta_lower[k] : 0.0;
}
inline LabelCode label_code(const CandidateSet& set, int k) { return set.code[k]; }

}  // namespace pdd::fast
