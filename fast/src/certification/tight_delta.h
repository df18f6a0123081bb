// tight_delta.h — internal to fast/src: a candidate's delta² with a root bound far tighter than
// the engine's double one where the contact is far shallower than the pair (refine.h's
// refine_tight, pdd2_accel's exact order).
//
// Input:  a list (CandidateSet or QuickCandidates, which know their pair) and a candidate i.
// Output: v = delta² and r, its root bound (value_bounds.h: the exact delta² lies in
//         [lower_of(v, r), upper_of(v, r)]); always true (the double value and bound where the
//         compensated heights do not apply: a parallel edge pair).
#pragma once

#include <algorithm>
#include <cmath>

#include "certification/certify.h"
#include "certification/compensated_heights.h"
#include "certification/value_bounds.h"
#include "kernel/candidate_directions.h"
#include "kernel/quick_candidates.h"

namespace pdd::fast::detail {

// The largest of four heights h~ (|h~_i - H*_i| <= e_i) and how far the exact largest can be
// from it. With e the largest e_i, a vertex j with h~_j < max h~ - 2e has H*_j < max h~ - e <=
// H*_k (k attaining max h~), so the exact maximum is attained within N = {i : h~_i >= max h~
// - 2e} and lies within e_N (the largest e_i over N) of max h~. N is taken as h~_i >= fl(max
// h~ - 4e): that threshold's rounding is <= u (|max h~| + 4e) <= 2e (compensated_heights.h's
// e_i >= u |h~_i|), so it is <= max h~ - 2e and N is covered. Far vertices (heights ~|n| L,
// errors ~u |n| L) do not enter: a contact ~1e-17 of the size deep keeps ~15 correct digits.
// (The smallest: the same on -h.)
struct Extreme {
  double value, error;
};
inline Extreme largest(const double (&h)[4], const double (&e)[4], double sign = 1.0) {
  double top = -INFINITY, e_all = 0;
  for (int k = 0; k < 4; ++k) top = std::max(top, sign * h[k]), e_all = std::max(e_all, e[k]);
  const double near = top - 4 * e_all;
  double e_near = 0;
  for (int k = 0; k < 4; ++k)
    if (sign * h[k] >= near) e_near = std::max(e_near, e[k]);
  return {sign * top, e_near};
}
inline Extreme smallest(const double (&h)[4], const double (&e)[4]) { return largest(h, e, -1.0); }

// The smaller of two such values: within the larger error of the two, or within the smaller
// one's own when it is certainly the smaller (b - a >= ea + eb in exact arithmetic: the
// computed difference errs by <= u (|a| + |b|), hence the margin). The larger: on -x.
inline Extreme lesser(const Extreme& a, const Extreme& b, double sign = 1.0) {
  const double x = sign * a.value, y = sign * b.value;
  const double margin = (a.error + b.error + 2 * kUnitRoundoff * (std::fabs(x) + std::fabs(y))) * (1 + 0x1p-40);
  if (y - x >= margin) return a;
  if (x - y >= margin) return b;
  return {sign * std::min(x, y), std::max(a.error, b.error)};
}
inline Extreme greater(const Extreme& a, const Extreme& b) { return lesser(a, b, -1.0); }

// delta² of candidate i of a list (CandidateSet or QuickCandidates) with its root bound
// (value_bounds.h): D = max hA - min hB on compensated_heights.h's heights and normal (e_n per
// component), else the double one. |D~ - D*| <= eA + eB + u |D~| (largest, smallest):
// value_bounds.h's rigid bound with e_h the larger.
template <class List>
bool tight_delta2(const List& s, int i, double& v, double& r) {
  const Candidate c = candidate(s, i);
  CompensatedHeights h;
  if (!compensated_heights(*s.A, *s.B, c, h)) {
    v = s.delta_sq[i], r = rigid_rel(s, i);
    return true;
  }
  const Extreme a = largest(h.hA, h.eA), b = smallest(h.hB, h.eB);
  const double D = a.value - b.value;
  v = D * D / h.nn;
  r = rigid_root_rel(D, h.nn, DegreeBounds{std::max(a.error, b.error), h.e_n});
  return true;
}

}  // namespace pdd::fast::detail
