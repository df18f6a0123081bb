// exact_predicates.cpp — exact evaluation of the definitions §3 decisions: floating-point
// expansions (expansion.h) when the pair is in their exact range, GMP rationals (mpq) otherwise.
// Both evaluate the same polynomials with the same rules (exact_geometry.h's), so they agree with
// each other and with the exact engine by construction.
#include "exact/exact_predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "exact/exact_geometry.h"
#include "exact/expansion.h"
#include "exact/integer_depth.h"
#include "kernel/pair_memo.h"

namespace pdd::fast {

using namespace detail;

namespace {

// ---- Expansions: exact_geometry.h's constructions, term for term.

// ok: cleared when an expansion exceeded its capacity (expansion.h); nothing is then decided.
ExpVec face_normal_out_of_exp(const TetVertices& A, int i, bool& ok) {
  const auto& f = kFace[i];
  const ExpVec n = cross(difference(A[f[1]], A[f[0]]), difference(A[f[2]], A[f[0]]));
  const Expansion h = dot(n, difference(A[i], A[f[0]]));
  ok = ok && h.ok;
  return h.sign() > 0 ? negated(n) : n;
}

ExpVec edge_pair_normal_exp(const TetVertices& A, const TetVertices& B, int a, int b,
                            EdgePairKind* kind, bool& ok) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const ExpVec e = difference(A[v], A[u]);
  ExpVec n = cross(difference(B[y], B[x]), e);
  ok = ok && n.ok();
  *kind = EdgePairKind::Generic;
  if (!n.is_zero()) return n;
  const ExpVec w = difference(B[x], A[u]);
  n = difference(scaled(w, dot(e, e)), scaled(e, dot(w, e)));
  ok = ok && n.ok();
  *kind = n.is_zero() ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  return n;
}

EdgePairSide side_rule_exp(const TetVertices& A, const ExpVec& n, int a, bool& ok) {
  const int u = kEdges[a][0];
  const Expansion h1 = dot(n, difference(A[kOffEdge[a][0]], A[u]));
  const Expansion h2 = dot(n, difference(A[kOffEdge[a][1]], A[u]));
  ok = ok && h1.ok && h2.ok;
  const int g1 = h1.sign(), g2 = h2.sign();
  if (g1 <= 0 && g2 <= 0) return EdgePairSide::Keep;
  if (g1 >= 0 && g2 >= 0) return EdgePairSide::Flip;
  return EdgePairSide::Undecidable;
}

// sign(max_i n.s_i − min_j n.r_j) = the largest sign of n.(s_i − r_j) over the 16 pairs.
Sign depth_sign_exp(const TetVertices& A, const TetVertices& B, const ExpVec& n, bool& ok) {
  int best = -1;
  for (int i = 0; i < 4 && best < 1; ++i)
    for (int j = 0; j < 4 && best < 1; ++j) {
      const Expansion h = dot(n, difference(A[i], B[j]));
      ok = ok && h.ok;
      const int s = h.sign();
      best = s > best ? s : best;
    }
  return sign_of(best);
}

// `kind` (optional): an edge pair's kind (a colinear pair's n is 0).
ExpVec oriented_normal_exp(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                           bool& ok, EdgePairKind* kind = nullptr, EdgePairSide* rule = nullptr) {
  if (label.kind == ContactKind::FV) return face_normal_out_of_exp(A, label.a, ok);
  if (label.kind == ContactKind::VF) return negated(face_normal_out_of_exp(B, label.a, ok));
  EdgePairKind own;
  if (!kind) kind = &own;
  const ExpVec n = edge_pair_normal_exp(A, B, label.a, label.b, kind, ok);
  const EdgePairSide side = side_rule_exp(A, n, label.a, ok);
  if (rule) *rule = side;
  const bool flip = side == EdgePairSide::Flip ||
                    (side == EdgePairSide::Undecidable && label.orientation == EdgeOrientation::Minus);
  return flip ? negated(n) : n;
}

}  // namespace

bool oriented_normal_expansion(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               ExpVec& n) {
  if (!in_exact_range(A, B)) return false;
  bool ok = true;
  EdgePairKind kind = EdgePairKind::Generic;
  n = oriented_normal_exp(A, B, label, ok, &kind);
  return ok && n.ok() && kind != EdgePairKind::Colinear;
}

Sign orientation_sign_exact(const TetVertices& T) {
  if (in_exact_range(T, T)) {
    const ExpVec n = cross(difference(T[1], T[0]), difference(T[2], T[0]));
    const Expansion d = dot(n, difference(T[3], T[0]));
    if (d.ok) return sign_of(d.sign());
  }
  const QTet q = exact_tet(T);
  return sign_of(sgn(dot(cross(q[1] - q[0], q[2] - q[0]), q[3] - q[0])));
}

EdgePairClass classify_edge_pair_exact(const TetVertices& A, const TetVertices& B, int a, int b) {
  if (IntegerFrame frame(A, B); frame.usable()) return classify_edge_pair_framed(frame, a, b);
  EdgePairClass c;
  if (in_exact_range(A, B)) {
    bool ok = true;
    const ExpVec n = edge_pair_normal_exp(A, B, a, b, &c.kind, ok);
    if (ok && c.kind != EdgePairKind::Colinear) c.side = side_rule_exp(A, n, a, ok);
    if (ok) return c;
    c = EdgePairClass{};
  }
  const QTet qa = exact_tet(A), qb = exact_tet(B);
  const QV n = edge_pair_normal(qa, qb, a, b, &c.kind);
  if (c.kind != EdgePairKind::Colinear) c.side = side_rule(qa, n, a);
  return c;
}

Sign depth_sign_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  if (in_exact_range(A, B)) {
    bool ok = true;
    const ExpVec n = oriented_normal_exp(A, B, label, ok);
    const Sign s = ok ? depth_sign_exp(A, B, n, ok) : Sign::Zero;
    if (ok) return s;
  }
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

ExactDirection::ExactDirection(const TetVertices& A, const TetVertices& B, const DirectionLabel& l)
    : A_(A), B_(B), l1_(l) {}

namespace {
thread_local PairMemo<std::optional<bool>, 32> same_memo;  // ExactDirection's (header)
}  // namespace

std::optional<bool> ExactDirection::same(const DirectionLabel& l, bool rule, int side) const {
  std::optional<bool> value;  // (the answer does not depend on `side`: one memo entry)
  same_memo.get(A_, B_, label_key(l1_) | label_key(l) << 10 | unsigned(rule) << 20, value,
                [&](std::optional<bool>& v) {
                  v = computed(l, rule, side);
                  return true;
                });
  return value;
}

// A vector that the exact normal n2 of label l is orthogonal to, whatever its kind: an edge of
// the face (FV, VF), or either edge of the pair (EE: n2 = eB × eA is orthogonal to both; a
// parallel pair's (e.e) w − (w.e) e is orthogonal to e, parallel to both edges; a colinear
// pair's is 0). Two of them (k = 0, 1) span n2's orthogonal plane when n2 != 0 (a face's edges;
// a generic pair's edges).
static ExpVec orthogonal_to_normal(const TetVertices& A, const TetVertices& B, const DirectionLabel& l, int k) {
  if (l.kind == ContactKind::FV || l.kind == ContactKind::VF) {
    const TetVertices& T = l.kind == ContactKind::FV ? A : B;
    const auto& f = kFace[l.a];
    return difference(T[f[1 + k]], T[f[0]]);
  }
  return k == 0 ? difference(A[kEdges[l.a][1]], A[kEdges[l.a][0]]) : difference(B[kEdges[l.b][1]], B[kEdges[l.b][0]]);
}

// computed()'s first test over the pair's integer frame: false when n1 is not orthogonal to
// one of the two vectors of orthogonal_to_normal (then n1 and n2 differ in direction), true
// when it is orthogonal to both; nullopt where the frame does not apply (no frame, or n1 of
// degree 3: a parallel edge pair). The same two signs as the expansions' dots, exactly
// (integer_heights.h: n1 a cross product of frame differences, each sign n1.(X_p − X_q)).
std::optional<bool> ExactDirection::orthogonal_over_integers(const DirectionLabel& l) const {
  if (integer_state_ == 0) {
    integer_state_ = -1;
    if (!frame_.usable()) return std::nullopt;
    if (l1_.kind == ContactKind::EE) {
      const int u = kEdges[l1_.a][0], v = kEdges[l1_.a][1], x = kEdges[l1_.b][0], y = kEdges[l1_.b][1];
      frame_.normal(4 + y, 4 + x, v, u, ni_);  // eB x eA
    } else {
      const int o = l1_.kind == ContactKind::FV ? 0 : 4;
      const auto& f = kFace[l1_.a];
      frame_.normal(o + f[1], o + f[0], o + f[2], o + f[0], ni_);
    }
    if (ni_[0] == 0 && ni_[1] == 0 && ni_[2] == 0) return std::nullopt;  // parallel edges
    integer_state_ = 1;
  }
  if (integer_state_ < 0) return std::nullopt;
  for (int k = 0; k < 2; ++k) {
    int p, q;  // orthogonal_to_normal(l, k) as frame indices: X_p − X_q
    if (l.kind == ContactKind::EE) {
      const int o = k == 0 ? 0 : 4, e = k == 0 ? l.a : l.b;
      p = o + kEdges[e][1], q = o + kEdges[e][0];
    } else {
      const int o = l.kind == ContactKind::FV ? 0 : 4;
      p = o + kFace[l.a][1 + k], q = o + kFace[l.a][0];
    }
    if (frame_.dot_sign(ni_, p, q) != 0) return false;
  }
  return true;
}

std::optional<bool> ExactDirection::same_as(const DirectionLabel& l) const { return same(l, true); }

std::optional<bool> ExactDirection::same_as(const DirectionLabel& l, int side) const { return same(l, true, side); }

std::optional<bool> ExactDirection::same_as_labelled(const DirectionLabel& l) const { return same(l, false); }

// n2: the label's exact oriented candidate (rule), or for an edge pair ±(eB × eA) as labelled.
std::optional<bool> ExactDirection::computed(const DirectionLabel& l, bool rule, int side) const {
  if (in_range_ < 0) {
    // Granularity: coordinates multiples of 2^-152, products of 6 differences of 2^-912
    // (normal); magnitudes below (2^101)^6 · 2^40 (no overflow). See expansion.h.
    in_range_ = 1;
    for (const TetVertices* T : {&A_, &B_})
      for (const Vec3d& p : *T)
        for (double x : p) {
          const double a = std::fabs(x);
          if (a != 0.0 && !(a >= 0x1p-100 && a <= 0x1p100)) in_range_ = 0;
        }
  }
  if (in_range_ == 0) return std::nullopt;
  // The first test below (n1 orthogonal to n2's two vectors) over integers where it can be
  const std::optional<bool> orthogonal = orthogonal_over_integers(l);
  if (orthogonal == false) return false;
  if (state_ == 0) {
    state_ = -1;
    // l1's normal up to its sign (the orthogonality tests below need no orientation): a
    // face's e1 x e2, an edge pair's eB x eA (the common perpendicular when parallel)
    bool ok = true;
    if (l1_.kind == ContactKind::FV || l1_.kind == ContactKind::VF) {
      const TetVertices& T = l1_.kind == ContactKind::FV ? A_ : B_;
      const auto& f = kFace[l1_.a];
      n_ = cross(difference(T[f[1]], T[f[0]]), difference(T[f[2]], T[f[0]]));
    } else {
      EdgePairKind kind;
      n_ = edge_pair_normal_exp(A_, B_, l1_.a, l1_.b, &kind, ok);
    }
    state_ = ok && n_.ok() ? 1 : -1;
  }
  if (state_ < 0) return std::nullopt;
  // Not the same direction when n1 is not orthogonal to a vector n2 is orthogonal to (n2 = 0
  // included: no direction): two degree-3 dots instead of n2 and n1 × n2 (degree 4); directions
  // a rounding apart (aligned pairs) mostly end here.
  for (int k = 0; k < 2 && !orthogonal; ++k) {
    const Expansion d = dot(n_, orthogonal_to_normal(A_, B_, l, k));
    if (!d.ok) return std::nullopt;
    if (d.n != 0) return false;
  }
  // (the caller's sign of n1.n2, for an l2 whose two vectors span n2's orthogonal plane)
  if (side != 0) return side > 0;
  // the sign: l1's oriented normal from here on (built at its first use)
  if (!oriented_) {
    bool ok = true;
    n_ = oriented_normal_exp(A_, B_, l1_, ok);
    if (!ok || !n_.ok()) return state_ = -1, std::nullopt;
    oriented_ = true;
  }
  bool ok = true;
  ExpVec n2;
  EdgePairKind kind = EdgePairKind::Generic;
  if (rule || l.kind != ContactKind::EE) {
    n2 = oriented_normal_exp(A_, B_, l, ok, &kind);
  } else {
    n2 = edge_pair_normal_exp(A_, B_, l.a, l.b, &kind, ok);
    if (l.orientation == EdgeOrientation::Minus) n2 = negated(n2);
  }
  if (!ok || !n2.ok()) return std::nullopt;
  // Where the two vectors above span n2's orthogonal plane (a face's edges; the edges of a
  // generic pair, n2 = ±eB × eA != 0), n1, orthogonal to both, is a multiple of n2: only the
  // sign of n1.n2 is left. Parallel edges (both vectors along e) need n1 × n2 = 0 too.
  if (kind != EdgePairKind::Generic) {
    const ExpVec c = cross(n_, n2);
    if (!c.ok()) return std::nullopt;
    if (!c.is_zero()) return false;
  }
  const Expansion d = dot(n_, n2);
  if (!d.ok) return std::nullopt;
  return d.sign() > 0;
}

std::optional<bool> same_direction_exact(const TetVertices& A, const TetVertices& B,
                                         const DirectionLabel& l1, const DirectionLabel& l2) {
  return ExactDirection(A, B, l1).same_as(l2);
}

// Range (expansion.h's argument with degree 10): a non-zero |coordinate| >= 2^-40 is a multiple
// of its last bit >= 2^-92, so is every difference; n has degree 2 in differences (faces and
// generic edge pairs), heights and D degree 3, n.n degree 4, D² n.n degree 10: every term is a
// multiple of 2^-920 (a double, nothing lost to underflow). Magnitudes: differences < 2^41, so
// |D² n.n| < (3 · 2^125)² · 3 · 2^166 < 2^430, far below overflow with the splitter's 2^27.
// A parallel edge pair (n = (e.e) w − (w.e) e: degree 3, D 4, n.n 6, D² n.n 14) only with every
// non-zero |coordinate| in [2^-20, 2^20]: multiples of 2^-72, so every term of degree <= 14 is a
// multiple of 2^-1008 (normal); differences < 2^21, D < 36 · 2^84, n.n < 108 · 2^126, so
// |D² n.n| < 2^312 (2^339 with the splitter's 2^27).
namespace {
bool every_coordinate_within(const TetVertices& A, const TetVertices& B, double lo, double hi) {
  for (const TetVertices* T : {&A, &B})
    for (const Vec3d& p : *T)
      for (double x : p) {
        const double a = std::fabs(x);
        if (a != 0.0 && !(a >= lo && a <= hi)) return false;
      }
  return true;
}
}  // namespace

bool normal_for_degree_ten(const TetVertices& A, const TetVertices& B, const DirectionLabel& label, ExpVec& n,
                           EdgePairSide* rule) {
  if (!every_coordinate_within(A, B, 0x1p-40, 0x1p40)) return false;
  bool ok = true;
  EdgePairKind kind = EdgePairKind::Generic;  // (faces: stays Generic)
  n = oriented_normal_exp(A, B, label, ok, &kind, rule);
  if (!ok || !n.ok() || kind == EdgePairKind::Colinear) return false;
  return kind != EdgePairKind::Parallel || every_coordinate_within(A, B, 0x1p-20, 0x1p20);
}

namespace {
// Vertices of T whose height h = s n.(p − o) (s = +1: A's vertices, for the largest; s = −1:
// B's, for the least) may be the largest exactly; bit i: vertex i kept. From the double value
// of n (approx_of: each component within e_k of n_k) and the coordinate differences rounded
// (within u of themselves): |h − h~| <= sum_k |d~_k| (e_k (1 + u) + (u + gamma_3) |n~_k|) (the
// products' and two sums' roundings, gamma_3 <= 3.0001 u), taken as e = sum_k |d~_k| (e_k +
// 5u |n~_k|) (1 + 2^-40) (the bound's own roundings, a few u relative) + 2^-1000 (terms that
// underflow). Vertex i is dropped when another one j is certainly higher: fl(h~_j − h~_i)
// (1 − 2^-50) > fl(e_i + e_j) (1 + 2^-50), each side's two roundings (<= u each) inside the
// 2^-50, so h_j >= h~_j − e_j > h~_i + e_i >= h_i. Grids tie several heights exactly: those
// stay, and the expansions order them. (NaN: kept.)
unsigned extreme_candidates(const ExpVec& n, const TetVertices& T, const Vec3d& o, double s) {
  constexpr double u = 0x1p-53;
  double nv[3], ne[3];
  for (int k = 0; k < 3; ++k) {
    const Approx a = approx_of(n.x[k]);
    nv[k] = a.v, ne[k] = a.err;
  }
  double h[4], e[4];
  for (int i = 0; i < 4; ++i) {
    double x = 0.0, b = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = T[i][k] - o[k];
      x += nv[k] * d;
      b += std::fabs(d) * (ne[k] + 5 * u * std::fabs(nv[k]));
    }
    h[i] = s * x, e[i] = b * (1 + 0x1p-40) + 0x1p-1000;
  }
  unsigned keep = 0;
  for (int i = 0; i < 4; ++i) {
    bool below = false;
    for (int j = 0; j < 4 && !below; ++j)
      below = (h[j] - h[i]) * (1 - 0x1p-50) > (e[i] + e[j]) * (1 + 0x1p-50);
    if (!below) keep |= 1u << i;
  }
  return keep;
}
}  // namespace

// The vertices of A (of B) at or before vertex v in index order: where the label puts v at A's
// largest height (B's least) exactly, the first one attaining it is among them. FV:i, n out of
// A: the face's vertices share one height (n is their cross product) and s_i lies below it;
// VF:j likewise for B's face, n into B; a decided edge pair (the rule kept or flipped n): both
// of A's other vertices have g_k <= 0, at or below the edge's height (definitions §3).
constexpr unsigned up_to(int v) { return (2u << v) - 1; }

ExactDepthParts depth_parts_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  ExactDepthParts parts;
  ExpVec n;
  EdgePairSide rule = EdgePairSide::Undecidable;
  if (!normal_for_degree_ten(A, B, label, n, &rule)) return parts;
  bool ok = true;
  Expansion hi, lo;
  unsigned onlyA = 0xFu, onlyB = 0xFu;
  if (label.kind == ContactKind::FV) onlyA = up_to(kFace[label.a][0]);
  if (label.kind == ContactKind::VF) onlyB = up_to(kFace[label.a][0]);
  if (label.kind == ContactKind::EE && rule != EdgePairSide::Undecidable) onlyA = up_to(kEdges[label.a][0]);
  const unsigned keepA = extreme_candidates(n, A, A[0], 1.0) & onlyA;
  const unsigned keepB = extreme_candidates(n, B, A[0], -1.0) & onlyB;
  bool firstA = true, firstB = true;
  for (int i = 0; i < 4; ++i) {
    if (keepA >> i & 1) {
      const Expansion ha = dot(n, difference(A[i], A[0]));
      if (firstA || difference(ha, hi).sign() > 0) hi = ha;
      ok = ok && ha.ok, firstA = false;
    }
    if (keepB >> i & 1) {
      const Expansion hb = dot(n, difference(B[i], A[0]));
      if (firstB || difference(hb, lo).sign() < 0) lo = hb;
      ok = ok && hb.ok, firstB = false;
    }
  }
  // compressed: the same values in a few components, so that the products of
  // compare_delta2_exact stay short
  parts.D = compressed(difference(hi, lo));
  parts.nn = compressed(dot(n, n));
  parts.ok = ok && parts.D.ok && parts.nn.ok && parts.nn.sign() > 0;
  return parts;
}

namespace {
// x · y with its error bound: |x̃ỹ − xy| <= |x̃| e_y + |ỹ| e_x + e_x e_y, plus the product's
// rounding u |x̃ỹ|; (1 + 4u) covers the rounding of the bound's own terms. The components are
// multiples of 2^-1008 (depth_parts_exact), so non-zero values and products are normal; a term
// of the bound that underflows loses less than 2^-1074, which the caller's 2^-1000 covers.
Approx times(const Approx& x, const Approx& y) {
  constexpr double u = 0x1p-53;
  Approx r;
  r.v = x.v * y.v;
  r.err = (std::fabs(x.v) * y.err + std::fabs(y.v) * x.err + x.err * y.err) * (1.0 + 4.0 * u) +
          u * std::fabs(r.v);
  return r;
}
}  // namespace

namespace {
// D²/(n.n) of parts (D != 0) as a double with its root bound (delta2_by_expansions' bound).
bool value_of_parts(const ExactDepthParts& parts, double& v, double& r) {
  constexpr double u = 0x1p-53;
  const Approx D = approx_of(parts.D), nn = approx_of(parts.nn);
  const double rho_D = D.err / std::fabs(D.v), rho_n = nn.err / nn.v;
  if (!(rho_D <= 0.01 && rho_n <= 0.01)) return false;  // (NaN: false)
  v = D.v * D.v / nn.v;
  r = 1.02 * (rho_D + rho_n + 4 * u);
  return std::isfinite(v) && v > 0.0;
}
}  // namespace

bool delta2_by_expansions(const TetVertices& A, const TetVertices& B, const DirectionLabel& label, double& v,
                          double& r) {
  IntegerFrame frame(A, B);  // (over integers where the pair has a frame: integer_depth.h)
  FramedDepth framed;
  if (frame.usable() && framed_depth(frame, label, framed) && framed_delta2(frame, framed, v, r)) return true;
  const ExactDepthParts parts = depth_parts_exact(A, B, label);
  return parts.ok && parts.D.sign() != 0 && value_of_parts(parts, v, r);
}

namespace {
// The lesser (greater) of two exact values.
const Expansion& lesser(const Expansion& a, const Expansion& b) { return difference(a, b).sign() <= 0 ? a : b; }
const Expansion& greater(const Expansion& a, const Expansion& b) { return difference(a, b).sign() >= 0 ? a : b; }

// A candidate's overlap and n.n (ExactDepthParts' D holds the overlap).
ExactDepthParts overlap_parts_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label) {
  ExactDepthParts parts;
  ExpVec n;
  if (!normal_for_degree_ten(A, B, label, n)) return parts;
  bool ok = true;
  Expansion hiA, loA, hiB, loB;
  for (int i = 0; i < 4; ++i) {
    const Expansion ha = dot(n, difference(A[i], A[0])), hb = dot(n, difference(B[i], A[0]));
    ok = ok && ha.ok && hb.ok;
    hiA = i == 0 ? ha : greater(hiA, ha), loA = i == 0 ? ha : lesser(loA, ha);
    hiB = i == 0 ? hb : greater(hiB, hb), loB = i == 0 ? hb : lesser(loB, hb);
  }
  parts.D = compressed(difference(lesser(hiA, hiB), greater(loA, loB)));
  parts.nn = compressed(dot(n, n));
  parts.ok = ok && parts.D.ok && parts.nn.ok && parts.nn.sign() > 0;
  return parts;
}
}  // namespace

bool eq11_by_expansions(const TetVertices& A, const TetVertices& B, const DirectionLabel* l, int n, bool& zero,
                        double& v, double& r) {
  zero = false;
  ExactDepthParts least;
  for (int k = 0; k < n; ++k) {
    ExactDepthParts p = overlap_parts_exact(A, B, l[k]);
    if (!p.ok) return false;
    if (p.D.sign() <= 0) {
      zero = true;
      return true;
    }
    if (k == 0) {
      least = std::move(p);
      continue;
    }
    const std::optional<int> below = compare_delta2_exact(p, least);
    if (!below) return false;
    if (*below < 0) least = std::move(p);
  }
  return n > 0 && value_of_parts(least, v, r);
}

// The two cases of compare_delta2_exact that need no product of expansions, common on aligned
// pairs (parallel faces and edges give candidates of equal n.n or equal D, many of them exact
// ties). With D_p, D_q > 0 and n.n > 0:
//   n_p.n_p = n_q.n_q = m:  D_p² m − D_q² m = m (D_p − D_q)(D_p + D_q), sign = sign(D_p − D_q);
//   D_p = D_q = D:          D² n_q.n_q − D² n_p.n_p, sign = sign(n_q.n_q − n_p.n_p).
// Each sign is that of one exact difference of expansions (linear in their lengths). Tried only
// when the rounded values are within 2^-40 relative (a necessary condition for equality: each
// approx() is within 2·48 u of its exact value: the gate decides cost only, never the sign),
// so other pairs pay two comparisons.
// nullopt: neither case applies (or an expansion exceeds its capacity).
namespace {
bool nearly_equal(double a, double b) { return std::fabs(a - b) <= 0x1p-40 * std::fabs(a); }
std::optional<int> compare_delta2_equal_part(const ExactDepthParts& p, const ExactDepthParts& q) {
  if (!(p.D.sign() > 0 && q.D.sign() > 0)) return std::nullopt;
  if (nearly_equal(p.nn.approx(), q.nn.approx())) {
    const Expansion dn = difference(p.nn, q.nn);
    if (dn.ok && dn.sign() == 0) {
      const Expansion dd = difference(p.D, q.D);
      if (dd.ok) return dd.sign();
    }
  }
  if (nearly_equal(p.D.approx(), q.D.approx())) {
    const Expansion dd = difference(p.D, q.D);
    if (dd.ok && dd.sign() == 0) {
      const Expansion dn = difference(q.nn, p.nn);
      if (dn.ok) return dn.sign();
    }
  }
  return std::nullopt;
}
}  // namespace

// The sign of D_p² n_q.n_q − D_q² n_p.n_p over integers: each expansion's value is an integer
// times a power of two (to_integer, below), so each side of the difference is an integer product
// times a power of two, and the two are compared once shifted to the same power. Exact, as a
// product of the expansions would be, for a few GMP operations on integers of a few hundred
// bits instead of the O(n² m) two_products of expansions of up to 48 components (measured: a
// sixth of their instructions). The comparisons that reach it are near ties of nearly parallel
// directions (aligned pairs: delta² ~1e-32 relative apart, or equal), which no truncated or
// double filter decides. Each parts' D² and n.n are converted once (ExactDepthParts::integers).
// Written by hand on GMP's integers: an expansion is not a number GMP reads.
namespace {
// out = x / 2^e exactly (an integer), e returned (0 for the value 0): each component is
// (-1)^s m 2^k with m its 53-bit significand (subnormals: 52 bits, k = -1074), read from its
// bits; Horner over the components by decreasing k (nonoverlapping components come in
// increasing k; any order is sorted first), a shift and an addition each.
long to_integer(const Expansion& x, mpz_t out) {
  struct Term {
    long k;
    unsigned long m;
    bool negative;
  } t[kExpansionCapacity];
  for (int i = 0; i < x.n; ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x.c[i], sizeof bits);
    const long ex = long((bits >> 52) & 0x7FF);
    const std::uint64_t frac = bits & ((std::uint64_t(1) << 52) - 1);
    t[i] = ex == 0 ? Term{-1074, frac, (bits >> 63) != 0} : Term{ex - 1075, frac | (std::uint64_t(1) << 52), (bits >> 63) != 0};
  }
  std::sort(t, t + x.n, [](const Term& a, const Term& b) { return a.k > b.k; });
  mpz_set_ui(out, 0);
  long e = x.n > 0 ? t[0].k : 0;
  for (int i = 0; i < x.n; ++i) {
    mpz_mul_2exp(out, out, static_cast<mp_bitcnt_t>(e - t[i].k));
    e = t[i].k;
    if (t[i].negative) mpz_sub_ui(out, out, t[i].m);
    else mpz_add_ui(out, out, t[i].m);
  }
  return e;
}
}  // namespace

struct ExactDepthIntegers {
  mpz_class D2, nn;  // D² = D2 2^eD2, n.n = nn 2^enn
  long eD2 = 0, enn = 0;
};

namespace {
const ExactDepthIntegers& integers_of(const ExactDepthParts& p) {
  if (!p.integers) {
    auto x = std::make_shared<ExactDepthIntegers>();
    x->eD2 = 2 * to_integer(p.D, x->D2.get_mpz_t());
    mpz_mul(x->D2.get_mpz_t(), x->D2.get_mpz_t(), x->D2.get_mpz_t());
    x->enn = to_integer(p.nn, x->nn.get_mpz_t());
    p.integers = std::move(x);
  }
  return *p.integers;
}

std::optional<int> compare_delta2_integers(const ExactDepthParts& p, const ExactDepthParts& q) {
  struct Scratch {  // per thread: the products keep their limbs between calls
    mpz_t a, b;
    Scratch() { mpz_init2(a, 1024), mpz_init2(b, 1024); }
    ~Scratch() { mpz_clear(a), mpz_clear(b); }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
  };
  thread_local Scratch z;
  const ExactDepthIntegers &x = integers_of(p), &y = integers_of(q);
  mpz_mul(z.a, x.D2.get_mpz_t(), y.nn.get_mpz_t());  // D_p² n_q.n_q = a 2^sa
  mpz_mul(z.b, y.D2.get_mpz_t(), x.nn.get_mpz_t());  // D_q² n_p.n_p = b 2^sb
  const long sa = x.eD2 + y.enn, sb = y.eD2 + x.enn;
  if (sa > sb) mpz_mul_2exp(z.a, z.a, static_cast<mp_bitcnt_t>(sa - sb));
  if (sb > sa) mpz_mul_2exp(z.b, z.b, static_cast<mp_bitcnt_t>(sb - sa));
  const int c = mpz_cmp(z.a, z.b);
  return c > 0 ? 1 : c < 0 ? -1 : 0;
}
}  // namespace

std::optional<int> compare_delta2_exact(const ExactDepthParts& p, const ExactDepthParts& q) {
  if (const std::optional<int> s = compare_delta2_equal_part(p, q)) return s;
  // Filter: the sign of the computed difference when it exceeds the computed error bound (the
  // subtraction's own rounding, relative u, within the factor 1 + 4u); exact expansions below.
  {
    constexpr double u = 0x1p-53;
    const Approx dp = approx_of(p.D), dq = approx_of(q.D);
    const Approx a = times(times(dp, dp), approx_of(q.nn)), b = times(times(dq, dq), approx_of(p.nn));
    const double d = a.v - b.v, bound = (a.err + b.err) * (1.0 + 4.0 * u) + 0x1p-1000;
    if (std::fabs(d) > bound) return d > 0 ? 1 : -1;
  }
  return compare_delta2_integers(p, q);
}

// The exact normals of p and q certainly are not parallel: some component of the computed
// p~ x q~ exceeds its error. With |p - p~|, |q - q~| <= ep, eq per component and M the largest
// |component|, each exact product p_a q_b is within Mp eq + Mq ep + ep eq of p~_a q~_b, a
// component of p x q (two products) within twice that; the roundings of the two products (u Mp
// Mq each) and of their difference (u 2 Mp Mq (1 + u)) add < 5u Mp Mq, taken as 8u Mp Mq; a
// product that underflows errs by 2^-1075 more (2^-1060 covers them). The factor 1 + 2^-40
// covers the bound's own roundings.
bool certainly_not_parallel(const ApproxNormal& p, const ApproxNormal& q) {
  const double Mp = std::max({std::fabs(p.n[0]), std::fabs(p.n[1]), std::fabs(p.n[2])});
  const double Mq = std::max({std::fabs(q.n[0]), std::fabs(q.n[1]), std::fabs(q.n[2])});
  const double bound =
      (2 * (Mp * q.e + Mq * p.e + p.e * q.e) + 8 * 0x1p-53 * Mp * Mq + 0x1p-1060) * (1 + 0x1p-40);
  const double c[3] = {p.n[1] * q.n[2] - p.n[2] * q.n[1], p.n[2] * q.n[0] - p.n[0] * q.n[2],
                       p.n[0] * q.n[1] - p.n[1] * q.n[0]};
  return std::fabs(c[0]) > bound || std::fabs(c[1]) > bound || std::fabs(c[2]) > bound;  // (NaN: false)
}

// As certainly_not_parallel: each exact product p_a q_a is within Mp eq + Mq ep + ep eq of
// p~_a q~_a (three of them); the three products' and two sums' roundings are below
// 3u · 3 Mp Mq (1 + O(u)), taken as 16u Mp Mq; 2^-1060 for products that underflow; the factor
// 1 + 2^-40 for the bound's own roundings.
int certain_dot_sign(const ApproxNormal& p, const ApproxNormal& q) {
  const double Mp = std::max({std::fabs(p.n[0]), std::fabs(p.n[1]), std::fabs(p.n[2])});
  const double Mq = std::max({std::fabs(q.n[0]), std::fabs(q.n[1]), std::fabs(q.n[2])});
  const double bound =
      (3 * (Mp * q.e + Mq * p.e + p.e * q.e) + 16 * 0x1p-53 * Mp * Mq + 0x1p-1060) * (1 + 0x1p-40);
  const double d = p.n[0] * q.n[0] + p.n[1] * q.n[1] + p.n[2] * q.n[2];
  return d > bound ? 1 : d < -bound ? -1 : 0;  // (NaN: 0)
}

int first_least_delta2_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel* l, int n,
                             const ApproxNormal* approx, const DeltaOrderHint& decided) {
  if (n <= 1) return n == 1 ? 0 : -1;
  int w = 0;
  std::optional<ExactDirection> direction;  // l[w]'s, built at its first use
  ExactDepthParts least;                    // l[w]'s, likewise (ok: built)
  for (int k = 1; k < n; ++k) {
    if (decided)
      if (const std::optional<int> below = decided(k, w)) {
        if (*below < 0) w = k, direction.reset(), least.ok = false;
        continue;
      }
    if (!(approx && certainly_not_parallel(approx[w], approx[k]))) {
      if (!direction) direction.emplace(A, B, l[w]);
      const int side = approx && !approx[k].parallel_pair ? certain_dot_sign(approx[w], approx[k]) : 0;
      if (direction->same_as(l[k], side).value_or(false)) continue;  // equal delta: the earlier kept
    }
    if (!least.ok && !(least = depth_parts_exact(A, B, l[w])).ok) return -1;
    ExactDepthParts p = depth_parts_exact(A, B, l[k]);
    if (!p.ok) return -1;
    const std::optional<int> below = compare_delta2_exact(p, least);
    if (!below) return -1;
    if (*below < 0) w = k, direction.reset(), least = std::move(p);  // strictly below: a tie keeps the earlier
  }
  return w;
}

}  // namespace pdd::fast
