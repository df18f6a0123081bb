// record_line.h: the text written directly is the text of the JSON object it replaces,
// asked_keys(result_json(r, number), variants).dump() (a mesh contact: {"a", "b", then that
// object's keys but the name}), byte for byte, on records of every kind.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pdd/compare/engines.h"
#include "pdd/compare/generate.h"
#include "pdd/io/record_line.h"
#include "pdd/io/result_json.h"
#include "pdd/pdd.h"

namespace {

using pdd::PairResult;
using pdd::Rational;
using pdd::io::Json;

constexpr unsigned kAllBits = (1u << (pdd::kValueCount + 1)) - 1;  // every value and §9's keys

std::string object_text(const PairResult<double>& r, unsigned variants) {
  return pdd::compare::fast_record(r, variants).dump();  // (`pdd solve`'s record object)
}
std::string object_text(const PairResult<Rational>& r, unsigned variants) {
  const pdd::io::NumberWriter<Rational> number = [](const Rational& q) { return Json(q.get_str()); };
  return pdd::io::asked_keys(pdd::io::result_json(r, number), variants).dump();
}
// The mesh contact's object: a and b first, then the record's keys but its name.
template <class R>
std::string contact_object_text(std::size_t a, std::size_t b, const PairResult<R>& r, unsigned variants) {
  Json j;
  j["a"] = a;
  j["b"] = b;
  const Json record = Json::parse(object_text(r, variants));
  for (const auto& [key, value] : record.items())
    if (key != "name") j[key] = value;
  return j.dump();
}

template <class R>
void check_all_ways(const PairResult<R>& r) {
  for (unsigned variants : {kAllBits, 0u, 1u, 0x2du, 0x80u, 0x88u, 0x7fu}) {
    BOOST_TEST(pdd::io::record_line(r, variants) == object_text(r, variants));
    BOOST_TEST(pdd::io::contact_line(17, 4, r, variants) == contact_object_text(17, 4, r, variants));
  }
}

double from_bits(std::uint64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(record_line_text)

// Every double that can reach a record's number: nlohmann's shortest round-trip form, null
// where not finite (the serializer's rule).
BOOST_AUTO_TEST_CASE(numbers_are_written_as_the_serializer_writes_them) {
  std::vector<double> xs = {0.0, -0.0, 1.0, -1.0, 0.1, 1e-5, 1e21, 1e22, 123456789012345680.0, 5e-324,
                            2.2250738585072014e-308, std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN(), 3.325493306398034e-05, 0.00039905919676776403};
  std::mt19937_64 rng(11);
  for (int k = 0; k < 20000; ++k) xs.push_back(from_bits(rng()));  // any bit pattern: every exponent
  for (int k = 0; k < 2000; ++k) xs.push_back(double(std::int64_t(rng() % 2000001) - 1000000));  // integers
  PairResult<double> r;
  r.intersecting = true;
  for (std::size_t i = 0; i + 7 <= xs.size(); i += 7) {
    for (std::size_t k = 0; k < pdd::kValueCount; ++k) pdd::record_value(r, k) = xs[i + k % 7];
    r.q1_A[(i / 3) % 4][i % 3] = xs[i];
    r.q1_B_global[(i / 5) % 4][i % 3] = xs[i + 1];
    BOOST_TEST_REQUIRE(pdd::io::record_line(r) == object_text(r, kAllBits));
  }
}

// The fast engine's records of several families (every value, the gradient, pdd2_global
// declined where it is), under several sets of variants, as records and as mesh contacts.
BOOST_AUTO_TEST_CASE(fast_records_of_every_kind) {
  pdd::fast::SolveOptions with_gradient;
  with_gradient.gradient = true;
  int records = 0, declined = 0, rejected = 0;
  for (const char* family : {"paper", "aligned", "adversarial", "shared-face", "scaled-small"}) {
    for (const auto& pair : pdd::compare::generate_family(family, 5, 12)) {
      for (const auto& options : {pdd::fast::SolveOptions{}, with_gradient}) {
        PairResult<double> r = pdd::fast::solve_pair(pair, options);
        r.name = pair.name;
        check_all_ways(r);
        ++records;
        declined += r.pdd2_global_error.has_value();
        rejected += r.error.has_value();
      }
    }
  }
  BOOST_TEST_MESSAGE(records << " records, " << declined << " with pdd2_global declined, " << rejected << " rejected");
  BOOST_TEST(records == 5 * 12 * 2);
}

// Names and messages that need escaping (quotes, backslashes, control characters, UTF-8),
// a rejected pair, a declined pdd2_global.
BOOST_AUTO_TEST_CASE(strings_are_escaped_as_the_serializer_escapes_them) {
  for (const std::string name : {"plain", "with \"quotes\"", "back\\slash", "tab\there", "new\nline",
                                 "bell\x07", "caf\xc3\xa9", ""}) {
    PairResult<double> r;
    r.name = name;
    r.intersecting = true;
    r.rigid_dir = pdd::DirectionLabel::parse("EE:4:1");
    check_all_ways(r);
    r.pdd2_global_error = "no double normal: " + name;
    check_all_ways(r);
    PairResult<double> bad;
    bad.name = name;
    bad.error = "flat tetrahedron \"" + name + "\"";
    check_all_ways(bad);
  }
}

// The exact engine's numbers: "p/q" strings (`pdd mesh --engine reference`).
BOOST_AUTO_TEST_CASE(exact_records) {
  PairResult<Rational> r;
  r.name = "exact";
  r.intersecting = true;
  r.rigid_pd2 = Rational(1, 3);
  r.pdd2 = Rational(-7, 2);
  r.pdd2_global = Rational(5);
  r.pdd2_global_lower = Rational(4, 9);
  r.pdd2_global_normal = std::array<Rational, 3>{Rational(1), Rational(0), Rational(-1, 1024)};
  r.q1_A[2][1] = Rational(22, 7);
  r.pdd2_dir = pdd::DirectionLabel::parse("FV:1");
  check_all_ways(r);
  r.error = "rejected";
  check_all_ways(r);
}

BOOST_AUTO_TEST_SUITE_END()
