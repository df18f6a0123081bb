// refine.h — internal to fast/src: when a minimum over candidates cannot be certified in doubles
// (definitions §8, value_bounds.h), evaluate exactly only the candidates that can still be the
// minimum ("contenders") instead of the whole pair on the exact path.
//
// Input:  a candidate list (CandidateSet or QuickCandidates, which know their pair), for each
//         candidate i a certified lower bound lo(i) of its exact value (value_bounds.h; +inf for
//         a candidate that is not in the family, e.g. infeasible), and hi, a certified upper
//         bound of the exact value of one candidate of the family (the double path's choice).
// Output: the exact minimum over the family, rounded once (exact_candidate.h), with the label of
//         the first candidate in canonical order attaining it — the exact path's value and
//         label, bit for bit — and certified = refined = true; or false (nothing changed) when
//         there are more than kMaxRefined contenders or the value is not a normal double.
//
// Why it is the exact minimum (proof). Let x* be the exact minimum over the family. The choice's
// exact value is >= x* and <= hi, so x* <= hi. Every candidate j with exact value <= x* has
// lo(j) <= x* <= hi, so it is a contender: the exact minimisers, and all exact ties with them,
// are among the contenders, and every other candidate's exact value is > x*. The minimum over
// the contenders, first in canonical order among equals (indices ascend), is therefore the
// family's, with the exact path's tie rule (canonical order).
// Cost: a few exact candidates (~10–30 µs each) on the rare pairs that need it (shallow
// contacts whose double error bound exceeds 1e-9 relative), instead of the whole exact path.
#pragma once

#include <optional>

#include "exact/exact_candidate.h"
#include "kernel/candidate_directions.h"
#include "kernel/rigid_depth.h"

namespace pdd::fast::detail {

inline constexpr int kMaxRefined = 8;  // more contenders: the whole exact path is as cheap

// The contenders {i : !(lo(i) > hi)} (NaN counts as a contender) in canonical order; false
// when there are more than kMaxRefined.
template <class List, class Lo>
bool contenders(const List& s, Lo lo, double hi, int* idx, int& m) {
  m = 0;
  for (int i = 0; i < s.count; ++i)
    if (!(lo(i) > hi)) {
      if (m == kMaxRefined) return false;
      idx[m++] = i;
    }
  return m > 0;
}

// `exact_value(c, q)`: the family's exact value of candidate c into q; false when c is not in
// the family (e.g. an undecidable EE direction in case 1).
template <class List, class Lo, class ExactValue>
bool refine_minimum(const List& s, Lo lo, double hi, ExactValue exact_value, Choice& ch) {
  int idx[kMaxRefined], m = 0;
  if (!s.A || !contenders(s, lo, hi, idx, m)) return false;
  const ExactFrame f = exact_frame(*s.A, *s.B);
  Q best, v;
  int bi = -1;
  for (int j = 0; j < m; ++j) {
    const ExactCandidate c = exact_candidate(f, unpack_label(label_code(s, idx[j])));
    if (!exact_value(c, v)) continue;
    if (bi < 0 || v < best) {
      best = v;
      bi = idx[j];
    }
  }
  if (bi < 0) return false;
  bool ok = true;
  const double d = rounded_value(unscaled(f, best, 2), ok);
  if (!ok || !(d > 0.0)) return false;
  ch.value = d;
  ch.index = bi;
  ch.code = label_code(s, bi);
  ch.certified = ch.refined = true;
  return true;
}

}  // namespace pdd::fast::detail
