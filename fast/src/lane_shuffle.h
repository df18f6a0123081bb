// lane_shuffle.h — internal to fast/src: lane permutations of GCC vector-extension types, for
// both GCC and clang (superset_kernel.cpp).
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
// 8 doubles (64 bytes) as two 32-byte halves. Without AVX-512 GCC lowers a 64-byte
// __builtin_shuffle element by element through the stack (measured: most of the kernel's
// time on an AVX2 machine); on halves each output half is one two-source 4-lane permute
// (vpermpd/vblendpd/vperm2f128 on AVX2), which every clone compiles well. Same lanes moved.
typedef double pdd_v4d __attribute__((vector_size(32)));
typedef long long pdd_v4l __attribute__((vector_size(32)));
struct pdd_halves {
  pdd_v4d lo, hi;
};
template <class V>
static inline __attribute__((always_inline)) pdd_halves split_halves(V v) {
  pdd_halves h;
  __builtin_memcpy(&h.lo, &v, 32);
  __builtin_memcpy(&h.hi, reinterpret_cast<const char*>(&v) + 32, 32);
  return h;
}
template <class V>
static inline __attribute__((always_inline)) V join_halves(pdd_v4d lo, pdd_v4d hi) {
  V r;
  __builtin_memcpy(&r, &lo, 32);
  __builtin_memcpy(reinterpret_cast<char*>(&r) + 32, &hi, 32);
  return r;
}
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V v, M mask) {
  if constexpr (sizeof(V) == 64 && sizeof(v[0]) == 8) {
    const pdd_halves h = split_halves(v);
    const pdd_v4l m0 = {mask[0] & 7, mask[1] & 7, mask[2] & 7, mask[3] & 7};
    const pdd_v4l m1 = {mask[4] & 7, mask[5] & 7, mask[6] & 7, mask[7] & 7};
    return join_halves<V>(__builtin_shuffle(h.lo, h.hi, m0), __builtin_shuffle(h.lo, h.hi, m1));
  } else {
    return __builtin_shuffle(v, mask);
  }
}
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle(V a, V b, M mask) {
  if constexpr (sizeof(V) == 64 && sizeof(a[0]) == 8) {
    const pdd_halves ha = split_halves(a), hb = split_halves(b);
    pdd_v4d out[2];
    for (int half = 0; half < 2; ++half) {
      const pdd_v4l m = {mask[4 * half] & 15, mask[4 * half + 1] & 15, mask[4 * half + 2] & 15,
                         mask[4 * half + 3] & 15};
      const pdd_v4d from_a = __builtin_shuffle(ha.lo, ha.hi, m & 7);
      const pdd_v4d from_b = __builtin_shuffle(hb.lo, hb.hi, m & 7);
      out[half] = (m & 8) != 0 ? from_b : from_a;
    }
    return join_halves<V>(out[0], out[1]);
  } else {
    return __builtin_shuffle(a, b, mask);
  }
}
#endif

}  // namespace pdd::fast::detail
