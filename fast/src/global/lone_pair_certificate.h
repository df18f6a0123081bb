// lone_pair_certificate.h — internal to fast/src/global: pdd2_global certified without the
// pieces where the minimiser moves one vertex of each tetrahedron (the rigid depth's bound,
// attained: a vertex of one block resting on a vertex of the other, as blocks set on each
// other's columns are: A's top at 3 x 0.1 = 0.30000000000000004, B's bottom at 0.3), or one
// edge of each on translates of one line (certify_edge_pair, below).
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
// L is computed rigorously (facet_bounds.h: each candidate direction n exactly, its overlaps
// rounded down, n.n rounded up; L = min over the directions of D^2 / (32 n.n), rounded down).
// A candidate normal v is only a guess: its value is evaluate_tight's, certified or not taken.
// Where the lone pair's cone meets a neighbouring piece whose two more vertices are close to the
// plane (a vertex resting 1e-9 deep on a vertex, A's and B's edges at it leaving along common
// lines), the minimiser lies just inside that piece, its value ~1e-8 above L: the certificate
// declines, and gives the extreme ray nudged out of the cone (near_minimiser) for the shallow
// certificate to start from (global_depth.cpp).
#pragma once

#include "global/facet_bounds.h"
#include "global/relaxed_value.h"

namespace pdd::fast::global {

struct LonePairResult {
  V3 normal{};      // v (A -> B, unnormalised)
  Evaluation eval;  // relaxed(v): value, error <= kGlobalRel, solution and heights
  double lower = 0; // L = PD^2 / 32 rounded down: every relaxed(u) >= L
  // Declined with a lone pair's candidate evaluated (certified) above the bound: that normal
  // (next to the minimiser where the lone pair's cone meets another piece), else 0.
  V3 near_minimiser{};
  // Declined with an edge pair's candidate evaluated: its d = a - b (exact), for which
  // relaxed(u) >= (u.d)^2 / 12 wherever u.d >= 0 (certify_edge_pair), else 0: a bound the
  // shallow certificate can take beside its own where the minimiser lies off the edge pair's
  // regime (an edge on a collinear edge whose tetrahedron's face through it reaches the plane).
  V3 edge_d{};
  V3 edge_v{};  // that edge pair's candidate normal (a start for the shallow certificate), else 0
  // That edge pair's edges are translates (a2 - a = b2 - b exactly); false: translates only up
  // to a rounding (edges resting on nearly collinear ones: a turned scene's).
  bool edge_translate = true;
};

bool certify_lone_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out);

// Edge pairs: an edge of A on the collinear edge of B, as two decimal blocks set on each other's
// columns put them (A's top edge 5.6e-17 above B's bottom edge), or an edge resting on a nearly
// collinear one (two blocks resting on each other 1e-9 deep, both turned: their edges are
// translates only up to a rounding). For any two vertices a, a2 of A and b, b2 of B, the
// relaxed QP kept to their four constraints (dropping constraints lowers the minimum) moves a
// and a2 down, b and b2 up; its value V(h) is a convex function of their heights h = (u.a,
// u.a2, u.b, u.b2) along the unit u (a convex QP whose right-hand side is linear in them),
// unchanged by a common shift, and symmetric: exchanging the two ends of both sides, sh =
// (u.a2, u.a, u.b2, u.b), gives the same problem (the object norm treats a tetrahedron's
// vertices alike). So V(h) = (V(h) + V(sh)) / 2 >= V((h + sh) / 2), where A's two heights are
// equal and so are B's, p = u.d apart, d = (a + a2 - b - b2) / 2 the mean offset: there V =
// p^2 / 12 (two vertices of a tetrahedron moved by t, its two free ones following by -2t/3,
// cost t^2 / 6 a side, the depth p split evenly). Hence relaxed(u) >= (u.d)^2 / 12 where u.d >=
// 0, beside relaxed(u) >= D(u)^2 / 32 everywhere; for translates (a2 - a = b2 - b) d = a - b.
// d is rounded (d~, within d_error: the slab below is widened by it). With L = V (1 - 9e-10), V the
// candidate's certified value, every unit u then has relaxed(u) >= L when u.d >= c0 = sqrt(12 L)
// or D(u) >= d0 = sqrt(32 L): checked by the polytope {u : D(u) <= d0, u.d <= c0} lying inside
// the unit ball (its vertices, from the facet normals of M bounded exactly as above). The
// candidate normals: perpendicular to the edge and to a third vertex's offset from its bound
// (the midpoint of a and b, -d/3 for A's, +d/3 for B's: a tetrahedron's free vertices follow by
// -2t/3), nudged into the regime across the edge, and, for translates, exactly across it: at a
// depth ~1e-17 of the size a double normal tilted along the edge by its rounding splits the two
// ends' heights by a fraction of the depth (the value ~1e-3 off; at a depth of 1e-9 of the size
// by 1e-8 of it, which moves the value by its square), so the edge needs a double triple
// exactly across it: where it has a zero
// component (an edge in a coordinate plane, as every edge of a grid's faces) one lies across it
// by construction, else one is solved for and kept where its dot product with the edge is
// exactly 0 (a cube's diagonal, (h, h, h)). Measured on the
// same blocks: every edge on a collinear edge, 256 Kuhn pairs and 320 five-tetrahedra ones
// (120 of which pdd2_global declined: no double normal near the rounded ones attained the
// value), docs/performance.md, "Vertex on vertex".
bool certify_edge_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out);

// The vertex pairs' certificate, else the edge pairs' (the facet normals' bounds computed once).
bool certify_lone_pairs(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out);

// The same with the pair's facet bounds given (global_depth.cpp shares them with the shallow
// certificate's overlap test).
bool certify_lone_pairs(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds,
                        LonePairResult& out);


}  // namespace pdd::fast::global
