// piece_enumeration.cpp — see piece_enumeration.h for what it computes and H_S's equation.
#include "global/piece_enumeration.h"

#include <Eigen/Eigenvalues>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <climits>
#include <optional>
#include <cmath>
#include <type_traits>

#include "exact/expansion.h"
#include "global/accurate_piece_matrix.h"
#include "global/eigen_polish.h"
#include "global/piece_region.h"
#include "global/piece_screen.h"

namespace pdd::fast::global {
namespace {

using detail::ColumnsB;
using detail::kPopcount;
using detail::kSignOf;
using detail::RowLanes;
using detail::ScreenLanes;
using detail::screen;
using detail::surviving_pieces;

// kSmallSets[mA]: the sets mb of B with mA + |mb| <= 3 (bit mb), the pieces (S_A, S_B) with
// |S_A| = mA whose H_S has structural zero eigenvalues (4 - |S| of them).
struct SmallSets {
  unsigned sets[5] = {};
  constexpr SmallSets() {
    for (int mA = 0; mA <= 4; ++mA)
      for (unsigned mb = 1; mb < 16; ++mb)
        if (mA + kPopcount[mb] <= 3) sets[mA] |= 1u << mb;
  }
  constexpr unsigned operator[](int mA) const { return sets[mA]; }
};
inline constexpr SmallSets kSmallSets;

// B's sets in the order of the lanes (columns(): by size, then value) and each set's rank in it;
// kByRank[lo|hi][bits]: a set mask's bits moved to their ranks (bit rank[mb] for bit mb), for
// the last needed lane (survivors_double: the lanes keep that order, less the sets not in use).
inline constexpr unsigned char kBySize[15] = {1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14, 15};
struct ByRank {
  unsigned short lo[256] = {}, hi[256] = {};
  constexpr ByRank() {
    int rank[16] = {};
    for (int r = 0; r < 15; ++r) rank[kBySize[r]] = r;
    for (unsigned m = 0; m < 256; ++m)
      for (int b = 0; b < 8; ++b) {
        if (!(m >> b & 1u)) continue;
        if (b > 0) lo[m] = static_cast<unsigned short>(lo[m] | 1u << rank[b]);
        hi[m] = static_cast<unsigned short>(hi[m] | 1u << rank[8 + b]);
      }
  }
};
inline constexpr ByRank kByRank;

// kInverse[k] = 1 / k (k = 1..5), each correctly rounded as the division at run time: a lane's
// w = 1 / (5 - |mb|) without a division per column.
inline constexpr double kInverse[6] = {0, 1.0 / 1, 1.0 / 2, 1.0 / 3, 1.0 / 4, 1.0 / 5};

// A coordinate as a double: itself, or a rational rounded once.
struct AsDouble {
  double operator()(double x) const { return x; }
  double operator()(const detail::Q& x) const { return x.get_d(); }
};

// The 16 subsets' sums and second moments (xx xy xz yy yz zz) of A's and B's positions, each
// from the subset without its highest vertex i: the terms added in increasing i, from 0 (the
// same roundings as summing each subset on its own).
template <class T>
void subset_sums(const std::array<std::array<T, 3>, 4>& pA, const std::array<std::array<T, 3>, 4>& pB,
                 std::array<T, 3> (&SA)[16], std::array<T, 3> (&SB)[16], std::array<T, 6> (&QA)[16],
                 std::array<T, 6> (&QB)[16]) {
  constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  SA[0] = SB[0] = {T(0), T(0), T(0)};
  QA[0].fill(T(0)), QB[0].fill(T(0));
  for (unsigned m = 1; m < 16; ++m) {
    const int i = m >= 8 ? 3 : m >= 4 ? 2 : m >= 2 ? 1 : 0;
    const unsigned rest = m & ~(1u << i);
    for (int k = 0; k < 3; ++k) SA[m][k] = SA[rest][k] + pA[i][k], SB[m][k] = SB[rest][k] + pB[i][k];
    for (int q = 0; q < 6; ++q)
      QA[m][q] = QA[rest][q] + pA[i][kR[q]] * pA[i][kC[q]], QB[m][q] = QB[rest][q] + pB[i][kR[q]] * pB[i][kC[q]];
  }
}

// Doubles, by subset as lanes (lane m: subset m): the same operations, each subset's sum from
// the subset without its highest vertex (the lanes [2^i, 2^(i+1)) from [0, 2^i), i = 0..3), so
// that each step vectorises; and qmax[m], the largest |second moment| of subset m.
struct SubsetLanes {
  double s[3][16], q[6][16], qmax[16];
};
void subset_lanes(const std::array<std::array<double, 3>, 4>& p, SubsetLanes& out) {
  constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 3; ++k) out.s[k][0] = 0;
  for (int q = 0; q < 6; ++q) out.q[q][0] = 0;
#pragma GCC unroll 4
  for (int i = 0; i < 4; ++i) {
    const int w = 1 << i;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < w; ++l) out.s[k][w + l] = out.s[k][l] + p[i][k];
    for (int q = 0; q < 6; ++q) {
      const double x = p[i][kR[q]] * p[i][kC[q]];
      for (int l = 0; l < w; ++l) out.q[q][w + l] = out.q[q][l] + x;
    }
  }
  for (int m = 0; m < 16; ++m) {
    double x = std::fabs(out.q[0][m]);
    for (int q = 1; q < 6; ++q) x = std::max(x, std::fabs(out.q[q][m]));
    out.qmax[m] = x;
  }
}

// The exact zero eigenvalues of a piece's H_S on the enumeration's own vertices pA, pB (the
// points its H is built from): 3 - dim aff(S), S's active vertices. 20 H_S = sum_S (C - x)(C -
// x)^T + k T_A T_A^T with C an affine combination of S's vertices and T_A a combination of their
// differences (piece_enumeration.h), so H_S's range lies in the directions of aff(S), and as a
// sum of outer products with positive weights of vectors spanning them it has that rank: the
// generic count 4 - |S| (|S| <= 3 points span at most |S| - 1 directions) plus one for each
// direction the points fail to span, exactly. Blocks stacked on each other's columns put a vertex
// of A on the line of a vertical edge of B (three active vertices on one line: two exact zeros,
// not one); the third eigenvalue, ~1e-17 |H| as computed, is then 0, not a stationary value in
// a resting contact's window. Decided by exact signs (expansion.h: differences, their cross
// products, and the triple product against the plane's normal); `generic` where an expansion
// does not fit or a coordinate lies outside its exact range (nothing is claimed then).
int affine_zeros(const Corners<double>& pA, const Corners<double>& pB, unsigned ma, unsigned mb, int generic) {
  if (!detail::in_exact_range(pA, pB)) return generic;
  Vec3d x[8];
  int m = 0;
  for (int i = 0; i < 4; ++i)
    if (ma >> i & 1u) x[m++] = pA[i];
  for (int i = 0; i < 4; ++i)
    if (mb >> i & 1u) x[m++] = pB[i];
  int p = -1;  // a point off x[0]
  for (int i = 1; i < m && p < 0; ++i)
    if (x[i] != x[0]) p = i;
  if (p < 0) return 3;  // (one point: dim 0)
  const detail::ExpVec dp = detail::difference(x[p], x[0]);
  detail::ExpVec n;
  int q = -1;  // a point off the line x[0] x[p]
  for (int i = 1; i < m && q < 0; ++i) {
    if (i == p) continue;
    const detail::ExpVec c = detail::cross(dp, detail::difference(x[i], x[0]));
    if (!c.ok()) return generic;
    if (c.x[0].sign() != 0 || c.x[1].sign() != 0 || c.x[2].sign() != 0) n = c, q = i;
  }
  if (q < 0) return std::max(generic, 2);  // on one line
  for (int i = 1; i < m; ++i) {
    if (i == p || i == q) continue;
    const detail::Expansion d = detail::dot(n, detail::difference(x[i], x[0]));
    if (!d.ok) return generic;
    if (d.sign() != 0) return generic;  // (three directions: no zero)
  }
  return std::max(generic, 1);  // in one plane
}

// One piece's geometry (relaxed_pieces.h's closed form: c = C.n, T_A = TA.n = -T_B), its
// 20 H's moments' combination H (exact or in doubles), and (exact path) the power of two pe
// its double matrix is scaled by.
template <class T>
struct PieceGeometry {
  unsigned ma = 0, mb = 0;
  int mA = 0, mB = 0;
  std::array<T, 3> C, TA, S;
  T h[3][3];
  long pe = 0;
  // Exact path on the integer sums (PieceEnumeration::build_integers): C = NC / (d 2^E), T_A =
  // NT / (d f 2^E); d = 0 where not built so.
  struct Integers {
    mpz_class NC[3], NT[3];
    long d = 0, f = 0;
  };
  std::conditional_t<std::is_same_v<T, double>, char, Integers> ints{};
};

// The enumeration of enumerate_pieces (below) over one pair: the subset sums, the pieces that
// survive the pruning, and each survivor's H and conditions for consider_piece.
template <class T, class ToDouble>
class PieceEnumeration {
  static constexpr bool kExact = !std::is_same_v<T, double>;
  using TV = std::array<T, 3>;
  using M6 = std::array<T, 6>;  // xx xy xz yy yz zz
  static constexpr int kR[6] = {0, 0, 0, 1, 1, 2}, kC[6] = {0, 1, 2, 1, 2, 2};
  static TV vadd(const TV& a, const TV& b) { return TV{a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
  static TV vsub(const TV& a, const TV& b) { return TV{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
  static TV vmul(const TV& a, const T& s) { return TV{a[0] * s, a[1] * s, a[2] * s}; }

 public:
  PieceEnumeration(const Corners<T>& pA, const Corners<T>& pB, const Search& search, ToDouble to_d)
      : pA(pA), pB(pB), search(search), P(search.P), best(search.best), to_d(to_d) {}

  void run() {
    sums();
    if constexpr (kExact) survivors_exact();
    else survivors_double();
    const unsigned offA = ~search.contact & 0xFu, offB = ~search.contact >> 4 & 0xFu;
    for (unsigned ma = 1; ma < 16; ++ma) {
      if (ma & offA) continue;
      for (unsigned bits = survivors[ma]; bits; bits &= bits - 1) {
        const unsigned mb = unsigned(__builtin_ctz(bits));
        if (!(mb & offB)) visit(ma, mb);
      }
    }
  }

 private:
  double amax(const TV& x) const {
    double m = 0;
    for (const T& c : x) m = std::max(m, std::fabs(to_d(c)));
    return m;
  }

  // The pieces' double matrices N = 20 H by rows (surviving_pieces), with their eigenvalue
  // counts at the window's edges. Double path: on its own sums. Exact path: on the exact
  // positions rounded once (|x| < 4 here), each coordinate within u |x| of the exact one;
  // that moves the exact 20 H by at most 704 u L^2 per entry (C moves by <= u L and each C - a
  // by <= 2u L, |C - a| <= 2L: 8u L^2 per outer product, <= 8 of them; T_A = wA sum (C - a)
  // moves by <= 2u L mA wA, |T_A| <= 2L mA wA, so k T_A T_A^T by <= 8 k wA^2 mA^2 u L^2 <=
  // 640u L^2 (mA = 4: k <= 5, wA = 1)), inside the 2^14 u mag of n_error (piece_screen.h's
  // count, 10720u L^2 + 9u mag, leaves 5655u L^2 with mag >= L^2): the counts hold for the
  // exact H too.
  void sums() {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) dA[i][k] = to_d(pA[i][k]), dB[i][k] = to_d(pB[i][k]);
    subset_lanes(dA, sa), subset_lanes(dB, sb);
    if constexpr (kExact) {
      if (!integer_sums()) subset_sums(pA, pB, xSA, xSB, xQA, xQB);
    }
    top = best.value_in(0) * (1 - kPrune);
  }

  // Exact path: the positions as integers over one power of two, X = x 2^E (the coordinates are
  // dyadic: differences of doubles, scaled by a power of two), and the subsets' sums and second
  // moments of those integers (units 2^-E and 2^-2E); false (the rationals' sums are taken) where
  // a coordinate's denominator is not a power of two.
  bool integer_sums() {
    if constexpr (kExact) {
      long e = 0;
      for (const Corners<T>* side : {&pA, &pB})
        for (const auto& x : *side)
          for (const T& c : x) {
            const mpz_srcptr den = c.get_den_mpz_t();
            const long bits = long(mpz_sizeinbase(den, 2)) - 1;
            if (long(mpz_scan1(den, 0)) != bits) return false;  // (not a power of two)
            e = std::max(e, bits);
          }
      ints.E = e;
      auto lanes = [&](const Corners<T>& p, mpz_class (&x)[4][3], mpz_class (&s)[16][3], mpz_class (&q)[16][6]) {
        for (int i = 0; i < 4; ++i)
          for (int k = 0; k < 3; ++k) {
            const long bits = long(mpz_sizeinbase(p[i][k].get_den_mpz_t(), 2)) - 1;
            mpz_mul_2exp(x[i][k].get_mpz_t(), p[i][k].get_num_mpz_t(), static_cast<mp_bitcnt_t>(ints.E - bits));
          }
        for (int k = 0; k < 3; ++k) s[0][k] = 0;
        for (int r = 0; r < 6; ++r) q[0][r] = 0;
        for (unsigned m = 1; m < 16; ++m) {  // (as subset_sums: from m without its highest vertex)
          const int i = m >= 8 ? 3 : m >= 4 ? 2 : m >= 2 ? 1 : 0;
          const unsigned rest = m & ~(1u << i);
          for (int k = 0; k < 3; ++k) mpz_add(s[m][k].get_mpz_t(), s[rest][k].get_mpz_t(), x[i][k].get_mpz_t());
          for (int r = 0; r < 6; ++r) {
            q[m][r] = q[rest][r];
            mpz_addmul(q[m][r].get_mpz_t(), x[i][kR[r]].get_mpz_t(), x[i][kC[r]].get_mpz_t());
          }
        }
      };
      lanes(pA, ints.XA, ints.SA, ints.QA), lanes(pB, ints.XB, ints.SB, ints.QB);
      integers = true;
    }
    return true;
  }

  // B's sets of `sets` (bit mb) as the lanes of cols, by size then value (the sets a row drops
  // as dominated, the larger ones, come last: a row then needs fewer lanes), padded with the
  // empty set to a multiple of 4 lanes; lane[mb] is set mb's lane.
  void columns(unsigned sets) {
    int n = 0;
    for (int& l : lane) l = 0;
    for (unsigned mb : kBySize)
      if (sets >> mb & 1u) column(n++, mb);
    cols.lanes = (n + 3) & ~3;
    while (n < cols.lanes) column(n++, 0);
  }
  void column(int l, unsigned mb) {
    for (int k = 0; k < 3; ++k) cols.S[k][l] = sb.s[k][mb];
    for (int q = 0; q < 6; ++q) cols.Q[q][l] = sb.q[q][mb];
    cols.q[l] = sb.qmax[mb];
    cols.m[l] = kPopcount[mb];
    cols.w[l] = kInverse[5 - kPopcount[mb]];
    for (int mA = 1; mA <= 4; ++mA) cols.r[mA][l] = detail::kLaneR.r[mA][mb];
    cols.mb[l] = static_cast<unsigned char>(mb);
    lane_set[l] = int(1u << mb & 0xFFFEu);
    if (mb) lane[mb] = l;
  }
  // The sets (bit mb) of the lanes l < n (a multiple of 4) of x equal to 0 (zero) or not, from
  // lane_set[l] = bit cols.mb[l] (0 on padding lanes), 4 lanes a step.
  unsigned sets_where(const int (&x)[16], int n, bool zero) const {
#if defined(__SSE2__)
    __m128i acc = _mm_setzero_si128();
    for (int l = 0; l < n; l += 4) {
      const __m128i z = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + l)), _mm_setzero_si128());
      const __m128i set = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane_set + l));
      acc = _mm_or_si128(acc, zero ? _mm_and_si128(z, set) : _mm_andnot_si128(z, set));
    }
    acc = _mm_or_si128(acc, _mm_shuffle_epi32(acc, 0x4E));
    acc = _mm_or_si128(acc, _mm_shuffle_epi32(acc, 0xB1));
    return unsigned(_mm_cvtsi128_si32(acc));
#else  // (the same bits, one lane at a time)
    unsigned sets = 0;
    for (int l = 0; l < n; ++l) sets |= unsigned(lane_set[l]) & (0u - unsigned((x[l] == 0) == zero));
    return sets;
#endif
  }

  // Pieces above the window. A piece's G_S(n) = n^T H_S n is the least object norm of a
  // deformation putting S's vertices on one plane of normal n (the equality QP of the active
  // set, its other constraints dropped); adding a vertex to S adds a constraint, so S within S'
  // gives H_S' - H_S positive semi-definite, and every eigenvalue of H_S' is at least H_S's
  // smallest. surviving_pieces' count below_top == 0 certifies that the exact 20 H_S (of the
  // same centred vertices as every piece) has no eigenvalue below 20 top (window_edges: its
  // edge lies above 20 top by more than H_S's error): then no superset of S has an exact
  // eigenvalue in the window either, and such a piece is dropped as surviving_pieces drops its
  // own (no stationary value in the window, piece_screen.h). The rows go by increasing ma, so
  // that every row of a subset of ma comes first: above[ma'] holds the sets mb' of the pieces
  // (ma', mb') found above, and a row drops every set mb containing some mb' of a row ma'
  // within ma (ma' != ma; ma' = ma would need the row's own counts first): on the paper's pairs
  // ~66 pieces a pair without the region test (piece_region.h), and whole rows (all of A active,
  // most of the energy bench's contacts).
  static unsigned up_closure(unsigned sets) {  // every mb containing some mb' of sets (bit sets)
    sets |= (sets & 0x5555u) << 1;
    sets |= (sets & 0x3333u) << 2;
    sets |= (sets & 0x0F0Fu) << 4;
    sets |= (sets & 0x00FFu) << 8;
    return sets;
  }

  // Double path: the pieces outside the region of the window's top (piece_region.h) are not
  // built; every row's pieces outside the window are dropped (surviving_pieces), the rest
  // gathered and screened side by side (screen); survivors[ma] keeps the bits of the
  // pieces left for consider_piece. All use the best value offered so far (the start's): a
  // higher threshold than later ones, so nothing is dropped that a later one would keep.
  void survivors_double() {
    static thread_local ScreenLanes lanes;  // (~42 KB: off the stack)
    lanes.n = 0;
    unsigned region[16];
    {
      double qA[4][3], qB[4][3];
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) qA[i][k] = dA[i][k], qB[i][k] = dB[i][k];
      if (!detail::region_pieces(qA, qB, top, region))
        for (unsigned& r : region) r = 0xFFFEu;
    }
    unsigned all = 0;
    for (unsigned ma = 1; ma < 16; ++ma) all |= region[ma];
    columns(all & 0xFFFEu);
    unsigned above[16] = {}, reach[16] = {};  // reach[ma]: the sets above in rows strictly within ma
    // (The bookkeeping below runs fixed loops over the 4 vertices and the lanes where it can:
    // loops over a mask's set bits end at a data-dependent count, mispredicted about once a
    // loop, ~6 loops a row.)
    for (unsigned ma = 1; ma < 16; ++ma) {
      unsigned r = 0;  // (in a register: reach[ma] and reach[sub] may alias, which kept it in memory)
      for (unsigned i = 0; i < 4; ++i) {  // (the rows ma less one vertex; ma itself adds 0 here)
        const unsigned sub = ma & ~(1u << i);
        r |= reach[sub] | above[sub];
      }
      reach[ma] = r;
      const unsigned need = region[ma] & ~up_closure(r) & 0xFFFEu;
      survivors[ma] = 0;
      if (!need) continue;
      // up to the last lane needed, in 4s: the lane of need's set of highest rank (the lanes go
      // by rank)
      const unsigned ranks = kByRank.lo[need & 0xFFu] | kByRank.hi[need >> 8];
      const int n = (lane[kBySize[31 - __builtin_clz(ranks)]] + 4) & ~3;
      RowLanes row;
      surviving_pieces(row_sums(ma).data(), row_moments(ma).data(), sa.qmax[ma], kPopcount[ma], cols, n, top,
                       search.lower, row);
      // The kept pieces' and the pieces above's bits, here (SSE2, 4 lanes a step): inside
      // surviving_pieces' vector clones a call or a reduction after the lanes' vector stores
      // cost more (vectorised: 15% of the function; called from the clone, a helper left the
      // AVX-512 clone's upper registers dirty on return, no vzeroupper, and every SSE
      // instruction of the caller after it paid for that: ~40% of enumerate_pieces' own time,
      // measured with perf).
      survivors[ma] = sets_where(row.keep, n, false) & need;
      above[ma] = sets_where(row.below_top, n, true);
      // the screen's pieces: the survivors with exactly one eigenvalue in the window (the only
      // case it decides)
      const unsigned one = sets_where(row.one, n, false) & survivors[ma];
      // Of the others, a piece with structural zero eigenvalues (4 - |S| of them, |S| <= 3)
      // whose nonzero ones lie certainly above the window is dropped here, as its visit would
      // drop it (outside_window_cheaply's test, on N = 20 H within n_error as survivors_exact
      // takes it): a shallow contact's window counts the zeros in, so such pieces are never
      // `one`, ~17 a pair at 5e-7 of the size, and each visit would build its matrix first.
      for (unsigned bits = survivors[ma] & ~one & kSmallSets[kPopcount[ma]]; bits; bits &= bits - 1) {
        const unsigned mb = unsigned(__builtin_ctz(bits));
        if (nonzero_above(row, lane[mb], 4 - kPopcount[ma] - kPopcount[mb])) survivors[ma] &= ~(1u << mb);
      }
      for (unsigned bits = one; bits; bits &= bits - 1) {
        const unsigned mb = unsigned(__builtin_ctz(bits));
        const int l = lane[mb];
        const int p = lanes.n++;
        for (int q = 0; q < 6; ++q) lanes.N[q][p] = row.N[q][l];
        for (int k = 0; k < 3; ++k) lanes.C[k][p] = row.C[k][l], lanes.TA[k][p] = row.TA[k][l];
        lanes.n_error[p] = row.n_error[l], lanes.below_low[p] = row.below_low[l], lanes.one[p] = row.one[l];
        for (int i = 0; i < 4; ++i) lanes.sign[i][p] = kSignOf[ma][i], lanes.sign[4 + i][p] = kSignOf[mb][i];
        lanes.ma[p] = static_cast<unsigned char>(ma), lanes.mb[p] = static_cast<unsigned char>(mb);
      }
    }
    double qA[4][3], qB[4][3];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) qA[i][k] = dA[i][k], qB[i][k] = dB[i][k];
    screen(lanes, qA, qB, 1e-12 * P.scale, top, search.lower);
    for (int p = 0; p < lanes.n; ++p) survivors[lanes.ma[p]] &= ~(unsigned(!lanes.keep[p]) << lanes.mb[p]);
  }

  // Exact path: only the pieces whose eigenvalues all lie certainly above the window's top
  // edge or below its bottom one are dropped: such a piece holds no stationary value in the
  // window, and no wall offer either (a wall's value lies between H's two smallest
  // eigenvalues, Cauchy interlacing: above the top, or below the bottom edge); the pieces
  // with eigenvalues on both sides of the window keep their wall offers (a far vertex's
  // minimiser, consider_piece). A compact pair needs no wall offers (search.walls false,
  // global_depth.cpp): a piece with two or three active vertices (1 or 2 eigenvalues exactly 0,
  // below the window: PieceMatrix's zeros) whose other eigenvalues lie certainly above the top
  // edge holds no stationary value in the window and is dropped too, before its rational H is
  // built; on contacts made by rounding, whose windows (~1e-33 |H|) lie far below the counts'
  // resolution, those are most of the pieces. The test on N = 20 H, entries within n_error of
  // the exact 20 H (piece_screen.h; on the exact positions rounded once, as the counts).
  void survivors_exact() {
    columns(0xFFFEu);
    for (unsigned ma = 1; ma < 16; ++ma) {
      RowLanes row;
      surviving_pieces(row_sums(ma).data(), row_moments(ma).data(), sa.qmax[ma], kPopcount[ma], cols, cols.lanes, top,
                       search.lower, row);
      survivors[ma] = 0;
      for (unsigned mb = 1; mb < 16; ++mb) {
        const int l = lane[mb];
        if (row.below_top[l] == 0 || row.below_low[l] == 3) continue;
        const int zeros = std::max(0, 4 - kPopcount[ma] - kPopcount[mb]);
        if (!search.walls && zeros > 0 && nonzero_above(row, l, zeros)) continue;
        survivors[ma] |= 1u << mb;
      }
    }
  }
  bool nonzero_above(const RowLanes& row, int l, int zeros) const {  // (lane l)
    Eigen::Matrix3d N;
    for (int q = 0; q < 6; ++q) N(kR[q], kC[q]) = N(kC[q], kR[q]) = row.N[q][l];
    const double e = row.n_error[l];
    return nonzero_eigenvalues_above(N, N.norm(), e, zeros, detail::window_edges(top, search.lower, e).hi);
  }

  // A's sums and second moments of subset m in doubles (surviving_pieces' rows).
  std::array<double, 3> row_sums(unsigned m) const { return {sa.s[0][m], sa.s[1][m], sa.s[2][m]}; }
  std::array<double, 6> row_moments(unsigned m) const {
    return {sa.q[0][m], sa.q[1][m], sa.q[2][m], sa.q[3][m], sa.q[4][m], sa.q[5][m]};
  }
  // The sums and moments of the path's own type (build): exact, or the doubles'.
  TV sum_of(bool a, unsigned m) const {
    if constexpr (kExact) return a ? xSA[m] : xSB[m];
    else {
      const SubsetLanes& x = a ? sa : sb;
      return TV{x.s[0][m], x.s[1][m], x.s[2][m]};
    }
  }
  T moment_of(bool a, unsigned m, int q) const {
    if constexpr (kExact) return a ? xQA[m][q] : xQB[m][q];
    else return (a ? sa : sb).q[q][m];
  }

  // relaxed_pieces.h's closed form: c = C.n, T_A = TA.n = -T_B; 20 H by moments (above).
  void build(PieceGeometry<T>& g) const {
    if constexpr (kExact) {
      if (integers) return build_integers(g);
    }
    const unsigned ma = g.ma, mb = g.mb;
    const int mA = g.mA = kPopcount[ma], mB = g.mB = kPopcount[mb];
    const T wA = T(1) / T(5 - mA), wB = T(1) / T(5 - mB);
    const TV SA = sum_of(true, ma), SB = sum_of(false, mb);
    g.C = vmul(vadd(vmul(SA, wA), vmul(SB, wB)), T(1) / (T(mA) * wA + T(mB) * wB));
    g.TA = vmul(vsub(vmul(g.C, T(mA)), SA), wA);
    g.S = vadd(SA, SB);
    const TV &C = g.C, &TA = g.TA, &S = g.S;
    const T m = T(mA + mB), k = T(10 - mA - mB);
    for (int q = 0; q < 6; ++q) {
      const int r = kR[q], c = kC[q];
      g.h[r][c] = (moment_of(true, ma, q) + moment_of(false, mb, q) - C[r] * S[c] - S[r] * C[c] + m * C[r] * C[c] +
                   k * TA[r] * TA[c]) / T(20);
      g.h[c][r] = g.h[r][c];
    }
  }

  // build() on the integer sums (integer_sums): the same rationals, each reduced once. With f =
  // 5 - mA, d = mA (5 - mB) + mB f (clearing wA and wB), SA, SB, QA, QB the integer sums and
  // moments: C = NC / d with NC = SA (5 - mB) + SB f; T_A = NT / (d f) with NT = mA NC - d SA;
  // S = SA + SB; and 20 d^2 f^2 H = (QA + QB) d^2 f^2 - (NC S^T + S NC^T) d f^2 + m NC NC^T f^2
  // + k NT NT^T, each in units of 2^-E (vectors) or 2^-2E (H).
  void build_integers(PieceGeometry<T>& g) const {
    if constexpr (kExact) {
      const unsigned ma = g.ma, mb = g.mb;
      const int mA = g.mA = kPopcount[ma], mB = g.mB = kPopcount[mb];
      const long f = 5 - mA, d = mA * (5 - mB) + mB * f;
      mpz_class(&NC)[3] = g.ints.NC, (&NT)[3] = g.ints.NT, S[3];
      g.ints.d = d, g.ints.f = f;
      for (int k = 0; k < 3; ++k) {
        mpz_mul_si(NC[k].get_mpz_t(), ints.SA[ma][k].get_mpz_t(), 5 - mB);
        mpz_addmul_ui(NC[k].get_mpz_t(), ints.SB[mb][k].get_mpz_t(), static_cast<unsigned long>(f));
        mpz_mul_si(NT[k].get_mpz_t(), NC[k].get_mpz_t(), mA);
        mpz_submul_ui(NT[k].get_mpz_t(), ints.SA[ma][k].get_mpz_t(), static_cast<unsigned long>(d));
        mpz_add(S[k].get_mpz_t(), ints.SA[ma][k].get_mpz_t(), ints.SB[mb][k].get_mpz_t());
        set_ratio(g.C[k], NC[k], d, ints.E);
        set_ratio(g.TA[k], NT[k], d * f, ints.E);
        set_ratio(g.S[k], S[k], 1, ints.E);
      }
      const long dff = d * f * f, m = mA + mB, kk = 10 - mA - mB;
      mpz_class x, t;
      for (int q = 0; q < 6; ++q) {
        const int r = kR[q], c = kC[q];
        mpz_add(x.get_mpz_t(), ints.QA[ma][q].get_mpz_t(), ints.QB[mb][q].get_mpz_t());
        mpz_mul_si(x.get_mpz_t(), x.get_mpz_t(), d * dff);
        mpz_mul(t.get_mpz_t(), NC[r].get_mpz_t(), S[c].get_mpz_t());
        mpz_addmul(t.get_mpz_t(), S[r].get_mpz_t(), NC[c].get_mpz_t());
        mpz_submul_ui(x.get_mpz_t(), t.get_mpz_t(), static_cast<unsigned long>(dff));
        mpz_mul(t.get_mpz_t(), NC[r].get_mpz_t(), NC[c].get_mpz_t());
        mpz_addmul_ui(x.get_mpz_t(), t.get_mpz_t(), static_cast<unsigned long>(m * f * f));
        mpz_mul(t.get_mpz_t(), NT[r].get_mpz_t(), NT[c].get_mpz_t());
        mpz_addmul_ui(x.get_mpz_t(), t.get_mpz_t(), static_cast<unsigned long>(kk));
        set_ratio(g.h[r][c], x, 20 * d * dff, 2 * ints.E);
        g.h[c][r] = g.h[r][c];
      }
    }
  }
  // out = n / (den 2^e), reduced (den > 0, e >= 0).
  static void set_ratio(T& out, const mpz_class& n, long den, long e) {
    if constexpr (kExact) {
      mpz_set(mpq_numref(out.get_mpq_t()), n.get_mpz_t());
      mpz_set_ui(mpq_denref(out.get_mpq_t()), static_cast<unsigned long>(den));
      mpz_mul_2exp(mpq_denref(out.get_mpq_t()), mpq_denref(out.get_mpq_t()), static_cast<mp_bitcnt_t>(e));
      out.canonicalize();
    }
  }

  // Exact path: H rounded after scaling by 2^-pe, its largest entry near 1 (a piece of the
  // near vertices of a pair with a vertex 1e200 away has entries ~1e-400 in the pair's
  // scaled units: they would underflow). Eigenvectors do not change; eigenvalues and the
  // values they are compared with are taken in the piece's units (consider_piece).
  void rounded_matrix(PieceGeometry<T>& g, Eigen::Matrix3d& H) const {
    if constexpr (kExact) {
      g.pe = LONG_MIN;
      for (int q = 0; q < 6; ++q) g.pe = std::max(g.pe, detail::log2_estimate(g.h[kR[q]][kC[q]]));
      if (g.pe == LONG_MIN) g.pe = 0;
    }
    for (int q = 0; q < 6; ++q) {
      const int r = kR[q], c = kC[q];
      if constexpr (kExact) {
        T x = g.h[r][c];
        detail::scale_pow2(x, -g.pe);
        H(r, c) = H(c, r) = to_d(x);
      } else {
        H(r, c) = H(c, r) = to_d(g.h[r][c]);
      }
    }
  }

  double h_error(const PieceGeometry<T>& g) const {
    if constexpr (kExact) return 0;
    const double c = amax(g.C), t = amax(g.TA);
    return 0x1p-39 * (sa.qmax[g.ma] + sb.qmax[g.mb] + 2 * c * amax(g.S) + (g.mA + g.mB) * c * c + (10 - g.mA - g.mB) * t * t) /
           20;
  }

  // The conditions' vectors: in doubles, with an absolute floor for their rounding (a few
  // roundings of coordinates <= scale: far above); exact path, each scaled by its own power
  // of two before rounding once (relative error u, no floor: a condition of the near
  // vertices beside a far one would underflow or drown in an absolute floor).
  V3 rounded(TV x) const {
    if constexpr (kExact) {
      long top = LONG_MIN;
      for (const T& y : x) top = std::max(top, detail::log2_estimate(y));
      if (top != LONG_MIN)
        for (T& y : x) detail::scale_pow2(y, -top);
    }
    return V3{to_d(x[0]), to_d(x[1]), to_d(x[2])};
  }
  // The conditions' vectors d_i = a_i - c - T_A (side A) and e_j = c - b_j - T_A (side B); on
  // the integer sums, (X_i d f - NC f - NT) / (d f 2^E) and (NC f - X_j d f - NT) / (d f 2^E),
  // each reduced once (the same rationals).
  TV condition(const PieceGeometry<T>& g, bool a, int i) const {
    if constexpr (kExact) {
      if (g.ints.d != 0) {
        std::array<mpz_class, 3> n;
        condition_numerator(g, a, i, n);
        TV out;
        for (int k = 0; k < 3; ++k) set_ratio(out[k], n[k], g.ints.d * g.ints.f, ints.E);
        return out;
      }
    }
    return a ? vsub(vsub(pA[i], g.C), g.TA) : vsub(vsub(g.C, pB[i]), g.TA);
  }
  // A positive multiple of condition(g, a, i), as integers: on the integer sums its numerator;
  // else the rationals times the least common multiple of their denominators.
  void condition_integers(const PieceGeometry<T>& g, bool a, int i, std::array<mpz_class, 3>& out) const {
    if constexpr (kExact) {
      if (g.ints.d != 0) {
        condition_numerator(g, a, i, out);
        return;
      }
      const TV l = condition(g, a, i);
      mpz_class den = 1;
      for (int k = 0; k < 3; ++k) mpz_lcm(den.get_mpz_t(), den.get_mpz_t(), l[k].get_den_mpz_t());
      for (int k = 0; k < 3; ++k) {
        mpz_divexact(out[k].get_mpz_t(), den.get_mpz_t(), l[k].get_den_mpz_t());
        out[k] *= l[k].get_num();
      }
    }
  }
  // condition()'s numerators over d f 2^E (integer sums only).
  void condition_numerator(const PieceGeometry<T>& g, bool a, int i, std::array<mpz_class, 3>& out) const {
    if constexpr (kExact) {
      const long df = g.ints.d * g.ints.f;
      for (int k = 0; k < 3; ++k) {
        mpz_class& n = out[k];
        mpz_mul_si(n.get_mpz_t(), (a ? ints.XA : ints.XB)[i][k].get_mpz_t(), a ? df : -df);
        if (a) mpz_submul_ui(n.get_mpz_t(), g.ints.NC[k].get_mpz_t(), static_cast<unsigned long>(g.ints.f));
        else mpz_addmul_ui(n.get_mpz_t(), g.ints.NC[k].get_mpz_t(), static_cast<unsigned long>(g.ints.f));
        mpz_sub(n.get_mpz_t(), n.get_mpz_t(), g.ints.NT[k].get_mpz_t());
      }
    }
  }
  Conditions conditions(const PieceGeometry<T>& g) const {
    Conditions cond;
    cond.floor = kExact ? 0.0 : 1e-12 * P.scale;
    for (int i = 0; i < 4; ++i) {
      const TV d = condition(g, true, i), e = condition(g, false, i);
      cond.l[i] = rounded(d);        // d_i = a_i - c - T_A
      cond.sign[i] = kSignOf[g.ma][i];  // (tables, not selects: GCC branches on those)
      cond.l[4 + i] = rounded(e);    // e_j = c - b_j + T_B
      cond.sign[4 + i] = kSignOf[g.mb][i];
    }
    cond.finish();
    return cond;
  }

  // Exact path: eigenvector k of the piece held its signs (represented()): its exact H and
  // conditions (conditions()' vectors, exact: d_i = a_i - c - T_A, e_j = c - b_j + T_B).
  void suspect(const PieceGeometry<T>& g, int k, std::optional<IntegerMatrix>& hi) {
    if constexpr (kExact) {
      const auto& h = g.h;
      if (!hi) hi = integer_matrix(h);
      Best::Suspect x{{{{h[0][0], h[0][1], h[0][2]}, {h[1][0], h[1][1], h[1][2]}, {h[2][0], h[2][1], h[2][2]}}},
                      k, {}, *hi};
      for (int c = 0; c < 8; ++c) {
        const bool a = c < 4;
        const int i = c & 3;
        condition_integers(g, a, i, x.l[c]);
        if (!((a ? g.ma : g.mb) >> i & 1u))  // (the sign: + at an active vertex)
          for (mpz_class& y : x.l[c]) mpz_neg(y.get_mpz_t(), y.get_mpz_t());
      }
      best.suspects.push_back(std::move(x));
    }
  }

  void visit(unsigned ma, unsigned mb) {
    PieceGeometry<T> g;
    g.ma = ma, g.mb = mb;
    build(g);
    Eigen::Matrix3d H;
    rounded_matrix(g, H);
    std::optional<IntegerMatrix> hi;  // exact path: g.h over one denominator, on the first refine
    auto calls = piece_calls([&] { return conditions(g); },
                             [&](const V3& v, double mu) {
                               if constexpr (kExact) {
                                 if (!hi) hi = integer_matrix(g.h);
                                 return refine(*hi, v, mu, g.pe);
                               } else {
                                 return refine(g.h, v, mu, g.pe);
                               }
                             },
                             [&](const V3& e, const V3& f, V3 (&r)[2]) {
                               if constexpr (kExact) return ritz(g.h, e, f, r);
                               else return false;
                             },
                             [&](int k) { suspect(g, k, hi); });
    // The double H too coarse for this piece's in-window eigenvalue (consider_piece's accuracy
    // estimate: a contact far shallower than the pair): the piece again on its H to about its
    // own rounding (accurate_piece_matrix.h) before the pair goes to the exact pieces, and every
    // later piece of the pair on that H at once. The first visit's offers stand (an offer only
    // lowers the best).
    if constexpr (!kExact) {
      const int zeros = std::max(0, 4 - g.mA - g.mB);  // (PieceMatrix::zeros)
      Eigen::Matrix3d Hw;
      double ew = 0;
      // (the accurate visit's vectors as computed: PieceMatrix::accurate)
      auto accurate_calls = piece_calls([&] { return conditions(g); }, [](const V3& v, double) { return v; },
                                        [](const V3&, const V3&, V3 (&)[2]) { return false; }, [](int) {});
      // (a pair already sent to the exact pieces: the cheaper double visit, its offers only)
      // (a pair on the accurate H already: first the cheap tests on the double H, whose bounds
      // decide the pieces with structural zeros far above a shallow window, ~1,800 instructions
      // of double words each saved)
      // The visit on the accurate H; where it still cannot resolve an eigenvalue, once more with
      // the piece's exact zeros (affine_zeros) where its active vertices are degenerate: an
      // eigenvalue that is exactly 0 is not one to resolve.
      auto consider_accurate = [&] {
        consider_piece(PieceMatrix{Hw, ew, false, 0, true, zeros, &*accurate, ma, mb}, accurate_calls, search);
        if (!best.needs_exact) return;
        const int exact_zeros = affine_zeros(dA, dB, ma, mb, zeros);
        if (exact_zeros == zeros) return;
        best.needs_exact = false;
        consider_piece(PieceMatrix{Hw, ew, false, 0, true, exact_zeros, &*accurate, ma, mb}, accurate_calls, search);
      };
      if (accurate && !best.needs_exact) {
        if (outside_window(PieceMatrix{H, h_error(g), false, 0, false, zeros}, calls, search)) return;
        if (accurate->matrix(ma, mb, Hw, ew)) {
          consider_accurate();
          return;
        }
      }
      const bool needed_exact = best.needs_exact;
      consider_piece(PieceMatrix{H, h_error(g), false, 0, false, zeros}, calls, search);
      if (needed_exact || !best.needs_exact) return;
      if (!accurate) accurate.emplace(dA, dB);
      if (accurate->matrix(ma, mb, Hw, ew)) {
        best.needs_exact = false;
        consider_accurate();
      }
    } else {
      consider_piece(PieceMatrix{H, h_error(g), kExact, g.pe}, calls, search);
    }
  }

  const Corners<T>& pA;
  const Corners<T>& pB;
  const Search& search;
  const Problem& P;
  Best& best;
  ToDouble to_d;
  std::array<std::array<double, 3>, 4> dA, dB;
  SubsetLanes sa, sb;    // the subsets' sums and moments in doubles (both paths: the counts)
  TV xSA[16], xSB[16];  // exact path: the exact sums
  M6 xQA[16], xQB[16];
  // Exact path: the positions' integer sums (integer_sums), where taken (integers).
  struct IntegerSums {
    long E = 0;
    mpz_class XA[4][3], XB[4][3];  // the positions
    mpz_class SA[16][3], SB[16][3], QA[16][6], QB[16][6];
  };
  bool integers = false;
  std::conditional_t<kExact, IntegerSums, char> ints{};
  ColumnsB cols;          // B's sums as lanes (surviving_pieces; every lane in use written)
  int lane[16];           // lane[mb]: set mb's lane in cols (0 for a set not in cols)
  alignas(16) int lane_set[16];  // lane l's set as a bit (cols.mb[l]; 0 on padding lanes)
  unsigned survivors[16];
  double top = 0;         // the window's top edge: the best value so far, less kPrune
  std::optional<AccurateMoments> accurate;  // double path: built on the first piece that needs it
};

}  // namespace

void enumerate_pieces(const Corners<double>& pA, const Corners<double>& pB, const Search& search) {
  PieceEnumeration<double, AsDouble>(pA, pB, search, AsDouble{}).run();
}

void enumerate_pieces(const Corners<detail::Q>& pA, const Corners<detail::Q>& pB, const Search& search) {
  PieceEnumeration<detail::Q, AsDouble>(pA, pB, search, AsDouble{}).run();
}

}  // namespace pdd::fast::global
