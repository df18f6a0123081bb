// fast_aligned_global_test — definitions §9 on aligned pairs (parallel faces, parallel and
// colinear edges, coplanar faces: the pairs of structured meshes) stays on the double path.
//
// Pairs: the shipped aligned family (fixtures/families/aligned.json: Kuhn and five-tetrahedra
// cubes shifted by a non-grid offset, stacked cubes with touching faces) and the degenerate
// families of parallel edges, colinear edges and coplanar faces. On all of them the quick
// candidate lanes decline, which used to send the definitions §9 search to work without a start
// (all 225 pieces to the eigensolver, and on shifted five-tetrahedra pairs the exact pieces) and
// made global_minimiser decline every pair (the contact energy then ran the whole solve_pair).
// Pinned without timing, by what each path reports:
//  - global_depth with no start normal (the caller had no candidate: global_depth.h offers the
//    pair's own shallowest directions) neither builds its pieces in rationals (exact_value) nor
//    declines (certified), and its value is solve_pair's pdd2_global within definitions §8
//    twice over (both within 1e-9 of the exact minimum: 2e-9 of each other);
//  - global_minimiser declines none of them and equals solve_pair's definitions §9 fields bit
//    for bit (pdd/global_minimiser.h); so on the near-touching family, whose enumeration is
//    exact (its value taken again in rationals, as solve_pair takes it).
// solve_pair's pdd2_global itself is judged against the exact engine by fast_golden_test and
// tests/compare (golden records of these files).
#define BOOST_TEST_MODULE fast_aligned_global
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "global/global_depth.h"
#include "pdd/global_minimiser.h"
#include "pdd/io/fixture_io.h"
#include "pdd/pdd.h"

using namespace pdd;

namespace {

const std::string kFixtures = PDD_FAST_FIXTURES_DIR;
const char* const kFiles[] = {"families/aligned.json", "families/parallel-edges.json",
                              "families/colinear-edges.json", "families/coplanar-faces.json"};

std::vector<TetPair> read_pairs(const std::string& file) {
  const io::FixtureFile f = io::read_fixture_file(file);
  if (f.error) throw std::runtime_error(file + ": " + *f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) out.push_back(e.pair);
  return out;
}

// The intersecting pairs of every file with their solve_pair records (definitions §9 on).
struct Solved {
  TetPair pair;
  PairResult<double> record;
};
std::vector<Solved> solved_pairs(const std::vector<const char*>& files = {std::begin(kFiles), std::end(kFiles)}) {
  std::vector<Solved> out;
  fast::SolveOptions o;
  o.with_global = true;
  for (const char* f : files)
    for (const TetPair& p : read_pairs(kFixtures + "/" + f)) {
      PairResult<double> r = fast::solve_pair(p, o);
      if (!r.error && r.intersecting) out.push_back({p, r});
    }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(global_depth_without_start_stays_in_doubles) {
  const std::vector<Solved> pairs = solved_pairs();
  BOOST_TEST(pairs.size() >= 30u);  // 24 aligned + the degenerate families' intersecting pairs
  const double none[3] = {0, 0, 0};
  int exact = 0;
  for (const Solved& s : pairs) {
    BOOST_TEST_CONTEXT(s.pair.name) {
      const PairResult<double>& r = s.record;
      BOOST_REQUIRE(!r.pdd2_global_error);
      // the pair as given (coordinates of order 1: inside the double pieces' range); the
      // bounds as the pdd2_global fallback passes them: certified rigid_pd2 and pdd2_relaxed
      const fast::GlobalOptimum g = fast::global_depth(s.pair.A, s.pair.B, none, r.pdd2_relaxed, {}, r.rigid_pd2);
      exact += g.exact_value;
      BOOST_TEST(g.certified);
      BOOST_TEST(std::fabs(g.value - r.pdd2_global) <= 2e-9 * r.pdd2_global, g.value << " vs " << r.pdd2_global);
      bool ok = true;  // the normal reproduces the value (definitions §8 on the normal)
      const double along = fast::exact_relaxed_value(s.pair.A, s.pair.B, g.normal, ok);
      BOOST_TEST(ok);
      BOOST_TEST(std::fabs(along - g.value) <= 1e-9 * along, along << " along the normal, reported " << g.value);
    }
  }
  BOOST_TEST(exact == 0);  // none in rationals: the start's offers prune as a caller's start does
}

// global_minimiser against solve_pair's fields on `pairs`: the number declined and compared.
std::pair<int, int> check_against_solve_pair(const std::vector<Solved>& pairs) {
  int declined = 0, compared = 0;
  for (const Solved& s : pairs) {
    BOOST_TEST_CONTEXT(s.pair.name) {
      const auto g = fast::global_minimiser(s.pair.A, s.pair.B);
      if (!g) {
        ++declined;
        continue;
      }
      const PairResult<double>& r = s.record;
      BOOST_REQUIRE(!r.pdd2_global_error);
      BOOST_TEST(g->pd2 == r.pdd2_global);
      BOOST_TEST((g->normal == *r.pdd2_global_normal));
      BOOST_TEST((g->q1_A == r.q1_A_global));
      BOOST_TEST((g->q1_B == r.q1_B_global));
      ++compared;
    }
  }
  return {declined, compared};
}

BOOST_AUTO_TEST_CASE(global_minimiser_takes_aligned_pairs) {
  const auto [declined, compared] = check_against_solve_pair(solved_pairs());
  BOOST_TEST(compared >= 30);
  BOOST_TEST(declined == 0);
}

// Near-touching pairs (depths ~1e-12 of their size): global_depth builds the pieces in
// rationals, and solve_pair takes the value again exactly on the pair as given; global_minimiser
// does the same instead of declining (the caller would redo the exact enumeration in solve_pair).
BOOST_AUTO_TEST_CASE(global_minimiser_takes_exact_enumerations) {
  const auto [declined, compared] = check_against_solve_pair(solved_pairs({"families/near-touching.json"}));
  BOOST_TEST(compared == 4);  // the family's 4 intersecting pairs
  BOOST_TEST(declined == 0);
}
