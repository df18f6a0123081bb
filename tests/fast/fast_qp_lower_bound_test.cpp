// fast_qp_lower_bound_test — the dual lower bounds of qp_lower_bound.h against the exact values.
//
// For every entry of a quick list's lanes: lo <= the exact QP value of that candidate (exact
// rationals, exact_candidate.h) for case 1, case 2 and the relaxed case 2; +inf exactly on the
// entries that are not candidates (and, in case 1, on undecidable edge pairs); tight where the
// derivation says it is (a vertex through a face: the case-1 value is the m = 1 bound itself,
// t²/16, so lo must sit within 0.1% below it). split_at against a plain loop.
#define BOOST_TEST_MODULE fast_qp_lower_bound
#include <boost/test/unit_test.hpp>

#include "certification/qp_lower_bound.h"
#include "certification/value_bounds.h"
#include "exact/exact_candidate.h"
#include "exact/exact_path.h"
#include "fast_test_util.h"
#include "kernel/power_scale.h"
#include "kernel/quick_candidates.h"
#include "qp/deformable_depth.h"
#include "shallow_contact.h"
#include "pdd/pdd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;
using pdd::fast::detail::QpCase;
using pdd::fast::detail::QpLowerBounds;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Tally {
  int pairs = 0, entries = 0, tight = 0;
  double ratio_sum = 0.0;  // lo / exact, case 2, over entries with lo > 0
};

// Checks every entry of one pair (rescaled as the hot path does); false when the quick lanes
// decline.
bool check_pair(const TetPair& p, Tally& t) {
  const detail::ScaledPair sp = detail::power_scaled(p.A, p.B);
  if (!sp.finite || !sp.exact) return false;
  QuickCandidates q;
  if (!quick_lanes(sp.A, sp.B, q)) return false;
  QpLowerBounds st, de;
  detail::qp_lower_bounds(q, QpCase::Static, st);
  detail::qp_lower_bounds(q, QpCase::Deformable, de);
  quick_edge_list(q);
  bool is_candidate[detail::kQpEntries] = {};
  for (int k = 0; k < q.count; ++k) is_candidate[q.src[k]] = true;
  const detail::ExactFrame f = detail::exact_frame(sp.A, sp.B);
  ++t.pairs;
  for (int e = 0; e < detail::kQpEntries; ++e) {
    if (!is_candidate[e]) {
      BOOST_TEST(st.lo[e] == kInf, p.name << " entry " << e);
      BOOST_TEST(de.lo[e] == kInf, p.name << " entry " << e);
      continue;
    }
    ++t.entries;
    const DirectionLabel l = unpack_label(entry_label_code(q, e));
    const detail::ExactCandidate c = detail::exact_candidate(f, l);
    const detail::Q def = detail::unscaled(f, detail::exact_deformable_value(c), 2);
    const detail::Q rel = detail::unscaled(f, detail::exact_relaxed_value(c), 2);
    BOOST_TEST(de.lo[e] >= 0.0);
    BOOST_TEST(detail::Q(de.lo[e]) <= rel, p.name << " " << l.str() << " deform lo " << de.lo[e]);
    BOOST_TEST(detail::Q(de.lo[e]) <= def, p.name << " " << l.str());
    if (l.orientation != EdgeOrientation::Decided) {
      BOOST_TEST(st.lo[e] == kInf, p.name << " " << l.str() << ": case 1 skips it");
    } else {
      const detail::Q sv = detail::unscaled(f, detail::exact_static_value(c), 2);
      BOOST_TEST(st.lo[e] >= 0.0);
      BOOST_TEST(detail::Q(st.lo[e]) <= sv, p.name << " " << l.str() << " static lo " << st.lo[e]);
      if (detail::Q(st.lo[e]) >= sv * detail::Q(0.998)) ++t.tight;
    }
    const double r = def.get_d();
    if (de.lo[e] > 0 && r > 0) t.ratio_sum += de.lo[e] / r;
  }
  return true;
}

TetPair scaled(const TetPair& p, double s, const char* name) {
  TetPair o = p;
  o.name = name;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      o.A[i][k] *= s;
      o.B[i][k] *= s;
    }
  return o;
}

}  // namespace

// Random intersecting pairs (paper-like), at scales 1, 2^-300 and 2^300 (the bounds are taken on
// the rescaled pair, so all three must hold alike), and translated far from the origin.
BOOST_AUTO_TEST_CASE(below_exact_on_random_pairs) {
  Tally t;
  int declined = 0;
  for (const TetPair& p : random_pairs(150, 97, true)) {
    declined += !check_pair(p, t);
    check_pair(scaled(p, 0x1p-300, "tiny"), t);
    check_pair(scaled(p, 0x1p300, "huge"), t);
    TetPair far = p;
    for (int i = 0; i < 4; ++i) far.A[i][0] += 1e6, far.B[i][0] += 1e6;
    check_pair(far, t);
  }
  BOOST_TEST(declined < 15);  // generic pairs: the quick lanes decide
  BOOST_TEST(t.entries > 20000);
  // useful, not only valid: measured ~0.8 of the exact case-2 value on average
  BOOST_TEST(t.ratio_sum / t.entries > 0.6, "mean lo/exact " << t.ratio_sum / t.entries);
}

// A vertex of B through a face of A at depth t (the closed-form family): the case-1 optimum of
// FV along that face moves the one vertex by t, the other three of B by −t/4 each (free), cost
// (t² + 3 t²/16 + t²/16)/20 = t²/16 = the m = 1 bound; so lo must be within the 0.1% safety
// factor below it, yet never above: the rounding margins are what is tested here.
BOOST_AUTO_TEST_CASE(tight_on_a_vertex_through_a_face) {
  Tally t;
  int checked = 0;
  pdd::compare::ReproducibleRng rng(5);
  for (int k = 0; k < 300; ++k) {
    const double depth = std::ldexp(rng.uniform(1.0, 2.0), -int(rng.uniform(0.0, 30.0)));
    TetPair p;
    p.name = "poke";
    p.A = {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, -10}}};
    const double x = rng.uniform(1.0, 4.0), y = rng.uniform(1.0, 4.0);
    p.B = {{{x, y, -depth}, {x - 3, y + 1, 6}, {x + 2, y - 2, 7}, {x + 1, y + 3, 5}}};
    checked += check_pair(p, t);
  }
  BOOST_TEST(checked > 250);
  BOOST_TEST(t.tight >= checked, "tight entries " << t.tight << " of " << checked << " pairs");
}

BOOST_AUTO_TEST_CASE(split_matches_a_plain_loop) {
  pdd::compare::ReproducibleRng rng(11);
  for (int k = 0; k < 2000; ++k) {
    QpLowerBounds b;
    for (double& x : b.lo) x = rng.uniform(0.0, 1.0) < 0.3 ? kInf : rng.uniform(0.0, 10.0);
    const double t = rng.uniform(0.0, 10.0);
    int below = 0;
    double above = kInf;
    for (double x : b.lo) {
      below += x <= t;
      if (x > t && x < above) above = x;
    }
    const detail::QpSplit s = detail::split_at(b, t);
    BOOST_TEST(s.below == below);
    BOOST_TEST(s.above == above);
  }
}

// A pair with nearly parallel edges in a shallow contact: the set sweep cannot certify its pdd2
// minimum in doubles (its pruning bound coeff·delta² is too weak) and evaluates it exactly
// (refine.h), while the lane sweep's dual bounds certify it in doubles. The two values would
// differ in the last digits (6.5e-16 apart), so solve_pair runs the lane sweeps too: solve_pair
// and the hot path give the same values bit for bit and labels, each within definitions §8 of
// the exact value.
BOOST_AUTO_TEST_CASE(refined_by_solve_pair_certified_by_the_lanes) {
  const double z = -0x1.6cb49ed376162p-4;
  TetPair p;
  p.name = "review-16";
  p.A = {{{-5, 0x1p-31, z}, {5, -0x1p-31, z}, {0, 3, 5}, {0.5, -3, 5}}};
  p.B = {{{-5, 0, 0}, {5, 0, 0}, {0, 3, -5}, {0, -3, -5}}};
  const PairResult<double> r = solve_pair(p);
  const PairResult<double> e = detail::solve_pair_exact_path(p.A, p.B).result;  // exact, rounded
  BOOST_REQUIRE(!r.error && r.intersecting);
  const Depth hot[3] = {fast::pdd2_static(p.A, p.B), fast::pdd2(p.A, p.B), fast::pdd2_relaxed(p.A, p.B)};
  const double ref[3] = {r.pdd2_static, r.pdd2, r.pdd2_relaxed};
  const double ex[3] = {e.pdd2_static, e.pdd2, e.pdd2_relaxed};
  const std::optional<DirectionLabel> lab[3] = {r.pdd2_static_dir, r.pdd2_dir, r.pdd2_relaxed_dir};
  for (int i = 0; i < 3; ++i) {
    BOOST_TEST((hot[i].status == DepthStatus::Ok));
    // within 1e-9 of the exact value (the exact path's value is it rounded once: 2^-52 more)
    BOOST_TEST(std::fabs(hot[i].pd2 - ex[i]) <= 1.001e-9 * ex[i], hot[i].pd2 << " vs exact " << ex[i]);
    BOOST_TEST(std::fabs(ref[i] - ex[i]) <= 1.001e-9 * ex[i]);
    BOOST_TEST((hot[i].dir && lab[i] && *hot[i].dir == *lab[i]));
    BOOST_TEST(hot[i].pd2 == ref[i]);
  }
}

// Shallow contacts on the quick lanes (deformable_depth.cpp's shallow_choice): a vertex of B
// (tip) or a small face of B (face) 1e-4 to 1e-7 of the pair's size through a face of A, in
// general position (random tetrahedra in [-1, 1]^3; as tests/compare's shallow contacts). The
// QP minima are ~1e-8 to 1e-14 of the squared size, where the double intervals (~u L / depth
// relative) cannot certify them; on compensated heights the lanes certify (nearly) every one,
// within definitions §8 of the exact path's value, and the candidate list is not built.
// Measured: all 119 pairs with quick lanes certified in each variant; with the double
// intervals alone, none.
BOOST_AUTO_TEST_CASE(shallow_contacts_certified_by_the_lanes) {
  pdd::compare::ReproducibleRng rng(23);
  int pairs = 0, certified[3] = {0, 0, 0};
  for (double depth : {1e-4, 1e-5, 1e-6, 1e-7})
    for (int trial = 0; trial < 30; ++trial) {
      const TetPair p = pdd::test::shallow_contact_pair(
          depth, trial % 2, [&] { return rng.uniform(-1, 1); },
          "shallow " + std::to_string(depth) + (trial % 2 ? " face " : " tip ") + std::to_string(trial));
      const detail::ScaledPair sp = detail::power_scaled(p.A, p.B);
      QuickCandidates q;
      if (!sp.finite || !sp.exact || !quick_lanes(sp.A, sp.B, q)) continue;
      const PairResult<double> x = detail::solve_pair_exact_path(sp.A, sp.B).result;  // exact, rounded
      if (x.error || !x.intersecting) continue;
      ++pairs;
      const double ex[3] = {x.pdd2_static, x.pdd2, x.pdd2_relaxed};
      for (int i = 0; i < 3; ++i) {
        Choice ch;
        const bool ok = i == 0 ? pdd2_static_lanes(q, ch) : i == 1 ? pdd2_lanes(q, ch) : pdd2_relaxed_lanes(q, ch);
        if (!ok || !ch.certified) continue;
        ++certified[i];
        // within 1e-9 of the exact value (the exact path's value is it rounded once: 2^-52 more)
        BOOST_TEST(std::fabs(ch.value - ex[i]) <= 1.001e-9 * ex[i], p.name << " variant " << i << ": " << ch.value
                                                                            << " vs exact " << ex[i]);
      }
    }
  BOOST_TEST_MESSAGE("shallow contacts certified by the lanes: " << certified[0] << ", " << certified[1] << ", "
                                                                 << certified[2] << " of " << pairs);
  BOOST_TEST(pairs >= 80);
  for (int i = 0; i < 3; ++i) BOOST_TEST(certified[i] >= 0.9 * pairs, "variant " << i << ": " << certified[i]);
}

// value_bounds.h's qp_root_rel_tiny: wherever it holds, qp_root_rel is <= kTinyQpRoot for the
// wide solver bound (kSolverDisplacementCoeff, H) and for every tight one it covers
// (kSolverDisplacementCoeffTight, H' <= 8 H), as pdd2_accel(A, B, 1) relies on. Inputs driven
// onto the test's boundary (F and nn at most 1e-6 above their thresholds, one at a time and
// both) for extents 2^-53..8 (the rescaled range), both degree classes and heights up to 8 L;
// the largest bound found is printed against the proof's 9.975e-11.
BOOST_AUTO_TEST_CASE(tiny_qp_root_bound_holds_on_its_boundary) {
  pdd::compare::ReproducibleRng rng(97);
  double worst = 0.0;
  int held = 0;
  for (int i = 0; i < 400000; ++i) {
    const double L = std::ldexp(rng.uniform(1.0, 2.0), rng.integer(-53, 2));
    const DegreeBounds db = degree_bounds(filter_bounds_of_extent(L), i % 2 == 1);
    const double H = L * std::ldexp(rng.uniform(0.0, 1.0), rng.integer(-30, 3));
    const double X = 2 * db.e_h + 1.5 * kSolverDisplacementCoeff * kUnitRoundoff * H;
    const int mode = i % 3;
    const double F = X * X * 8.4e21 * (1 + (mode == 2 ? 1e6 : 1e-6) * rng.uniform(0.0, 1.0));
    const double nn = db.e_n * db.e_n * 1.25e21 * (1 + (mode == 1 ? 1e6 : 1e-6) * rng.uniform(0.0, 1.0));
    if (!qp_root_rel_tiny(F, nn, H, db)) continue;
    ++held;
    const double wide = qp_root_rel(F, nn, H, db);
    const double tight = qp_root_rel(F, nn, 8 * H, db, kSolverDisplacementCoeffTight);
    worst = std::max({worst, wide, tight});
    BOOST_TEST(wide <= kTinyQpRoot);
    BOOST_TEST(tight <= kTinyQpRoot);
  }
  BOOST_TEST(held > 300000);
  BOOST_TEST(worst > 9.0e-11, "the boundary was reached: worst " << worst);
  BOOST_TEST_MESSAGE("qp_root_rel_tiny: largest qp_root_rel where it holds " << worst);
}
