// Floating-point expansions (fast/src/exact/expansion.h) against GMP rationals
// (exact_geometry.h) on the inputs they are there for: aligned pairs whose edges are parallel
// exactly or up to rounding, whose faces are coplanar or parallel. Every exact predicate of
// exact_predicates.h (which takes expansions in their range) must give the rational answer, and
// compensated_displacements.h's double words must bound the rational displacements.
#define BOOST_TEST_MODULE fast_expansion
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <optional>
#include <tuple>
#include <string>
#include <vector>

#include "exact/exact_geometry.h"
#include "exact/exact_heights.h"
#include "exact/exact_candidate.h"
#include "exact/exact_predicates.h"
#include "exact/expansion.h"
#include "exact/integer_depth.h"
#include "certification/compensated_displacements.h"
#include "qp/direction_qp_impl.h"
#include "pdd/compare/random.h"
#include "structured_cells.h"

using namespace pdd;
using namespace pdd::fast;
using detail::Q;

namespace {

// A cell tetrahedron of a grid of side h at a random decimal origin (coordinates rounded): Kuhn
// path `perm`, or with one vertex nudged by a few ulps (nearly parallel edges, nearly coplanar
// faces).
TetVertices cell_tet(compare::ReproducibleRng& r, const Vec3d& origin, double h, int perm, bool nudge) {
  TetVertices t = pdd::test::kuhn_cell_tet(origin, h, perm);
  if (nudge) {
    double& x = t[r.integer(0, 3)][r.integer(0, 2)];
    x = std::nextafter(x, r.integer(0, 1) ? HUGE_VAL : -HUGE_VAL);
  }
  return t;
}

std::pair<TetVertices, TetVertices> aligned_pair(compare::ReproducibleRng& r) {
  const double h = r.uniform(0.5, 2.0);
  const Vec3d o = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
  // B's origin: a non-grid shift, or an exact grid multiple (coplanar faces, colinear edges)
  const bool on_grid = r.integer(0, 2) == 0;
  Vec3d ob;
  for (int k = 0; k < 3; ++k) ob[k] = o[k] + (on_grid ? r.integer(-1, 1) * h : r.uniform(-1, 1) * h);
  return {cell_tet(r, o, h, r.integer(0, 5), r.integer(0, 3) == 0),
          cell_tet(r, ob, h, r.integer(0, 5), r.integer(0, 3) == 0)};
}

int sign_of_q(const Q& q) { return sgn(q); }

// Every definitions §3 candidate label of the pair (edge pairs classified exactly: colinear
// ones left out, undecidable ones with both orientations).
std::vector<DirectionLabel> candidate_labels(const TetVertices& A, const TetVertices& B) {
  std::vector<DirectionLabel> labels;
  for (int f = 0; f < 4; ++f) labels.push_back({ContactKind::FV, f, 0, EdgeOrientation::Decided});
  for (int f = 0; f < 4; ++f) labels.push_back({ContactKind::VF, f, 0, EdgeOrientation::Decided});
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const EdgePairClass c = classify_edge_pair_exact(A, B, a, b);
      if (c.kind == EdgePairKind::Colinear) continue;
      if (c.side == EdgePairSide::Undecidable) {
        labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Plus});
        labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Minus});
      } else {
        labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Decided});
      }
    }
  return labels;
}

// The label's oriented normal in rationals (definitions §3).
detail::QV oriented_normal_q(const detail::QTet& qa, const detail::QTet& qb, const DirectionLabel& l) {
  if (l.kind == ContactKind::FV) return detail::face_normal_out_of(qa, l.a);
  if (l.kind == ContactKind::VF) return detail::face_normal_into(qb, l.a);
  EdgePairKind kind;
  detail::QV n = detail::edge_pair_normal(qa, qb, l.a, l.b, &kind);
  const EdgePairSide side = detail::side_rule(qa, n, l.a);
  if (side == EdgePairSide::Flip || (side == EdgePairSide::Undecidable && l.orientation == EdgeOrientation::Minus))
    n = detail::negated(n);
  return n;
}

// D = max_i n.s_i − min_j n.r_j along n, in rationals (definitions §4).
Q depth_q(const detail::QTet& qa, const detail::QTet& qb, const detail::QV& n) {
  Q hi = dot(n, qa[0]), lo = dot(n, qb[0]);
  for (int i = 1; i < 4; ++i) {
    const Q ha = dot(n, qa[i]), hb = dot(n, qb[i]);
    if (ha > hi) hi = ha;
    if (hb < lo) lo = hb;
  }
  return hi - lo;
}

}  // namespace

BOOST_AUTO_TEST_CASE(predicates_match_rationals_on_aligned_pairs) {
  compare::ReproducibleRng r(38);
  int parallel = 0, colinear = 0, zero_g = 0, zero_depth = 0, same_direction = 0;
  int delta_compared = 0, delta_ties = 0, delta_near = 0, parts_checked = 0, eq11_checked = 0, eq11_zero = 0;
  for (int it = 0; it < 3000; ++it) {
    const auto [A, B] = aligned_pair(r);
    BOOST_REQUIRE(detail::in_exact_range(A, B));
    const detail::QTet qa = detail::exact_tet(A), qb = detail::exact_tet(B);
    for (const auto* T : {&A, &B}) {
      const detail::QTet q = detail::exact_tet(*T);
      const Sign s = sign_of(sign_of_q(dot(cross(q[1] - q[0], q[2] - q[0]), q[3] - q[0])));
      BOOST_TEST((orientation_sign_exact(*T) == s));
    }
    if (orientation_sign_exact(A) == Sign::Zero || orientation_sign_exact(B) == Sign::Zero) continue;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        EdgePairKind kind;
        const detail::QV n = detail::edge_pair_normal(qa, qb, a, b, &kind);
        const EdgePairClass c = classify_edge_pair_exact(A, B, a, b);
        BOOST_TEST((c.kind == kind), "kind " << a << ":" << b);
        parallel += kind == EdgePairKind::Parallel;
        colinear += kind == EdgePairKind::Colinear;
        if (kind == EdgePairKind::Colinear) continue;
        BOOST_TEST((c.side == detail::side_rule(qa, n, a)), "side " << a << ":" << b);
        for (int i : kOffEdge[a]) zero_g += sgn(dot(n, qa[i] - qa[kEdges[a][0]])) == 0;
      }
    // depth signs of every candidate label, and same_direction_exact against rational cross
    // products of the oriented normals
    const std::vector<DirectionLabel> labels = candidate_labels(A, B);
    auto exact_normal = [&](const DirectionLabel& l) { return oriented_normal_q(qa, qb, l); };
    std::vector<Q> delta2;  // definitions §4: D²/(n.n), per label, in rationals
    Q e11 = -1;              // eq. 11: the least overlap²/(n.n), 0 when some overlap is <= 0
    for (const auto& l : labels) {
      const detail::QV n = exact_normal(l);
      Q hi = dot(n, qa[0]), lo = dot(n, qb[0]), loA = hi, hiB = lo;
      for (int i = 1; i < 4; ++i) {
        const Q ha = dot(n, qa[i]), hb = dot(n, qb[i]);
        if (ha > hi) hi = ha;
        if (hb < lo) lo = hb;
        if (ha < loA) loA = ha;
        if (hb > hiB) hiB = hb;
      }
      const Q overlap = (hi < hiB ? hi : hiB) - (loA > lo ? loA : lo);
      const Q e = overlap > 0 ? Q(overlap * overlap / dot(n, n)) : Q(0);
      if (e11 < 0 || e < e11) e11 = e;
      const int want = sgn(Q(hi - lo));
      zero_depth += want == 0;
      BOOST_TEST((depth_sign_exact(A, B, l) == sign_of(want)), l.str());
      delta2.push_back(Q(hi - lo) * Q(hi - lo) / dot(n, n));
    }
    // eq. 11 by expansions: the same zero, else the least value within a few u
    {
      bool zero = false;
      double v = 0, r = 1;
      if (eq11_by_expansions(A, B, labels.data(), int(labels.size()), zero, v, r)) {
        BOOST_TEST(zero == (e11 == 0));
        if (!zero) BOOST_TEST((abs(Q(v) - e11) <= Q(1, 1000000000000) * e11), "eq11 " << v);
        eq11_checked += 1;
        eq11_zero += zero;
      }
    }
    // the order of delta² by expansions (no division) against the rationals' order
    std::vector<ExactDepthParts> parts;
    for (const auto& l : labels) parts.push_back(depth_parts_exact(A, B, l));
    // each part exact: D²/(n.n) from the expansions is the rationals' delta² (the heights'
    // extremes taken among the vertices a double filter cannot rule out)
    auto value_of = [](const detail::Expansion& e) {
      Q v = 0;
      for (int c = 0; c < e.n; ++c) v += Q(e.c[c]);
      return v;
    };
    for (std::size_t i = 0; i < labels.size(); ++i) {
      if (!parts[i].ok || delta2[i] == 0) continue;
      const Q D = value_of(parts[i].D);
      BOOST_TEST((D * D / value_of(parts[i].nn) == delta2[i]), "parts " << labels[i].str());
      parts_checked += 1;
    }
    for (std::size_t i = 0; i < labels.size(); i += 3)
      for (std::size_t j = i + 1; j < labels.size(); j += 5) {
        if (!parts[i].ok || !parts[j].ok) continue;
        const std::optional<int> got = compare_delta2_exact(parts[i], parts[j]);
        if (!got) continue;
        const int want = delta2[i] < delta2[j] ? -1 : (delta2[j] < delta2[i] ? 1 : 0);
        BOOST_TEST(*got == want, labels[i].str() << " " << labels[j].str());
        delta_compared += 1;
        delta_ties += want == 0;
        // near ties (delta² within 1e-12 relative, not equal): beyond the double filter,
        // decided over integers
        const Q gap = delta2[i] - delta2[j];
        delta_near += want != 0 && abs(gap) <= Q(1, 1000000000000) * delta2[i];
      }
    for (std::size_t k = 1; k < labels.size(); k += 7) {
      const detail::QV n1 = exact_normal(labels[0]), n2 = exact_normal(labels[k]);
      const bool want = detail::is_zero(detail::cross(n1, n2)) && sgn(dot(n1, n2)) > 0;
      same_direction += want;
      const std::optional<bool> got = same_direction_exact(A, B, labels[0], labels[k]);
      if (got) BOOST_TEST(*got == want, labels[0].str() << " " << labels[k].str());
    }
  }
  // the degeneracies the draws are made for do occur
  BOOST_TEST(parallel > 1000);
  BOOST_TEST(colinear > 100);
  BOOST_TEST(zero_g > 1000);
  BOOST_TEST(zero_depth > 10);
  BOOST_TEST(same_direction > 100);
  BOOST_TEST(delta_compared > 10000);
  BOOST_TEST(delta_ties > 100);
  BOOST_TEST(delta_near > 100);
  BOOST_TEST(parts_checked > 10000);
  BOOST_TEST(eq11_checked > 1000);
  BOOST_TEST(eq11_zero > 10);
  BOOST_TEST(eq11_checked - eq11_zero > 100);
  BOOST_TEST_MESSAGE("eq. 11 by expansions " << eq11_checked << " (zero " << eq11_zero << ")");
  BOOST_TEST_MESSAGE("delta² compared by expansions " << delta_compared << ", parts checked " << parts_checked << ", exact ties " << delta_ties
                                                      << ", near ties " << delta_near);
  BOOST_TEST_MESSAGE("parallel " << parallel << ", colinear " << colinear << ", zero g " << zero_g
                                 << ", zero depths " << zero_depth << ", same directions " << same_direction);
}

// exact_heights.h: the sign of ((p1 − p0) × (q1 − q0)).(p − q) against rationals, on the heights
// the separating-axis decision and the superset's plane tests take: faces of one cell and edges
// of two against vertices of either, for cells of a grid against a copy shifted along (1, 1, 1)
// by a short binary fraction (exact zeros: a vertex in a diagonal plane), by a tenth of a cell
// (the same up to rounding) and by a random offset. short_dot_sign, where it answers, gives the
// same sign (its exact-in-doubles shortcut is taken on a share of the heights, and the test can
// fail either way: both signs and zeros occur in numbers). Every other cell pair is mirrored in
// y (exact), so that diagonal planes x = y become x = -y: in_axis_or_diagonal_plane's shortcut
// (zeros by comparisons) is checked to name only exact zeros, in both forms, and to take a share
// of them.
// integer_depth.h: on pairs with an integer frame (decimal grids and their copies shifted a
// quarter cell, a cell or half a cell; cells at random origins, some nudged by an ulp), every
// edge pair's framed kind and orientation rule are the rationals', every label's framed D and
// n.n equal the rationals' (times the frame's units), every framed comparison of delta² is the
// rationals' order, first_least_delta2_framed is the rationals' first least delta² (and refuses
// a list holding a colinear edge pair), framed_depth_sign is the sign of D, and framed_delta2's
// value holds the exact delta² within its root bound.
namespace {
Q limbs_value(const mp_limb_t* x, int k, int unit_exponent) {
  mpz_class z = 0;
  for (int i = k - 1; i >= 0; --i) z = (z << 64) + mpz_class(static_cast<unsigned long>(x[i]));
  Q v(z);
  if (unit_exponent >= 0) v *= Q(mpz_class(1) << unit_exponent);
  else v /= Q(mpz_class(1) << -unit_exponent);
  return v;
}
}  // namespace

// ExactDirection (exact_predicates.h) against rationals where its first test runs over the
// pair's integer frame: a tetrahedron against its own translate by a random offset (each edge
// of B parallel to its copy in A up to the roundings of the shift, exactly where they cancel),
// and aligned grid cells (aligned_pair). For every pair of labels l1, l2 (faces, and both
// labelled orientations of every edge pair that is not colinear): same_as_labelled(l2) is
// n1 x n2 = 0 and n1.n2 > 0, n1 l1's oriented candidate, n2 l2's normal as labelled (an edge
// pair's eB x eA or common perpendicular, negated for ':-'); same_as(l2) the same with l2
// oriented by the rule.
BOOST_AUTO_TEST_CASE(direction_tests_over_integers_match_rationals) {
  compare::ReproducibleRng r(41);
  int checked = 0, same = 0, framed = 0, translates = 0;
  for (int it = 0; it < 150; ++it) {
    TetVertices A, B;
    if (it % 3 != 0) {  // a translate: coordinates in [0, 1), a shift of up to a tenth of that
      const double t[3] = {r.uniform(-0.1, 0.1), r.uniform(-0.1, 0.1), r.uniform(-0.1, 0.1)};
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) A[i][k] = r.uniform(0.0625, 1), B[i][k] = A[i][k] + t[k];
      translates += 1;
    } else {
      std::tie(A, B) = aligned_pair(r);
    }
    if (orientation_sign_exact(A) == Sign::Zero || orientation_sign_exact(B) == Sign::Zero) continue;
    BOOST_REQUIRE(detail::in_exact_range(A, B));
    detail::IntegerFrame frame(A, B);
    framed += frame.usable();
    const detail::QTet qa = detail::exact_tet(A), qb = detail::exact_tet(B);
    std::vector<DirectionLabel> labels;
    for (int f = 0; f < 4; ++f) labels.push_back({ContactKind::FV, f, 0, EdgeOrientation::Decided});
    for (int f = 0; f < 4; ++f) labels.push_back({ContactKind::VF, f, 0, EdgeOrientation::Decided});
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        if (classify_edge_pair_exact(A, B, a, b).kind == EdgePairKind::Colinear) continue;
        labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Plus});
        labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Minus});
      }
    auto as_labelled = [&](const DirectionLabel& l) {
      if (l.kind != ContactKind::EE) return oriented_normal_q(qa, qb, l);
      EdgePairKind kind;
      const detail::QV n = detail::edge_pair_normal(qa, qb, l.a, l.b, &kind);
      return l.orientation == EdgeOrientation::Minus ? detail::negated(n) : n;
    };
    auto same_way = [](const detail::QV& n1, const detail::QV& n2) {
      return detail::is_zero(detail::cross(n1, n2)) && sgn(dot(n1, n2)) > 0;
    };
    for (const DirectionLabel& l1 : labels) {
      if (l1.kind == ContactKind::EE && l1.orientation == EdgeOrientation::Minus) continue;  // (l1 by the rule)
      const DirectionLabel first = l1.kind == ContactKind::EE ? DirectionLabel::ee(l1.a, l1.b, EdgeOrientation::Plus) : l1;
      const detail::QV n1 = oriented_normal_q(qa, qb, first);
      const ExactDirection d(A, B, first);
      for (const DirectionLabel& l2 : labels) {
        const bool want = same_way(n1, as_labelled(l2));
        const std::optional<bool> got = d.same_as_labelled(l2);
        BOOST_REQUIRE(got.has_value());
        BOOST_TEST(*got == want, first.str() << " " << l2.str() << " (labelled)");
        const std::optional<bool> rule = d.same_as(l2);
        BOOST_REQUIRE(rule.has_value());
        BOOST_TEST(*rule == same_way(n1, oriented_normal_q(qa, qb, l2)), first.str() << " " << l2.str());
        checked += 1;
        same += want;
      }
    }
  }
  // the integer frame is there on most pairs, and the answers include both verdicts
  BOOST_TEST(translates > 90);
  BOOST_TEST(framed > 120);
  BOOST_TEST(checked > 100000);
  BOOST_TEST(same > 1000);
  BOOST_TEST_MESSAGE("direction tests " << checked << " (same " << same << "), pairs with a frame " << framed);
}

BOOST_AUTO_TEST_CASE(framed_delta2_matches_rationals) {
  compare::ReproducibleRng r(20261201);
  long framed = 0, parallel = 0, colinear = 0, compared = 0, ties = 0, firsts = 0, refused = 0, values = 0,
       zero_depths = 0;
  const double cells[] = {0.1, 0.025, 0.3, 1.0 / 3};
  for (int it = 0; it < 3000; ++it) {
    TetVertices A, B;
    if (it % 2 == 0) {
      std::tie(A, B) = aligned_pair(r);
    } else {
      const double h = cells[r.integer(0, 3)];
      const int shift = r.integer(0, 3);  // a quarter cell along (1, 1, 1), one cell up, half a cell in x and y, none
      Vec3d oa, ob;
      for (int k = 0; k < 3; ++k) {
        oa[k] = r.integer(-8, 8) * h;
        const double s = shift == 0 ? 0.25 * h : shift == 1 ? (k == 2 ? h : 0.0) : shift == 2 ? (k < 2 ? 0.5 * h : 0.0) : 0.0;
        ob[k] = oa[k] + r.integer(-1, 1) * h + s;
      }
      A = pdd::test::kuhn_cell_tet(oa, h, r.integer(0, 5));
      B = pdd::test::kuhn_cell_tet(ob, h, r.integer(0, 5));
    }
    detail::IntegerFrame frame(A, B);
    if (!frame.usable() || orientation_sign_exact(A) == Sign::Zero || orientation_sign_exact(B) == Sign::Zero)
      continue;
    ++framed;
    const int e = frame.unit_exponent();
    const detail::QTet qa = detail::exact_tet(A), qb = detail::exact_tet(B);
    std::vector<DirectionLabel> colinear_labels;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        EdgePairKind kind;
        const detail::QV n = detail::edge_pair_normal(qa, qb, a, b, &kind);
        const EdgePairClass c = detail::classify_edge_pair_framed(frame, a, b);
        BOOST_TEST((c.kind == kind), "kind " << a << ":" << b);
        if (kind == EdgePairKind::Colinear) {
          colinear_labels.push_back({ContactKind::EE, a, b, EdgeOrientation::Decided});
          continue;
        }
        BOOST_TEST((c.side == detail::side_rule(qa, n, a)), "side " << a << ":" << b);
      }
    const std::vector<DirectionLabel> labels = candidate_labels(A, B);
    std::vector<detail::FramedDepth> fd(labels.size());
    std::vector<Q> delta2(labels.size());
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const detail::QV n = oriented_normal_q(qa, qb, labels[i]);
      const Q D = depth_q(qa, qb, n), nn = dot(n, n);
      delta2[i] = D * D / nn;
      BOOST_REQUIRE(detail::framed_depth(frame, labels[i], fd[i]));
      parallel += fd[i].parallel;
      const int degree = fd[i].parallel ? 1 : 0;  // units 2^((3 + degree) e) and 2^((4 + 2 degree) e)
      BOOST_TEST((limbs_value(fd[i].D, 4, (3 + degree) * e) == abs(D)), labels[i].str());
      BOOST_TEST((fd[i].D_sign == sgn(D)), labels[i].str());
      BOOST_TEST((detail::framed_depth_sign(frame, labels[i]) == sgn(D)), labels[i].str());
      zero_depths += D == 0;
      BOOST_TEST((limbs_value(fd[i].nn, 6, (4 + 2 * degree) * e) == nn), labels[i].str());
      double v = 0, rr = 1;
      if (detail::framed_delta2(frame, fd[i], v, rr)) {
        BOOST_TEST((Q(v) * Q(1 - rr) * Q(1 - rr) <= delta2[i] && delta2[i] <= Q(v) * Q(1 + rr) * Q(1 + rr)), labels[i].str());
        ++values;
      } else {
        BOOST_TEST((D == 0), labels[i].str());
      }
    }
    // asked again (integer_depth.cpp's per-pair memo), after another pair's depth in between
    // (the memo is the last pair's: that pair's answers, never this one's): the same limbs
    {
      detail::IntegerFrame other_frame(B, A);  // (B against A: another pair)
      detail::FramedDepth x;
      if (other_frame.usable()) detail::framed_depth(other_frame, labels[0], x);
      for (std::size_t i = 0; i < labels.size(); ++i) {
        BOOST_REQUIRE(detail::framed_depth(frame, labels[i], x));
        BOOST_TEST((std::memcmp(x.D, fd[i].D, sizeof x.D) == 0 && std::memcmp(x.nn, fd[i].nn, sizeof x.nn) == 0 &&
                    x.D_sign == fd[i].D_sign && x.parallel == fd[i].parallel),
                   "asked again: " << labels[i].str());
      }
    }
    for (std::size_t i = 0; i < labels.size(); ++i)
      for (std::size_t j = i + 1; j < labels.size(); ++j) {
        const int want = delta2[i] < delta2[j] ? -1 : (delta2[j] < delta2[i] ? 1 : 0);
        BOOST_TEST(detail::compare_framed_delta2(fd[i], fd[j]) == want, labels[i].str() << " " << labels[j].str());
        ++compared;
        ties += want == 0;
      }
    int want_first = 0;
    for (std::size_t i = 1; i < labels.size(); ++i)
      if (delta2[i] < delta2[want_first]) want_first = int(i);
    BOOST_TEST(detail::first_least_delta2_framed(frame, labels.data(), int(labels.size())) == want_first);
    ++firsts;
    // The same with no depth known yet (another pair asked in between): each contender's oriented
    // normal taken first, one along an earlier contender's direction passed over before its depth
    // is computed; and on a subset of the labels (two of every three) with every other one of them
    // asked beforehand, so that known and unknown depths alternate.
    {
      detail::IntegerFrame other_frame(B, A);
      detail::FramedDepth x;
      auto forget = [&] {
        if (other_frame.usable()) detail::framed_depth(other_frame, labels[0], x);
      };
      forget();
      BOOST_TEST(detail::first_least_delta2_framed(frame, labels.data(), int(labels.size())) == want_first,
                 "no depth known");
      std::vector<DirectionLabel> sub;
      std::vector<std::size_t> at;
      for (std::size_t i = 0; i < labels.size(); ++i)
        if ((i + std::size_t(it)) % 3 != 0) sub.push_back(labels[i]), at.push_back(i);
      forget();
      for (std::size_t j = 0; j < sub.size(); j += 2) detail::framed_depth(frame, sub[j], x);
      int want_sub = 0;
      for (std::size_t j = 1; j < sub.size(); ++j)
        if (delta2[at[j]] < delta2[at[want_sub]]) want_sub = int(j);
      BOOST_TEST(detail::first_least_delta2_framed(frame, sub.data(), int(sub.size())) == want_sub, "subset");
      ++firsts;
    }
    if (!colinear_labels.empty()) {
      std::vector<DirectionLabel> with = labels;
      with.insert(with.begin() + int(with.size() / 2), colinear_labels[0]);
      BOOST_TEST(detail::first_least_delta2_framed(frame, with.data(), int(with.size())) == -1);
      ++refused, colinear += int(colinear_labels.size());
    }
  }
  BOOST_TEST_MESSAGE(framed << " framed pairs, " << parallel << " parallel and " << colinear << " colinear edge pairs, "
                            << compared << " comparisons (" << ties << " exact ties), " << firsts
                            << " first least (" << refused << " refused), " << values << " values, " << zero_depths << " zero depths");
  BOOST_TEST(framed > 1500);
  BOOST_TEST(zero_depths > 100);   // touching candidates: the depth signs' hard case     // the kind of pair the frame is for
  BOOST_TEST(parallel > 5000);   // parallel edge pairs (degree 3) are exercised
  BOOST_TEST(ties > 10000);      // and exact ties
  BOOST_TEST(refused > 300);
  BOOST_TEST(values > 30000);
}

// Parallel edge pairs at the frame's bounds (integer_heights.h: coordinates up to 2^60 − 2^7 of
// its unit, differences near 2^61): their common perpendicular's heights reach 2^249 and n.n
// 2^372 (integer_depth.h), the widest integers framed_depth computes. B's edges 0–1 and 2–3 are
// A's edge 0–1 and 0–2 moved (exactly: multiples of 2^7 below 2^59), beside random vertices of
// both signs and a coordinate of 1 (the frame's unit); a third of the pairs on small integers,
// a third Kuhn cells stacked by rounding (heights that differ in their lowest words only).
// Every label's framed D, its sign and n.n equal the rationals', parallel labels of both
// orientations included. Measured: 3,341 parallel edge pairs, 302 of them with D < 0.
BOOST_AUTO_TEST_CASE(parallel_edge_pairs_at_the_frames_bounds) {
  compare::ReproducibleRng r(20261205);
  long checked = 0, parallel = 0, negative = 0;
  auto big = [&r] { return std::ldexp(double(r.integer(-(1 << 30), 1 << 30)) * double(1 << 20), 7); };
  auto small = [&r] { return double(r.integer(-8, 8)); };  // (heights whose high words agree)
  for (int it = 0; it < 900; ++it) {
    TetVertices A, B;
    if (it % 3 == 2) {
      // Kuhn cells of 0.1 stacked by rounding (A's top 0.2 + 0.1 = 0.30000000000000004, B's
      // bottom 0.3): edges of B over A's, heights of both ends ~1e-17 apart (their high words
      // agree, the low ones decide)
      const double h = 0.1;
      const Vec3d oa = {r.integer(-4, 4) * h, r.integer(-4, 4) * h, 0.2}, ob = {oa[0], oa[1], 0.3};
      A = pdd::test::kuhn_cell_tet(oa, h, r.integer(0, 5));
      B = pdd::test::kuhn_cell_tet(ob, h, r.integer(0, 5));
    } else {
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) A[i][k] = it % 3 ? big() : small(), B[i][k] = it % 3 ? big() : small();
    }
    for (int k = 0; k < 3 && it % 3 != 2; ++k) {
      B[1][k] = B[0][k] + (A[1][k] - A[0][k]);
      B[3][k] = B[2][k] + (it % 2 ? A[2][k] - A[0][k] : A[0][k] - A[2][k]);
    }
    if (it % 3 != 2) A[3][2] = 1.0;
    detail::IntegerFrame frame(A, B);
    if (orientation_sign_exact(A) == Sign::Zero || orientation_sign_exact(B) == Sign::Zero) continue;
    BOOST_REQUIRE(frame.usable());
    const int e = frame.unit_exponent();
    const detail::QTet qa = detail::exact_tet(A), qb = detail::exact_tet(B);
    for (const DirectionLabel& l : candidate_labels(A, B)) {
      const detail::QV n = oriented_normal_q(qa, qb, l);
      const Q D = depth_q(qa, qb, n), nn = dot(n, n);
      detail::FramedDepth fd;
      BOOST_REQUIRE(detail::framed_depth(frame, l, fd));
      const int degree = fd.parallel ? 1 : 0;
      BOOST_TEST((limbs_value(fd.D, 4, (3 + degree) * e) == abs(D)), l.str());
      BOOST_TEST((fd.D_sign == sgn(D)), l.str());
      BOOST_TEST((limbs_value(fd.nn, 6, (4 + 2 * degree) * e) == nn), l.str());
      ++checked;
      parallel += fd.parallel;
      negative += fd.parallel && sgn(D) < 0;
    }
  }
  BOOST_TEST_MESSAGE(checked << " labels, " << parallel << " parallel edge pairs (" << negative << " with D < 0)");
  BOOST_TEST(parallel > 2500);  // the parallel edge pairs are exercised
  BOOST_TEST(negative > 200);   // separating parallel directions: D's sign exercised
}

BOOST_AUTO_TEST_CASE(height_signs_match_rationals) {
  compare::ReproducibleRng r(5);
  int zeros = 0, nonzero = 0, short_dots = 0, tested = 0, planes[2] = {0, 0};
  for (int it = 0; it < 600; ++it) {
    const double h = std::ldexp(1.0, r.integer(-3, 1));
    const Vec3d o = {h * r.integer(-8, 8), h * r.integer(-8, 8), h * r.integer(-8, 8)};
    const double frac = it % 3 == 0 ? 0.5 : (it % 3 == 1 ? 0.1 : r.uniform(0, 1));
    Vec3d ob;
    for (int k = 0; k < 3; ++k) ob[k] = o[k] + (frac + r.integer(-1, 0)) * h;
    TetVertices A = pdd::test::kuhn_cell_tet(o, h, r.integer(0, 5));
    TetVertices B = pdd::test::kuhn_cell_tet(ob, h, r.integer(0, 5));
    const bool mirrored = it % 2 == 1;
    if (mirrored)
      for (int i = 0; i < 4; ++i) A[i][1] = -A[i][1], B[i][1] = -B[i][1];
    BOOST_REQUIRE(detail::in_exact_range(A, B));
    const Vec3d* pts[8];
    for (int i = 0; i < 4; ++i) pts[i] = &A[i], pts[4 + i] = &B[i];
    for (int trial = 0; trial < 20; ++trial) {
      const Vec3d& p1 = *pts[r.integer(0, 7)];
      const Vec3d& p0 = *pts[r.integer(0, 7)];
      const Vec3d& q1 = *pts[r.integer(0, 7)];
      const Vec3d& q0 = *pts[r.integer(0, 7)];
      const Vec3d& p = *pts[r.integer(0, 7)];
      const Vec3d& q = *pts[r.integer(0, 7)];
      Q u[3], v[3], d[3];
      for (int k = 0; k < 3; ++k) u[k] = Q(p1[k]) - Q(p0[k]), v[k] = Q(q1[k]) - Q(q0[k]), d[k] = Q(p[k]) - Q(q[k]);
      const Q want = (u[1] * v[2] - u[2] * v[1]) * d[0] + (u[2] * v[0] - u[0] * v[2]) * d[1] +
                     (u[0] * v[1] - u[1] * v[0]) * d[2];
      detail::LazyNormal n(p1, p0, q1, q0);
      bool ok = true;
      const int got = detail::exact_height_sign(n, p, q, ok);
      BOOST_TEST(ok);
      BOOST_TEST(got == sgn(want));
      detail::LazyNormal m(p1, p0, q1, q0);
      int s = 2;
      if (detail::short_dot_sign(m, p, q, s)) {
        ++short_dots;
        BOOST_TEST(s == sgn(want));
      }
      double du[3], dv[3], dw[3];
      if (detail::exact_difference(p1, p0, du) && detail::exact_difference(q1, q0, dv) &&
          detail::exact_difference(p, q, dw) && detail::in_axis_or_diagonal_plane(du, dv, dw)) {
        ++planes[mirrored];
        BOOST_TEST(sgn(want) == 0);
      }
      (sgn(want) == 0 ? zeros : nonzero) += 1;
      ++tested;
    }
  }
  BOOST_TEST_MESSAGE("heights " << tested << ", zeros " << zeros << ", short dots " << short_dots
                                << ", zeros by planes " << planes[0] << " + " << planes[1] << " mirrored");
  BOOST_TEST(planes[0] > zeros / 8);
  BOOST_TEST(planes[1] > zeros / 8);
  BOOST_TEST(zeros > tested / 10);
  BOOST_TEST(nonzero > tested / 10);
  BOOST_TEST(short_dots > tested / 10);
}

// Expansion arithmetic on sums that cancel exactly in doubles' rounding: (a + b) − a − b = 0,
// products of differences against rationals.
BOOST_AUTO_TEST_CASE(expansion_arithmetic_is_exact) {
  compare::ReproducibleRng r(7);
  for (int it = 0; it < 20000; ++it) {
    const double x[6] = {r.uniform(-10, 10), r.uniform(-1e-8, 1e-8), r.uniform(-1e5, 1e5),
                         r.uniform(-10, 10),  r.uniform(-3, 3),       r.uniform(-1e-3, 1e-3)};
    const detail::Expansion p = detail::product(detail::difference(x[0], x[1]), detail::difference(x[2], x[3]));
    const detail::Expansion e = detail::difference(p, detail::scaled(detail::difference(x[4], x[5]), x[0]));
    const Q want = (Q(x[0]) - Q(x[1])) * (Q(x[2]) - Q(x[3])) - (Q(x[4]) - Q(x[5])) * Q(x[0]);
    Q got = 0;
    for (int i = 0; i < e.n; ++i) got += Q(e.c[i]);
    BOOST_TEST(e.ok);
    BOOST_TEST((got == want));
    BOOST_TEST(e.sign() == sgn(want));
    for (int i = 1; i < e.n; ++i) BOOST_TEST(std::fabs(e.c[i - 1]) < std::fabs(e.c[i]));  // increasing
  }
}

// compressed(): the same exact value (rationals), the same sign, no more components, increasing
// and non-zero; the largest component is the value rounded to within one ulp (Shewchuk's
// compress), checked as |value − c_top| <= ulp(c_top). Values that cancel to exactly 0 included.
BOOST_AUTO_TEST_CASE(compressed_keeps_the_exact_value) {
  compare::ReproducibleRng r(11);
  int zeros = 0, shorter = 0;
  for (int it = 0; it < 20000; ++it) {
    const double x[6] = {r.uniform(-10, 10), r.uniform(-1e-8, 1e-8), r.uniform(-1e5, 1e5),
                         r.uniform(-10, 10),  r.uniform(-3, 3),       r.uniform(-1e-3, 1e-3)};
    const detail::Expansion a = detail::product(detail::difference(x[0], x[1]), detail::difference(x[2], x[3]));
    const detail::Expansion b = detail::product(detail::difference(x[4], x[5]), detail::difference(x[0], x[1]));
    // every fourth draw: a − a·1, exactly 0 whatever the components
    const detail::Expansion e =
        it % 4 == 0 ? detail::difference(a, detail::scaled(a, 1.0)) : detail::sum(detail::product(a, b), a);
    const detail::Expansion c = detail::compressed(e);
    Q want = 0, got = 0;
    for (int i = 0; i < e.n; ++i) want += Q(e.c[i]);
    for (int i = 0; i < c.n; ++i) got += Q(c.c[i]);
    BOOST_TEST(c.ok);
    BOOST_TEST((got == want));
    BOOST_TEST(c.sign() == sgn(want));
    BOOST_TEST(c.n <= e.n);
    for (int i = 0; i < c.n; ++i) BOOST_TEST(c.c[i] != 0.0);
    for (int i = 1; i < c.n; ++i) BOOST_TEST(std::fabs(c.c[i - 1]) < std::fabs(c.c[i]));
    if (c.n > 0) {
      const double top = c.c[c.n - 1];
      const double ulp = std::nextafter(std::fabs(top), HUGE_VAL) - std::fabs(top);
      const Q gap = want - Q(top);
      BOOST_TEST((gap <= Q(ulp) && -gap <= Q(ulp)));
    }
    zeros += sgn(want) == 0;
    shorter += c.n < e.n;
  }
  BOOST_TEST(zeros >= 4000);   // the a − a draws
  BOOST_TEST(shorter > 1000);  // compression does shorten products
}

// compensated_displacements.h: case 2's optimal displacements under the exact optimum's status
// pattern, in double words, lie within their bounds of the rational ones (exact_candidate.h's
// solver, direction_qp_impl.h's displacement_below/above), on aligned pairs (grid shifts; two
// Kuhn paths of one cube, every sixth pair the same one: contacts made by rounding, values a
// rounding apart) and, for most vertices, within 2^-20 of their own size. The pattern is read
// from the rational solution (A's vertex at the plane when its margin C − h + S_A < 0, B's
// when C − h + S_B > 0, constrained ones always); a pair with a free margin exactly 0 has no
// verified pattern in the engine (valued_on_heights) and is skipped here.
BOOST_AUTO_TEST_CASE(compensated_displacements_match_rationals) {
  compare::ReproducibleRng r(45);
  int checked = 0, displaced = 0, tight = 0;  // vertices bounded to 2^-20 of their displacement: tight
  for (int it = 0; it < 400; ++it) {
    auto [A, B] = aligned_pair(r);
    if (it % 3 == 0) {  // two Kuhn paths of one cube (the same one every sixth pair)
      const double h = r.uniform(0.5, 2.0);
      const Vec3d o = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
      const int p = r.integer(0, 5);
      A = pdd::test::kuhn_cell_tet(o, h, p);
      B = pdd::test::kuhn_cell_tet(o, h, it % 2 ? p : r.integer(0, 5));
    }
    if (orientation_sign_exact(A) == Sign::Zero || orientation_sign_exact(B) == Sign::Zero) continue;
    const detail::ExactFrame f = detail::exact_frame(A, B);
    for (const DirectionLabel& l : candidate_labels(A, B)) {
      const detail::ExactCandidate c = detail::exact_candidate(f, l);
      const Solution<Q> s = detail::solve_deformable_sorted(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
      unsigned atA = c.conA, atB = c.conB;
      bool degenerate = false;
      for (int i = 0; i < 4; ++i) {
        if (!(c.conA >> i & 1u)) {
          const Q m = s.c - c.hA[i] + s.sumA;
          degenerate = degenerate || m == 0;
          if (m < 0) atA |= 1u << i;
        }
        if (!(c.conB >> i & 1u)) {
          const Q m = s.c - c.hB[i] + s.sumB;
          degenerate = degenerate || m == 0;
          if (m > 0) atB |= 1u << i;
        }
      }
      if (degenerate || !(c.nn > 0)) continue;
      ++checked;
      // The frame's normal is 2^(2 shift) times the pair's (a cross product of differences
      // scaled by 2^shift, oriented alike), its heights 2^(3 shift) times: T = T_frame / 2^(3 shift).
      detail::CompensatedDisplacements moved;
      if (!detail::compensated_displacements(A, B, l, detail::AtPlane{atA, atB}, moved)) continue;
      for (int i = 0; i < 4; ++i) {
        const Q tA = detail::unscaled(f, displacement_below(c.hA[i], (c.conA >> i & 1u) != 0, s), 3);
        const Q tB = detail::unscaled(f, displacement_above(c.hB[i], (c.conB >> i & 1u) != 0, s), 3);
        BOOST_TEST(abs(Q(moved.tA[i]) - tA) <= Q(moved.eA[i]), l.str() << " A" << i << ": " << moved.tA[i] << " vs " << tA.get_d());
        BOOST_TEST(abs(Q(moved.tB[i]) - tB) <= Q(moved.eB[i]), l.str() << " B" << i << ": " << moved.tB[i] << " vs " << tB.get_d());
        tight += Q(moved.eA[i]) <= abs(tA) * Q(1, 1 << 20) && Q(moved.eB[i]) <= abs(tB) * Q(1, 1 << 20);
      }
      ++displaced;
    }
  }
  BOOST_TEST_MESSAGE(displaced << " of " << checked << " case-2 optima's displacements in double words within their bounds ("
                               << tight << " vertices within 2^-20 of their size)");
  BOOST_TEST(checked > 1000);
  BOOST_TEST(displaced > 0.9 * checked);
  BOOST_TEST(tight > 0.5 * 4 * displaced);
}
