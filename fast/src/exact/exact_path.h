// exact_path.h — internal to fast/src: the fast engine's slow path (definitions §8).
//
// Input:  a valid pair (finite coordinates, both volumes non-zero; the caller has checked).
// Output: every definitions §6 quantity, computed by this engine's own closed-form
//         algorithms (definitions §3 candidates, §4 depths, §5 per-direction QPs of src/qp/direction_qp_impl.h) on exact
//         rationals (GMP mpq_class: every input double is the rational it denotes), with exact
//         ties broken by canonical order, then rounded once to double (mpq_get_d: truncation,
//         relative error < 2^-52). `representable` is false when a non-zero value or a
//         coordinate of q1 is outside the normal double range after rounding.
// Independent of reference/: no CGAL, no shared arithmetic, so the two engines still check
// each other. Cost: milliseconds per pair (used on the pairs whose error bound is too wide).
#pragma once

#include <array>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

struct ExactPathResult {
  PairResult<double> result;  // name and error are left to the caller
  bool representable = true;
  // pdd2_relaxed's normal (exact, A -> B) by rounded_normal (exact_candidate.h): pdd2_global's
  // start (global_depth.h).
  // Zero when the pair does not intersect.
  std::array<double, 3> relaxed_normal{};
};

ExactPathResult solve_pair_exact_path(const TetVertices& A, const TetVertices& B);

}  // namespace pdd::fast::detail
