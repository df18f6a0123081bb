// exact_geometry.h — internal to fast/src: the fast engine's exact arithmetic on GMP rationals,
// and the definitions §3 direction rules written once on it for both exact users: the predicates
// that back the filters (exact_predicates.cpp) and the exact slow path (exact_path.cpp).
// Each input double is taken as the rational it denotes (mpq_class from a double is exact).
// Written on gmpxx rather than on reference/'s CGAL kernel on purpose: this engine must stay
// independent of reference/ so that the two can check each other.
#pragma once

#include <gmpxx.h>

#include <array>
#include <climits>

#include "exact/exact_predicates.h"
#include "kernel/direction_geometry.h"

namespace pdd::fast::detail {

using Q = mpq_class;

// log2 |x| within 1 (the bit lengths of numerator and denominator); LONG_MIN for 0.
inline long log2_estimate(const Q& x) {
  if (sgn(x) == 0) return LONG_MIN;
  return long(mpz_sizeinbase(x.get_num_mpz_t(), 2)) - long(mpz_sizeinbase(x.get_den_mpz_t(), 2));
}
// x * 2^e, exactly.
inline void scale_pow2(Q& x, long e) {
  if (e > 0) mpz_mul_2exp(x.get_num_mpz_t(), x.get_num_mpz_t(), e);
  else if (e < 0) mpz_mul_2exp(x.get_den_mpz_t(), x.get_den_mpz_t(), -e);
  x.canonicalize();
}

struct QV {
  Q x[3];
};
using QTet = std::array<QV, 4>;

inline QV operator-(const QV& a, const QV& b) {
  return {{a.x[0] - b.x[0], a.x[1] - b.x[1], a.x[2] - b.x[2]}};
}
inline QV scaled(const QV& a, const Q& s) { return {{a.x[0] * s, a.x[1] * s, a.x[2] * s}}; }
inline QV negated(const QV& a) { return {{-a.x[0], -a.x[1], -a.x[2]}}; }
inline Q dot(const QV& a, const QV& b) { return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2]; }
inline QV cross(const QV& a, const QV& b) {
  return {{a.x[1] * b.x[2] - a.x[2] * b.x[1], a.x[2] * b.x[0] - a.x[0] * b.x[2],
           a.x[0] * b.x[1] - a.x[1] * b.x[0]}};
}
inline bool is_zero(const QV& a) { return sgn(a.x[0]) == 0 && sgn(a.x[1]) == 0 && sgn(a.x[2]) == 0; }

inline QV exact_point(const Vec3d& p) { return {{Q(p[0]), Q(p[1]), Q(p[2])}}; }
inline QTet exact_tet(const TetVertices& T) {
  return {exact_point(T[0]), exact_point(T[1]), exact_point(T[2]), exact_point(T[3])};
}

// FV:i — the normal of A's face opposite s_i, pointing out of A (definitions §3 item 1).
inline QV face_normal_out_of(const QTet& A, int i) {
  const auto& f = kFace[i];
  QV n = cross(A[f[1]] - A[f[0]], A[f[2]] - A[f[0]]);
  return sgn(dot(n, A[i] - A[f[0]])) > 0 ? negated(n) : n;
}
// VF:j — the normal of B's face opposite r_j, pointing into B (definitions §3 item 2).
inline QV face_normal_into(const QTet& B, int j) { return negated(face_normal_out_of(B, j)); }

// EE:a:b — the unoriented normal of definitions §3 item 3: eB × eA, else (parallel edges)
// (e.e) w − (w.e) e with w = r_x − s_u; colinear edges: zero (no direction).
inline QV edge_pair_normal(const QTet& A, const QTet& B, int a, int b, EdgePairKind* kind) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const QV e = A[v] - A[u];
  QV n = cross(B[y] - B[x], e);
  *kind = EdgePairKind::Generic;
  if (!is_zero(n)) return n;
  const QV w = B[x] - A[u];
  n = scaled(w, dot(e, e)) - scaled(e, dot(w, e));
  *kind = is_zero(n) ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  return n;
}

// The orientation rule on g_k = n.(s_k − s_u) for A's two off-edge vertices: both <= 0 keep n,
// both >= 0 flip it (both 0: keep), mixed signs: undecidable (both sides are candidates).
inline EdgePairSide side_rule(const QTet& A, const QV& n, int a) {
  const int u = kEdges[a][0];
  const int g1 = sgn(dot(n, A[kOffEdge[a][0]] - A[u])), g2 = sgn(dot(n, A[kOffEdge[a][1]] - A[u]));
  if (g1 <= 0 && g2 <= 0) return EdgePairSide::Keep;
  if (g1 >= 0 && g2 >= 0) return EdgePairSide::Flip;
  return EdgePairSide::Undecidable;
}

}  // namespace pdd::fast::detail
