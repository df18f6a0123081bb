// definitions §9 in the exact engine: pdd2_global with its witness normal, positions and proved
// lower bound (reference/pdd/reference/global_pdd.h, relaxed_pieces.h).
//
// What is asserted, and where each expected value comes from:
// - a hand-derived pair whose optimum is a candidate direction (derivation below), and the
//   shipped pair poke-vertex-through-face whose optimum provably is not one (the exact witness
//   is below every candidate's relaxed value);
// - on every property fixture: lower <= pdd2_global <= pdd2_relaxed <= pdd2; the gap target;
//   the witness normal's value re-solved by CGAL's QP in the paper's full formulation (an
//   independent formulation of the same QP) equals pdd2_global; q1_*_global have object norm
//   pdd2_global and are separated by a plane with that normal;
// - the lower bound checked against the exact relaxed value along many other normals;
// - invariants: scaling by 2 multiplies the exact values by 4, an exact translation changes
//   nothing, swapping A and B (normal negated) gives intervals that intersect;
// - the closed form of relaxed_pieces.h equals CGAL's QP wherever its active set is optimal.
#include <boost/test/unit_test.hpp>

#include <random>
#include <set>
#include <string>

#include "fixtures.h"
#include "pdd/reference/candidate_directions.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/relaxed_pieces.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
const SolveOptions kReduced{QpFormulation::Reduced};
const Rational kGap = Rational(1) / Rational(1000000000000LL);  // definitions §9's 1e-12

// Pairs on which the branch and bound does not close the gap within its budget (the lower
// bound stays valid, but short of the witness). Empty since bound (Q) (global_pdd.cpp's
// hull_bound): adversarial-1-29 (a vertex 1e18 away, the minimiser on that vertex's wall) was
// here at a gap of 1.7e-8; coordinates-1-to-1e18, adversarial-1-9 and -19 (a vertex 1e15-1e18
// away) until the patches tried the multipliers of their corners' pieces and of the witness;
// adversarial-1-3, -13 and -23 (a vertex 1e-18 inside a face, whose minimiser lies in a band
// ~1e-19 rad wide) until patches below the doubles' grid went on in exact rationals. The test
// checks that each listed pair still misses the target and every other one meets it.
const std::set<std::string> kGapNotClosed = {};

Rational relaxed_along(const ExactPair& p, const Vector& n, QpFormulation f) {
  CandidateDirection d;
  d.n = n;
  auto qp = direction_qp(p, d, PddCase::Relaxed, f);
  BOOST_REQUIRE(qp);
  return qp->value;
}

Vector normal_of(const ExactResult& r) {
  BOOST_REQUIRE(r.pdd2_global_normal);
  const auto& n = *r.pdd2_global_normal;
  return Vector(n[0], n[1], n[2]);
}

Rational sigma(const ExactPair& p, const Positions<Rational>& qa, const Positions<Rational>& qb) {
  Rational total = 0;
  for (int t = 0; t < 2; ++t) {
    const ExactTet& X = t ? p.B : p.A;
    const Positions<Rational>& Q = t ? qb : qa;
    Rational sq = 0, sum[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        const Rational d = Q[i][k] - X[i][k];
        sq += d * d, sum[k] += d;
      }
    total += (sq + sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / 20;
  }
  return total;
}
}  // namespace

// The regular tetrahedron A = (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1) and B = A + (0, 0, 3/2).
// The half-turn about the z axis maps A to A and B to B, so the relaxed value G is invariant
// under it and its gradient at e_z is parallel to e_z: e_z is a stationary direction, and it is
// a candidate (EE of A's edge s0 s3 with B's edge r1 r2: (r2 - r1) x (s3 - s0) = (0,0,8)).
// Along e_z, A's heights are 1, -1, -1, 1 and B's 1/2, 5/2, 1/2, 5/2 (overlap delta = 1/2).
// Active sets {s0, s3}, {r1, r2} (m = 2 each, w = 1/3): c = (2/3 + 2 (1/2)/3) / (4/3) = 3/4,
// T_A = (2 c - 2) / 3 = -1/6, active A vertices move by c - 1 = -1/4, free ones by 1/6;
// KKT: active d = 1 - 3/4 + 1/6 = 5/12 >= 0, free d = -1 - 3/4 + 1/6 < 0. Cost of A:
// (2/16 + 2/36 + 1/36) / 20 = 1/96, B the same by symmetry: relaxed(e_z) = 1/48 = delta^2/12.
// That no other normal does better is what the program proves (its lower bound).
BOOST_AUTO_TEST_CASE(optimum_at_a_candidate_hand_derived) {
  TetPair p{"regular-shifted", {},
            {{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}},
            {{{1, 1, 2.5}, {1, -1, 0.5}, {-1, 1, 0.5}, {-1, -1, 2.5}}}};
  const ExactResult r = solve_exact(p, kReduced);
  BOOST_REQUIRE(r.intersecting);
  BOOST_TEST(relaxed_along(to_exact(p), Vector(0, 0, 1), QpFormulation::Full) == Rational(1, 48));
  BOOST_TEST(r.pdd2_global == Rational(1, 48));
  BOOST_TEST(r.pdd2_relaxed == Rational(1, 48));
  BOOST_REQUIRE(r.pdd2_global_lower);
  BOOST_TEST(*r.pdd2_global_lower <= r.pdd2_global);
  BOOST_TEST(*r.pdd2_global_lower >= Rational(1, 48) * (1 - kGap));
}

// poke-vertex-through-face (fixtures/smoke.json): every candidate's relaxed value is at least
// pdd2_relaxed = 3/224 (golden), and the exact witness is below it: the optimum over all planes
// is not a candidate direction. The witness value is re-solved here by the full formulation.
BOOST_AUTO_TEST_CASE(optimum_not_a_candidate) {
  TetPair p{"poke", {}, {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
            {{{1, 1, -1}, {3, 1, -1}, {1, 3, -1}, {1.5, 1.5, 0.5}}}};
  const ExactResult r = solve_exact(p, kReduced);
  BOOST_TEST(r.pdd2_relaxed == Rational(3, 224));
  BOOST_TEST(r.pdd2_global < Rational(3, 224) * Rational(9, 10));  // 0.0110 vs 0.0134
  BOOST_TEST(relaxed_along(to_exact(p), normal_of(r), QpFormulation::Full) == r.pdd2_global);
  for (const auto& d : candidate_directions(to_exact(p)))
    BOOST_TEST(relaxed_along(to_exact(p), d.n, QpFormulation::Reduced) > r.pdd2_global, d.label.str());
}

// adversarial-1-29 (fixtures/families/adversarial.json): s1 is 1e18 away from the others. An
// independent search (Python mpmath, 80 digits: the relaxed QP solved per plane offset by its
// threshold structure, minimised over c by golden section, then a pattern search over the
// sphere from the engine's earlier witness (1, -5/16, -15/16), whose value 0.000803262817742296
// it reproduced) reached 0.000720963442344484 at n ~ (0.70908, -0.21916, -0.67020), where
// n.(s1 - s0) = -15810: the minimiser sits on the wall where s1 stops being free (within 1e-14
// rad of the plane normal to s1 - s0), which the patches cannot resolve. The wall witnesses of
// global_pdd.cpp must find at least that, and the proved lower bound (gap met since bound (Q))
// must not exceed it: the independent value lies in the engine's interval.
BOOST_AUTO_TEST_CASE(far_vertex_witness_on_its_wall) {
  for (const TetPair& pair : test::load_pairs("families/adversarial.json")) {
    if (pair.name != "adversarial-1-29") continue;
    const ExactResult r = solve_exact(pair, kReduced);
    BOOST_REQUIRE(r.intersecting);
    BOOST_REQUIRE(r.pdd2_global_lower);
    BOOST_TEST(r.pdd2_global <= Rational(720963442344484LL) / Rational(1000000000000000000LL));
    // (the independent value is printed to 15 digits: its last digit rounded up)
    BOOST_TEST(*r.pdd2_global_lower <= Rational(720963442344485LL) / Rational(1000000000000000000LL));
    BOOST_TEST(r.pdd2_global - *r.pdd2_global_lower <= kGap * r.pdd2_global);
    BOOST_TEST(relaxed_along(to_exact(pair), normal_of(r), QpFormulation::Full) == r.pdd2_global);
    return;
  }
  BOOST_FAIL("adversarial-1-29 not found");
}

// A vertex 1e15 away where the minimiser lies in the band normal to its offset (pdd generate
// --family adversarial --seed 101, pair 39; not a shipped fixture). Along that band the far
// vertex's height sweeps through the other seven within ~1e-14 rad, so one patch's corners
// fall in up to four active sets (f/f, d/f, d/d, c/d), and no single piece's multipliers bound
// it: the gap stopped at 37% of the value with its 1,000 exact patches spent. Bound (Q), the
// exact minimum of G over each patch's hull in one QP (all active sets at once), closes it
// (~100 such QPs). The witness is re-solved by the full formulation.
BOOST_AUTO_TEST_CASE(far_vertex_band_gap_closed) {
  TetPair p{"adversarial-101-39", {},
            {{{-687499999999998.4, -999999999999995.2, 625000000000007.4},
              {7.329927766436054, 3.1387307446093127, 3.179897467032423},
              {9.557033192526355, 7.224239331728396, 6.028756997720545},
              {0.7901867511128946, 7.9696781226671645, 6.2377807894446}}},
            {{{3.152070483949826, 3.456869097575158, 6.613628663520281},
              {8.224052090727028, 7.481751067348652, 7.894871453945757},
              {0.46815284297627713, 6.117352947194075, 3.8854231266616646},
              {3.33217682984867, 2.8647862744117214, 5.688322476618486}}}};
  const ExactResult r = solve_exact(p, kReduced);
  BOOST_REQUIRE(r.intersecting);
  BOOST_REQUIRE(r.pdd2_global_lower);
  BOOST_TEST(r.pdd2_global < r.pdd2_relaxed);
  BOOST_TEST(*r.pdd2_global_lower <= r.pdd2_global);
  BOOST_TEST(r.pdd2_global - *r.pdd2_global_lower <= kGap * r.pdd2_global,
             "gap " << CGAL::to_double((r.pdd2_global - *r.pdd2_global_lower) / r.pdd2_global));
  BOOST_TEST(relaxed_along(to_exact(p), normal_of(r), QpFormulation::Full) == r.pdd2_global);
}

// relaxed_hull_minimum (direction_qp.h), the QP behind bound (Q), against its definition on
// poke-vertex-through-face: with one normal it is G(n) = relaxed(n) n.n; with four it is
// attained (G at its own minimiser sum lambda_k c_k equals it: not merely a number below G) and
// at most G at each corner and at sampled points of the hull; and, the corners scaled to
// |c| <= 1 (by powers of two here; global_pdd.cpp's hull_bound scales by any dyadic s_k, the
// same lemma), it is at most relaxed(u) for every sampled u of the cone they span (the lemma
// global_pdd.cpp relies on). Corners are integer vectors near a common direction; every
// comparison is exact.
BOOST_AUTO_TEST_CASE(hull_minimum_bounds_the_cone) {
  TetPair pair{"poke", {}, {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
               {{{1, 1, -1}, {3, 1, -1}, {1, 3, -1}, {1.5, 1.5, 0.5}}}};
  const ExactPair p = to_exact(pair);
  // relaxed(n) is the same for every positive multiple of n: the QP (dyadic numbers only) gets
  // n times its components' denominators
  auto relaxed = [&](const Vector& n) {
    const Rational d = Rational(n.x().denominator()) * Rational(n.y().denominator()) *
                       Rational(n.z().denominator());
    return relaxed_along(p, n * d, QpFormulation::Reduced);
  };
  auto G = [&](const Vector& n) { return relaxed(n) * n.squared_length(); };
  const Vector n0(Rational(3, 4), Rational(-1, 8), Rational(1, 2));
  BOOST_TEST(relaxed_hull_minimum(p, {n0}) == G(n0));
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> coord(-2048, 2048), weight(1, 1000);
  int cones = 0;
  while (cones < 12) {
    std::vector<Vector> c;
    const Vector centre(coord(rng), coord(rng), coord(rng));
    for (int k = 0; k < 4; ++k) {  // corners near a common direction, so the cone is narrow
      const Vector v = centre + Vector(coord(rng) / 8, coord(rng) / 8, coord(rng) / 8);
      if (v.squared_length() == 0) break;
      // scaled to |v| <= 1 by a power of two: components stay dyadic
      Rational s = 1;
      while (s * s * v.squared_length() > 1) s /= 2;
      c.push_back(v * s);
    }
    if (c.size() < 4) continue;
    ++cones;
    std::vector<Rational> lambda;
    const Rational h = relaxed_hull_minimum(p, c, &lambda);
    BOOST_TEST(h >= 0);
    BOOST_REQUIRE(lambda.size() == 4u);
    Vector star = CGAL::NULL_VECTOR;
    Rational total = 0;
    for (int j = 0; j < 4; ++j) {
      BOOST_TEST(lambda[j] >= 0);
      total += lambda[j];
      star = star + c[j] * lambda[j];
    }
    BOOST_TEST(total == 1);
    BOOST_TEST(G(star) == h);  // attained: the QP returns the minimum, not just a lower number
    for (const Vector& v : c) BOOST_TEST(h <= G(v));
    for (int k = 0; k < 10; ++k) {
      Rational w[4], sum = 0;
      for (Rational& x : w) x = weight(rng), sum += x;
      Vector u = CGAL::NULL_VECTOR;
      for (int j = 0; j < 4; ++j) u = u + c[j] * (w[j] / sum);
      BOOST_TEST(h <= G(u));                                              // a point of the hull
      BOOST_TEST(h <= relaxed(u));                                        // relaxed(u/|u|)
    }
  }
}

// Nearly coplanar faces (pdd generate --family adversarial --seed 101, pair 6: B's face 2^-40
// out of the plane of A's face; not a shipped fixture): pdd2_global ~ 3.06e-27 beside a size of
// ~10, so the minimising piece's H has entries ~1 and an eigenvalue ~1e-27. Two limits of the
// doubles would hold the gap at 1e-4: the certified eigenvalue (H - mu I checked exactly for
// mu = the Rayleigh quotient shrunk by 1e-15 .. 1e-4; the quotient of a double vector carries a
// relative error ~u^2 |H| / mu ~ 1e-6, so only the 1e-4 shrink passed) and the witness (a double
// normal, off by an angle ~u, sits ~1.4e-6 above the minimum). Newton's method on the exact
// characteristic polynomial (certified_min_eigenvalue) and one exact, unrounded step of inverse
// iteration (the witness) close it: the gap must be met, with the witness re-solved by the full
// formulation.
BOOST_AUTO_TEST_CASE(nearly_coplanar_faces_gap_closed) {
  TetPair p{"adversarial-101-6", {},
            {{{5.3125, 9.25, 4.6875}, {4.0625, 2.6875, 4.4375}, {10.0, 1.75, 1.75}, {6.125, 2.4375, 5.75}}},
            {{{9.64062500000017, -3.1875000000006253, 3.5468749999994884},
              {7.453125000000341, 7.203124999999602, 2.9531250000005116},
              {5.921875000000114, 4.140624999999488, 5.484374999999716},
              {6.25, 5.0, 9.375}}}};
  const ExactResult r = solve_exact(p, kReduced);
  BOOST_REQUIRE(r.intersecting);
  BOOST_REQUIRE(r.pdd2_global_lower);
  BOOST_TEST(r.pdd2_global > 0);
  BOOST_TEST(r.pdd2_global < Rational(1, 100000000) * Rational(1, 100000000) * Rational(1, 100000000));
  BOOST_TEST(*r.pdd2_global_lower <= r.pdd2_global);
  BOOST_TEST(r.pdd2_global - *r.pdd2_global_lower <= kGap * r.pdd2_global);
  BOOST_TEST(relaxed_along(to_exact(p), normal_of(r), QpFormulation::Full) == r.pdd2_global);
}

BOOST_AUTO_TEST_CASE(witness_bounds_and_positions_on_every_fixture) {
  int checked = 0;
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactResult r = solve_exact(pair, kReduced);
      if (r.error) continue;
      const ExactPair p = to_exact(pair);
      BOOST_REQUIRE(r.pdd2_global_lower);
      if (!r.intersecting) {
        BOOST_TEST(r.pdd2_global == 0);
        BOOST_TEST(!r.pdd2_global_normal);
        continue;
      }
      const Rational& g = r.pdd2_global;
      BOOST_TEST(*r.pdd2_global_lower <= g, pair.name);
      BOOST_TEST(g <= r.pdd2_relaxed, pair.name);
      BOOST_TEST(r.pdd2_relaxed <= r.pdd2, pair.name);
      BOOST_TEST(*r.pdd2_global_lower >= 0, pair.name);
      // every relaxed value is >= PD^2/32 (global_pdd.h's GlobalOptions::floor): the witness
      // too, and the reported lower bound is never below it
      BOOST_TEST(g >= r.rigid_pd2 / 32, pair.name);
      BOOST_TEST(*r.pdd2_global_lower >= r.rigid_pd2 / 32, pair.name);
      const bool closed = *r.pdd2_global_lower >= g * (1 - kGap);
      BOOST_TEST(closed != (kGapNotClosed.count(pair.name) > 0),
                 pair.name << ": gap " << CGAL::to_double((g - *r.pdd2_global_lower) / g));
      const Vector n = normal_of(r);
      BOOST_TEST(relaxed_along(p, n, QpFormulation::Full) == g, pair.name);
      BOOST_TEST(sigma(p, r.q1_A_global, r.q1_B_global) == g, pair.name);
      Rational hiA, loB;
      for (int i = 0; i < 4; ++i) {
        const Rational a = n.x() * r.q1_A_global[i][0] + n.y() * r.q1_A_global[i][1] + n.z() * r.q1_A_global[i][2];
        const Rational b = n.x() * r.q1_B_global[i][0] + n.y() * r.q1_B_global[i][1] + n.z() * r.q1_B_global[i][2];
        if (i == 0 || a > hiA) hiA = a;
        if (i == 0 || b < loB) loB = b;
      }
      BOOST_TEST(hiA <= loB, pair.name << ": the deformed pair is separated by the witness plane");
      ++checked;
    }
  BOOST_TEST(checked >= 20);
}

// The proved lower bound against the exact relaxed value along 300 other normals per pair.
BOOST_AUTO_TEST_CASE(lower_bound_holds_on_sampled_normals) {
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> coord(-1000, 1000);
  int checked = 0;
  for (const char* name : {"paper.json", "sliver.json", "nested.json"})
    for (const TetPair& pair : test::load_pairs(std::string("families/") + name)) {
      const ExactResult r = solve_exact(pair, kReduced);
      if (r.error || !r.intersecting) continue;
      const ExactPair p = to_exact(pair);
      for (int k = 0; k < 300; ++k) {
        const Vector n(coord(rng), coord(rng), coord(rng));
        if (n == CGAL::NULL_VECTOR) continue;
        BOOST_TEST(relaxed_along(p, n, QpFormulation::Reduced) >= *r.pdd2_global_lower, pair.name);
      }
      if (++checked >= 8) break;
    }
  BOOST_TEST(checked >= 8);
}

BOOST_AUTO_TEST_CASE(scaling_translation_and_swap) {
  int checked = 0;
  for (const TetPair& pair : test::load_pairs("families/paper.json")) {
    const ExactResult r = solve_exact(pair, kReduced);
    if (!r.intersecting) continue;
    TetPair scaled = pair, moved = pair, swapped = pair;
    for (auto* t : {&scaled.A, &scaled.B})
      for (auto& v : *t)
        for (double& x : v) x *= 2;
    for (auto* t : {&moved.A, &moved.B})
      for (auto& v : *t) v[0] += 64;  // exact for the paper's coordinates (|x| < 16, 2^-k grid)
    bool exact_move = true;
    for (int t = 0; t < 2; ++t)
      for (int i = 0; i < 4; ++i)
        exact_move = exact_move && Rational((t ? moved.B : moved.A)[i][0]) ==
                                       Rational((t ? pair.B : pair.A)[i][0]) + 64;
    std::swap(swapped.A, swapped.B);
    const ExactResult s = solve_exact(scaled, kReduced), w = solve_exact(swapped, kReduced);
    BOOST_TEST(s.pdd2_global == 4 * r.pdd2_global, pair.name);
    BOOST_TEST(*s.pdd2_global_lower == 4 * *r.pdd2_global_lower, pair.name);
    if (exact_move) {
      const ExactResult m = solve_exact(moved, kReduced);
      BOOST_TEST(m.pdd2_global == r.pdd2_global, pair.name);
      BOOST_TEST(*m.pdd2_global_lower == *r.pdd2_global_lower, pair.name);
    }
    // relaxed(u; A, B) = relaxed(-u; B, A): the two certified intervals must intersect, and
    // each witness, negated, is a witness of the other problem.
    BOOST_TEST(*w.pdd2_global_lower <= r.pdd2_global, pair.name);
    BOOST_TEST(*r.pdd2_global_lower <= w.pdd2_global, pair.name);
    BOOST_TEST(relaxed_along(to_exact(swapped), -normal_of(r), QpFormulation::Reduced) == r.pdd2_global,
               pair.name);
    ++checked;
  }
  BOOST_TEST(checked >= 5);
}

// relaxed_pieces.h: wherever an active set's KKT signs hold, n^T H n equals CGAL's QP optimum.
BOOST_AUTO_TEST_CASE(closed_form_pieces_equal_the_qp) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coord(-50, 50);
  int matched = 0;
  for (const TetPair& pair : test::load_pairs("families/paper.json")) {
    const ExactPair p = to_exact(pair);
    for (int k = 0; k < 40; ++k) {
      const Vector n(coord(rng), coord(rng), coord(rng));
      if (n == CGAL::NULL_VECTOR) continue;
      int optimal = 0;
      for (unsigned a = 1; a < 16; ++a)
        for (unsigned b = 1; b < 16; ++b) {
          const RelaxedPiece piece = relaxed_piece(p, {a, b});
          if (!piece_is_optimal_at(piece, n)) continue;
          ++optimal;
          BOOST_TEST(piece_quadratic(piece, n) / n.squared_length() ==
                     relaxed_along(p, n, QpFormulation::Reduced));
        }
      // an intersecting pair has exactly one optimal set at a generic normal (ties aside)
      if (optimal > 0) ++matched;
    }
  }
  BOOST_TEST(matched >= 100);
}
