// fast_properties_test — invariants, definitions §5 inequalities, pruning and q1 on random pairs
// (paper Sec. VI protocol: vertices uniform in a 10-cube, intersecting pairs, fixed seeds).
#define BOOST_TEST_MODULE fast_properties
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <cmath>

#include "certification/value_bounds.h"
#include "certification/value_relations.h"
#include "exact/exact_path.h"
#include "fast_test_util.h"
#include "kernel/candidate_directions.h"
#include "kernel/rigid_depth.h"
#include "pdd/pdd.h"
#include "qp/deformable_depth.h"

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;

namespace {
// Inequalities that hold exactly in real arithmetic are checked with a relative slack of 1e-12:
// each side is a min over candidates of values with relative rounding error ~1e-14 (O(10) flops
// on O(10) data); a genuine violation (wrong candidate set or solver) is O(1e-2) or larger.
constexpr double kSlack = 1e-12;
bool leq(double a, double b) { return a <= b + kSlack * std::fabs(b) + 1e-300; }

std::vector<PairResult<double>> solve_all(const std::vector<TetPair>& ps) {
  std::vector<PairResult<double>> out;
  for (const auto& p : ps) out.push_back(solve_pair(p));
  return out;
}
}  // namespace

// definitions §5: pdd2 <= pdd2_static <= PD²; pdd2 <= PD²/2; relaxed <= pdd2 <= accel6 <= accel1.
// Also E11 <= PD (the overlap never exceeds delta along a candidate).
BOOST_AUTO_TEST_CASE(spec_inequalities_on_random_pairs) {
  double ratio_sum = 0.0, ratio_sq = 0.0;
  int rigid_is_best = 0;
  const auto ps = random_pairs(1500, 42, true);
  for (const auto& r : solve_all(ps)) {
    BOOST_TEST_CONTEXT(r.name) {
      BOOST_TEST(r.intersecting);
      BOOST_TEST(r.pdd2 > 0.0);
      BOOST_TEST(leq(r.pdd2, r.pdd2_static));
      BOOST_TEST(leq(r.pdd2_static, r.rigid_pd2));
      BOOST_TEST(leq(r.pdd2, r.rigid_pd2 / 2));
      BOOST_TEST(leq(r.pdd2_relaxed, r.pdd2));
      BOOST_TEST(leq(r.pdd2, r.pdd2_accel6));
      BOOST_TEST(leq(r.pdd2_accel6, r.pdd2_accel1));
      BOOST_TEST(leq(r.eq11_pd2, r.rigid_pd2));
    }
    const double ratio = std::sqrt(r.pdd2 / r.rigid_pd2);
    ratio_sum += ratio;
    ratio_sq += ratio * ratio;
    rigid_is_best += r.pdd2_dir == r.rigid_dir;
  }
  const double n = double(ps.size()), mean = ratio_sum / n;
  BOOST_TEST_MESSAGE("PD_d/PD def/def mean " << mean << " std "
                                             << std::sqrt(ratio_sq / n - mean * mean)
                                             << "; rigid direction optimal in "
                                             << 100.0 * rigid_is_best / n << "% (paper: 27.94% "
                                             << "(3.15%), 52.33%)");
}

// The pruned sweeps equal the unpruned minimum over all candidates, and every candidate's
// lower bound (deformable_depth.h) is below its value.
BOOST_AUTO_TEST_CASE(pruning_is_exact) {
  for (const auto& p : random_pairs(300, 5, true)) {
    CandidateSet set;
    build_candidates(p.A, p.B, set);
    double mins[3] = {1e300, 1e300, 1e300};
    for (int i = 0; i < set.count; ++i) {
      const Candidate c = candidate(set, i);
      const double v[3] = {static_value(c), deformable_value(c), relaxed_value(c)};
      BOOST_TEST(leq(kStaticBoundCoeff * delta2(set, i), v[0]));
      BOOST_TEST(leq(kDeformableBoundCoeff * delta2(set, i), v[1]));
      BOOST_TEST(leq(kDeformableBoundCoeff * delta2(set, i), v[2]));
      for (int k = 0; k < 3; ++k) mins[k] = std::min(mins[k], v[k]);
    }
    // A choice the double bounds cannot certify is refined (refine.h): then its value is
    // certified on compensated heights or taken exactly, within definitions §8 of the exact
    // path's instead of the double minimum.
    const PairResult<double> e = detail::solve_pair_exact_path(p.A, p.B).result;
    auto expect = [](const Choice& c, double double_min, double exact) {
      return c.refined ? std::fabs(c.value - exact) <= fast::kContractRel * exact : c.value == double_min;
    };
    const int hint = rigid_pd2(set).index;
    BOOST_TEST(expect(pdd2_static(set, hint), mins[0], e.pdd2_static));
    BOOST_TEST(expect(pdd2(set, hint), mins[1], e.pdd2));
    BOOST_TEST(expect(pdd2_relaxed(set, hint), mins[2], e.pdd2_relaxed));
    BOOST_TEST(expect(pdd2(set, -1), mins[1], e.pdd2));
  }
}

// q1 attains pdd2 (definitions §2 object norm of the deformed positions) and resolves the
// penetration along pdd2_dir: every deformed A vertex at or below, every B vertex at or above
// the plane, constrained ones on it. Tolerance 1e-9 relative to the pair's scale (10): the
// positions are x + (T/n.n) n with O(1e-15) relative rounding.
BOOST_AUTO_TEST_CASE(deformed_positions_attain_and_separate) {
  for (const auto& p : random_pairs(300, 9, true)) {
    const PairResult<double> r = solve_pair(p);
    BOOST_TEST(close_rel(sigma(p.A, r.q1_A) + sigma(p.B, r.q1_B), r.pdd2, 1e-9));
    CandidateSet set;
    build_candidates(p.A, p.B, set);
    int found = -1;
    for (int k = 0; k < set.count; ++k)
      if (label(set, k) == *r.pdd2_dir) found = k;
    BOOST_REQUIRE(found >= 0);
    const Candidate cand = candidate(set, found);
    const Candidate* c = &cand;
    const double scale = std::sqrt(c->nn) * 10.0, tol = 1e-9 * scale;
    double plane = -1e300;
    for (int i = 0; i < 4; ++i)
      if (c->conA >> i & 1u || c->conB >> i & 1u) {
        const auto& x = (c->conA >> i & 1u) ? r.q1_A[i] : r.q1_B[i];
        plane = c->n[0] * x[0] + c->n[1] * x[1] + c->n[2] * x[2];
      }
    for (int i = 0; i < 4; ++i) {
      const double hA = c->n[0] * r.q1_A[i][0] + c->n[1] * r.q1_A[i][1] + c->n[2] * r.q1_A[i][2];
      const double hB = c->n[0] * r.q1_B[i][0] + c->n[1] * r.q1_B[i][1] + c->n[2] * r.q1_B[i][2];
      BOOST_TEST(hA <= plane + tol);
      BOOST_TEST(hB >= plane - tol);
      if (c->conA >> i & 1u) BOOST_TEST(std::fabs(hA - plane) <= tol);
      if (c->conB >> i & 1u) BOOST_TEST(std::fabs(hB - plane) <= tol);
    }
  }
}

// Scaling all coordinates by 2 multiplies every floating-point operation's operands by powers of
// two, so (barring under/overflow, impossible here) every computed value scales exactly:
// squared depths ×4 bit for bit, the filter bounds scale alike, labels are identical.
BOOST_AUTO_TEST_CASE(scale_by_two_is_exact) {
  for (const auto& p : random_pairs(300, 17, true)) {
    TetPair q = p;
    for (auto* T : {&q.A, &q.B})
      for (auto& v : *T)
        for (double& x : v) x *= 2;
    const auto r = solve_pair(p), s = solve_pair(q);
    BOOST_TEST(s.rigid_pd2 == 4 * r.rigid_pd2);
    BOOST_TEST(s.eq11_pd2 == 4 * r.eq11_pd2);
    BOOST_TEST(s.pdd2_static == 4 * r.pdd2_static);
    BOOST_TEST(s.pdd2 == 4 * r.pdd2);
    BOOST_TEST(s.pdd2_relaxed == 4 * r.pdd2_relaxed);
    BOOST_TEST(s.pdd2_accel1 == 4 * r.pdd2_accel1);
    BOOST_TEST(s.pdd2_accel6 == 4 * r.pdd2_accel6);
    BOOST_TEST((s.rigid_dir == r.rigid_dir && s.pdd2_dir == r.pdd2_dir &&
                s.pdd2_static_dir == r.pdd2_static_dir && s.pdd2_relaxed_dir == r.pdd2_relaxed_dir));
  }
}

// Translating both tetrahedra by (8, −16, 4) changes every coordinate by an exact amount in
// real arithmetic but rounds it (ulp <= 2^-47 for |x| < 32), a relative perturbation of the
// pair of ~1e-15 of its size. Squared depths move by ~2 PD · 1e-14 · (geometry factor); we allow
// 1e-9 relative + 1e-9 absolute (in units of the 10-cube²), far above that, far below O(1e-3)
// differences a wrong direction would produce. Labels are not compared (near-ties may flip).
BOOST_AUTO_TEST_CASE(translation_invariance) {
  for (const auto& p : random_pairs(300, 23, true)) {
    TetPair q = p;
    const double t[3] = {8, -16, 4};
    for (auto* T : {&q.A, &q.B})
      for (auto& v : *T)
        for (int k = 0; k < 3; ++k) v[k] += t[k];
    const auto r = solve_pair(p), s = solve_pair(q);
    BOOST_TEST(s.intersecting);
    for (auto [a, b] : {std::pair{r.rigid_pd2, s.rigid_pd2}, {r.eq11_pd2, s.eq11_pd2},
                        {r.pdd2_static, s.pdd2_static}, {r.pdd2, s.pdd2},
                        {r.pdd2_relaxed, s.pdd2_relaxed}, {r.pdd2_accel1, s.pdd2_accel1},
                        {r.pdd2_accel6, s.pdd2_accel6}})
      BOOST_TEST(close_rel(a, b, 1e-9, 1e-9), a << " vs " << b);
  }
}

// Relabelling the vertices of A and of B permutes the candidates but not the set of directions
// nor their constrained/free structure, so every value is unchanged up to rounding (same
// tolerance argument as translation; here the coordinates are not even perturbed).
BOOST_AUTO_TEST_CASE(vertex_permutation_invariance) {
  const int perms[3][4] = {{3, 2, 1, 0}, {1, 0, 3, 2}, {2, 3, 0, 1}};
  int k = 0;
  for (const auto& p : random_pairs(300, 29, true)) {
    const int* pa = perms[k % 3];
    const int* pb = perms[(k + 1) % 3];
    ++k;
    TetPair q = p;
    for (int i = 0; i < 4; ++i) {
      q.A[i] = p.A[pa[i]];
      q.B[i] = p.B[pb[i]];
    }
    const auto r = solve_pair(p), s = solve_pair(q);
    for (auto [a, b] : {std::pair{r.rigid_pd2, s.rigid_pd2}, {r.eq11_pd2, s.eq11_pd2},
                        {r.pdd2_static, s.pdd2_static}, {r.pdd2, s.pdd2},
                        {r.pdd2_relaxed, s.pdd2_relaxed}})
      BOOST_TEST(close_rel(a, b, 1e-9, 1e-12), a << " vs " << b);
  }
}

// The hot-path overloads over raw tetrahedra (what a benchmark times) return exactly what
// solve_pair reports: same values bit for bit once the exact relations are kept, same labels (both run the lane sweeps of
// deformable_depth.h first; fast_qp_lower_bound_test and fast_golden_test check it on harder
// pairs).
BOOST_AUTO_TEST_CASE(hot_path_overloads_match_solve_pair) {
  for (const auto& p : random_pairs(200, 41, false)) {
    const auto r = solve_pair(p);
    const Choice rigid = rigid_pd2_choice(p.A, p.B), st = pdd2_static_choice(p.A, p.B), def = pdd2_choice(p.A, p.B),
                 rel = pdd2_relaxed_choice(p.A, p.B), a1 = pdd2_accel_choice(p.A, p.B, 1),
                 a6 = pdd2_accel_choice(p.A, p.B, 6);
    // solve_pair's values are the hot values with the exact relations of definitions §5 kept
    // (value_relations.h): bit for bit after the same lowering
    PairResult<double> h;
    h.rigid_pd2 = rigid.value, h.pdd2_static = st.value, h.pdd2 = def.value;
    h.pdd2_relaxed = rel.value, h.pdd2_accel1 = a1.value, h.pdd2_accel6 = a6.value;
    if (r.intersecting) keep_exact_relations(h);
    BOOST_TEST(h.rigid_pd2 == r.rigid_pd2);
    BOOST_TEST(h.pdd2_static == r.pdd2_static);
    BOOST_TEST(h.pdd2 == r.pdd2);
    BOOST_TEST(h.pdd2_relaxed == r.pdd2_relaxed);
    BOOST_TEST(h.pdd2_accel1 == r.pdd2_accel1);
    BOOST_TEST(h.pdd2_accel6 == r.pdd2_accel6);
    if (!r.intersecting) continue;
    BOOST_TEST((rigid.label() == *r.rigid_dir && st.label() == *r.pdd2_static_dir &&
                def.label() == *r.pdd2_dir && rel.label() == *r.pdd2_relaxed_dir));
  }
}
