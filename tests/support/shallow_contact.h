// shallow_contact.h — a shallow contact in general position, for tests: a random tetrahedron A
// in [-1, 1]^3 and B touching A's face 1 2 3 from outside, `depth` (relative 0.7 to 1.3) through
// it: B's vertex 0 (tip) or a small face 0 1 2 around the face's centroid (face), the other
// vertices 0.2 to 1.2 above the face. `uniform` draws from [-1, 1); the draws' order is part of
// the pairs (tests pin what they see).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "pdd/pdd.h"

namespace pdd::test {

template <class Uniform>
TetPair shallow_contact_pair(double depth, bool face, Uniform&& uniform, std::string name) {
  using V = std::array<double, 3>;
  auto sub = [](const V& a, const V& b) { return V{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot = [](const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  TetPair p;
  p.name = std::move(name);
  for (auto& v : p.A)
    for (double& x : v) x = uniform();
  const V e = sub(p.A[2], p.A[1]), f = sub(p.A[3], p.A[1]);
  V n{e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
  const double len = std::sqrt(dot(n, n));
  if (dot(n, sub(p.A[0], p.A[1])) > 0) n = {-n[0], -n[1], -n[2]};
  for (double& x : n) x /= len;  // unit, outward from face 1 2 3
  V c{};
  for (int i = 1; i < 4; ++i)
    for (int k = 0; k < 3; ++k) c[k] += p.A[i][k] / 3;
  // tip: B's vertex 0 inside A, the others above the face; face: B's face 0 1 2 a small
  // triangle around the centroid, each vertex 0.7 to 1.3 times `depth` inside A
  const int inside = face ? 3 : 1;
  for (int j = 0; j < 4; ++j) {
    const double r0 = uniform(), r1 = uniform(), r2 = uniform();
    const V r{r0, r1, r2};
    const double h = dot(r, n), s = j < inside ? 0.1 : 1.0;
    const double height = j < inside ? -depth * (1 + 0.3 * uniform()) : 0.2 + std::abs(uniform());
    for (int k = 0; k < 3; ++k) p.B[j][k] = c[k] + (j < inside && inside == 1 ? 0.0 : s * (r[k] - h * n[k])) + height * n[k];
  }
  return p;
}

}  // namespace pdd::test
