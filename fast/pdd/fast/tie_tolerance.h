// tie_tolerance.h — when two floating-point candidate values count as a tie (SPEC §3/§5 labels).
//
// The exact engine breaks exact ties by canonical order. Here an exact tie arrives as two values
// computed along different operation sequences, so they may differ in the last bits. Values are
// squared lengths computed from heights whose relative error is O(100 u) ~ 1e-14 for inputs of
// moderate conditioning (filter_bounds.h). A relative tolerance of 1e-9 is 10^5 times that error,
// so exact ties are recognised, while two values that truly differ by less than 1e-9 relative are
// indistinguishable at any tolerance a harness can use to compare the engines' values; only the
// label could then differ from the exact engine's, and it attains the same value to 1e-9.
//
// Input: a value v and the minimum vmin >= 0 of its family. Output: whether v ties with vmin.
#pragma once

namespace pdd::fast {

inline constexpr double kTieRelTol = 1e-9;

inline bool ties_with_min(double v, double vmin) { return v <= vmin + kTieRelTol * vmin; }

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
inline int first_tied_minimum(const double* v, int n) {
  const double vmin = minimum(v, n);
  for (int i = 0; i < n; ++i)
    if (ties_with_min(v[i], vmin)) return i;
  return -1;
}

}  // namespace pdd::fast
