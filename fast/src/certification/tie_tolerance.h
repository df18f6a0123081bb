// tie_tolerance.h — when two floating-point candidate values tie (labels of definitions §3/§5).
//
// Input:  a value v, the minimum vmin >= 0 of its family (rigid delta², or one PD_d variant)
//         and the pair's scale kappa = tie_kappa(R), R = the largest |coordinate| of the pair.
// Output: v ties with vmin  iff  v <= tie_threshold(vmin, kappa) = vmin + kappa·sqrt(vmin),
//         i.e. the relative gap (v − vmin)/vmin is at most kTieCoeff·u·R/sqrt(vmin).
//
// The exact engine breaks exact ties by canonical order. Here an exact tie arrives as two values
// computed along different operation sequences, so they differ by rounding. The band is derived
// from the error bound of the values, in the model of the harness (compare/pdd/compare/
// engine_comparison.h), counted for this engine:
//   every value v is a squared length whose root is a difference of heights h = n.x/|n| (a
//   depth, or for PD_d displacements linear in heights with coefficients <= 1). A height costs
//   <= ~10 roundings of quantities <= R (the differences x − y, the cross product giving n,
//   the dot product; filter_bounds.h counts them), so sqrt(v) carries an absolute error
//   <= 20 u R and v a relative error <= E·u·R/sqrt(v) with E = 40 (u = 2^-53).
// Constraints on the band c·u·R/sqrt(vmin) (relative), with K = 256 the harness's factor:
//   (1) exact ties are recognised: two exactly equal values are computed at most 2E u R/sqrt(v)
//       apart (relative), so c >= 2E = 80;
//   (2) every declared tie is a near tie the harness accepts: the exact values of a declared
//       tie differ by at most (c + 2E) u R/sqrt(vmin) relative, and the harness accepts a label
//       whose exact value is within K u R/sqrt(vmin) of the exact minimum, so c <= K − 2E = 176.
// kTieCoeff = 128, the power of two between, leaves a factor 1.6 on (1) and 1.4 on (2).
// For a well-conditioned pair (R/sqrt(v) ~ 20 on the paper's protocol) the band is ~3e-13
// relative: two values whose true gap is 1e-11 are not taken for a tie (a fixed 1e-9 would take
// them for one, and the harness could not accept the resulting label).
// The threshold grows with vmin, so a threshold computed from any upper bound of the final
// minimum is >= the final one (used by the pruned sweeps of deformable_depth.h).
#pragma once

#include <cmath>

#include "certification/filter_bounds.h"
#include "pdd/tet_pair.h"

namespace pdd::fast {

inline constexpr double kTieCoeff = 128.0;

// kappa = kTieCoeff u R, R = max |coordinate| over both tetrahedra.
inline double tie_kappa(const TetVertices& A, const TetVertices& B) {
  double r = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const double a = std::fabs(A[i][k]), b = std::fabs(B[i][k]);
      r = r > a ? r : a;
      r = r > b ? r : b;
    }
  return kTieCoeff * kUnitRoundoff * r;
}

inline double tie_threshold(double vmin, double kappa) { return vmin + kappa * std::sqrt(vmin); }

inline bool ties_with_min(double v, double vmin, double kappa) {
  return v <= tie_threshold(vmin, kappa);
}

// Minimum of v[0..n), n >= 1. Four independent accumulators break the latency chain of a single
// running min; min over non-NaN values is order-independent, so the result is the same.
inline double minimum(const double* v, int n) {
  const double v0 = v[0];
  double m[4] = {v0, v0, v0, v0};
  int i = 0;
  for (; i + 4 <= n; i += 4)
    for (int j = 0; j < 4; ++j) m[j] = v[i + j] < m[j] ? v[i + j] : m[j];
  for (; i < n; ++i) m[0] = v[i] < m[0] ? v[i] : m[0];
  const double a = m[0] < m[1] ? m[0] : m[1], b = m[2] < m[3] ? m[2] : m[3];
  return a < b ? a : b;
}

// First index i < n (canonical order) whose value ties with the minimum (n >= 1).
inline int first_tied_minimum(const double* v, int n, double kappa) {
  const double threshold = tie_threshold(minimum(v, n), kappa);
  for (int i = 0; i < n; ++i)
    if (v[i] <= threshold) return i;
  return -1;
}

}  // namespace pdd::fast
