// compensated_qp_order.cpp — exact_qp_order.h's closed forms on Bounded double words. See the
// header.
#include "certification/compensated_qp_order.h"

#include <cmath>

#include "certification/compensated_heights.h"
#include "pdd/tet_tables.h"

namespace pdd::fast::detail {
namespace {

using dw::Bounded;
using dw::kU;

// The largest of four heights with a bound on its distance to the exact largest: the one
// picked, t (the largest double word: (hi, lo) orders them exactly), lies within e_t of its
// exact height, so the exact largest is >= h~_t − e_t; each exact H*_i <= h~_i + e_i = h~_t −
// (h~_t − h~_i) + e_i, and g_i = fl(x − 4u fl(S)) − 2^-1060, x = fl(t.hi − i.hi) >= 0 and S =
// |t.hi| + |i.hi|, is below the exact gap h~_t − h~_i (>= x − 2u S: x's rounding u S, the low
// parts' u S; the subtraction's rounding u S (1 + u) < 2u S (1 − u); 2^-1060 covers 4u fl(S)
// underflowing). So the exact largest is within max(e_t, max_i (e_i − g_i)) of h~_t; fl(e_i −
// g_i), when positive, within u of itself (the factor 1 + 2^-40). NaN: an infinite bound.
Bounded highest(const Bounded (&h)[4]) {
  auto above = [](const dw::DW& x, const dw::DW& y) { return x.hi > y.hi || (x.hi == y.hi && x.lo > y.lo); };
  int t = 0;
  for (int i = 1; i < 4; ++i)
    if (above(h[i].v, h[t].v)) t = i;
  Bounded top = h[t];
  for (int i = 0; i < 4; ++i) {
    if (i == t) continue;
    const double x = h[t].v.hi - h[i].v.hi, S = std::fabs(h[t].v.hi) + std::fabs(h[i].v.hi);
    const double w = h[i].e - ((x - 4 * kU * S) - 0x1p-1060);
    if (!(w <= 0)) top.e = std::isnan(w) ? INFINITY : std::fmax(top.e, w * (1 + 0x1p-40));
  }
  return top;
}

// The sums of d_i² and of d_i over the vertices of `at`, d_i = E − k h_i.
struct Deviations {
  Bounded squares, total;
};
Deviations deviations(const Bounded& E, int k, const Bounded (&h)[4], unsigned at) {
  Deviations s;
  for (int i = 0; i < 4; ++i) {
    if (!(at >> i & 1u)) continue;
    const Bounded d = dw::minus(E, dw::times(h[i], k));
    s.squares = dw::plus(s.squares, dw::times(d, d));
    s.total = dw::plus(s.total, d);
  }
  return s;
}

bool finite(const Bounded& x) { return std::isfinite(x.v.hi) && std::isfinite(x.v.lo) && std::isfinite(x.e); }

// Case 2's plane for a pattern: m_X the counts at the plane, w_A = 5 − m_B, w_B = 5 − m_A,
// den = m_A w_A + m_B w_B and E = w_A sum_A h + w_B sum_B h (C = E / den); false when no vertex
// is at the plane (den = 0).
struct Plane {
  int mA = 0, mB = 0, wA = 0, wB = 0, den = 0;
  Bounded E;
};
bool plane_of(const Bounded (&hA)[4], const Bounded (&hB)[4], const QpPattern& pattern, Plane& p) {
  p.mA = __builtin_popcount(pattern.atA), p.mB = __builtin_popcount(pattern.atB);
  p.wA = 5 - p.mB, p.wB = 5 - p.mA, p.den = p.mA * p.wA + p.mB * p.wB;
  if (p.den == 0 || p.mA > 4 || p.mB > 4) return false;
  Bounded PA, PB;
  for (int i = 0; i < 4; ++i) {
    if (pattern.atA >> i & 1u) PA = dw::plus(PA, hA[i]);
    if (pattern.atB >> i & 1u) PB = dw::plus(PB, hB[i]);
  }
  p.E = dw::plus(dw::times(PA, p.wA), dw::times(PB, p.wB));
  return true;
}

}  // namespace

bool compensated_qp_parts(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                          const QpPattern& pattern, bool a_static, CompensatedQpParts& out) {
  DoubleWordHeights w;
  if (!double_word_heights(A, B, label, w)) return false;
  Bounded hA[4], hB[4];
  for (int i = 0; i < 4; ++i) hA[i] = {w.hA[i], w.eA[i]}, hB[i] = {w.hB[i], w.eB[i]};
  const int mB = __builtin_popcount(pattern.atB);
  Bounded F;
  int K;
  if (a_static) {
    // C: the height A's constrained vertices share (0 here: the origin is one of them), else
    // A's highest (a VF label)
    const Bounded C = pattern.conA ? hA[__builtin_ctz(pattern.conA)] : highest(hA);
    const Deviations b = deviations(C, 1, hB, pattern.atB);
    F = dw::plus(dw::times(b.squares, 5 - mB), dw::times(b.total, b.total));
    K = 5 - mB;
  } else {
    Plane pl;
    if (!plane_of(hA, hB, pattern, pl)) return false;
    const int wA = pl.wA, wB = pl.wB, den = pl.den;
    const Deviations a = deviations(pl.E, den, hA, pattern.atA), b = deviations(pl.E, den, hB, pattern.atB);
    F = dw::plus(dw::plus(dw::times(dw::plus(a.squares, b.squares), wA * wB), dw::times(dw::times(a.total, a.total), wA)),
                 dw::times(dw::times(b.total, b.total), wB));
    K = den * den * wA * wB;
  }
  Bounded nn;
  for (int k = 0; k < 3; ++k) {
    const Bounded n{w.n[k], w.en[k]};
    nn = dw::plus(nn, dw::times(n, n));
  }
  out.F = F;
  out.Knn = dw::times(nn, K);
  return finite(out.F) && finite(out.Knn) && dw::certain_sign(out.Knn) > 0;
}

bool compensated_displacements(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               const QpPattern& pattern, CompensatedDisplacements& out) {
  DoubleWordHeights w;
  if (!double_word_heights(A, B, label, w)) return false;
  // n* = e1 x e2 certainly not 0: the label's direction (not an edge pair's taken as ± by its
  // label while its edges are parallel, whose direction is another vector)
  Bounded nn;
  for (int k = 0; k < 3; ++k) nn = dw::plus(nn, dw::times(Bounded{w.n[k], w.en[k]}, Bounded{w.n[k], w.en[k]}));
  if (!(dw::certain_sign(nn) > 0)) return false;
  Bounded hA[4], hB[4];
  for (int i = 0; i < 4; ++i) hA[i] = {w.hA[i], w.eA[i]}, hB[i] = {w.hB[i], w.eB[i]};
  Plane pl;
  if (!plane_of(hA, hB, pattern, pl)) return false;
  const int mA = pl.mA, mB = pl.mB, den = pl.den;
  const Bounded& E = pl.E;
  // x / k rounded, and its distance to x* / k
  auto divided = [](const Bounded& x, int k, double& t, double& e) {
    t = x.v.hi / k;
    e = ((x.e + kU * std::fabs(x.v.hi)) / k + kU * std::fabs(t)) * (1 + 0x1p-40);
    return std::isfinite(t) && std::isfinite(e);
  };
  for (int side = 0; side < 2; ++side) {
    const Bounded(&h)[4] = side ? hB : hA;
    const unsigned at = side ? pattern.atB : pattern.atA;
    const int m = side ? mB : mA;
    double* t = side ? out.tB : out.tA;
    double* e = side ? out.eB : out.eA;
    Bounded total;
    for (int i = 0; i < 4; ++i) {
      if (!(at >> i & 1u)) continue;
      const Bounded d = dw::minus(E, dw::times(h[i], den));
      total = dw::plus(total, d);
      if (!divided(d, den, t[i], e[i])) return false;
    }
    if (m == 4) continue;
    double S = 0, eS = 0;
    if (!divided(total, den * (5 - m), S, eS)) return false;
    for (int i = 0; i < 4; ++i)
      if (!(at >> i & 1u)) t[i] = -S, e[i] = eS;
  }
  return true;
}

std::optional<int> compare_qp_compensated(const CompensatedQpParts& p, const CompensatedQpParts& q) {
  const int s = dw::certain_sign(dw::minus(dw::times(p.F, q.Knn), dw::times(q.F, p.Knn)));
  if (s == 0) return std::nullopt;
  return s;
}

}  // namespace pdd::fast::detail
