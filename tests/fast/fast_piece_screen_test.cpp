// fast_piece_screen_test — the double path's pruning of global_depth's pieces (piece_screen.h)
// against exact and independent computations:
//  - eigenvalues_below_certain: whenever it decides, its count equals the exact number of
//    eigenvalues of the double matrix below t (Descartes' rule on the characteristic
//    polynomial of the exact rational matrix, written here again in mpq), on random matrices,
//    singular ones, thresholds at and one ulp beside exact eigenvalues, entries from 1e-150 to
//    1e150; and it decides most well-separated cases (a function that never decides would
//    prune nothing).
//  - screen: a piece it drops has its single in-window eigenvector (long-double Eigen, an
//    independent solver) violating one of the piece's sign conditions beyond their rounding
//    floor in both orientations (certainly outside the piece's cone); a piece whose
//    eigenvector satisfies every condition is always kept;
//    the same with windows far narrower than the matrices' error (shallow contacts), where
//    only the counts around the widened window give the screen its gap.
//  - region_pieces (piece_region.h): every piece whose cone holds a direction u of the region
//    D(u)^2 < 32 top (D, the overlap along u, in long double) is kept, on random directions
//    and on directions beside the 50 lines where the region's least values lie; and it does
//    drop pieces (not vacuous).
#define BOOST_TEST_MODULE fast_piece_screen
#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "global/piece_region.h"
#include "global/piece_screen.h"
#include "pdd/compare/random.h"

using namespace pdd::fast::detail;

namespace {

using Rng = pdd::compare::ReproducibleRng;

// The exact number of eigenvalues of the rational symmetric matrix h (xx xy xz yy yz zz) below
// t: N = h - tI has characteristic polynomial x^3 - tr x^2 + c1 x - det, all roots real, so its
// negative roots number the sign changes of (1, tr, c1, det) with zero coefficients skipped.
int exact_below(const double h[6], double t) {
  const mpq_class T(t);
  const mpq_class a00 = mpq_class(h[0]) - T, a11 = mpq_class(h[3]) - T, a22 = mpq_class(h[5]) - T;
  const mpq_class a01(h[1]), a02(h[2]), a12(h[4]);
  const mpq_class tr = a00 + a11 + a22;
  const mpq_class c1 = a00 * a11 - a01 * a01 + a00 * a22 - a02 * a02 + a11 * a22 - a12 * a12;
  const mpq_class det =
      a00 * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02);
  int changes = 0, last = 1;
  for (const mpq_class* c : {&tr, &c1, &det}) {
    const int s = sgn(*c);
    if (s == 0) continue;
    if (s != last) ++changes;
    last = s;
  }
  return changes;
}

// A random rotation (Gram-Schmidt of random vectors) times diag(l) times its transpose.
void rotated(Rng& rng, const double l[3], double h[6]) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = rng.uniform(-1, 1);
  const Eigen::Matrix3d q = Eigen::HouseholderQR<Eigen::Matrix3d>(m).householderQ();
  const Eigen::Matrix3d a = q * Eigen::Vector3d(l[0], l[1], l[2]).asDiagonal() * q.transpose();
  h[0] = a(0, 0), h[1] = a(0, 1), h[2] = a(0, 2), h[3] = a(1, 1), h[4] = a(1, 2), h[5] = a(2, 2);
}

int count(const double h[6], double t) {
  return eigenvalues_below_certain(h[0], h[1], h[2], h[3], h[4], h[5], t);
}

}  // namespace

BOOST_AUTO_TEST_CASE(certain_counts_are_exact) {
  Rng rng(20261124);
  int decided = 0, separated = 0, separated_decided = 0, wrong = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::ldexp(1.0, int(rng.uniform(-500, 500)));  // 1e-150 .. 1e150
    double l[3] = {rng.uniform(0, 1) * scale, rng.uniform(0, 1) * scale, rng.uniform(0, 1) * scale};
    if (trial % 5 == 1) l[0] = 0;                       // singular (a piece of rank 2)
    if (trial % 5 == 2) l[0] = l[1] = 0;                // rank 1
    if (trial % 5 == 3) l[1] = l[2] * (1 + 1e-12);      // nearly double
    double h[6];
    rotated(rng, l, h);
    double t = rng.uniform(-0.1, 1.1) * scale;
    if (trial % 7 == 0) t = l[int(rng.uniform(0, 3))];  // at an eigenvalue (of the exact diag)
    if (trial % 7 == 1) t = std::nextafter(t, INFINITY);
    if (trial % 11 == 0) h[0] = 0, h[1] = 0, h[2] = 0;  // a zero row and column: an exact 0
    if (trial % 13 == 0) t = 0;
    const int c = count(h, t), e = exact_below(h, t);
    if (c >= 0) {
      ++decided;
      if (c != e) ++wrong;
      BOOST_TEST(c == e, "trial " << trial << ": certain count " << c << ", exact " << e << " scale "
                                  << scale << " t " << t << " h " << h[0] << " " << h[1] << " " << h[2]
                                  << " " << h[3] << " " << h[4] << " " << h[5]);
    }
    // well separated (every eigenvalue of the diag at least 1e-6 of the scale from t) and in
    // the range the engine uses (piece_screen.h: 2^-200 .. 2^100; outside, det underflows or
    // overflows and the count is rightly undecided)
    bool sep = std::fabs(std::log2(scale)) <= 100;
    for (double x : l) sep = sep && std::fabs(x - t) > 1e-6 * scale;
    if (sep) ++separated, separated_decided += c >= 0;
  }
  BOOST_TEST(wrong == 0);
  // decidable range (piece_screen.h): entries <= 2^100 and det's magnitude sum >= 2^-800, so
  // scales of about 2^-266 .. 2^100, 37% of the exponents drawn: at least a quarter decided
  BOOST_TEST(decided > 5000);
  BOOST_TEST(separated_decided > 0.99 * separated, separated_decided << " of " << separated);
  // exactly at an eigenvalue the count is never claimed (det is exactly 0)
  const double d[6] = {1, 0, 0, 2, 0, 3};
  BOOST_TEST(count(d, 2.0) == -1);
  BOOST_TEST(count(d, 2.5) == 2);
  BOOST_TEST(count(d, 0.5) == 0);
  BOOST_TEST(count(d, 3.5) == 3);
  // a PSD matrix whose h01 h12 underflows, then is multiplied by h02; exact count 1
  const double under[6] = {1, 3.487961642486959e-162, 6.615855428177285, 1, 1.372229031336404e-161,
                           53.056013317976664};
  BOOST_TEST(exact_below(under, 1.0) == 1);
  BOOST_TEST((count(under, 1.0) == -1 || count(under, 1.0) == 1));
  const double nan_h[6] = {NAN, 0, 0, 1, 0, 1};
  BOOST_TEST(count(nan_h, 0.5) == -1);
}

namespace {

struct Lane {
  double N[6], C[3], TA[3], sign[8];
  double lo, hi;
};

// The unit eigenvector (long double) of the one eigenvalue of N in [lo, hi), if exactly one.
bool in_window_vector(const Lane& x, Eigen::Matrix<long double, 3, 1>& v) {
  Eigen::Matrix<long double, 3, 3> m;
  m << x.N[0], x.N[1], x.N[2], x.N[1], x.N[3], x.N[4], x.N[2], x.N[4], x.N[5];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<long double, 3, 3>> es(m);
  int found = 0;
  for (int k = 0; k < 3; ++k)
    if (es.eigenvalues()(k) >= x.lo && es.eigenvalues()(k) < x.hi) v = es.eigenvectors().col(k), ++found;
  return found == 1;
}

// Condition k's vector l and its verdict at s v: the margin s sign (l.v) + floor (>= 0: holds
// up to the conditions' own rounding; < 0: s v is certainly outside the piece's cone).
long double margin(const Lane& x, const double pA[4][3], const double pB[4][3], int k,
                   const Eigen::Matrix<long double, 3, 1>& v, double floor) {
  long double l[3], dot = 0;
  for (int j = 0; j < 3; ++j) {
    l[j] = k < 4 ? (pA[k][j] - x.C[j]) - x.TA[j] : (x.C[j] - pB[k - 4][j]) - x.TA[j];
    dot += l[j] * v(j);
  }
  return x.sign[k] * dot + floor;
}

}  // namespace

namespace {

struct Tally {
  int dropped = 0, kept = 0, forced_kept = 0;
};

// One round: 40 lanes whose N = a random rotation of diag(eig(p)), with random C, T_A and
// signs; every third lane with one eigenvalue in the window [lo, hi) = window_edges(top, lower,
// n_error) gets signs its vector satisfies (it must be kept). After screen(), every dropped
// lane's in-window eigenvector violates a condition beyond the floor in both orientations: N's
// own (in [lo, hi)), and that of N + E for `perturbed` random E with entries within n_error
// (an exact 20 H the bound admits; its eigenvalue sought in [check_lo, check_hi), where the
// lane is skipped if E moved a neighbour in too).
template <class Eigenvalues>
void screen_round(Rng& rng, int round, double top, double lower, double n_error, Eigenvalues eig, int perturbed,
                  double check_lo, double check_hi, Tally& tally) {
  const double floor = 1e-12;
  double pA[4][3], pB[4][3];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) pA[i][j] = rng.uniform(-1, 1), pB[i][j] = rng.uniform(-1, 1);
  const Edges e = window_edges(top, lower, n_error);
  ScreenLanes S;
  std::vector<Lane> lanes;
  std::vector<int> must_keep;
  for (int p = 0; p < 40; ++p) {
    Lane x;
    double l[3];
    eig(p, e, l);
    rotated(rng, l, x.N);
    for (int j = 0; j < 3; ++j) x.C[j] = rng.uniform(-0.5, 0.5), x.TA[j] = rng.uniform(-0.5, 0.5);
    for (double& s : x.sign) s = rng.uniform01() < 0.5 ? 1 : -1;
    x.lo = e.lo, x.hi = e.hi;
    Eigen::Matrix<long double, 3, 1> v;
    const bool forced = in_window_vector(x, v) && p % 3 == 0;
    if (forced)  // signs that the vector satisfies: the piece must be kept
      for (int k = 0; k < 8; ++k) {
        x.sign[k] = 1;
        if (margin(x, pA, pB, k, v, floor) < 0) x.sign[k] = -1;
      }
    for (int q = 0; q < 6; ++q) S.N[q][p] = x.N[q];
    for (int j = 0; j < 3; ++j) S.C[j][p] = x.C[j], S.TA[j][p] = x.TA[j];
    for (int k = 0; k < 8; ++k) S.sign[k][p] = x.sign[k];
    S.n_error[p] = n_error;
    const int below_lo = count(x.N, e.lo), below_hi = count(x.N, e.hi);
    S.below_low[p] = below_lo;
    S.one[p] = below_lo >= 0 && below_hi == below_lo + 1;
    lanes.push_back(x);
    must_keep.push_back(forced);
  }
  S.n = int(lanes.size());
  screen(S, pA, pB, floor, top, lower);
  for (int p = 0; p < S.n; ++p) {
    BOOST_TEST_CONTEXT("round " << round << " lane " << p) {
      if (must_keep[p]) {
        BOOST_TEST(S.keep[p] == 1);
        ++tally.forced_kept;
      }
      if (S.keep[p]) {
        ++tally.kept;
        continue;
      }
      ++tally.dropped;
      for (int trial = 0; trial <= perturbed; ++trial) {
        Lane y = lanes[p];
        Eigen::Matrix<long double, 3, 1> v;
        if (trial == 0) {
          BOOST_TEST(in_window_vector(y, v));
        } else {
          for (int q = 0; q < 6; ++q) y.N[q] += rng.uniform(-n_error, n_error);
          y.lo = check_lo, y.hi = check_hi;
          if (!in_window_vector(y, v)) continue;
        }
        // both orientations outside the cone beyond the floor (long double slack)
        for (long double s : {1.0L, -1.0L}) {
          long double worst = INFINITY;
          for (int k = 0; k < 8; ++k) worst = std::min(worst, margin(y, pA, pB, k, s * v, floor));
          BOOST_TEST(worst < -1e-15L, "trial " << trial << " orientation " << double(s) << " margin "
                                               << double(worst));
        }
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(screen_drops_only_pieces_whose_vector_violates_a_condition) {
  Rng rng(77);
  Tally tally;
  for (int round = 0; round < 200; ++round) {
    const double top = rng.uniform(0.2, 1), lower = top * rng.uniform(0.1, 0.5);
    // 20 H with one eigenvalue inside the window (in 20 H's units), the others outside; every
    // fourth lane a close neighbour above it
    auto eig = [&](int p, const Edges& e, double (&l)[3]) {
      l[0] = rng.uniform(e.lo, e.hi), l[1] = rng.uniform(e.hi, 3 * e.hi), l[2] = rng.uniform(0, e.lo);
      if (p % 4 == 0) l[2] = e.hi * (1 + rng.uniform(1e-9, 1e-3));
    };
    screen_round(rng, round, top, lower, 1e-16, eig, 0, 0, 0, tally);
  }
  BOOST_TEST(tally.dropped > 1000);  // the screen does drop pieces (not vacuous)
  BOOST_TEST(tally.kept > 100);
  BOOST_TEST(tally.forced_kept > 100);
}

// A shallow contact's pieces: the window (~1e-14) far narrower than the matrices' error bound
// (n_error 1e-12), one eigenvalue of N inside it, the other two ~0.01 to 1 away (three in
// four lanes) or just above it (the fourth: inside the widening, whose counts then fail). The
// window's own edges never give the screen a gap (delta <= 0); the counts around the widened
// window do. Dropped pieces are checked on N and on two N + E each.
BOOST_AUTO_TEST_CASE(screen_sees_the_gap_beyond_a_narrow_window) {
  Rng rng(78);
  Tally tally;
  for (int round = 0; round < 200; ++round) {
    const double top = 1e-15 * rng.uniform(0.2, 1), lower = top * rng.uniform(0.01, 0.03);
    auto eig = [&](int p, const Edges& e, double (&l)[3]) {
      l[0] = 20 * top * rng.uniform(0.05, 0.95), l[1] = rng.uniform(0.01, 1), l[2] = rng.uniform(0.01, 1);
      if (p % 4 == 0) l[1] = e.hi * (1 + rng.uniform(0.01, 10));  // a neighbour beside the window
    };
    screen_round(rng, round, top, lower, 1e-12, eig, 2, -1, 1e-6, tally);
  }
  BOOST_TEST(tally.dropped > 1000);  // the widened gap decides (the window alone: none)
  BOOST_TEST(tally.kept > 100);
  BOOST_TEST(tally.forced_kept > 100);
}

BOOST_AUTO_TEST_CASE(tables_are_the_bits) {  // kPopcount and kSignOf against the bits themselves
  for (unsigned m = 0; m < 16; ++m) {
    BOOST_TEST(kPopcount[m] == __builtin_popcount(m));
    for (int i = 0; i < 4; ++i) BOOST_TEST(kSignOf[m][i] == ((m >> i & 1u) ? 1.0 : -1.0));
  }
}

namespace {

// D(u) (long double): the highest vertex of A less the lowest of B along u, and the top sets
// of A and bottom sets of B along u (the prefixes of the heights' order), none when two of A's
// or of B's heights lie within `tie` of each other (the order there is the region's tolerance).
struct Along {
  long double D;
  unsigned a_sets[4], b_sets[4];
  bool clear;
};
Along along(const double (&pA)[4][3], const double (&pB)[4][3], const long double (&u)[3], long double tie) {
  Along r;
  long double ha[4], hb[4];
  for (int i = 0; i < 4; ++i) {
    ha[i] = pA[i][0] * u[0] + pA[i][1] * u[1] + pA[i][2] * u[2];
    hb[i] = pB[i][0] * u[0] + pB[i][1] * u[1] + pB[i][2] * u[2];
  }
  int oa[4] = {0, 1, 2, 3}, ob[4] = {0, 1, 2, 3};
  std::sort(oa, oa + 4, [&](int x, int y) { return ha[x] > ha[y]; });
  std::sort(ob, ob + 4, [&](int x, int y) { return hb[x] < hb[y]; });
  r.D = ha[oa[0]] - hb[ob[0]];
  r.clear = true;
  unsigned ma = 0, mb = 0;
  for (int k = 0; k < 4; ++k) {
    ma |= 1u << oa[k], mb |= 1u << ob[k];
    r.a_sets[k] = ma, r.b_sets[k] = mb;
    if (k < 3 && (ha[oa[k]] - ha[oa[k + 1]] < tie || hb[ob[k + 1]] - hb[ob[k]] < tie)) r.clear = false;
  }
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(region_keeps_every_piece_its_region_reaches) {
  Rng rng(79);
  long checked = 0, dropped = 0, applied = 0, wrong = 0, intersecting = 0;
  static const int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int trial = 0; trial < 300; ++trial) {
    // two overlapping tetrahedra about the origin (centred as the enumeration centres them)
    double pA[4][3], pB[4][3], c[3] = {0, 0, 0};
    const double shift = rng.uniform(0, 0.8);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        pA[i][k] = rng.uniform(-1, 1), pB[i][k] = rng.uniform(-1, 1) + (k == 0 ? shift : 0);
        c[k] += (pA[i][k] + pB[i][k]) / 8;
      }
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) pA[i][k] -= c[k], pB[i][k] -= c[k];
    // directions beside the lines of the edges' cross products, where the region's least D lies,
    // and the least D itself, PD (the least over the facet normals, which lie on these lines;
    // not positive: the pair does not intersect)
    double E[12][3];
    for (int e = 0; e < 6; ++e)
      for (int k = 0; k < 3; ++k)
        E[e][k] = pA[kEdge[e][1]][k] - pA[kEdge[e][0]][k], E[6 + e][k] = pB[kEdge[e][1]][k] - pB[kEdge[e][0]][k];
    long double least = INFINITY;
    std::vector<std::array<long double, 3>> dirs;
    for (int f = 0; f < 12; ++f)
      for (int g = f + 1; g < 12; ++g) {
        long double x[3] = {(long double)E[f][1] * E[g][2] - (long double)E[f][2] * E[g][1],
                            (long double)E[f][2] * E[g][0] - (long double)E[f][0] * E[g][2],
                            (long double)E[f][0] * E[g][1] - (long double)E[f][1] * E[g][0]};
        const long double n = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(n > 1e-9)) continue;
        for (int s : {1, -1})
          for (int j = 0; j < 6; ++j) {
            const long double eps = j == 0 ? 0 : std::pow(10.0L, -rng.uniform(2, 9));
            long double u[3], m = 0;
            for (int k = 0; k < 3; ++k) u[k] = s * x[k] / n + eps * rng.uniform(-1, 1), m += u[k] * u[k];
            for (long double& y : u) y /= std::sqrt(m);
            dirs.push_back({u[0], u[1], u[2]});
            if (j == 0) least = std::min(least, along(pA, pB, u, 0).D);
          }
      }
    if (!(least > 1e-6)) continue;  // (not intersecting, or barely)
    ++intersecting;
    for (int j = 0; j < 20000; ++j) {  // and random directions
      long double u[3];
      long double n = 0;
      for (long double& x : u) x = rng.uniform(-1, 1), n += x * x;
      if (n > 1 || n < 1e-6) continue;
      for (long double& x : u) x /= std::sqrt(n);
      dirs.push_back({u[0], u[1], u[2]});
    }
    const double top = double(least * least / 32) * rng.uniform(1.0, 4.0);
    unsigned rows[16];
    if (!region_pieces(pA, pB, top, rows)) continue;
    ++applied;
    for (unsigned ma = 1; ma < 16; ++ma) dropped += 15 - __builtin_popcount(rows[ma] & 0xFFFEu);
    for (const auto& d : dirs) {
      const long double u[3] = {d[0], d[1], d[2]};
      const Along r = along(pA, pB, u, 1e-12L);
      if (!r.clear || !(r.D * r.D < 32.0L * top * (1 - 1e-9L))) continue;
      for (int k = 0; k < 4; ++k)
        for (int m = 0; m < 4; ++m) {
          ++checked;
          if (!(rows[r.a_sets[k]] >> r.b_sets[m] & 1u)) ++wrong;
        }
    }
  }
  BOOST_TEST_MESSAGE("region: " << applied << " of " << intersecting << " pairs, " << checked << " pieces checked, "
                                  << dropped << " dropped");
  BOOST_TEST(wrong == 0);
  BOOST_TEST(applied == intersecting);  // (every intersecting pair here: the test applies)
  BOOST_TEST(applied > 100);
  BOOST_TEST(checked > 100000);
  BOOST_TEST(dropped > 100 * applied);  // most pieces dropped (not vacuous)
}
