// power_scale.h — internal to fast/src: exact power-of-two rescaling of a pair (SPEC §8).
//
// Input:  a pair with finite coordinates.
// Output: the pair multiplied by 2^e, with e chosen so that the largest |coordinate| R lies in
//         [1, 2), and `exact` = whether every scaled coordinate is exactly x·2^e (always when
//         e >= 0; when e < 0, unless a non-zero coordinate would become subnormal).
// Why: every error bound of the double path (filter_bounds.h, value_bounds.h) assumes the
// extent L in [2^-200, 2^200] and no overflow; after scaling R < 2, so nothing overflows, and the
// bounds are invariant under the scaling (all relative). Values scale back by 2^-2e, positions
// by 2^-e, exactly unless the result leaves the normal range (checked by the caller).
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

struct ScaledPair {
  TetVertices A, B;
  int e = 0;
  bool exact = true;
  bool finite = true;  // false: a coordinate is ±inf or NaN (nothing else is set then)
};

// A non-finite coordinate: `finite` false and nothing else (callers may test it instead of
// calling all_finite first).
// x·2^e is computed as one multiplication by the double 2^e when |e| <= 1000 (2^e is then a
// normal double, built from its exponent bits): the same correctly rounded product as ldexp
// (exact unless the result is subnormal), without a library call per coordinate.
// Exactness: x·2^e is exact iff the exact product is 0 or at least DBL_MIN (normal range, no
// overflow as R·2^e < 2). The smallest non-zero |x| = m has the smallest product, so the test on
// m decides it for every coordinate: m·2^e >= DBL_MIN after rounding and, since a product just
// below DBL_MIN rounds up to exactly DBL_MIN, (m·2^e)/2^e == m.
// The 24 coordinates are read as 12 two-lane vectors (GCC/Clang vector extensions, SSE2 on
// x86-64): the same maxima, minima and products as a scalar loop (max, min and the finiteness
// test are exact in any order; each product is one correctly rounded multiplication), without
// a compare-and-branch per coordinate.
inline ScaledPair power_scaled(const TetVertices& A, const TetVertices& B) {
  typedef double v2 __attribute__((vector_size(16)));
  typedef long long v2l __attribute__((vector_size(16)));
  static_assert(sizeof(TetVertices) == 12 * sizeof(double), "TetVertices: 12 packed doubles");
  constexpr double kInf = HUGE_VAL;
  v2 x[12];
  std::memcpy(&x[0], &A, sizeof A);
  std::memcpy(&x[6], &B, sizeof B);
  v2 Rv = {0.0, 0.0}, mv = {kInf, kInf};  // max |x|; min non-zero |x|
  v2l bad = {0, 0};                       // x − x is 0 for a finite x, NaN for ±inf and NaN
  for (int i = 0; i < 12; ++i) {
    const v2 a = x[i] < 0.0 ? -x[i] : x[i];
    bad |= (a - a) != 0.0;
    Rv = Rv > a ? Rv : a;
    const v2 ma = a != 0.0 ? a : kInf;
    mv = mv < ma ? mv : ma;
  }
  const double R = Rv[0] > Rv[1] ? Rv[0] : Rv[1], m = mv[0] < mv[1] ? mv[0] : mv[1];
  ScaledPair s;
  if (bad[0] | bad[1]) {
    s.finite = s.exact = false;
    return s;
  }
  if (R >= DBL_MIN) {  // normal R: ilogb(R) = biased exponent − 1023
    std::uint64_t bits;
    std::memcpy(&bits, &R, sizeof bits);
    s.e = 1023 - int((bits >> 52) & 0x7ff);
  } else {
    s.e = R > 0.0 ? -std::ilogb(R) : 0;
  }
  if (s.e >= -1000 && s.e <= 1000) {
    const std::uint64_t pbits = std::uint64_t(s.e + 1023) << 52;  // 2^e, a normal double
    double p;
    std::memcpy(&p, &pbits, sizeof p);
    for (int i = 0; i < 12; ++i) x[i] = x[i] * p;
    std::memcpy(&s.A, &x[0], sizeof s.A);
    std::memcpy(&s.B, &x[6], sizeof s.B);
    // (m p rounded up to exactly DBL_MIN is not exact: m p / p == m tells, as division by a
    // power of two is exact in the normal range; a review found that case. A computed m p >=
    // 2 DBL_MIN comes from an exact product >= 2 DBL_MIN (1 − u) > DBL_MIN, which is exact:
    // the division, a long latency on every call, runs only below that.)
    const double mp = m * p;
    s.exact = m == kInf || mp >= 2 * DBL_MIN || (mp >= DBL_MIN && mp / p == m);
    return s;
  }
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      s.A[i][k] = std::ldexp(A[i][k], s.e);
      s.B[i][k] = std::ldexp(B[i][k], s.e);
      const double a = std::fabs(s.A[i][k]), b = std::fabs(s.B[i][k]);
      if ((a != 0.0 && a < DBL_MIN) || (b != 0.0 && b < DBL_MIN) ||
          (A[i][k] != 0.0 && a == 0.0) || (B[i][k] != 0.0 && b == 0.0))
        s.exact = false;
    }
  return s;
}

// v·2^k when it is 0 or a normal double; `ok` cleared otherwise. One multiplication by the
// double 2^k when |k| <= 1000 (correctly rounded, as ldexp), else ldexp.
inline double unscaled(double v, int k, bool& ok) {
  double w;
  if (k >= -1000 && k <= 1000) {
    const std::uint64_t pbits = std::uint64_t(k + 1023) << 52;
    double p;
    std::memcpy(&p, &pbits, sizeof p);
    w = v * p;
  } else {
    w = std::ldexp(v, k);
  }
  if (v != 0.0 && !(std::fabs(w) >= DBL_MIN && std::fabs(w) <= DBL_MAX)) ok = false;
  return w;
}

}  // namespace pdd::fast::detail
