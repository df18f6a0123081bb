// superset_kernel.h — internal to fast/src: the vectorised arithmetic over the superset of
// candidate directions (superset_depth.h): D, n.n and D²/(n.n) of the 8 faces and of both
// orientations of the 36 edge pairs, the tie-band masks, and optionally the full edge lanes of
// the candidate list (EdgeLanes, with filter verdicts) for quick_candidates.
//
// Input:  tetrahedra A, B (raw doubles).
// Output: SupersetLanes (below). All values bit-identical to direction_geometry's arithmetic (same
//         IEEE operations in the same order); arithmetic and flop count in superset_kernel.cpp.
//         Non-finite input: garbage values and `finite` != 0; callers check `finite` first.
#pragma once

#include <cstdint>

#include "kernel/direction_geometry.h"
#include "kernel/edge_pair_formula.h"

namespace pdd::fast::detail {

// v8, v8l: edge_pair_formula.h.


// The far-entry skip of the bound bits (proof at tie_and_certify_bits, superset_kernel.cpp): an
// entry with value > kFarFactor · t2, D² >= (kFarBoundScale e_h)² and n.n >= (kFarBoundScale e_n)²
// cannot change certify()'s verdict.
inline constexpr double kFarFactor = 1.001, kFarBoundScale = 1e5;

// Output of the vector kernel (lanes: see superset_kernel.cpp).
struct alignas(64) SupersetLanes {
  v8 X[3];          // the pair's coordinates (scaled, superset_kernel_scaled), lanes s0..s3, r0..r3
  v8 EA[3], EB[3];  // edge vectors of A and of B, lanes = edges (padding 0), per coordinate
  v8 NAB[3];        // raw face normals, lanes NA[0..3], NB[0..3], per coordinate
  v8 det;           // lanes 3 and 7: det of A and of B (edges_and_faces)
  v8 dp[6], dm[6];  // D(+n), D(−n) per edge pair (a, b)
  v8 inv[6];        // 1/(n.n)
  v8 val[6];        // min(D(±n))² / (n.n)   (padding: +inf)
  v8 G[4];          // eB[b] . NA[f]
  v8 face_val;      // D²/(n.n) of the faces
  v8 H[4];          // face heights: lane f, vertex j of the other tetrahedron (face_draft)
  double extent;    // L of filter_bounds.h
  double finite;    // 0 when every coordinate is finite (else NaN)
  double lo;        // min over S of D (positivity)
  double vmin;      // min over S of the value
  double kappa;     // tie band of the pair (tie_tolerance.h)
  double t1, t2;    // tie_threshold(vmin); the bound on tie_threshold(t1) used for the masks
  std::uint8_t face_bits;   // faces with value <= t2
  std::uint64_t lane_bits;  // edge pairs (bit 8a + b) with min(value(±n)) <= t2
  // Entries that superset_depth.cpp's certify() must bound (the others are provably far from
  // the minimum: see tie_and_certify_bits in superset_kernel.cpp): faces, and edge pairs (bit 8a + b).
  std::uint8_t face_bound_bits;
  std::uint64_t lane_bound_bits;
};

// Fills K. When `full` is non-null, also every field of the candidate list's edge lanes
// (EdgeLanes), filter verdicts included (bounds of filter_bounds.h for K.extent).
void superset_kernel(const TetVertices& A, const TetVertices& B, SupersetLanes& K, EdgeLanes* full);

// superset_kernel(power_scaled(A, B).A, power_scaled(A, B).B, K, nullptr), bit for bit, with the
// scaling fused into the kernel (no scaled copy of the pair; power_scale.h's reductions on the
// kernel's coordinate vectors): true, with power_scaled's exponent e, when power_scale.h's
// common case applies and is exact (common_scale); false otherwise (K not filled: the caller
// scales the general way).
bool superset_kernel_scaled(const TetVertices& A, const TetVertices& B, SupersetLanes& K, int& e);

// K without the edge pairs of `unresolved` (bit 8a + b; superset_depth.cpp's
// choice_without_unresolved): K.lo, K.vmin over the faces and the other lanes, the thresholds
// t1, t2 from the new minimum, and the tie and bound bits by tie_and_certify_bits' rules (the
// far-entry skip tested on each entry's own D² and n.n against D_min2 = (kFarBoundScale e_h)²
// and nn_min = (kFarBoundScale e_n)²). False, K unchanged, when the new lo is not above deg3 (a
// possibly non-positive depth).
bool drop_lanes(SupersetLanes& K, double deg3, double D_min2, double nn_min, std::uint64_t unresolved);

// Face f (FV:f for f < 4, VF:(f − 4) otherwise) as face_of_A / face_of_B write it, from the
// kernel's normals, determinants and heights; finish_face then gives the candidate.
void face_draft(const SupersetLanes& K, int f, Draft& d);

}  // namespace pdd::fast::detail
