// double_word.h — internal to fast/src: double-word arithmetic (x = hi + lo, |lo| <= u |hi|,
// "normalised") and the error of each operation, for the compensated evaluations
// (compensated_heights.h, global/accurate_piece_matrix.h). Written by hand: a handful of
// error-free transformations with their bounds derived here, not a library (no Debian package
// offers them with the bounds stated).
//
//   two_sum(a, b) = (s, e), s + e = a + b exactly (Knuth; no overflow at these magnitudes);
//   two_prod(a, b) = (p, e), p + e = a b exactly (e = fma(a, b, −p)) unless e underflows:
//     then off by <= 2^-1075 (callers add an absolute term);
//   mul(x, y): (ch, c1) = two_prod(xh, yh); t0 = xl yl; t1 = fma(xh, yl, t0);
//     c2 = fma(xl, yh, t1); c3 = c1 + c2; two_sum(ch, c3). Error <= 6.2u² |xh| |yh|:
//     |xl yl| <= u²|xh yh| (t0's rounding: u³); t1 errs by <= u |xh yl + t0| <= u²(1 + u)
//     |xh yh|; c2 by <= u |xl yh + t1| <= 2u²(1 + u) |xh yh|; c3 by <= u (|c1| + |c2|) <= u
//     (u + 2u(1 + u)) |xh yh| < 3.1 u² |xh yh|; two_sum exact: < 6.2 u² in all;
//   add(x, y): (sh, s1) = two_sum(xh, yh); v = xl + yl; w = s1 + v; two_sum(sh, w). Error
//     <= 4u² (|xh| + |yh|): v errs by <= u (|xl| + |yl|) <= u² (|xh| + |yh|), w by <= u (|s1|
//     + |v|) <= u (u |sh| + u (|xh| + |yh|)(1 + u)) <= 2.1 u² (|xh| + |yh|); two_sum exact.
//   Both results are normalised (two_sum's).
#pragma once

#include <array>
#include <cmath>

// Run-time dispatch on x86-64 with GCC (as piece_screen.cpp) for functions built on these: a
// clone where fma is an instruction rather than a library call. fma is correctly rounded either
// way: the same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_FMA_CLONES __attribute__((target_clones("fma", "default")))
#else
#define PDD_FMA_CLONES
#endif

namespace pdd::fast::detail::dw {

inline constexpr double kU = 0x1p-53;

struct DW {
  double hi, lo;
};

inline DW two_sum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
inline DW two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
inline DW mul(DW x, DW y) {
  const DW c = two_prod(x.hi, y.hi);
  const double t0 = x.lo * y.lo, t1 = std::fma(x.hi, y.lo, t0), c2 = std::fma(x.lo, y.hi, t1);
  return two_sum(c.hi, c.lo + c2);
}
inline DW add(DW x, DW y) {
  const DW s = two_sum(x.hi, y.hi);
  return two_sum(s.hi, s.lo + (x.lo + y.lo));
}
inline DW neg(DW x) { return {-x.hi, -x.lo}; }

// A double word with a certified bound on its distance to an exact value x*: |v − x*| <= e
// (v = hi + lo, normalised: |v| <= |hi| (1 + u), taken as |hi| (1 + 2u) below). Each operation's
// bound is the operands' propagated ones, the operation's own error (above), 2^-1060 for the
// parts that round to subnormals (each error < 2^-1075, fewer than eight an operation), and a
// factor 1 + 2^-40 for the bound's own few roundings (each <= u):
//   plus:  e_x + e_y + 4u² (|x_h| + |y_h|);
//   times: |x~ y~ − x* y*| <= |x~| e_y + (|y~| + e_y) e_x, plus 6.2 u² |x_h y_h|.
// A non-finite value or bound decides nothing (certain_sign).
struct Bounded {
  DW v{0.0, 0.0};
  double e = 0.0;
};
inline Bounded exactly(double x) { return {{x, 0.0}, 0.0}; }
inline Bounded plus(const Bounded& x, const Bounded& y) {
  return {add(x.v, y.v),
          (x.e + y.e + 4 * kU * kU * (std::fabs(x.v.hi) + std::fabs(y.v.hi)) + 0x1p-1060) * (1 + 0x1p-40)};
}
inline Bounded minus(const Bounded& x, const Bounded& y) { return plus(x, {neg(y.v), y.e}); }
inline Bounded times(const Bounded& x, const Bounded& y) {
  const double X = std::fabs(x.v.hi) * (1 + 2 * kU), Y = std::fabs(y.v.hi) * (1 + 2 * kU);
  return {mul(x.v, y.v),
          (X * y.e + (Y + y.e) * x.e + 6.2 * kU * kU * std::fabs(x.v.hi * y.v.hi) + 0x1p-1060) * (1 + 0x1p-40)};
}
inline Bounded times(const Bounded& x, int k) { return times(x, exactly(double(k))); }
// The sign of x* where |hi| (1 − 2u) exceeds the bound (|v − hi| <= u |hi|), else 0 (NaN: 0).
inline int certain_sign(const Bounded& x) {
  return std::fabs(x.v.hi) * (1 - 2 * kU) > x.e ? (x.v.hi > 0 ? 1 : -1) : 0;
}

}  // namespace pdd::fast::detail::dw
