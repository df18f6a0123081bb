// fast_translation_test — pdd.h's "Translation": the engine computes a pair on its copy moved
// so that A's first vertex is the origin, when that move is exact, and moves positions back.
//
//  - anchored_pair moves the pair exactly when every one of the 24 differences x − s0 is exact
//    and the non-zero ones span at most 2^20, judged in GMP rationals, on random coordinates of
//    every kind (dyadic, decimal, mixed signs, extreme exponents, ±0, infinities and NaN);
//  - solve_pair(p) is move_positions(solve_pair(m), s0) bit for bit (the record's JSON line,
//    every value asked, definitions §9 included), and rigid_pd2, pdd2_static, pdd2, pdd2_relaxed,
//    pdd2_accel, pdd2_global and global_minimiser give p and m the same bits, on the shipped
//    aligned and degenerate families and on element pairs of a grid;
//  - a pair moved by an exact translation gets the same values, labels and normals, and the
//    rest poses come back bit for bit.
#define BOOST_TEST_MODULE fast_translation
#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/global_minimiser.h"
#include "pdd/io/fixture_io.h"
#include "pdd/io/record_line.h"
#include "pdd/pdd.h"

using namespace pdd;

namespace {

const std::string kFixtures = PDD_FAST_FIXTURES_DIR;

std::vector<TetPair> read_pairs(const std::string& file) {
  const io::FixtureFile f = io::read_fixture_file(kFixtures + "/" + file);
  if (f.error) throw std::runtime_error(file + ": " + *f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) out.push_back(e.pair);
  return out;
}

// The element pairs of a 2x2x2 Kuhn grid of cell h against its copy moved by t (every pair of
// elements, intersecting or not).
std::vector<TetPair> grid_pairs(double h, const std::array<double, 3>& t) {
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<TetVertices> tets;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (const auto& p : kPerm) {
          TetVertices T;
          int c[3] = {i, j, k};
          for (int v = 0; v < 4; ++v) {
            if (v > 0) ++c[p[v - 1]];
            T[v] = {c[0] * h, c[1] * h, c[2] * h};
          }
          tets.push_back(T);
        }
  std::vector<TetPair> out;
  for (const TetVertices& a : tets)
    for (TetVertices b : tets) {
      for (auto& x : b)
        for (int k = 0; k < 3; ++k) x[k] += t[k];
      out.push_back(TetPair{"", {}, a, b});
    }
  return out;
}

std::vector<TetPair> test_pairs() {
  std::vector<TetPair> all;
  for (const char* f : {"families/aligned.json", "families/parallel-edges.json", "families/colinear-edges.json",
                        "families/coplanar-faces.json", "families/near-touching.json", "families/touching.json",
                        "families/scaled-large.json", "families/sliver.json", "adversarial.json"})
    for (const TetPair& p : read_pairs(f)) all.push_back(p);
  // h = 1/8 (dyadic) half a cell along (1, 1, 1), and a third of a cell off the grid
  for (const TetPair& p : grid_pairs(0.125, {0.0625, 0.0625, 0.0625})) all.push_back(p);
  for (const TetPair& p : grid_pairs(0.125, {0.046875, 0.0, 0.125})) all.push_back(p);
  return all;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TetPair as_pair(const fast::AnchoredPair& m, const std::string& name) { return TetPair{name, {}, m.A, m.B}; }

// The exactness rule, in rationals.
bool exact_rule(const TetVertices& A, const TetVertices& B) {
  const auto& o = A[0];
  if (o[0] == 0 && o[1] == 0 && o[2] == 0 && !std::signbit(o[0]) && !std::signbit(o[1]) && !std::signbit(o[2]))
    return false;
  mpq_class hi = 0, lo = -1;  // the largest |x − s0| and the least non-zero one (-1: none yet)
  for (const TetVertices* T : {&A, &B})
    for (const auto& x : *T)
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(x[k]) || !std::isfinite(o[k])) return false;
        const double d = x[k] - o[k];
        if (!std::isfinite(d)) return false;
        const mpq_class e = mpq_class(x[k]) - mpq_class(o[k]);
        if (mpq_class(d) != e) return false;
        const mpq_class a = abs(e);
        if (a > hi) hi = a;
        if (a != 0 && (lo < 0 || a < lo)) lo = a;
      }
  return lo < 0 || lo >= hi / (1 << 20);
}

}  // namespace

BOOST_AUTO_TEST_CASE(anchored_pair_is_exact_exactly_when_every_difference_is) {
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> unit(-1, 1);
  auto draw = [&](int kind) -> double {
    switch (kind) {
      case 0: return std::ldexp(double(std::int64_t(rng() % 2001) - 1000), -6);  // dyadic grid
      case 1: return 0.1 * double(rng() % 40);                                  // decimal grid
      case 2: return 0.5 + 0.01 * unit(rng);                                    // near each other
      case 3: return unit(rng);                                                 // mixed signs
      case 4: return std::ldexp(unit(rng), int(rng() % 2000) - 1000);           // any exponent
      case 5: {                                                                 // random bits
        std::uint64_t b = rng();
        double x;
        std::memcpy(&x, &b, sizeof x);
        return x;
      }
      default: {
        const double special[] = {0.0, -0.0, std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::max(),
                                  -std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()};
        return special[rng() % 7];
      }
    }
  };
  int exact = 0, inexact = 0;
  for (int n = 0; n < 200000; ++n) {
    const int kind = int(rng() % 7);
    TetVertices A, B;
    for (TetVertices* T : {&A, &B})
      for (auto& x : *T)
        for (double& c : x) c = draw(kind == 6 && rng() % 4 ? int(rng() % 3) : kind);
    const std::optional<fast::AnchoredPair> m = fast::anchored_pair(A, B);
    const bool rule = exact_rule(A, B);
    BOOST_REQUIRE_EQUAL(m.has_value(), rule);
    (rule ? exact : inexact) += 1;
    if (!m) continue;
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) {
        BOOST_REQUIRE(mpq_class(m->A[v][k]) == mpq_class(A[v][k]) - mpq_class(A[0][k]));
        BOOST_REQUIRE(mpq_class(m->B[v][k]) == mpq_class(B[v][k]) - mpq_class(A[0][k]));
      }
    BOOST_REQUIRE(same_bits(m->origin[0], A[0][0]) && same_bits(m->origin[1], A[0][1]) &&
                  same_bits(m->origin[2], A[0][2]));
  }
  // both answers are exercised (the dyadic and near kinds are mostly exact)
  BOOST_TEST(exact > 20000);
  BOOST_TEST(inexact > 20000);
}

BOOST_AUTO_TEST_CASE(solve_pair_is_the_anchored_record_moved) {
  fast::SolveOptions all;
  all.with_global = true;
  int anchored = 0;
  for (const TetPair& p : test_pairs()) {
    const std::optional<fast::AnchoredPair> m = fast::anchored_pair(p.A, p.B);
    if (!m) continue;
    ++anchored;
    PairResult<double> moved = fast::solve_pair(as_pair(*m, p.name), all);
    BOOST_REQUIRE(fast::move_positions(moved, *m, p.A, p.B));
    const PairResult<double> direct = fast::solve_pair(p, all);
    BOOST_REQUIRE_EQUAL(io::record_line(direct), io::record_line(moved));
    BOOST_REQUIRE_EQUAL(direct.stats.slow_path, moved.stats.slow_path);
    // the hot functions compute the same pair
    auto same = [](const fast::Depth& a, const fast::Depth& b) {
      return same_bits(a.pd2, b.pd2) && a.dir == b.dir && a.status == b.status;
    };
    BOOST_REQUIRE(same(fast::rigid_pd2(p.A, p.B), fast::rigid_pd2(m->A, m->B)));
    BOOST_REQUIRE(same(fast::pdd2_static(p.A, p.B), fast::pdd2_static(m->A, m->B)));
    BOOST_REQUIRE(same(fast::pdd2(p.A, p.B), fast::pdd2(m->A, m->B)));
    BOOST_REQUIRE(same(fast::pdd2_relaxed(p.A, p.B), fast::pdd2_relaxed(m->A, m->B)));
    BOOST_REQUIRE(same(fast::pdd2_accel(p.A, p.B, 1), fast::pdd2_accel(m->A, m->B, 1)));
    const fast::NormalDepth g = fast::pdd2_global(p.A, p.B), gm = fast::pdd2_global(m->A, m->B);
    BOOST_REQUIRE(same_bits(g.pd2, gm.pd2) && g.normal == gm.normal && g.status == gm.status);
    const auto gp = fast::global_minimiser(p.A, p.B);
    if (gp) {
      BOOST_REQUIRE(same_bits(gp->pd2, direct.pdd2_global));
      BOOST_REQUIRE(gp->q1_A == direct.q1_A_global && gp->q1_B == direct.q1_B_global);
    }
    // rest poses come back bit for bit
    if (!direct.intersecting) BOOST_REQUIRE(direct.q1_A == p.A && direct.q1_B == p.B);
  }
  BOOST_TEST(anchored > 500);
}

// The same pair moved by exact translations: the same values, labels and normals; positions
// moved by the translation (up to one rounding each).
BOOST_AUTO_TEST_CASE(translated_pairs_get_the_same_bits) {
  fast::SolveOptions all;
  all.with_global = true;
  const std::array<double, 3> shifts[] = {{1, 2, 3}, {-5.5, 0.25, 1024}, {0.125, -0.375, 7}};
  int compared = 0;
  for (const TetPair& p : test_pairs()) {
    const std::optional<fast::AnchoredPair> m = fast::anchored_pair(p.A, p.B);
    if (!m) continue;
    const PairResult<double> r = fast::solve_pair(p, all);
    for (const auto& t : shifts) {
      TetPair q = p;
      for (TetVertices* T : {&q.A, &q.B})
        for (auto& x : *T)
          for (int k = 0; k < 3; ++k) x[k] += t[k];
      const std::optional<fast::AnchoredPair> mq = fast::anchored_pair(q.A, q.B);
      if (!mq || mq->A != m->A || mq->B != m->B) continue;  // the move was not exact for q
      ++compared;
      const PairResult<double> s = fast::solve_pair(q, all);
      BOOST_REQUIRE_EQUAL(r.intersecting, s.intersecting);
      for (std::size_t k = 0; k < kValueCount; ++k) BOOST_REQUIRE(same_bits(record_value(r, k), record_value(s, k)));
      BOOST_REQUIRE(same_bits(r.pdd2_global, s.pdd2_global));
      BOOST_REQUIRE(r.pdd2_global_normal == s.pdd2_global_normal);
      BOOST_REQUIRE(r.rigid_dir == s.rigid_dir && r.pdd2_dir == s.pdd2_dir && r.pdd2_static_dir == s.pdd2_static_dir &&
                    r.pdd2_relaxed_dir == s.pdd2_relaxed_dir);
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) {
          const double u = std::ldexp(1.0, -52);
          const double scale = std::fabs(s.q1_B[v][k]) + std::fabs(r.q1_B[v][k]) + std::fabs(t[k]);
          BOOST_REQUIRE(std::fabs((s.q1_B[v][k] - t[k]) - r.q1_B[v][k]) <= 2 * u * scale);
        }
    }
  }
  BOOST_TEST(compared > 1000);
}
