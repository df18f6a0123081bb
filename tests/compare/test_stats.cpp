// stats.h: the one median and the quantiles every report of compare/ uses.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "pdd/compare/stats.h"

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
