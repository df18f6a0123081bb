// pdd.h — the public interface of pdd: penetration depth between two tetrahedra.
//
//   #include <pdd/pdd.h>          // CMake: find_package(pdd CONFIG REQUIRED)
//                                 //        target_link_libraries(app PRIVATE pdd::fast)
//   pdd::TetPair p{"name", {}, A, B};               // A, B: 4 vertices x {x, y, z}, doubles
//   pdd::PairResult<double> r = pdd::fast::solve_pair(p);
//   if (r.error) ...;  else r.pdd2, r.pdd2_dir->str(), r.q1_A, ...
//   pdd::fast::SolveOptions o;  o.gradient = true;       // options: pdd/solve_options.h
//   r = pdd::fast::solve_pair(p, o);
//
// What is computed (docs/definitions.md; Kim & Kim's paper):
//   rigid_pd2      PD², the squared rigid penetration depth (definitions §4), and its direction label;
//   eq11_pd2       the paper's eq. 11 (an estimate, not a bound: it can be below PD²);
//   pdd2_static    PD_d² with A static (paper case 1);  pdd2  PD_d² with both deforming (case 2,
//                  eq. 3 with the constraints of eq. 10); pdd2_relaxed  case 2 with every
//                  constraint an inequality; pdd2_accel1 / pdd2_accel6  case 2 restricted to the
//                  1 / 6 shallowest candidate directions (the paper's acceleration);
//   q1_A, q1_B     deformed vertex positions that attain pdd2 and are separated by its plane.
// Every value is a squared length in the squared units of the coordinates. A pair whose
// interiors do not intersect has every value 0, no labels, and q1 = the rest pose.
// Labels (DirectionLabel, definitions §3): "FV:i" face of A opposite s_i, "VF:j" face of B opposite
// r_j, "EE:a:b" edge a of A against edge b of B (":+"/":-" for the two sides of an undecidable
// edge pair).
// Rejected pairs (definitions §1): a non-finite coordinate or a tetrahedron of volume exactly 0.
// The record's `error` says which tetrahedron and why, in the same words for both engines.
//
// Two engines, sharing no arithmetic:
//   pdd::fast       doubles, certified (definitions §8, below); target pdd::fast (needs TBB and GMP).
//   pdd::reference  exact rationals (CGAL, GMP); target pdd::reference. Slow (milliseconds to
//                   seconds a pair): the judge, and the source of counterexamples.
#pragma once

#include <gmpxx.h>

#include <cstddef>
#include <optional>
#include <vector>

#include "pdd/direction_label.h"
#include "pdd/pair_result.h"
#include "pdd/qp_formulation.h"
#include "pdd/solve_options.h"
#include "pdd/tet_pair.h"

namespace pdd {

// Options: each engine's solve_pair and solve_batch take one struct, pdd::fast::SolveOptions or
// pdd::reference::SolveOptions (pdd/solve_options.h: with_global, gradient, formulation), set
// once with the recommended defaults; `pdd solve` and the Python module use the same names and
// defaults. How the fast engine computed a pair is in its record (PairResult::stats).

// The gradient of pdd2_global (SolveOptions::gradient, PairResult::pdd2_global_grad): what it
// is, where two minimisers tie, why (*) majorizes pdd2_global, and how an implicit solver uses
// it as a contact energy are in docs/definitions.md §9, "The gradient of pdd2_global"; its
// accuracy at each engine's `gradient` option (pdd/solve_options.h).

// The reference engine's numbers: exact rationals (GMP's mpq_class, in lowest terms);
// `r.pdd2.get_str()` and `std::cout << r.pdd2` print "p/q" (or "p" for an integer).
using Rational = mpq_class;

}  // namespace pdd

namespace pdd::fast {

// The definitions §8 contract of every fast value: on every valid pair, whatever its scale, shape
// or position, every reported squared value v satisfies |v − exact| ≤ 1e-9 · exact, v = 0 exactly
// when the exact value is 0; `intersecting` is the exact decision; every label names a
// candidate whose exact value is within that bound of the exact minimum; q1 attains pdd2 for
// its label to the same accuracy. The engine enforces it itself: each value carries an error
// bound; where bounds are too wide to decide a minimum, the few candidates that can still be
// it are evaluated exactly ("refined": the engine's own closed forms on GMP rationals, tens of
// microseconds), and where that does not suffice the whole pair is recomputed on the engine's
// exact path (rare, about 100x slower). A result that is not a normal
// double gives an error record that starts "not representable".

// Every definitions §6 quantity of one pair.
//   pair     the two tetrahedra; A is the paper's T1 (static in case 1), B is T2.
//   options  with_global, gradient (pdd/solve_options.h).
// Returns the record; `error` set when the pair is rejected (definitions §1) or a candidate-based
// value is not representable (then nothing else is set). pdd2_global alone may be declined:
// where the depth is far below the pair's extent no normal in doubles may be certified to
// attain it (kGlobalNotRepresentable), or it may lie outside the double range
// (kGlobalOutOfRange); then `pdd2_global_error` says so, pdd2_global and q1_*_global are NaN,
// there is no normal, and every other value of the record is reported as usual.
// r.stats.slow_path: the pair took the exact path; r.stats.refined: some quantity was refined (a
// few candidates evaluated exactly) and the pair did not need the exact path for it.
PairResult<double> solve_pair(const TetPair& pair, const SolveOptions& options = {});

// solve_pair on every pair, on all cores (TBB), results in input order; bit-identical to
// solve_pair one at a time (stats included). A rejected pair is an error record; it never stops
// the batch.
std::vector<PairResult<double>> solve_batch(const std::vector<TetPair>& pairs,
                                            const SolveOptions& options = {});

// One quantity over raw vertices: the hot path for contact handling (no record, no positions).
enum class DepthStatus {
  Ok,                // pd2 is the certified value (0: the interiors do not intersect)
  Rejected,          // a non-finite coordinate or a flat tetrahedron (or pdd2_accel's k is
                     // not 1 or 6); pd2 = NaN, so that it never reads as "not intersecting"
  NotRepresentable,  // the exact value is not a normal double after scaling back; pd2 = NaN
};
struct Depth {
  double pd2 = 0.0;                   // the squared depth, definitions §8 contract; NaN unless Ok
  std::optional<DirectionLabel> dir;  // the minimising direction; none when pd2 == 0 and
                                      // for pdd2_accel (definitions §6 prints no label for it)
  DepthStatus status = DepthStatus::Ok;
};

// A, B: the tetrahedra's vertices s0..s3 and r0..r3 (any orientation). Same values and labels
// as the fields of solve_pair's record of the same name (the same certified computation on the
// same rescaled pair; the exceptions: where solve_pair cannot certify pdd2's deformed
// positions it reports the exact path's pdd2, which may differ from this one within
// definitions §8; and solve_pair lowers a value that rounded above a value it is exactly at
// most (definitions §5: pdd2 <= pdd2_static <= rigid_pd2, pdd2 <= rigid_pd2 / 2,
// pdd2_global <= pdd2_relaxed <= pdd2 <= pdd2_accel6 <= pdd2_accel1) to that bound, which
// keeps definitions §8; rigid_pd2 and pdd2_accel(k = 1) are never lowered). At a near tie
// (candidates' values within definitions §8's bound) either side may be named, and the record
// names the side these functions name: rigid_pd2 and pdd2_accel(k = 1) take the same certified
// routes in solve_pair (aligned meshes, edges parallel up to a rounding, are full of such ties).
Depth rigid_pd2(const TetVertices& A, const TetVertices& B);     // PD², definitions §4
Depth pdd2_static(const TetVertices& A, const TetVertices& B);   // PD_d², case 1, definitions §5
Depth pdd2(const TetVertices& A, const TetVertices& B);          // PD_d², case 2 (eq. 3, 10)
Depth pdd2_relaxed(const TetVertices& A, const TetVertices& B);  // case 2, inequalities only
// The paper's acceleration: case 2 on the k shallowest candidates; k = 1 or 6 (pdd2_accel1,
// pdd2_accel6), any other k is DepthStatus::Rejected.
Depth pdd2_accel(const TetVertices& A, const TetVertices& B, int k);
// rigid_pd2(A, B) and pdd2_accel(A, B, 1) of one pair, the same two Depths bit for bit, their
// common work (the candidate directions' kernel and the certified rigid choice that pdd2_accel1
// takes its direction from) done once: for a caller that wants both, as pdd::mesh's contacts
// with variants rigid,accel1.
struct RigidAndAccel1 {
  Depth rigid;   // rigid_pd2(A, B)
  Depth accel1;  // pdd2_accel(A, B, 1)
};
RigidAndAccel1 rigid_pd2_and_accel1(const TetVertices& A, const TetVertices& B);

// definitions §9: PD_d² over every separating plane (the paper's eq. 5 as defined, not restricted
// to the candidate directions): the minimum over unit normals of the relaxed QP, with the normal
// attaining it (A -> B; zero when pd2 == 0). Same contract as solve_pair's pdd2_global (within
// 1e-9 of the exact minimum, the normal reproducing the value).
// The fast engine's normal (here and solve_pair's pdd2_global_normal) is a direction, scaled by
// a power of two so that its largest |component| lies in [1, 2) (length in [1, 2 sqrt(3))):
// exactly the triple of doubles along which the value was certified. It is not rescaled to unit
// length because rounding n / |n| turns the direction by ~1e-16, and on a contact far shallower
// than the pair's extent that alone can move the value by more than 1e-9; where a unit normal
// is wanted, n / |n| is the same plane up to that rounding. (The exact engine's normal is its
// rational witness as found, of no fixed length.)
struct NormalDepth {
  double pd2 = 0.0;
  std::array<double, 3> normal{};
  DepthStatus status = DepthStatus::Ok;
};
NormalDepth pdd2_global(const TetVertices& A, const TetVertices& B);

// The exact intersection decision of definitions §4 alone: do the interiors of A and B intersect
// (touching is not intersecting)? For the many pairs of a mesh broadphase, most of them
// disjoint. overlap_filter is a certified separating-axis test in doubles over the 44 axes (the
// 8 face normals, the 36 edge-pair cross products) with a static forward error bound: Disjoint
// or Intersecting only when certain, Unknown otherwise (touching, nearly touching, parallel
// edges, a near-flat or non-finite element); about 100-150 ns, no allocation.
// interiors_intersect: the filter, then for the Unknown ones the exact separating-axis decision
// on the same axes (signs the filter leaves open taken by floating-point expansions; outside
// their range rigid_pd2's exact decision); equal to rigid_pd2(A, B).pd2 > 0 (NaN counted as
// intersecting); false for a rejected pair.
enum class Overlap { Disjoint, Intersecting, Unknown };
Overlap overlap_filter(const TetVertices& A, const TetVertices& B);
bool interiors_intersect(const TetVertices& A, const TetVertices& B);

// Translation. Every value, label, normal and decision above is invariant under a translation
// of both tetrahedra. Where moving the pair so that A's first vertex s0 is the origin is exact in
// doubles (each of the 24 coordinate differences from s0 exact: dyadic coordinates such as a
// grid of cell 2^-k or integer voxels, and most pairs of nearby vertices of like magnitude),
// every function above computes on the moved pair and moves the positions back by s0, one
// rounding per coordinate (at most 2^-53 |q|: an eighth of the positions' allowance of
// definitions §8 as `pdd compare` judges it, and far inside its 1e-9 R separation). So two pairs
// equal up to such a translation get the same values, labels and normals bit for bit.
//   anchored_pair   the moved pair and s0; nothing when a difference is not exact (or not
//                   finite), when a non-zero moved coordinate is below 2^-20 of the largest
//                   (vertices a rounding apart: the exact comparisons' expansions would not
//                   take the moved pair), or when s0 is already (+0, +0, +0) (the identity).
//   move_positions  moves a record of m = anchored_pair(A, B) back to the pair (A, B): every
//                   coordinate of q1_A, q1_B, q1_A_global, q1_B_global plus s0, except that a
//                   coordinate equal to its rest vertex's in m (a value not asked, a vertex that
//                   does not move) becomes the rest vertex's in (A, B), bit for bit (the same
//                   value: only a −0 would otherwise come back as +0). False (r left partly
//                   moved) when a finite coordinate would leave the double range:
//                   solve_pair and global_minimiser then compute the pair as given.
// With p anchored to m: solve_pair(p) equals solve_pair(m) moved, bit for bit, whenever the
// move returns true (the gradient, when asked, is computed from the moved positions); a
// caller meeting many pairs equal up to translation may compute one and move it to the others
// (pdd/mesh/contacts.h does).
struct AnchoredPair {
  TetVertices A, B;
  std::array<double, 3> origin{};
};
std::optional<AnchoredPair> anchored_pair(const TetVertices& A, const TetVertices& B);
bool move_positions(PairResult<double>& r, const AnchoredPair& m, const TetVertices& A, const TetVertices& B);

}  // namespace pdd::fast

namespace pdd::reference {

// Every definitions §6 quantity of one pair, exactly: each input double is taken as the rational it
// denotes and every value is an exact rational; labels are the first minimising candidate in
// the canonical order of definitions §3; q1 are exact rationals attaining pdd2. `options`:
// formulation, with_global, gradient (pdd/solve_options.h).
// Returns the record; `error` set when the pair is rejected (definitions §1).
PairResult<pdd::Rational> solve_pair(const TetPair& pair, const SolveOptions& options = {});

}  // namespace pdd::reference
