// The statistics of `pdd paper` on hand-made results (values derived in the comments).
#include <boost/test/unit_test.hpp>

#include "pdd/compare/paper_experiment.h"

using namespace pdd;
using namespace pdd::compare;

namespace {
PairResult<double> result(double pd2, double e11, double st, double def, double a1, double a6, double rel,
                          const char* rigid_dir, const char* pdd2_dir) {
  PairResult<double> r;
  r.intersecting = true;
  r.rigid_pd2 = pd2, r.eq11_pd2 = e11, r.pdd2_static = st, r.pdd2 = def;
  r.pdd2_accel1 = a1, r.pdd2_accel6 = a6, r.pdd2_relaxed = rel;
  r.rigid_dir = DirectionLabel::parse(rigid_dir);
  r.pdd2_dir = DirectionLabel::parse(pdd2_dir);
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(ratios_are_square_roots_of_squared_ratios) {
  // Pair 1: PD^2 = 4, static 1 -> ratio 1/2; def 0.25 -> 1/4. Pair 2: PD^2 = 16, static 4 ->
  // 1/2; def 9 -> 3/4. Static ratios {1/2, 1/2}: mean 1/2, std 0. Def ratios {1/4, 3/4}: mean
  // 1/2, sample std sqrt(((1/4)^2 + (1/4)^2) / 1) = sqrt(1/8).
  std::vector<PairResult<double>> rs = {result(4, 1, 1, 0.25, 0.25, 0.25, 0.25, "FV:0", "FV:0"),
                                        result(16, 16, 4, 9, 16, 9, 9, "FV:1", "EE:0:1")};
  PairResult<double> skipped;  // not intersecting: skipped and counted
  rs.push_back(skipped);
  const PaperStats s = paper_statistics(rs, [](double x) { return x; });
  BOOST_TEST(s.pairs == 2u);
  BOOST_TEST(s.skipped == 1u);
  BOOST_TEST(s.over_pd[0].mean == 0.5);
  BOOST_TEST(s.over_pd[0].std == 0.0);
  BOOST_TEST(s.over_pd[1].mean == 0.5);
  BOOST_TEST(s.over_pd[1].std == std::sqrt(0.125), boost::test_tools::tolerance(1e-15));
  // Over E11: pair 1 E11^2 = 1 -> def ratio sqrt(0.25/1) = 1/2; pair 2 -> 3/4: mean 5/8.
  BOOST_TEST(s.over_e11[1].mean == 0.625);
  BOOST_TEST(s.rigid_is_optimal == 1u);      // only pair 1 has rigid_dir == pdd2_dir
  BOOST_TEST(s.optimum_in_first_six == 2u);  // accel6 == pdd2 on both
}

BOOST_AUTO_TEST_CASE(volumes_of_both_tetrahedra) {
  // The unit corner tetrahedron has volume 1/6; B twice as large in each direction: 8/6.
  TetPair p;
  p.A = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  p.B = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}}};
  const auto v = tetrahedron_volumes({p});
  BOOST_TEST(v.size() == 2u);
  BOOST_TEST(v[0] == 1.0 / 6, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(v[1] == 8.0 / 6, boost::test_tools::tolerance(1e-15));
}
