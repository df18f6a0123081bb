#include "pdd/reference/object_norm.h"

namespace pdd::reference {

// Paper eq. 3 in the closed form of definitions §2.
Rational object_norm(const ExactTet& rest, const ExactTet& deformed) {
  Vector sum = CGAL::NULL_VECTOR;
  Rational squares = 0;
  for (int i = 0; i < 4; ++i) {
    const Vector d = deformed[i] - rest[i];
    sum = sum + d;
    squares += d.squared_length();
  }
  return (squares + sum.squared_length()) / 20;
}

}  // namespace pdd::reference
