// anchor.h — internal to fast/src: the pair moved so that A's first vertex is the origin, when
// that translation is exact in doubles (pdd.h's anchored_pair, "Translation").
//
// Input:  a pair (A = s0..s3, B = r0..r3), any coordinates.
// Output: true, with A' = A − s0 and B' = B − s0 computed coordinate by coordinate, when every
//         one of those 24 differences is exact (no rounding, no overflow), every non-zero
//         |x'| is at least 2^-20 of the largest (kAnchoredRange) and s0 is not (+0, +0, +0)
//         bit for bit; false otherwise (then A', B' are unspecified).
// Why: every value, label, normal and decision of definitions §6 is invariant under a
// translation of both tetrahedra; the engine computes them on A', B' so that two pairs equal up
// to an exact translation (the element pairs of a structured mesh against a shifted copy, where
// the coordinates are dyadic) get the same bits, and a caller may reuse one pair's record for
// the other (mesh contacts). Positions are moved back by s0 (move_positions, pdd.h).
// Exactness: the rounding error of d = fl(x − a) is computed exactly by Knuth's TwoSum of x and
// −a (six additions, no multiplication, so no contraction into FMA changes it; valid for any
// finite x, a whose sum does not overflow). d is exact iff that error is 0. An overflow gives
// d = ±inf and a NaN error; a non-finite x or a gives a NaN or ±inf error: never 0, so such a
// pair is never anchored. The identity case (s0 = +0 bits) is left out so that anchoring an
// anchored pair does nothing (x − (+0) = x for every x, −0 included, but +0 + (−0) = +0 would
// not move −0 back): anchored(anchored(p)) is "no", and the engine's result on p is its result
// on the anchored pair, positions moved back, whichever way it is reached (move_positions, pdd.h,
// which returns a position equal to its moved rest vertex as the rest vertex itself: x' + s0
// is x in value, but a −0 would come back as +0).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

// The rounding error of d = fl(x − a) (Knuth's TwoSum of x and −a): 0 iff d = x − a. T: a
// double, or a vector of them (lane-wise).
template <class T>
T difference_error(T x, T a, T d) {
  const T bv = d - x;   // the part of d that came from −a
  const T av = d - bv;  // the part that came from x
  return (x - av) + (-a - bv);
}

// The least non-zero |x'| relative to the largest that anchoring may create. The expansions
// of the exact comparisons take a pair only when every non-zero coordinate of the rescaled
// pair (largest |x| in [1, 2)) lies in [2^-20, 2^20] (exact_predicates.h: parallel edge pairs;
// [2^-40, 2^40] otherwise), so that their products stay exact. Moving a pair whose vertices
// are a rounding apart in some coordinate (a grid whose coordinates carry rounding or a mesh
// generator's noise: x = 0.7000000000000001 against 0.7) would create a coordinate of 1e-16
// and send its ties to rationals; such a pair is computed as given, whose range is its own.
inline constexpr double kAnchoredRange = 0x1p-20;

inline bool anchored(const TetVertices& A, const TetVertices& B, TetVertices& As, TetVertices& Bs) {
  std::uint64_t bits[3];
  std::memcpy(bits, A[0].data(), sizeof bits);
  if ((bits[0] | bits[1] | bits[2]) == 0) return false;  // (+0, +0, +0): the identity
  // The 24 coordinates as 12 two-lane vectors (GCC/Clang vector extensions, SSE2 on x86-64, as
  // power_scale.h) against s0 repeated, no library call (a scalar loop with fmin and fmax took
  // ~700 instructions a pair on the decision stage of a grid). Both errors of a vector are ±0
  // iff no bit but the sign bits is set; a NaN or an infinity (a non-finite input, an
  // overflow) sets exponent bits. Coordinates of unrelated magnitudes (the pairs of the
  // paper's protocol) stop at the first inexact vector.
  typedef double V __attribute__((vector_size(16)));
  typedef long long I __attribute__((vector_size(16)));
  const double o[12] = {A[0][0], A[0][1], A[0][2], A[0][0], A[0][1], A[0][2],
                        A[0][0], A[0][1], A[0][2], A[0][0], A[0][1], A[0][2]};
  const double* in[2] = {A[0].data(), B[0].data()};
  double* out[2] = {As[0].data(), Bs[0].data()};
  const I magnitude = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};
  const V inf = {HUGE_VAL, HUGE_VAL};
  V hi = {0, 0}, lo = inf;  // the largest |x'| and the least non-zero one, per lane
  for (int t = 1; t >= 0; --t)  // B first: the vertices least likely to be near s0
    for (int i = 0; i < 12; i += 2) {
      V x, s;
      std::memcpy(&x, in[t] + i, sizeof x);
      std::memcpy(&s, o + i, sizeof s);
      const V d = x - s;
      std::memcpy(out[t] + i, &d, sizeof d);
      const I e = (I)difference_error(x, s, d);
      if ((std::uint64_t(e[0]) | std::uint64_t(e[1])) << 1) return false;  // (unrelated coordinates fail early)
      const I ub = (I)d & magnitude;
      const V u = (V)ub;
      hi = u > hi ? u : hi;
      const V nz = u == 0 ? inf : u;
      lo = nz < lo ? nz : lo;
    }
  return std::min(lo[0], lo[1]) >= kAnchoredRange * std::max(hi[0], hi[1]);
}

}  // namespace pdd::fast::detail
