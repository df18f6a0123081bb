// Fixture families: the shipped files are exactly what scripts/make-fixtures.sh records, and
// every family has the property it is named after, checked exactly.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

#include "fixtures.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/generate.h"
#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/solve_exact.h"

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
    BOOST_TEST(io::fixture_json(compare::generate_family(r.family, r.seed, r.count)) == shipped,
               r.family);
  }
}

BOOST_AUTO_TEST_CASE(closed_form_tags_hold_exactly) {
  int checked = 0;
  for (const auto& pair : test::load_pairs("families/closed-form.json")) {
    const auto rec = compare::exact_record(reference::solve_exact(pair, {QpFormulation::Reduced}));
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
    const auto r = solve_exact(p, {QpFormulation::Reduced});
    BOOST_TEST((!r.error && !r.intersecting), p.name);
  }
  for (const auto& p : test::load_pairs("families/undecidable-optimum.json")) {
    const auto r = solve_exact(p, {QpFormulation::Reduced});
    BOOST_TEST((r.pdd2_dir && r.pdd2_dir->orientation != EdgeOrientation::Decided), p.name);
  }
  for (const auto& p : test::load_pairs("families/aligned.json")) {  // axis edges: exactly parallel
    BOOST_TEST(has_edge_kind(p, EdgePairKind::Parallel), p.name);
    BOOST_TEST(solve_exact(p, {QpFormulation::Reduced}).intersecting, p.name);
  }
  for (const auto& p : test::load_pairs("families/near-touching.json")) {
    const auto r = solve_exact(p, {QpFormulation::Reduced});
    BOOST_TEST(r.intersecting, p.name);
    BOOST_TEST(r.rigid_pd2 < Rational(1, 1000000000) * Rational(1, 1000000000) * 1000, p.name);
  }
  // contacts made by rounding (PD² < 2^-80 L², L the largest |coordinate|: ~1e-17 of the size)
  // and cells of a copy turned 2^-30 rad (PD² < 2^-40 L²), every kind present
  std::map<std::string, int> rounding_kinds;
  for (const auto& p : test::load_pairs("families/rounding-contacts.json")) {
    const auto r = solve_exact(p, {QpFormulation::Reduced});
    double L = 0;
    for (const auto* t : {&p.A, &p.B})
      for (const auto& v : *t)
        for (double x : v) L = std::max(L, std::abs(x));
    const std::string kind = p.tags.at(1);
    ++rounding_kinds[kind];
    BOOST_TEST(r.intersecting, p.name);
    BOOST_TEST(r.rigid_pd2 < Rational(std::ldexp(L * L, kind == "turned-2^-30" ? -40 : -80)), p.name);
  }
  BOOST_TEST(rounding_kinds.size() == 3u);
}

// The adversarial family and the hand-made fixtures/adversarial.json: every pair valid, the
// promised intersection status and feature per kind (tag 1), and every exact squared output
// 0 or a normal double (so definitions §8 applies to the fast engine on all of them).
BOOST_AUTO_TEST_CASE(adversarial_pairs_have_their_property) {
  using namespace reference;
  const Rational dbl_min(std::numeric_limits<double>::min()), dbl_max(std::numeric_limits<double>::max());
  auto normal_or_zero = [&](const Rational& v) {
    return v == 0 || (CGAL::abs(v) >= dbl_min && CGAL::abs(v) <= dbl_max);
  };
  auto ulps_apart = [](const Vec3d& a, const Vec3d& b, int max_ulps) {  // b within a few ulps of a
    for (int k = 0; k < 3; ++k) {
      double x = a[k];
      int steps = 0;
      while (x != b[k] && steps <= max_ulps) x = std::nextafter(x, b[k]), ++steps;
      if (steps > max_ulps) return false;
    }
    return a != b;
  };
  auto max_abs = [](const TetPair& p) {
    double m = 0;
    for (const auto* t : {&p.A, &p.B})
      for (const auto& v : *t)
        for (double x : v) m = std::max(m, std::abs(x));
    return m;
  };
  std::map<std::string, int> kinds;
  std::vector<TetPair> pairs = test::load_pairs("families/adversarial.json");
  for (auto& p : test::load_pairs("adversarial.json")) pairs.push_back(p);
  for (const auto& p : pairs) {
    BOOST_REQUIRE(p.tags.size() >= 2);
    const std::string kind = p.tags[1];
    ++kinds[kind];
    const auto r = solve_exact(p, {QpFormulation::Reduced});
    BOOST_REQUIRE_MESSAGE(!r.error, p.name << ": " << *r.error);
    BOOST_TEST(r.intersecting == (kind != "near-touching-out"), p.name);
    for (const Rational* v : {&r.rigid_pd2, &r.eq11_pd2, &r.pdd2_static, &r.pdd2, &r.pdd2_relaxed,
                              &r.pdd2_accel1, &r.pdd2_accel6})
      BOOST_TEST(normal_or_zero(*v), p.name);
    if (kind == "ulp-sliver") {
      bool found = false;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) found = found || ulps_apart(p.A[i], p.A[j], 1);
      BOOST_TEST(found, p.name);
    } else if (kind == "ulp-needle") {
      BOOST_TEST((ulps_apart(p.A[0], p.A[1], 2) && ulps_apart(p.A[0], p.A[2], 2)), p.name);
    } else if (kind == "nearly-flat") {
      BOOST_TEST(compare::tetrahedron_volume(p.A) < 1e-9, p.name);
    } else if (kind == "near-touching-in") {
      BOOST_TEST(r.rigid_pd2 < Rational(std::ldexp(1.0, -100)), p.name);
    } else if (kind == "far-translated") {
      BOOST_TEST(max_abs(p) >= 1e6, p.name);
    } else if (kind == "far-vertex") {
      BOOST_TEST(max_abs(p) >= 1e15, p.name);
    }
  }
  BOOST_TEST(kinds.size() == 10u);  // every kind is shipped
}
