#include "pdd/reference/validate_pair.h"

#include "pdd/reference/exact_kernel.h"
#include "pdd/rejection.h"

namespace pdd::reference {

std::optional<std::string> validate_tetrahedron(const TetVertices& tet, char which) {
  if (auto reason = non_finite_reason(tet, which)) return reason;
  const ExactTet t = to_exact(tet);
  if (CGAL::orientation(t[0], t[1], t[2], t[3]) == CGAL::COPLANAR) return flat_reason(which);
  return std::nullopt;
}

std::optional<std::string> validate_pair(const TetPair& pair) {
  return pair_rejection(validate_tetrahedron(pair.A, 'A'), validate_tetrahedron(pair.B, 'B'));
}

}  // namespace pdd::reference
