// fast_golden_test — the fast engine against the exact engine's golden records
// (fixtures/golden/**.jsonl, rational strings) on every fixture file that has one.
//
// Agreement required: error presence, `intersecting` and every label exactly (all decided by
// exact predicates or by exact ties, see tie_tolerance.h); the hot-path overloads (rigid_pd2,
// pdd2_accel over raw vertices) equal to solve_pair bit for bit. The VALUES and q1 are held to
// the project's argued tolerance (K eps R / sqrt(value), compare/pdd/compare/
// engine_comparison.h) by tests/compare/test_fast_vs_golden.cpp, not repeated here.
#define BOOST_TEST_MODULE fast_golden
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "deformable_depth.h"
#include "rigid_depth.h"
#include "pdd/pdd.h"

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
      BOOST_TEST(label(r.rigid_dir) == label(g.at("rigid_dir")));
      BOOST_TEST(label(r.pdd2_static_dir) == label(g.at("pdd2_static_dir")));
      BOOST_TEST(label(r.pdd2_dir) == label(g.at("pdd2_dir")));
      BOOST_TEST(label(r.pdd2_relaxed_dir) == label(g.at("pdd2_relaxed_dir")));
      // the hot paths over raw vertices (superset_depth.h) report what solve_pair reports
      const TetPair& p = pairs[&r - results.data()];
      const fast::Choice rigid = fast::rigid_pd2_choice(p.A, p.B), a1 = fast::pdd2_accel_choice(p.A, p.B, 1);
      BOOST_TEST(rigid.value == r.rigid_pd2);
      BOOST_TEST(a1.value == r.pdd2_accel1);
      if (r.intersecting) BOOST_TEST(rigid.label().str() == label(r.rigid_dir));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(all_fixtures_with_golden_records) {
  int files = 0;
  for (const char* top : {"smoke", "degenerate", "adversarial"}) {
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
  BOOST_TEST(files == 21);  // every shipped fixture file has a golden record: none may be skipped
}
