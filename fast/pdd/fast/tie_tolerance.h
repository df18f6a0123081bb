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

// First index i < n (canonical order) whose value ties with the minimum; −1 if none is finite.
inline int first_tied_minimum(const double* v, int n) {
  double vmin = v[0];
  for (int i = 1; i < n; ++i) vmin = v[i] < vmin ? v[i] : vmin;
  for (int i = 0; i < n; ++i)
    if (ties_with_min(v[i], vmin)) return i;
  return -1;
}

}  // namespace pdd::fast
