// best_offer.cpp — see best_offer.h.
#include "global/best_offer.h"

#include <algorithm>

namespace pdd::fast::global {

double Best::value_in(long extra) const {
  if (!A) return value;
  if (!have_q) return INFINITY;
  detail::Q x = qvalue;
  detail::scale_pow2(x, -2 * unit - extra);
  return x.get_d();
}

void Best::offer(const Problem& P, const V3& v) {
  if (!nonzero(v)) return;
  if (A) {
    detail::Q hA[4], hB[4];
    Solution<detail::Q> s;
    const detail::Q q = relaxed_exact(*A, *B, v, hA, hB, s);
    if (have_q && !(q < qvalue)) return;
    qvalue = q, have_q = true, n = v;
    value = value_in(0);
    return;
  }
  DirectionSolution& s = last;
  double hm = 0, hA[4], hB[4];
  const double x = relaxed_at(P, v, &s, &hm, hA, hB);
  const double error = value_error(P, v, s.cost, hm);
  offers.push_back({x, error, v});
  if (x < value) {
    value = x, n = v;
    win.n = v, win.sol = s, win.error = error;
    std::copy(hA, hA + 4, win.hA), std::copy(hB, hB + 4, win.hB);
  }
}

}  // namespace pdd::fast::global
