// definitions §9 on near-coplanar contacts (data/near-coplanar.json, written by
// data/near-coplanar.py): a face of B 1e-15 to 1e-11 inside a face of A, tetrahedra of size ~8, B's
// face parallel or tilted by ~1e-12 rad, along coordinate planes and not. The depth is ~1e-25 of
// the size squared, far below suspect_proof.h's kUnrepresentedDepth, so the fast engine's
// pdd2_global is decided on exact pieces with suspects (a piece's eigenvector that held its signs
// within tolerance, its eigenvalue below the best offer); on the 11 pairs along coordinate planes
// the exact engine's witness normals are themselves double triples that attain pdd2_global. Each
// suspect is settled (represent_suspect): the pairs are computed, every value within definitions §8
// of the exact engine's, pdd2_global inside [pdd2_global_lower, pdd2_global] to 1e-9 and reproduced
// by its normal; so is the public pdd::fast::pdd2_global's.
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/compare/engine_comparison.h"
#include "fixtures.h"
#include "pdd/pdd.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;

namespace {
std::vector<TetPair> near_coplanar_pairs() {
  return test::load_pairs_at(std::string(PDD_COMPARE_DATA_DIR) + "/near-coplanar.json");
}
}  // namespace

BOOST_AUTO_TEST_CASE(near_coplanar_pdd2_global_computed_within_contract) {
  const auto pairs = near_coplanar_pairs();
  BOOST_TEST(pairs.size() == 15u);
  int computed = 0;
  for (const auto& p : pairs) {
    const auto exact = reference::solve_exact(p, {QpFormulation::Reduced});
    BOOST_TEST_REQUIRE(!exact.error, p.name);
    BOOST_TEST_REQUIRE(exact.intersecting, p.name);
    const auto t0 = std::chrono::steady_clock::now();
    const auto fast = fast::solve_pair(p);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    BOOST_TEST_MESSAGE(p.name << ": fast::solve_pair " << ms << " ms");
    BOOST_TEST(!fast.error, p.name << " rejected: " << fast.error.value_or(""));
    BOOST_TEST(!fast.pdd2_global_error, p.name << " pdd2_global declined: " << fast.pdd2_global_error.value_or(""));
    if (fast.error || fast.pdd2_global_error) continue;
    const auto c = compare::compare_pair(p, exact, fast);
    BOOST_TEST(c.global_error <= compare::kContractRel,
               p.name << " pdd2_global " << fast.pdd2_global << " exact [" << c.global_lower << ", "
                      << c.global_exact << "]");
    BOOST_TEST(c.global_normal_error <= compare::kContractRel, p.name << " pdd2_global_normal");
    BOOST_TEST(!c.over_tolerance(), p.name);
    // the public hot path (depth.cpp: started from the rigid direction) on the same pair
    const fast::NormalDepth g = fast::pdd2_global(p.A, p.B);
    BOOST_TEST((g.status == fast::DepthStatus::Ok), p.name << " public pdd2_global rejected");
    if (g.status == fast::DepthStatus::Ok) {
      PairResult<double> record = fast;
      record.pdd2_global = g.pd2;
      record.pdd2_global_normal = g.normal;
      const auto cg = compare::compare_pair(p, exact, record);
      BOOST_TEST(cg.global_error <= compare::kContractRel, p.name << " public pdd2_global " << g.pd2);
      BOOST_TEST(cg.global_normal_error <= compare::kContractRel, p.name << " public normal");
    }
    ++computed;
  }
  BOOST_TEST(computed == int(pairs.size()));
}
