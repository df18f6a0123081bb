// best_offer.cpp — see best_offer.h.
#include "global/best_offer.h"

#include <algorithm>
#include <cmath>

namespace pdd::fast::global {

double Best::value_in(long extra) const {
  if (!A) return value;
  if (!have_q) return INFINITY;
  detail::Q x = qvalue;
  detail::scale_pow2(x, -2 * unit - extra);
  return x.get_d();
}

// relaxed_compensated (deformable_depth.h): the exact relaxed value along v lies within value
// (1 +- r)^2 (as evaluate_tight takes it), on a pair in the double pieces' range (global_depth.cpp:
// scale in [2^-100, 2^100], where the double path calls it too). Its lower end, computed with
// three roundings (<= 4u relative, the factor 1 - 8u), against the best rounded up: mpq's get_d
// truncates towards 0 and qvalue >= 0, so its successor is >= qvalue (0 or a subnormal below
// the smallest double: still an upper bound; above the double range: +inf, nothing shown).
bool Best::certainly_above(const V3& v) const {
  if (!(pair_scale >= 0x1p-100 && pair_scale <= 0x1p100)) return false;
  double x = 0, r = 1, hA[4], hB[4];
  DirectionSolution s;
  if (!relaxed_compensated(*A, *B, v, x, r, s, hA, hB) || !(r < 1) || !(x >= 0)) return false;
  const double lo = x * (1 - r) * (1 - r) * (1 - 8 * kU);
  return lo > std::nextafter(qvalue.get_d(), INFINITY);
}

}  // namespace pdd::fast::global
