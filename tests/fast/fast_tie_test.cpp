// fast_tie_test — the tie band of tie_tolerance.h: exact ties between differently computed
// candidates are recognised; true gaps of ~1e-11 relative are not ties.
#define BOOST_TEST_MODULE fast_tie
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>

#include "certification/certify.h"
#include "certification/tie_tolerance.h"
#include "exact/exact_path.h"
#include "exact/exact_predicates.h"
#include "fast_test_util.h"
#include "kernel/candidate_directions.h"
#include "kernel/power_scale.h"
#include "kernel/rigid_depth.h"
#include "pdd/pdd.h"

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;

namespace {

// Value of the candidate labelled `l` in the set (−1 when absent).
double value_of(const CandidateSet& set, const DirectionLabel& l) {
  for (int k = 0; k < set.count; ++k)
    if (label(set, k) == l) return set.delta_sq[k];
  return -1.0;
}

// x as an integer multiple of 2^-52 (exact for the coordinates used below, |x| < 2).
std::int64_t units(double x) {
  const double s = std::ldexp(x, 52);
  BOOST_REQUIRE(s == std::trunc(s));
  return std::int64_t(s);
}

}  // namespace

// The band's constant obeys the two constraints argued in tie_tolerance.h (E = 40, K = 256).
BOOST_AUTO_TEST_CASE(band_constant_between_error_and_harness) {
  static_assert(kTieCoeff >= 2 * 40 && kTieCoeff <= 256 - 2 * 40);
  // R/sqrt(v) = 20 (the paper's protocol): band = 128 u 20 ~ 2.8e-13 relative.
  const double R = 10.0, v = 0.25, kappa = kTieCoeff * kUnitRoundoff * R;
  BOOST_TEST(ties_with_min(v * (1 + 1e-14), v, kappa));
  BOOST_TEST(ties_with_min(v * (1 + 2e-13), v, kappa));
  BOOST_TEST(!ties_with_min(v * (1 + 1e-12), v, kappa));
  BOOST_TEST(!ties_with_min(v * (1 + 1e-11), v, kappa));
}

// Exact tie between an FV and two EE candidates with exactly parallel normals, computed along
// different operation sequences. A's base face s0 s1 s2 (coordinates in [1, 2): every
// difference of two coordinates is exact); B's top edge is A's edge s1 s2 translated by a
// dyadic t (exact additions), so eB = s2 − s1 exactly and the normals eB × (s1 − s0),
// eB × (s2 − s0) are exactly parallel to N_A,3 = (s1 − s0) × (s2 − s0). The exact minimum is
// attained by FV:3, EE:0:0 and EE:1:0 (checked with exact rationals while designing the test),
// so the label must be FV:3 (first in canonical order) whatever the rounding of each value.
BOOST_AUTO_TEST_CASE(exact_tie_fv_and_parallel_ee_is_recognised) {
  const Vec3d s0 = {1.03125, 1.1, 1.2}, s1 = {1.9, 1.05, 1.3}, s2 = {1.2, 1.95, 1.45},
              s3 = {1.4, 1.4, 1.99};
  const double ts[][3] = {{-0.0625, -0.0625, 0.03125},
                          {-0.125, -0.0625, 0.0625},
                          {-0.09375, -0.0625, 0.046875}};
  int differently_rounded = 0, ee_below_fv = 0;
  for (const auto& t : ts) {
    Vec3d r0, r1;
    for (int k = 0; k < 3; ++k) {
      r0[k] = s1[k] + t[k];
      r1[k] = s2[k] + t[k];
      // exact translation: r1 − r0 = s2 − s1 in exact arithmetic
      BOOST_REQUIRE(units(r1[k]) - units(r0[k]) == units(s2[k]) - units(s1[k]));
      BOOST_REQUIRE(units(r0[k]) - units(s1[k]) == units(t[k]));
    }
    const TetPair p = tet_pair({{s0, s1, s2, s3}}, {{r0, r1, {1.3, 1.2, -3.0}, {1.7, 1.9, -3.5}}});
    CandidateSet set;
    BOOST_REQUIRE((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
    BOOST_REQUIRE(set.intersecting);
    const double fv = value_of(set, DirectionLabel::fv(3));
    const double ee0 = value_of(set, DirectionLabel::ee(0, 0));
    const double ee1 = value_of(set, DirectionLabel::ee(1, 0));
    BOOST_REQUIRE((fv > 0 && ee0 > 0 && ee1 > 0));
    for (double x : {fv, ee0, ee1})
      for (double y : {fv, ee0, ee1}) BOOST_TEST(ties_with_min(x, y, set.tie_kappa));
    differently_rounded += (fv != ee0) + (fv != ee1);
    ee_below_fv += (ee0 < fv) + (ee1 < fv);
    BOOST_TEST(rigid_pd2(set).label() == DirectionLabel::fv(3));
    BOOST_TEST(rigid_pd2_choice(p.A, p.B).label() == DirectionLabel::fv(3));
    BOOST_TEST(*solve_pair(p).rigid_dir == DirectionLabel::fv(3));
  }
  BOOST_TEST(differently_rounded > 0);  // the tie is not a bitwise coincidence
  BOOST_TEST(ee_below_fv > 0);          // without the band the label would be an EE one
}

// A true gap of ~1.5e-11 relative is not a tie. A's base is the plane z = 0, B's top face
// r0 r1 r2 lies at z = 1/2 with r2 raised by eta = 2^-37. Exact values (rationals): VF:3 (and
// the later EE:0:1, EE:0:3) attain PD² = 0.25 + O(eta); FV:3, first in canonical order, is
// larger by 1.455e-11 relative. The band here is 128 u 6 / 0.5 ~ 1.7e-13: the label is VF:3
// (a fixed relative tolerance of 1e-9 would have chosen FV:3).
BOOST_AUTO_TEST_CASE(gap_of_1e_11_is_not_a_tie) {
  const double eta = std::ldexp(1.0, -37);
  const TetPair p = tet_pair({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 5}}},
                              {{{-4, -4, 0.5}, {6, -4, 0.5}, {-4, 6, 0.5 + eta}, {0, 0, -5}}});
  CandidateSet set;
  BOOST_REQUIRE((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
  BOOST_REQUIRE(set.intersecting);
  const double fv = value_of(set, DirectionLabel::fv(3));
  const double vf = value_of(set, DirectionLabel::vf(3));
  BOOST_TEST(fv / vf - 1 > 1e-11);
  BOOST_TEST(fv / vf - 1 < 2e-11);
  BOOST_TEST(!ties_with_min(fv, vf, set.tie_kappa));
  BOOST_TEST(rigid_pd2(set).label() == DirectionLabel::vf(3));
  BOOST_TEST(rigid_pd2_choice(p.A, p.B).label() == DirectionLabel::vf(3));
  BOOST_TEST(rigid_pd2_choice(p.A, p.B).value == vf);
  BOOST_TEST(*solve_pair(p).rigid_dir == DirectionLabel::vf(3));
}

// Blocks resting on each other 1e-9 deep, as `pdd mesh` meets them (element pairs of Gmsh
// transfinite plates, transfinite boxes and unstructured boxes, B moved up by the blocks'
// height less 1e-9): every candidate that can still be the rigid minimum is A's top face, B's
// bottom face or an edge pair lying in the resting plane z = const, all along +z, so their
// exact delta² are one value and the first of them in canonical order is the exact minimum's
// label. The structural test (certify.h's one_axis_direction) shows it without expansions: it
// must agree with the exact test (same_direction_exact) on every candidate along z, and refuse
// candidates of another direction; rigid_pd2 then certifies its choice as the exact first
// (what pdd2_accel1 takes), with the exact path's label and value (definitions §8).
BOOST_AUTO_TEST_CASE(resting_contacts_tie_along_one_axis) {
  const std::pair<TetVertices, TetVertices> pairs[] = {
      {TetVertices{{{0.03333333333326933, 0.0, 0.1}, {0.0, 0.0, 0.1}, {0.0, 0.03333333333347199, 0.1}, {0.03333333333326933, 0.0, 0.06666666666666667}}},
       TetVertices{{{0.012333333333333333, 0.006999999999999999, 0.099999999}, {0.045666666666602664, 0.006999999999999999, 0.099999999}, {0.012333333333333333, 0.04033333333347199, 0.099999999}, {0.012333333333333333, 0.04033333333347199, 0.13333333233333333}}}},
      {TetVertices{{{0.09999999999981414, 0.0, 0.5}, {0.0, 0.0, 0.5}, {0.0, 0.1000000000004162, 0.5}, {0.09999999999981414, 0.0, 0.4}}},
       TetVertices{{{0.037, 0.021, 0.499999999}, {0.13699999999981413, 0.021, 0.499999999}, {0.037, 0.1210000000004162, 0.499999999}, {0.037, 0.1210000000004162, 0.599999999}}}},
      {TetVertices{{{0.4620521328144115, 0.2003573719672778, 0.5}, {0.5197124346345628, 0.2336396521624281, 0.5}, {0.5205495546830375, 0.1685045796412356, 0.5}, {0.5099002544735984, 0.2123673020763618, 0.3756176197465442}}},
       TetVertices{{{0.4587401997669926, 0.1559086873115354, 0.499999999}, {0.5096877871109982, 0.13091310271246, 0.499999999}, {0.5163236381787243, 0.1895045796412355, 0.499999999}, {0.4732523597702786, 0.2071978808784119, 0.5828749703456607}}}},
  };
  for (const auto& [A, B] : pairs) {
    const detail::ScaledPair sp = detail::power_scaled(A, B);
    CandidateSet set;
    BOOST_REQUIRE((build_candidates(sp.A, sp.B, set) == BuildStatus::Ok));
    BOOST_REQUIRE(set.intersecting);
    int up[kMaxCandidates], off[kMaxCandidates], n = 0, others = 0;
    for (int k = 0; k < set.count; ++k) {
      const Candidate c = candidate(set, k);
      const unsigned zeros = c.parallel ? 0u : detail::structural_zero_components(sp.A, sp.B, label(set, k));
      if (zeros == 3u && c.n[2] > 0) up[n++] = k;  // x and y exactly 0: along +z (the sign is far from 0 here)
      else if (zeros != 3u && !c.parallel) off[others++] = k;
    }
    BOOST_REQUIRE(n > 0);
    for (int j = 1; j < n; ++j)
      BOOST_TEST(same_direction_exact(sp.A, sp.B, label(set, up[0]), label(set, up[j])).value_or(false));
    for (int j = 0; j < others; ++j) {
      const int two[2] = {up[0], off[j]};
      BOOST_TEST(!detail::one_axis_direction(set, two, 2));
      BOOST_TEST(!same_direction_exact(sp.A, sp.B, label(set, up[0]), label(set, off[j])).value_or(true));
    }
    BOOST_TEST(n >= 4);  // both faces and edge pairs of the plane
    BOOST_TEST(others > 0);
    BOOST_TEST(detail::one_axis_direction(set, up, n));
    const Choice ch = rigid_pd2(set);
    BOOST_TEST((ch.certified && ch.exact_first));
    const PairResult<double> ex = detail::solve_pair_exact_path(A, B).result;
    BOOST_TEST(ch.label() == *ex.rigid_dir);
    BOOST_TEST(std::abs(std::ldexp(ch.value, -2 * sp.e) - ex.rigid_pd2) <= 1e-9 * ex.rigid_pd2);
    const double a1 = pdd2_accel(A, B, 1).pd2, rigid = fast::rigid_pd2(A, B).pd2, a1_after = pdd2_accel(A, B, 1).pd2;
    BOOST_TEST(std::abs(rigid - ex.rigid_pd2) <= 1e-9 * ex.rigid_pd2);
    BOOST_TEST(std::abs(a1 - ex.pdd2_accel1) <= 1e-9 * ex.pdd2_accel1);
    BOOST_TEST(std::abs(a1_after - ex.pdd2_accel1) <= 1e-9 * ex.pdd2_accel1);
  }
}
