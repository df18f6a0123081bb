// global_depth.h — definitions §9 in the fast engine: PD_d^2 over every separating plane (paper
// eq. 5), by enumerating the stationary points of the relaxed value on the unit sphere.
//
// Input : a pair (in the engine's rescaled range, solve_pair.cpp, or as given on the exact
//         path), a start normal (the best candidate of pdd2_relaxed: the answer when nothing
//         beats it; zero when the caller has none: the pair's shallowest candidate directions
//         are offered instead, global_depth.cpp's offer_geometric_starts) and, on demand, its
//         exact normal: where the depth is far below the pair's size (the exact pieces below),
//         the double normal has no accurate digit in the direction that matters, so the exact
//         one is offered, rounded componentwise.
// Output: pdd2_global = relaxed(v) for the returned normal v (double components, A -> B), the
//         deformed positions attaining it, and whether the value is certified to definitions §8
//         (relative error <= kGlobalRel of the exact relaxed value along v).
//
// Math (the exact engine's reference/pdd/reference/relaxed_pieces.h proves the closed form;
// here it is used, not re-proved). G(n) = min of the relaxed QP with right-hand sides n.x is
// convex, 2-homogeneous and C^1: the QP's multipliers are unique (each constraint has its own
// variable t_i, so the constraint gradients are independent) and continuous, and dG/dn is a
// linear function of them. For an active set S = (S_A, S_B) (both non-empty for an intersecting
// pair) G(n) = n^T H_S n on the closed polyhedral cone R_S where S's KKT signs hold. A minimiser
// u* of G on the sphere is a stationary point: grad G(u*) = 2 G(u*) u*, and grad G(u*) = 2 H_S u*
// for the S optimal at u* (C^1: every S valid at u* gives the same gradient). So u* is an
// eigenvector of H_S lying in R_S, and
//     pdd2_global = min { mu : H_S v = mu v, v in R_S, S ranges over the 15 x 15 active sets }.
// The enumeration below visits every S, computes H_S and its eigenpairs, and evaluates
// relaxed(v) (the double closed form of direction_qp.h, which finds v's true active set) at every
// eigenvector whose eigenvalue could beat the current best and which satisfies S's signs up to
// a tolerance. In doubles it first drops, without an eigensolver, the pieces that certainly
// cannot hold such an eigenvector (piece_screen.h: no eigenvalue in the window, counted
// exactly; or the one in-window eigenvector violating a sign condition beyond the tolerance):
// on the paper's pairs about 2 of the 225 pieces reach the eigensolver. Eigenvalues within kDegenerate of each other (an eigenspace of dimension 2, where
// a computed eigenvector is arbitrary) are handled on the whole plane they span: the signs of S
// cut the circle of unit vectors of the plane into one arc (each sign condition is a half
// circle), and the arc's middle is evaluated.
// Lower bound: along every normal u, relaxed(u) >= D(u)^2 / 32 (deformable_depth.h's proof: keep
// only the highest vertex of A and the lowest of B, overlap D(u) along unit u), and D(u)^2 >=
// PD^2 (the rigid depth is the smallest overlap over all directions). So G >= PD^2 / 32 on the
// sphere, and an eigenvalue below it (a zero eigenvalue of a piece whose H has rank 1 or 2, most
// of them) cannot be a stationary value inside its piece: skipped without its vectors.
// Margins: an eigenpair is skipped only when its eigenvalue lies outside [lower, best) by more
// than its margin (kPrune relative above; H's rounding h_error, the solver's kEigen |H| and its
// loss near a double eigenvalue, consider_piece), or when a sign condition is violated by more
// than kSign of its scale; every other eigenpair is evaluated, so a skipped one cannot hide the
// minimiser (tolerances only cost evaluations). The value along the
// returned normal is certified by value_bounds.h's QP bound on its heights, else recomputed in
// rationals (the exact closed form, direction_qp_impl.h on mpq).
// Where the depth is far below the pair's size, the pieces would be built exactly; first the
// start is walked to the least of its pieces' charts and certified without them
// (shallow_certificate.h: a dual bound on a cap around the normal and the overlap bound off it),
// which answers the faces that touch by rounding (blocks stacked at 3 x 0.1 and 0.3) in ~20 us
// instead of ~1 ms; then, where the minimiser moves one vertex of each side (a vertex resting on
// a vertex), by the bound PD^2 / 32 attained, or an edge of each on translates of one line, by
// (u.d)^2 / 12 beside D(u)^2 / 32 (lone_pair_certificate.h, ~50-150 us); where the vertex pair's
// value lies above its bound (the minimiser where the lone pair's cone meets a neighbouring
// piece: blocks resting 1e-9 deep on each other's columns), the shallow certificate again from
// the lone pair's ray, its overlap off the cap shown on M's facets (facet_bounds.h, ~40-70 us);
// where they all decline, the exact pieces below.
// Where the depth is far below the pair's size (exact pieces), an eigenvector that held its
// signs only within the tolerance may hide a stationary value below the best offer; each such
// suspect is settled exactly before the pair is given up (suspect_proof.h's represented():
// proved outside its cone, or its eigenvalue bounded below and reached by a double normal --
// the eigenvector rounded, its neighbours, integer normals along it).
#pragma once

#include <array>
#include <functional>
#include <limits>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

struct GlobalOptimum {
  double value = 0;                 // pdd2_global
  std::array<double, 3> normal{};   // A -> B, unnormalised
  Positions<double> q1_A{}, q1_B{};
  bool certified = false;           // false: not representable (the caller reports it)
  bool exact_value = false;         // the value was recomputed in rationals (slow path)
  // Not certified, but the value is (definitions §8), attained along a rational normal that no
  // double triple represents (suspect_proof.h's witness, or shallow_certificate.h's normal in
  // double words: a depth ~1e-17 of the pair's size, a contact made by rounding); `normal` and
  // the positions are that witness's, rounded
  // componentwise: they do not attain the value (the depth is below their rounding). For a
  // caller that needs the value and only an approximate plane (the contact energy).
  bool witness = false;
  // Not certified (bound_shallow, face_bound): a depth far below the pair's size whose certificate
  // would take the shallow certificate or the exact pieces; `upper` is a certified upper bound
  // on pdd2_global below kBoundedDepth scale^2 (value_upper along `normal`, or face_bound's
  // D^2 / d.d, each lowered to the relaxed value's bound on compensated heights where that is
  // less), `value` the doubles' estimate along `normal`
  // (0 < value <= upper, or upper where the estimate is not in that range) and the positions
  // along it. For a caller summing many pairs that can bound their share (the contact energy).
  bool bounded = false;
  double upper = std::numeric_limits<double>::infinity();
};

// rigid_pd2: a value within 1e-8 relative of the pair's exact PD^2 (the engine's certified
// rigid_pd2, in the same units), or 0 when none is known. It prunes the enumeration: every
// G(u) >= PD^2 / 32 (below).
// The exact relaxed value along `n` for the pair as given, rounded once; `ok` cleared unless it
// is 0 or a normal double. For a caller that ran global_depth on a rescaled pair: a value
// computed exactly there (exact_value) may lie outside the double range in those units while
// the pair's own is a normal double (a depth of 1e-37 at coordinates 1e192 rescaled by 2^-640).
double exact_relaxed_value(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& n,
                           bool& ok);

// exact_start: called only when the exact pieces are needed (rare): pdd2_relaxed's exact normal
// rounded componentwise (exact_candidate.h's rounded_normal), or zero when none is known.
using ExactStart = std::function<std::array<double, 3>()>;
// start_value: the start's certified relaxed value (same units), or +inf when none: a double
// enumeration that ends above it could not evaluate the start's own normal, and is redone
// exactly.
// bound_shallow: where the start's value is already below the exact pieces' depth (so that only
// the shallow certificate, the lone pairs' or the exact pieces could certify it) and its bound
// (value_upper) below kBoundedDepth scale^2, return it `bounded` instead (GlobalOptimum::bounded).
// A contact made by rounding told apart without the search (for bound_shallow's callers, on a
// valid intersecting pair): along each of the eight face normals d (A's and B's, from the
// rounded edge vectors, oriented by the lesser overlap), moving B's four vertices by the overlap
// D(d) along d / |d| separates the pair at object-norm cost D^2 (a uniform displacement t of a
// tetrahedron costs (4 t^2 + 16 t^2) / 20 = t^2, definitions §2), so pdd2_global <=
// relaxed(d / |d|) <= D(d)^2 / d.d. With the heights' error e_h = 5 u |d|_1 scale
// (value_error's), D <= D~ + 2 e_h + u |D~|: a certified upper bound. Where the least is below
// kBoundedDepth = 1e-20 scale^2 (a depth below ~1e-10 of the pair's size: global_depth would
// send it to the shallow certificate or the exact pieces), the pair is returned `bounded` along
// that face normal (value: relaxed there in doubles, clamped into (0, upper]; the positions
// along it); else nothing is set (bounded false). On a contact made by rounding D~ is ~u of the
// size and 2 e_h dominates the bound (~1e-31 at cells of 0.1, where the value is ~1e-34): the
// upper bound is then relaxed(d) on compensated heights (deformable_depth.h's
// relaxed_upper_compensated: ~1 + 1e-15 times the value) where that is less. ~0.2 us, and ~1 us
// more with the compensated heights.
GlobalOptimum face_bound(const TetVertices& A, const TetVertices& B);

GlobalOptimum global_depth(const TetVertices& A, const TetVertices& B, const double start_normal[3],
                           double start_value, const ExactStart& exact_start, double rigid_pd2,
                           bool bound_shallow = false);

}  // namespace pdd::fast
