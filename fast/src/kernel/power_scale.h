// power_scale.h — internal to fast/src: exact power-of-two rescaling of a pair (definitions §8).
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

#include <algorithm>
#include <array>
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
// x86-64) and reduced on their bits, with no compare-and-branch per coordinate:
//   hi = max over (|x| bits >> 1), read as doubles. Those bits are < 2^62, so every such double
//        is finite and the maximum sees no NaN; the shift keeps the order (non-strictly) and the
//        exponent field (now bits 51..61). A coordinate is ±inf or NaN iff its |x| bits are
//        >= 0x7ff0...0 (even), iff the shifted bits are >= 0x3ff8...0: one test on hi decides
//        finiteness. For a normal max |x| = R, hi's exponent field is R's: e = 1023 − field.
//   lo = min over (|x| bits − 1), read as doubles: 0 becomes all ones, a NaN, which the
//        comparison `l < lo ? l : lo` never picks; every other |x| becomes a non-negative double
//        in the same order (finite |x|: a finite double). m = lo + 1 ulp is the least non-zero
//        |x|, or DBL_MAX + 1 ulp = +inf when every coordinate is 0.
// (Was: abs, max, min and a finiteness test on the values, 17.7 ns; this 10.3 ns per pair on
// the paper's pairs, identical results on 2·10^6 pairs with random bits, zeros, subnormals,
// infinities and NaNs.)
// The common case of the scaling, from the two reductions described below (hs: the maximum of
// the shifted |x| bits, ls: the minimum of |x| bits − 1, both read as doubles): every
// coordinate finite, R normal and |e| <= 1000. Then true, with e, the factor p = 2^e and
// `exact`; else false (power_scaled's other branches). One place for the rule: power_scaled
// and the superset kernel's fused scaling (superset_kernel.h) both decide with it.
inline bool common_scale(double hs, double ls, int& e, double& p, bool& exact) {
  std::uint64_t hb, mb;
  std::memcpy(&hb, &hs, sizeof hb);
  std::memcpy(&mb, &ls, sizeof mb);
  if (hb >= (0x7ff0000000000000ull >> 1)) return false;  // a coordinate is ±inf or NaN
  const int field = int(hb >> 51);  // normal R: ilogb(R) = field − 1023
  if (field == 0) return false;      // R subnormal or 0
  e = 1023 - field;
  if (e < -1000 || e > 1000) return false;
  const std::uint64_t pbits = std::uint64_t(e + 1023) << 52;  // 2^e, a normal double
  std::memcpy(&p, &pbits, sizeof p);
  ++mb;
  double m;  // least non-zero |x|; +inf when all are 0
  std::memcpy(&m, &mb, sizeof m);
  // (m p rounded up to exactly DBL_MIN is not exact: m p / p == m tells, as division by a
  // power of two is exact in the normal range. A computed m p >=
  // 2 DBL_MIN comes from an exact product >= 2 DBL_MIN (1 − u) > DBL_MIN, which is exact:
  // the division, a long latency on every call, runs only below that.)
  const double mp = m * p;
  exact = m == HUGE_VAL || mp >= 2 * DBL_MIN || (mp >= DBL_MIN && mp / p == m);
  return true;
}

inline ScaledPair power_scaled(const TetVertices& A, const TetVertices& B) {
  typedef double v2 __attribute__((vector_size(16)));
  typedef unsigned long long v2u __attribute__((vector_size(16)));
  static_assert(sizeof(TetVertices) == 12 * sizeof(double), "TetVertices: 12 packed doubles");
  constexpr unsigned long long kAbs = 0x7fffffffffffffffull;
  v2 x[12];
  std::memcpy(&x[0], &A, sizeof A);
  std::memcpy(&x[6], &B, sizeof B);
  v2 hi0 = {0.0, 0.0}, hi1 = hi0, lo0 = {DBL_MAX, DBL_MAX}, lo1 = lo0;  // two chains each
  for (int i = 0; i < 12; i += 2) {
    const v2u a0 = (v2u)x[i] & kAbs, a1 = (v2u)x[i + 1] & kAbs;
    const v2 h0 = (v2)(a0 >> 1), h1 = (v2)(a1 >> 1), l0 = (v2)(a0 - 1), l1 = (v2)(a1 - 1);
    hi0 = h0 > hi0 ? h0 : hi0;
    hi1 = h1 > hi1 ? h1 : hi1;
    lo0 = l0 < lo0 ? l0 : lo0;
    lo1 = l1 < lo1 ? l1 : lo1;
  }
  hi0 = hi1 > hi0 ? hi1 : hi0;
  lo0 = lo1 < lo0 ? lo1 : lo0;
  const double hs = hi0[1] > hi0[0] ? hi0[1] : hi0[0], ls = lo0[1] < lo0[0] ? lo0[1] : lo0[0];
  ScaledPair s;
  double p;
  if (common_scale(hs, ls, s.e, p, s.exact)) {
    for (int i = 0; i < 12; ++i) x[i] = x[i] * p;
    std::memcpy(&s.A, &x[0], sizeof s.A);
    std::memcpy(&s.B, &x[6], sizeof s.B);
    return s;
  }
  std::uint64_t hb;
  std::memcpy(&hb, &hs, sizeof hb);
  if (hb >= (0x7ff0000000000000ull >> 1)) {
    s.finite = s.exact = false;
    return s;
  }
  if (const int field = int(hb >> 51); field != 0) {  // normal R, |e| > 1000
    s.e = 1023 - field;
  } else {  // R subnormal or 0 (the shift lost R's last bit: take R again, rare)
    double R = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) R = std::fmax(R, std::fmax(std::fabs(A[i][k]), std::fabs(B[i][k])));
    s.e = R > 0.0 ? -std::ilogb(R) : 0;
  }
  s.exact = true;
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

// v·2^k, ldexp's correctly rounded value: one multiplication by the double 2^k when |k| <=
// 1000 (a product by a power of two is exact, or rounded once where it leaves the normal
// range), else ldexp (a library call, ~50 instructions).
inline double times_pow2(double v, int k) {
  if (k < -1000 || k > 1000) return std::ldexp(v, k);
  const std::uint64_t pbits = std::uint64_t(k + 1023) << 52;
  double p;
  std::memcpy(&p, &pbits, sizeof p);
  return v * p;
}

// v·2^k when it is 0 or a normal double; `ok` cleared otherwise.
inline double unscaled(double v, int k, bool& ok) {
  const double w = times_pow2(v, k);
  if (v != 0.0 && !(std::fabs(w) >= DBL_MIN && std::fabs(w) <= DBL_MAX)) ok = false;
  return w;
}

// The fast engine's scale of a normal (pdd2_global_normal, pdd.h): multiplied by the power of two
// that puts its largest |component| in [1, 2), which keeps its direction exactly (a unit vector
// rounded would not: the engine's normal is the triple along which the value was certified,
// and on a contact far shallower than the pair's extent only a few triples of doubles, not
// always one near the unit sphere, attain it). Left as it is when the scaling would not be
// exact (a component would become subnormal) or the normal is zero.
inline void power_normalized(std::array<double, 3>& n) {
  const double m = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
  if (!(m > 0) || !std::isfinite(m)) return;
  const int e = std::ilogb(m);
  std::array<double, 3> out;
  for (int k = 0; k < 3; ++k) {  // (times_pow2: ldexp's values, one product each)
    out[k] = times_pow2(n[k], -e);
    if (times_pow2(out[k], e) != n[k]) return;
  }
  n = out;
}

}  // namespace pdd::fast::detail
