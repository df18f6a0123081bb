#include "pdd/compare/theorem_audit.h"

#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/eq11.h"
#include "pdd/reference/minkowski_pd.h"
#include "pdd/reference/oriented_depth.h"
#include "pdd/reference/validate_pair.h"

namespace pdd::compare {

using namespace reference;

namespace {

bool intersects_after(const ExactPair& p, const Vector& v) {
  ExactPair moved = p;
  for (auto& r : moved.B) r = r + v;
  return minkowski_pd(moved).intersecting;
}

// max(0, min over candidates of sign(delta) delta^2): PD^2 by the corrected statement.
Rational min_oriented_depth_square(const ExactPair& p, const std::vector<CandidateDirection>& c) {
  Rational lo = oriented_depth_signed_square(p, c.front().n);
  for (const auto& d : c) lo = CGAL::min(lo, oriented_depth_signed_square(p, d.n));
  return CGAL::max(lo, Rational(0));
}

}  // namespace

TheoremVerdict theorem_verdict(const TetPair& pair, bool with_nef) {
  TheoremVerdict v;
  v.name = pair.name;
  if (auto why = validate_pair(pair)) {
    v.error = why;
    return v;
  }
  const ExactPair p = to_exact(pair);
  const auto cands = candidate_directions(p);
  const MinkowskiPd mink = minkowski_pd(p);
  v.intersecting = mink.intersecting;
  v.pd2 = mink.pd2;
  v.corrected_holds = (min_oriented_depth_square(p, cands) == mink.pd2);
  if (with_nef) v.nef_equal = nef_minkowski_equals_hull(p);
  const Eq11Result e = eq11(p, cands);
  v.e11_2 = e.e11_squared;
  v.eq11_holds = (v.e11_2 == v.pd2);
  if (!e.positive) return v;  // E11 = 0: some axis separates
  const CandidateDirection& axis = cands[e.argmin];
  v.axis = axis.label.str();
  v.nested = projections_nest(p, axis.n);
  if (v.eq11_holds) return v;
  const Vector w = (eq11_overlap(p, axis.n) / axis.n.squared_length()) * axis.n;  // |w| = E11
  v.witness = w;
  v.witness_plus_intersects = intersects_after(p, w);
  v.witness_minus_intersects = intersects_after(p, -w);
  return v;
}

}  // namespace pdd::compare
