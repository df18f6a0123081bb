// stats.h: the one median and the quantiles every report of compare/ uses.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "pdd/compare/stats.h"
#include "pdd/io/record_text.h"

using namespace pdd::compare;

BOOST_AUTO_TEST_SUITE(stats)

BOOST_AUTO_TEST_CASE(quantiles_interpolate_between_ranks) {
  // Sorted {1, 2, 3, 4, 5}: the median is 3; the 25% point sits at rank 1 (value 2); the 10%
  // point at rank 0.4: 1 + 0.4 (2 - 1) = 1.4.
  const auto q = quantiles({5, 1, 4, 2, 3}, {0, 0.1, 0.25, 0.5, 1});
  BOOST_TEST(q[0] == 1.0);
  BOOST_TEST(q[1] == 1.4, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(q[2] == 2.0);
  BOOST_TEST(q[3] == 3.0);
  BOOST_TEST(q[4] == 5.0);
  BOOST_TEST(quantiles({}, {0.5}).empty());
}

BOOST_AUTO_TEST_CASE(median_is_the_middle_or_the_mean_of_the_two_middles) {
  BOOST_TEST(median({3, 1, 2}) == 2.0);
  BOOST_TEST(median({4, 1, 3, 2}) == 2.5);  // not the upper middle (3)
  BOOST_TEST(median({7}) == 7.0);
  BOOST_TEST(std::isnan(median({})));      // no median
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(median({1, inf, inf, 2}) == inf);  // failures counted as +inf stay +inf
  BOOST_TEST(median({1, 2, inf}) == 2.0);
}

BOOST_AUTO_TEST_SUITE_END()

// decimal17 (record_text.h): a rational correctly rounded to 17 significant digits, half to
// even, laid out as %.17g would (positional for exponents -5..16); values worked by hand.
BOOST_AUTO_TEST_CASE(rationals_round_to_17_digits_half_to_even) {
  struct Case {
    const char* q;
    const char* decimal;
    bool exact;
  };
  const Case cases[] = {
      {"16/3", "5.3333333333333333", false},        // 5.33333333333333333|3...: down
      {"2/3", "0.66666666666666667", false},        // 0.66666666666666666|6...: up
      {"1/12", "0.083333333333333333", false},
      {"1/8", "0.125", true},
      {"-7", "-7", true},
      {"0", "0", true},
      {"123456789012345678", "1.2345678901234568e+17", false},  // ...67|8: up, e = 17
      {"1/100000000", "1e-08", true},                            // e = -8: scientific
      {"100000000000000005/100000000000000000", "1", false},     // a tie, 1000...0 even: stays
      {"100000000000000015/100000000000000000", "1.0000000000000002", false},  // a tie, odd: up
  };
  for (const auto& c : cases) {
    bool exact = !c.exact;
    BOOST_TEST(pdd::io::decimal17(c.q, &exact) == c.decimal, c.q);
    BOOST_TEST(exact == c.exact, c.q);
  }
  // 9999999999999999999.9 rounds up to 10^19 exactly: the carry moves the exponent.
  BOOST_TEST(pdd::io::decimal17("99999999999999999999/10") == "1e+19");
}
