// exact_path.cpp — the fast engine's exact slow path (see exact_path.h). Written by hand on
// GMP's mpq_class rather than on reference/'s CGAL kernel on purpose: the point of the slow path
// is to be this engine's own algorithms (the closed forms of direction_qp_impl.h, the SPEC §3
// rules as this engine reads them), so that reference/ still checks them independently.
#include "exact_path.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "deformable_depth.h"
#include "direction_qp_impl.h"
#include "exact_geometry.h"

namespace pdd::fast::detail {
namespace {


// One oriented candidate (SPEC §3): heights are n.(x − s_0), exact.
struct Cand {
  DirectionLabel label;
  QV n;
  Q nn, D, hA[4], hB[4];
  unsigned conA = 0, conB = 0;
};

struct Builder {
  QTet s, r;  // s_i − s_0, r_j − s_0
  std::vector<Cand> out;

  void emit(const DirectionLabel& l, const QV& n, unsigned conA, unsigned conB) {
    Cand c;
    c.label = l;
    c.n = n;
    c.nn = dot(n, n);
    for (int i = 0; i < 4; ++i) {
      c.hA[i] = dot(n, s[i]);
      c.hB[i] = dot(n, r[i]);
    }
    Q hi = c.hA[0], lo = c.hB[0];
    for (int i = 1; i < 4; ++i) {
      if (hi < c.hA[i]) hi = c.hA[i];
      if (c.hB[i] < lo) lo = c.hB[i];
    }
    c.D = hi - lo;
    c.conA = conA;
    c.conB = conB;
    out.push_back(std::move(c));
  }

  void faces() {
    for (int i = 0; i < 4; ++i) emit(DirectionLabel::fv(i), face_normal_out_of(s, i), mask_without(i), 0);
    for (int j = 0; j < 4; ++j) emit(DirectionLabel::vf(j), face_normal_into(r, j), 0, mask_without(j));
  }

  void edge_pairs() {
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        EdgePairKind kind;
        const QV n = edge_pair_normal(s, r, a, b, &kind);
        if (kind == EdgePairKind::Colinear) continue;  // no direction (SPEC §3)
        const unsigned ca = edge_mask(a), cb = edge_mask(b);
        switch (side_rule(s, n, a)) {
          case EdgePairSide::Keep: emit(DirectionLabel::ee(a, b), n, ca, cb); break;
          case EdgePairSide::Flip: emit(DirectionLabel::ee(a, b), negated(n), ca, cb); break;
          case EdgePairSide::Undecidable:
            emit(DirectionLabel::ee(a, b, EdgeOrientation::Plus), n, ca, cb);
            emit(DirectionLabel::ee(a, b, EdgeOrientation::Minus), negated(n), ca, cb);
            break;
        }
      }
  }
};

// Rounds a value (a squared length, held to 1e-9 relative) to double; `ok` is cleared when a
// non-zero value is not a normal double.
double rounded(const Q& q, bool& ok) {
  const double d = q.get_d();
  if (sgn(q) != 0 && !(std::fabs(d) >= DBL_MIN && std::fabs(d) <= DBL_MAX)) ok = false;
  return d;
}
// Rounds a coordinate of q1 to double; `ok` is cleared only when it overflows. A subnormal
// coordinate is a fine position (its absolute error, <= 2^-1075, is far below the 1e-9 R of
// SPEC §8); inputs with subnormal coordinates have such positions (the fuzzer found it).
double rounded_coordinate(const Q& q, bool& ok) {
  const double d = q.get_d();
  if (!(std::fabs(d) <= DBL_MAX)) ok = false;
  return d;
}

}  // namespace

ExactPathResult solve_pair_exact_path(const TetVertices& A, const TetVertices& B) {
  ExactPathResult er;
  PairResult<double>& r = er.result;
  r.q1_A = A;
  r.q1_B = B;
  // Coordinates relative to s_0, times 2^shift: integers (every double is an integer times a
  // power of two), so that the candidates' normals and heights are integer arithmetic (no gcd
  // work on power-of-two denominators). Values (squared lengths) are divided back by
  // 2^(2 shift), displacements by 2^shift — exactly.
  int lowest = 0;
  bool nonzero = false;
  for (const TetVertices* T : {&A, &B})
    for (const auto& p : *T)
      for (double x : p) {
        if (x == 0.0) continue;
        int e;
        std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1) with 53 bits: an integer times 2^(e − 53)
        lowest = nonzero ? std::min(lowest, e - 53) : e - 53;
        nonzero = true;
      }
  const long shift = nonzero ? -long(lowest) : 0;  // may be negative (huge coordinates): still exact
  auto scaled_coordinate = [&](double x) {
    Q q(x);
    if (shift > 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), shift);
    if (shift < 0) mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), -shift);
    return q;
  };
  auto unscale = [&](Q q, long times) {  // q / 2^(times · shift)
    const long k = times * shift;
    if (k > 0) mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), k);
    if (k < 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), -k);
    return q;
  };
  Builder bld;
  QV s0;
  for (int k = 0; k < 3; ++k) s0.x[k] = scaled_coordinate(A[0][k]);
  for (int i = 0; i < 4; ++i) {
    QV a, b;
    for (int k = 0; k < 3; ++k) {
      a.x[k] = scaled_coordinate(A[i][k]);
      b.x[k] = scaled_coordinate(B[i][k]);
    }
    bld.s[i] = a - s0;
    bld.r[i] = b - s0;
  }
  bld.faces();
  bld.edge_pairs();
  const std::vector<Cand>& C = bld.out;
  const int n = int(C.size());
  for (const Cand& c : C)
    if (sgn(c.D) <= 0) return er;  // a separating candidate: not intersecting (SPEC §4)
  r.intersecting = true;
  bool& ok = er.representable;

  // delta² and eq. 11 of every candidate (cheap); the QPs only where they can matter: scanning
  // in ascending exact delta², a candidate whose exact pruning bound coeff·delta² (deformable_
  // depth.h: every exact QP value is >= that) exceeds the best exact value so far can be neither
  // the minimum nor tie with it, and neither can any later one. Same results as evaluating every
  // candidate (ties: the first in canonical order), a fraction of the rational arithmetic.
  std::vector<Q> delta2(n);
  Q e11;
  bool e11_zero = false, e11_set = false;
  for (int k = 0; k < n; ++k) {
    const Cand& c = C[k];
    delta2[k] = c.D * c.D / c.nn;
    // eq. 11: overlap of the projections, L_n(A) + L_n(B) − L_n(A ∪ B)
    Q loA = c.hA[0], hiA = c.hA[0], loB = c.hB[0], hiB = c.hB[0];
    for (int i = 1; i < 4; ++i) {
      if (c.hA[i] < loA) loA = c.hA[i];
      if (hiA < c.hA[i]) hiA = c.hA[i];
      if (c.hB[i] < loB) loB = c.hB[i];
      if (hiB < c.hB[i]) hiB = c.hB[i];
    }
    const Q overlap = (hiA - loA) + (hiB - loB) - ((hiA < hiB ? hiB : hiA) - (loA < loB ? loA : loB));
    if (sgn(overlap) <= 0) e11_zero = true;
    const Q v = overlap * overlap / c.nn;
    if (!e11_set || v < e11) e11 = v;
    e11_set = true;
  }
  // Ascending exact delta², ties in canonical order (stable): also case 3's order.
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return delta2[a] < delta2[b]; });

  // Each QP variant evaluated once per candidate, on demand.
  std::vector<Solution<Q>> def_sol(n);
  std::vector<Q> st(n), def(n), rel(n);
  std::vector<char> have_st(n, 0), have_def(n, 0), have_rel(n, 0);
  auto sides = [&](int k) {
    return std::make_pair(side_of(C[k].hA, C[k].conA), side_of(C[k].hB, C[k].conB));
  };
  auto def_of = [&](int k) -> const Q& {
    if (!have_def[k]) {
      const auto sd = sides(k);
      def_sol[k] = solve_deformable_sorted(sd.first, sd.second);
      def[k] = def_sol[k].cost / (20 * C[k].nn);
      have_def[k] = 1;
    }
    return def[k];
  };
  auto st_of = [&](int k) -> const Q& {
    if (!have_st[k]) {
      const auto sd = sides(k);
      st[k] = solve_static_sides(sd.first, sd.second).cost / (20 * C[k].nn);
      have_st[k] = 1;
    }
    return st[k];
  };
  auto rel_of = [&](int k) -> const Q& {
    if (!have_rel[k]) {
      rel[k] = solve_relaxed_heights(C[k].hA, C[k].hB).cost / (20 * C[k].nn);
      have_rel[k] = 1;
    }
    return rel[k];
  };
  auto decided = [&](int k) { return C[k].label.orientation == EdgeOrientation::Decided; };
  // The first minimum (canonical order among exact ties) of value_of over usable candidates.
  auto qp_min = [&](const Q& coeff, auto&& value_of, auto&& usable) {
    int best = -1;
    for (int k : order) {
      if (!usable(k)) continue;
      if (best >= 0 && coeff * delta2[k] > value_of(best)) break;
      if (best < 0 || value_of(k) < value_of(best) || (value_of(k) == value_of(best) && k < best))
        best = k;
    }
    return best;
  };
  auto any = [](int) { return true; };
  const Q case2_coeff(kDeformableBoundCoeff), case1_coeff(kStaticBoundCoeff);  // dyadic: exact

  const int ir = order[0];
  r.rigid_pd2 = rounded(unscale(delta2[ir], 2), ok);
  r.rigid_dir = C[ir].label;
  r.eq11_pd2 = e11_zero ? 0.0 : rounded(unscale(e11, 2), ok);
  const int is = qp_min(case1_coeff, st_of, decided);
  r.pdd2_static = rounded(unscale(st[is], 2), ok);
  r.pdd2_static_dir = C[is].label;
  const int id = qp_min(case2_coeff, def_of, any);
  r.pdd2 = rounded(unscale(def[id], 2), ok);
  r.pdd2_dir = C[id].label;
  const int il = qp_min(case2_coeff, rel_of, any);
  r.pdd2_relaxed = rounded(unscale(rel[il], 2), ok);
  r.pdd2_relaxed_dir = C[il].label;

  // case 3: the first 1 and 6 candidates in ascending delta order
  Q accel = def_of(order[0]);
  r.pdd2_accel1 = rounded(unscale(accel, 2), ok);
  for (int m = 1; m < kAccelWide && m < n; ++m)
    if (def_of(order[m]) < accel) accel = def[order[m]];
  r.pdd2_accel6 = rounded(unscale(accel, 2), ok);

  // q1: x + (T / n.n) n along the pdd2 direction (direction_qp.h)
  const Cand& c = C[id];
  const Solution<Q>& sol = def_sol[id];
  for (int i = 0; i < 4; ++i) {
    const Q tA = displacement_below(c.hA[i], (c.conA >> i & 1u) != 0, sol) / c.nn;
    const Q tB = displacement_above(c.hB[i], (c.conB >> i & 1u) != 0, sol) / c.nn;
    for (int k = 0; k < 3; ++k) {
      r.q1_A[i][k] = rounded_coordinate(Q(A[i][k]) + unscale(tA * c.n.x[k], 1), ok);
      r.q1_B[i][k] = rounded_coordinate(Q(B[i][k]) + unscale(tB * c.n.x[k], 1), ok);
    }
  }
  return er;
}

}  // namespace pdd::fast::detail
