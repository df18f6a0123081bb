// clang_compat.h — force-included (-include) into pdd_fast in clang fuzzer builds only
// (fuzz/CMakeLists.txt), so that libFuzzer's clang-only coverage instrumentation reaches the
// fast engine.
//
// Why: fast/src/superset_kernel.cpp uses GCC's `__builtin_shuffle` (lines 47, 119-120 at the
// time of writing), which clang does not have (clang's __builtin_shufflevector needs constant
// indices). This defines it, for GCC vector-extension types, with GCC's documented semantics:
//   __builtin_shuffle(v, mask)     r[i] = v[mask[i] mod N]
//   __builtin_shuffle(a, b, mask)  r[i] = (a ++ b)[mask[i] mod 2N]
// Lane moves only, no arithmetic: every floating-point result is unchanged. Once fast/ builds
// with clang on its own, the macro is simply unused. It never applies to GCC builds.
#pragma once
#if defined(__clang__) && defined(__cplusplus)

namespace pdd_clang_compat {
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle1(V v, M mask) {
  constexpr int n = sizeof(V) / sizeof(v[0]);
  V r;
  for (int i = 0; i < n; ++i) r[i] = v[static_cast<int>(mask[i] & (n - 1))];
  return r;
}
template <class V, class M>
static inline __attribute__((always_inline)) V shuffle2(V a, V b, M mask) {
  constexpr int n = sizeof(V) / sizeof(a[0]);
  V r;
  for (int i = 0; i < n; ++i) {
    const int k = static_cast<int>(mask[i] & (2 * n - 1));
    r[i] = k < n ? a[k] : b[k - n];
  }
  return r;
}
}  // namespace pdd_clang_compat

#define PDD_CLANG_COMPAT_PICK(_1, _2, _3, NAME, ...) NAME
#define __builtin_shuffle(...)                                                             \
  PDD_CLANG_COMPAT_PICK(__VA_ARGS__, ::pdd_clang_compat::shuffle2,                         \
                        ::pdd_clang_compat::shuffle1, unused)(__VA_ARGS__)

#endif
