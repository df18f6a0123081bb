// rejection.h — why definitions §1 rejects a pair, worded once for both engines (plain data).
//
// A tetrahedron is rejected when a coordinate is not finite, or when its volume is exactly 0
// ("flat"). Each engine decides flatness with its own exact arithmetic (reference: CGAL's
// orientation on rationals; fast: filtered orient3d with a GMP fallback) and words the verdict
// with these functions, so that both engines reject the same pairs with the same words:
//   "tetrahedron A: vertex 2 coordinate y is not finite (inf)"
//   "tetrahedron B is flat: its four vertices are coplanar (volume 0)"
// Both tetrahedra invalid: both reasons, A first, joined by "; ".
// A result outside the normal double range (fast engine only, definitions §8): kNotRepresentable.
#pragma once

#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "pdd/tet_pair.h"

namespace pdd {

enum class Rejection { NonFinite, Flat };

// `which`: 'A' or 'B'. nullopt when all 12 coordinates are finite.
inline std::optional<std::string> non_finite_reason(const TetVertices& tet, char which) {
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(tet[i][k])) {
        std::ostringstream msg;
        msg << "tetrahedron " << which << ": vertex " << i << " coordinate " << "xyz"[k]
            << " is not finite (" << tet[i][k] << ")";
        return msg.str();
      }
  return std::nullopt;
}

inline std::string flat_reason(char which) {
  return std::string("tetrahedron ") + which +
         " is flat: its four vertices are coplanar (volume 0)";
}

// The record's error from the reasons of A and of B (nullopt: the pair is valid).
inline std::optional<std::string> pair_rejection(const std::optional<std::string>& a,
                                                 const std::optional<std::string>& b) {
  if (a && b) return *a + "; " + *b;
  return a ? a : b;
}

inline constexpr const char* kNotRepresentable =
    "not representable: a result is outside the normal double range (the fast engine's "
    "accuracy contract, docs/definitions.md §8)";
// The fast engine's pdd2_global_error (the record's other values stay): no normal in doubles
// was certified to attain pdd2_global (its value may well be an ordinary double: what doubles
// cannot resolve is the direction of its minimiser), or pdd2_global or its positions are
// outside the normal double range.
inline constexpr const char* kGlobalNotRepresentable =
    "pdd2_global declined: no normal in doubles was certified to attain it within the fast "
    "engine's accuracy contract (the depth is below the resolution of the pair's extent: its "
    "minimiser's direction is finer than doubles resolve; the exact engine gives it)";
inline constexpr const char* kGlobalOutOfRange =
    "pdd2_global not representable: its value or deformed positions are outside the normal "
    "double range";

}  // namespace pdd
