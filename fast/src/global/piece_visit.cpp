// piece_visit.cpp — see piece_visit.h.
#include "global/piece_visit.h"

namespace pdd::fast::global {

bool arc_middle(const Conditions& c, const V3& p, const V3& q, V3& out) {
  double lo = 0, hi = 0;
  bool started = false;
  for (int k = 0; k < 8; ++k) {
    const double a = c.sign[k] * dot(c.l[k], p), b = c.sign[k] * dot(c.l[k], q);
    const double R = std::hypot(a, b), tol = c.tol(k);
    if (R <= tol) continue;  // holds on the whole circle within tolerance
    const double phi = std::atan2(b, a), w = M_PI / 2 + std::asin(std::min(1.0, tol / R));
    double x0 = phi - w, x1 = phi + w;
    if (!started) {
      lo = x0, hi = x1, started = true;
      continue;
    }
    const double shift = 2 * M_PI * std::round(((lo + hi) / 2 - phi) / (2 * M_PI));
    x0 += shift, x1 += shift;
    lo = std::max(lo, x0), hi = std::min(hi, x1);
    if (lo > hi) return false;
  }
  const double t = started ? (lo + hi) / 2 : 0.0;
  out = add(mul(p, std::cos(t)), mul(q, std::sin(t)));
  return true;
}

}  // namespace pdd::fast::global
