// vec3.h — internal to fast/src/global: the double 3-vectors of the global depth's normals.
//
// Input : triples a, b (a normal, a vertex, a sign condition's vector), a scalar s.
// Output: dot(a, b) = sum_k a_k b_k, sub / add (componentwise), mul(a, s) = s a,
//         norm(a) = sqrt(a.a), cross(a, b), nonzero(a) (some component is not 0); each rounded
//         as written (the library compiles with -ffp-contract=off: the same bits in every file).
// kU: the unit roundoff 2^-53 in which every error bound of fast/src/global is written.
#pragma once

#include <array>
#include <cmath>

namespace pdd::fast::global {

using V3 = std::array<double, 3>;

inline constexpr double kU = 0x1p-53;  // unit roundoff

inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 mul(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline bool nonzero(const V3& v) { return v[0] != 0 || v[1] != 0 || v[2] != 0; }

}  // namespace pdd::fast::global
