// Bad input (SPEC §1): one test per kind; a batch keeps going and reports every bad pair.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "fixtures.h"
#include "pdd/compare/engines.h"
#include "pdd/reference/validate_pair.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
TetPair unit_pair() {
  TetPair p;
  p.name = "unit";
  p.A = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  p.B = p.A;
  return p;
}
bool contains(const std::optional<std::string>& s, const std::string& what) {
  return s && s->find(what) != std::string::npos;
}
}  // namespace

BOOST_AUTO_TEST_CASE(nan_coordinate) {
  TetPair p = unit_pair();
  p.B[2][1] = std::numeric_limits<double>::quiet_NaN();
  const auto why = validate_pair(p);
  BOOST_TEST(contains(why, "tetrahedron B: vertex 2 coordinate y is not finite"));
  BOOST_TEST(contains(solve_pair(p).error, "not finite"));
}

BOOST_AUTO_TEST_CASE(infinite_coordinate) {
  TetPair p = unit_pair();
  p.A[0][0] = -std::numeric_limits<double>::infinity();
  BOOST_TEST(contains(validate_pair(p), "tetrahedron A: vertex 0 coordinate x is not finite"));
}

BOOST_AUTO_TEST_CASE(flat_tetrahedra_are_rejected_exactly) {
  TetPair p = unit_pair();
  p.A[3] = {0.25, 0.25, 0};  // in the plane z = 0 of the other three
  BOOST_TEST(contains(validate_pair(p), "tetrahedron A is flat"));
  p = unit_pair();
  p.B[3] = {0.25, 0.25, 1e-300};  // tiny but non-zero volume: valid (SPEC §1)
  BOOST_TEST(!validate_pair(p).has_value());
  p.A[1] = p.A[0];  // A repeated vertex, B valid: only A named
  BOOST_TEST(contains(validate_pair(p), "tetrahedron A is flat"));
  BOOST_TEST(!contains(validate_pair(p), "tetrahedron B"));
}

BOOST_AUTO_TEST_CASE(malformed_empty_and_shapeless_files) {
  using compare::read_fixture_file;
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/malformed.json")).error,
                      "malformed JSON"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/empty.json")).error, "empty"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/no-pairs.json")).error,
                      "array field 'pairs'"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/does-not-exist.json")).error,
                      "cannot open"));
}

BOOST_AUTO_TEST_CASE(batch_reports_every_bad_pair_and_computes_the_rest) {
  const auto file = compare::read_fixture_file(test::fixture_path("bad/mixed.json"));
  BOOST_REQUIRE(!file.error);
  const auto results = compare::run_reference(file.entries, {QpFormulation::Reduced}, false);
  BOOST_REQUIRE(results.size() == 9u);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"good-before", ""},
      {"flat-A", "tetrahedron A is flat"},
      {"flat-B-colinear", "tetrahedron B is flat"},
      {"infinite-coordinate", "vertex 1 coordinate x is not finite"},
      {"missing-B", "missing field 'B'"},
      {"three-vertices", "field 'A' must be an array of 4 vertices"},
      {"string-coordinate", "vertex 3 coordinate z is not a number"},
      {"#7", "missing or empty string field 'name'"},
      {"good-after", ""}};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    BOOST_TEST(results[k].name == expected[k].first);
    if (expected[k].second.empty()) {
      BOOST_TEST(!results[k].error.has_value(), results[k].name);
      BOOST_TEST(results[k].intersecting, results[k].name);
    } else {
      BOOST_TEST(contains(results[k].error, expected[k].second), results[k].name);
    }
  }
}
