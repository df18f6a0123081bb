// accurate_piece_matrix.cpp — see accurate_piece_matrix.h.
#include "global/accurate_piece_matrix.h"

#include <algorithm>
#include <cmath>

#include "certification/double_word.h"

namespace pdd::fast::global {

using detail::dw::add;
using detail::dw::DW;
using detail::dw::kU;
using detail::dw::mul;
using detail::dw::neg;

namespace {
constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
DW dw(double x) { return {x, 0.0}; }
}  // namespace

// Each subset's sums from the subset without its highest vertex (piece_enumeration.cpp's
// subset_sums).
AccurateMoments::AccurateMoments(const std::array<std::array<double, 3>, 4>& pA,
                                 const std::array<std::array<double, 3>, 4>& pB)
    : pA_(pA), pB_(pB) {
  fill(pA, pB);
}

PDD_FMA_CLONES void AccurateMoments::fill(const std::array<std::array<double, 3>, 4>& pA,
                                          const std::array<std::array<double, 3>, 4>& pB) {
  for (int k = 0; k < 3; ++k) SA[0][k] = SB[0][k] = dw(0), aSA[0][k] = aSB[0][k] = 0;
  for (int q = 0; q < 6; ++q) QA[0][q] = QB[0][q] = dw(0), aQA[0][q] = aQB[0][q] = 0;
  for (unsigned m = 1; m < 16; ++m) {
    const int i = m >= 8 ? 3 : m >= 4 ? 2 : m >= 2 ? 1 : 0;
    const unsigned rest = m & ~(1u << i);
    for (int k = 0; k < 3; ++k) {
      SA[m][k] = add(SA[rest][k], dw(pA[i][k])), aSA[m][k] = aSA[rest][k] + std::fabs(pA[i][k]);
      SB[m][k] = add(SB[rest][k], dw(pB[i][k])), aSB[m][k] = aSB[rest][k] + std::fabs(pB[i][k]);
    }
    for (int q = 0; q < 6; ++q) {
      const double a = pA[i][kR[q]] * pA[i][kC[q]], b = pB[i][kR[q]] * pB[i][kC[q]];
      QA[m][q] = add(QA[rest][q], mul(dw(pA[i][kR[q]]), dw(pA[i][kC[q]]))), aQA[m][q] = aQA[rest][q] + std::fabs(a);
      QB[m][q] = add(QB[rest][q], mul(dw(pB[i][kR[q]]), dw(pB[i][kC[q]]))), aQB[m][q] = aQB[rest][q] + std::fabs(b);
    }
  }
}

// Error (running error analysis). For each computed node z~ of the expression of M = 20 H D
// (header) let |z| be the same expression on the inputs' magnitudes with every subtraction an
// addition (aS, aQ, ... below, in doubles: within a few u of their own value). If the operands
// are within d_x |x|, d_y |y| of theirs, then for an add, |x~ + y~ − (x + y)| <= max(d_x, d_y)
// |z| and its own rounding 4u² (|x~| + |y~|) (double_word.h) <= 4u² (1 + d) |z|; for a product,
// d_x + d_y + d_x d_y plus 6.2 u² (1 + d_x)(1 + d_y). Leaves are exact (d = 0). Along the
// expression: S_X (3 adds) 12 u²; Q_X (a product, 3 adds) 18.2 u²; Cn (two integer products, an
// add) 22.2 u²; U (two more products, an add) 32.4 u²; S 16 u²; k U U^T 77.2 u², d g² (Cn S^T +
// S Cn^T) 54.6 u², m g² Cn Cn^T 56.8 u², D (Q_A + Q_B) 28.4 u²; M (three adds) 89.2 u² (the d
// d terms are ~u⁴: inside the margin to 96). So |M~ − M| <= 96 u² |M|, |M| from the doubles
// with the relative 2^-40 for their roundings. Then H = fl(fl(M~.hi + M~.lo) / (20 D)): two
// roundings, <= 2u (1 + u) relative (the few u² beyond it inside the margin from 89.2 to 96).
// The absolute 2^-940 covers products' errors that may underflow (two_prod, < 2^-1075 each,
// fewer than 2^9 of them), each carried through later products by at most the coefficients
// (< 2^13) times the sums' magnitudes (< 2^110: the double path's |coordinates| < 2^102,
// global_depth.cpp): < 2^-943 in all.
PDD_FMA_CLONES bool AccurateMoments::scaled(unsigned ma, unsigned mb, DW (&Ms)[6], double (&aMs)[6], double& c20) const {
  const int mA = __builtin_popcount(ma), mB = __builtin_popcount(mb);
  if (mA == 0 || mB == 0 || ma > 15 || mb > 15) return false;
  const int g = 5 - mA, d = mA * (5 - mB) + mB * (5 - mA), m = mA + mB, k = 10 - m;
  const double D = double(d) * d * g * g, dg2 = double(d) * g * g, mg2 = double(m) * g * g;
  DW Cn[3], U[3], S[3];
  double aCn[3], aU[3], aS[3];
  for (int r = 0; r < 3; ++r) {
    Cn[r] = add(mul(dw(5 - mB), SA[ma][r]), mul(dw(5 - mA), SB[mb][r]));
    U[r] = add(mul(dw(mA), Cn[r]), neg(mul(dw(d), SA[ma][r])));
    S[r] = add(SA[ma][r], SB[mb][r]);
    aCn[r] = (5 - mB) * aSA[ma][r] + (5 - mA) * aSB[mb][r];
    aU[r] = mA * aCn[r] + d * aSA[ma][r];
    aS[r] = aSA[ma][r] + aSB[mb][r];
  }
  for (int q = 0; q < 6; ++q) {
    const int r = kR[q], c = kC[q];
    const DW cross = add(mul(Cn[r], S[c]), mul(S[r], Cn[c]));
    DW M = mul(dw(D), add(QA[ma][q], QB[mb][q]));
    M = add(M, neg(mul(dw(dg2), cross)));
    M = add(M, mul(dw(mg2), mul(Cn[r], Cn[c])));
    M = add(M, mul(dw(k), mul(U[r], U[c])));
    const double aM = D * (aQA[ma][q] + aQB[mb][q]) + dg2 * (aCn[r] * aS[c] + aS[r] * aCn[c]) +
                      mg2 * aCn[r] * aCn[c] + k * aU[r] * aU[c];
    Ms[q] = M;
    aMs[q] = aM;
  }
  c20 = 20 * D;
  return true;
}

PDD_FMA_CLONES bool AccurateMoments::matrix(unsigned ma, unsigned mb, Eigen::Matrix3d& H, double& h_error) const {
  DW M[6];
  double aM[6], c20 = 0;
  if (!scaled(ma, mb, M, aM, c20)) return false;
  constexpr double kGrow = 1 + 0x1p-40;
  h_error = 0;
  for (int q = 0; q < 6; ++q) {
    const int r = kR[q], c = kC[q];
    const double h = (M[q].hi + M[q].lo) / c20;
    H(r, c) = H(c, r) = h;
    const double err = (2 * kU * (1 + kU) * std::fabs(h) + 96 * kU * kU * aM[q] / c20) * kGrow + 0x1p-940;
    if (!std::isfinite(h) || !std::isfinite(err)) return false;
    h_error = std::max(h_error, err);
  }
  return true;
}

// The same M, then H = M / (20 D) as a double word: hi = fl(M.hi / c), the remainder M.hi - hi c
// exactly (fma: the remainder of a rounded quotient is a double), lo = fl((remainder + M.lo) /
// c), renormalised exactly (two_sum). |lo| <= 2u |H| (1 + u), and its two roundings cost
// <= 2u |lo|: within 5 u^2 |H| of M~ / c, so |v - H*| <= 96 u^2 |M| / c + 5 u^2 |H| (+ the
// absolute 2^-940, as above), the bound's own roundings in the factor 1 + 2^-40.
PDD_FMA_CLONES bool AccurateMoments::matrix(unsigned ma, unsigned mb, detail::dw::Bounded (&Hb)[3][3]) const {
  DW M[6];
  double aM[6], c20 = 0;
  if (!scaled(ma, mb, M, aM, c20)) return false;
  for (int q = 0; q < 6; ++q) {
    const int r = kR[q], c = kC[q];
    const double hi = M[q].hi / c20, lo = (std::fma(-hi, c20, M[q].hi) + M[q].lo) / c20;
    const DW v = detail::dw::two_sum(hi, lo);
    const double err = (96 * kU * kU * aM[q] / c20 + 5 * kU * kU * std::fabs(hi)) * (1 + 0x1p-40) + 0x1p-940;
    if (!std::isfinite(v.hi) || !std::isfinite(v.lo) || !std::isfinite(err)) return false;
    Hb[r][c] = Hb[c][r] = detail::dw::Bounded{v, err};
  }
  return true;
}

}  // namespace pdd::fast::global
