// piece_region.cpp — see piece_region.h for what is dropped and why it is safe.
#include "global/piece_region.h"

#include <algorithm>
#include <cmath>

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
  int code[kLanes];  // bit 0: x close, bit 1: -x close, bit 2: x below its accuracy (header)
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
  const double far = nx * (rho + w) * (1 + 0x1p-40);
  L.tol[l] = nx * w * (1 + 0x1p-40);
  // (& | ! on ints: no branch, so that the lanes vectorise; comparisons false on NaN)
  const int close_plus = !int(mxA - mnB > far), close_minus = !int(mxB - mnA > far);
  const int bad = !(int(delta <= 0x1p-20) & int(xx >= 0x1p-900));
  L.code[l] = kLineFlags.line[l] * (close_plus | close_minus << 1 | bad << 2);
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
  constexpr TopSetTable() {
    for (unsigned c = 0; c < 4096; ++c)
      for (unsigned m = 1; m < 16; ++m) {
        bool ok = true;
        for (unsigned i = 0; i < 4; ++i)
          for (unsigned j = 0; j < 4; ++j)
            if ((m >> i & 1u) && !(m >> j & 1u) && !(c >> (3 * i + j - (j > i)) & 1u)) ok = false;
        if (ok) sets[c] |= static_cast<unsigned short>(1u << m);
      }
  }
};
constexpr TopSetTable kTopSets;
// The top sets of the heights h of lane l (up = true) or of their negations (up = false: the
// comparisons transposed, -h_i + h_j = -(h_i - h_j), exactly).
unsigned top_sets(const double (&h)[4][kLanes], int l, double tol, bool up) {
  unsigned c = 0;
  for (unsigned i = 0; i < 4; ++i)
    for (unsigned j = i + 1; j < 4; ++j) {
      const double d = h[i][l] - h[j][l];
      const unsigned ij = 3 * i + j - 1, ji = 3 * j + i;  // (i < j)
      const unsigned ge = unsigned(!(d < -tol)), le = unsigned(!(d > tol));
      c |= up ? ge << ij | le << ji : le << ij | ge << ji;
    }
  return kTopSets.sets[c];
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
  for (int l = 0; l < kLanes; ++l) {
    const int code = L.code[l];
    if (!code) continue;
    if (code & 4) return false;
    // x close: A's top sets along x and B's bottom sets (the top sets of -h_B); -x: the reverse
    if (code & 1) {
      const unsigned b = top_sets(L.hB, l, L.tol[l], false);
      for (unsigned a = top_sets(L.hA, l, L.tol[l], true); a; a &= a - 1) rows[__builtin_ctz(a)] |= b;
    }
    if (code & 2) {
      const unsigned b = top_sets(L.hB, l, L.tol[l], true);
      for (unsigned a = top_sets(L.hA, l, L.tol[l], false); a; a &= a - 1) rows[__builtin_ctz(a)] |= b;
    }
  }
  return true;
}

}  // namespace pdd::fast::detail
