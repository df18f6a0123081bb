// Bad input (definitions §1): one test per kind; a batch keeps going and reports every bad pair.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdlib>
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
  BOOST_TEST(contains(solve_exact(p).error, "not finite"));
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
  p.B[3] = {0.25, 0.25, 1e-300};  // tiny but non-zero volume: valid (definitions §1)
  BOOST_TEST(!validate_pair(p).has_value());
  p.A[1] = p.A[0];  // A repeated vertex, B valid: only A named
  BOOST_TEST(contains(validate_pair(p), "tetrahedron A is flat"));
  BOOST_TEST(!contains(validate_pair(p), "tetrahedron B"));
}

BOOST_AUTO_TEST_CASE(malformed_empty_and_shapeless_files) {
  using io::read_fixture_file;
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/malformed.json")).error,
                      "malformed JSON"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/empty.json")).error, "empty"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/no-pairs.json")).error,
                      "array field 'pairs'"));
  BOOST_TEST(contains(read_fixture_file(test::fixture_path("bad/does-not-exist.json")).error,
                      "cannot open"));
}

BOOST_AUTO_TEST_CASE(batch_reports_every_bad_pair_and_computes_the_rest) {
  const auto file = io::read_fixture_file(test::fixture_path("bad/mixed.json"));
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
      {"#8 (byte 735)", "missing or empty string field 'name'"},  // 1-based, the byte of its '{'
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

// ---- the fixture reader (compare/src/fixture_io.cpp), one defect per case ----

namespace {
const std::string kGoodTets =
    R"("A": [[0,0,0],[4,0,0],[0,4,0],[0,0,4]], "B": [[1,1,1],[2,1,1],[1,2,1],[1,1,2]])";
std::string one_pair(const std::string& name_json) {
  return R"({"pairs": [{"name": )" + name_json + ", " + kGoodTets + "}]}";
}
}  // namespace

BOOST_AUTO_TEST_CASE(numbers_beyond_the_double_range_are_infinite_coordinates) {
  const auto f = io::read_fixture_file(test::fixture_path("bad/overflow.json"));
  BOOST_REQUIRE(!f.error);
  BOOST_REQUIRE(f.entries.size() == 6u);
  BOOST_TEST(!f.entries[0].error.has_value());
  BOOST_TEST(f.entries[1].pair.name == "overflow-x");
  BOOST_TEST(!f.entries[1].error.has_value());
  BOOST_TEST((std::isinf(f.entries[1].pair.A[1][0]) && f.entries[1].pair.A[1][0] > 0));
  BOOST_TEST((std::isinf(f.entries[2].pair.B[2][2]) && f.entries[2].pair.B[2][2] < 0));
  BOOST_TEST(contains(solve_exact(f.entries[1].pair).error, "not finite"));
  // A number is never a name, however it is written.
  BOOST_TEST(f.entries[3].pair.name == "#4 (byte 342)");  // the 4th entry, its '{' at byte 342
  BOOST_TEST(contains(f.entries[3].error, "field 'name' must be a string, not a number"));
  // A string is never a coordinate, however it is spelled.
  BOOST_TEST(contains(f.entries[4].error, "vertex 3 coordinate z is not a number"));
  BOOST_TEST(!f.entries[5].error.has_value());
  BOOST_TEST(f.entries[5].pair.A[1][0] == 4.0);
  // Other large and small numbers are read as the double they round to.
  const auto g = io::parse_fixture_text(
      R"({"pairs": [{"name": "n", "A": [[1e308,-1.7976931348623157e308,1e-400],[4,0,0],[0,4,0],)"
      R"([0,0,184467440737095516160]], "B": [[1,1,1],[2,1,1],[1,2,1],[1,1,2]]}]})");
  BOOST_REQUIRE(!g.error);
  BOOST_TEST(g.entries[0].pair.A[0][0] == 1e308);
  BOOST_TEST(g.entries[0].pair.A[0][1] == -1.7976931348623157e308);
  BOOST_TEST(g.entries[0].pair.A[0][2] == 0.0);
  BOOST_TEST(g.entries[0].pair.A[3][2] == 184467440737095516160.0);
}

BOOST_AUTO_TEST_CASE(malformed_numbers_make_the_file_unreadable_with_a_byte_position) {
  for (const char* n : {"1.e400", "1e400e5", "-01e400", "01", "1.", "-", "+1", ".5", "1e", "1e+",
                        "--1", "0x10", "1e400.5", "Infinity", "NaN"}) {
    const std::string text = R"({"pairs": [{"name": "x", "A": [[0,0,0],[)" + std::string(n) +
                             R"(,0,0],[0,4,0],[0,0,4]], "B": [[1,1,1],[2,1,1],[1,2,1],[1,1,2]]}]})";
    const auto f = io::parse_fixture_text(text);
    BOOST_TEST(contains(f.error, "malformed JSON at byte "), n << ": " << f.error.value_or("no error"));
    BOOST_TEST(f.entries.empty(), n);
  }
  const auto f = io::read_fixture_file(test::fixture_path("bad/number-dot-exponent.json"));
  BOOST_TEST(contains(f.error, "malformed JSON at byte 46: '1.e400' is not a valid number"),
             f.error.value_or("no error"));
}

BOOST_AUTO_TEST_CASE(duplicate_keys_nul_bytes_and_trailing_garbage_are_unreadable) {
  BOOST_TEST(contains(io::read_fixture_file(test::fixture_path("bad/duplicate-pairs.json")).error,
                      "duplicate key \"pairs\" at byte 110"));
  BOOST_TEST(contains(io::read_fixture_file(test::fixture_path("bad/duplicate-name.json")).error,
                      "duplicate key \"name\" at byte 28"));
  BOOST_TEST(contains(io::parse_fixture_text(R"({"pairs": [], "x": {"a": 1, "a": 2}})").error,
                      "duplicate key \"a\""));
  BOOST_TEST(contains(io::read_fixture_file(test::fixture_path("bad/nul-byte.json")).error,
                      "NUL byte at byte 110"));
  BOOST_TEST(contains(io::parse_fixture_text(std::string("{\"pairs\": [\0]}", 14)).error, "NUL byte at byte 11"));
  BOOST_TEST(contains(io::read_fixture_file(test::fixture_path("bad/trailing-garbage.json")).error,
                      "malformed JSON at byte "));
  BOOST_TEST(contains(io::parse_fixture_text(one_pair("\"a\"") + " x").error, "malformed JSON"));
  BOOST_TEST(!io::parse_fixture_text(one_pair("\"a\"") + " \n").error.has_value());
  BOOST_TEST(contains(io::parse_fixture_text(" \n\t").error, "file is empty"));
  BOOST_TEST(contains(io::parse_fixture_text(R"({"pairs": 3})").error, "array field 'pairs'"));
  BOOST_TEST(contains(io::parse_fixture_text(R"([{"pairs": []}])").error, "array field 'pairs'"));
  // Keys that look alike are different keys; the same key in sibling objects is fine.
  BOOST_TEST(!io::parse_fixture_text(R"({"pairs": [], "Pairs": 1, "y": [{"a": 1}, {"a": 2}]})").error.has_value());
}

BOOST_AUTO_TEST_CASE(directories_and_missing_files_get_honest_messages) {
  BOOST_TEST(contains(io::read_fixture_file(PDD_FIXTURES_DIR).error, "is a directory"));
  BOOST_TEST(contains(io::read_fixture_file(test::fixture_path("bad/does-not-exist.json")).error,
                      "No such file or directory"));
  BOOST_TEST(contains(io::check_fixture_file(PDD_FIXTURES_DIR).error, "is a directory"));
}

BOOST_AUTO_TEST_CASE(mistyped_fields_reject_one_pair_by_name_or_index) {
  const auto f = io::read_fixture_file(test::fixture_path("bad/mistyped.json"));
  BOOST_REQUIRE(!f.error);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"good", ""},
      {"#2 (byte 114)", "field 'name' must be a string, not an array"},
      {"#3 (byte 230)", "missing or empty string field 'name'"},
      {"bad-tags", "field 'tags' must be an array of strings"},
      {"A-not-array", "field 'A' must be an array of 4 vertices"},
      {"vertex-two-numbers", "field 'A' vertex 0 must be an array of 3 numbers"},
      {"#7 (byte 630)", "entry is not a JSON object"},  // the scalar 7 at byte 630
      {"good-after", ""}};
  BOOST_REQUIRE(f.entries.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    BOOST_TEST(f.entries[k].pair.name == expected[k].first);
    if (expected[k].second.empty()) BOOST_TEST(!f.entries[k].error.has_value());
    else BOOST_TEST(contains(f.entries[k].error, expected[k].second), f.entries[k].error.value_or("none"));
  }
}

BOOST_AUTO_TEST_CASE(streaming_hands_over_every_entry_in_order_in_chunks) {
  const auto whole = io::read_fixture_file(test::fixture_path("bad/mixed.json"));
  BOOST_REQUIRE(!whole.error);
  const auto check = io::check_fixture_file(test::fixture_path("bad/mixed.json"));
  BOOST_TEST(!check.error.has_value());
  BOOST_TEST(check.entries == whole.entries.size());
  std::vector<io::FixtureEntry> got;
  std::vector<std::size_t> sizes, firsts;
  const auto error = io::stream_fixture_file(
      test::fixture_path("bad/mixed.json"), 4, [&](std::vector<io::FixtureEntry>& c, std::size_t first) {
        sizes.push_back(c.size());
        firsts.push_back(first);
        for (auto& e : c) got.push_back(e);
        return true;
      });
  BOOST_TEST(!error.has_value());
  BOOST_TEST(sizes == (std::vector<std::size_t>{4, 4, 1}), boost::test_tools::per_element());
  BOOST_TEST(firsts == (std::vector<std::size_t>{0, 4, 8}), boost::test_tools::per_element());
  BOOST_REQUIRE(got.size() == whole.entries.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    BOOST_TEST(got[k].pair.name == whole.entries[k].pair.name);
    BOOST_TEST(got[k].error.value_or("-") == whole.entries[k].error.value_or("-"));
  }
  // The sink can stop the reading.
  std::size_t calls = 0;
  io::stream_fixture_file(test::fixture_path("bad/mixed.json"), 2,
                               [&](std::vector<io::FixtureEntry>&, std::size_t) { return ++calls < 2; });
  BOOST_TEST(calls == 2u);
}

// Coordinates are doubles: an integer literal that is not exactly one (2^53 + 1, a 30-digit
// integer) rejects its entry, naming the integer and its byte; one that is exactly a double
// (2^53, 10^20 = 2^20 5^20 with 5^20 < 2^53, -0) and any decimal or exponent literal (the
// nearest double, as everywhere) is read as it is.
BOOST_AUTO_TEST_CASE(integer_literals_that_are_not_doubles_reject_their_entry) {
  auto entry = [](const std::string& x) {
    const std::string text = R"({"pairs": [{"name": "p", "A": [[0,0,0],[)" + x +
                             R"(,0,0],[0,4,0],[0,0,4]], "B": [[1,1,1],[2,1,1],[1,2,1],[1,1,2]]}]})";
    const auto f = io::parse_fixture_text(text);
    BOOST_REQUIRE(!f.error);
    BOOST_REQUIRE(f.entries.size() == 1u);
    return f.entries[0];
  };
  // byte 40 (counted from 0, as every byte in a message): where the second vertex's x starts
  BOOST_TEST(entry("9007199254740993").error.value_or("") ==
             "the integer 9007199254740993 at byte 40 is not exactly a double (coordinates are "
             "doubles; write it as one, e.g. 9007199254740992)");
  BOOST_TEST(contains(entry("-123456789012345678901234567890").error,
                      "the integer -123456789012345678901234567890 at byte 40 is not exactly a double"));
  // 10^400 as an integer literal: beyond the double range, named with its byte (its first 60
  // digits shown); 1e400 (an exponent) is read as infinity, which the engines reject as
  // non-finite (the tests above).
  BOOST_TEST(entry("1" + std::string(400, '0')).error.value_or("") ==
             "the integer 1" + std::string(59, '0') + "... at byte 40 is beyond the largest double (not finite)");
  BOOST_TEST(!entry("1e400").error.has_value());
  BOOST_TEST(std::isinf(entry("1e400").pair.A[1][0]));
  for (const char* ok : {"9007199254740992", "100000000000000000000", "-0", "9007199254740993.0",
                         "9007199254740993e0", "0.1"}) {
    const auto e = entry(ok);
    BOOST_TEST(!e.error.has_value(), ok);
    BOOST_TEST(e.pair.A[1][0] == std::strtod(ok, nullptr), ok);
  }
}
