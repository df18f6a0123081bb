// The peers of `pdd bench` (FCL, libccd) on pairs whose rigid PD is known in closed form.
// No timing here: speed is reported by `pdd bench`, never asserted in tests.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "fixtures.h"
#include "pdd/compare/peer_ccd.h"
#include "pdd/compare/peer_fcl.h"

using namespace pdd;
using namespace pdd::compare;

namespace {

// Rounding allowance on top of each peer's stopping tolerance: the EPA runs O(100) double
// operations on coordinates of magnitude R <= 10 (smoke.json's poke pair), each within
// eps = 2^-53 relative; 1e-12 is ~50x that count (64 eps R ~ 7e-14), far below the tolerances.
constexpr double kRounding = 1e-12;

}  // namespace

BOOST_AUTO_TEST_SUITE(peers)

// "poke-vertex-through-face": B's apex (1.5, 1.5, 0.5) pokes 1/2 through A's face z = 0;
// PD = 1/2 exactly (pushing B down by 1/2 along −z).
BOOST_AUTO_TEST_CASE(fcl_poke_vertex_through_face) {
  const TetPair p = test::load_pair("smoke.json", "poke-vertex-through-face");
  for (double tol : {1e-6, 1e-10}) {
    const PeerDepth d = fcl_penetration_depth(p.A, p.B, {FclSolver::Indep, tol});
    BOOST_TEST_CONTEXT("gjk/epa tolerance " << tol) {
      BOOST_TEST((d.status == PeerStatus::Intersecting));
      // peer_fcl.h: FCL's EPA stops when the support gap h − d <= tol, d <= PD <= h, so
      // |PD_fcl − PD| <= tol in exact arithmetic, plus rounding.
      BOOST_TEST(std::abs(d.pd - 0.5) <= tol + kRounding);
    }
  }
}

BOOST_AUTO_TEST_CASE(ccd_poke_vertex_through_face) {
  const TetPair p = test::load_pair("smoke.json", "poke-vertex-through-face");
  for (double tol : {1e-4, 1e-10}) {
    const PeerDepth d = ccd_penetration_depth(p.A, p.B, {tol, ~0UL});
    BOOST_TEST_CONTEXT("epa_tolerance " << tol) {
      BOOST_TEST((d.status == PeerStatus::Intersecting));
      // peer_ccd.h: libccd's EPA stops when (h − d)·d < tol or the new support point is within
      // squared distance tol of the nearest face, so |PD_ccd − PD| <= max(tol/PD_ccd,
      // sqrt(tol)) in exact arithmetic, plus rounding. PD_ccd = d.pd (the reported value).
      const double bound = std::max(tol / d.pd, std::sqrt(tol)) + kRounding;
      BOOST_TEST(std::abs(d.pd - 0.5) <= bound);
    }
  }
}

// "disjoint-1": unit corner tetrahedra 5 apart on each axis; no intersection.
BOOST_AUTO_TEST_CASE(peers_disjoint) {
  const TetPair p = test::load_pair("smoke.json", "disjoint-1");
  for (FclSolver s : {FclSolver::Indep, FclSolver::Libccd}) {
    const PeerDepth d = fcl_penetration_depth(p.A, p.B, {s, 1e-6});
    BOOST_TEST((d.status == PeerStatus::NotIntersecting));
    BOOST_TEST(d.pd == 0.0);
  }
  const PeerDepth c = ccd_penetration_depth(p.A, p.B);
  BOOST_TEST((c.status == PeerStatus::NotIntersecting));
  BOOST_TEST(c.pd == 0.0);
  const PeerDepth m = ccd_mpr_depth(p.A, p.B);
  BOOST_TEST((m.status == PeerStatus::NotIntersecting));
  BOOST_TEST(m.pd == 0.0);
}

// The same pairs with A and B swapped: PD is symmetric.
BOOST_AUTO_TEST_CASE(peers_symmetric) {
  const TetPair p = test::load_pair("smoke.json", "poke-vertex-through-face");
  const PeerDepth f = fcl_penetration_depth(p.B, p.A, {FclSolver::Indep, 1e-6});
  BOOST_TEST((f.status == PeerStatus::Intersecting));
  BOOST_TEST(std::abs(f.pd - 0.5) <= 1e-6 + kRounding);
  const PeerDepth c = ccd_penetration_depth(p.B, p.A, {1e-10, ~0UL});
  BOOST_TEST((c.status == PeerStatus::Intersecting));
  BOOST_TEST(std::abs(c.pd - 0.5) <= std::max(1e-10 / c.pd, 1e-5) + kRounding);
}

BOOST_AUTO_TEST_SUITE_END()
