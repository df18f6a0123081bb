// expansion.h — exact arithmetic on doubles by floating-point expansions (Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates", 1997): the exact
// signs of the low-degree polynomials of exact_predicates.h without rationals.
//
// Input:  doubles (the pair's coordinates), combined by +, −, ×.
// Output: an Expansion: doubles e_0..e_{m−1}, non-zero, nonoverlapping and increasing in
//         magnitude, whose exact sum is the exact value; sign() is the sign of the largest
//         component, hence of the value (a nonoverlapping expansion's smaller components sum to
//         less than its largest in magnitude); approx() the components added in increasing
//         order (relative error <= 2u once the expansion is compressed by that sum).
//
// Exactness. two_sum and two_product (Knuth, Dekker; round-to-nearest, no FMA contraction:
// fast/CMakeLists.txt builds with -ffp-contract=off) return the rounded result and its exact
// error as long as nothing overflows and no product loses bits below 2^-1074. Every routine
// below is built from them (Shewchuk's grow_expansion_zeroelim, scale_expansion_zeroelim).
// in_exact_range() states when that holds for the polynomials of exact_predicates.cpp (degree
// <= 4 in coordinate differences): every non-zero |coordinate| in [2^-200, 2^200]. Then every
// coordinate is a multiple of g = 2^-252 (its last bit), so is every difference, and every
// term of a product of k <= 4 differences is a multiple of g^4 = 2^-1008; each two_sum and
// Dekker split of such multiples yields multiples of the same (an error term of a sum of
// multiples of g' is a multiple of g'; the split halves of a are multiples of a's last bit),
// and every multiple of 2^-1008 below 2^1000 with at most 53 significant bits is a double
// (normal or subnormal): nothing is lost to underflow. Magnitudes stay below
// (2^201)^4 · 2^10 · 2^27 (the splitter's factor) < 2^1000: no overflow.
// Outside that range the callers use GMP rationals (exact_geometry.h).
#pragma once

#include <cmath>
#include <boost/container/small_vector.hpp>

#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

inline bool in_exact_range(const TetVertices& A, const TetVertices& B) {
  for (const TetVertices* T : {&A, &B})
    for (const Vec3d& p : *T)
      for (double x : p) {
        const double a = std::fabs(x);
        if (a != 0.0 && !(a >= 0x1p-200 && a <= 0x1p200)) return false;
      }
  return true;
}

struct Expansion {
  // increasing magnitude, no zeros; empty = 0. Inline storage: no allocation for the short
  // expansions of aligned inputs (most terms cancel or vanish there).
  boost::container::small_vector<double, 16> c;

  int sign() const { return c.empty() ? 0 : (c.back() > 0 ? 1 : -1); }
  double approx() const {
    double s = 0.0;
    for (double x : c) s += x;
    return s;
  }
};

// a + b = x + y exactly, x = fl(a + b) (Knuth).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}
// |a| >= |b| or a = 0: a + b = x + y exactly (Dekker).
inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  y = b - (x - a);
}
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}
// a · b = x + y exactly (Dekker).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  y = al * bl - (((x - ah * bh) - al * bh) - ah * bl);
}

// The exact difference a − b of two doubles.
inline Expansion difference(double a, double b) {
  Expansion e;
  double x, y;
  two_sum(a, -b, x, y);
  if (y != 0.0) e.c.push_back(y);
  if (x != 0.0) e.c.push_back(x);
  return e;
}

// e + b (Shewchuk's grow_expansion_zeroelim), in place: component i is read before slot
// m <= i is written.
inline void grow(Expansion& e, double b) {
  double q = b, x, y;
  std::size_t m = 0;
  for (std::size_t i = 0; i < e.c.size(); ++i) {
    two_sum(q, e.c[i], x, y);
    q = x;
    if (y != 0.0) e.c[m++] = y;
  }
  e.c.resize(m);
  if (q != 0.0) e.c.push_back(q);
}

inline Expansion sum(Expansion e, const Expansion& f) {
  for (double c : f.c) grow(e, c);
  return e;
}
inline Expansion negated(Expansion e) {
  for (double& c : e.c) c = -c;
  return e;
}
inline Expansion difference(const Expansion& e, const Expansion& f) { return sum(e, negated(f)); }

// e · b (Shewchuk's scale_expansion_zeroelim).
inline Expansion scaled(const Expansion& e, double b) {
  Expansion h;
  if (e.c.empty() || b == 0.0) return h;
  h.c.reserve(2 * e.c.size());
  double q, hh;
  two_product(e.c[0], b, q, hh);
  if (hh != 0.0) h.c.push_back(hh);
  for (std::size_t i = 1; i < e.c.size(); ++i) {
    double p1, p0, s;
    two_product(e.c[i], b, p1, p0);
    two_sum(q, p0, s, hh);
    if (hh != 0.0) h.c.push_back(hh);
    fast_two_sum(p1, s, q, hh);
    if (hh != 0.0) h.c.push_back(hh);
  }
  if (q != 0.0) h.c.push_back(q);
  return h;
}

inline Expansion product(const Expansion& e, const Expansion& f) {
  Expansion r;
  for (double c : f.c) r = sum(r, scaled(e, c));
  return r;
}

// Exact 3-vectors.
struct ExpVec {
  Expansion x[3];
  bool is_zero() const { return x[0].c.empty() && x[1].c.empty() && x[2].c.empty(); }
};
inline ExpVec difference(const Vec3d& p, const Vec3d& q) {
  ExpVec v;
  for (int k = 0; k < 3; ++k) v.x[k] = difference(p[k], q[k]);
  return v;
}
inline ExpVec cross(const ExpVec& a, const ExpVec& b) {
  ExpVec n;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    n.x[k] = difference(product(a.x[i], b.x[j]), product(a.x[j], b.x[i]));
  }
  return n;
}
inline Expansion dot(const ExpVec& a, const ExpVec& b) {
  return sum(sum(product(a.x[0], b.x[0]), product(a.x[1], b.x[1])), product(a.x[2], b.x[2]));
}
inline ExpVec scaled(const ExpVec& a, const Expansion& s) {
  ExpVec r;
  for (int k = 0; k < 3; ++k) r.x[k] = product(a.x[k], s);
  return r;
}
inline ExpVec difference(const ExpVec& a, const ExpVec& b) {
  ExpVec r;
  for (int k = 0; k < 3; ++k) r.x[k] = difference(a.x[k], b.x[k]);
  return r;
}
inline ExpVec negated(ExpVec a) {
  for (auto& e : a.x) e = negated(e);
  return a;
}

}  // namespace pdd::fast::detail
