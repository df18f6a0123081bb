// definitions §5's inequalities and the meaning of the answer, exactly, on every property fixture:
//   pdd2 <= pdd2_static <= PD^2,  pdd2 <= PD^2 / 2,
//   pdd2_relaxed <= pdd2 <= pdd2_accel6 <= pdd2_accel1,  E11^2 <= PD^2;
// the deformed positions attain pdd2 (object norm, eq. 3) and really separate along pdd2_dir,
// with the constrained vertices on the plane.
#include <boost/test/unit_test.hpp>

#include "fixtures.h"
#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/object_norm.h"
#include "pdd/reference/oriented_depth.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
ExactTet to_tet(const Positions<Rational>& q) {
  ExactTet t;
  for (int i = 0; i < 4; ++i) t[i] = Point(q[i][0], q[i][1], q[i][2]);
  return t;
}
}  // namespace

BOOST_AUTO_TEST_CASE(spec_inequalities_and_separation) {
  int intersecting = 0;
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactResult r = solve_exact(pair, {QpFormulation::Reduced});
      BOOST_REQUIRE(!r.error);
      if (!r.intersecting) continue;
      ++intersecting;
      const std::string& n = pair.name;
      BOOST_TEST(r.pdd2 > 0, n);
      BOOST_TEST(r.pdd2 <= r.pdd2_static, n);
      BOOST_TEST(r.pdd2_static <= r.rigid_pd2, n);
      BOOST_TEST(2 * r.pdd2 <= r.rigid_pd2, n);
      BOOST_TEST(r.pdd2_relaxed <= r.pdd2, n);
      BOOST_TEST(r.pdd2 <= r.pdd2_accel6, n);
      BOOST_TEST(r.pdd2_accel6 <= r.pdd2_accel1, n);
      BOOST_TEST(r.eq11_pd2 <= r.rigid_pd2, n);

      const ExactPair p = to_exact(pair);
      const ExactTet qa = to_tet(r.q1_A), qb = to_tet(r.q1_B);
      BOOST_TEST(object_norm(p.A, qa) + object_norm(p.B, qb) == r.pdd2, n);
      bool found = false;  // pdd2_dir must name one of the pair's candidates
      for (const auto& d : candidate_directions(p)) {
        if (d.label != *r.pdd2_dir) continue;
        found = true;
        const ExactPair deformed{qa, qb};
        const Rational plane = max_projection(qa, d.n);
        BOOST_TEST(oriented_depth_numerator(deformed, d.n) == 0, n);  // touching, separated
        for (int i = 0; i < 4; ++i) {
          if (d.constrained_A[i]) BOOST_TEST(d.n * (qa[i] - CGAL::ORIGIN) == plane, n);
          if (d.constrained_B[i]) BOOST_TEST(d.n * (qb[i] - CGAL::ORIGIN) == plane, n);
        }
      }
      BOOST_TEST(found, n << ": pdd2_dir " << *r.pdd2_dir << " is not a candidate");
    }
  BOOST_TEST(intersecting >= 12);
}
