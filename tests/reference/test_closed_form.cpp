// Values derived by hand (derivations in the comments), checked exactly.
#include <boost/test/unit_test.hpp>

#include "fixtures.h"
#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
CandidateDirection direction(const ExactPair& p, const std::string& label) {
  for (const auto& d : candidate_directions(p))
    if (d.label.str() == label) return d;
  throw std::runtime_error("no direction " + label);
}
Rational q(long num, long den = 1) { return Rational(num, den); }
}  // namespace

// poke-vertex-through-face: A = corner tetrahedron (0,0,0),(10,0,0),(0,10,0),(0,0,10);
// B's base r0, r1, r2 lies at z = -1 and its apex r3 = (1.5, 1.5, 0.5) pokes through A's face
// z = 0 (opposite s3) to depth t = 1/2. The apex is 1.5 from the faces x = 0 and y = 0 and far
// from the slanted face, so:
//   PD = t = 1/2 along FV:3 (n = -z, out of A through z = 0), PD^2 = 1/4.
// Case 1 (A static): any admissible plane leaves int A on one side, so B's apex must travel at
// least t along the plane normal u. With t3 = t fixed, minimising sum t_i^2 + (sum t_i)^2
// over the other three (which have slack 1 >= t/4) gives t_i = -S, S = t/4, value (5/4) t^2,
// so sigma_B = t^2 / 16 = 1/64, attained along FV:3 and nowhere else.
// Case 2 along FV:3, u = -z, plane at u.x = c: A's face (u = 0) is constrained, t = c for
// s0..s2, the free s3 (u = -10) takes t = -S => S = 3c/2, cost_A = 3c^2 + 2 (3c/2)^2 =
// 7.5 c^2; B's apex (u = -1/2) must reach c: tau = c + 1/2, cost_B = 1.25 tau^2 as above.
// d/dc [7.5 c^2 + 1.25 (c + 1/2)^2] = 0 => c = -1/14, tau = 3/7, total 52.5/196, / 20 = 3/224.
// Positions: A's face rises to z = 1/14, s3 drops by 3/28 to z = 277/28; the apex lands on
// z = 1/14 and the base rises by tau/4 = 3/28 to z = -25/28.
BOOST_AUTO_TEST_CASE(vertex_poking_through_a_face) {
  const TetPair pair = test::load_pair("smoke.json", "poke-vertex-through-face");
  const ExactResult r = solve_exact(pair);
  BOOST_REQUIRE(!r.error);
  BOOST_TEST(r.intersecting);
  BOOST_TEST(r.rigid_pd2 == q(1, 4));
  BOOST_TEST(r.rigid_dir->str() == "FV:3");
  BOOST_TEST(r.eq11_pd2 == q(1, 4));  // partial overlap on the minimising axis: E11 = PD
  BOOST_TEST(r.pdd2_static == q(1, 64));
  BOOST_TEST(r.pdd2_static_dir->str() == "FV:3");

  const ExactPair p = to_exact(pair);
  const CandidateDirection fv3 = direction(p, "FV:3");
  for (auto f : {QpFormulation::Full, QpFormulation::Reduced}) {
    const auto def = direction_qp(p, fv3, PddCase::Deformable, f);
    BOOST_REQUIRE(def.has_value());
    BOOST_TEST(def->value == q(3, 224));
    for (int i = 0; i < 3; ++i) {
      BOOST_TEST(def->q1_A[i].z() == q(1, 14));
      BOOST_TEST(def->q1_B[i].z() == q(-25, 28));
    }
    BOOST_TEST(def->q1_A[3].z() == q(277, 28));
    BOOST_TEST(def->q1_B[3].z() == q(1, 14));
    BOOST_TEST(def->q1_B[3].x() == q(3, 2));  // no motion orthogonal to n
    // Relaxed along FV:3: for c in (-1/2, 0) A's face must still drop to c (same costs), for
    // c >= 0 only B moves (cost >= 1.25/4 > 52.5/196): same optimum 3/224.
    BOOST_TEST(direction_qp(p, fv3, PddCase::Relaxed, f)->value == q(3, 224));
    BOOST_TEST(direction_qp(p, fv3, PddCase::Static, f)->value == q(1, 64));
  }
  BOOST_TEST(r.pdd2 <= q(3, 224));  // the global case-2 minimum is at most FV:3's
}

// nested-1: B = corner tetrahedron with legs 1/2 at (2,2,2), well inside A (legs 10).
// Leaving through x = 0, y = 0 or z = 0 costs 2.5; through the slanted face x+y+z = 10 B's
// lowest value of x+y+z is 6, so the distance is 4/sqrt(3): PD^2 = 16/3 along FV:0.
// Eq. 11: the projections nest on every axis, and the overlap is B's width; B's smallest
// width is its height over its own slanted face, (1/2)/sqrt(3), on a VF/FV normal:
// E11^2 = 1/12 < PD^2. The appendix theorem fails here.
BOOST_AUTO_TEST_CASE(nested_pair_breaks_the_appendix_theorem) {
  const ExactResult r = solve_exact(test::load_pair("smoke.json", "nested-1"));
  BOOST_TEST(r.rigid_pd2 == q(16, 3));
  BOOST_TEST(r.rigid_dir->str() == "FV:0");
  BOOST_TEST(r.eq11_pd2 == q(1, 12));
}

// Interiors disjoint (far apart) or only touching (a shared face): not intersecting, every
// value 0, no labels, q1 = the rest pose (definitions §4, §6).
BOOST_AUTO_TEST_CASE(disjoint_and_touching_pairs_report_zero) {
  for (const std::string name : {"disjoint-1", "touching-face-1"}) {
    const TetPair pair = test::load_pair("smoke.json", name);
    const ExactResult r = solve_exact(pair);
    BOOST_REQUIRE(!r.error);
    BOOST_TEST(!r.intersecting, name);
    for (const Rational* v : {&r.rigid_pd2, &r.eq11_pd2, &r.pdd2_static, &r.pdd2,
                              &r.pdd2_relaxed, &r.pdd2_accel1, &r.pdd2_accel6})
      BOOST_TEST(*v == q(0), name);
    BOOST_TEST(!r.rigid_dir.has_value());
    BOOST_TEST(!r.pdd2_dir.has_value());
    BOOST_TEST(r.q1_B[3][2] == Rational(pair.B[3][2]));
  }
}

// A pure translation of B along n with A static costs |t|^2 = sigma (paper eq. 5): with both
// tetrahedra translated by the same vector nothing changes, and scaling the poke example by
// 2^20 multiplies every squared value by 2^40 (fixtures large-/small-coordinates-1 are the
// poke example scaled by 2^20 and 2^-20).
BOOST_AUTO_TEST_CASE(scaled_copies_of_the_poke_example) {
  const Rational s40 = Rational(1LL << 40);
  const ExactResult big = solve_exact(test::load_pair("degenerate.json", "large-coordinates-1"),
                                     {QpFormulation::Reduced});
  const ExactResult small = solve_exact(test::load_pair("degenerate.json", "small-coordinates-1"),
                                       {QpFormulation::Reduced});
  BOOST_TEST(big.rigid_pd2 == q(1, 4) * s40);
  BOOST_TEST(big.pdd2_static == q(1, 64) * s40);
  BOOST_TEST(small.rigid_pd2 == q(1, 4) / s40);
  BOOST_TEST(small.pdd2_static == q(1, 64) / s40);
  BOOST_TEST(big.pdd2 == small.pdd2 * s40 * s40);
}
