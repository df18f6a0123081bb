// resolve.h — internals of pdd::mesh::resolve / resolve_self / check_resolution (mesh.h):
// pushing two interpenetrating tetrahedral meshes (or one self-intersecting mesh) apart until
// no element pair intersects (R1), no element is inverted or flat (R2), fixed vertices have not
// moved (R3) and every element stays usable (R4: V1/V0 in [rho, 1/rho], eta1/eta0 >= kappa),
// all four decided exactly by check_resolution on the doubles written.
//
// The method: projective-dynamics rounds with the deformable metric PD_d, R2 and R4 kept as
// invariants of every step.
//   round k, from positions P_k (P_0 the rest pose):
//     1. contacts: every element pair whose interiors intersect at P_k (fresh broadphase and
//        the exact decision, intersecting_pairs);
//     2. local step (pair_targets): each pair (a, b) is projected, in the object norm, onto the
//        configurations in which a plane separates its two tetrahedra: the variant's per-pair
//        solution (pdd2_global by default) gives the plane u.x = c midway between q1_A and q1_B
//        along its normal u (A -> B); opened by a gap g = kPlaneGap (longest edge of the pair)
//        and shifted past the fixed vertices of either side, it gives every free vertex on the
//        wrong side the half-space u.x <= c - g/2 (A) or u.x >= c + g/2 (B). A vertex's target
//        y_v is its position projected in turn onto each of its half-spaces of this round and
//        the latest one it held before (a vertex once in contact stays constrained);
//     3. global step (elastic_step.h): the displacement Delta minimising
//            1/2 sum_e V_e |grad Delta|_e^2 + 1/2 sum_v w_v |Delta_v - omega (y_v - x_v)|^2,
//        (K + W) Delta = W omega (y - x), w_v = kAnchor K_vv, omega = kOvershoot, y_v = x_v for a
//        vertex without target, fixed vertices Dirichlet (Delta = 0): the contact vertices are
//        pulled to their half-spaces and the interior follows elastically over the rest mesh;
//     4. step limit (move_side): P_{k+1,v} = P_{k,v} + t_v Delta_v with t_v = 1 first; every
//        element with a moved vertex that is inverted or flat (exact orientation) or fails R4
//        with a margin (usable_with_margin, in doubles) halves t of its moved vertices, and
//        after kMaxHalvings halvings sets them to 0, until every element passes.
//   The rounds stop at the first whose contact stage finds no pair, or when kStallRounds rounds
//   found no fewer pairs than the best one (then the fallbacks), or at max_rounds.
//
// Why R2 and R4 hold along the way: P_0 satisfies both (V1 = V0, eta1 = eta0). If P_k does,
// every element of P_{k+1} with a moved vertex has been checked, and one that fails has its
// moved vertices' t halved until it passes or they reach 0; with all its t at 0 its vertices
// are bit for bit at P_k (P + 0 * D == P for finite D), where it passed. Each pass lowers some
// t, and after kMaxHalvings passes every offending vertex is at 0, so the loop ends with every
// element of P_{k+1} passing. The margin test in doubles is stricter than R4 by kQualityMargin,
// far above the rounding of the ratios; the exact verdict at the end is the judge all the same.
//
// Fallbacks, in order, when the rounds stall (report.method says which produced the result):
//   - the per-pair rounds from the rest pose (resolve_tuned's run_rounds): each free vertex moves
//     by omega times the longest of its pairs' target displacements (per-pair PD_d positions, or
//     the rigid translation for a pair found in more than two consecutive rounds), step limit as
//     above;
//   - two meshes (deep overlaps): the smallest separating translation along the line of the
//     meshes' vertex centroids (bisection with the exact contact stage; a rigid translation keeps
//     R2 and R4 up to rounding, which the step limit's check covers), then walked back towards
//     the rest pose by steps of gamma (1/2 down to 1/64) of every free vertex's way back, each
//     followed by a few per-pair rounds; a step that does not end resolved and cheaper is undone
//     (method "translation");
//   - self-contact of several bodies (connected components by shared vertices), when every
//     intersecting pair at rest joins two bodies and no body meets two others: each contacting
//     body pair cut out and resolved as two meshes, all of the above included (method "bodies");
//   - self-contact: the rigid variant's per-pair rounds from the rest pose (method "rigid rounds").
// A run stops at once (report.stopped_because) when every vertex is fixed or no intersecting pair
// has a finite per-pair solution.
//
// Strict separation without inflating the cost: touching is not intersecting, but rounding the
// moved coordinates to doubles can leave a just-separated pair intersecting by a few units in the
// last place; the gap g (1e-3 of an edge; per-pair rounds: kMargin, 1e-6 of an edge plus 1e-12 of
// the largest coordinate) keeps the two sides strictly apart at a cost far below an element
// layer's.
//
// A pair whose per-pair solve fails (pdd2_global_error, a record error, no direction) falls back
// to pdd2's positions, then to the rigid translation; when every variant fails the pair gives no
// target this round (it stays in the contact set and is reported if it remains).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"
#include "pdd/sign.h"

namespace pdd::mesh::detail {

// How the per-pair rounds (the fallback) combine a vertex's targets, per variant (round_rule):
// global and pdd2 take the longest target with overshoot omega = 1.2 and push a pair found in
// more than two consecutive rounds by its rigid translation (on the balls 1.99 apart, 693
// pairs: 9 rounds (global) and 7 (pdd2); with the weighted mean and omega 1.5 both stalled
// with a few pairs left after 100 rounds, elements nearly flat); rigid (the baseline) takes the
// rest-volume-weighted mean with omega = 1.5 (with the longest target it diverged).
struct RoundRule {
  double overshoot;  // omega
  bool longest;      // the longest target, else the weighted mean
  int rigid_after;   // rounds before a pair is pushed by its rigid translation (0: never)
};
RoundRule round_rule(ResolveVariant variant);

// Stage 1 of a round, and check_resolution's R1: every pair of the given elements of A (and of
// B; B == nullptr: self-contact, pairs a < b sharing no vertex) whose interiors intersect at
// the meshes' positions, sorted by (a, b). Fresh broadphase (box_pairs) and the exact decision.
std::vector<std::array<std::size_t, 2>> intersecting_pairs(const Mesh& A,
                                                           const std::vector<std::size_t>& ea,
                                                           const Mesh* B,
                                                           const std::vector<std::size_t>& eb);

// The exact orientation of the four points (CGAL's exact predicate); Zero: flat.
Sign orientation(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, const Vec3d& p3);

// The elements of m that are valid at its positions (element_problem: finite and not flat),
// in order; the others appended to `skipped` (unless null) with the reason.
std::vector<std::size_t> valid_elements(const Mesh& m, char which,
                                        std::vector<SkippedElement>* skipped);

// resolve / resolve_self (B == nullptr: self-contact).
Resolution resolve_tuned(const Mesh& A, const Mesh* B, const ResolveOptions& options);

}  // namespace pdd::mesh::detail
