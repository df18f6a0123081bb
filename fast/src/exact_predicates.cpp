// exact_predicates.cpp — GMP (mpq) evaluation of the SPEC §3 decisions. See the header.
#include "exact_predicates.h"

#include <gmpxx.h>

#include <array>

namespace pdd::fast {
namespace {

using Q = mpq_class;
struct QV {
  Q x, y, z;
};

QV qv(const Vec3d& p) { return {Q(p[0]), Q(p[1]), Q(p[2])}; }  // mpq_set_d: exact
QV sub(const QV& a, const QV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QV scale(const Q& s, const QV& a) { return {s * a.x, s * a.y, s * a.z}; }
Q dot(const QV& a, const QV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QV cross(const QV& a, const QV& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool is_zero(const QV& a) { return sgn(a.x) == 0 && sgn(a.y) == 0 && sgn(a.z) == 0; }

std::array<QV, 4> qtet(const TetVertices& T) {
  return {qv(T[0]), qv(T[1]), qv(T[2]), qv(T[3])};
}

QV raw_face_normal(const std::array<QV, 4>& T, int f) {
  const auto& v = kFace[f];
  return cross(sub(T[v[1]], T[v[0]]), sub(T[v[2]], T[v[0]]));
}

// The unoriented EE normal of SPEC §3 item 3 (cross product, else the parallel formula).
QV edge_pair_normal(const std::array<QV, 4>& A, const std::array<QV, 4>& B, int a, int b,
                    EdgePairKind* kind) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  QV e = sub(A[v], A[u]);
  QV n = cross(sub(B[y], B[x]), e);
  *kind = EdgePairKind::Generic;
  if (!is_zero(n)) return n;
  QV w = sub(B[x], A[u]);
  n = sub(scale(dot(e, e), w), scale(dot(w, e), e));
  *kind = is_zero(n) ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  return n;
}

EdgePairSide side_rule(const std::array<QV, 4>& A, const QV& n, int a) {
  const int u = kEdges[a][0], v = kEdges[a][1];
  int lo = 0, hi = 0;  // counts of g_k < 0 and g_k > 0
  for (int k = 0; k < 4; ++k) {
    if (k == u || k == v) continue;
    int s = sgn(dot(n, sub(A[k], A[u])));
    lo += s < 0;
    hi += s > 0;
  }
  if (hi == 0) return EdgePairSide::Keep;    // both <= 0
  if (lo == 0) return EdgePairSide::Flip;    // both >= 0
  return EdgePairSide::Undecidable;
}

}  // namespace

Sign orientation_sign_exact(const TetVertices& T) {
  auto q = qtet(T);
  return sign_of(sgn(dot(cross(sub(q[1], q[0]), sub(q[2], q[0])), sub(q[3], q[0]))));
}

EdgePairClass classify_edge_pair_exact(const TetVertices& A, const TetVertices& B, int a, int b) {
  auto qa = qtet(A), qb = qtet(B);
  EdgePairClass c;
  QV n = edge_pair_normal(qa, qb, a, b, &c.kind);
  if (c.kind != EdgePairKind::Colinear) c.side = side_rule(qa, n, a);
  return c;
}

Sign depth_sign_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  auto qa = qtet(A), qb = qtet(B);
  QV n;
  if (label.kind == ContactKind::FV) {
    n = raw_face_normal(qa, label.a);
    if (sgn(dot(n, sub(qa[label.a], qa[kFace[label.a][0]]))) > 0) n = scale(Q(-1), n);
  } else if (label.kind == ContactKind::VF) {
    n = raw_face_normal(qb, label.a);
    if (sgn(dot(n, sub(qb[label.a], qb[kFace[label.a][0]]))) < 0) n = scale(Q(-1), n);
  } else {
    EdgePairKind kind;
    n = edge_pair_normal(qa, qb, label.a, label.b, &kind);
    EdgePairSide side = side_rule(qa, n, label.a);
    bool flip = side == EdgePairSide::Flip ||
                (side == EdgePairSide::Undecidable && label.orientation == EdgeOrientation::Minus);
    if (flip) n = scale(Q(-1), n);
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
