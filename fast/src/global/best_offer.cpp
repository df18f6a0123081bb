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

}  // namespace pdd::fast::global
