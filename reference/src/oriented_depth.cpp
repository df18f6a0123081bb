#include "pdd/reference/oriented_depth.h"

namespace pdd::reference {

Rational max_projection(const ExactTet& tet, const Vector& n) {
  Rational m = n * (tet[0] - CGAL::ORIGIN);
  for (int i = 1; i < 4; ++i) m = CGAL::max(m, n * (tet[i] - CGAL::ORIGIN));
  return m;
}

Rational min_projection(const ExactTet& tet, const Vector& n) {
  Rational m = n * (tet[0] - CGAL::ORIGIN);
  for (int i = 1; i < 4; ++i) m = CGAL::min(m, n * (tet[i] - CGAL::ORIGIN));
  return m;
}

Rational oriented_depth_numerator(const ExactPair& pair, const Vector& n) {
  return max_projection(pair.A, n) - min_projection(pair.B, n);
}

Rational oriented_depth_signed_square(const ExactPair& pair, const Vector& n) {
  const Rational d = oriented_depth_numerator(pair, n);
  return d * CGAL::abs(d) / n.squared_length();
}

}  // namespace pdd::reference
