#define BOOST_TEST_MODULE compare_bench
#include <boost/test/unit_test.hpp>
