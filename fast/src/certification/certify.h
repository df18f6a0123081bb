// certify.h — internal to fast/src: definitions §8 bounds of the candidates of a list (CandidateSet
// or QuickCandidates), from value_bounds.h. One place for "the root bound of candidate k".
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "certification/compensated_heights.h"
#include "certification/value_bounds.h"
#include "exact/exact_predicates.h"
#include "exact/integer_depth.h"
#include "kernel/candidate_directions.h"
#include "kernel/quick_candidates.h"

namespace pdd::fast::detail {

inline bool is_parallel(const CandidateSet& s, int k) { return s.lane[k] < 0 && s.parallel[k] == 1; }
inline bool is_parallel(const QuickCandidates&, int) { return false; }  // quick declines them
// Candidate k's degree bounds (value_bounds.h): its class's, or its own (nearly parallel).
inline DegreeBounds bounds_of(const CandidateSet& s, int k) {
  if (s.lane[k] < 0 && s.parallel[k] == 2) return DegreeBounds{s.own_eh[k], s.own_en[k]};
  return degree_bounds(s.fb, is_parallel(s, k));
}
inline DegreeBounds bounds_of(const QuickCandidates& s, int) { return degree_bounds(s.fb, false); }

// Root bound of delta² of candidate k (value_bounds.h, rigid).
template <class List>
double rigid_rel(const List& s, int k) {
  return rigid_root_rel(s.depth[k], s.nn[k], bounds_of(s, k));
}

// Cheap test, products only: |D| >= 400 e_h and n.n >= (400 e_n)². Then rigid_rel(s, k) is
// finite and <= 1.02 (2/400 + u + sqrt(3)/400 + 4u) < 0.00952 (value_bounds.h), so
// lower_of(delta², rigid_rel) >= (1 − 0.00952)² (1 − 3u) delta² > 0.981 delta² (the three
// roundings of lower_of included). Used to skip the division and square root of
// rigid_rel for candidates far above a chosen value v (delta² > 2 v, or coeff delta² > 2 v):
// their lower bound then exceeds 1.96 v >= the chosen candidate's own lower bound, so it can
// never be the minimum of the lower bounds, and skipping it leaves that minimum unchanged.
// Or, with kSmallRigidLower: a candidate with rigid_rel_small and
// kSmallRigidLower · x > m (x = delta², or coeff delta² with coeff a power of two) has
// lower bound >= 0.981 x > m: the computed product is <= 0.98 (1 + u)² x < 0.981 x.
inline constexpr double kSmallRigidLower = 0.98;
template <class List>
bool rigid_rel_small(const List& s, int k) {
  const DegreeBounds db = bounds_of(s, k);
  const double D = s.depth[k], eh = 400 * db.e_h, en = 400 * db.e_n;
  return (D * D >= eh * eh) & (s.nn[k] >= en * en);  // (no short-circuit: no branch)
}

// Largest |height| of a candidate (value_bounds.h: Hm).
inline double max_height(const DirectionGeometry& c) {
  double m = 0.0;
  for (int i = 0; i < 4; ++i) m = std::max(m, std::max(std::fabs(c.hA[i]), std::fabs(c.hB[i])));
  return m;
}

// Root bound of a QP value v = F/(20 n.n) along candidate c.
inline double qp_rel(const Candidate& c, double v, const FilterBounds& fb) {
  return qp_root_rel(v * 20.0 * c.nn, c.nn, max_height(c), degree_bounds_of(fb, c));
}

// Candidate i's double normal and the bound e_n on each component's error (value_bounds.h):
// the exact direction tests' hints (exact_predicates.h's ApproxNormal).
template <class List>
ApproxNormal approx_normal(const List& s, int i) {
  const Candidate x = candidate(s, i);
  return ApproxNormal{{x.n[0], x.n[1], x.n[2]}, bounds_of(s, i).e_n, x.parallel};
}

// The position in c[0..n) (candidate indices in canonical order) of the first least exact
// delta², exact ties to the earliest; -1 where neither compensated depths nor expansions can
// decide (first_least_delta2_exact's running minimum, each step decided first by
// compare_delta2_compensated where both candidates have compensated depths: delta² a rounding
// apart, aligned pairs; then by exact direction and expansions, given each candidate's double
// normal and its bound e_n so that directions certainly apart are not tested for equality).
// Where the pair has an integer frame (integer_heights.h), the whole order is taken over
// integers instead (integer_depth.h: a few hundred instructions a comparison, exact ties
// included).
template <class List>
int first_least_delta2(const List& s, const int* c, int n) {
  DirectionLabel l[kMaxCandidates];
  for (int k = 0; k < n; ++k) l[k] = unpack_label(label_code(s, c[k]));
  IntegerFrame frame(*s.A, *s.B);
  if (frame.usable())
    if (const int w = first_least_delta2_framed(frame, l, n); w >= 0) return w;
  ApproxNormal a[kMaxCandidates];
  CompensatedDepth d[kMaxCandidates];
  bool have[kMaxCandidates];
  for (int k = 0; k < n; ++k) {
    a[k] = approx_normal(s, c[k]);
    have[k] = !a[k].parallel_pair && compensated_depth(*s.A, *s.B, l[k], d[k]);
  }
  auto compensated = [&d, &have](int k, int w) -> std::optional<int> {
    if (!have[k] || !have[w]) return std::nullopt;
    return compare_delta2_compensated(d[k], d[w]);
  };
  return first_least_delta2_exact(*s.A, *s.B, l, n, a, compensated);
}

}  // namespace pdd::fast::detail
