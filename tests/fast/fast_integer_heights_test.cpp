// The integer frame of fast/src/exact/integer_heights.h: every sign det[p1 − p0, q1 − q0, p − q]
// it gives equals the sign of the same determinant in GMP rationals, on pairs of the kind it is
// for (grids of decimal cells and their copies shifted by decimal offsets, exact zeros common),
// on pairs whose coordinates use all 60 bits the frame allows (the products' bounds of its
// header reached), and the frame is refused exactly where the coordinates span more than 60
// bits (checked against the bits counted here independently), for coordinates of 2^60 and more,
// and for subnormal, infinite and NaN coordinates.
#define BOOST_TEST_MODULE fast_integer_heights
#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <cmath>
#include <random>

#include "exact/integer_heights.h"

using namespace pdd;
using fast::detail::IntegerFrame;

namespace {

const Vec3d& vertex(const TetVertices& A, const TetVertices& B, int i) { return i < 4 ? A[i] : B[i - 4]; }

// The sign of det[p1 − p0, q1 − q0, p − q] in rationals (vertex indices 0..3 A, 4..7 B).
int rational_sign(const TetVertices& A, const TetVertices& B, const int (&ix)[6]) {
  mpq_class d[3][3];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      d[r][k] = mpq_class(vertex(A, B, ix[2 * r])[k]) - mpq_class(vertex(A, B, ix[2 * r + 1])[k]);
  const mpq_class det = d[0][1] * d[1][2] * d[2][0] - d[0][2] * d[1][1] * d[2][0] + d[0][2] * d[1][0] * d[2][1] -
                        d[0][0] * d[1][2] * d[2][1] + d[0][0] * d[1][1] * d[2][2] - d[0][1] * d[1][0] * d[2][2];
  return sgn(det);
}

// Whether the frame must exist: every coordinate finite, below 2^60, not subnormal, and all
// lowest set bits within 60 of the highest one (counted with frexp, not as the frame does).
bool spans_at_most_60_bits(const TetVertices& A, const TetVertices& B) {
  int hi = -100000, lo = 100000;
  for (int i = 0; i < 8; ++i)
    for (double x : vertex(A, B, i)) {
      if (!std::isfinite(x) || std::fabs(x) >= 0x1p60) return false;
      if (x == 0.0) continue;
      if (std::fpclassify(x) == FP_SUBNORMAL) return false;
      int e = 0;
      double m = std::frexp(std::fabs(x), &e);  // |x| = m 2^e, m in [0.5, 1)
      hi = std::max(hi, e - 1);
      int low = e;
      while (m != std::floor(m)) m *= 2, --low;  // the lowest set bit is 2^low
      lo = std::min(lo, low);
    }
  return hi < lo || hi + 1 - lo <= 60;
}

struct Tally {
  long frames = 0, usable = 0, signs = 0, zeros = 0, wrong = 0, refusals_wrong = 0;
};

void check_pair(const TetVertices& A, const TetVertices& B, std::mt19937_64& rng, Tally& t) {
  IntegerFrame frame(A, B);
  ++t.frames;
  const bool usable = frame.usable();
  if (usable != spans_at_most_60_bits(A, B)) ++t.refusals_wrong;
  if (!usable) return;
  ++t.usable;
  for (int s = 0; s < 12; ++s) {
    int ix[6];
    for (int& i : ix) i = int(rng() % 8);
    const int want = rational_sign(A, B, ix);
    const int got = frame.height_sign(ix[0], ix[1], ix[2], ix[3], ix[4], ix[5]);
    ++t.signs;
    t.zeros += want == 0;
    if (got != want && ++t.wrong <= 5) BOOST_TEST_MESSAGE("sign " << got << " rational " << want);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(signs_equal_rationals_on_grids_and_their_shifted_copies) {
  std::mt19937_64 rng(20261201);
  Tally t;
  const double cells[] = {0.1, 0.025, 1.0 / 3, 0x1p-3, 7.3e5, 1e-3};
  for (int it = 0; it < 30000; ++it) {
    const double h = cells[it % 6];
    std::uniform_int_distribution<int> cell(-8, 8);
    const double offset[3] = {0.1 * (it % 7), 0.025 * (it % 5), h * 0.3};
    TetVertices A, B;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) A[i][k] = h * cell(rng), B[i][k] = h * cell(rng) + (it % 3 ? offset[k] : 0.0);
    if (it % 11 == 0) B[2][1] = -0.0;
    check_pair(A, B, rng, t);
  }
  BOOST_TEST_MESSAGE(t.frames << " pairs, " << t.usable << " with a frame, " << t.signs << " signs, " << t.zeros
                              << " exact zeros");
  BOOST_TEST(t.wrong == 0);
  BOOST_TEST(t.refusals_wrong == 0);
  BOOST_TEST(t.usable > t.frames / 2);  // the kind of pair it is for
  BOOST_TEST(t.zeros > t.signs / 10);   // exact zeros are exercised
}

// Coordinates at the bounds of the header: |X| up to 2^60 − 2^7 with both signs (differences
// near 2^61, cross products near 2^123, terms near 2^184), beside small integers.
BOOST_AUTO_TEST_CASE(signs_equal_rationals_at_the_bounds) {
  std::mt19937_64 rng(7);
  Tally t;
  std::uniform_int_distribution<long> significand(-(1L << 52), 1L << 52);
  std::uniform_int_distribution<int> small(-8, 8);
  for (int it = 0; it < 20000; ++it) {
    TetVertices A, B;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        A[i][k] = rng() % 2 ? std::ldexp(double(significand(rng)), 7) : double(small(rng));
        B[i][k] = rng() % 2 ? std::ldexp(double(significand(rng)), 7) : double(small(rng));
      }
    A[0][0] = 0x1p59 * (2 - 0x1p-52);  // the largest coordinate the frame takes
    B[1][1] = -A[0][0];
    A[3][2] = 1.0;                       // and the smallest bit: 60 bits in all
    check_pair(A, B, rng, t);
  }
  BOOST_TEST(t.wrong == 0);
  BOOST_TEST(t.refusals_wrong == 0);
  BOOST_TEST(t.usable == t.frames);
}

BOOST_AUTO_TEST_CASE(refused_beyond_sixty_bits_and_for_non_normal_coordinates) {
  TetVertices A{}, B{};
  A[1] = {1, 0, 0}, A[2] = {0, 1, 0}, A[3] = {0, 0, 1};
  B = A;
  auto usable = [&] { return IntegerFrame(A, B).usable(); };
  BOOST_TEST(usable());
  B[3][0] = 0x1p-59;  // 60 bits from 2^-59 to 2^0
  BOOST_TEST(usable());
  B[3][0] = 0x1p-60;  // 61
  BOOST_TEST(!usable());
  B[3][0] = 0.1;      // 0.1's lowest set bit is 2^-55: 56 bits
  BOOST_TEST(usable());
  B[3][0] = 0x1p60;   // beyond 2^60
  BOOST_TEST(!usable());
  B[3][0] = 0x1p-1074;
  BOOST_TEST(!usable());
  B[3][0] = HUGE_VAL;
  BOOST_TEST(!usable());
  B[3][0] = std::nan("");
  BOOST_TEST(!usable());
  A = TetVertices{}, B = TetVertices{};  // every coordinate 0: every sign 0
  IntegerFrame zero(A, B);
  BOOST_TEST(zero.usable());
  BOOST_TEST(zero.height_sign(1, 0, 2, 0, 3, 0) == 0);
}
