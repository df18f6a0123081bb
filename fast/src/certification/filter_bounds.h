// filter_bounds.h — static error bounds that make floating-point signs exact (filter stage).
//
// Input:  the two tetrahedra A, B (raw doubles, definitions §1).
// Output: absolute bounds E2, E3, E4 such that, for every polynomial predicate P of degree
//         k = 2, 3, 4 that the fast engine evaluates (see list below), the computed value P~
//         satisfies |P~ − P| < E_k, where P is the exact value on the input doubles.
//         Hence |P~| > E_k  ==>  sign(P~) = sign(P).  Otherwise the caller falls back to the
//         exact GMP predicate (exact_predicates.h).
//
// Derivation (first-order forward error analysis, u = 2^-53 the unit roundoff).
// Let L = max over the three axes of (max coordinate − min coordinate) over the 8 vertices.
// Every difference of two input points then has |x − y| <= L per component, and its computed
// value carries an error <= u·L (one rounding). Products of errors are O(u²) and are covered by
// the slack factor (>= 2.9x) below.
//   deg 2 — cross product of two differences, one component a·b − c·d:
//           |value| <= 2L², error <= 4·L·uL (inputs) + 2·uL² (products) + 2u·L² (subtraction)
//           = 8uL².                                               E2 = 64 u L²     (8x slack)
//   deg 3 — triple product (cross of differences)·(difference), e.g. orient3d, EE g_k, heights:
//           |value| <= 6L³, error <= 3·(8uL²·L + 2L²·uL) + 3u·6L³ = 48uL³. The worst deg-3
//           quantity we sign is an EE depth D = max(0,g) − h_x − min(0,q) (or its mirror) with
//           three such terms and two roundings: 3·48 + u·(12 + 18)L³ = 174uL³.
//                                                                  E3 = 512 u L³    (2.9x slack)
//           The parallel-edge normal n = (e·e)w − (w·e)e is also degree 3 with |n_k| <= 6L³ and
//           error <= 48uL³ (e·e: 15uL²; each product term 21uL³; subtraction 6uL³).
//   deg 4 — heights along the parallel-edge normal n·(x − y): |value| <= 18L⁴, error <=
//           3·(48uL³·L + 6L³·uL) + 3u·18L⁴ = 216uL⁴; a depth D (difference of two) <= 468uL⁴.
//                                                                  E4 = 2048 u L⁴   (4.4x slack)
// Range guard: the analysis assumes no overflow and negligible underflow. For
// L in [2^-200, 2^200] every intermediate is <= 36·2^800 (no overflow) and every underflowed
// product contributes an absolute error <= 2^-1074, far below u·L^k >= 2^-453. Outside that range
// (or for L = 0 / non-finite) all bounds are +inf, i.e. every sign goes to the exact fallback.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "pdd/tet_pair.h"

namespace pdd::fast {

inline constexpr double kUnitRoundoff = 0x1p-53;
inline constexpr double kFilterCoeffDeg2 = 64.0;
inline constexpr double kFilterCoeffDeg3 = 512.0;
inline constexpr double kFilterCoeffDeg4 = 2048.0;
inline constexpr double kFilterMinExtent = 0x1p-200;
inline constexpr double kFilterMaxExtent = 0x1p+200;

struct FilterBounds {
  double deg2 = std::numeric_limits<double>::infinity();
  double deg3 = std::numeric_limits<double>::infinity();
  double deg4 = std::numeric_limits<double>::infinity();
};

// The bounds for extent L (see above).
inline FilterBounds filter_bounds_of_extent(double L) {
  FilterBounds fb;
  if (!(L >= kFilterMinExtent && L <= kFilterMaxExtent)) return fb;  // all +inf: exact path
  const double uL2 = kUnitRoundoff * L * L;
  fb.deg2 = kFilterCoeffDeg2 * uL2;
  fb.deg3 = kFilterCoeffDeg3 * uL2 * L;
  fb.deg4 = kFilterCoeffDeg4 * uL2 * L * L;
  return fb;
}

// L of the header: the largest per-axis extent of the 8 vertices.
inline double pair_extent(const TetVertices& A, const TetVertices& B) {
  double L = 0.0;
  for (int k = 0; k < 3; ++k) {
    double lo = A[0][k], hi = A[0][k];
    for (int i = 0; i < 4; ++i) {
      lo = std::min(lo, std::min(A[i][k], B[i][k]));
      hi = std::max(hi, std::max(A[i][k], B[i][k]));
    }
    L = std::max(L, hi - lo);
  }
  return L;
}

inline FilterBounds filter_bounds(const TetVertices& A, const TetVertices& B) {
  return filter_bounds_of_extent(pair_extent(A, B));
}

}  // namespace pdd::fast
