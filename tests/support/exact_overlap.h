// exact_overlap.h — independent exact judges for tests, on GMP integers, sharing no code with
// the engines: do two tetrahedra's interiors intersect (definitions §4: touching is not
// intersecting), and the sign of a tetrahedron's volume.
//
// Exact integers: every coordinate times 2^-s (s the smallest exponent of a unit in the last
// place among the non-zero coordinates involved) is an integer, and every sign below is
// invariant under that common positive scaling.
//
// The intersection judge: for non-flat tetrahedra A and B the interiors are disjoint iff the
// origin is not interior to M = A ⊕ (−B), iff some facet normal u of M has
// max_i u.s_i <= min_j u.r_j (u or −u). Every facet normal of M is parallel to a face normal of
// A or of B or to eA × eB for non-parallel edges (a facet is the sum of faces of A and −B of
// total dimension 2). So: disjoint iff one of those 44 exact axes (zero ones skipped) weakly
// separates the vertex sets. Flat or non-finite tetrahedra: no interior, never intersecting.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <initializer_list>

#include "pdd/tet_pair.h"

namespace pdd::test {

using Q = mpz_class;
using QV = std::array<Q, 3>;

inline QV sub(const QV& a, const QV& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline QV cross(const QV& a, const QV& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Q dot(const QV& a, const QV& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline bool is_zero(const QV& a) { return sgn(a[0]) == 0 && sgn(a[1]) == 0 && sgn(a[2]) == 0; }

inline bool finite(const TetVertices& T) {
  for (const auto& v : T)
    for (double x : v)
      if (!std::isfinite(x)) return false;
  return true;
}

// The tetrahedra as integers (header); precondition: finite coordinates.
inline std::array<std::array<QV, 4>, 2> to_integers(std::initializer_list<const TetVertices*> tets) {
  int s = 0;
  bool any = false;
  for (const auto* T : tets)
    for (const auto& v : *T)
      for (double x : v)
        if (x != 0.0) {
          int e;
          std::frexp(x, &e);  // x = f 2^e, |f| in [0.5, 1): x = (f 2^53) 2^(e - 53)
          if (!any || e - 53 < s) s = e - 53;
          any = true;
        }
  auto conv = [&](double x) {
    if (x == 0.0) return Q(0);
    int e;
    const double f = std::frexp(x, &e);
    Q m(std::ldexp(f, 53));  // an integer below 2^53 in magnitude: exact
    return Q(m << (e - 53 - s));
  };
  std::array<std::array<QV, 4>, 2> out;
  int t = 0;
  for (const auto* T : tets) {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) out[t][i][k] = conv((*T)[i][k]);
    ++t;
  }
  return out;
}

// The exact sign of det[p1 - p0, p2 - p0, p3 - p0] (0: flat); precondition: finite.
inline int exact_orientation(const TetVertices& T) {
  const auto x = to_integers({&T})[0];
  return sgn(dot(cross(sub(x[1], x[0]), sub(x[2], x[0])), sub(x[3], x[0])));
}

// The judge (header).
inline bool exact_interiors_intersect(const TetVertices& A, const TetVertices& B) {
  if (!finite(A) || !finite(B)) return false;
  const auto ab = to_integers({&A, &B});
  const auto &a = ab[0], &b = ab[1];
  for (const auto* t : {&a, &b}) {
    const auto& x = *t;
    if (sgn(dot(cross(sub(x[1], x[0]), sub(x[2], x[0])), sub(x[3], x[0]))) == 0) return false;  // flat
  }
  auto separates = [&](const QV& u) {
    Q amax = dot(u, a[0]), amin = amax, bmax = dot(u, b[0]), bmin = bmax;
    for (int i = 1; i < 4; ++i) {
      const Q ha = dot(u, a[i]), hb = dot(u, b[i]);
      if (ha > amax) amax = ha;
      if (ha < amin) amin = ha;
      if (hb > bmax) bmax = hb;
      if (hb < bmin) bmin = hb;
    }
    return amax <= bmin || bmax <= amin;
  };
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  static const int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto* t : {&a, &b})
    for (const auto& f : kFaces) {
      const auto& x = *t;
      if (separates(cross(sub(x[f[1]], x[f[0]]), sub(x[f[2]], x[f[0]])))) return false;
    }
  for (const auto& ea : kEdges)
    for (const auto& eb : kEdges) {
      const QV u = cross(sub(a[ea[1]], a[ea[0]]), sub(b[eb[1]], b[eb[0]]));
      if (!is_zero(u) && separates(u)) return false;
    }
  return true;
}

}  // namespace pdd::test
