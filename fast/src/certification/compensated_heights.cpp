// compensated_heights.cpp — see compensated_heights.h for the arithmetic and its bounds.
#include "certification/compensated_heights.h"

#include <cmath>

#include "certification/double_word.h"
#include "exact/exact_predicates.h"
#include "exact/expansion.h"
#include "exact/integer_depth.h"
#include "kernel/direction_geometry.h"
#include "kernel/pair_memo.h"

namespace pdd::fast::detail {
namespace {

using dw::add;
using dw::DW;
using dw::kU;
using dw::mul;
using dw::neg;
using dw::two_sum;

struct DV {
  DW x[3];
};
DV diff(const std::array<double, 3>& p, const std::array<double, 3>& o) {  // exact
  return {{two_sum(p[0], -o[0]), two_sum(p[1], -o[1]), two_sum(p[2], -o[2])}};
}

constexpr double kGrow = 1 + 0x1p-40;  // the bounds' own roundings (header)

bool finite_heights(const CompensatedHeights& h) {
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(h.hA[i]) || !std::isfinite(h.hB[i]) || !std::isfinite(h.eA[i]) || !std::isfinite(h.eB[i]))
      return false;
  return true;
}

// A label's exact direction as double words, unoriented (the header's normal, unrounded):
// n* = ±e1 x e2, the origin o, and N_k from the high parts.
struct Span {
  DW n[3];
  double N[3];
  std::array<double, 3> o;
};

// n* = e1 x e2 of exact differences, in double words, and N_k from the high parts.
[[gnu::always_inline]] inline void cross_of(const DV& e1, const DV& e2, Span& sp) {
  for (int k = 0; k < 3; ++k) {
    const int r = (k + 1) % 3, s = (k + 2) % 3;
    sp.n[k] = add(mul(e1.x[r], e2.x[s]), neg(mul(e1.x[s], e2.x[r])));
    sp.N[k] = std::fabs(e1.x[r].hi * e2.x[s].hi) + std::fabs(e1.x[s].hi * e2.x[r].hi);
  }
}

[[gnu::always_inline]] inline void span_of(const TetVertices& A, const TetVertices& B, const DirectionLabel& l,
                                           Span& sp) {
  // The direction's two spanning vectors e1, e2 (n* = e1 x e2 up to sign) and the origin o, a
  // vertex of the constrained set whose heights are exactly 0 (A's face or edge; B's face).
  const TetVertices* T = &A;
  std::array<double, 3> p1, p2, q1, q2;
  switch (l.kind) {
    case ContactKind::FV:
    case ContactKind::VF: {
      T = l.kind == ContactKind::FV ? &A : &B;
      const auto& f = kFace[l.a];
      sp.o = (*T)[f[0]], p1 = (*T)[f[1]], q1 = sp.o, p2 = (*T)[f[2]], q2 = sp.o;
      break;
    }
    default: {
      const int u = kEdges[l.a][0], v = kEdges[l.a][1], x = kEdges[l.b][0], y = kEdges[l.b][1];
      sp.o = A[u], p1 = B[y], q1 = B[x], p2 = A[v], q2 = A[u];  // eB x eA (definitions §3)
      break;
    }
  }
  cross_of(diff(p1, q1), diff(p2, q2), sp);
}

// The eight heights (e1 x e2).(x − o) as double words, each within e = 25 u^2 M of the exact
// one (header), with that bound and the absolute terms of underflowed products: each of the
// normal's components errs by up to 6 · 2^-1075 more (two mul, three products each that may
// underflow; the add is exact there), which reaches the height times |d_k| (2^-1066 sum |d_k|
// covers it at any scale), and the height's own products add less than 2^-1070 (2^-1040).
struct Heights {
  DW hA[4], hB[4];
  double eA[4], eB[4];
};
[[gnu::always_inline]] inline DW height_of(const Span& sp, const std::array<double, 3>& x, double& e) {
  const DV d = diff(x, sp.o);
  DW s = mul(sp.n[0], d.x[0]);
  s = add(s, mul(sp.n[1], d.x[1]));
  s = add(s, mul(sp.n[2], d.x[2]));
  const double M = sp.N[0] * std::fabs(d.x[0].hi) + sp.N[1] * std::fabs(d.x[1].hi) + sp.N[2] * std::fabs(d.x[2].hi);
  e = 25 * kU * kU * M * kGrow + 0x1p-1040 +
      0x1p-1066 * (std::fabs(d.x[0].hi) + std::fabs(d.x[1].hi) + std::fabs(d.x[2].hi));
  return s;
}
[[gnu::always_inline]] inline void heights_of(const TetVertices& A, const TetVertices& B, const Span& sp,
                                              Heights& h) {
  for (int i = 0; i < 4; ++i) {
    h.hA[i] = height_of(sp, A[i], h.eA[i]);
    h.hB[i] = height_of(sp, B[i], h.eB[i]);
  }
}

// The sign of a height when certain: the double word's value is within u |hi| of hi, so
// |hi| (1 − 2u) above its bound e fixes the exact sign; 0 otherwise.
inline int certain_sign(const DW& h, double e) {
  return std::fabs(h.hi) * (1 - 2 * kU) > e ? (h.hi > 0 ? 1 : -1) : 0;
}

// The label's orientation of e1 x e2 (definitions §3), +1 or −1, from certain signs of its
// heights, not from a rounded normal: FV, out of A (A's opposite vertex below); VF, into B (B's
// opposite vertex above); EE, eB x eA kept or flipped by the orientation rule: Plus and Minus
// (the rule undecidable) keep and flip; a Decided label keeps when A's off-edge vertices lie
// below (both g <= 0), flips when above, and either certain non-zero g tells which. 0 when the
// sign needed is not certain (a face of nearly zero height over its opposite vertex; both g
// within their bounds; a parallel edge pair, e1 x e2 = 0).
inline int orientation_of(const DirectionLabel& l, const Heights& h) {
  switch (l.kind) {
    case ContactKind::FV:
      return -certain_sign(h.hA[l.a], h.eA[l.a]);
    case ContactKind::VF:
      return certain_sign(h.hB[l.a], h.eB[l.a]);
    default: {
      if (l.orientation != EdgeOrientation::Decided) return l.orientation == EdgeOrientation::Plus ? 1 : -1;
      const int i = kOffEdge[l.a][0], j = kOffEdge[l.a][1];
      const int g = certain_sign(h.hA[i], h.eA[i]);
      return -(g != 0 ? g : certain_sign(h.hA[j], h.eA[j]));
    }
  }
}

// The span and heights of label l, and the orientation (orientation_of; 0: not certain).
[[gnu::always_inline]] inline int oriented_span(const TetVertices& A, const TetVertices& B, const DirectionLabel& l,
                                                Span& sp, Heights& h) {
  span_of(A, B, l, sp);
  heights_of(A, B, sp, h);
  return orientation_of(l, h);
}

}  // namespace

// compensated_heights, computed (the memo below asks it once a pair and candidate)
PDD_FMA_CLONES bool compensated_heights_computed(const TetVertices& A, const TetVertices& B, const Candidate& c,
                                                 CompensatedHeights& out) {
  if (c.parallel) return false;
  const DirectionLabel& l = c.label;
  Span sp;
  Heights h;
  const int sign = oriented_span(A, B, l, sp, h);
  if (sign == 0) return false;
  out.e_n = 0;
  for (int k = 0; k < 3; ++k) {
    out.n[k] = sign * sp.n[k].hi;
    out.e_n = std::fmax(out.e_n, (kU * std::fabs(out.n[k]) * (1 + kU) + 10.5 * kU * kU * sp.N[k]) * kGrow + 0x1p-1070);
  }
  out.nn = out.n[0] * out.n[0] + out.n[1] * out.n[1] + out.n[2] * out.n[2];
  if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
  // rounded to the high part: u |h~| more (header)
  for (int i = 0; i < 4; ++i) {
    out.hA[i] = sign * h.hA[i].hi, out.eA[i] = h.eA[i] + kU * std::fabs(out.hA[i]) * kGrow;
    out.hB[i] = sign * h.hB[i].hi, out.eB[i] = h.eB[i] + kU * std::fabs(out.hB[i]) * kGrow;
  }
  // Constrained vertices: exactly on the plane through o (0), or (B's edge of an edge pair)
  // at one common height, that of its first vertex.
  for (int i = 0; i < 4; ++i) {
    if (l.kind == ContactKind::FV && (c.conA >> i & 1u)) out.hA[i] = 0, out.eA[i] = 0;
    if (l.kind == ContactKind::VF && (c.conB >> i & 1u)) out.hB[i] = 0, out.eB[i] = 0;
    if (l.kind == ContactKind::EE && (c.conA >> i & 1u)) out.hA[i] = 0, out.eA[i] = 0;
  }
  if (l.kind == ContactKind::EE) {
    const int x = kEdges[l.b][0], y = kEdges[l.b][1];
    out.hB[y] = out.hB[x], out.eB[y] = out.eB[x];
  }
  return finite_heights(out);
}

// The extremes of four double-word heights: a normalised double word's value orders as (hi, lo)
// lexicographically (hi = RN(hi + lo) and RN is monotone: hi1 > hi2 implies v1 >= v2), so the
// one picked is the largest (smallest) value, within max e_i of the exact extreme
// (|max a_i − max b_i| <= max |a_i − b_i|).
namespace {
bool above(const DW& x, const DW& y) { return x.hi > y.hi || (x.hi == y.hi && x.lo > y.lo); }
}  // namespace

namespace {
// double_word_heights (header), inlined into compensated_depth's hot loop
[[gnu::always_inline]] inline bool oriented_words(const TetVertices& A, const TetVertices& B, const DirectionLabel& l,
                                                  DoubleWordHeights& out) {
  Span sp;
  Heights h;
  const int sign = oriented_span(A, B, l, sp, h);
  if (sign == 0) return false;
  for (int k = 0; k < 3; ++k) {
    out.n[k] = sign > 0 ? sp.n[k] : neg(sp.n[k]);
    out.en[k] = 10.5 * kU * kU * sp.N[k] * kGrow;
  }
  for (int i = 0; i < 4; ++i) {
    out.hA[i] = sign > 0 ? h.hA[i] : neg(h.hA[i]), out.hB[i] = sign > 0 ? h.hB[i] : neg(h.hB[i]);
    out.eA[i] = h.eA[i], out.eB[i] = h.eB[i];
  }
  // constrained vertices at their exact heights: 0 on the face or A's edge through o, B's edge
  // at one height (n* is orthogonal to it)
  if (l.kind == ContactKind::FV || l.kind == ContactKind::VF) {
    DW* T = l.kind == ContactKind::FV ? out.hA : out.hB;
    double* e = l.kind == ContactKind::FV ? out.eA : out.eB;
    for (int i : kFace[l.a]) T[i] = DW{0, 0}, e[i] = 0;
  } else {
    for (int i : kEdges[l.a]) out.hA[i] = DW{0, 0}, out.eA[i] = 0;
    const int x = kEdges[l.b][0], y = kEdges[l.b][1];
    out.hB[y] = out.hB[x], out.eB[y] = out.eB[x];
  }
  return true;
}
}  // namespace

PDD_FMA_CLONES bool double_word_heights(const TetVertices& A, const TetVertices& B, const DirectionLabel& l,
                                        DoubleWordHeights& out) {
  return oriented_words(A, B, l, out);
}

PDD_FMA_CLONES bool compensated_depth_computed(const TetVertices& A, const TetVertices& B, const DirectionLabel& l,
                                      CompensatedDepth& out) {
  DoubleWordHeights h;
  if (!oriented_words(A, B, l, h)) return false;
  double e = 0.0;  // the largest height error
  for (int i = 0; i < 4; ++i) e = std::fmax(e, std::fmax(h.eA[i], h.eB[i]));
  DW top = h.hA[0], bottom = h.hB[0];
  for (int i = 1; i < 4; ++i) {
    if (above(h.hA[i], top)) top = h.hA[i];
    if (above(bottom, h.hB[i])) bottom = h.hB[i];
  }
  out.D = add(top, neg(bottom));
  out.eD = (2 * e + 4 * kU * kU * (std::fabs(top.hi) + std::fabs(bottom.hi))) * kGrow;
  // n.n: each |n~_k − n*_k| <= En_k = 10.5 u^2 N_k (header), so |n~_k² − n*_k²| <= En_k (2 |n~_k|
  // + En_k); the squares' roundings 6.2 u² n_k², the two adds' 4 u² of their operands (< 8.1 u²
  // sum n_k² in all).
  out.nn = DW{0, 0};
  out.enn = 0;
  double sq = 0;
  for (int k = 0; k < 3; ++k) {
    out.nn = add(out.nn, mul(h.n[k], h.n[k]));
    const double En = h.en[k], a = std::fabs(h.n[k].hi);
    out.enn += En * (2 * a * (1 + kU) + En);
    sq += a * a;
  }
  out.enn = (out.enn + 14.3 * kU * kU * sq) * kGrow;
  // range: no overflow in compare_delta2_compensated's products, and each value (within u of
  // its high part) far above its bound and the absolute terms (underflowed products) it carries
  const double D = out.D.hi, nn = out.nn.hi;
  return std::isfinite(D) && std::isfinite(nn) && std::isfinite(out.eD) && std::isfinite(out.enn) &&
         D * (1 - 2 * kU) - out.eD > 0x1p-300 && D < 0x1p+100 && nn * (1 - 2 * kU) - out.enn > 0x1p-300 &&
         nn < 0x1p+200;
}

// D_p² n_q.n_q − D_q² n_p.n_p in double words, each step's error bounded (double_word.h: mul
// 6.2 u² of the high parts' product, add 4 u² of the operands'):
//   a = D²: |a~ − D*²| <= eD (2|D~| + eD) + 6.2 u² D~²                             =: ea
//   X = a nn': |X~ − D*² nn'*| <= ea |nn'~| + (|a~| + ea) enn' + 6.2 u² |a~| |nn'~| =: eX
//   X − Y: within eX + eY + 4 u² (|X~| + |Y~|) of the exact difference.
// |x~| is the high part's magnitude within (1 + u), absorbed with the bound's own roundings in
// 1 + 2^-40; every underflowed product (each < 2^-1075, far fewer than 2^20 of them, times
// factors < 2^310 by the range above) is covered by 2^-700. The difference's value is within
// u |hi| of its high part: a sign when |hi| (1 − 2u) exceeds the bound.
PDD_FMA_CLONES std::optional<int> compare_delta2_compensated(const CompensatedDepth& p, const CompensatedDepth& q) {
  auto term = [](const CompensatedDepth& x, const CompensatedDepth& y, double& err) {
    const DW a = mul(x.D, x.D);
    const double D = std::fabs(x.D.hi), ea = x.eD * (2 * D + x.eD) + 6.2 * kU * kU * D * D;
    const DW X = mul(a, y.nn);
    const double A = std::fabs(a.hi), N = std::fabs(y.nn.hi);
    err = ea * N + (A + ea) * y.enn + 6.2 * kU * kU * A * N;
    return X;
  };
  double ex = 0, ey = 0;
  const DW X = term(p, q, ex), Y = term(q, p, ey);
  const DW d = add(X, neg(Y));
  const double bound = (ex + ey + 4 * kU * kU * (std::fabs(X.hi) + std::fabs(Y.hi))) * kGrow + 0x1p-700;
  if (!(std::fabs(d.hi) * (1 - 2 * kU) > bound)) return std::nullopt;  // (NaN: undecided)
  return d.hi > 0 ? 1 : -1;
}

PDD_FMA_CLONES bool compensated_heights_along(const TetVertices& A, const TetVertices& B,
                                              const std::array<double, 3>& v, CompensatedHeights& out,
                                              const std::array<double, 3>& lo) {
  int top = 0;
  double best = -INFINITY;
  for (int i = 0; i < 4; ++i) {
    const double h = v[0] * (A[i][0] - A[0][0]) + v[1] * (A[i][1] - A[0][1]) + v[2] * (A[i][2] - A[0][2]);
    if (h > best) best = h, top = i;  // (a heuristic choice: any vertex is a valid origin)
  }
  const std::array<double, 3> o = A[top];
  for (int k = 0; k < 3; ++k) out.n[k] = v[k];
  out.e_n = std::fmax(std::fabs(lo[0]), std::fmax(std::fabs(lo[1]), std::fabs(lo[2])));  // n* - n~ = lo
  out.nn = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
  // A height v.(x − o): the difference exact (two_sum), three products of a double and a
  // double word (mul, at most the header's 6.2 u^2 each) and two adds: within the header's
  // 25 u^2 M, M = sum |v_k| |d_k| (no normal error here), then rounded to its high part (u).
  auto height = [&](const std::array<double, 3>& x, double& h, double& e) {
    const DV d = diff(x, o);
    DW s = mul(DW{v[0], lo[0]}, d.x[0]);
    s = add(s, mul(DW{v[1], lo[1]}, d.x[1]));
    s = add(s, mul(DW{v[2], lo[2]}, d.x[2]));
    const double M = std::fabs(v[0] * d.x[0].hi) + std::fabs(v[1] * d.x[1].hi) + std::fabs(v[2] * d.x[2].hi);
    h = s.hi;
    e = (kU * std::fabs(h) + 25 * kU * kU * M) * kGrow + 0x1p-1040;
  };
  for (int i = 0; i < 4; ++i) {
    height(A[i], out.hA[i], out.eA[i]);
    height(B[i], out.hB[i], out.eB[i]);
  }
  out.hA[top] = 0, out.eA[top] = 0;  // the origin itself: exactly 0
  return finite_heights(out);
}

bool expansion_heights_computed(const TetVertices& A, const TetVertices& B, const Candidate& c, CompensatedHeights& out) {
  const DirectionLabel& l = c.label;
  ExpVec n;
  const bool edges = l.kind == ContactKind::EE;
  const int u = edges ? kEdges[l.a][0] : 0, v = edges ? kEdges[l.a][1] : 0, x = edges ? kEdges[l.b][0] : 0,
            y = edges ? kEdges[l.b][1] : 0;
  const unsigned face = 0xFu & ~(1u << l.a);  // a face label's constrained vertices
  if (edges ? c.conA != ((1u << u) | (1u << v)) || c.conB != ((1u << x) | (1u << y))
            : l.kind == ContactKind::FV ? c.conA != face || c.conB != 0 : c.conA != 0 || c.conB != face)
    return false;
  if (IntegerFrame frame(A, B); frame.usable()) {
    // over the pair's integer frame (integer_depth.h): the same exact normal and heights, each
    // rounded once (~4,000 instructions a candidate where the expansions take ~12,000); where a
    // value leaves the double range there, by expansions below (edge pairs only)
    FramedHeights fh;
    if (framed_heights(frame, l, fh)) {
      for (int k = 0; k < 3; ++k) out.n[k] = fh.n[k];
      out.e_n = fh.e_n;
      out.nn = out.n[0] * out.n[0] + out.n[1] * out.n[1] + out.n[2] * out.n[2];
      if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
      for (int i = 0; i < 4; ++i) out.hA[i] = fh.h[i], out.eA[i] = fh.e[i], out.hB[i] = fh.h[4 + i], out.eB[i] = fh.e[4 + i];
      return finite_heights(out);
    }
  }
  if (!edges || !oriented_normal_expansion(A, B, l, n)) return false;
  out.e_n = 0;
  for (int k = 0; k < 3; ++k) {
    const Approx a = approx_of(compressed(n.x[k]));
    out.n[k] = a.v, out.e_n = std::fmax(out.e_n, a.err);
  }
  out.nn = out.n[0] * out.n[0] + out.n[1] * out.n[1] + out.n[2] * out.n[2];
  if (!(out.nn > 0) || !std::isfinite(out.nn)) return false;
  // The heights relative to s_u exactly (A's edge at 0, B's edge at one common height: n*.eB = 0
  // exactly, so the exact heights of its vertices are equal), then relative to A's vertex
  // highest along n* (framed_heights' origin), each rounded once: u of its own value.
  Expansion H[8];  // (default: 0)
  for (int i = 0; i < 4; ++i) {
    if (!(c.conA >> i & 1u)) H[i] = compressed(dot(n, difference(A[i], A[u])));
    if (i != y) H[4 + i] = compressed(dot(n, difference(B[i], A[u])));
  }
  H[4 + y] = H[4 + x];
  int t = 0;
  for (int i = 1; i < 4; ++i) t = approx_of(H[i]).v > approx_of(H[t]).v ? i : t;
  double h[8], e[8];
  for (int i = 0; i < 8; ++i) {
    const Expansion D = compressed(difference(H[i], H[t]));
    if (!D.ok) return false;
    const Approx a = approx_of(D);
    h[i] = a.v, e[i] = a.err;
  }
  for (int i = 0; i < 4; ++i) out.hA[i] = h[i], out.eA[i] = e[i], out.hB[i] = h[4 + i], out.eB[i] = e[4 + i];
  return finite_heights(out);
}

// The values of one pair ask the same candidates' heights and depths again (kernel/pair_memo.h):
// memoised per thread, keyed by the label, and by the constrained sets and the parallel flag
// the heights also depend on.
namespace {
unsigned candidate_key(const Candidate& c) {
  return label_key(c.label) | unsigned(c.conA) << 10 | unsigned(c.conB) << 14 | unsigned(c.parallel) << 18;
}
thread_local PairMemo<CompensatedHeights, 32> heights_memo;
thread_local PairMemo<CompensatedHeights, 16> expansion_memo;
thread_local PairMemo<CompensatedDepth, 32> depth_memo;
}  // namespace

bool compensated_heights(const TetVertices& A, const TetVertices& B, const Candidate& c, CompensatedHeights& out) {
  return heights_memo.get(A, B, candidate_key(c), out,
                          [&](CompensatedHeights& h) { return compensated_heights_computed(A, B, c, h); });
}

bool expansion_heights(const TetVertices& A, const TetVertices& B, const Candidate& c, CompensatedHeights& out) {
  return expansion_memo.get(A, B, candidate_key(c), out,
                            [&](CompensatedHeights& h) { return expansion_heights_computed(A, B, c, h); });
}

PDD_FMA_CLONES CompensatedNormal compensated_normal(const std::array<double, 3>& p1, const std::array<double, 3>& p0,
                                                   const std::array<double, 3>& q1, const std::array<double, 3>& q0) {
  Span sp;
  cross_of(diff(p1, p0), diff(q1, q0), sp);
  CompensatedNormal n;
  for (int k = 0; k < 3; ++k) n.n[k] = sp.n[k], n.N[k] = sp.N[k];
  return n;
}

PDD_FMA_CLONES bool compensated_height_sign(const CompensatedNormal& n, const std::array<double, 3>& p,
                                            const std::array<double, 3>& q, int& sign) {
  Span sp;
  for (int k = 0; k < 3; ++k) sp.n[k] = n.n[k], sp.N[k] = n.N[k];
  sp.o = q;
  double e;
  const DW h = height_of(sp, p, e);
  if (!std::isfinite(h.hi) || !std::isfinite(e)) return false;
  sign = certain_sign(h, e);
  return sign != 0;
}

bool compensated_depth(const TetVertices& A, const TetVertices& B, const DirectionLabel& l, CompensatedDepth& out) {
  return depth_memo.get(A, B, label_key(l), out,
                        [&](CompensatedDepth& d) { return compensated_depth_computed(A, B, l, d); });
}

}  // namespace pdd::fast::detail
