#include "pdd/reference/validate_pair.h"

#include <cmath>
#include <sstream>

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

std::optional<std::string> validate_tetrahedron(const TetVertices& tet, const std::string& which) {
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(tet[i][k])) {
        std::ostringstream msg;
        msg << "tetrahedron " << which << ": vertex " << i << " coordinate " << "xyz"[k]
            << " is not finite (" << tet[i][k] << ")";
        return msg.str();
      }
  const ExactTet t = to_exact(tet);
  if (CGAL::orientation(t[0], t[1], t[2], t[3]) == CGAL::COPLANAR)
    return "tetrahedron " + which + " is flat: its four vertices are coplanar (volume 0)";
  return std::nullopt;
}

std::optional<std::string> validate_pair(const TetPair& pair) {
  const auto a = validate_tetrahedron(pair.A, "A");
  const auto b = validate_tetrahedron(pair.B, "B");
  if (a && b) return *a + "; " + *b;
  if (a) return a;
  return b;
}

}  // namespace pdd::reference
