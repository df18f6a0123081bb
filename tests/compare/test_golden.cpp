// The exact engine reproduces every golden file digit for digit.
#include <boost/test/unit_test.hpp>

#include "fixtures.h"
#include "pdd/compare/golden.h"

BOOST_AUTO_TEST_CASE(exact_engine_matches_golden_files) {
  const auto files = pdd::io::golden_fixture_files(PDD_FIXTURES_DIR);
  BOOST_TEST(files.size() >= 19u);
  for (const auto& m : pdd::compare::check_golden(PDD_FIXTURES_DIR, pdd::QpFormulation::Reduced))
    BOOST_ERROR(m.file << ": " << m.detail);
}
