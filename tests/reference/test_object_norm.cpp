// Object norm (paper eq. 3, definitions §2) against hand derivations.
#include <boost/test/unit_test.hpp>

#include "pdd/reference/object_norm.h"

using namespace pdd::reference;

namespace {
ExactTet tet(std::initializer_list<std::array<double, 3>> v) {
  ExactTet t;
  int i = 0;
  for (const auto& p : v) t[i++] = Point(Rational(p[0]), Rational(p[1]), Rational(p[2]));
  return t;
}
ExactTet translated(const ExactTet& t, const Vector& d) {
  ExactTet out = t;
  for (auto& p : out) p = p + d;
  return out;
}
// Paper eq. 3 literally: 1/10 sum_{i >= j} d_i . d_j.
Rational eq3_literal(const ExactTet& q0, const ExactTet& q1) {
  Rational s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j <= i; ++j) s += (q1[i] - q0[i]) * (q1[j] - q0[j]);
  return s / 10;
}
}  // namespace

BOOST_AUTO_TEST_CASE(pure_translation_gives_squared_length) {
  // d_i = t for every i: (4|t|^2 + |4t|^2) / 20 = 20|t|^2 / 20 = |t|^2 (paper eq. 5).
  const ExactTet q0 = tet({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const Vector t(Rational(3), Rational(-4), Rational(12));  // |t|^2 = 169
  BOOST_TEST(object_norm(q0, translated(q0, t)) == Rational(169));
  BOOST_TEST(object_norm(q0, q0) == Rational(0));
}

BOOST_AUTO_TEST_CASE(one_vertex_moved) {
  // Only d_3 = (0, 0, h): (h^2 + h^2) / 20 = h^2 / 10. With h = 1/2: 1/40.
  const ExactTet q0 = tet({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  ExactTet q1 = q0;
  q1[3] = q1[3] + Vector(0, 0, Rational(1, 2));
  BOOST_TEST(object_norm(q0, q1) == Rational(1, 40));
}

BOOST_AUTO_TEST_CASE(closed_form_equals_eq3_sum) {
  // definitions §2's two forms agree: sum_{i>=j} d_i.d_j = (sum |d_i|^2 + |sum d_i|^2) / 2.
  const ExactTet q0 = tet({{0.5, 1, -2}, {3, 0.25, 1}, {-1, 2, 0}, {0, 0, 7}});
  const ExactTet q1 = tet({{1.5, -1, 2}, {3, 4.25, 1}, {0.125, 2, -3}, {9, 0, 7}});
  BOOST_TEST(object_norm(q0, q1) == eq3_literal(q0, q1));
}
