// lane_shuffle.h — internal to fast/src: lane permutations of GCC vector-extension types (the
// kernel's 4-lane halves, edge_pair_formula.h), for both GCC and clang (superset_kernel.cpp).
//
//   shuffle(v, mask)     r[i] = v[mask[i] mod N]
//   shuffle(a, b, mask)  r[i] = (a ++ b)[mask[i] mod 2N]
// GCC: its __builtin_shuffle, which compiles constant masks to single permute instructions.
// clang has no __builtin_shuffle (its __builtin_shufflevector needs literal indices), so there
// the same semantics are written as a loop over lanes; every mask in the kernel is a constant
// after inlining, which clang folds to the same kind of permutes. Lane moves only: every
// floating-point result is identical on both compilers.
// Written by hand because the two compilers' builtins differ and the kernel needs both forms.
#pragma once

namespace pdd::fast::detail {

#if defined(__clang__)
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V v, M mask) {
  constexpr int n = sizeof(V) / sizeof(v[0]);
  V r;
  for (int i = 0; i < n; ++i) r[i] = v[static_cast<int>(mask[i] & (n - 1))];
  return r;
}
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V a, V b, M mask) {
  constexpr int n = sizeof(V) / sizeof(a[0]);
  V r;
  for (int i = 0; i < n; ++i) {
    const int k = static_cast<int>(mask[i] & (2 * n - 1));
    r[i] = k < n ? a[k] : b[k - n];
  }
  return r;
}
#else
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V v, M mask) {
  return __builtin_shuffle(v, mask);
}
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V a, V b, M mask) {
  return __builtin_shuffle(a, b, mask);
}
#endif

}  // namespace pdd::fast::detail
