// exact_path.cpp — the fast engine's exact slow path (see exact_path.h). Written by hand on
// GMP's mpq_class rather than on reference/'s CGAL kernel on purpose: the point of the slow path
// is to be this engine's own algorithms (the closed forms of direction_qp_impl.h, the
// definitions §3 rules as this engine reads them), so that reference/ still checks them
// independently.
#include "exact/exact_path.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "exact/exact_candidate.h"
#include "qp/deformable_depth.h"
#include "qp/direction_qp_impl.h"

namespace pdd::fast::detail {
namespace {

// Every candidate of definitions §3 in canonical order (exact_candidate.h).
struct Builder {
  const ExactFrame& f;
  std::vector<ExactCandidate> out;

  void emit(const DirectionLabel& l, const QV& n, unsigned conA, unsigned conB) {
    out.push_back(exact_candidate(f, l, n, conA, conB));
  }

  void faces() {
    for (int i = 0; i < 4; ++i) emit(DirectionLabel::fv(i), face_normal_out_of(f.s, i), mask_without(i), 0);
    for (int j = 0; j < 4; ++j) emit(DirectionLabel::vf(j), face_normal_into(f.r, j), 0, mask_without(j));
  }

  void edge_pairs() {
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        EdgePairKind kind;
        const QV n = edge_pair_normal(f.s, f.r, a, b, &kind);
        if (kind == EdgePairKind::Colinear) continue;  // no direction (definitions §3)
        const unsigned ca = edge_mask(a), cb = edge_mask(b);
        switch (side_rule(f.s, n, a)) {
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

}  // namespace

ExactPathResult solve_pair_exact_path(const TetVertices& A, const TetVertices& B) {
  ExactPathResult er;
  PairResult<double>& r = er.result;
  r.q1_A = A;
  r.q1_B = B;
  // Coordinates relative to s_0, times 2^shift: integers (exact_candidate.h).
  const ExactFrame frame = exact_frame(A, B);
  Builder bld{frame, {}};
  bld.faces();
  bld.edge_pairs();
  const std::vector<ExactCandidate>& C = bld.out;
  const int n = int(C.size());
  for (const ExactCandidate& c : C)
    if (sgn(c.D) <= 0) return er;  // a separating candidate: not intersecting (definitions §4)
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
    delta2[k] = exact_delta2(C[k]);
    const Q overlap = exact_overlap(C[k]);  // eq. 11
    if (sgn(overlap) <= 0) e11_zero = true;
    const Q v = overlap * overlap / C[k].nn;
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
  auto def_of = [&](int k) -> const Q& {
    if (!have_def[k]) {
      def[k] = exact_deformable_value(C[k], &def_sol[k]);
      have_def[k] = 1;
    }
    return def[k];
  };
  auto st_of = [&](int k) -> const Q& {
    if (!have_st[k]) {
      st[k] = exact_static_value(C[k]);
      have_st[k] = 1;
    }
    return st[k];
  };
  auto rel_of = [&](int k) -> const Q& {
    if (!have_rel[k]) {
      rel[k] = exact_relaxed_value(C[k]);
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
  r.rigid_pd2 = rounded_value(unscaled(frame, delta2[ir], 2), ok);
  r.rigid_dir = C[ir].label;
  r.eq11_pd2 = e11_zero ? 0.0 : rounded_value(unscaled(frame, e11, 2), ok);
  const int is = qp_min(case1_coeff, st_of, decided);
  r.pdd2_static = rounded_value(unscaled(frame, st[is], 2), ok);
  r.pdd2_static_dir = C[is].label;
  const int id = qp_min(case2_coeff, def_of, any);
  r.pdd2 = rounded_value(unscaled(frame, def[id], 2), ok);
  r.pdd2_dir = C[id].label;
  const int il = qp_min(case2_coeff, rel_of, any);
  r.pdd2_relaxed = rounded_value(unscaled(frame, rel[il], 2), ok);
  r.pdd2_relaxed_dir = C[il].label;
  er.relaxed_normal = rounded_normal(C[il].n);

  // case 3: the first 1 and 6 candidates in ascending delta order
  Q accel = def_of(order[0]);
  r.pdd2_accel1 = rounded_value(unscaled(frame, accel, 2), ok);
  for (int m = 1; m < kAccelWide && m < n; ++m)
    if (def_of(order[m]) < accel) accel = def[order[m]];
  r.pdd2_accel6 = rounded_value(unscaled(frame, accel, 2), ok);

  // q1: x + (T / n.n) n along the pdd2 direction (direction_qp.h)
  exact_positions(A, B, frame, C[id], def_sol[id], r.q1_A, r.q1_B, ok);
  return er;
}

}  // namespace pdd::fast::detail
