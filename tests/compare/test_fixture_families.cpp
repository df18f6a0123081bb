// Fixture families: the shipped files are exactly what scripts/make-fixtures.sh records, and
// every family has the property it is named after, checked exactly.
#include <boost/test/unit_test.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "fixtures.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/generate.h"
#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/solve_pair.h"

using namespace pdd;

namespace {
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
struct Recipe {
  std::string family;
  std::uint64_t seed;
  std::size_t count;
};
// The "family seed count" lines of scripts/make-fixtures.sh.
std::vector<Recipe> recipes() {
  const std::string script = read_text(std::string(PDD_FIXTURES_DIR) + "/../scripts/make-fixtures.sh");
  std::vector<Recipe> out;
  const std::regex line(R"(^([a-z-]+) (\d+) (\d+)$)");
  std::istringstream in(script);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_match(l, m, line)) out.push_back({m[1], std::stoull(m[2]), std::stoul(m[3])});
  }
  return out;
}
}  // namespace

BOOST_AUTO_TEST_CASE(fixture_families_reproduce) {
  const auto rs = recipes();
  BOOST_TEST(rs.size() == compare::fixture_families().size());  // every family is shipped
  for (const auto& r : rs) {
    const std::string shipped = read_text(test::fixture_path("families/" + r.family + ".json"));
    BOOST_TEST(compare::fixture_json(compare::generate_family(r.family, r.seed, r.count)) == shipped,
               r.family);
  }
}

BOOST_AUTO_TEST_CASE(closed_form_tags_hold_exactly) {
  int checked = 0;
  for (const auto& pair : test::load_pairs("families/closed-form.json")) {
    const auto rec = compare::exact_record(reference::solve_pair(pair, {reference::QpFormulation::Reduced}));
    for (const auto& [key, value] : compare::tag_expectations(pair)) {
      BOOST_TEST(rec.at(key).get<std::string>() == value, pair.name << " " << key);
      ++checked;
    }
  }
  BOOST_TEST(checked == 6 * 4);
}

BOOST_AUTO_TEST_CASE(families_have_their_property) {
  using namespace reference;
  auto has_edge_kind = [](const TetPair& p, EdgePairKind k) {
    const ExactPair e = to_exact(p);
    if (k == EdgePairKind::Colinear) return !colinear_edge_pairs(e).empty();
    for (const auto& d : candidate_directions(e))
      if (d.edge_kind == k) return true;
    return false;
  };
  for (const auto& p : test::load_pairs("families/parallel-edges.json"))
    BOOST_TEST(has_edge_kind(p, EdgePairKind::Parallel), p.name);
  for (const auto& p : test::load_pairs("families/colinear-edges.json"))
    BOOST_TEST(has_edge_kind(p, EdgePairKind::Colinear), p.name);
  for (const auto& p : test::load_pairs("families/touching.json")) {
    const auto r = solve_pair(p, {QpFormulation::Reduced});
    BOOST_TEST((!r.error && !r.intersecting), p.name);
  }
  for (const auto& p : test::load_pairs("families/undecidable-optimum.json")) {
    const auto r = solve_pair(p, {QpFormulation::Reduced});
    BOOST_TEST((r.pdd2_dir && r.pdd2_dir->orientation != EdgeOrientation::Decided), p.name);
  }
  for (const auto& p : test::load_pairs("families/near-touching.json")) {
    const auto r = solve_pair(p, {QpFormulation::Reduced});
    BOOST_TEST(r.intersecting, p.name);
    BOOST_TEST(r.rigid_pd2 < Rational(1, 1000000000) * Rational(1, 1000000000) * 1000, p.name);
  }
}
