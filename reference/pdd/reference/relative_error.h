// relative_error.h — how far a double is from an exact value, measured exactly.
//
// Input:  a double `approx` (e.g. a value of the fast engine) and an exact rational `exact`.
// Output: |approx − exact| / |exact|, computed in rationals and rounded once to a double;
//         0 when both are 0, +inf when only `exact` is 0 or `approx` is not finite.
// Used by the harness's judge (compare/harness) and by the fast engine's fuzz target, which
// checks the same contract without the harness.
#pragma once

#include <cmath>
#include <limits>

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

inline double relative_error(double approx, const Rational& exact) {
  if (!std::isfinite(approx)) return std::numeric_limits<double>::infinity();
  const Rational diff = CGAL::abs(Rational(approx) - exact);
  if (exact == 0) return diff == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return CGAL::to_double(diff / CGAL::abs(exact));
}

}  // namespace pdd::reference
