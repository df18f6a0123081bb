// integer_heights.h — internal to fast/src: exact signs of heights along a cross product of
// coordinate differences, n.(p − q) with n = (p1 − p0) × (q1 − q0) (det[p1 − p0, q1 − q0, p − q],
// the degree-3 predicates of exact_sat.h), in machine integers, for a pair whose coordinates
// are all integer multiples of one power of two 2^e and below 2^(e + 60) in magnitude (and
// below 2^60).
//
// Input:  IntegerFrame(A, B): the pair (any doubles: an inf or a NaN refuses the frame).
//         height_sign(p1, p0, q1, q0, p, q): six of the pair's vertices by index (0..3: A's
//         s0..s3, 4..7: B's r0..r3).
// Output: usable(): such an e exists (computed once, on first use); then height_sign is the
//         exact sign of n.(p − q): −1, 0 or +1 (normal() and dot_sign() share n between heights);
//         dot() the exact value n.(p − q), vertex() the integers X and unit_exponent() e, for
//         integer_depth.h's depths.
//
// Why it applies: a grid of decimal cell (0.1, 0.025 ...) and a copy shifted by a decimal
// offset have coordinates whose lowest set bits lie within ~60 bits of their highest ones, and
// so do most pairs of nearby vertices of like magnitude (the pairs of aligned meshes whose
// separating-axis signs the doubles cannot decide). Where it applies it decides every sign,
// exact zeros included, in a few dozen instructions; the double words of compensated_heights.h
// take ~140 instructions a height and ~230 a normal and cannot show a zero, the expansions of
// exact_heights.h ~1,000. Elsewhere (a coordinate far smaller than the others, or subnormal)
// the callers keep those.
//
// Method. Let 2^h <= max |coordinate| < 2^(h + 1), h <= 59, and e = h − 59. When every
// coordinate x times 2^−e is an integer X (find_scale), every coordinate is X 2^e with
// |X| < 2^60, and X is an int64. (That holds iff every coordinate's lowest set bit is at least
// 2^(h − 59): the coordinates span at most 60 bits.) Then (in units of 2^e, all exact):
//   differences      |X_i − X_j| < 2^61                                   (int64)
//   n_k = u_i v_j − u_j v_i: products < 2^122, difference < 2^123         (__int128)
//   n.w = sum_k n_k w_k, |w_k| < 2^61: terms < 2^184. With n_k = h_k 2^64 + l_k
//         (h_k = n_k >> 64, floor: |h_k| <= 2^59; 0 <= l_k < 2^64):
//         H = sum h_k w_k, |H| < 3 2^120;  L = sum l_k w_k, |L| < 3 2^125 < 2^127  (__int128)
//         n.w = H 2^64 + L = (H + (L >> 64)) 2^64 + (L mod 2^64), the last term in [0, 2^64):
//         its sign is that of S = H + (L >> 64) (|S| < 2^121 + 2^63) when S != 0, else
//         that of L mod 2^64 (0 or positive).
// (>> on a negative __int128 is GCC's and Clang's arithmetic shift, floor division by 2^64.)
// Written by hand: boost::multiprecision's fixed int256_t gives the same exact sum without the
// split, at about 2.4 times the time a sign (measured with the frame and the normal included:
// a generic limb loop per operation); GMP's mpz allocates.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

class IntegerFrame {
 public:
  IntegerFrame(const TetVertices& A, const TetVertices& B) : A_(A), B_(B) {}

  bool usable() {
    if (state_ < 0) state_ = find_scale() ? 1 : 0;
    return state_ == 1;
  }
  // The pair the frame was made of (a memo's key: what the frame computes depends on it alone).
  const TetVertices& a() const { return A_; }
  const TetVertices& b() const { return B_; }

  // Vertices by index: 0..3 A's s0..s3, 4..7 B's r0..r3. Precondition of both: usable().
  // n = (p1 − p0) × (q1 − q0) in units 2^(2e) (header: each component below 2^123).
  void normal(int p1, int p0, int q1, int q0, __int128 (&n)[3]) const {
    std::int64_t u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = X_[p1][k] - X_[p0][k], v[k] = X_[q1][k] - X_[q0][k];
    n[0] = __int128(u[1]) * v[2] - __int128(u[2]) * v[1];
    n[1] = __int128(u[2]) * v[0] - __int128(u[0]) * v[2];
    n[2] = __int128(u[0]) * v[1] - __int128(u[1]) * v[0];
  }

  // n.(p − q) for n from normal(), exactly: hi 2^64 + lo (units 2^(3e); header: hi = S, lo =
  // L mod 2^64), |n.(p − q)| < 2^186 (so |hi| < 2^122).
  struct Wide {
    __int128 hi;
    std::uint64_t lo;
  };
  Wide dot(const __int128 (&n)[3], int p, int q) const {
    __int128 H = 0, L = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t w = X_[p][k] - X_[q][k];
      const std::int64_t h = std::int64_t(n[k] >> 64);  // floor(n_k / 2^64)
      const std::uint64_t l = std::uint64_t(n[k]);       // n_k mod 2^64
      H += __int128(h) * w;
      const unsigned __int128 m = static_cast<unsigned __int128>(l) * (w < 0 ? 0 - std::uint64_t(w) : std::uint64_t(w));
      L += w < 0 ? -__int128(m) : __int128(m);  // |l w| < 2^125
    }
    return Wide{H + (L >> 64), std::uint64_t(L)};
  }

  // The exact sign of n.(p − q) for n from normal() (header).
  int dot_sign(const __int128 (&n)[3], int p, int q) const {
    const Wide d = dot(n, p, q);
    if (d.hi != 0) return d.hi > 0 ? 1 : -1;
    return d.lo != 0 ? 1 : 0;
  }

  // e: a coordinate x is X 2^e (precondition: usable()).
  int unit_exponent() const { return e_; }

  // Vertex i's X (|X_k| < 2^60; precondition: usable()).
  const std::int64_t (&vertex(int i) const)[3] { return X_[i]; }

  // The exact sign of det[p1 − p0, q1 − q0, p − q].
  int height_sign(int p1, int p0, int q1, int q0, int p, int q) const {
    __int128 n[3];
    normal(p1, p0, q1, q0, n);
    return dot_sign(n, p, q);
  }

 private:
  // The largest unit that works, 2^e = 2^(h − 59) (h: the top bit of the largest |coordinate|),
  // for coordinates below 2^60 (so that 2^−e >= 1): every X = x 2^−e must be an integer (then
  // |X| < 2^60). A non-zero x gives |X| >= |x| > 0, so X is exact where it is a normal double
  // (below 1 it is no integer: subnormal X fail the int64 round trip as fractions do); the
  // round trip is exact for |X| < 2^60 and changes any X with a fraction (compared bit for bit).
  bool find_scale() {
    static_assert(sizeof(TetVertices) == 12 * sizeof(double), "TetVertices: 12 contiguous doubles");
    double c[24];
    std::memcpy(c, A_.data(), sizeof(TetVertices));
    std::memcpy(c + 12, B_.data(), sizeof(TetVertices));
    double top = 0.0;
    for (int i = 0; i < 24; ++i) {
      const double a = std::fabs(c[i]);
      top = a > top || a != a ? a : top;  // (a NaN stays)
    }
    if (!(top < 0x1p60)) return false;  // (inf and NaN too)
    double unit_inverse = 1.0;          // (every coordinate 0: any unit)
    e_ = 0;
    if (top > 0.0) {
      std::uint64_t b;
      std::memcpy(&b, &top, sizeof b);
      const int h = int(b >> 52 & 0x7ff) - 1023;  // 2^h <= top < 2^(h + 1) (top normal)
      if (59 - h > 1023) return false;            // (2^(59 − h) a normal double; top subnormal too)
      const std::uint64_t scale_bits = std::uint64_t(59 - h + 1023) << 52;
      e_ = h - 59;
      std::memcpy(&unit_inverse, &scale_bits, sizeof unit_inverse);
    }
    std::int64_t* out = &X_[0][0];
    std::uint64_t fraction = 0;  // the bits in which some X and its int64 round trip differ
    for (int i = 0; i < 24; ++i) {
      const double X = c[i] * unit_inverse + 0.0, R = double(out[i] = std::int64_t(X));  // (+0.0: −0 is +0)
      std::uint64_t x, r;
      std::memcpy(&x, &X, sizeof x);
      std::memcpy(&r, &R, sizeof r);
      fraction |= x ^ r;
    }
    return fraction == 0;
  }

  const TetVertices& A_;
  const TetVertices& B_;
  int state_ = -1;        // not computed yet
  int e_ = 0;             // the unit's exponent (usable())
  std::int64_t X_[8][3];  // the vertices in units 2^e (usable())
};

}  // namespace pdd::fast::detail
