// piece_screen.cpp — see piece_screen.h for what is pruned and why it is safe.
#include "global/piece_screen.h"

#include <algorithm>

namespace pdd::fast::detail {

// Run-time dispatch on x86-64 with GCC, as superset_kernel.cpp (the clones compute the same
// IEEE operations: no FMA, -ffp-contract=off).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_SCREEN_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_SCREEN_CLONES
#endif

namespace {
// surviving_pieces on the first L lanes (the same operations per lane at every L).
template <int L>
inline __attribute__((always_inline)) void surviving_lanes(const double SA[3], const double QA[6], double qa, int mA,
                                                           const ColumnsB& __restrict b, double top, double lower,
                                                           RowLanes& __restrict out) {
  constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  const double wA = 1.0 / (5 - mA), dA = double(mA);
  const double* __restrict rA = b.r[mA];
  for (int l = 0; l < L; ++l) {
    const double wB = b.w[l], mB = b.m[l];
    const double r = rA[l];  // 1 / (dA wA + mB wB)
    double C[3], TA[3], S[3];
    for (int k = 0; k < 3; ++k) {
      C[k] = (SA[k] * wA + b.S[k][l] * wB) * r;
      TA[k] = (C[k] * dA - SA[k]) * wA;
      S[k] = SA[k] + b.S[k][l];
      out.C[k][l] = C[k], out.TA[k][l] = TA[k];
    }
    const double m = dA + mB, kk = 10 - dA - mB;
    double h[6];  // 20 H
    for (int q = 0; q < 6; ++q) {
      const int rr = kR[q], cc = kC[q];
      h[q] = QA[q] + b.Q[q][l] - C[rr] * S[cc] - S[rr] * C[cc] + m * C[rr] * C[cc] + kk * TA[rr] * TA[cc];
      out.N[q][l] = h[q];
    }
    const double c = std::max({std::fabs(C[0]), std::fabs(C[1]), std::fabs(C[2])});
    const double t = std::max({std::fabs(TA[0]), std::fabs(TA[1]), std::fabs(TA[2])});
    const double sm = std::max({std::fabs(S[0]), std::fabs(S[1]), std::fabs(S[2])});
    out.n_error[l] = 0x1p-39 * (qa + b.q[l] + 2 * c * sm + m * c * c + kk * t * t);  // (header)
  }
  // The counts in a second lane loop over the stored matrices: one loop doing both keeps more
  // values live than AVX2's 16 vector registers hold, and its spills cost more than the
  // reloads here (the same operations on the same values: the same bits).
  for (int l = 0; l < L; ++l) {
    const double h[6] = {out.N[0][l], out.N[1][l], out.N[2][l], out.N[3][l], out.N[4][l], out.N[5][l]};
    const Edges e = window_edges(top, lower, out.n_error[l]);
    const int below_top = eigenvalues_below_certain(h[0], h[1], h[2], h[3], h[4], h[5], e.hi);
    const int below_low = eigenvalues_below_certain(h[0], h[1], h[2], h[3], h[4], h[5], e.lo);
    out.keep[l] = !(below_top == 0 || (below_top > 0 && below_top == below_low));
    out.one[l] = below_low >= 0 && below_top == below_low + 1;
    out.below_low[l] = below_low;
    out.below_top[l] = below_top;
  }
}

PDD_SCREEN_CLONES void surviving_4(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b,
                                   double top, double lower, RowLanes& out) {
  surviving_lanes<4>(SA, QA, qa, mA, b, top, lower, out);
}
PDD_SCREEN_CLONES void surviving_8(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b,
                                   double top, double lower, RowLanes& out) {
  surviving_lanes<8>(SA, QA, qa, mA, b, top, lower, out);
}
PDD_SCREEN_CLONES void surviving_12(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b,
                                    double top, double lower, RowLanes& out) {
  surviving_lanes<12>(SA, QA, qa, mA, b, top, lower, out);
}
PDD_SCREEN_CLONES void surviving_16(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b,
                                    double top, double lower, RowLanes& out) {
  surviving_lanes<16>(SA, QA, qa, mA, b, top, lower, out);
}
}  // namespace

void surviving_pieces(const double SA[3], const double QA[6], double qa, int mA, const ColumnsB& b, int lanes,
                      double top, double lower, RowLanes& out) {
  switch (lanes) {
    case 4: return surviving_4(SA, QA, qa, mA, b, top, lower, out);
    case 8: return surviving_8(SA, QA, qa, mA, b, top, lower, out);
    case 12: return surviving_12(SA, QA, qa, mA, b, top, lower, out);
    default: return surviving_16(SA, QA, qa, mA, b, top, lower, out);
  }
}

PDD_SCREEN_CLONES void screen(ScreenLanes& __restrict S, const double (&pA)[4][3], const double (&pB)[4][3],
                              double floor, double top, double lower) {
  constexpr int kNewton = 16;
  // The lanes run in whole 8-lane vectors: up to 7 padding lanes (copies of the last piece,
  // their verdicts unused) instead of the vectorised loops' scalar remainder (a lane there
  // costs as much as a vector: the screen took ~45 ns per piece before).
  if (S.n <= 0) return;
  const int n = (S.n + 7) & ~7;  // <= ScreenLanes::kMax (232 = 29 * 8 >= 225)
  for (int p = S.n; p < n; ++p) {
    const int q = S.n - 1;
    for (int k = 0; k < 6; ++k) S.N[k][p] = S.N[k][q];
    for (int k = 0; k < 3; ++k) S.C[k][p] = S.C[k][q], S.TA[k][p] = S.TA[k][q];
    for (int k = 0; k < 8; ++k) S.sign[k][p] = S.sign[k][q];
    S.n_error[p] = S.n_error[q], S.below_low[p] = S.below_low[q], S.one[p] = S.one[q];
  }
  double a[ScreenLanes::kMax], b[ScreenLanes::kMax], d[ScreenLanes::kMax], lo[ScreenLanes::kMax],
      hi[ScreenLanes::kMax], x[ScreenLanes::kMax], x0[ScreenLanes::kMax], x1[ScreenLanes::kMax],
      clear_lo[ScreenLanes::kMax], clear_hi[ScreenLanes::kMax];
  int lo_positive[ScreenLanes::kMax], done[ScreenLanes::kMax];
  int narrow = 0;  // some window narrower than kNarrowWindow n_error
  for (int p = 0; p < n; ++p) {
    const double h00 = S.N[0][p], h01 = S.N[1][p], h02 = S.N[2][p], h11 = S.N[3][p], h12 = S.N[4][p],
                 h22 = S.N[5][p];
    a[p] = h00 + h11 + h22;
    b[p] = h00 * h11 - h01 * h01 + h00 * h22 - h02 * h02 + h11 * h22 - h12 * h12;
    d[p] = h00 * (h11 * h22 - h12 * h12) - h01 * (h01 * h22 - h12 * h02) + h02 * (h01 * h12 - h11 * h02);
    const Edges e = window_edges(top, lower, S.n_error[p]);
    lo[p] = e.lo, hi[p] = e.hi;
    clear_lo[p] = e.lo, clear_hi[p] = e.hi;
    x0[p] = lo[p], x1[p] = hi[p], x[p] = 0.5 * (lo[p] + hi[p]);
    lo_positive[p] = int(S.below_low[p]) % 2 == 0;  // f > 0 at lo
    done[p] = 0;
    narrow |= int(hi[p] - lo[p] < kNarrowWindow * S.n_error[p]);
  }
  // [clear_lo, clear_hi): the window widened by g = kClearWidening tr N on both sides where the
  // counts show no eigenvalue of N in the margins (header: the other eigenvalues' gap); only
  // when some window is narrow enough for it to matter (a shallow contact's), else the window
  if (narrow) {
    for (int p = 0; p < n; ++p) {
      const double g = kClearWidening * a[p], l2 = lo[p] - g, h2 = hi[p] + g;
      const double h00 = S.N[0][p], h01 = S.N[1][p], h02 = S.N[2][p], h11 = S.N[3][p], h12 = S.N[4][p],
                   h22 = S.N[5][p];
      const int below = int(S.below_low[p]);
      const int clear = int(g > 0) & int(below >= 0) &
                        int(eigenvalues_below_certain(h00, h01, h02, h11, h12, h22, l2) == below) &
                        int(eigenvalues_below_certain(h00, h01, h02, h11, h12, h22, h2) == below + 1);
      clear_lo[p] = clear ? l2 : lo[p];
      clear_hi[p] = clear ? h2 : hi[p];
    }
  }
  for (int it = 0; it < kNewton; ++it) {
    for (int p = 0; p < n; ++p) {
      const double xp = x[p];
      const double f = ((-xp + a[p]) * xp - b[p]) * xp + d[p], df = (-3 * xp + 2 * a[p]) * xp - b[p];
      const bool on_lo_side = (f > 0) == bool(lo_positive[p]);
      const double y0 = on_lo_side ? xp : x0[p], y1 = on_lo_side ? x1[p] : xp;
      double next = xp - f / df;
      next = next > y0 && next < y1 ? next : 0.5 * (y0 + y1);
      const double eps = 0x1p-24 * (hi[p] - lo[p]);
      const bool stop = f == 0 || std::fabs(next - xp) <= eps || y1 - y0 <= eps;
      const bool moving = !done[p];
      x0[p] = moving ? y0 : x0[p], x1[p] = moving ? y1 : x1[p];
      x[p] = moving && f != 0 ? next : xp;
      done[p] = done[p] | int(stop);
    }
    int all_done = 1;
    for (int p = 0; p < n; ++p) all_done &= done[p];
    if (all_done) break;
  }
  for (int p = 0; p < n; ++p) {
    const double mu = x[p];
    const double m00 = S.N[0][p] - mu, m01 = S.N[1][p], m02 = S.N[2][p], m11 = S.N[3][p] - mu,
                 m12 = S.N[4][p], m22 = S.N[5][p] - mu;
    // rows r0 = (m00 m01 m02), r1 = (m01 m11 m12), r2 = (m02 m12 m22); r0 x r1, r0 x r2, r1 x r2
    const double a0 = m01 * m12 - m02 * m11, a1 = m02 * m01 - m00 * m12, a2 = m00 * m11 - m01 * m01;
    const double b0 = m01 * m22 - m02 * m12, b1 = m02 * m02 - m00 * m22, b2 = m00 * m12 - m01 * m02;
    const double c0 = m11 * m22 - m12 * m12, c1 = m12 * m02 - m01 * m22, c2 = m01 * m12 - m11 * m02;
    const double na = a0 * a0 + a1 * a1 + a2 * a2, nb = b0 * b0 + b1 * b1 + b2 * b2,
                 nc = c0 * c0 + c1 * c1 + c2 * c2;
    // the largest (the first of equals), by single selects (nested ones stop the vectoriser)
    double big = na, x0_ = a0, x1_ = a1, x2_ = a2;
    const bool take_b = nb > big;
    big = take_b ? nb : big, x0_ = take_b ? b0 : x0_, x1_ = take_b ? b1 : x1_, x2_ = take_b ? b2 : x2_;
    const bool take_c = nc > big;
    big = take_c ? nc : big, x0_ = take_c ? c0 : x0_, x1_ = take_c ? c1 : x1_, x2_ = take_c ? c2 : x2_;
    const double nv = std::sqrt(big);
    const double inv = (int(big >= 0x1p-900) & int(nv < HUGE_VAL)) ? 1 / nv : 0.0;  // 0: not resolved
    const double v0 = x0_ * inv, v1 = x1_ * inv, v2 = x2_ * inv;
    const double w0 = m00 * v0 + m01 * v1 + m02 * v2;
    const double w1 = m01 * v0 + m11 * v1 + m12 * v2;
    const double w2 = m02 * v0 + m12 * v1 + m22 * v2;
    const double spread = std::fabs(m00 * v0) + std::fabs(m01 * v1) + std::fabs(m02 * v2) +
                          std::fabs(m01 * v0) + std::fabs(m11 * v1) + std::fabs(m12 * v2) +
                          std::fabs(m02 * v0) + std::fabs(m12 * v1) + std::fabs(m22 * v2);
    const double res = (std::sqrt(w0 * w0 + w1 * w1 + w2 * w2) * (1 + 3 * kScreenU) + 5 * kScreenU * spread) /
                       (1 - 5 * kScreenU) * (1 + 4 * kScreenU);
    const double e3 = 3 * S.n_error[p] * (1 + 4 * kScreenU);  // |E|_2 bound (header)
    const double delta = std::min(mu - clear_lo[p], clear_hi[p] - mu) * (1 - 4 * kScreenU) - e3;
    const double sin_t = (res + e3) * (1 + 4 * kScreenU) / delta;
    const double slack = std::sqrt(2.0) * sin_t + 8 * kScreenU;
    const double C0 = S.C[0][p], C1 = S.C[1][p], C2 = S.C[2][p], T0 = S.TA[0][p], T1 = S.TA[1][p],
                 T2 = S.TA[2][p];
    int violated_plus = 0, violated_minus = 0;
    auto condition = [&](double l0, double l1, double l2, double sign) {
      const double n1 = std::fabs(l0) + std::fabs(l1) + std::fabs(l2);
      const double lv = sign * (l0 * v0 + l1 * v1 + l2 * v2);
      const double beyond = floor + n1 * slack;  // (header: certainly outside the cone)
      violated_plus |= int(lv < -beyond);
      violated_minus |= int(-lv < -beyond);
    };
#pragma GCC unroll 4
    for (int i = 0; i < 4; ++i)  // (unrolled, so that the lane loop vectorises)
      condition((pA[i][0] - C0) - T0, (pA[i][1] - C1) - T1, (pA[i][2] - C2) - T2, S.sign[i][p]);
#pragma GCC unroll 4
    for (int i = 0; i < 4; ++i)
      condition((C0 - pB[i][0]) - T0, (C1 - pB[i][1]) - T1, (C2 - pB[i][2]) - T2, S.sign[4 + i][p]);
    // (& on ints: no branch, so that the loop vectorises)
    const int skip = S.one[p] & int(mu > lo[p]) & int(mu < hi[p]) & int(inv > 0) & int(delta > 0) &
                     int(sin_t <= 1e-3) & int(spread >= 0x1p-900) & violated_plus & violated_minus;
    S.keep[p] = 1 - skip;
  }
}

}  // namespace pdd::fast::detail
