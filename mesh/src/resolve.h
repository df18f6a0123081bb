// resolve.h — internals of pdd::mesh::resolve / resolve_self / check_resolution (mesh.h):
// pushing two interpenetrating tetrahedral meshes (or one self-intersecting mesh) apart until
// no element pair intersects, no element is inverted and fixed vertices have not moved, all
// three decided exactly.
//
// The method: rounds of contact-space projection with the deformable metric PD_d.
//   round k:  1. contacts: every element pair whose interiors intersect at the current
//                positions P_k: a fresh broadphase (box_pairs, over every valid element) and
//                the exact decision (fast::interiors_intersect);
//             2. local step: each pair (a, b) is projected, in the object norm, onto the set of
//                configurations in which a plane separates its two tetrahedra: the per-pair
//                solution of the chosen variant (definitions §9's pdd2_global: q1_A_global,
//                q1_B_global; pdd2: q1_A, q1_B; rigid: the rigid translation along rigid_dir
//                split half and half) gives target displacements d_i along the pair's unit
//                normal u (A -> B) for its eight vertices;
//             3. global step (lumped): each free vertex v moves by omega times one combination
//                of the targets d_{p,v} of the pairs p it belongs to: for global and pdd2 the
//                longest of them (the vertex satisfies its most demanding pair; overshoot
//                omega = 1.2), for rigid the weighted mean sum_p w_p d_{p,v} / sum_p w_p, w_p
//                the rest volume of v's element in p (its weight in sigma_mesh; omega = 1.5).
//                A pair found intersecting in more than two consecutive rounds is pushed by its
//                rigid translation instead (default_tuning below has the measurements);
//             4. step limit (R2): the new position of v is P_v + alpha_v D_v (D_v the
//                combination of step 3) with alpha_v = omega first; every element with a
//                moved vertex whose exact orientation (CGAL's filtered exact orientation
//                predicate on the doubles) differs from its rest orientation or is zero halves
//                alpha of its moved vertices, and after kMaxHalvings halvings sets them to 0
//                (that vertex does not move this round).
//   It stops at the first round whose contact stage finds no pair, or after max_rounds
//   rounds. Then check_resolution decides R1-R3 afresh on the final doubles (R1 over every
//   pair: a full broadphase and the exact decision), and the report's resolved is its
//   r1 && r2 && r3: a run cannot claim what is not there.
//
// Why elements never invert (R2 is an invariant, not a hope): P_0 is the rest pose, where
// every valid element has its rest orientation. If P_k has it, every element at P_{k+1} has
// been checked exactly, and an element that fails has its moved vertices' alphas halved until
// it passes or they reach 0; with all its alphas 0 its vertices are bit for bit at P_k
// (P + 0 * D == P for finite D), where it was valid. Lowering alpha of a vertex can break
// another element that shares it, which is then checked and halved too; each pass lowers some
// alpha, and after kMaxHalvings passes every offending vertex is at 0, so the loop ends with
// every element of P_{k+1} valid.
//
// Why it stops: at most max_rounds rounds, each finite (the step limit ends as argued above).
// Why it usually resolves shallow overlaps quickly: the per-pair projection is the exact
// separating move of that pair, and the lumped global step is a Jacobi iteration of the
// projective-dynamics solve; where a vertex belongs to several pairs a mean under-moves it,
// which the overshoot omega > 1 makes up, and the longest target over-satisfies the others.
// Deep overlaps (several element layers) stall: only pairs move, the vertices behind a
// contact do not follow it, and the step limit squeezes elements nearly flat. For two meshes
// resolve then descends instead (ResolveTuning::descend): from the smallest separating
// translation along the line of the meshes' centroids, which is resolved, back towards the
// rest pose by steps each followed by a few rounds on the shallow contacts it makes, keeping
// only resolved and cheaper states. It ends resolved, at a cost below that translation's.
// Self-contact has no such start (one mesh cannot be translated apart from itself): stalled
// global or pdd2 rounds restart from the rest pose with the rigid variant's rounds, which move
// each pair's elements as a whole (two-spheres.msh: 38 rounds, where global diverged).
//
// Strict separation without inflating the cost: a per-pair solution makes the pair touch
// (touching is not intersecting), but rounding the moved coordinates to doubles can leave it
// intersecting by a few units in the last place; a pair that shallow would then stay
// intersecting round after round, as the overshoot scales its tiny depth by omega only. Each pair's
// displacement is therefore lengthened by a gap mu along u (A by mu/2 away from B, B by mu/2
// away from A), mu = kMargin * (the pair's longest edge) + kMarginUlp * (the largest |coordinate|
// of the pair): far above the rounding of the coordinates (2^-52 |x|), and so small against the
// element that its cost, at most mu^2 per pair and mesh, is below 10^-12 of an element layer's.
//
// Fixed vertices (fix_a, fix_b, per-vertex flags) are never written. In a pair where one side
// has fixed vertices, the displacement those vertices were given (their retreat along u) is
// given to the other side instead, as a translation of its free vertices along u by the largest
// such retreat: the fixed side then lies in u.x <= c + m and the free side in u.x >= c + m (the
// plane of the solution shifted by m), so the pair is still separated, at the cost of a
// translation by m of the free side; for a whole fixed element this is the static case (the
// paper's case 1) restricted to the solution's normal. Where both elements of a pair have fixed
// vertices, each side takes the other's retreat; that can fail to separate, and the rounds then
// report the pair as remaining.
//
// A pair whose per-pair solve fails (pdd2_global_error, a record error, no direction) falls back
// to pdd2's positions, then to the rigid translation; when every variant fails the pair does not
// move this round (it stays in the contact set and is reported if it remains).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"
#include "pdd/sign.h"

namespace pdd::mesh::detail {

// Tuning of the rounds. The defaults are default_tuning(variant)'s, the measured choice of
// `pdd bench resolve` (two generated balls of 10^5 elements overlapping by one to two element
// layers; see default_tuning below for the numbers).
struct ResolveTuning {
  double overshoot = 1.5;         // omega
  double margin = 1e-6;           // kMargin: gap mu per pair relative to its longest edge
  double margin_ulp = 1e-12;      // kMarginUlp: relative to the pair's largest |coordinate|
  int max_halvings = 24;          // kMaxHalvings: then alpha = 0
  // Combine a vertex's targets by the longest one instead of the weighted mean (step 3).
  bool longest = false;
  // A pair found intersecting in more than this many consecutive rounds is pushed by its rigid
  // translation instead of the variant's solution (0: never). A pair that survives rounds is
  // one whose deformable targets the step limit keeps cutting (an element of it nearly flat);
  // its translation moves the element as a whole instead of squeezing it further.
  int rigid_after = 0;
  // Sweeps of harmonic extension of the contact vertices' displacements to the vertices
  // around them (each sweep: D_v = mean of D over v's neighbours, for free vertices in no
  // pair; one more ring per sweep); 0: only contact vertices move.
  int smooth_sweeps = 0;
  // Drop the components of a pair's displacements that move a vertex towards the other
  // element (A's along +u, B's along -u): the pair stays separated (a vertex only retreats
  // further from the plane).
  bool retreat_only = false;
  // A vertex whose step the limit cut in a round counts as fixed in the next round's pairs
  // (its retreat goes to the other element).
  bool pass_blocked = false;
  // The step limit also halves where an element's volume would fall below this share of its
  // rest volume and below its volume before the step (in doubles; the exact sign test stays).
  double min_ratio = 0;
  // Deep overlaps: when half of max_rounds did not clear the contacts, or 10 rounds left half
  // of the first round's pairs, or 10 rounds found no fewer pairs than an earlier round (two meshes, at most one of them with fixed vertices; for
  // self-contact see the header's top comment), restart from the rest pose with the meshes translated apart
  // along the line of their vertex centroids by the smallest separating distance (bisection
  // with the exact contact stage), then walk back towards the rest pose: a step moves every
  // free vertex by gamma of its way back (step limit as in step 4), then up to descend_inner
  // rounds resolve the shallow contacts it made; a step that does not end resolved and cheaper
  // is undone and gamma halved (from 1/2 down to 1/64). Every accepted state is resolved, so
  // the run ends resolved. It may use the rounds of max_rounds the first attempt left.
  bool descend = false;
  std::size_t descend_inner = 20;
};

// The defaults per variant: descend on for all. global and pdd2: the longest target, omega 1.2, rigid after 2
// rounds: on the balls 1.99 apart (693 pairs) 9 rounds (global) and 7 (pdd2); 1.97 apart (1420
// pairs) 20 and 15 rounds; with the weighted mean and omega 1.5 both stalled with a few pairs
// left after 100 rounds, elements nearly flat. rigid (the baseline): the weighted mean, omega
// 1.5 (18 and 59 rounds; with the longest target it diverged at 1.97).
ResolveTuning default_tuning(ResolveVariant variant);

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

// resolve / resolve_self with explicit tuning (B == nullptr: self-contact).
Resolution resolve_tuned(const Mesh& A, const Mesh* B, const ResolveOptions& options,
                         const ResolveTuning& tuning);

}  // namespace pdd::mesh::detail
