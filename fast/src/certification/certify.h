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

inline bool is_parallel(const CandidateSet& s, int k) { return s.parallel[k] == 1; }
inline bool is_parallel(const QuickCandidates&, int) { return false; }  // quick declines them
// Candidate k's degree bounds (value_bounds.h): its class's, or its own (nearly parallel), as
// the set stores them.
inline DegreeBounds bounds_of(const CandidateSet& s, int k) { return DegreeBounds{s.e_h[k], s.e_n[k]}; }
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
// (a CandidateSet's: the normal read where candidate() would copy it from, without the rest)
inline ApproxNormal approx_normal(const CandidateSet& s, int i) {
  const double e = bounds_of(s, i).e_n;
  if (s.lane[i] < 0) {
    const double* n = s.explicit_[i].n;
    return ApproxNormal{{n[0], n[1], n[2]}, e, is_parallel(s, i)};
  }
  const int l = s.lane[i];
  const double g = s.sign[i];
  return ApproxNormal{{g * s.edges.n0[l], g * s.edges.n1[l], g * s.edges.n2[l]}, e, false};
}

// Bit k set: component k of the label's raw normal is exactly 0 by structural zeros — each of
// its two products x_i y_j, x_j y_i has a factor that is a difference of two equal doubles (for
// finite doubles a − b is 0 exactly when a == b). Raw normals: (p1 − p0) × (p2 − p0) over kFace
// for FV:i (A) and VF:j (B), eB × eA for EE:a:b. Sufficient, not necessary: a 0 bit means "not
// shown". (An exactly parallel edge pair's normal is not a cross product: not asked.)
inline unsigned structural_zero_components(const TetVertices& A, const TetVertices& B, const DirectionLabel& l) {
  const Vec3d *p0, *p1, *q0, *q1;  // the two factors x = p1 − p0, y = q1 − q0
  if (l.kind == ContactKind::EE) {
    p0 = &B[kEdges[l.b][0]], p1 = &B[kEdges[l.b][1]], q0 = &A[kEdges[l.a][0]], q1 = &A[kEdges[l.a][1]];
  } else {
    const TetVertices& T = l.kind == ContactKind::FV ? A : B;
    const auto& f = kFace[l.a];
    p0 = q0 = &T[f[0]], p1 = &T[f[1]], q1 = &T[f[2]];
  }
  unsigned mask = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const bool first = (*p1)[i] == (*p0)[i] || (*q1)[j] == (*q0)[j];
    const bool second = (*p1)[j] == (*p0)[j] || (*q1)[i] == (*q0)[i];
    mask |= unsigned(first && second) << k;
  }
  return mask;
}

// Candidates c[0..n) whose exact oriented normals all point one way along a coordinate axis,
// shown without expansions (aligned pairs: a face along a coordinate plane, the edge pairs
// lying in it, the face of the other tetrahedron that touches it): the same two components
// exactly 0 by structural zeros (structural_zero_components), so that every normal is a
// non-zero multiple of one axis (a face's normal and a non-parallel edge pair's are never 0),
// and each one's dot product with c[0]'s certainly positive (certain_dot_sign on the double
// normals and their bounds). Their delta² are then exactly equal: delta depends on the
// oriented direction only (definitions §4: D scales with n). False: not shown (an exactly
// parallel edge pair among them, another direction, a sign within its bound).
// a: the candidates' approx_normal, filled as far as the test went (all n when true). from: the
// first k tested (the members before it passed already: a caller growing the set one by one).
template <class List>
bool one_axis_direction(const List& s, const int* c, int n, ApproxNormal* a, int from = 0) {
  const auto zeros_of = [&s](int i) { return structural_zero_components(*s.A, *s.B, unpack_label(label_code(s, i))); };
  const unsigned axis = n > 0 ? zeros_of(c[0]) : 0u;
  if (axis != 3u && axis != 5u && axis != 6u) return false;  // two components exactly 0
  for (int k = from; k < n; ++k) {
    a[k] = approx_normal(s, c[k]);
    if (a[k].parallel_pair || (k > 0 && (zeros_of(c[k]) != axis || certain_dot_sign(a[0], a[k]) != 1))) return false;
  }
  return true;
}
template <class List>
bool one_axis_direction(const List& s, const int* c, int n) {
  ApproxNormal a[kMaxCandidates];
  return one_axis_direction(s, c, n, a);
}

// one_axis_direction, else member by member against c[0]: certainly not parallel in doubles
// ends it (certainly_not_parallel), else the exact test (ExactDirection::same_as, given the
// certain sign of the dot product where there is one). Expansions: where a few candidates are
// known to tie (accel's contenders); a list's order over an integer frame is cheaper
// (first_least_delta2).
template <class List>
bool one_exact_direction(const List& s, const int* c, int n) {
  if (n < 2) return n == 1;
  ApproxNormal a[kMaxCandidates];
  if (one_axis_direction(s, c, n, a)) return true;
  for (int k = 0; k < n; ++k) {
    a[k] = approx_normal(s, c[k]);
    if (k > 0 && certainly_not_parallel(a[0], a[k])) return false;
  }
  const ExactDirection first(*s.A, *s.B, unpack_label(label_code(s, c[0])));
  for (int k = 1; k < n; ++k) {
    const int side = a[k].parallel_pair ? 0 : certain_dot_sign(a[0], a[k]);
    if (!first.same_as(unpack_label(label_code(s, c[k])), side).value_or(false)) return false;
  }
  return true;
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
  if (n > 1 && one_axis_direction(s, c, n)) return 0;  // exact ties: the earliest
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
