// resolve.h — internals of pdd::mesh::resolve / resolve_self / check_resolution (mesh.h):
// pushing two interpenetrating tetrahedral meshes (or one self-intersecting mesh) apart until
// no element pair intersects (R1), no element is inverted or flat (R2), fixed vertices have not
// moved (R3) and every element stays usable (R4: V1/V0 in [rho, 1/rho], eta1/eta0 >= kappa),
// all four decided exactly by check_resolution on the doubles written.
//
// The method: projective-dynamics rounds with the deformable metric PD_d, R2 and R4 kept as
// invariants of every step. Its phases, one file each under resolve/:
//   round k, from positions P_k (P_0 the rest pose; rounds.h):
//     1. contacts: every element pair whose interiors intersect at P_k (the exact decision on
//        a candidate list kept over the rounds, contact_list.h: the set intersecting_pairs
//        below gives);
//     2. local step (local_step.h): each pair projected, in the object norm, onto the
//        configurations in which a plane separates its two tetrahedra (the variant's per-pair
//        solution, pdd2_global by default): a half-space for each of its free vertices on the
//        wrong side of the plane, opened by a small gap; two meshes: the pairs of a contact
//        patch (pairs sharing vertices) whose planes disagree all take one direction
//        (patch_direction.h), each pair's plane then midway between its two tetrahedra's
//        extents along it. A vertex's target y_v is its position projected in turn onto
//        each of its half-spaces of this round and the latest one it held before (a vertex
//        once in contact stays constrained);
//     3. global step (../elastic_step.h): the displacement Delta minimising
//            1/2 sum_e V_e |grad Delta|_e^2 + 1/2 sum_v w_v |Delta_v - omega (y_v - x_v)|^2,
//        fixed vertices Dirichlet (Delta = 0): the contact vertices are pulled to their
//        half-spaces and the interior follows elastically over the rest mesh;
//     4. step limit (step_limit.h): P_{k+1,v} = P_{k,v} + t_v Delta_v, t_v halved on the
//        vertices of every element that would invert, flatten or fail R4 with a margin.
//   The rounds stop at the first whose contact stage finds no pair, or when they stall (then
//   the fallbacks; two meshes' first rounds also when their pair count falls too slowly to
//   finish within the budget, rounds.h), or at max_rounds.
//
// Why R2 and R4 hold along the way: P_0 satisfies both (V1 = V0, eta1 = eta0); the step limit
// keeps every element passing (step_limit.h); its margin test in doubles is stricter than R4
// far above the rounding of the ratios, and the exact verdict at the end is the judge all the
// same.
//
// Fallbacks, in order, when the rounds stall (report.method says which produced the result;
// fallbacks.h):
//   - two meshes whose rounds stalled on kFewPairs pairs or fewer (rounds.h; also after
//     kFewPairsRounds rounds without fewer there): up to kFinishRounds per-pair rounds (below)
//     from where the rounds stopped, whose moves take a pair's vertices the whole way where the
//     elastic step moves a vertex pulled alone a tenth of its pull (method "rounds");
//   - self-contact of several bodies, when every intersecting pair at rest joins two bodies:
//     when the contacting bodies come in pairs, each pair resolved as two meshes, all of the
//     below included (method "bodies"); else (a chain, a square or a triangle of bodies, or the
//     pairs not resolved) the bodies spread: each cluster's bodies translated away from its
//     centre by the smallest separating factor, then walked back towards the rest pose as the
//     translation below is (method "bodies");
//   - self-contact (one body folded into itself, or bodies the above declined): the
//     projective-dynamics rounds again from the rest pose, vertices without pull weakly
//     anchored (ElasticStep::Anchor::Free: the interior follows the contact further), within
//     the first budget (method "rounds");
//   - self-contact under the global variant: the projective-dynamics rounds again from the rest
//     pose with pdd2's per-pair planes, whose candidate directions neighbouring pairs share,
//     with the default anchors, then from the rest pose with the weak ones (method "pdd2 rounds");
//   - self-contact: the per-pair rounds from the rest pose (rounds.h): each free vertex moves by
//     a share of its pairs' per-pair PD_d moves (or of the rigid translation for a pair found in
//     more than two consecutive rounds), step limit as above (two meshes go on to the
//     translation: from rest these rounds resolved none of their measured cases, resolve.cpp);
//   - two meshes under the global or pdd2 variant that the above did not resolve: the
//     projective-dynamics rounds again from the rest pose with the rigid variant's per-pair
//     planes, finished per pair as above where they stop on a few pairs (method "rigid rounds";
//     where two meshes nearly coincide the deformable planes can point every way and hold a few
//     hundred pairs, fallbacks.h);
//   - two meshes (deep overlaps): the cheapest separating rigid translation over a few
//     directions, then walked back towards the rest pose with projective-dynamics rounds in
//     between, each step's rounds finished per pair as the first fallback finishes them where
//     they stop on a few pairs (method "translation");
//   - two meshes that the translation cannot move (both with fixed vertices): per-pair rounds on
//     to max_rounds;
//   - self-contact: the rigid variant's per-pair rounds from the rest pose (method "rigid rounds").
// A run stops at once (report.stopped_because) when every vertex is fixed or no intersecting pair
// has a finite per-pair solution.
//
// Strict separation without inflating the cost: touching is not intersecting, but rounding the
// moved coordinates to doubles can leave a just-separated pair intersecting by a few units in the
// last place; the gaps of the local steps (local_step.h) keep the two sides strictly apart at a
// cost far below an element layer's.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"
#include "pdd/sign.h"

namespace pdd::mesh::detail {

// Stage 1 of a round, and check_resolution's R1: every pair of the given elements of A (and of
// B; B == nullptr: self-contact, pairs a < b sharing no vertex) whose interiors intersect at
// the meshes' positions, sorted by (a, b). Fresh broadphase (box_pairs) and the exact decision.
std::vector<std::array<std::size_t, 2>> intersecting_pairs(const Mesh& A,
                                                           const std::vector<std::size_t>& ea,
                                                           const Mesh* B,
                                                           const std::vector<std::size_t>& eb);

// box_pairs / box_pairs_self (B == nullptr) with every element's box grown by `grow` on each
// side: every pair whose boxes, moved by at most `grow` per coordinate, can still overlap
// (the contact stage's candidate list, resolve/contact_list.h).
std::vector<std::array<std::size_t, 2>> grown_box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                        const Mesh* B, const std::vector<std::size_t>& eb,
                                                        double grow, const BroadphaseOptions& options);

// The exact orientation of the four points (CGAL's exact predicate); Zero: flat.
Sign orientation(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, const Vec3d& p3);

// The elements of m that are valid at its positions (element_problem: finite and not flat),
// in order; the others appended to `skipped` (unless null) with the reason.
std::vector<std::size_t> valid_elements(const Mesh& m, char which,
                                        std::vector<SkippedElement>* skipped);

// resolve / resolve_self (B == nullptr: self-contact): the phases in order, then the exact
// verdict and the report.
Resolution resolve_meshes(const Mesh& A, const Mesh* B, const ResolveOptions& options);

}  // namespace pdd::mesh::detail
