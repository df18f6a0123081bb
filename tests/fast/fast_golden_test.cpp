// fast_golden_test — the fast engine against the exact engine's golden records
// (fixtures/golden/**.jsonl, rational strings) on every fixture file that has one.
//
// Agreement required: error presence, `intersecting` and every label exactly (all decided by
// exact predicates or by exact ties, see tie_tolerance.h); the hot-path overloads (rigid_pd2,
// pdd2_accel over raw vertices) equal to solve_pair bit for bit, pdd2_global over raw vertices
// within the contract of solve_pair's. The VALUES and q1 are held to
// the project's argued tolerance (definitions §8, compare/harness/pdd/compare/
// engine_comparison.h) by tests/compare/test_fast_vs_golden.cpp, not repeated here.
#define BOOST_TEST_MODULE fast_golden
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "exact/exact_geometry.h"
#include "global/global_depth.h"
#include "kernel/rigid_depth.h"
#include "pdd/io/fixture_io.h"
#include "pdd/io/golden_files.h"
#include "pdd/pdd.h"
#include "pdd/rejection.h"
#include "qp/deformable_depth.h"

using namespace pdd;

namespace {

const std::string kFixtures = PDD_FAST_FIXTURES_DIR;

// Every pair of a fixture file, through io/'s reader (the one `pdd` uses).
std::vector<TetPair> read_pairs(const std::string& file) {
  const io::FixtureFile f = io::read_fixture_file(file);
  if (f.error) throw std::runtime_error(file + ": " + *f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) out.push_back(e.pair);  // malformed entries: engines reject
  return out;
}

// Golden records by name; numbers kept as the exact strings written (only error, intersecting
// and the labels are compared here).
std::map<std::string, PairResult<std::string>> read_golden(const std::string& file) {
  std::map<std::string, PairResult<std::string>> out;
  for (auto& r : io::read_result_lines<std::string>(
           file, [](const io::Json& j) { return j.get<std::string>(); }))
    out[r.name] = std::move(r);
  return out;
}

std::string label(const std::optional<DirectionLabel>& l) { return l ? l->str() : "null"; }

// The fast engine's pdd2_global_error kGlobalNotRepresentable (no double normal attains
// pdd2_global; the record keeps its other values) where
// pdd compare allows it (compare/harness/src/engine_comparison.cpp): the exact pdd2_relaxed
// below 1e-14 R^2, R the largest coordinate difference from A's first vertex.
bool global_unresolvable(const TetPair& p, const PairResult<std::string>& g) {
  using fast::detail::Q;
  Q relaxed(g.pdd2_relaxed);
  relaxed.canonicalize();
  Q R = 0;
  for (const auto* t : {&p.A, &p.B})
    for (const auto& v : *t)
      for (int k = 0; k < 3; ++k) {
        Q d = Q(v[k]) - Q(p.A[0][k]);
        if (d < 0) d = -d;
        if (d > R) R = d;
      }
  return g.intersecting && relaxed < Q(1e-14) * R * R;
}

// The labels of a fast record, in a record of the golden type (the other fields unset).
PairResult<std::string> labels_of(const PairResult<double>& r) {
  PairResult<std::string> l;
  l.rigid_dir = r.rigid_dir;
  l.pdd2_static_dir = r.pdd2_static_dir;
  l.pdd2_dir = r.pdd2_dir;
  l.pdd2_relaxed_dir = r.pdd2_relaxed_dir;
  return l;
}

std::set<std::string> global_rejected;  // pairs whose pdd2_global the fast engine declines

void check_file(const std::string& fixture, const std::string& golden) {
  const auto pairs = read_pairs(fixture);
  const auto gold = read_golden(golden);
  const auto results = fast::solve_batch(pairs);
  for (const auto& r : results) {
    BOOST_TEST_CONTEXT(fixture << " / " << r.name) {
      const auto it = gold.find(r.name);
      BOOST_REQUIRE(it != gold.end());
      const PairResult<std::string>& g = it->second;
      const TetPair& p = pairs[&r - results.data()];
      const bool declined = r.pdd2_global_error.has_value();
      if (declined && *r.pdd2_global_error == kGlobalNotRepresentable && !r.error && !g.error &&
          global_unresolvable(p, g))
        global_rejected.insert(r.name);  // allowed here, and pinned below; the rest is checked
      else
        BOOST_TEST(!declined, "pdd2_global declined: " << *r.pdd2_global_error);
      if (declined)  // nothing of it can be read as a depth
        BOOST_TEST((std::isnan(r.pdd2_global) && !r.pdd2_global_normal && std::isnan(r.q1_B_global[3][2])));
      BOOST_TEST(bool(r.error) == bool(g.error));
      if (r.error || g.error) continue;
      BOOST_TEST(r.intersecting == g.intersecting);
      // The aligned and rounding-contacts families, the adversarial family's nearly coplanar faces and nearly parallel
      // edges (within 2^-40) and the slivers and needles of 1-ulp edges are made of near ties:
      // candidates whose directions differ by rounding or by the construction's 2^-40 have values
      // equal to ~1e-16 to ~1e-12, and
      // definitions §8 lets either side of a tie closer than 1e-9 be named. There the labels are
      // judged by that contract against the exact values (tests/compare/test_fast_vs_golden.cpp,
      // fast_engine_within_contract_of_golden), and here the hot paths must name solve_pair's.
      auto tagged = [&p](const char* t) { return std::find(p.tags.begin(), p.tags.end(), t) != p.tags.end(); };
      const bool near_ties = tagged("aligned") || tagged("rounding-contacts") || tagged("nearly-coplanar-faces") ||
                             tagged("nearly-parallel-edges") || tagged("ulp-sliver") || tagged("ulp-needle");
      const PairResult<std::string>& want = near_ties ? labels_of(r) : g;
      BOOST_TEST(label(r.rigid_dir) == label(want.rigid_dir));
      BOOST_TEST(label(r.pdd2_static_dir) == label(want.pdd2_static_dir));
      BOOST_TEST(label(r.pdd2_dir) == label(want.pdd2_dir));
      BOOST_TEST(label(r.pdd2_relaxed_dir) == label(want.pdd2_relaxed_dir));
      // the hot paths over raw vertices (superset_depth.h) report what solve_pair reports
      const fast::Choice rigid = fast::rigid_pd2_choice(p.A, p.B), a1 = fast::pdd2_accel_choice(p.A, p.B, 1);
      BOOST_TEST(rigid.value == r.rigid_pd2);
      BOOST_TEST(a1.value == r.pdd2_accel1);
      if (r.intersecting) BOOST_TEST(rigid.label().str() == label(r.rigid_dir));
      // pdd2_static, pdd2, pdd2_relaxed over raw vertices (the lane sweeps pruned by
      // qp_lower_bound.h, which solve_pair runs too): solve_pair's values bit for bit and the
      // golden labels
      const fast::Depth hot[3] = {fast::pdd2_static(p.A, p.B), fast::pdd2(p.A, p.B), fast::pdd2_relaxed(p.A, p.B)};
      // solve_pair keeps the exact relations of definitions §5 (value_relations.h): the hot
      // values with the same lowering, against the record's bounds (pdd2's may be the exact
      // path's, pdd.h)
      double ref[3] = {hot[0].pd2, hot[1].pd2, hot[2].pd2};
      if (r.intersecting) {
        ref[0] = std::min(ref[0], r.rigid_pd2);
        ref[1] = std::min({ref[1], r.pdd2_static, r.pdd2_accel6});
        if (std::isnormal(r.rigid_pd2 / 2)) ref[1] = std::min(ref[1], r.rigid_pd2 / 2);
        ref[2] = std::min(ref[2], r.pdd2);
      }
      const double got[3] = {r.pdd2_static, r.pdd2, r.pdd2_relaxed};
      const std::optional<DirectionLabel>* gl[3] = {&want.pdd2_static_dir, &want.pdd2_dir, &want.pdd2_relaxed_dir};
      for (int i = 0; i < 3; ++i) {
        BOOST_TEST((hot[i].status == fast::DepthStatus::Ok));
        BOOST_TEST(got[i] == ref[i], got[i] << " vs " << ref[i] << " (hot " << hot[i].pd2 << ")");
        if (r.intersecting) BOOST_TEST((hot[i].dir && hot[i].dir->str() == label(*gl[i])));
      }
      // pdd2_global over raw vertices (its own start and screen, depth.cpp): both values are
      // within 1e-9 of the exact minimum (definitions §8), so within 2e-9 of each other (the
      // normals may differ among ties), and its normal reproduces its value: the exact relaxed
      // value along it (global_depth.h) within 1e-9.
      const fast::NormalDepth gd = fast::pdd2_global(p.A, p.B);
      if (declined) {  // the hot path declines it too, never with a number
        BOOST_TEST((gd.status == fast::DepthStatus::NotRepresentable && std::isnan(gd.pd2)));
        continue;
      }
      BOOST_TEST((gd.status == fast::DepthStatus::Ok));
      if (!r.intersecting) BOOST_TEST(gd.pd2 == 0.0);
      if (r.intersecting && gd.status == fast::DepthStatus::Ok) {
        BOOST_TEST(std::fabs(gd.pd2 - r.pdd2_global) <= 2e-9 * r.pdd2_global, gd.pd2 << " vs " << r.pdd2_global);
        bool ok = true;
        const double along = fast::exact_relaxed_value(p.A, p.B, gd.normal, ok);
        BOOST_TEST(ok);
        BOOST_TEST(std::fabs(along - gd.pd2) <= 1e-9 * along, along << " along the normal, reported " << gd.pd2);
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(all_fixtures_with_golden_records) {
  int files = 0;
  for (const std::string& rel : io::golden_fixture_files(kFixtures)) {
    const std::string golden = io::golden_path(kFixtures, rel);
    BOOST_TEST_CONTEXT(rel) {
      BOOST_REQUIRE_MESSAGE(std::ifstream(golden).good(), "no golden file " << golden);
    }
    check_file(kFixtures + "/" + rel, golden);
    ++files;
  }
  BOOST_TEST(files == 24);  // every shipped fixture file has a golden record: none may be skipped
  // Exactly the pairs whose double normals cannot represent pdd2_global (suspect_proof.h's
  // unrepresented(): a vertex 1e-18 inside a face, the exact minimum 13%, 7% and 22% below the
  // best double normal's value), and four contacts made by rounding (pdd2_relaxed ~1e-34 against
  // coordinates ~1: no double normal need attain it, global_unresolvable), have it declined; the
  // other pairs of those classes (a far vertex, a vertex 2^-60 inside a face, the other contacts
  // made by rounding, whose fast values lie in the exact engine's closed intervals) keep their
  // values: a wider rejection fails here.
  const std::set<std::string> expected = {"adversarial-1-3",       "adversarial-1-13",      "adversarial-1-23",
                                          "rounding-contacts-1-0", "rounding-contacts-1-3", "rounding-contacts-1-6",
                                          "rounding-contacts-1-9"};
  BOOST_TEST((global_rejected == expected));
}
