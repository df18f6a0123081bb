#include "pdd/reference/eq11.h"

#include "pdd/reference/oriented_depth.h"

namespace pdd::reference {

Rational eq11_overlap(const ExactPair& pair, const Vector& n) {
  const Rational a_lo = min_projection(pair.A, n), a_hi = max_projection(pair.A, n);
  const Rational b_lo = min_projection(pair.B, n), b_hi = max_projection(pair.B, n);
  const Rational union_width = CGAL::max(a_hi, b_hi) - CGAL::min(a_lo, b_lo);
  return (a_hi - a_lo) + (b_hi - b_lo) - union_width;
}

bool projections_nest(const ExactPair& pair, const Vector& n) {
  const Rational a_lo = min_projection(pair.A, n), a_hi = max_projection(pair.A, n);
  const Rational b_lo = min_projection(pair.B, n), b_hi = max_projection(pair.B, n);
  return (a_lo <= b_lo && b_hi <= a_hi) || (b_lo <= a_lo && a_hi <= b_hi);
}

Eq11Result eq11(const ExactPair& pair, const std::vector<CandidateDirection>& candidates) {
  Eq11Result out;
  out.positive = true;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Rational o = eq11_overlap(pair, candidates[k].n);
    if (o <= 0) return Eq11Result{};  // some axis separates: E11 = 0
    const Rational sq = o * o / candidates[k].n.squared_length();
    if (k == 0 || sq < out.e11_squared) {
      out.e11_squared = sq;
      out.argmin = k;
    }
  }
  return out;
}

}  // namespace pdd::reference
