// rigid_depth.h — rigid penetration depth and the paper's eq. 11 value (definitions §4).
//
// Input:  a CandidateSet (candidate_directions.h) of an intersecting pair.
// Output: rigid_pd2   PD² = (min_n delta(n))², delta(n) = D(n)/|n|, D = max_i n.s_i − min_j n.r_j,
//                     computed as min D²/(n.n) (D > 0 for every candidate of an intersecting pair);
//                     index = first candidate in canonical order attaining it (tie_tolerance.h).
//         eq11_pd2    E11² = (min_n overlap(n)/|n|)², overlap = L_n(A) + L_n(B) − L_n(A ∪ B),
//                     L_n the width of the projection (paper eq. 11); 0 if some overlap <= 0.
// Both return 0 (index −1) for a non-intersecting set. Hot path: no allocation, no strings.
// definitions §8: a choice the double bounds cannot certify is refined (refine.h): its contenders
// are evaluated exactly; `certified` stays false only when that is not possible (then the caller
// takes the exact path).
#pragma once

#include "kernel/candidate_directions.h"
#include "kernel/quick_candidates.h"

namespace pdd::fast {

struct Choice {
  double value = 0.0;  // squared depth
  int index = -1;      // index of the candidate in the set, −1 when none or no set was built
  LabelCode code = 0;  // packed definitions §3 label of the choice (valid when value > 0)
  // definitions §8 verdict (value_bounds.h): value within kCertifyRel of the exact minimum and the
  // label's exact value too. False: the caller must take the exact path.
  bool certified = false;
  // Certified by evaluating the contenders exactly (refine.h) rather than in doubles alone.
  bool refined = false;
  // index is certainly the exact engine's choice: the first candidate in canonical order
  // attaining the exact minimum (every other candidate's exact value is above it, or ordered
  // exactly), not only one within definitions §8 of it (a near tie may name either side).
  bool exact_first = false;
  DirectionLabel label() const { return unpack_label(code); }
};

Choice rigid_pd2(const CandidateSet& set);
Choice rigid_pd2(const QuickCandidates& q);  // same candidates, same result
// rigid_pd2(set), kept per thread for the last pair it was asked of (kernel/pair_memo.h: the
// pair's bits): one pair's values ask it again (rigid_pd2_choice, then pdd2_accel's k = 1 at
// the rigid direction), and on a contact made by rounding it is the exact tie order's cost.
Choice rigid_pd2_reusing(const CandidateSet& set);
// `certified` (optional): the definitions §8 verdict (value_bounds.h; exact 0 is certified only
// when some overlap is surely <= 0). Not certified in doubles: the contenders are evaluated exactly
// (refine.h), `refined` (optional) then set.
double eq11_pd2(const CandidateSet& set, bool* certified = nullptr, bool* refined = nullptr);

// Convenience over raw tetrahedra (the hot path): rigid_superset (superset_depth.h) when it
// decides (index −1: no list is built), else the candidate set (index then refers to it);
// value 0 when the pair does not intersect or is invalid. Same value and label either way,
// except at the near ties of superset_depth.h's choice without unresolved edge pairs, where
// solve_pair reports the superset's choice as this function does.
Choice rigid_pd2_choice(const TetVertices& A, const TetVertices& B);

// What rigid_pd2_choice's first try (rigid_superset_scaled on the raw pair, superset_depth.h)
// gave, where a caller ran it already asking more of it (pdd2_accel(A, B, 1)'s geometry,
// `unique` and tie band): the choice and its verdict do not depend on what else is asked
// (superset_depth.h), so rigid_pd2_choice(A, B, &first) is rigid_pd2_choice(A, B) without the
// second kernel run. ran, unresolved: rigid_superset_scaled's kernel_ran and unresolved; done:
// its return value; ch, e: its choice and exponent.
struct SupersetFirstTry {
  bool ran = false, done = false, unresolved = false;
  Choice ch;
  int e = 0;
};
Choice rigid_pd2_choice(const TetVertices& A, const TetVertices& B, const SupersetFirstTry* first);

}  // namespace pdd::fast
