// piece_region.cpp — see piece_region.h for what is dropped and why it is safe.
#include "global/piece_region.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pdd::fast::detail {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_REGION_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_REGION_CLONES
#endif

namespace {

constexpr double kU = 0x1p-53;
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
// The 50 lines (header) in 64 lanes: lanes 8 ea + eb, eb < 6, A's edge ea with B's edge eb
// (kEdge's order), then lanes 48 + j, j < 14: A's faces opposite vertex 0..3, B's faces, A's and
// B's opposite edge pairs, as pairs of the 12 edge vectors (0..5 A's, 6..11 B's; 12 a zero
// vector). The other lanes are padding (zero vectors, no line).
constexpr int kLanes = 64;
constexpr int kOtherF[16] = {3, 1, 0, 0, 9, 7, 6, 6, 0, 1, 2, 6, 7, 8, 12, 12};
constexpr int kOtherG[16] = {4, 2, 2, 1, 10, 8, 8, 7, 5, 4, 3, 11, 10, 9, 12, 12};
constexpr bool is_line(int l) { return l < 48 ? l % 8 < 6 : l < 62; }
struct LineFlags {
  int line[kLanes] = {};
  constexpr LineFlags() {
    for (int l = 0; l < kLanes; ++l) line[l] = is_line(l);
  }
};
constexpr LineFlags kLineFlags;

struct Lines {
  double gB[3][8];                       // B's edge vectors, lanes 6 and 7 zero
  double f[3][16], g[3][16];             // the other lines' two edges
  double hA[4][kLanes], hB[4][kLanes];  // the vertices' heights along the line's x, as computed
  double tol[kLanes];                    // |x| w (1 + 2^-40), w = M (3.47 delta + 16u) (header)
  // bit 0: x close, bit 1: -x close, bit 2: x below its accuracy, or D along x or -x not
  // certainly positive (header); 0 on padding lanes
  int code[kLanes];
};

// One line's cross product x = f x g, accuracy, closeness and heights (header), into lane l.
inline __attribute__((always_inline)) void line_lane(Lines& __restrict L, int l, double f0, double f1, double f2,
                                                     double g0, double g1, double g2, const double (&pA)[4][3],
                                                     const double (&pB)[4][3], double M, double rho) {
  const double p0 = f1 * g2, q0 = f2 * g1, p1 = f2 * g0, q1 = f0 * g2, p2 = f0 * g1, q2 = f1 * g0;
  const double x0 = p0 - q0, x1 = p1 - q1, x2 = p2 - q2;
  const double m = std::fabs(p0) + std::fabs(q0) + std::fabs(p1) + std::fabs(q1) + std::fabs(p2) + std::fabs(q2);
  const double xx = x0 * x0 + x1 * x1 + x2 * x2;
  const double nx = std::sqrt(xx);
  const double delta = 17 * kU * m / nx;  // (nx = 0: inf or NaN, bad below)
  double mxA = -INFINITY, mnA = INFINITY, mxB = -INFINITY, mnB = INFINITY;
#pragma GCC unroll 4
  for (int i = 0; i < 4; ++i) {
    const double a = pA[i][0] * x0 + pA[i][1] * x1 + pA[i][2] * x2;
    const double b = pB[i][0] * x0 + pB[i][1] * x1 + pB[i][2] * x2;
    L.hA[i][l] = a, L.hB[i][l] = b;
    mxA = std::max(mxA, a), mnA = std::min(mnA, a), mxB = std::max(mxB, b), mnB = std::min(mnB, b);
  }
  const double w = M * (3.47 * delta + 16 * kU);
  const double far = nx * (rho + w) * (1 + 0x1p-40), tol = nx * w * (1 + 0x1p-40);
  const double plus = mxA - mnB, minus = mxB - mnA;  // D along x and along -x, times |x|
  L.tol[l] = tol;
  // (& | ! on ints: no branch, so that the lanes vectorise; comparisons false on NaN)
  const int bad = !(int(delta <= 0x1p-20) & int(xx >= 0x1p-900) & int(plus > tol) & int(minus > tol));
  L.code[l] = kLineFlags.line[l] * (int(!(plus > far)) | int(!(minus > far)) << 1 | bad << 2);
}

// Every line, side by side. E: the edge vectors (E[e][k], e = 0..12).
PDD_REGION_CLONES void line_lanes(Lines& __restrict L, const double (&E)[13][3], const double (&pA)[4][3],
                                  const double (&pB)[4][3], double M, double rho) {
  for (int ea = 0; ea < 6; ++ea) {
    const double f0 = E[ea][0], f1 = E[ea][1], f2 = E[ea][2];
    for (int l = 0; l < 8; ++l) line_lane(L, 8 * ea + l, f0, f1, f2, L.gB[0][l], L.gB[1][l], L.gB[2][l], pA, pB, M, rho);
  }
  for (int l = 0; l < 16; ++l)
    line_lane(L, 48 + l, L.f[0][l], L.f[1][l], L.f[2][l], L.g[0][l], L.g[1][l], L.g[2][l], pA, pB, M, rho);
}

// The top sets of four heights h within tol: bit m (m = 1..15) set when min over m >= max over
// the rest - tol, i.e. every i in m and j outside m have h_i - h_j >= -tol. From the twelve
// comparisons (i != j, bit 3 i + j - (j > i); each difference rounded once) by a table.
struct TopSetTable {
  unsigned short sets[4096] = {};
  // (the comparisons each set needs first: a constant expression within the compilers' step
  // limits, clang's 2^20 included)
  constexpr TopSetTable() {
    unsigned need[16] = {};
    for (unsigned m = 1; m < 16; ++m)
      for (unsigned i = 0; i < 4; ++i)
        for (unsigned j = 0; j < 4; ++j)
          if ((m >> i & 1u) && !(m >> j & 1u)) need[m] |= 1u << (3 * i + j - (j > i));
    for (unsigned c = 0; c < 4096; ++c)
      for (unsigned m = 1; m < 16; ++m)
        if ((c & need[m]) == need[m]) sets[c] |= static_cast<unsigned short>(1u << m);
  }
};
constexpr TopSetTable kTopSets;
// The comparisons of the heights h of lane l (bit 3 i + j - (j > i): h_i - h_j >= -tol) for h
// (up) and for -h (down: -h_i + h_j = -(h_i - h_j) exactly, the comparisons transposed): the
// six differences d_ij, i < j, in three pairs, each compared with -tol (ge: d >= -tol) and tol
// (le: d <= tol), true on NaN as the table's definition.
struct PairBits {  // 6 bits (pairs 01 02 03 12 13 23) to their positions ij and ji
  unsigned short ij[64] = {}, ji[64] = {};
  constexpr PairBits() {
    constexpr int kI[6] = {0, 0, 0, 1, 1, 2}, kJ[6] = {1, 2, 3, 2, 3, 3};
    for (unsigned c = 0; c < 64; ++c)
      for (int p = 0; p < 6; ++p)
        if (c >> p & 1u) {
          ij[c] |= static_cast<unsigned short>(1u << (3 * kI[p] + kJ[p] - 1));
          ji[c] |= static_cast<unsigned short>(1u << (3 * kJ[p] + kI[p]));
        }
  }
};
constexpr PairBits kPairBits;
void comparisons(const double (&h)[4][kLanes], int l, double tol, unsigned& up, unsigned& down) {
  const double h0 = h[0][l], h1 = h[1][l], h2 = h[2][l], h3 = h[3][l];
#if defined(__SSE2__)
  const __m128d d0 = _mm_sub_pd(_mm_setr_pd(h0, h0), _mm_setr_pd(h1, h2));  // h0 - h1, h0 - h2
  const __m128d d1 = _mm_sub_pd(_mm_setr_pd(h0, h1), _mm_setr_pd(h3, h2));  // h0 - h3, h1 - h2
  const __m128d d2 = _mm_sub_pd(_mm_setr_pd(h1, h2), _mm_setr_pd(h3, h3));  // h1 - h3, h2 - h3
  const __m128d lo = _mm_set1_pd(-tol), hi = _mm_set1_pd(tol);
  const unsigned ge = unsigned(_mm_movemask_pd(_mm_cmpnlt_pd(d0, lo))) |
                      unsigned(_mm_movemask_pd(_mm_cmpnlt_pd(d1, lo))) << 2 |
                      unsigned(_mm_movemask_pd(_mm_cmpnlt_pd(d2, lo))) << 4;
  const unsigned le = unsigned(_mm_movemask_pd(_mm_cmpngt_pd(d0, hi))) |
                      unsigned(_mm_movemask_pd(_mm_cmpngt_pd(d1, hi))) << 2 |
                      unsigned(_mm_movemask_pd(_mm_cmpngt_pd(d2, hi))) << 4;
#else  // (the same bits: bit p for pair p of 01 02 03 12 13 23, true on NaN)
  const double d[6] = {h0 - h1, h0 - h2, h0 - h3, h1 - h2, h1 - h3, h2 - h3};
  unsigned ge = 0, le = 0;
  for (int p = 0; p < 6; ++p) ge |= unsigned(!(d[p] < -tol)) << p, le |= unsigned(!(d[p] > tol)) << p;
#endif
  up = kPairBits.ij[ge] | kPairBits.ji[le];
  down = kPairBits.ij[le] | kPairBits.ji[ge];
}

}  // namespace

bool region_pieces(const double (&pA)[4][3], const double (&pB)[4][3], double top, unsigned (&rows)[16]) {
  if (!(top > 0) || !(top < 0x1p900)) return false;
  double M = 0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) M = std::max({M, std::fabs(pA[i][k]), std::fabs(pB[i][k])});
  double E[13][3] = {};
  for (int e = 0; e < 6; ++e)
    for (int k = 0; k < 3; ++k) {
      E[e][k] = pA[kEdge[e][1]][k] - pA[kEdge[e][0]][k];
      E[6 + e][k] = pB[kEdge[e][1]][k] - pB[kEdge[e][0]][k];
    }
  static thread_local Lines L;
  for (int l = 0; l < 8; ++l)
    for (int k = 0; k < 3; ++k) L.gB[k][l] = E[l < 6 ? 6 + l : 12][k];
  for (int l = 0; l < 16; ++l)
    for (int k = 0; k < 3; ++k) L.f[k][l] = E[kOtherF[l]][k], L.g[k][l] = E[kOtherG[l]][k];
  const double rho = std::sqrt(32 * top) * (1 + 0x1p-40);
  line_lanes(L, E, pA, pB, M, rho);
  for (int r = 0; r < 16; ++r) rows[r] = 0;
  // The lanes with a code (a few of the 64): a loop over their bits, not a test a lane (those
  // tests mispredicted about once per close lane)
  std::uint64_t coded = 0;
#if defined(__SSE2__)
  for (int l = 0; l < kLanes; l += 4) {
    const __m128i codes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(L.code + l));
    const __m128i zero = _mm_cmpeq_epi32(codes, _mm_setzero_si128());
    coded |= std::uint64_t(~unsigned(_mm_movemask_ps(_mm_castsi128_ps(zero))) & 15u) << l;
  }
#else  // (the same bits, one lane at a time)
  for (int l = 0; l < kLanes; ++l) coded |= std::uint64_t(L.code[l] != 0) << l;
#endif
  for (; coded; coded &= coded - 1) {
    const int l = __builtin_ctzll(coded);
    const int code = L.code[l];
    if (code & 4) return false;
    // x close: A's top sets along x and B's bottom sets (the top sets of -h_B); -x: the reverse
    unsigned a_up, a_down, b_up, b_down;
    comparisons(L.hA, l, L.tol[l], a_up, a_down);
    comparisons(L.hB, l, L.tol[l], b_up, b_down);
    if (code & 1) {
      const unsigned b = kTopSets.sets[b_down];
      for (unsigned a = kTopSets.sets[a_up]; a; a &= a - 1) rows[__builtin_ctz(a)] |= b;
    }
    if (code & 2) {
      const unsigned b = kTopSets.sets[b_up];
      for (unsigned a = kTopSets.sets[a_down]; a; a &= a - 1) rows[__builtin_ctz(a)] |= b;
    }
  }
  return true;
}

}  // namespace pdd::fast::detail
