// expansion.h — exact arithmetic on doubles by floating-point expansions (Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates", 1997): the exact
// signs of the low-degree polynomials of exact_predicates.h without rationals.
//
// Input:  doubles (the pair's coordinates), combined by +, −, ×.
// Output: an Expansion: doubles e_0..e_{m−1}, non-zero, nonoverlapping and increasing in
//         magnitude, whose exact sum is the exact value; sign() is the sign of the largest
//         component, hence of the value (a nonoverlapping expansion's smaller components sum to
//         less than its largest in magnitude); approx() the components added in increasing
//         order (relative error <= 2u once the expansion is compressed by that sum); ok = false
//         when a result would exceed the fixed capacity (then nothing about it may be used).
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

// Fixed capacity, on the stack (no allocation): an operation whose result would not fit sets
// ok = false (propagated), and the callers then take GMP rationals (exact_predicates.cpp).
// Aligned inputs give short expansions (most terms are exact zeros and vanish).
inline constexpr int kExpansionCapacity = 48;
struct Expansion {
  double c[kExpansionCapacity];  // increasing magnitude, no zeros; n = 0: the value 0
  int n = 0;
  bool ok = true;

  Expansion() = default;
  Expansion(const Expansion& o) : n(o.n), ok(o.ok) {
    for (int i = 0; i < n; ++i) c[i] = o.c[i];
  }
  Expansion& operator=(const Expansion& o) {
    n = o.n;
    ok = o.ok;
    for (int i = 0; i < n; ++i) c[i] = o.c[i];
    return *this;
  }
  void push(double x) {
    if (n == kExpansionCapacity) {
      ok = false;
      return;
    }
    c[n++] = x;
  }
  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
  double approx() const {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += c[i];
    return s;
  }
};

// a + b = x + y exactly (Knuth).
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
  if (y != 0.0) e.push(y);
  if (x != 0.0) e.push(x);
  return e;
}

// e + b (Shewchuk's grow_expansion_zeroelim), in place: component i is read before slot
// m <= i is written.
inline void grow(Expansion& e, double b) {
  double q = b, x, y;
  int m = 0;
  for (int i = 0; i < e.n; ++i) {
    two_sum(q, e.c[i], x, y);
    q = x;
    if (y != 0.0) e.c[m++] = y;
  }
  e.n = m;
  if (q != 0.0) e.push(q);
}

inline Expansion sum(Expansion e, const Expansion& f) {
  e.ok = e.ok && f.ok;
  for (int i = 0; i < f.n; ++i) grow(e, f.c[i]);
  return e;
}
inline Expansion negated(Expansion e) {
  for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
  return e;
}
inline Expansion difference(const Expansion& e, const Expansion& f) { return sum(e, negated(f)); }

// e · b (Shewchuk's scale_expansion_zeroelim).
inline Expansion scaled(const Expansion& e, double b) {
  Expansion h;
  h.ok = e.ok;
  if (e.n == 0 || b == 0.0) return h;
  double q, hh;
  two_product(e.c[0], b, q, hh);
  if (hh != 0.0) h.push(hh);
  for (int i = 1; i < e.n; ++i) {
    double p1, p0, s;
    two_product(e.c[i], b, p1, p0);
    two_sum(q, p0, s, hh);
    if (hh != 0.0) h.push(hh);
    fast_two_sum(p1, s, q, hh);
    if (hh != 0.0) h.push(hh);
  }
  if (q != 0.0) h.push(q);
  return h;
}

// e · f = sum over i of e · f_i, each partial product grown into the result in place (sum()).
inline Expansion product(const Expansion& e, const Expansion& f) {
  Expansion r;
  r.ok = e.ok && f.ok;
  for (int i = 0; i < f.n; ++i) {
    const Expansion s = scaled(e, f.c[i]);
    r.ok = r.ok && s.ok;
    for (int j = 0; j < s.n; ++j) grow(r, s.c[j]);
  }
  return r;
}

// e, the same exact value in fewer components (Shewchuk's compress): a downward pass of
// fast_two_sum from the largest component gathers what each component adds, an upward pass
// renormalises; the result is nonoverlapping and increasing, its largest component within one
// ulp of the value, zero components dropped (the value 0 gives n = 0). Only sums: exact in the
// range stated above. Used before products, whose cost grows with the product of the lengths.
inline Expansion compressed(const Expansion& e) {
  Expansion h;
  h.ok = e.ok;
  if (e.n == 0) return h;
  double g[kExpansionCapacity];
  int bottom = e.n - 1;
  double Q = e.c[bottom];
  for (int i = e.n - 2; i >= 0; --i) {
    double Qn, q;
    fast_two_sum(Q, e.c[i], Qn, q);
    if (q != 0.0) {
      g[bottom--] = Qn;
      Q = q;
    } else {
      Q = Qn;
    }
  }
  for (int i = bottom + 1; i < e.n; ++i) {
    double Qn, q;
    fast_two_sum(g[i], Q, Qn, q);
    if (q != 0.0) h.c[h.n++] = q;
    Q = Qn;
  }
  if (Q != 0.0) h.c[h.n++] = Q;
  return h;
}

// Exact 3-vectors.
struct ExpVec {
  Expansion x[3];
  bool is_zero() const { return x[0].n == 0 && x[1].n == 0 && x[2].n == 0; }
  bool ok() const { return x[0].ok && x[1].ok && x[2].ok; }
};
inline ExpVec difference(const Vec3d& p, const Vec3d& q) {
  ExpVec v;
  for (int k = 0; k < 3; ++k) v.x[k] = difference(p[k], q[k]);
  return v;
}
// x·y − z·w for doubles: two exact products, their exact difference (at most 4 terms).
inline Expansion two_by_two(double x, double y, double z, double w) {
  Expansion e;
  double h, l;
  two_product(x, y, h, l);
  if (l != 0.0) e.push(l);
  if (h != 0.0) e.push(h);
  two_product(z, w, h, l);
  grow(e, -l);
  grow(e, -h);
  return e;
}
inline double value_of_short(const Expansion& e) { return e.n == 0 ? 0.0 : e.c[0]; }  // n <= 1

inline ExpVec cross(const ExpVec& a, const ExpVec& b) {
  ExpVec n;
  bool exact_inputs = true;  // every component a single double (differences exact in doubles)
  for (int k = 0; k < 3; ++k) exact_inputs = exact_inputs && a.x[k].n <= 1 && b.x[k].n <= 1;
  if (exact_inputs) {  // the common case on aligned inputs: 2x2 determinants of doubles
    double av[3], bv[3];
    for (int k = 0; k < 3; ++k) av[k] = value_of_short(a.x[k]), bv[k] = value_of_short(b.x[k]);
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      n.x[k] = two_by_two(av[i], bv[j], av[j], bv[i]);
    }
    return n;
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    n.x[k] = difference(product(a.x[i], b.x[j]), product(a.x[j], b.x[i]));
  }
  return n;
}
// (product()'s partial products of the three components grown into one result: the same
// exact value without the intermediate expansions)
inline Expansion dot(const ExpVec& a, const ExpVec& b) {
  Expansion r;
  r.ok = true;
  for (int k = 0; k < 3; ++k) {
    const Expansion &e = a.x[k], &f = b.x[k];
    r.ok = r.ok && e.ok && f.ok;
    for (int i = 0; i < f.n; ++i) {
      const Expansion s = scaled(e, f.c[i]);
      r.ok = r.ok && s.ok;
      for (int j = 0; j < s.n; ++j) grow(r, s.c[j]);
    }
  }
  return r;
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

// An expansion's value in doubles and a bound of its error, computed: the components summed in
// increasing order (recursive summation: |error| <= gamma_(n-1) sum |c_i|, gamma_k = k u/(1 − k u),
// u = 2^-53), with sum |c_i| itself computed; 2 (n + 1) u covers gamma_(n−1) and the relative
// error gamma_n of the computed sum |c_i| for n <= kExpansionCapacity. On a compressed expansion
// (a few components, the largest within an ulp of the value) the bound is a few u of the value.
struct Approx {
  double v = 0.0, err = 0.0;
};
inline Approx approx_of(const Expansion& e) {
  constexpr double u = 0x1p-53;
  Approx a;
  double m = 0.0;
  for (int i = 0; i < e.n; ++i) a.v += e.c[i], m += std::fabs(e.c[i]);
  a.err = 2.0 * (e.n + 1) * u * m;
  return a;
}

}  // namespace pdd::fast::detail
