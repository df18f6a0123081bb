// exact_predicates.cpp — exact evaluation of the definitions §3 decisions: floating-point
// expansions (expansion.h) when the pair is in their exact range, GMP rationals (mpq) otherwise.
// Both evaluate the same polynomials with the same rules (exact_geometry.h's), so they agree with
// each other and with the exact engine by construction.
#include "exact/exact_predicates.h"

#include "exact/exact_geometry.h"
#include "exact/expansion.h"

namespace pdd::fast {

using namespace detail;

namespace {

// ---- Expansions: exact_geometry.h's constructions, term for term.

ExpVec face_normal_out_of_exp(const TetVertices& A, int i) {
  const auto& f = kFace[i];
  const ExpVec n = cross(difference(A[f[1]], A[f[0]]), difference(A[f[2]], A[f[0]]));
  return dot(n, difference(A[i], A[f[0]])).sign() > 0 ? negated(n) : n;
}

ExpVec edge_pair_normal_exp(const TetVertices& A, const TetVertices& B, int a, int b,
                            EdgePairKind* kind) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const ExpVec e = difference(A[v], A[u]);
  ExpVec n = cross(difference(B[y], B[x]), e);
  *kind = EdgePairKind::Generic;
  if (!n.is_zero()) return n;
  const ExpVec w = difference(B[x], A[u]);
  n = difference(scaled(w, dot(e, e)), scaled(e, dot(w, e)));
  *kind = n.is_zero() ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  return n;
}

EdgePairSide side_rule_exp(const TetVertices& A, const ExpVec& n, int a) {
  const int u = kEdges[a][0];
  const int g1 = dot(n, difference(A[kOffEdge[a][0]], A[u])).sign();
  const int g2 = dot(n, difference(A[kOffEdge[a][1]], A[u])).sign();
  if (g1 <= 0 && g2 <= 0) return EdgePairSide::Keep;
  if (g1 >= 0 && g2 >= 0) return EdgePairSide::Flip;
  return EdgePairSide::Undecidable;
}

// sign(max_i n.s_i − min_j n.r_j) = the largest sign of n.(s_i − r_j) over the 16 pairs.
Sign depth_sign_exp(const TetVertices& A, const TetVertices& B, const ExpVec& n) {
  int best = -1;
  for (int i = 0; i < 4 && best < 1; ++i)
    for (int j = 0; j < 4 && best < 1; ++j) {
      const int s = dot(n, difference(A[i], B[j])).sign();
      best = s > best ? s : best;
    }
  return sign_of(best);
}

ExpVec oriented_normal_exp(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  if (label.kind == ContactKind::FV) return face_normal_out_of_exp(A, label.a);
  if (label.kind == ContactKind::VF) return negated(face_normal_out_of_exp(B, label.a));
  EdgePairKind kind;
  const ExpVec n = edge_pair_normal_exp(A, B, label.a, label.b, &kind);
  const EdgePairSide side = side_rule_exp(A, n, label.a);
  const bool flip = side == EdgePairSide::Flip ||
                    (side == EdgePairSide::Undecidable && label.orientation == EdgeOrientation::Minus);
  return flip ? negated(n) : n;
}

}  // namespace

Sign orientation_sign_exact(const TetVertices& T) {
  if (in_exact_range(T, T)) {
    const ExpVec n = cross(difference(T[1], T[0]), difference(T[2], T[0]));
    return sign_of(dot(n, difference(T[3], T[0])).sign());
  }
  const QTet q = exact_tet(T);
  return sign_of(sgn(dot(cross(q[1] - q[0], q[2] - q[0]), q[3] - q[0])));
}

EdgePairClass classify_edge_pair_exact(const TetVertices& A, const TetVertices& B, int a, int b) {
  EdgePairClass c;
  if (in_exact_range(A, B)) {
    const ExpVec n = edge_pair_normal_exp(A, B, a, b, &c.kind);
    if (c.kind != EdgePairKind::Colinear) c.side = side_rule_exp(A, n, a);
    return c;
  }
  const QTet qa = exact_tet(A), qb = exact_tet(B);
  const QV n = edge_pair_normal(qa, qb, a, b, &c.kind);
  if (c.kind != EdgePairKind::Colinear) c.side = side_rule(qa, n, a);
  return c;
}

Sign depth_sign_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  if (in_exact_range(A, B)) return depth_sign_exp(A, B, oriented_normal_exp(A, B, label));
  const QTet qa = exact_tet(A), qb = exact_tet(B);
  QV n;
  if (label.kind == ContactKind::FV) {
    n = face_normal_out_of(qa, label.a);
  } else if (label.kind == ContactKind::VF) {
    n = face_normal_into(qb, label.a);
  } else {
    EdgePairKind kind;
    n = edge_pair_normal(qa, qb, label.a, label.b, &kind);
    const EdgePairSide side = side_rule(qa, n, label.a);
    const bool flip = side == EdgePairSide::Flip ||
                      (side == EdgePairSide::Undecidable && label.orientation == EdgeOrientation::Minus);
    if (flip) n = negated(n);
  }
  Q hi = dot(n, qa[0]), lo = dot(n, qb[0]);
  for (int i = 1; i < 4; ++i) {
    Q ha = dot(n, qa[i]), hb = dot(n, qb[i]);
    if (ha > hi) hi = ha;
    if (hb < lo) lo = hb;
  }
  return sign_of(sgn(Q(hi - lo)));
}

}  // namespace pdd::fast
