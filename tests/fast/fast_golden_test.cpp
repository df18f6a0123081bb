// fast_golden_test — the fast engine against the exact engine's golden records
// (fixtures/golden/**.jsonl, rational strings) on every fixture file that has one.
//
// Agreement required: error presence, `intersecting` and every label exactly (all decided by
// exact predicates or by exact ties, see tie_tolerance.h); values and q1 to 1e-8 relative
// (+1e-12 absolute for q1); the hot-path overloads (rigid_pd2, pdd2_accel over raw vertices)
// equal to solve_pair bit for bit. The fast values carry rounding errors ~1e-16 amplified by the
// conditioning of the pair (observed worst 1e-10, on slivers); 1e-8 keeps two orders of margin
// and still catches any wrong direction, active set or variant (errors >= 1e-3 relative).
#define BOOST_TEST_MODULE fast_golden
#include <gmpxx.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "pdd/fast/deformable_depth.h"
#include "pdd/fast/rigid_depth.h"
#include "pdd/fast/solve_pair.h"

using namespace pdd;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kFixtures = PDD_FAST_FIXTURES_DIR;

std::vector<TetPair> read_pairs(const fs::path& file) {
  std::ifstream in(file);
  const json j = json::parse(in);
  std::vector<TetPair> out;
  for (const auto& p : j.at("pairs")) {
    TetPair t;
    t.name = p.at("name").get<std::string>();
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        t.A[i][k] = p.at("A")[i][k].get<double>();
        t.B[i][k] = p.at("B")[i][k].get<double>();
      }
    out.push_back(t);
  }
  return out;
}

std::map<std::string, json> read_golden(const fs::path& file) {
  std::map<std::string, json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) {
      json j = json::parse(line);
      out[j.at("name").get<std::string>()] = j;
    }
  return out;
}

bool close(double fast, const std::string& exact, double rel, double abs) {
  const mpq_class e(exact), f(fast);
  mpq_class d = f - e;
  if (d < 0) d = -d;
  mpq_class m = e < 0 ? mpq_class(-e) : e;
  return d <= mpq_class(rel) * m + mpq_class(abs);
}

std::string label(const std::optional<DirectionLabel>& l) { return l ? l->str() : "null"; }
std::string label(const json& j) { return j.is_null() ? "null" : j.get<std::string>(); }

void check_file(const fs::path& fixture, const fs::path& golden) {
  const auto pairs = read_pairs(fixture);
  const auto gold = read_golden(golden);
  const auto results = fast::solve_batch(pairs);
  for (const auto& r : results) {
    BOOST_TEST_CONTEXT(fixture.filename().string() << " / " << r.name) {
      const auto it = gold.find(r.name);
      BOOST_REQUIRE(it != gold.end());
      const json& g = it->second;
      BOOST_TEST(bool(r.error) == !g.at("error").is_null());
      if (r.error || !g.at("error").is_null()) continue;
      BOOST_TEST(r.intersecting == g.at("intersecting").get<bool>());
      const std::pair<const char*, double> values[] = {
          {"rigid_pd2", r.rigid_pd2},     {"eq11_pd2", r.eq11_pd2},
          {"pdd2_static", r.pdd2_static}, {"pdd2", r.pdd2},
          {"pdd2_relaxed", r.pdd2_relaxed}, {"pdd2_accel1", r.pdd2_accel1},
          {"pdd2_accel6", r.pdd2_accel6}};
      for (const auto& [key, v] : values)
        BOOST_TEST(close(v, g.at(key).get<std::string>(), 1e-8, 0.0),
                   key << ": fast " << v << " exact " << g.at(key).get<std::string>());
      BOOST_TEST(label(r.rigid_dir) == label(g.at("rigid_dir")));
      BOOST_TEST(label(r.pdd2_static_dir) == label(g.at("pdd2_static_dir")));
      BOOST_TEST(label(r.pdd2_dir) == label(g.at("pdd2_dir")));
      BOOST_TEST(label(r.pdd2_relaxed_dir) == label(g.at("pdd2_relaxed_dir")));
      // the hot paths over raw vertices (superset_depth.h) report what solve_pair reports
      const TetPair& p = pairs[&r - results.data()];
      const fast::Choice rigid = fast::rigid_pd2(p.A, p.B), a1 = fast::pdd2_accel(p.A, p.B, 1);
      BOOST_TEST(rigid.value == r.rigid_pd2);
      BOOST_TEST(a1.value == r.pdd2_accel1);
      if (r.intersecting) BOOST_TEST(rigid.label().str() == label(r.rigid_dir));
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
          BOOST_TEST(close(r.q1_A[i][k], g.at("q1_A")[i][k].get<std::string>(), 1e-8, 1e-12));
          BOOST_TEST(close(r.q1_B[i][k], g.at("q1_B")[i][k].get<std::string>(), 1e-8, 1e-12));
        }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(all_fixtures_with_golden_records) {
  int files = 0;
  for (const char* top : {"smoke", "degenerate"}) {
    const fs::path golden = kFixtures / "golden" / (std::string(top) + ".jsonl");
    if (!fs::exists(golden)) continue;
    check_file(kFixtures / (std::string(top) + ".json"), golden);
    ++files;
  }
  if (fs::is_directory(kFixtures / "families"))
    for (const auto& e : fs::directory_iterator(kFixtures / "families")) {
      if (e.path().extension() != ".json") continue;
      const fs::path golden =
          kFixtures / "golden" / "families" / (e.path().stem().string() + ".jsonl");
      if (!fs::exists(golden)) continue;
      check_file(e.path(), golden);
      ++files;
    }
  BOOST_TEST(files >= 2);  // the fixture tree must be found: a vacuous pass is a failure
}
