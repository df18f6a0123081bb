// Exact invariants of every reported value (definitions §4–§6), on every property fixture:
// translating both tetrahedra changes nothing; scaling by 2 multiplies every squared value by
// exactly 4; permuting vertex order keeps every value. The reduced formulation is used for
// speed; test_formulations shows it equals the full one exactly.
#include <boost/test/unit_test.hpp>

#include <algorithm>

#include "fixtures.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;
using namespace pdd::reference;

namespace {
const SolveOptions kReduced{QpFormulation::Reduced};

std::array<Rational, 7> values(const ExactResult& r) {
  return {r.rigid_pd2, r.eq11_pd2, r.pdd2_static, r.pdd2, r.pdd2_relaxed, r.pdd2_accel1,
          r.pdd2_accel6};
}
std::array<std::optional<DirectionLabel>, 4> labels(const ExactResult& r) {
  return {r.rigid_dir, r.pdd2_static_dir, r.pdd2_dir, r.pdd2_relaxed_dir};
}
template <class F>
TetPair map_coordinates(TetPair p, F f) {
  for (auto* t : {&p.A, &p.B})
    for (auto& v : *t)
      for (int k = 0; k < 3; ++k) v[k] = f(v[k], k);
  return p;
}
// Whether x + t is exactly representable, so the translated pair is exactly the translate.
bool exact_sum(double x, double t) { return Rational(x + t) == Rational(x) + Rational(t); }
}  // namespace

BOOST_AUTO_TEST_CASE(translation_changes_nothing) {
  const std::array<double, 3> t = {4, -2, 0.5};
  int tested = 0;
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      bool exact = true;
      map_coordinates(pair, [&](double x, int k) { return exact = exact && exact_sum(x, t[k]), x; });
      if (!exact) continue;  // a rounded translate is a different pair; skip it
      const ExactResult a = solve_exact(pair, kReduced);
      const ExactResult b =
          solve_exact(map_coordinates(pair, [&](double x, int k) { return x + t[k]; }), kReduced);
      BOOST_TEST((values(a) == values(b)), pair.name);
      BOOST_TEST((labels(a) == labels(b)), pair.name);
      for (int i = 0; i < 4; ++i)
        BOOST_TEST(b.q1_B[i][2] == a.q1_B[i][2] + Rational(t[2]), pair.name);
      ++tested;
    }
  BOOST_TEST(tested >= 10);
}

BOOST_AUTO_TEST_CASE(scaling_by_two_multiplies_squares_by_four) {
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactResult a = solve_exact(pair, kReduced);
      const ExactResult b = solve_exact(map_coordinates(pair, [](double x, int) { return 2 * x; }),
                                       kReduced);
      auto va = values(a);
      for (auto& v : va) v = v * 4;
      BOOST_TEST((va == values(b)), pair.name);
      BOOST_TEST((labels(a) == labels(b)), pair.name);
      BOOST_TEST(b.q1_A[0][0] == 2 * a.q1_A[0][0], pair.name);
    }
}

BOOST_AUTO_TEST_CASE(permuting_vertices_keeps_every_value) {
  // Labels name vertices and edges, so they change with the permutation; values must not.
  const std::array<std::array<int, 4>, 3> perms = {{{1, 0, 2, 3}, {3, 2, 1, 0}, {2, 3, 0, 1}}};
  for (const auto& file : test::property_fixture_files())
    for (const TetPair& pair : test::load_pairs(file)) {
      const ExactResult a = solve_exact(pair, kReduced);
      for (std::size_t k = 0; k < perms.size(); ++k) {
        TetPair p = pair;
        for (int i = 0; i < 4; ++i) {
          p.A[i] = pair.A[perms[k][i]];
          p.B[i] = pair.B[perms[(k + 1) % perms.size()][i]];
        }
        BOOST_TEST((values(a) == values(solve_exact(p, kReduced))), pair.name << " perm " << k);
      }
    }
}
