// fast_batch_test — solve_batch equals solve_pair pair by pair (same code per pair, no shared
// state, so bitwise equal), in input order, with invalid pairs reported in place.
#define BOOST_TEST_MODULE fast_batch
#include <boost/test/unit_test.hpp>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "fast_test_util.h"
#include "kernel/power_scale.h"
#include "pdd/pdd.h"
#include "structured_cells.h"

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;

namespace {
const TetVertices kGood = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
const TetVertices kFlat = {{{0, 0, 0.1}, {1, 0, 0.1}, {0, 1, 0.1}, {0.3, 0.3, 0.1}}};

TetVertices with(TetVertices T, int i, int k, double x) {
  T[i][k] = x;
  return T;
}

bool same(const PairResult<double>& a, const PairResult<double>& b) {
  return a.name == b.name && a.error == b.error && a.intersecting == b.intersecting &&
         a.rigid_pd2 == b.rigid_pd2 && a.eq11_pd2 == b.eq11_pd2 &&
         a.pdd2_static == b.pdd2_static && a.pdd2 == b.pdd2 && a.pdd2_relaxed == b.pdd2_relaxed &&
         a.pdd2_accel1 == b.pdd2_accel1 && a.pdd2_accel6 == b.pdd2_accel6 &&
         a.rigid_dir == b.rigid_dir && a.pdd2_static_dir == b.pdd2_static_dir &&
         a.pdd2_dir == b.pdd2_dir && a.pdd2_relaxed_dir == b.pdd2_relaxed_dir &&
         a.q1_A == b.q1_A && a.q1_B == b.q1_B;
}

struct Bad {
  TetPair pair;
  const char* must_contain[2];
};

std::vector<Bad> bad_pairs() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {tet_pair(with(kGood, 2, 1, nan), kGood, "nan-A"), {"tetrahedron A", "vertex 2"}},
      {tet_pair(kGood, with(kGood, 3, 0, inf), "inf-B"), {"tetrahedron B", "vertex 3"}},
      {tet_pair(with(kGood, 0, 2, -inf), kGood, "minf-A"), {"tetrahedron A: vertex 0 coordinate z is not finite (-inf)"}},
      {tet_pair(kFlat, kGood, "flat-A"), {"tetrahedron A is flat: its four vertices are coplanar (volume 0)"}},
      {tet_pair(kGood, kFlat, "flat-B"), {"tetrahedron B is flat"}},
      {tet_pair(kGood, {{kGood[0], kGood[0], kGood[1], kGood[2]}}, "repeated-B"),
       {"tetrahedron B is flat"}},
      {tet_pair(kFlat, with(kGood, 1, 1, nan), "flat-A-nan-B"),
       {"tetrahedron A is flat", "; tetrahedron B: vertex 1 coordinate y is not finite (nan)"}},
  };
}
}  // namespace

BOOST_AUTO_TEST_CASE(each_bad_input_kind) {
  for (const Bad& b : bad_pairs()) {
    const PairResult<double> r = solve_pair(b.pair);
    BOOST_TEST_CONTEXT(b.pair.name) {
      BOOST_REQUIRE(r.error);
      for (const char* s : b.must_contain)
        if (s)
          BOOST_TEST(r.error->find(s) != std::string::npos, *r.error);
      BOOST_TEST(!r.intersecting);
    }
  }
}

BOOST_AUTO_TEST_CASE(batch_equals_single) {
  std::vector<TetPair> pairs = random_pairs(400, 31, false);  // mixed: ~half intersect
  int k = 0;
  for (const Bad& b : bad_pairs()) pairs.insert(pairs.begin() + 37 * ++k, b.pair);
  const auto batch = solve_batch(pairs);
  BOOST_REQUIRE(batch.size() == pairs.size());
  int intersecting = 0, errors = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PairResult<double> one = solve_pair(pairs[i]);
    BOOST_TEST(same(batch[i], one), "pair " << i);
    BOOST_TEST((batch[i].stats.slow_path == one.stats.slow_path && batch[i].stats.refined == one.stats.refined),
               "pair " << i);
    intersecting += batch[i].intersecting;
    errors += bool(batch[i].error);
  }
  BOOST_TEST(errors == int(bad_pairs().size()));
  BOOST_TEST(intersecting > 50);
  BOOST_TEST(solve_batch({}).empty());
}

// solve_pair with SolveOptions::with_global = false (pdd.h): definitions §9 skipped, every other
// field bit for bit the same as with it; pdd2_global 0, no normal, q1_*_global the rest pose. Also
// on scaled pairs, where the positions are rescaled (a skipped search must not leave rescaled rest
// poses).
BOOST_AUTO_TEST_CASE(skipping_the_global_search_changes_nothing_else) {
  std::vector<TetPair> pairs = random_pairs(200, 77, false);
  for (int k = 0; k < 40; ++k) {  // the same pairs far from unit scale
    TetPair p = pairs[k];
    for (auto* t : {&p.A, &p.B})
      for (auto& v : *t)
        for (double& c : v) c = std::ldexp(c, k % 2 ? 300 : -300);
    pairs.push_back(p);
  }
  int intersecting = 0;
  for (const TetPair& p : pairs) {
    PairResult<double> with = solve_pair(p), without = solve_pair(p, SolveOptions{false});
    BOOST_TEST(without.pdd2_global == 0.0);
    BOOST_TEST(!without.pdd2_global_normal);
    BOOST_TEST((without.q1_A_global == p.A && without.q1_B_global == p.B));
    intersecting += with.intersecting;
    if (with.intersecting && !with.error) BOOST_TEST(with.pdd2_global > 0.0);
    with.pdd2_global = 0, with.pdd2_global_normal.reset();
    with.q1_A_global = p.A, with.q1_B_global = p.B;
    BOOST_TEST(same(with, without), p.name);
  }
  BOOST_TEST(intersecting > 50);
}

// SolveOptions::values (solve_options.h): the asked values, their labels and (pdd2 asked) q1 are
// the full record's bit for bit (value_relations.h orders the relations so that each value
// depends on few others, and solve_pair computes those); the others are 0 with no label, q1 the
// rest pose where pdd2 is not asked. definitions §9 too. Random pairs and aligned ones (grid
// cells against cells of a shifted grid: ties, the candidate list's exact paths).
BOOST_AUTO_TEST_CASE(asking_for_some_values_computes_them_alone) {
  std::vector<TetPair> pairs = random_pairs(150, 78, true);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const Vec3d o = {0.5, -0.25, 0.125}, q = {o[0] + 0.37 * 0.3, o[1] + 0.21 * 0.3, o[2] + 0.13 * 0.3};
      pairs.push_back(tet_pair(pdd::test::kuhn_cell_tet(o, 0.3, i), pdd::test::kuhn_cell_tet(q, 0.3, j), "kuhn"));
      if (i < 5 && j < 5)
        pairs.push_back(tet_pair(pdd::test::five_cell_tet(o, 0.3, i, false),
                                 pdd::test::five_cell_tet(q, 0.3, j, false), "five"));
    }
  std::vector<unsigned> masks = {45u /* rigid, static, pdd2, accel1: pdd mesh's default */};
  for (unsigned k = 0; k < kValueCount; ++k) masks.push_back(1u << k);
  int intersecting = 0;
  for (const TetPair& p : pairs) {
    SolveOptions no_global;
    no_global.with_global = false;
    const PairResult<double> full = solve_pair(p, no_global);
    BOOST_REQUIRE(!full.error);
    intersecting += full.intersecting;
    for (unsigned mask : masks) {
      SolveOptions o = no_global;
      o.values = mask;
      const PairResult<double> r = solve_pair(p, o);
      BOOST_TEST_CONTEXT(p.name << ", values " << mask) {
        BOOST_TEST(!r.error);
        BOOST_TEST(r.intersecting == full.intersecting);
        for (std::size_t k = 0; k < kValueCount; ++k) {
          const double v = record_value(r, k), f = record_value(full, k);
          const int l = kLabelOfValue[k];
          if (!(mask >> k & 1u)) {
            BOOST_TEST(v == 0.0, kValueKeys[k]);
            if (l >= 0) BOOST_TEST(!record_label(r, std::size_t(l)), kValueKeys[k]);
            continue;
          }
          if (l >= 0) BOOST_TEST((record_label(r, std::size_t(l)) == record_label(full, std::size_t(l))), kValueKeys[k]);
          BOOST_TEST(v == f, kValueKeys[k] << " " << v << " vs " << f);
        }
        const bool pdd2_asked = mask >> 3 & 1u;
        BOOST_TEST((pdd2_asked ? r.q1_A == full.q1_A && r.q1_B == full.q1_B : r.q1_A == p.A && r.q1_B == p.B));
      }
    }
    SolveOptions rigid_and_global;
    rigid_and_global.values = 1u;
    const PairResult<double> g = solve_pair(p, rigid_and_global), fg = solve_pair(p);
    BOOST_TEST(g.pdd2_global == fg.pdd2_global, p.name);
    BOOST_TEST((g.pdd2_global_normal == fg.pdd2_global_normal), p.name);
    BOOST_TEST((g.q1_A_global == fg.q1_A_global && g.q1_B_global == fg.q1_B_global), p.name);
    BOOST_TEST(g.pdd2 == 0.0, p.name);
    BOOST_TEST(g.rigid_pd2 == fg.rigid_pd2, p.name);
  }
  BOOST_TEST(intersecting > 150);
}

// The hot paths over raw vertices (hot_path.h) decide finiteness inside power_scaled (one pass
// over the 24 coordinates): every non-finite pair above is Rejected with pd2 NaN by each of them,
// and no value is made up from a NaN or an infinity (NaN loses a max comparison, so a max-based
// test alone would miss it: the pairs put NaN and ±inf at different vertices and axes).
BOOST_AUTO_TEST_CASE(hot_paths_reject_non_finite_coordinates) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k)
      for (double x : {nan, inf, -inf}) {
        const TetVertices bad = with(kGood, v, k, x);
        for (const auto& [A, B] : {std::pair{bad, kGood}, std::pair{kGood, bad}}) {
          BOOST_TEST_CONTEXT("vertex " << v << " axis " << k << " value " << x) {
            for (const Depth d : {rigid_pd2(A, B), pdd2_static(A, B), pdd2(A, B),
                                  pdd2_relaxed(A, B), pdd2_accel(A, B, 1), pdd2_accel(A, B, 6)}) {
              BOOST_TEST((d.status == DepthStatus::Rejected));
              BOOST_TEST(std::isnan(d.pd2));  // a rejected pair never reads as a depth of 0
            }
            const NormalDepth g = pdd2_global(A, B);
            BOOST_TEST((g.status == DepthStatus::Rejected && std::isnan(g.pd2)));
          }
        }
      }
}

// Values scale back by one multiplication with 2^k (power_scale.h's unscaled, |k| <= 1000) or
// by ldexp beyond: the pair scaled by 2^j has every squared depth scaled by exactly 2^(2j),
// bit for bit, on both sides of the switch (2j = ±1000 and ±1004 for j = ±500, ±502).
BOOST_AUTO_TEST_CASE(hot_paths_scale_back_exactly) {
  const std::vector<TetPair> pairs = random_pairs(40, 77, true);
  for (int j : {-502, -500, -37, 37, 500, 502})
    for (const TetPair& p : pairs) {
      TetVertices A = p.A, B = p.B;
      for (auto* T : {&A, &B})
        for (auto& vtx : *T)
          for (double& c : vtx) c = std::ldexp(c, j);
      const Depth r0 = rigid_pd2(p.A, p.B), r1 = rigid_pd2(A, B);
      const Depth a0 = pdd2_accel(p.A, p.B, 1), a1 = pdd2_accel(A, B, 1);
      BOOST_TEST_CONTEXT(p.name << " scaled by 2^" << j) {
        for (const auto& [d0, d1] : {std::pair{r0, r1}, std::pair{a0, a1}}) {
          BOOST_REQUIRE((d0.status == DepthStatus::Ok));
          const double want = std::ldexp(d0.pd2, 2 * j);
          if (want == 0.0 || std::fabs(want) >= DBL_MIN) {  // a normal double: exactly it
            BOOST_TEST((d1.status == DepthStatus::Ok));
            BOOST_TEST(d1.pd2 == want);
          } else {  // below the normal range: definitions §8's error record, never a rounded value
            BOOST_TEST((d1.status == DepthStatus::NotRepresentable));
          }
        }
        BOOST_TEST((r1.dir == r0.dir));
      }
    }
}

// power_scaled's exactness test: R = 1000 gives e = -9; a coordinate
// m = (2 - 2^-52) 2^-1014 has m 2^-9 = 2^-1022 - 2^-1075 exactly, which rounds (to even) up
// to DBL_MIN: a normal result, but not x 2^e, so the pair is not "exactly" rescaled. One ulp
// above, m 2^-9 = 2^-1022 exactly: exact.
BOOST_AUTO_TEST_CASE(power_scaled_exactness_at_the_normal_boundary) {
  const double m = std::ldexp(2 - std::ldexp(1.0, -52), -1014);
  TetVertices A = kGood, B = kGood;
  A[1][0] = 1000.0;
  A[2][2] = m;
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  BOOST_TEST(sp.e == -9);
  BOOST_TEST(std::fabs(sp.A[2][2]) == DBL_MIN);  // rounded up
  BOOST_TEST(!sp.exact);
  A[2][2] = std::ldexp(1.0, -1013);
  BOOST_TEST(detail::power_scaled(A, B).exact);
}

// power_scaled (power_scale.h reduces the coordinates on their bits) against its definition
// written plainly: finite iff every coordinate is; e = −ilogb(max |x|) (0 for an all-zero
// pair); each coordinate x·2^e rounded (ldexp); `exact` as below. Inputs:
// random bit patterns (NaNs, infinities, subnormals), special values mixed into ordinary pairs,
// every power-of-two scale, tiny integers as bits (subnormals next to zero). `exact` is the
// header's: no non-zero coordinate leaves the normal range (a subnormal x·2^e is not trusted
// even when it happens to be exact).
BOOST_AUTO_TEST_CASE(power_scaled_against_its_definition) {
  std::mt19937_64 g(41);
  const double specials[] = {0.0,        -0.0,         DBL_MIN,      -DBL_MIN,  DBL_TRUE_MIN,
                             -DBL_MAX,   DBL_MAX,      HUGE_VAL,     -HUGE_VAL, std::nan(""),
                             1.0,        1e-300,       1e300,        DBL_MIN / 2, 3 * DBL_TRUE_MIN,
                             0x1p-1000,  0x1p1000,     7 * DBL_TRUE_MIN, 1.5,  -0x1.fffffffffffffp-1023};
  constexpr int kSpecials = sizeof specials / sizeof specials[0];
  int checked = 0, finite = 0, inexact = 0;
  for (int it = 0; it < 200000; ++it) {
    TetVertices T[2] = {kGood, kGood};
    double* c = &T[0][0][0];
    const int mode = it % 5;
    for (int j = 0; j < 24; ++j) {
      if (mode == 0) {
        const std::uint64_t b = g();
        std::memcpy(&c[j], &b, sizeof b);
      } else if (mode == 1) {
        if (g() % 4 == 0) c[j] = specials[g() % kSpecials];
      } else if (mode == 2) {
        c[j] = (g() % 2 ? 1.0 : -1.0) * std::ldexp(1.0 + double(g() % 1000) / 1000.0, int(g() % 2150) - 1075);
        if (g() % 3 == 0) c[j] = 0.0;
      } else if (mode == 3) {
        const std::uint64_t b = g() % 64;
        std::memcpy(&c[j], &b, sizeof b);
      } else {
        c[j] = std::ldexp(double(g() % 2001) - 1000.0, int(g() % 2000) - 1000);
      }
    }
    const detail::ScaledPair s = detail::power_scaled(T[0], T[1]);
    bool all_finite = true;
    double R = 0.0;
    for (int j = 0; j < 24; ++j) {
      all_finite = all_finite && std::isfinite(c[j]);
      R = std::fmax(R, std::fabs(c[j]));
    }
    ++checked;
    BOOST_TEST(s.finite == all_finite);
    if (!all_finite) continue;
    ++finite;
    const int e = R > 0.0 ? -std::ilogb(R) : 0;
    BOOST_TEST(s.e == e);
    bool exact = true;
    const double* sc = &s.A[0][0];
    const double* sb = &s.B[0][0];
    for (int j = 0; j < 24; ++j) {
      const double y = std::ldexp(c[j], e);
      const double got = j < 12 ? sc[j] : sb[j - 12];
      BOOST_TEST(std::memcmp(&got, &y, sizeof y) == 0);
      exact = exact && (c[j] == 0.0 || (std::fabs(y) >= DBL_MIN && std::ldexp(y, -e) == c[j]));
    }
    BOOST_TEST(s.exact == exact);
    inexact += !exact;
  }
  BOOST_TEST(finite > 50000);  // every mode but the random bits is mostly finite
  BOOST_TEST(inexact > 100);   // the subnormal side is reached
  BOOST_TEST_MESSAGE("power_scaled: " << checked << " pairs, " << finite << " finite, " << inexact << " inexact");
}
