// integer_normals.h against a brute-force search in rationals: over the window of tries, the
// first triple returned has the least distance of c alpha to the integers (both components), up
// to the search's fixed-point error, along generic directions (the loop over every try) and along
// directions a rounding away from a coordinate plane or a diagonal (its slow-drift path, which
// considers a few tries only), those with a fractional part near a half included, and from a
// cube's diagonal planes (the slow drift every second, third or fourth try); every triple
// returned is c's integer normal; and, along generic directions, the very triples of the plain
// loop over every try (the search screens the tries).
#define BOOST_TEST_MODULE fast_integer_normals
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>
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

// The search along y over `tries` against the brute force (header comment); m = 2, the largest
// component of y. Every triple returned is checked: the r-th one's metric is at most the
// window's r-th least (up to the search's error), so a try the search skips cannot be better
// than one it returns.
void check_window_best(const Q (&y)[3], int tries, const char* what) {
  const int m = 2;
  std::vector<global::V3> out;
  global::integer_normals(y, tries, 4, out);
  BOOST_REQUIRE(!out.empty());
  const Q alpha[2] = {y[0] / y[m], y[1] / y[m]};
  auto metric_of = [&](const Q& c) {
    const Q d0 = frac_distance(c * alpha[0]), d1 = frac_distance(c * alpha[1]);
    return Q(d0 * d0 + d1 * d1);
  };
  // brute force: every try's sum of squared distances, least first
  std::vector<Q> metrics;
  for (int j = 0; j < tries; ++j) metrics.push_back(metric_of(Q((std::int64_t(1) << 53) - 1 - j)));
  std::sort(metrics.begin(), metrics.end());
  for (std::size_t r = 0; r < out.size(); ++r) {  // each one c's integer normal, along y
    const Q c(std::fabs(out[r][m]));
    BOOST_TEST(c.get_d() <= 0x1p53);
    BOOST_TEST(sgn(Q(out[r][m])) == sgn(y[m]));
    for (int t = 0; t < 2; ++t) {
      const Q rest = Q(out[r][t]) * Q(sgn(y[m])) - c * alpha[t];
      BOOST_TEST(abs(rest) <= Q(1, 2));
    }
    // The search tracks each fractional part in 64-bit fixed point, off by < j 2^-64 after j
    // tries, and compares metrics in doubles (relative rounding < 4 2^-53): sqrt(metric) within
    // sqrt(2) tries 2^-64 + 4 2^-53 sqrt(metric) of the exact one.
    const double got = std::sqrt(metric_of(c).get_d()), least = std::sqrt(metrics[r].get_d());
    BOOST_TEST(got <= least * (1 + 8 * 0x1p-53) + 4 * tries * 0x1p-64,
               what << ": triple " << r << " at " << got << ", the window's " << r << "-th least " << least);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(first_triple_is_the_window_best) {
  const int tries = 1 << 12;
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
    std::ostringstream what;
    what << "eps " << d.eps;
    check_window_best(y, tries, what.str().c_str());
  }
}

// Along a direction a rounding off a coordinate plane or a diagonal whose fractional part of
// c alpha starts near a half at the window's first try c = 2^53 - 1 (alpha = 2^-54 + eta: c alpha
// = 1/2 - 2^-54 + c eta), so that the offset's nearest integer changes inside the window (eta =
// 2^-96: c alpha falls by ~2^-54 a try from 1/2 + ~2^-43, past 1/2 after ~2^11 of the 2^12
// tries) or stays (eta = 0: just below a half throughout), beside a part a rounding off -1; and
// parts set at the first try and drifting at chosen rates (below), so that the least metric lies
// inside a segment after a change, or both parts change.
BOOST_AUTO_TEST_CASE(parts_starting_near_a_half) {
  const int tries = 1 << 12;
  const Q two54 = Q(mpz_class(1) << 54), two96 = Q(mpz_class(1) << 96), two55 = Q(mpz_class(1) << 55);
  // alpha = (f - N) / c0 for the window's first try c0 = 2^53 - 1: c0 alpha = f mod 1 (the part
  // at the first try) and the part moves by -alpha ~ N / c0 a try
  const Q c0((std::int64_t(1) << 53) - 1);
  auto part = [&](const Q& f, std::int64_t N) { return Q((f - Q(N)) / c0); };
  const std::int64_t slow = std::int64_t(1) << 29, fast = std::int64_t(1) << 39;  // ~2^-24, ~2^-14 a try
  const Q cases[][3] = {
      {Q(1) / two54 + Q(1) / two96, Q(-1) + Q(3) / two55, Q(1)},  // crosses a half
      {Q(1) / two54, Q(-1) + Q(3) / two55, Q(1)},                  // stays below a half
      {Q(-1) + Q(3) / two55, Q(1) / two54 + Q(1) / two96, Q(-1)},  // the same, components swapped
      {Q(1) / two54 + Q(1) / two96, Q(1) / two54 - Q(1) / two96, Q(1)},
      // part 0 crosses a half at try ~1,680 (0.4999 rising by 2^-24 a try), part 1 rises through
      // 0 from -0.2 by 2^-14 a try (at ~3,280): the least metric inside the second segment
      {part(Q(4999, 10000), slow), part(Q(8, 10), fast), Q(1)},
      // both cross a half, part 0 after part 1 (at ~3,360 and ~1,680): two changes, taken in order
      {part(Q(4998, 10000), slow), part(Q(4999, 10000), slow), Q(1)},
  };
  int i = 0;
  for (const auto& y : cases) {
    std::ostringstream what;
    what << "near a half, case " << i++;
    check_window_best(y, tries, what.str().c_str());
  }
}

// Along a direction a rounding off a cube's diagonal planes (alpha ~ 1/2, 1/3, 1/4 up to a tiny
// tilt, or exactly: the parts alternate between near an integer and near a multiple of 1/q, so
// neither drifts slowly try by try, only every q-th try: the interleaved classes of
// integer_normals.cpp, each a slow drift), beside a part near an integer or another multiple of
// 1/q, and a generic part (no class drifts slowly: the loop).
BOOST_AUTO_TEST_CASE(parts_near_a_multiple_of_a_third_or_a_half) {
  const int tries = 1 << 12;
  struct Case {
    Q a0, a1;
  };
  const Q tiny1 = Q(3, 7) * Q(1) / Q(mpz_class(1) << 56), tiny2 = Q(5, 11) * Q(1) / Q(mpz_class(1) << 66);
  const Case cases[] = {
      {Q(1, 2) + tiny1, Q(1, 2) - tiny2}, {Q(1, 2), Q(-1, 2)},          {Q(1, 2) - tiny2, Q(0) + tiny1},
      {Q(1, 3) + tiny1, Q(2, 3) + tiny2}, {Q(1, 4) - tiny1, Q(1, 2) + tiny2}, {Q(-3, 4) + tiny2, Q(1, 4)},
      {Q(1, 2) + tiny1, Q(2341, 7534)},
  };
  int i = 0;
  for (const Case& c : cases) {
    const Q y[3] = {c.a0, c.a1, Q(1)};
    std::ostringstream what;
    what << "a multiple of 1/q, case " << i++;
    check_window_best(y, tries, what.str().c_str());
  }
}

// The loop over every try, as integer_normals.cpp describes it (the parts F - j A in 64-bit
// fixed point, the metric d0² + d1² of their distances to the integers in doubles, the `keep`
// least kept, a new one before equal ones), written plainly: along generic directions (no
// drift applies) the search screens the tries four at a time and must return these triples,
// bit for bit (its screen skips only tries whose metric cannot beat the kept ones).
namespace {
std::vector<global::V3> plain_loop(const Q (&y)[3], int tries, int keep) {
  const int m = 2, idx[2] = {0, 1};
  const std::uint64_t c0 = (std::uint64_t(1) << 53) - 1;
  Q alpha[2];
  std::uint64_t A[2], F[2];
  for (int t = 0; t < 2; ++t) {
    alpha[t] = y[idx[t]] / y[m];
    const mpz_class two64 = mpz_class(1) << 64;
    auto frac64 = [&](std::uint64_t c) {  // floor(c alpha 2^64) mod 2^64, from its rational value
      const Q x = alpha[t] * Q(mpz_class(static_cast<unsigned long>(c))) * Q(two64);
      mpz_class f;
      mpz_fdiv_q(f.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
      f -= two64 * mpz_class(f / two64);  // (truncated quotient: f mod 2^64 up to one 2^64)
      if (f < 0) f += two64;
      return std::uint64_t(mpz_get_ui(f.get_mpz_t()));
    };
    A[t] = frac64(1), F[t] = frac64(c0);
  }
  std::vector<std::pair<double, std::uint64_t>> top;  // (metric, c), least first
  for (int j = 0; j < tries; ++j) {
    const double d0 = std::fabs(double(std::int64_t(F[0]))), d1 = std::fabs(double(std::int64_t(F[1])));
    const double metric = d0 * d0 + d1 * d1;
    if (int(top.size()) < keep || metric < top.back().first) {
      if (int(top.size()) == keep) top.pop_back();
      auto at = std::lower_bound(top.begin(), top.end(), metric,
                                 [](const std::pair<double, std::uint64_t>& e, double v) { return e.first < v; });
      top.insert(at, {metric, c0 - std::uint64_t(j)});
    }
    F[0] -= A[0], F[1] -= A[1];
  }
  std::vector<global::V3> out;
  for (const auto& e : top) {
    global::V3 v;
    v[m] = sgn(y[m]) > 0 ? double(e.second) : -double(e.second);
    for (int t = 0; t < 2; ++t) {
      mpz_class num = alpha[t].get_num() * static_cast<unsigned long>(e.second), den = alpha[t].get_den(), q;
      num = 2 * num + den;
      den *= 2;
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
      v[idx[t]] = (sgn(y[m]) > 0 ? 1.0 : -1.0) * q.get_d();
    }
    out.push_back(v);
  }
  return out;
}
}  // namespace

BOOST_AUTO_TEST_CASE(screened_tries_return_the_loops_triples) {
  std::uint64_t state = 12345;
  auto next = [&state]() {  // (a fixed linear congruential sequence: the same directions every run)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * 0x1p-53;
  };
  const int windows[] = {1, 3, 15, 16, 17, 33, 1000, 1024, 1041, 4099, 1 << 15};
  int n = 0;
  for (int w : windows)
    for (int i = 0; i < 12; ++i) {
      const Q y[3] = {Q(2 * next() - 1), Q(2 * next() - 1), Q(1 + next())};  // |y_0|, |y_1| < y_2
      const int keep = 1 + (i % 8);
      std::vector<global::V3> got;
      global::integer_normals(y, w, keep, got);
      BOOST_TEST((got == plain_loop(y, w, keep)), "window " << w << ", direction " << i);
      ++n;
    }
  BOOST_TEST(n == 132);
}
