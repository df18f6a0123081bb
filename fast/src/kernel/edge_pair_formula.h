// edge_pair_formula.h — internal to fast/src: the arithmetic of one edge pair (definitions §3),
// written once for every place that evaluates it — a scalar lane (double: direction_geometry.cpp's
// candidate lanes, superset_depth.cpp's chosen candidate) and the kernel's 8-wide vectors (v8:
// superset_kernel.cpp). The same expressions in the same order give bit-identical results in
// every instantiation (no FMA: -ffp-contract=off; no reassociation), which tests/fast check.
//
// Edge a = (u, v) of A, edge b = (x, y) of B, eA = s_v − s_u, eB = r_y − r_x:
//   n  = eB × eA                                           (unnormalised, unoriented)
//   h  = n.(r_x − s_u)                                     the height of B's edge over A's
//   g_m = n.(s_k − s_u) = eps(u,v,k) eB.NA_f               A's off-edge vertex k = kOffEdge[a][m],
//                                                           f = 6 − u − v − k (kOffA below)
//   q_m = n.(r_j − r_x) = −eps(x,y,j) eA.NB_f'             B's off-edge vertex j = kOffEdge[b][m]
//   D(+n) = max(0, g1, g2) − h − min(0, q1, q2)           depth along +n (definitions §4)
//   D(−n) = −min(0, g1, g2) + h + max(0, q1, q2)          depth along −n
//   n.n, and the value D²/(n.n).
// Error bounds of these quantities: filter_bounds.h (degrees 2 and 3 in the coordinates) and
// value_bounds.h.
#pragma once

#include "kernel/direction_geometry.h"

namespace pdd::fast::detail {

// The 8-wide vectors of the superset kernel: two 4-lane halves (GCC vector extensions, also in
// clang). A native 64-byte vector_size type is lowered by GCC without AVX-512 through the stack
// (its splats, selects, permutes and the joins of its halves: eight scalar stores and 16-byte
// reloads, store-forwarding stalls; measured: most of the kernel's time on an AVX2 machine),
// while every operation on a 32-byte half is one AVX instruction (two SSE2 ones in the default
// clone). Lane-wise operations on both halves: the same IEEE operations as on 8 lanes.
typedef double v4h __attribute__((vector_size(32)));
typedef long long v4hl __attribute__((vector_size(32)));

struct v8 {
  v4h lo, hi;  // lanes 0..3, 4..7
  v8() = default;  // (v8{} is all zero)
  constexpr v8(v4h l, v4h h) : lo(l), hi(h) {}
  constexpr v8(double a, double b, double c, double d, double e, double f, double g, double h)
      : lo{a, b, c, d}, hi{e, f, g, h} {}
  double operator[](int i) const {  // lane i (a copy of its bits)
    double x;
    __builtin_memcpy(&x, reinterpret_cast<const char*>(this) + 8 * i, sizeof x);
    return x;
  }
};
struct v8l {
  v4hl lo, hi;
  v8l() = default;
  constexpr v8l(v4hl l, v4hl h) : lo(l), hi(h) {}
  constexpr v8l(long long a, long long b, long long c, long long d, long long e, long long f,
                long long g, long long h)
      : lo{a, b, c, d}, hi{e, f, g, h} {}
};

#define PDD_FORMULA static inline __attribute__((always_inline))

PDD_FORMULA v8 operator+(v8 a, v8 b) { return {a.lo + b.lo, a.hi + b.hi}; }
PDD_FORMULA v8 operator-(v8 a, v8 b) { return {a.lo - b.lo, a.hi - b.hi}; }
PDD_FORMULA v8 operator*(v8 a, v8 b) { return {a.lo * b.lo, a.hi * b.hi}; }
PDD_FORMULA v8 operator/(v8 a, v8 b) { return {a.lo / b.lo, a.hi / b.hi}; }
PDD_FORMULA v8 operator-(v8 a) { return {-a.lo, -a.hi}; }
// A scalar operand is splat per half (one vbroadcastsd).
PDD_FORMULA v8 operator*(double s, v8 b) { return {s * b.lo, s * b.hi}; }
PDD_FORMULA v8 operator/(double s, v8 b) { return {s / b.lo, s / b.hi}; }
PDD_FORMULA v8 operator*(v8 a, double s) { return {a.lo * s, a.hi * s}; }
PDD_FORMULA v8 operator-(v8 a, double s) { return {a.lo - s, a.hi - s}; }
PDD_FORMULA v8l operator&(v8l a, v8l b) { return {a.lo & b.lo, a.hi & b.hi}; }
PDD_FORMULA v8l operator|(v8l a, v8l b) { return {a.lo | b.lo, a.hi | b.hi}; }
PDD_FORMULA v8l operator~(v8l a) { return {~a.lo, ~a.hi}; }
PDD_FORMULA v8l operator<<(v8l a, int k) { return {a.lo << k, a.hi << k}; }
PDD_FORMULA v8l& operator|=(v8l& a, v8l b) { return a = a | b; }

// max2 / min2 on vectors, lane-wise, with the scalar ones' semantics (direction_geometry.h).
PDD_FORMULA v8 max2(v8 a, v8 b) {
  return {a.lo > b.lo ? a.lo : b.lo, a.hi > b.hi ? a.hi : b.hi};
}
PDD_FORMULA v8 min2(v8 a, v8 b) {
  return {a.lo < b.lo ? a.lo : b.lo, a.hi < b.hi ? a.hi : b.hi};
}
// Lane-wise (a <= t) & bits, i.e. bits[i] where a[i] <= t, else 0.
PDD_FORMULA v8l le_bits(v8 a, double t, v8l bits) {
  return {(a.lo <= t) & bits.lo, (a.hi <= t) & bits.hi};
}

// For edge e and its m-th off-edge vertex k (kOffEdge[e][m]): eps(edge, k) and the face
// 6 − u − v − k. A's heights: g_m = eps · eB.NA_face; B's: q_m = −eps · eA.NB_face.
struct OffEdgeFaces {
  double eps[6][2];
  int face[6][2];
};
constexpr OffEdgeFaces make_off_edge_faces() {
  OffEdgeFaces t{};
  for (int e = 0; e < 6; ++e)
    for (int m = 0; m < 2; ++m) {
      const int u = kEdges[e][0], v = kEdges[e][1], k = kOffEdge[e][m];
      t.eps[e][m] = parity(u, v, k);
      t.face[e][m] = 6 - u - v - k;
    }
  return t;
}
inline constexpr OffEdgeFaces kOffFaces = make_off_edge_faces();
// The sign of q_m (B's off-edge vertices): −eps.
constexpr double off_sign_B(int b, int m) { return -kOffFaces.eps[b][m]; }

// n = eB × eA. S: a scalar of eA (one edge of A against a lane of B's edges), T: the lane type.
template <class T, class S>
PDD_FORMULA void edge_pair_normal(S ax, S ay, S az, T bx, T by, T bz, T& m0, T& m1, T& m2) {
  m0 = by * az - bz * ay;
  m1 = bz * ax - bx * az;
  m2 = bx * ay - by * ax;
}

// n.w (h for w = r_x − s_u).
template <class T>
PDD_FORMULA T edge_pair_dot(T m0, T m1, T m2, T wx, T wy, T wz) {
  return m0 * wx + m1 * wy + m2 * wz;
}

// n.n
template <class T>
PDD_FORMULA T edge_pair_nn(T m0, T m1, T m2) {
  return m0 * m0 + m1 * m1 + m2 * m2;
}

// D(+n) and D(−n) from A's off-edge heights g1, g2, the edge height h and B's q1, q2.
template <class T>
PDD_FORMULA void edge_pair_depths(T g1, T g2, T h, T q1, T q2, T& dp, T& dm) {
  const T zero{};
  dp = max2(zero, max2(g1, g2)) - h - min2(zero, min2(q1, q2));
  dm = -min2(zero, min2(g1, g2)) + h + max2(zero, max2(q1, q2));
}

}  // namespace pdd::fast::detail
