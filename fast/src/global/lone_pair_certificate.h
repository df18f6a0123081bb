// lone_pair_certificate.h — internal to fast/src/global: pdd2_global certified by the rigid
// depth's bound, without the pieces, where the minimiser moves one vertex of each tetrahedron
// (a vertex of one block resting on a vertex of the other, as blocks set on each other's
// columns are: A's top at 3 x 0.1 = 0.30000000000000004, B's bottom at 0.3).
//
// Input : the pair (engine units, global_depth.h) and its Problem.
// Output: true with a normal v (A -> B, doubles), its certified evaluation (relaxed_value.h's
//         evaluate_tight: value V within kGlobalRel of relaxed(v)) and a proved lower bound L on
//         relaxed(u) over every unit u with V (1 + kGlobalRel) <= L (1 + 8e-10); false when no
//         candidate normal reaches that (the caller then searches the exact pieces).
//
// Math. Along every unit u, relaxed(u) >= D(u)^2 / 32 (deformable_depth.h: keep only A's highest
// vertex a and B's lowest b, D(u) = u.(a - b) the overlap), and D(u) >= PD, the rigid depth
// (the least overlap over all directions: the distance from the origin to the boundary of
// M = A - B, attained at a facet normal of M, so at a face normal of A or B or the cross product
// of an edge of A and an edge of B, either orientation). So every relaxed(u) >= PD^2 / 32 =: L.
// The bound is attained where the relaxed QP moves a alone and b alone: then each moves by D/2
// and its tetrahedron's other vertices follow by -D/8 (the free optimum of deformable_depth.h's
// one-vertex cost), so the plane lies at the midpoint m of a and b, and the lone pair holds while
// A's other vertices x stay below m - D/8 and B's others y above m + D/8 (u.(a - b) = D). On that
// cone of normals relaxed(u) = (u.(a - b))^2 / 32, least at an extreme ray, where two of the six
// other vertices reach their bounds: u perpendicular to x - (m - d/8) and to y - (m + d/8)
// (d = a - b; the same offset for two vertices of one side), so
//     v = (x - p_x) x (y - p_y),   p_A = m - d/8,  p_B = m + d/8.
// When a and b nearly coincide (|d| ~ the depth, far below the size), the minimiser of that
// piece lies within ~|d| / size rad of the direction minimising D, so relaxed(v) exceeds L by a
// relative ~|d| / size: ~1e-16 on contacts made by rounding, far inside the 8e-10 the check
// leaves. Measured on 5-tetrahedra and Kuhn blocks set on each other's columns by rounding:
// 896 of 1310 and 384 of 743 pairs that took the exact pieces have pdd2_global = rigid_pd2 / 32
// within 1e-10 (docs/performance.md, "Vertex on vertex").
// L is computed rigorously: each candidate direction n exactly (expansion.h: cross products of
// coordinate differences), its overlaps D(+-n) = max of the exact heights' differences, each
// rounded down from its exact expansion (approx_of's bound), n.n rounded up; L = min over the
// directions of D^2 / (32 n.n), rounded down. A candidate normal v is only a guess: its value
// is evaluate_tight's, certified or not taken.
#pragma once

#include "global/relaxed_value.h"

namespace pdd::fast::global {

struct LonePairResult {
  V3 normal{};      // v (A -> B, unnormalised)
  Evaluation eval;  // relaxed(v): value, error <= kGlobalRel, solution and heights
  double lower = 0; // L = PD^2 / 32 rounded down: every relaxed(u) >= L
};

bool certify_lone_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out);

// A proved lower bound on PD^2, the rigid depth squared (the least squared overlap over unit
// directions), within a few u of it; false where expansion.h cannot take the pair (a coordinate
// outside its exact range, an expansion over its capacity) or the pair does not intersect.
bool rigid_depth_squared_lower(const TetVertices& A, const TetVertices& B, double& pd2_low);

}  // namespace pdd::fast::global
