// direction_qp_impl.h — internal to fast/src: the closed-form per-direction QP of
// direction_qp.h (derivation and proof there) written once, for any ordered field T.
//
// Instantiated on double (the fast path, direction_qp.cpp) and on GMP rationals (mpq_class, the
// exact slow path, exact_path.cpp): the same operations in the same order, so the double path
// is this algorithm rounded, and the exact path is this algorithm without rounding. No infinity
// is used as a sentinel (rationals have none): "no breakpoint left" is a flag.
#pragma once

#include <type_traits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "qp/direction_qp.h"

namespace pdd::fast::detail {

// Doubles take selects and counts in T (no branch on the data: the sorting network's branches
// mispredicted; measured on the paper's rigid candidates, solve_deformable 55 -> 45 ns).
// Exact types (mpq_class) keep branches and int counts: a select evaluates both sides, and a
// rational count turns integer arithmetic into rational (the exact path is 10% slower with them).
template <class T>
inline constexpr bool kSelects = std::is_floating_point_v<T>;
template <class T>
using Count = std::conditional_t<kSelects<T>, T, int>;  // small integers: exact either way

#if defined(__SSE2__)
// The selects below as MINSD / MAXSD, which execute exactly them (MINSD x, y = x < y ? x : y;
// MAXSD x, y = x > y ? x : y, the second operand on ties and NaN; a compiler folding them on
// constants may not follow that rule, but the heights sorted here are never constants): GCC
// 12 compiles the ternaries to a branch and a swap each, about half of them mispredicted on
// random heights.
inline double select_less(double x, double y) { return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(x), _mm_set_sd(y))); }
inline double select_greater(double x, double y) { return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(x), _mm_set_sd(y))); }
#endif

template <class T>
inline void cswap_asc(T& a, T& b) {  // afterwards a <= b (unless NaN)
#if defined(__SSE2__)
  if constexpr (std::is_same_v<T, double>) {
    const double lo = select_less(b, a), hi = select_greater(a, b);  // (b < a ? b : a, b < a ? a : b)
    a = lo;
    b = hi;
    return;
  }
#endif
  if constexpr (kSelects<T>) {
    const bool swap = b < a;
    const T lo = swap ? b : a, hi = swap ? a : b;
    a = lo;
    b = hi;
  } else if (b < a) {
    T t = a;
    a = b;
    b = t;
  }
}
// Afterwards a >= b: cswap_asc with the arguments exchanged (its comparison is then a < b).
template <class T>
inline void cswap_desc(T& a, T& b) {
  cswap_asc(b, a);
}

// Sorting networks, n <= 4. The descending one is the ascending network on −v (the same
// comparisons, so the same permutation as negating, sorting and negating, without the
// negations).
template <class T, void (*Swap)(T&, T&)>
inline void sort_network(T* v, int n) {
  if (n == 2) {
    Swap(v[0], v[1]);
  } else if (n == 3) {
    Swap(v[0], v[1]);
    Swap(v[1], v[2]);
    Swap(v[0], v[1]);
  } else if (n == 4) {
    Swap(v[0], v[1]);
    Swap(v[2], v[3]);
    Swap(v[0], v[2]);
    Swap(v[1], v[3]);
    Swap(v[1], v[2]);
  }
}
template <class T>
inline void sort_small(T* v, int n) {
  sort_network<T, cswap_asc<T>>(v, n);
}
template <class T>
inline void sort_small_desc(T* v, int n) {
  sort_network<T, cswap_desc<T>>(v, n);
}

// Side<T>, Solution<T>, side_of and the displacements: direction_qp.h.

// A side at plane offset c with constrained (ncon at hcon) and the first k of f active.
// Returns sum_active (c − H)² + (sum_active (c − H))² / (5 − m), writes S = sum/(5 − m).
// (The sum form avoids cancellation in m c − P.)
template <class T>
inline T side_cost(int ncon, const T& hcon, const T* f, int k, const T& c, T* S) {
  const T dc = c - hcon;
  T s1 = ncon * dc, s2 = ncon * dc * dc;
  for (int i = 0; i < k; ++i) {
    const T d = c - f[i];
    s1 += d;
    s2 += d * d;
  }
  *S = s1 / (5 - ncon - k);
  return s2 + s1 * *S;
}

// The merged-breakpoint walk of direction_qp.h. A.hfree sorted descending, B.hfree ascending.
template <class T>
Solution<T> two_sided(const Side<T>& A, const Side<T>& B) {
  int kA = A.nfree, kB = 0;
  Count<T> mA = A.ncon + A.nfree, mB = B.ncon;  // (kSelects above)
  T PA = A.ncon * A.hcon, PB = B.ncon * B.hcon;
  for (int i = 0; i < A.nfree; ++i) PA += A.hfree[i];
  T X{};
  while (kA > 0 || kB < B.nfree) {
    const bool hasA = kA > 0, hasB = kB < B.nfree;
    T XA{}, XB{};
    if (hasA) XA = (5 - mA) * A.hfree[kA - 1] + PA;
    if (hasB) XB = (5 - mB) * B.hfree[kB] + PB;
    const bool takeA = hasA && (!hasB || XA <= XB);
    X = takeA ? XA : XB;
    if ((mA * X - 5 * PA) * (5 - mB) + (mB * X - 5 * PB) * (5 - mA) >= 0) break;
    if (takeA) {
      --kA;
      mA -= 1;
      PA -= A.hfree[kA];
    } else {
      PB += B.hfree[kB];
      ++kB;
      mB += 1;
    }
  }
  // A's sum over its active vertices, added afresh: the walk's running PA (every height of A
  // minus the inactive ones) carries rounding errors of the whole height range, this one only
  // of the active heights (value_bounds.h, tight case). Exact arithmetic: the same value.
  PA = A.ncon * A.hcon;
  for (int i = 0; i < kA; ++i) PA += A.hfree[i];
  Solution<T> s;
  const Count<T> den = mA * (5 - mB) + mB * (5 - mA);
  if (den == 0)
    s.c = X / 5;
  else
    s.c = (PA * (5 - mB) + PB * (5 - mA)) / den;
  s.cost = side_cost(A.ncon, A.hcon, A.hfree, kA, s.c, &s.sumA) +
           side_cost(B.ncon, B.hcon, B.hfree, kB, s.c, &s.sumB);
  return s;
}

// Root of S_B alone (B ascending): the minimiser of phi_B. `bounded` = false when S_B = 0 on a
// whole half-line (no constrained vertex): then phi_B = 0 for every c below the lowest vertex.
template <class T>
T root_of_side(const Side<T>& B, bool& bounded) {
  int kB = 0, mB = B.ncon;
  T PB = B.ncon * B.hcon;
  bounded = mB != 0;
  if (!bounded) return PB;
  while (kB < B.nfree) {
    const T X = (5 - mB) * B.hfree[kB] + PB;
    if (mB * X - 5 * PB >= 0) break;
    PB += B.hfree[kB];
    ++kB;
    ++mB;
  }
  return PB / mB;
}

// Case 2 (both deform): A sorted descending, B ascending.
template <class T>
Solution<T> solve_deformable_sorted(Side<T> A, Side<T> B) {
  sort_small_desc(A.hfree, A.nfree);
  sort_small(B.hfree, B.nfree);
  return two_sided(A, B);
}

// Case 1 (A static). Precondition (direction_qp.h): feasible.
template <class T>
Solution<T> solve_static_sides(const Side<T>& A, Side<T> B) {
  sort_small(B.hfree, B.nfree);
  Solution<T> s;
  if (A.ncon > 0) {
    s.c = A.hcon;
  } else {
    T amax = A.hfree[0];
    for (int i = 1; i < A.nfree; ++i)
      if (amax < A.hfree[i]) amax = A.hfree[i];
    bool bounded = false;
    const T root = root_of_side(B, bounded);
    s.c = (bounded && amax < root) ? root : amax;
  }
  int kB = 0;
  T PB = B.ncon * B.hcon;
  while (kB < B.nfree && (5 - B.ncon - kB) * B.hfree[kB] + PB <= 5 * s.c) PB += B.hfree[kB++];
  s.cost = side_cost(B.ncon, B.hcon, B.hfree, kB, s.c, &s.sumB);
  return s;
}

// Relaxed case 2: every vertex free.
template <class T>
Solution<T> solve_relaxed_heights(const T hA[4], const T hB[4]) {
  Side<T> a, b;
  a.nfree = b.nfree = 4;
  for (int i = 0; i < 4; ++i) {
    a.hfree[i] = hA[i];
    b.hfree[i] = hB[i];
  }
  return solve_deformable_sorted(a, b);
}

}  // namespace pdd::fast::detail
