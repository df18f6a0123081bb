// integer_normals.h against a brute-force search in rationals: over the window of tries, the
// first triple returned has the least distance of c alpha to the integers (both components), up
// to the search's fixed-point error, along generic directions (the loop over every try) and along
// directions a rounding away from a coordinate plane or a diagonal (its slow-drift path, which
// considers a few tries only); every triple returned is c's integer normal.
#define BOOST_TEST_MODULE fast_integer_normals
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "global/integer_normals.h"

using namespace pdd::fast;
using detail::Q;

namespace {

// |x - round(x)|, exactly
Q frac_distance(const Q& x) {
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  const Q f = x - Q(fl);
  return f <= Q(1, 2) ? f : Q(1) - f;
}

struct Direction {
  double base[3];  // a direction whose ratios are integers (or generic)
  double eps;      // perturbation of its components (0: as is)
};

}  // namespace

BOOST_AUTO_TEST_CASE(first_triple_is_the_window_best) {
  const int tries = 1 << 12, m = 2;  // y_m = y[2], the largest component below
  const std::vector<Direction> dirs = {
      {{0.7534, -0.2341234, 1}, 0},  {{0.1234567, 0.87654321, -1}, 0}, {{1, -1, 1}, 1e-8},
      {{0, -1, 1}, 1e-12},           {{-1, 0, 1}, 1e-16},               {{1, 1, -1}, 1e-17},
      {{0, 0, 1}, 3e-18},            {{-1, 1, 1}, 1e-20},               {{1, 0, -1}, 7e-23},
      {{0, 1, 1}, 2.5e-17},
  };
  for (const Direction& d : dirs) {
    Q y[3];
    for (int k = 0; k < 3; ++k) y[k] = Q(d.base[k]);
    const Q tilt[2] = {Q(d.eps) * Q(3, 7), Q(d.eps) * Q(5, 11)};
    for (int t = 0; t < 2; ++t) y[t] += d.base[t] > 0 ? Q(-tilt[t]) : tilt[t];  // |y_0|, |y_1| < |y_2|
    std::vector<global::V3> out;
    global::integer_normals(y, tries, 4, out);
    BOOST_REQUIRE(!out.empty());
    const Q alpha[2] = {y[0] / y[m], y[1] / y[m]};
    // brute force: the least sum of squared distances over the window
    Q best = -1;
    for (int j = 0; j < tries; ++j) {
      const Q c((std::int64_t(1) << 53) - 1 - j);
      const Q d0 = frac_distance(c * alpha[0]), d1 = frac_distance(c * alpha[1]);
      const Q metric = d0 * d0 + d1 * d1;
      if (best < 0 || metric < best) best = metric;
    }
    for (std::size_t r = 0; r < out.size(); ++r) {  // each one c's integer normal, along y
      const Q c(std::fabs(out[r][m]));
      BOOST_TEST(c.get_d() <= 0x1p53);
      BOOST_TEST(sgn(Q(out[r][m])) == sgn(y[m]));
      for (int t = 0; t < 2; ++t) {
        const Q rest = Q(out[r][t]) * Q(sgn(y[m])) - c * alpha[t];
        BOOST_TEST(abs(rest) <= Q(1, 2));
      }
    }
    const Q c(std::fabs(out[0][m]));
    const Q d0 = frac_distance(c * alpha[0]), d1 = frac_distance(c * alpha[1]);
    // The search tracks each fractional part in 64-bit fixed point, off by < j 2^-64 after j
    // tries, and compares metrics in doubles (relative rounding < 4 2^-53): sqrt(metric) within
    // sqrt(2) tries 2^-64 + 4 2^-53 sqrt(metric) of the exact one.
    const double got = std::sqrt(Q(d0 * d0 + d1 * d1).get_d()), least = std::sqrt(best.get_d());
    BOOST_TEST(got <= least * (1 + 8 * 0x1p-53) + 4 * tries * 0x1p-64,
               "eps " << d.eps << ": first triple at " << got << ", the window's best " << least);
  }
}
