// qp_lower_bound.cpp — the dual lower bounds of qp_lower_bound.h (proof and rounding there).
// The lane loop is branch-free so that GCC vectorises it in its AVX-512 and AVX2 clones.
#include "certification/qp_lower_bound.h"

#include <cstring>
#include <limits>

#include "certification/value_bounds.h"
#include "kernel/direction_geometry.h"

namespace pdd::fast::detail {
namespace {

// Run-time dispatch on x86-64 with GCC, as superset_kernel.cpp (the clones compute the same
// IEEE operations: no FMA, -ffp-contract=off); clang has no target_clones on templates.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_QP_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_QP_CLONES
#endif
#define PDD_QP_INLINE static inline __attribute__((always_inline))

constexpr double kInf = std::numeric_limits<double>::infinity();

// c_m (case 1) and c_km (case 2), qp_lower_bound.h.
constexpr double c_static(int m) { return double(m) / (4.0 * (5 - m)); }
constexpr double c_deform(int k, int m) { return double(k * m) / (4.0 * (5 * (k + m) - 2 * k * m)); }

PDD_QP_INLINE double mx(double a, double b) { return a > b ? a : b; }
PDD_QP_INLINE double mn(double a, double b) { return a < b ? a : b; }
// d² for d > 2^-500, else 0 (NaN: 0); qp_lower_bound.h, range.
PDD_QP_INLINE double pos_sq(double d) { return d > 0x1p-500 ? d * d : 0.0; }

// The bound of one oriented entry for case K, before the factor kLowerSafety / n.n: A's three
// highest heights a0 >= a1 >= a2, B's heights ascending b0 <= .. <= b3, ε of the entry.
template <QpCase K>
PDD_QP_INLINE double dual_bound(double a0, double a1, double a2, double b0, double b1, double b2,
                                double b3, double eps) {
  // means of B's m lowest (m <= 4 in case 1, <= 3 in case 2), of A's k highest (k <= 3)
  const double sB2 = b0 + b1, sB3 = sB2 + b2;
  const double mB1 = b0, mB2 = sB2 * 0.5, mB3 = sB3 * (1.0 / 3.0);
  const double a = a0 - eps;  // d = (mean_A − ε) − mean_B (qp_lower_bound.h)
  if constexpr (K == QpCase::Static) {
    const double mB4 = (sB3 + b3) * 0.25;
    return mx(mx(c_static(1) * pos_sq(a - mB1), c_static(2) * pos_sq(a - mB2)),
              mx(c_static(3) * pos_sq(a - mB3), c_static(4) * pos_sq(a - mB4)));
  } else {
    const double e2 = (a0 + a1) * 0.5 - eps, e3 = ((a0 + a1) + a2) * (1.0 / 3.0) - eps;
    const double d1 = mx(mx(c_deform(1, 1) * pos_sq(a - mB1), c_deform(1, 2) * pos_sq(a - mB2)),
                         c_deform(1, 3) * pos_sq(a - mB3));
    const double d2 = mx(mx(c_deform(2, 1) * pos_sq(e2 - mB1), c_deform(2, 2) * pos_sq(e2 - mB2)),
                         c_deform(2, 3) * pos_sq(e2 - mB3));
    const double d3 = mx(mx(c_deform(3, 1) * pos_sq(e3 - mB1), c_deform(3, 2) * pos_sq(e3 - mB2)),
                         c_deform(3, 3) * pos_sq(e3 - mB3));
    return mx(mx(d1, d2), d3);
  }
}

// ε and the factor kLowerSafety / n.n (0 when rho_n is not small), qp_lower_bound.h.
PDD_QP_INLINE double epsilon(double e_h, double Hm) {
  return 2.0002 * e_h + 32.0 * kUnitRoundoff * Hm + 0x1p-1000;
}
PDD_QP_INLINE double scale_of(double nn, double e_n) {
  return 3.0 * e_n * e_n * 0x1p23 <= nn ? kLowerSafety / nn : 0.0;
}
PDD_QP_INLINE double ab(double x) { return x < 0 ? -x : x; }

// Padding lanes (b = 6, 7) are not edge pairs.
struct PaddingMask {
  double is_pad[kLanes];
  constexpr PaddingMask() : is_pad() {
    for (int i = 0; i < kLanes; ++i) is_pad[i] = i % kLaneStride >= 6 ? 1.0 : 0.0;
  }
};
constexpr PaddingMask kPadding;

// Edge lanes. Heights as lane_candidate computes them: A {0, 0, g1, g2}, B {hx, hx, hx + q1,
// hx + q2} for +n, all negated for −n. Sorted without a network: with p >= m the two
// non-zero A heights, {0, 0, p, m} descending is (max(p,0), max(m,0), min(p,0), min(m,0)), and
// with P >= M, {hx, hx, P, M} ascending is (min(M,hx), min(P,hx), max(M,hx), max(P,hx)); for −n
// the same values negated in reverse order.
template <QpCase K>
PDD_QP_CLONES void lane_bounds(const EdgeLanes& L, double e_h, double e_n, double* __restrict out) {
  for (int i = 0; i < kLanes; ++i) {
    const double g1 = L.g1[i], g2 = L.g2[i], hx = L.hx[i];
    const double c = hx + L.q1[i], d = hx + L.q2[i];
    const double Hm = mx(mx(mx(ab(g1), ab(g2)), ab(hx)), mx(ab(c), ab(d)));
    const double eps = epsilon(e_h, Hm), f = scale_of(L.nn[i], e_n);
    const double p = mx(g1, g2), m = mn(g1, g2), P = mx(c, d), M = mn(c, d);
    const double a0 = mx(p, 0.0), a1 = mx(m, 0.0), a2 = mn(p, 0.0), a3 = mn(m, 0.0);
    const double b0 = mn(M, hx), b1 = mn(P, hx), b2 = mx(M, hx), b3 = mx(P, hx);
    const double up = dual_bound<K>(a0, a1, a2, b0, b1, b2, b3, eps);
    const double down = dual_bound<K>(-a3, -a2, -a1, -b3, -b2, -b1, -b0, eps);
    // the orientation rule (definitions §3; signs clear in a quick list): +n is a candidate unless
    // both g > 0 (flip), −n when flipped or undecidable; case 1 skips undecidable pairs
    const bool pos1 = g1 > 0.0, pos2 = g2 > 0.0, pad = kPadding.is_pad[i] != 0.0;
    const bool und = pos1 ^ pos2, skip = pad | (K == QpCase::Static && und);
    out[2 * i] = (!(pos1 & pos2) & !skip) ? up * f : kInf;
    out[2 * i + 1] = ((pos1 | pos2) & !skip) ? down * f : kInf;
  }
}

// Faces, as lanes (f): any heights, sorted by the network (0,1) (2,3) (0,2) (1,3) (1,2).
template <QpCase K>
PDD_QP_CLONES void face_bounds(const double (*ha)[8], const double (*hb)[8], const double* nn,
                               double e_h, double e_n, double* __restrict out) {
  for (int f = 0; f < 8; ++f) {
    double a0 = ha[0][f], a1 = ha[1][f], a2 = ha[2][f], a3 = ha[3][f];
    double b0 = hb[0][f], b1 = hb[1][f], b2 = hb[2][f], b3 = hb[3][f];
    const double Hm = mx(mx(mx(ab(a0), ab(a1)), mx(ab(a2), ab(a3))),
                         mx(mx(ab(b0), ab(b1)), mx(ab(b2), ab(b3))));
    double t;
    t = mx(a0, a1), a1 = mn(a0, a1), a0 = t;
    t = mx(a2, a3), a3 = mn(a2, a3), a2 = t;
    t = mx(a0, a2), a2 = mn(a0, a2), a0 = t;
    t = mx(a1, a3), a3 = mn(a1, a3), a1 = t;
    t = mx(a1, a2), a2 = mn(a1, a2), a1 = t;
    t = mn(b0, b1), b1 = mx(b0, b1), b0 = t;
    t = mn(b2, b3), b3 = mx(b2, b3), b2 = t;
    t = mn(b0, b2), b2 = mx(b0, b2), b0 = t;
    t = mn(b1, b3), b3 = mx(b1, b3), b1 = t;
    t = mn(b1, b2), b2 = mx(b1, b2), b1 = t;
    out[f] = dual_bound<K>(a0, a1, a2, b0, b1, b2, b3, epsilon(e_h, Hm)) * scale_of(nn[f], e_n);
  }
}

template <QpCase K>
void bounds_of(const QuickCandidates& q, QpLowerBounds& out) {
  const DegreeBounds db = degree_bounds(q.fb, false);  // (a quick list has no parallel pair)
  alignas(64) double ha[4][8], hb[4][8], nn[8];
  for (int f = 0; f < 8; ++f) {
    const DirectionGeometry& g = q.faces[f];
    for (int i = 0; i < 4; ++i) {
      ha[i][f] = g.hA[i];
      hb[i][f] = g.hB[i];
    }
    nn[f] = g.nn;
  }
  face_bounds<K>(ha, hb, nn, db.e_h, db.e_n, out.lo);
  lane_bounds<K>(q.edges, db.e_h, db.e_n, out.lo + 8);
}

}  // namespace

// Two 4-lane accumulators of each (GCC vector types: the plain loop was not vectorised);
// kQpEntries = 104 = 13 · 8; min of non-NaN values is exact in any order.
static_assert(kQpEntries % 8 == 0);
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));
PDD_QP_CLONES QpSplit split_at(const QpLowerBounds& b, double t) {
  const v4d tv = {t, t, t, t}, inf = {kInf, kInf, kInf, kInf};
  v4d a0 = inf, a1 = inf;
  v4l c0 = {0, 0, 0, 0}, c1 = c0;
  for (int e = 0; e < kQpEntries; e += 8) {
    v4d x0, x1;
    std::memcpy(&x0, b.lo + e, sizeof x0);
    std::memcpy(&x1, b.lo + e + 4, sizeof x1);
    const v4d y0 = x0 > tv ? x0 : inf, y1 = x1 > tv ? x1 : inf;
    a0 = y0 < a0 ? y0 : a0;
    a1 = y1 < a1 ? y1 : a1;
    c0 -= (x0 <= tv);  // (a true comparison is −1)
    c1 -= (x1 <= tv);
  }
  a0 = a1 < a0 ? a1 : a0;
  c0 += c1;
  QpSplit s{int(c0[0] + c0[1] + c0[2] + c0[3]), kInf};
  for (int j = 0; j < 4; ++j) s.above = a0[j] < s.above ? a0[j] : s.above;
  return s;
}

void qp_lower_bounds(const QuickCandidates& q, QpCase which, QpLowerBounds& out) {
  if (which == QpCase::Static)
    bounds_of<QpCase::Static>(q, out);
  else
    bounds_of<QpCase::Deformable>(q, out);
}

}  // namespace pdd::fast::detail
