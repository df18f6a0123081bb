// exact_predicates.cpp — GMP (mpq) evaluation of the definitions §3 decisions. See the header; the
// arithmetic and the rules are exact_geometry.h's.
#include "exact/exact_predicates.h"

#include "exact/exact_geometry.h"

namespace pdd::fast {

using namespace detail;

Sign orientation_sign_exact(const TetVertices& T) {
  const QTet q = exact_tet(T);
  return sign_of(sgn(dot(cross(q[1] - q[0], q[2] - q[0]), q[3] - q[0])));
}

EdgePairClass classify_edge_pair_exact(const TetVertices& A, const TetVertices& B, int a, int b) {
  const QTet qa = exact_tet(A), qb = exact_tet(B);
  EdgePairClass c;
  const QV n = edge_pair_normal(qa, qb, a, b, &c.kind);
  if (c.kind != EdgePairKind::Colinear) c.side = side_rule(qa, n, a);
  return c;
}

Sign depth_sign_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
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
