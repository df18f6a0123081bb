// shallow_certificate.h — internal to fast/src/global: pdd2_global certified without the pieces
// for a contact far shallower than the pair (the contacts made by rounding: depths ~1e-17 of the
// size, values ~1e-34 of its square), where the double pieces cannot resolve the value and the
// exact ones cost milliseconds.
//
// Input : the pair (engine units, global_depth.h), its Problem, a start normal v0 (A -> B).
// Output: true with a normal v (+ low, in double words), its certified evaluation (relaxed_value.h's
//         evaluate_tight: value V within kGlobalRel of relaxed(v)) and a proved lower bound
//         L >= V (1 - kShallowGap) on relaxed(u) over every unit u; false when any step below
//         fails (the caller then searches the exact pieces).
//
// Math. The relaxed QP along n (direction_qp.h's form: heights H = n.x, displacements T, plane
// C, cost F = sum_tets T^T (I + J) T, relaxed(n) = F* / (20 n.n)) has, for multipliers l, m >= 0
// with sum l = sum m, the Lagrangian dual value
//     q(n) = n.g - kappa,   g = sum_i l_i a_i - sum_j m_j b_j,
//     kappa = (l^T (I - J/5) l + m^T (I - J/5) m) / 4            ((I + J)^-1 = I - J/5),
// and weak duality F*(n) >= q(n) holds for every n with the same (l, m) (the dual's feasible set
// does not depend on n). Scaling (l, m) by s >= 0 gives F*(n) >= s n.g - s^2 kappa, so for a
// unit u with u.g >= 0:
//     relaxed(u) >= (u.g)^2 / (80 kappa).                                              (1)
// (1) is sharp only where u is parallel to g. At a contact by rounding the double multipliers'
// g points anywhere (its part across v is ~|l| size, the value ~|l| depth), so the multipliers
// are moved, exactly, by the least change of three of them that makes sum l = sum m and g
// parallel to v (a 3 x 3 rational system; the change is ~1e-16 of them, and must keep them
// >= 0; where a minimiser lies where pieces meet, a multiplier at the plane is ~0 and the
// change may turn it negative: then another three, a vertex off the plane among them, since
// weak duality holds for multipliers >= 0 on every vertex; likewise where the moved g points
// away from v, g.v <= 0: a vertex of one grid on the collinear edge of its shifted copy puts
// the active vertices on one line, and the three of them move to any g). Where the bound below
// then falls short of L (a minimiser where pieces meet: the evaluation's multipliers, even
// moved, bound it at about half its value), the multipliers are the optimum of the dual over
// the plane across v instead (g parallel to v among the constraints: its value is the least of
// F*(n) = 20 |n|^2 relaxed(n/|n|) over the plane n.v = v.v, so B0 = relaxed(v) where v is that
// plane's minimiser), v moved to that minimiser first (shallow_certificate.cpp's plane_dual),
// and moved exactly as above.
// Then u.g = (g.v) cos(theta) / |v| with theta the angle of u to v, and (1) reads
// relaxed(u) >= B0 cos^2(theta), B0 = (g.v)^2 / (v.v 80 kappa) (B0 = relaxed(v) for the exact
// multipliers at a stationary v): on the cap cos(theta) >= c0 = sqrt(L / B0), relaxed >= L.
// Off the cap, relaxed(u) >= D(u)^2 / 32 (deformable_depth.h; D(u) the overlap along u, the
// support function of M = A - B): a ball B(q, R1) inside a simplex T of four points of M, with
// q = -R v/|v|, gives D(u) >= u.q + R1 >= R1 - R (cos(theta) + e) > R1 - R (c0 + e) for every
// unit u off the cap (e: v/|v| rounded); D(u) >= d0 = sqrt(32 L) there gives relaxed >= L.
// With L = V (1 - kShallowGap), 1 - c0 ~ kShallowGap / 2, and the ball needs a margin R
// kShallowGap / 2 above d0 ~ the depth and the roundings of its test (~u size): R ~ 1e-3 of
// the size suffices, a ball beneath the contact's face of M well inside it. Where none fits
// (the overlap region reaches the edge of that face: a vertex resting on a vertex, an edge on
// an edge), the same is shown on M's facets (facet_bounds.h's polytope_inside_ball: the
// polytope {u : D(u) <= d0, u.vh <= c0 + e} inside the unit ball, e covering vh's and lo's
// roundings), which needs no room beneath the face: only that D grows off the cap, as it does
// at first order away from a facet normal whose foot lies inside its facet.
// A vertex on an edge (a grid against its copy moved along a diagonal that its cells' diagonal
// edges share: a vertex of one lies on such an edge of the other, up to rounding): turning u
// about the edge keeps D(u) as small as the depth over a whole arc, beyond the cap. There (1)
// holds with other multipliers as well: for A's edge E0 E1 and B's vertex W (e = E1 - E0,
// w = W - E0, w.e / e.e in (0, 1) the vertex's fraction along the edge), l = e.e - w.e and w.e
// on E0 and E1, m = e.e on W, so g = (w.e) e - (e.e) w = -(e.e) w_perp, the vertex's offset
// across the edge (B's edge and A's vertex: the same, negated), and
//     relaxed(u) >= (u.g)^2 / (80 kappa),  80 kappa = 20 ((e.e - w.e)^2 + (w.e)^2 + 3/5 (e.e)^2),
// (a vertex a quarter along the edge: 2 (u.w_perp)^2 / 49; at the edge's end, w.e = 0, the
// vertex pair's (u.w)^2 / 32), whose value along the arc is the vertex-on-edge piece's own, the
// edge tilted to balance it: beyond the plane u.g = sqrt(80 kappa L) it covers the arc. g exactly
// (expansions), rounded, its error added to the plane's offset; 80 kappa rounded up. Where the
// cap (or the tied caps below) and the overlap do not cover the rest, each such plane is tried
// beside the caps' planes, then all of them (the vertices within 2^-24 of the pair's size of an
// edge's line, between its ends: any multipliers bound, these are only where the arc's are).
// Measured on a Kuhn grid of cell 0.1 against its copy moved a quarter cell along (1, 1, 1),
// the first 3,000 element pairs: 926 took the exact pieces, 307 with these planes (259 with
// the arcs' ends as starts as well, global_depth.cpp's least_overlap_starts).
// An edge on a collinear edge (a grid placed up to a rounding against its copy moved along an
// axis: A's edge E0 E1 and B's F0 F1 on one line, F0 inside A's edge and E1 inside B's): both
// incidences hold, and the arc of normals about the line where the overlap is as small as the
// depth runs between two caps. Any nonnegative sum of valid multipliers is valid, and the
// multipliers that balance the four vertices' moments along the line (so that g lies across
// it, and a tilt of u towards the line, up to the depth over the edge's length, leaves u.g) are
// exactly the combinations l1 + r l2 of the two incidences'; the least relaxed value over such
// tilts is their best bound. So each two incidences are also tried together, r chosen best at a
// cap's normal (shallow_certificate.cpp's combined_incidence): on the blocks' side walls one
// such plane covers the whole arc (1.000024 L at the cap's rim, 1.48 L a quarter of the arc
// away, on a Kuhn pair).
// Minimisers tied at a vertex of M (blocks cut into five tetrahedra a cube whose cuts alternate
// across the contact: a vertex resting on a vertex, the overlap least along two to four facet
// normals through it, the relaxed values there equal or ~1e-8 apart): off one cap lie the
// others, where D is the depth itself. A cap about each (a walk from each facet direction whose
// point lies outside the ball off the caps so far), L_i on cap i, and with L = min L_i and
// d0 = sqrt(32 L) the polytope {u : D(u) <= d0, u off every cap} inside the unit ball (a plane
// a cap): relaxed >= L everywhere, the least cap's value reported. Where a face or an edge
// rests on a face (a turned scene's resting blocks: a diagonal face's minimiser 45 degrees from
// the contact's, D(u) below d0 all the way between them), with a mean offset's plane beside the
// caps: for any two vertices a side, relaxed(u) >= (u.d)^2 / 12 with d = (a + a2 - b - b2) / 2
// wherever u.d >= 0 (lone_pair_certificate.h), so beyond u.d = sqrt(12 L) relaxed >= L; d from
// the edge pair of the lone pairs' where one was found, else from each cap's contact vertices
// (A's two highest and B's two lowest along its normal), rounded, its error added to the offset;
// such a plane is tried beside a single cap first (often it covers the other minimiser too).
// Finding v (heuristic, checked by the certificate): the minimiser tilts from the contact's
// face normal by ~depth / size, below a double normal's rounding unless solved for: on the
// active set S of v, F(v + E y) = sum_S (eta_i + y.xi_i)^2 + k (tau + y.xi_T)^2 (the piece's
// H_S in the frame v, E: eta the heights about the plane, from compensated heights, accurate
// to their own u; xi the positions across v, doubles), least at the 2 x 2 solve; repeated until
// S no longer changes (or S's positions across v lie on one line, a lone pair's two: v stays,
// the bound decides it). The walk keeps the normal in double words, v + lo: where the contact
// plane is off the axes, the tilt is below a double normal's rounding (lo stays 0 where every
// step's sum is a double; a walk in doubles, cheaper a step, ends where the exact part fails
// on about half the resting contacts measured: docs/performance.md) (heights along v + lo
// on compensated heights, relaxed_value.h; the multipliers' integers of v + lo; the overlap
// tests along v, their margins widened by the angle alpha <= 2 |lo| / |v| between v and v +
// lo: a point p's projection across the normal moves by <= 2 alpha |p|, its height by <= alpha
// |p|). Such a value is certified along a normal no double triple represents (ShallowResult's
// low; global_depth.cpp looks for a double normal near it).
#pragma once

#include "global/facet_bounds.h"
#include "global/relaxed_value.h"

namespace pdd::fast::global {

// The certified gap between the reported value and the lower bound (definitions §8's 1e-9,
// with kGlobalRel's evaluation: 3e-10 + 1e-10 relative, well inside).
inline constexpr double kShallowGap = 3e-10;

struct ShallowResult {
  V3 normal{};      // v (A -> B, unnormalised)
  V3 low{};         // the normal is v + low in double words (0: v itself; else no double
                    // triple represents it: v is its rounding)
  Evaluation eval;  // relaxed(v): value, error <= kGlobalRel, solution and heights
  double lower = 0; // L: every relaxed(u) >= L
};

// bounds: the pair's facet bounds (facet_bounds.h), for the overlap off the cap where the ball
// beneath the contact's face does not fit; null: that test is not made. edge_d: an edge pair's
// d (lone_pair_certificate.h's LonePairResult::edge_d), whose bound relaxed(u) >= (u.d)^2 / 12
// (u.d >= 0) holds beyond the plane u.d = sqrt(12 L): where the overlap alone does not cover
// what lies off the cap, the polytope test with both planes (an edge resting on a collinear
// edge, the minimiser where the face of its tetrahedron through the edge reaches the plane,
// ~1.6e-7 above the edge pair's bound: between the two, around the edge's own normal, the
// overlap is as small as the depth); null: not taken.
bool certify_shallow(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v0, ShallowResult& out,
                     FacetBounds* bounds = nullptr, const V3* edge_d = nullptr);

}  // namespace pdd::fast::global
