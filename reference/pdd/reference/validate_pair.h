// validate_pair.h — input validation of definitions §1, decided exactly.
//
// A tetrahedron is valid when its 12 coordinates are finite and its volume is non-zero
// (either orientation); the volume sign is CGAL's exact orientation predicate on the
// rationals the doubles denote, so "flat" means exactly flat, never "nearly flat".
#pragma once

#include <optional>
#include <string>

#include "pdd/tet_pair.h"

namespace pdd::reference {

// nullopt when valid; otherwise the reason (pdd/rejection.h), naming the tetrahedron ('A' or 'B').
std::optional<std::string> validate_tetrahedron(const TetVertices& tet, char which);

// nullopt when both tetrahedra are valid; otherwise every reason, joined by "; ".
std::optional<std::string> validate_pair(const TetPair& pair);

}  // namespace pdd::reference
