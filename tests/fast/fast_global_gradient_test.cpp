// The fast engine's gradient of pdd2_global (definitions §9, "The gradient of pdd2_global";
// SolveOptions::gradient), against finite differences of pdd2_global itself.
//
// Notation: f = pdd2_global, P the current positions (8 vertices), W a displacement of P, sigma(W) the
// object norm of W summed over A and B, <g, W> the sum of the 24 products.
// What is asserted, and why each bound holds:
// - the gradient is -d sigma/d d at d = q1_global - P: Euler's relation <g, d> = -2 f (to the
//   rounding of 24 products), and sum_i g_i = 0 (the relaxed optimum along a normal cannot be
//   improved by translating both tetrahedra along it, so the displacements of A and B sum to 0);
// - (*) of definitions §9 with the returned positions Q: for every W,
//       f(P + W) <= s(W) := sigma(Q - P - W) = U + <g, W> + sigma(W),  U = sigma(Q - P),
//   exactly when Q is separated. The fast Q is separated up to tau = 1e-9 R (the accuracy
//   contract, R the largest coordinate magnitude): translating B by tau along the normal
//   separates it and adds at most 2 sqrt(s) tau + tau^2 to s (Cauchy-Schwarz in the object
//   norm); the reported f(P + W) is within 1e-9 of the exact value. So, with W = +-h V,
//       fast f(P + W) (1 - 1e-9) <= s(W) + 2 sqrt(s(W)) tau + tau^2 + rounding   (bracket)
//   for every h: the one-sided difference quotients bracket <g, V>. This is the one-sided
//   finite difference test; no tolerance is chosen.
// - central differences: writing the two bracket inequalities as upper bounds on the one-sided
//   quotients' distances to <g, V>, their half-sum gives
//       |(f+ - f-) / 2h - <g, V>| <= h sigma(V) + slack / h + |f+ + f- - 2U| / 2h,
//   the last term measured (the second difference: O(h) where f is smooth). The step balances
//   the first two terms: h = sqrt(slack(0)) with sigma(V) = 1. The bound is then about
//   sqrt(1e-9 f + 2 sqrt(f) tau) + O(h), far below |<g, V>| ~ |g|: the check has teeth, as
//   shown by running it on a wrong gradient (the d_i term alone), which it rejects.
// - shallow contacts (a vertex 1e-1 to 1e-4 through a face of a tetrahedron of size 10):
//   the same bounds.
// - a pair whose minimiser is not unique (mirror-symmetric: two tilted planes tie): the
//   gradient returned is the gradient of the branch of the returned minimiser, an element of
//   Clarke's generalized gradient. By symmetry the mirror image of the returned minimiser is a
//   minimiser too, so the bracket holds for the mirrored gradient as well; along an
//   antisymmetric V (<g', V> = -<g, V>) both one-sided quotients are then <= -|<g, V>| + h +
//   slack/h: pdd2_global decreases both ways, a concave kink, and the returned gradient lies
//   between the one-sided derivatives -|a| and +|a|.
#define BOOST_TEST_MODULE fast_global_gradient
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fast_test_util.h"
#include "pdd/pdd.h"

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;

namespace {

using Grad = PairGradient<double>;
constexpr double kValueRel = 1e-9;  // the accuracy contract of every fast value
constexpr double kSeparation = 1e-9;  // q1_global separated up to this times R

// sigma of a displacement of the eight vertices (both tetrahedra).
double sigma8(const Grad& W) {
  double total = 0;
  for (int t = 0; t < 2; ++t) {
    double sq = 0, s[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        sq += W[4 * t + i][k] * W[4 * t + i][k];
        s[k] += W[4 * t + i][k];
      }
    total += (sq + s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / 20;
  }
  return total;
}
double dot(const Grad& a, const Grad& b) {
  double s = 0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) s += a[i][k] * b[i][k];
  return s;
}
double abs_dot(const Grad& a, const Grad& b) {  // sum of |products|: bounds dot's rounding
  double s = 0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) s += std::fabs(a[i][k] * b[i][k]);
  return s;
}
double& at(TetPair& p, int i, int k) { return i < 4 ? p.A[i][k] : p.B[i - 4][k]; }
double at(const TetPair& p, int i, int k) { return i < 4 ? p.A[i][k] : p.B[i - 4][k]; }
double q_at(const PairResult<double>& r, int i, int k) {
  return i < 4 ? r.q1_A_global[i][k] : r.q1_B_global[i - 4][k];
}
double largest_coordinate(const TetPair& p) {
  double R = 0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) R = std::max(R, std::fabs(at(p, i, k)));
  return R;
}

// P + W in doubles; W is replaced by the displacement actually made (each coordinate's
// difference, exact by Sterbenz's lemma where both lie within a factor 2, checked otherwise).
TetPair moved(const TetPair& p, Grad& W) {
  TetPair q = p;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = at(p, i, k), y = x + W[i][k];
      at(q, i, k) = y;
      W[i][k] = y - x;
      BOOST_REQUIRE(W[i][k] + x == y && y - W[i][k] == x);
    }
  return q;
}

SolveOptions with_gradient() {
  SolveOptions o;
  o.gradient = true;
  return o;
}

double global_value(const TetPair& p) {
  const PairResult<double> r = solve_pair(p);
  BOOST_REQUIRE(!r.error);
  BOOST_REQUIRE(!r.pdd2_global_error);
  return r.pdd2_global;
}

// A random direction with sigma(V) = 1.
Grad random_direction(pdd::compare::ReproducibleRng& rng) {
  Grad V;
  for (auto& v : V)
    for (double& c : v) c = rng.uniform(-1, 1);
  const double s = std::sqrt(sigma8(V));
  for (auto& v : V)
    for (double& c : v) c /= s;
  return V;
}

// The displacement d = Q - P and U = sigma(d) of a record.
Grad displacement(const TetPair& p, const PairResult<double>& r) {
  Grad d;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) d[i][k] = q_at(r, i, k) - at(p, i, k);
  return d;
}

struct Quotients {
  double fp, fm, U, a, h, slack_p, slack_m;  // f(P + hV), f(P - hV), sigma(Q - P), <g, V>
};

// The bracket (*) for W = +-h V, asserted; returns what the central-difference bound needs.
// `g` is the gradient checked (the engine's, or a wrong one to show the check rejects it);
// returns false where a bracket inequality fails.
bool bracket(const TetPair& p, const PairResult<double>& r, const Grad& g, const Grad& V, double h,
             Quotients& out) {
  const Grad d = displacement(p, r);
  const double U = sigma8(d);
  const double tau = kSeparation * largest_coordinate(p);
  bool ok = true;
  for (int sign : {1, -1}) {
    Grad W;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) W[i][k] = sign * h * V[i][k];
    const TetPair q = moved(p, W);
    const double f = global_value(q);
    const double s = U + dot(g, W) + sigma8(W);
    // rounding of s as computed here: each of the ~50 terms within 1e-15 relative
    const double rounding = 1e-14 * (U + abs_dot(g, W) + sigma8(W));
    const double slack = 2 * std::sqrt(std::max(s, 0.0)) * tau + tau * tau + rounding;
    ok = ok && f * (1 - kValueRel) <= s + slack;
    (sign > 0 ? out.fp : out.fm) = f;
    (sign > 0 ? out.slack_p : out.slack_m) = slack + kValueRel * f;
  }
  out.U = U, out.a = dot(g, V), out.h = h;
  return ok;
}

// The step of the central difference: h^2 sigma(V) = the slack at P (sigma(V) = 1).
double step_for(const TetPair& p, double f) {
  const double tau = kSeparation * largest_coordinate(p);
  return std::sqrt(2 * kValueRel * f + 2 * std::sqrt(f) * tau + tau * tau);
}

// Both checks of the header on one pair along `directions` random V; returns how many
// directions a wrong gradient (the d_i term alone, without sum_k d_k) failed.
int check_pair(const TetPair& p, pdd::compare::ReproducibleRng& rng, int directions) {
  const PairResult<double> r = solve_pair(p, with_gradient());
  BOOST_REQUIRE(!r.error);
  BOOST_REQUIRE(r.intersecting);
  BOOST_REQUIRE(r.pdd2_global_grad);
  const Grad& g = *r.pdd2_global_grad;
  const Grad d = displacement(p, r);
  Grad wrong;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) wrong[i][k] = -d[i][k] / 10;
  const double f = r.pdd2_global, h = step_for(p, f);
  int rejected = 0;
  for (int j = 0; j < directions; ++j) {
    const Grad V = random_direction(rng);
    Quotients q;
    BOOST_TEST(bracket(p, r, g, V, h, q), p.name << " direction " << j);
    const double central = (q.fp - q.fm) / (2 * h);
    const double bound = h + std::max(q.slack_p, q.slack_m) / h + std::fabs(q.fp + q.fm - 2 * q.U) / (2 * h);
    BOOST_TEST(std::fabs(central - q.a) <= bound,
               p.name << " direction " << j << ": central " << central << ", <g, V> " << q.a << ", bound " << bound);
    Quotients w;
    const bool wrong_bracket = bracket(p, r, wrong, V, h, w);
    rejected += !wrong_bracket || std::fabs(central - w.a) > bound;
  }
  return rejected;
}

}  // namespace

// The formula: <g, d> = -2 f (Euler) and sum_i g_i = 0, on random intersecting pairs; zero
// when not intersecting; no key without the option.
BOOST_AUTO_TEST_CASE(gradient_is_minus_the_norm_derivative_at_the_witness) {
  int checked = 0;
  for (const TetPair& p : random_pairs(60, 11, false)) {
    const PairResult<double> plain = solve_pair(p), r = solve_pair(p, with_gradient());
    BOOST_TEST(!plain.pdd2_global_grad);
    if (r.error) continue;
    BOOST_REQUIRE(r.pdd2_global_grad);
    const Grad& g = *r.pdd2_global_grad;
    BOOST_TEST(r.pdd2_global == plain.pdd2_global);  // the gradient changes nothing else
    if (!r.intersecting) {
      for (const auto& v : g)
        for (double c : v) BOOST_TEST(c == 0.0);
      continue;
    }
    if (r.pdd2_global_error) continue;
    const Grad d = displacement(p, r);
    // Euler with U = sigma(d) (the positions' own norm; the reported value is within 1e-9 of it):
    // 24 products and the engine's ~6 u per component, within 1e-14 of the absolute sum
    BOOST_TEST(std::fabs(dot(g, d) + 2 * sigma8(d)) <= 1e-14 * (abs_dot(g, d) + sigma8(d)), p.name);
    BOOST_TEST(std::fabs(sigma8(d) - r.pdd2_global) <= kValueRel * r.pdd2_global, p.name);
    double norm = 0;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) norm += std::fabs(g[i][k]);
    for (int k = 0; k < 3; ++k) {
      double s = 0;
      for (int i = 0; i < 8; ++i) s += g[i][k];
      // the positions' displacements sum to 0 up to their rounding (u |q| each: 8 of them)
      BOOST_TEST(std::fabs(s) <= 1e-14 * (norm + largest_coordinate(p)), p.name);
    }
    ++checked;
  }
  BOOST_TEST(checked > 10);
}

// Central and one-sided differences on random pairs (the paper's protocol: vertices uniform in
// [0, 10]^3).
BOOST_AUTO_TEST_CASE(finite_differences_on_random_pairs) {
  pdd::compare::ReproducibleRng rng(5);
  int rejected = 0, tried = 0;
  for (const TetPair& p : random_pairs(8, 23, true)) {
    rejected += check_pair(p, rng, 4);
    tried += 4;
  }
  // The check has teeth: the gradient without the sum_k d_k term fails it along some direction.
  BOOST_TEST_MESSAGE(rejected << " of " << tried << " directions reject the wrong gradient");
  BOOST_TEST(rejected > 0);
}

// Shallow contacts: B's apex through A's face z = 0 by depth t, the other vertices perturbed
// so that nothing is axis-aligned.
BOOST_AUTO_TEST_CASE(finite_differences_on_shallow_contacts) {
  pdd::compare::ReproducibleRng rng(8);
  for (double t : {1e-1, 1e-2, 1e-3, 1e-4}) {
    TetPair p = tet_pair({{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
                         {{{2, 2, t}, {1, 1, -5}, {4, 1, -5}, {1, 4, -5}}}, "shallow");
    for (int i = 1; i < 4; ++i)
      for (int k = 0; k < 3; ++k) p.B[i][k] += rng.uniform(-0.5, 0.5);
    check_pair(p, rng, 4);
  }
}

// Two planes tie: A is mirror-symmetric in x (a ridge along y at the top), B's apex pokes into
// the ridge from above and B is mirror-symmetric in x too. Derivation: along n = (sin a, 0,
// cos a), |a| <= 45 degrees, A's top is the ridge (height 0) and B's apex is at -0.3 cos a, so
// the rigid overlap 0.3 cos a is least at a = +-45 degrees (the two faces of the ridge); the
// mirror maps every separated configuration to one, so f's minimisers come in mirror pairs,
// and the engine returns one of them.
BOOST_AUTO_TEST_CASE(tie_between_two_planes_gives_a_branch_gradient) {
  const TetPair p = tet_pair({{{0, -2, 0}, {0, 2, 0}, {-2, 0, -2}, {2, 0, -2}}},
                             {{{0, 0.25, -0.3}, {-1, -0.5, 2}, {1, -0.5, 2}, {0, 1.5, 2}}}, "ridge");
  const PairResult<double> r = solve_pair(p, with_gradient());
  BOOST_REQUIRE(!r.error);
  BOOST_REQUIRE(!r.pdd2_global_error);
  BOOST_REQUIRE(r.pdd2_global_normal);
  // the minimiser is off the mirror plane x = 0 (else it would be unique by symmetry)
  BOOST_TEST(std::fabs((*r.pdd2_global_normal)[0]) > 0.1);
  const Grad& g = *r.pdd2_global_grad;
  // The mirror image of the returned minimiser (x -> -x; the mirror keeps every vertex index:
  // s0, s1, r0, r3 are on the plane, s2 <-> s3 and r1 <-> r2 swap) is a minimiser too, with
  // the mirrored gradient.
  PairResult<double> m = r;
  auto mirror = [](Positions<double>& q, int i, int j) {
    std::swap(q[i], q[j]);
    for (auto& v : q) v[0] = -v[0];
  };
  mirror(m.q1_A_global, 2, 3);
  mirror(m.q1_B_global, 1, 2);
  Grad gm;
  {
    const Grad d = displacement(p, m);
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int i = 0; i < 4; ++i) s += d[4 * t + i][k];
        for (int i = 0; i < 4; ++i) gm[4 * t + i][k] = -(d[4 * t + i][k] + s) / 10;
      }
  }
  // V: the apex r0 moves along x (antisymmetric: <gm, V> = -<g, V>), sigma(V) = 1.
  Grad V{};
  V[4][0] = std::sqrt(10.0);  // sigma of one vertex moved by x: (x^2 + x^2) / 20 = x^2 / 10
  BOOST_TEST(sigma8(V) == 1.0, boost::test_tools::tolerance(1e-15));
  const double h = step_for(p, r.pdd2_global);
  Quotients q, qm;
  BOOST_TEST(bracket(p, r, g, V, h, q));
  BOOST_TEST(bracket(p, m, gm, V, h, qm));
  // equal up to the order of the sums over B's vertices (r1, r2 swapped): a few ulps
  BOOST_TEST(qm.a == -q.a, boost::test_tools::tolerance(1e-12));
  // the tie is broken by V: the branches' slopes differ by more than the bracket's slack, so
  // that the inequalities below show forward < backward (a kink, not a derivative)
  const double slack = h + std::max(q.slack_p, q.slack_m) / h;
  BOOST_TEST(std::fabs(q.a) > slack);
  // one-sided quotients: both at most -|a| + slack (the kink), and the returned <g, V> lies
  // between the forward quotient and the backward one
  const double forward = (q.fp - q.U) / h, backward = (q.U - q.fm) / h;
  BOOST_TEST(forward <= -std::fabs(q.a) + slack);
  BOOST_TEST(backward >= std::fabs(q.a) - slack);
  BOOST_TEST((forward - slack <= q.a && q.a <= backward + slack));
}
