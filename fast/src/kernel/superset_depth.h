// superset_depth.h — rigid PD² and its label from a superset of the candidate directions
// (definitions §4), without the orientation rule of definitions §3 except near the minimum. The hot
// path of rigid_pd2(A, B) and pdd2_accel(A, B, 1).
//
// Input:  tetrahedra A (s0..s3), B (r0..r3), raw doubles.
// Output: true, and Choice{value = PD², code = definitions §3 label of the first candidate
//         in canonical order attaining it (tie_tolerance.h), index = −1 (no candidate list is built)}, and
//         optionally the chosen candidate's geometry (for the case-2 QP of pdd2_accel1); or
//         false ("declined": the pair is invalid, not clearly intersecting, or a decision near
//         the minimum needs the exact fallback) — the caller then uses the candidate list.
//         Value, label and geometry are bit-identical to rigid_pd2(build_candidates(A, B)),
//         except where the choice is certified only with the edge pairs the doubles cannot
//         resolve left out (choice_without_unresolved): at a near tie the list may then name
//         one of those pairs along its own normal, a few ulps from this choice, both within
//         definitions §8 (solve_pair reports this choice there: rigid_superset_of_kernel).
//
// ---- Why a superset suffices for the VALUE (proof).
// Let M = A ⊕ (−B) = conv{s_i − r_j} and h(u) = max_{x in M} u.x = max_i u.s_i − min_j u.r_j =:
// D(u), its support function. If the interiors intersect, the origin is interior to M and
// PD = dist(0, ∂M) = min over facets F of M of h(u_F)/|u_F| (u_F the outward facet normal; a
// point of ∂M nearest to 0 lies on a facet, and the facet's plane is at distance h(u_F)/|u_F|).
// For EVERY u ≠ 0 the ball B(0, PD) ⊂ M gives h(u) >= PD |u|, i.e. D(u)²/(u.u) >= PD².
// A facet of M is the Minkowski sum of faces of A and of −B with a common outward normal and
// dimension 2: a facet of A (normal ∝ ±N_A,f), a facet of B (∝ ±N_B,f), or the sum of two
// non-parallel edges (normal ∝ ±eB × eA). With its OUTWARD orientation it is a definitions §3
// candidate: FV/VF are oriented outward by construction; for an edge-edge facet with outward
// normal u, A's support set in direction u is its edge (s_u, s_v), so u.(s_k − s_u) < 0 for
// A's two other vertices — for n = u both g_k < 0 and the rule keeps n, for n = −u both
// g_k > 0 and the rule flips to −n = u (such a pair is never undecidable). Hence over the superset
//     S = { FV:0..3, VF:0..3 } ∪ { +n, −n : n = eB × eA, all 36 edge pairs }
// we have   min_{u in S} D(u)²/(u.u) = PD²   — every element is >= PD², the outward facet
// normals are in S and attain it. No orientation rule, no classification, no exact predicate is
// needed for the value: per edge pair take min(D(n), D(−n)), where with the heights of
// direction_geometry.h (A: 0, 0, g1, g2; B: hx, hx + q1, hx + q2)
//     D(+n) = max(0, g1, g2) − hx − min(0, q1, q2),   D(−n) = −min(0, g1, g2) + hx + max(0, q1, q2).
// Parallel edge pairs (n = 0) span no facet and are not needed for the value.
// Intersection: the interiors intersect iff D(u) > 0 for every u in S (if not, the origin is
// on or outside some facet plane, whose normal is in S). So min_S D > E3 (filter_bounds.h,
// degree 3) decides "intersecting" exactly; otherwise we decline (exact fallback in the list).
// An exactly parallel edge pair has D(±n) = 0 exactly, so its computed |D| <= E3: declined too.
//
// ---- The LABEL. The label is the first REAL candidate (definitions §3 orientation rule) in
// canonical order whose value ties with the minimum over the real candidates. Entries of S that are
// not real candidates are the discarded orientation of decided edge pairs; their value is >= PD²,
// and if one attains PD² then a real facet-normal candidate ties with it. So only the few
// entries of S within the tie band of min_S need the orientation rule (filtered signs of
// g1, g2; declined when unclear). The list path takes vmin_c = min over real candidates and
// then the first real v <= tie_threshold(vmin_c); we reproduce it exactly: with
// t1 = tie_threshold(min_S) and t2 >= tie_threshold(t1) (one square root, see
// superset_kernel.cpp), every real candidate that can be the real minimum or tie with it has
// v <= t2 (the threshold is monotone), so the entries of S with v <= t2 decide. If no real
// candidate lies below t1 (impossible unless the tie band is below the rounding error), we
// decline.
//
// ---- Cost. See src/kernel/superset_kernel.cpp for the flop count per pair (≈ 1900 flops, ≈ 115 ns).
#pragma once

#include <cstring>

#include "kernel/candidate_directions.h"
#include "kernel/rigid_depth.h"

namespace pdd::fast {

// `geometry` (optional): filled with the chosen candidate (n, heights, masks, label), equal to
// candidate(build_candidates(A, B), index of the label).
// ch.certified: the definitions §8 verdict (value_bounds.h). `unique` (optional): certified, and
// the chosen candidate is the first of the candidate list in exact delta order (stable in
// canonical order: what pdd2_accel1 takes): every other entry of S is certainly above it (in
// the rounded values, or in exact orders: over the pair's integer frame, or in depth parts in
// double words where it is a rounding away), or tied with it exactly and after it in canonical
// order (over the frame; without one, exactly in its direction), or no candidate
// (superset_depth.cpp).
// Precondition for ch.certified and `unique` (not for the value and label): A and B rescaled by
// power_scale.h (largest |coordinate| in [1, 2)), as hot_path.h does; the error bounds assume
// that range (value_bounds.h), and so does the kernel's choice of entries to bound
// (tie_and_certify_bits in superset_kernel.cpp: no underflow in its thresholds).
// `band` (optional, with `unique`): asked where the choice is certified and not certainly
// `unique` (TieBandTest below).
class TieBandTest;
namespace detail {
struct SupersetLanes;  // superset_kernel.h
}
bool rigid_superset(const TetVertices& A, const TetVertices& B, Choice& ch,
                    Candidate* geometry = nullptr, bool* unique = nullptr, TieBandTest* band = nullptr);

// rigid_superset(power_scaled(A, B)...) on the raw pair, the scaling fused into the kernel
// (superset_kernel_scaled): the same choice, geometry and `unique` bit for bit (value and
// geometry of the scaled pair, e the exponent: the value scales back by 2^-2e), and `extent`
// (optional) the scaled pair's L of filter_bounds.h (filter_bounds(scaled pair) is
// filter_bounds_of_extent(*extent): the same maxima, minima and differences). False when
// power_scale.h's common exact case does not apply or the choice declines: the caller then
// takes hot_path.h's general frame. `kernel_ran` (optional): true when the common exact case
// applied (the kernel ran on the scaled pair), so that a false return is rigid_superset's own
// decline on that pair, and an uncertified choice its uncertified choice. `unresolved`
// (optional): when no certified choice was reached at the first try, whether the kernel found
// edge pairs whose n the doubles cannot resolve (near_parallel_bound.h: aligned pairs); the
// candidate list's lanes of such pairs are unclear, so quick_candidates.h would decline: a hint
// for the caller's next route. `band`: as for rigid_superset.
bool rigid_superset_scaled(const TetVertices& A, const TetVertices& B, Choice& ch, int& e,
                           Candidate* geometry = nullptr, bool* unique = nullptr,
                           double* extent = nullptr, bool* kernel_ran = nullptr,
                           bool* unresolved = nullptr, TieBandTest* band = nullptr);

// rigid_superset_scaled(A, B, ...) on a pair already rescaled (power_scaled: e = 0, the kernel ran),
// from the kernel's lanes of that pair (superset_kernel(A, B, K, full) with any `full`: the same
// lanes bit for bit), for a caller that ran the kernel for quick_lanes (solve_pair). The same
// choice, geometry, `unique`, `unresolved` and band verdict; K is changed.
bool rigid_superset_of_kernel(detail::SupersetLanes& K, Choice& ch, Candidate* geometry = nullptr,
                              bool* unique = nullptr, bool* unresolved = nullptr, TieBandTest* band = nullptr);

// The candidates of the list that may be its exact first (stable delta order, what
// pdd2_accel(A, B, 1) takes) when the choice is certified but not `unique`: entry[0] the choice,
// then every entry of S not certainly above it that is a candidate of the list (its
// orientation not certainly discarded by definitions §3's rule), as geometry for the
// per-direction solvers (lane and face geometry as `geometry` above; an edge pair labelled by
// its direction, EE:a:b:+ for +(eB × eA) and EE:a:b:- for its opposite). Accepted only where
// every edge pair left out of S (unresolved: nearly or exactly parallel) is shown to be no exact
// first: its candidate certainly above the choice, or its facets so and its direction not along
// a band edge pair that it precedes (superset_depth.cpp's band_accepted, with the proof).
struct TieBand {
  static constexpr int kMax = 12;  // more: no band (aligned pairs have 2 to 10)
  int count = 0;
  Candidate entry[kMax];
  TetVertices A, B;  // the pair the entries are of (the kernel's, rescaled; set before the test sees it)
};

// What a caller does with a tie band (pdd2_accel1: its case-2 values within definitions §8 of
// each other). rigid_superset and rigid_superset_scaled build the band where `unique` is not
// settled by the doubles and exact directions alone (the rest would take depth parts in double
// words: superset_depth.cpp's ties_share_direction), or, with `always`, wherever the choice is
// certified and not certainly `unique` (tests: every band). agree() runs first, then the
// unresolved edge pairs are checked (TieBand above); `accepted` is set when both pass: the band
// holds the exact first and the caller's test agreed (then `unique` stays false, unsought).
// agree() may run on a band that is then not accepted. Where agree() set `disagreed` and the
// depth parts in double words do not show the choice unique either, the band is built again
// and settle() asked instead (pdd2_accel1: the exact first's own value, decided exactly: more
// than those depth parts cost where they decide), with the same checks after it.
class TieBandTest {
 public:
  virtual bool agree(const TieBand& band, const FilterBounds& fb) = 0;
  virtual bool settle(const TieBand&, const FilterBounds&) { return false; }
  bool always = false;
  bool accepted = false;
  bool disagreed = false;

 protected:
  ~TieBandTest() = default;
};

// The last pair on this thread whose rigid_superset_scaled gave no certified choice (rigid_pd2
// records it, with its `unresolved`), so that pdd2_accel(A, B, 1) right after rigid_pd2(A, B) on
// the same pair, the depth stage's order, does not run the same kernel and choice again: the
// same bits give the same outcome (the choice is certified or not whatever `geometry`,
// `unique` and `band` ask). recall: true, with `unresolved`, when A and B are that pair bit for
// bit.
namespace detail {
struct UncertifiedSuperset {
  TetVertices A, B;
  bool valid = false, unresolved = false;
};
inline thread_local UncertifiedSuperset last_uncertified_superset;
}  // namespace detail
inline void remember_uncertified_superset(const TetVertices& A, const TetVertices& B, bool unresolved) {
  detail::UncertifiedSuperset& m = detail::last_uncertified_superset;
  m.A = A, m.B = B, m.valid = true, m.unresolved = unresolved;
}
inline bool recall_uncertified_superset(const TetVertices& A, const TetVertices& B, bool& unresolved) {
  const detail::UncertifiedSuperset& m = detail::last_uncertified_superset;
  // (the first coordinate first: most calls meet another pair and stop there)
  if (!m.valid || m.A[0][0] != A[0][0] || std::memcmp(&m.A, &A, sizeof A) != 0 || std::memcmp(&m.B, &B, sizeof B) != 0)
    return false;
  unresolved = m.unresolved;
  return true;
}

// A benchmark baseline only, NOT definitions §8: the same kernel and pick on the pair as given,
// with none of the certification (no power-of-two rescaling, no certify pass, no exact path;
// ch.certified stays false). `pdd bench` times it beside rigid_pd2(A, B) to report what the
// certification costs.
bool rigid_superset_uncertified(const TetVertices& A, const TetVertices& B, Choice& ch);

}  // namespace pdd::fast
