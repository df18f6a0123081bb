#define BOOST_TEST_MODULE fast_smoke
#include <boost/test/unit_test.hpp>
#include "pdd/fast/solve_pair.h"
#include <cstdio>
BOOST_AUTO_TEST_CASE(nested) {
  pdd::TetPair p;
  p.A = {{{0,0,0},{10,0,0},{0,10,0},{0,0,10}}};
  p.B = {{{2,2,2},{2.5,2,2},{2,2.5,2},{2,2,2.5}}};
  auto r = pdd::fast::solve_pair(p);
  std::printf("int %d rigid %g %s e11 %g st %g %s d %g %s rel %g %s a1 %g a6 %g\n", r.intersecting, r.rigid_pd2, r.rigid_dir->str().c_str(), r.eq11_pd2, r.pdd2_static, r.pdd2_static_dir->str().c_str(), r.pdd2, r.pdd2_dir->str().c_str(), r.pdd2_relaxed, r.pdd2_relaxed_dir->str().c_str(), r.pdd2_accel1, r.pdd2_accel6);
  BOOST_TEST(r.intersecting);
}
