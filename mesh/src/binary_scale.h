// binary_scale.h — the power of two that brings a magnitude into [1/2, 1).
//
// The mesh layer scales coordinates, edges and pulls by 2^-e before it squares or multiplies
// them: a power of two commutes with every rounding while no value leaves the normal range, so
// the scaled sums are the same bits as on the values as given wherever those are normal
// doubles, and stay in range where they are not (a squared edge of a mesh of size L leaves the
// double range beyond L ~ 1e+-154, a volume ~L^3 or a squared cross product ~L^4 sooner).
#pragma once

#include <cmath>

namespace pdd::mesh::detail {

// Inputs: largest, a magnitude (the largest |entry| of what is to be scaled).
// Output: e with largest * 2^-e in [1/2, 1) (std::frexp's exponent); 0 where largest is 0, NaN or
// infinite (nothing to scale, or nothing a scale would bring into range).
inline int binary_exponent(double largest) {
  return largest > 0 && std::isfinite(largest) ? std::ilogb(largest) + 1 : 0;
}

}  // namespace pdd::mesh::detail
