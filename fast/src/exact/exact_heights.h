// exact_heights.h — internal to fast/src: exact signs of heights along a face normal,
// n.(p − q) with n = (p1 − p0) × (q1 − q0), by floating-point expansions (expansion.h): the
// degree-3 determinants of exact_sat.h's separating axes and of the superset kernel's exact
// direction ties (superset_depth.cpp). No rationals, no tolerance.
//
// Input:  doubles whose non-zero coordinates lie in in_exact_range (expansion.h; the callers
//         check it): every product and sum below is then exact.
// Output: exact_height_sign: the exact sign of n.(p − q), ok = false when an expansion exceeded
//         its capacity (the sign may then not be used).
// Method: a term n_k (p_k − q_k) vanishes when p_k == q_k (n_k is then not computed) or n_k = 0;
// n_k is the exact 2x2 minor of the differences (two products by Dekker's two_product when the
// differences are exact in doubles, the common case on aligned inputs; else expansion.h's cross
// of the exact differences); one term left: sign(n_k) sign(p_k − q_k) (the comparison is exact);
// otherwise the doubles' dot product where each of its steps is exact (short_dot_sign), else
// the expansions'.
#pragma once

#include "exact/expansion.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

// x·y − z·w exactly (expansion.h's two_by_two), a product with a zero factor skipped: aligned
// inputs have many zero coordinate differences, and then no Dekker split is needed.
inline void minor2(double x, double y, double z, double w, Expansion& e) {
  const bool first = x != 0.0 && y != 0.0, second = z != 0.0 && w != 0.0;
  e.n = 0;
  e.ok = true;
  if (first && second) {
    double h, l;
    two_product(x, y, h, l);
    if (l != 0.0) e.push(l);
    e.push(h);
    two_product(z, w, h, l);
    grow(e, -l);
    grow(e, -h);
    return;
  }
  if (!first && !second) return;
  double h, l;
  if (first) {
    two_product(x, y, h, l);
  } else {
    two_product(z, w, h, l);
    h = -h, l = -l;
  }
  if (l != 0.0) e.push(l);
  e.push(h);
}

// d = p − q when every coordinate difference is exact in doubles (its two_sum error is 0).
inline bool exact_difference(const Vec3d& p, const Vec3d& q, double* d) {
  bool exact = true;
  for (int k = 0; k < 3; ++k) {
    double y;
    two_sum(p[k], -q[k], d[k], y);
    exact = exact && y == 0.0;
  }
  return exact;
}

// The exact normal (p1 − p0) × (q1 − q0), each component computed when first asked for: 2x2
// minors of the differences when these are exact in doubles (the common case), else
// expansion.h's cross of the exact differences (all components at once). A height along a
// touching face's normal often needs one component or none (zero coordinate differences).
struct LazyNormal {
  double u[3], v[3];
  bool have[3] = {false, false, false};
  bool ok = true;        // false: an expansion exceeded its capacity
  bool exact_uv = true;  // u and v are the exact differences (the minors are then taken lazily)
  ExpVec n;
  LazyNormal(const Vec3d& p1, const Vec3d& p0, const Vec3d& q1, const Vec3d& q0) {
    if (exact_difference(p1, p0, u) && exact_difference(q1, q0, v)) return;
    exact_uv = false;
    n = cross(difference(p1, p0), difference(q1, q0));
    ok = n.ok();
    have[0] = have[1] = have[2] = true;
  }
  const Expansion& operator[](int k) {
    if (!have[k]) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      minor2(u[i], v[j], u[j], v[i], n.x[k]);
      have[k] = true;
    }
    return n.x[k];
  }
};

// The sign of n.(p − q) when the doubles compute it exactly: every component of n a single
// double (its expansion has at most one term), every difference p_k − q_k exact, every product
// n_k (p_k − q_k) exact (two_product's error 0) and every partial sum exact (two_sum's error 0):
// then the computed sum is the value. On aligned inputs most heights left to this point are
// exact zeros of this kind (a vertex in a plane through grid points: c (d_x − d_y) with
// d_x = d_y). False (s unchanged) when some step is not exact.
inline bool short_dot_sign(LazyNormal& n, const Vec3d& p, const Vec3d& q, int& s) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Expansion& e = n[k];
    if (e.n > 1) return false;
    double d, err;
    two_sum(p[k], -q[k], d, err);
    if (err != 0.0) return false;
    double prod, perr;
    two_product(e.n == 0 ? 0.0 : e.c[0], d, prod, perr);
    if (perr != 0.0) return false;
    double next;
    two_sum(sum, prod, next, err);
    if (err != 0.0) return false;
    sum = next;
  }
  s = sum > 0.0 ? 1 : (sum < 0.0 ? -1 : 0);
  return true;
}

// The exact sign of n.(p − q) (above): terms with p_k == q_k vanish without computing n_k;
// zero components vanish; one term left: sign(n_k)·sign(p_k − q_k); else short_dot_sign where
// the doubles are exact, else the expansions' dot.
// det[u, v, w] = 0 seen by comparisons: u, v, w (exact differences) all in one plane through 0
// of the forms x_k = 0 or x_i = ±x_j (a grid's axis and diagonal planes: the exact zeros of
// aligned inputs, which the terms below would otherwise take through the expansions).
inline bool in_axis_or_diagonal_plane(const double* u, const double* v, const double* w) {
  for (int k = 0; k < 3; ++k)
    if (u[k] == 0.0 && v[k] == 0.0 && w[k] == 0.0) return true;
  for (int i = 0; i < 2; ++i)
    for (int j = i + 1; j < 3; ++j)
      if ((u[i] == u[j] && v[i] == v[j] && w[i] == w[j]) || (u[i] == -u[j] && v[i] == -v[j] && w[i] == -w[j]))
        return true;
  return false;
}

inline int exact_height_sign(LazyNormal& n, const Vec3d& p, const Vec3d& q, bool& ok) {
  // n = u x v, so n.(p - q) = det[u, v, p - q]: 0 when the three lie in a plane through 0
  if (double w[3]; n.exact_uv && exact_difference(p, q, w) && in_axis_or_diagonal_plane(n.u, n.v, w)) return 0;
  int terms = 0, last = 0;
  for (int k = 0; k < 3; ++k)
    if (p[k] != q[k] && n[k].n != 0) ++terms, last = k;
  if (terms == 0) return 0;
  if (terms == 1) return n[last].sign() * (p[last] > q[last] ? 1 : -1);
  int s = 0;
  if (short_dot_sign(n, p, q, s)) return s;
  for (int k = 0; k < 3; ++k) n[k];
  const Expansion d = dot(n.n, difference(p, q));
  ok = ok && d.ok;
  return d.sign();
}

}  // namespace pdd::fast::detail
