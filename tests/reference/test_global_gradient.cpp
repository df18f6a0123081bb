// The gradient of pdd2_global (pdd.h, "The gradient of pdd2_global"; SolveOptions::gradient) in
// the exact engine, and the fast engine's against it.
//
// Notation: f = pdd2_global, P the current positions (8 vertices), W a displacement of P, sigma(W) its
// object norm over A and B, <g, W> the sum of the 24 products; U = f's witness value at P (the
// exact engine's pdd2_global: sigma of its witness positions, within 1e-12 above the minimum)
// and L = its proved lower bound.
// What is asserted, exactly (rationals, no tolerance), and why it must hold:
// - the formula at the witness: <g, d> = -2 U (Euler, d = q1_global - P) and sum_i g_i = 0 (the
//   relaxed optimum along a normal is not improved by translating both tetrahedra along it);
//   not intersecting: 0; no gradient unless asked; asking changes no other field.
// - (*) of definitions §9 with the witness Q: f(P + W) <= U + <g, W> + sigma(W) for every W, and
//   L(P + W) <= f(P + W). So, exactly, for steps W and -W of P (both doubles):
//       L(P + W) - U - sigma(W) <= <g, W> <= U + sigma(W) - L(P - W).            (box)
//   The same box holds for the true gradient (any minimiser's: (*) with that minimiser), so
//   it is a certified interval for <grad f, W>: about 2 (1e-12 f + sigma(W)) + |second
//   difference| wide. The step makes sigma(W) = 1e-12 f, so the interval is a few sqrt(1e-12)
//   of the slope wide plus the curvature's O(h) term: 3e-6 to 7e-5 of it measured.
// - the fast engine's gradient lies in the same certified interval. This is more than its
//   guarantee (solve_pair.cpp: sqrt((1 + K) 2e-9) of |g| in the dual object norm, from the
//   accuracy contract of the positions alone); it holds because the fast normal is polished to
//   about 1e-16: the two engines' gradients agree to 1.4e-14 on the paper's pairs.
// - a tie (the mirror-symmetric ridge of tests/fast/fast_global_gradient_test.cpp): the
//   mirrored witness is a witness too, so along an antisymmetric W both L(P + W) and L(P - W)
//   are <= U - |<g, W>| + sigma(W): f decreases both ways (a concave kink); the gradient
//   returned is that of the returned witness's branch, between the one-sided derivatives.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "fixtures.h"
#include "pdd/compare/random.h"
#include "pdd/pdd.h"
#include "pdd/reference/solve_exact.h"

// Inside pdd::reference: its Rational (the engine's) is the one meant, not pdd.h's pdd::Rational.
namespace pdd::reference {
namespace {

using Grad = PairGradient<Rational>;

SolveOptions with_gradient() {
  SolveOptions o;
  o.gradient = true;
  return o;
}

Rational coordinate(const ExactPair& p, int i, int k) { return i < 4 ? p.A[i][k] : p.B[i - 4][k]; }
Rational q_at(const ExactResult& r, int i, int k) {
  return i < 4 ? r.q1_A_global[i][k] : r.q1_B_global[i - 4][k];
}
double& at(TetPair& p, int i, int k) { return i < 4 ? p.A[i][k] : p.B[i - 4][k]; }

Rational sigma8(const Grad& W) {
  Rational total = 0;
  for (int t = 0; t < 2; ++t) {
    Rational sq = 0, s[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) sq += W[4 * t + i][k] * W[4 * t + i][k], s[k] += W[4 * t + i][k];
    total += (sq + s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / Rational(20);
  }
  return total;
}
Rational dot(const Grad& a, const Grad& b) {
  Rational s = 0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) s += a[i][k] * b[i][k];
  return s;
}
Grad displacement(const ExactPair& p, const ExactResult& r) {
  Grad d;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) d[i][k] = q_at(r, i, k) - coordinate(p, i, k);
  return d;
}
Grad exact_of(const PairGradient<double>& g) {
  Grad out;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = Rational(g[i][k]);
  return out;
}

// P + W and P - W in doubles for a step w_ik ~ h v_ik, the same exact step both ways: w is
// rounded to a multiple of twice x's ulp, so that x + w and x - w are representable also where
// they leave x's binade (upwards the ulp doubles; x on a binade's edge, as an integer, is a
// multiple of it). Checked exactly. W: the step.
void steps(const TetPair& p, const std::array<std::array<double, 3>, 8>& w, TetPair& plus, TetPair& minus,
           Grad& W) {
  plus = minus = p;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = at(plus, i, k);
      const double q = 2 * (std::nextafter(std::fabs(x), INFINITY) - std::fabs(x));
      const double step = x == 0 ? w[i][k] : std::round(w[i][k] / q) * q;  // 0 +- w: exact
      at(plus, i, k) = x + step;
      at(minus, i, k) = x - step;
      BOOST_REQUIRE(Rational(at(plus, i, k)) - Rational(x) == Rational(step));
      BOOST_REQUIRE(Rational(x) - Rational(at(minus, i, k)) == Rational(step));
      W[i][k] = Rational(step);
    }
}

struct Box {
  Rational lo, hi;
};

// The certified interval of <grad f, W> (header): from L(P + W) and L(P - W).
Box box(const TetPair& p, const ExactResult& r, const std::array<std::array<double, 3>, 8>& w, Grad& W) {
  TetPair plus, minus;
  steps(p, w, plus, minus, W);
  const ExactResult a = solve_exact(plus), b = solve_exact(minus);
  BOOST_REQUIRE((a.pdd2_global_lower && b.pdd2_global_lower));
  const Rational s = sigma8(W);
  return {*a.pdd2_global_lower - r.pdd2_global - s, r.pdd2_global + s - *b.pdd2_global_lower};
}

// A random direction scaled so that sigma(step) is about 1e-12 f (the header's choice).
std::array<std::array<double, 3>, 8> random_step(compare::ReproducibleRng& rng, double f) {
  std::array<std::array<double, 3>, 8> v;
  for (auto& x : v)
    for (double& c : x) c = rng.uniform(-1, 1);
  Grad V;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) V[i][k] = Rational(v[i][k]);
  const double scale = std::sqrt(1e-12 * f / CGAL::to_double(sigma8(V)));
  for (auto& x : v)
    for (double& c : x) c *= scale;
  return v;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(global_gradient)

// The formula, exactly, on the smoke pairs (intersecting and not).
BOOST_AUTO_TEST_CASE(exact_gradient_at_the_witness) {
  int intersecting = 0;
  for (const TetPair& pair : test::load_pairs("smoke.json")) {
    const ExactResult plain = solve_exact(pair), r = solve_exact(pair, with_gradient());
    BOOST_TEST(!plain.pdd2_global_grad);
    BOOST_REQUIRE(r.pdd2_global_grad);
    BOOST_TEST(r.pdd2_global == plain.pdd2_global);
    const Grad& g = *r.pdd2_global_grad;
    if (!r.intersecting) {
      for (const auto& v : g)
        for (const Rational& c : v) BOOST_TEST(c == Rational(0), pair.name);
      continue;
    }
    ++intersecting;
    const ExactPair p = to_exact(pair);
    BOOST_TEST(dot(g, displacement(p, r)) == -2 * r.pdd2_global, pair.name);
    for (int k = 0; k < 3; ++k) {
      Rational s = 0;
      for (int i = 0; i < 8; ++i) s += g[i][k];
      BOOST_TEST(s == Rational(0), pair.name);
    }
  }
  BOOST_TEST(intersecting >= 4);
}

// The certified interval contains the exact witness's slope (a theorem, checked) and the fast
// engine's (its accuracy), on the poke pair and on the paper protocol's first shipped pairs.
BOOST_AUTO_TEST_CASE(fast_and_exact_gradients_in_the_certified_interval) {
  std::vector<TetPair> pairs = {test::load_pair("smoke.json", "poke-vertex-through-face")};
  for (const TetPair& p : test::load_pairs("families/paper.json"))
    if (pairs.size() < 3 && solve_exact(p, SolveOptions{QpFormulation::Reduced, false}).intersecting)
      pairs.push_back(p);
  compare::ReproducibleRng rng(3);
  fast::SolveOptions fast_gradient;
  fast_gradient.gradient = true;
  for (const TetPair& pair : pairs) {
    const ExactResult r = solve_exact(pair, with_gradient());
    const PairResult<double> fr = fast::solve_pair(pair, fast_gradient);
    BOOST_REQUIRE((r.intersecting && !fr.error && !fr.pdd2_global_error));
    const Grad& g = *r.pdd2_global_grad;
    const Grad gf = exact_of(*fr.pdd2_global_grad);
    for (int j = 0; j < 3; ++j) {
      Grad W;
      const Box b = box(pair, r, random_step(rng, CGAL::to_double(r.pdd2_global)), W);
      BOOST_TEST((b.lo <= dot(g, W) && dot(g, W) <= b.hi), pair.name << " step " << j);
      BOOST_TEST((b.lo <= dot(gf, W) && dot(gf, W) <= b.hi),
                 pair.name << " step " << j << ": fast " << CGAL::to_double(dot(gf, W)) << " not in ["
                           << CGAL::to_double(b.lo) << ", " << CGAL::to_double(b.hi) << "]");
      // the interval is narrow: a millionth of the slope or so (header), so this tests something
      BOOST_TEST_MESSAGE(pair.name << ": interval width / |slope| = "
                                   << CGAL::to_double((b.hi - b.lo) / CGAL::abs(dot(g, W))));
    }
  }
}

// Two planes tie (the ridge of the fast test, derivation there): along an antisymmetric step,
// f decreases both ways, by at least |<g, W>| - sigma(W) (proved lower bounds), and the witness
// returned is one of a mirror pair.
BOOST_AUTO_TEST_CASE(tie_between_two_planes_is_a_concave_kink) {
  const TetPair pair{"ridge", {}, {{{0, -2, 0}, {0, 2, 0}, {-2, 0, -2}, {2, 0, -2}}},
                     {{{0, 0.25, -0.3}, {-1, -0.5, 2}, {1, -0.5, 2}, {0, 1.5, 2}}}};
  const ExactResult r = solve_exact(pair, with_gradient());
  BOOST_REQUIRE(r.pdd2_global_normal);
  BOOST_TEST(CGAL::abs((*r.pdd2_global_normal)[0]) > CGAL::abs((*r.pdd2_global_normal)[2]) / 10);
  const Grad& g = *r.pdd2_global_grad;
  // the apex r0 moves along x by 2^-10 (exact), W antisymmetric under the mirror x -> -x
  std::array<std::array<double, 3>, 8> w{};
  w[4][0] = 0x1p-10;
  Grad W;
  TetPair plus, minus;
  steps(pair, w, plus, minus, W);
  const Rational a = dot(g, W);
  // the mirrored witness's gradient at r0 is g's with x negated: <g', W> = -a
  // the step breaks the tie by more than its own cost and the witnesses' gap (1e-12 U), so that
  // the witness values below must drop too
  BOOST_TEST(CGAL::abs(a) - sigma8(W) > r.pdd2_global / Rational(1000000000000LL));
  for (const TetPair& q : {plus, minus}) {
    const ExactResult s = solve_exact(q);
    BOOST_REQUIRE(s.pdd2_global_lower);
    BOOST_TEST(*s.pdd2_global_lower <= r.pdd2_global - CGAL::abs(a) + sigma8(W));
    BOOST_TEST(s.pdd2_global < r.pdd2_global);  // f(P + W) < f(P) and f(P - W) < f(P): a kink
  }
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace pdd::reference
