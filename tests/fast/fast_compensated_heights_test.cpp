// fast_compensated_heights_test — compensated_heights.h and pdd2_accel(A, B, 1) on it
// (deformable_depth.cpp's accel1_compensated), against rationals computed here again from the
// definition (n* = e1 x e2 of the candidate's face or edge pair, H*_i = n*.(x_i - o), oriented
// as the candidate's double normal):
//  - every height and normal component lies within its certified bound, for every
//    non-parallel candidate of random pairs, 1-ulp slivers, nearly parallel edges, scaled pairs
//    and shallow contacts; and the bounds are not vacuous (the worst error reaches a sizeable
//    fraction of its bound on some input, so a bound scaled down would fail);
//  - on shallow contacts (depth 10^-2.5 .. 10^-12 of the size) pdd2_accel1 is within definitions §8's
//    1e-9 of the exact case-2 value along the exact rigid label; where the rigid direction is
//    certified in doubles (to ~1e-4 of the size) but the double heights cannot certify
//    pdd2_accel1, rigid_and_accel1 now does (>= 95% of those pairs; ~75% at 1e-3 and none at
//    1e-4 before);
//  - compensated_positions (deformable_depth.h) puts every coordinate q within 3u max(Q, |q|)
//    of the exact case-2 positions P + d* of the pdd2 label (Q the pair's largest |coordinate|),
//    on shallow contacts and on contacts made by rounding (structured_cells.h);
//  - on the same pairs pdd2_static, whose contenders (VF ones included: C is then A's highest
//    height) certify on compensated heights, is within 1e-9 of the exact minimum over the
//    case-1 family, computed here in rationals;
//  - compensated_depth's double-word D and n.n lie within their bounds, compare_delta2_compensated
//    never contradicts the exact order and decides the near ties a rounding apart, and
//    first_least_delta2 (certify.h) names the exact first least delta² (exact_candidate.h's
//    rationals), on Kuhn cells against a copy shifted by a non-dyadic offset, contacts made by
//    rounding and random pairs; on the same pairs every dot-product sign of two candidates'
//    double normals that certain_dot_sign (exact_predicates.h) decides is the exact normals'
//    (1.5 million decided; a bound 1e9 times narrower gets 359 wrong).
#define BOOST_TEST_MODULE fast_compensated_heights
#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "certification/certify.h"
#include "certification/compensated_heights.h"
#include "exact/exact_candidate.h"
#include "exact/integer_heights.h"
#include "kernel/candidate_directions.h"
#include "kernel/direction_geometry.h"
#include "kernel/pair_memo.h"
#include "kernel/power_scale.h"
#include "kernel/superset_depth.h"
#include "pdd/compare/random.h"
#include "pdd/pdd.h"
#include "qp/deformable_depth.h"
#include "qp/direction_qp_impl.h"
#include "structured_cells.h"

using namespace pdd;
using namespace pdd::fast;

namespace {

using Rng = pdd::compare::ReproducibleRng;
using Q = mpq_class;

TetVertices random_tet(Rng& rng, double size) {
  TetVertices T;
  for (auto& v : T)
    for (double& x : v) x = rng.uniform(0, size);
  return T;
}

// The exact heights and normal of candidate c of (A, B), by the definition.
struct Exact {
  Q n[3], hA[4], hB[4];
};
Exact exact_of(const TetVertices& A, const TetVertices& B, const Candidate& c) {
  const DirectionLabel& l = c.label;
  std::array<double, 3> o, p1, q1, p2, q2;
  if (l.kind == ContactKind::FV || l.kind == ContactKind::VF) {
    const TetVertices& T = l.kind == ContactKind::FV ? A : B;
    const auto& f = kFace[l.a];
    o = T[f[0]], p1 = T[f[1]], q1 = o, p2 = T[f[2]], q2 = o;
  } else {
    const int u = kEdges[l.a][0], v = kEdges[l.a][1], x = kEdges[l.b][0], y = kEdges[l.b][1];
    o = A[u], p1 = B[y], q1 = B[x], p2 = A[v], q2 = A[u];
  }
  Q e1[3], e2[3];
  for (int k = 0; k < 3; ++k) e1[k] = Q(p1[k]) - Q(q1[k]), e2[k] = Q(p2[k]) - Q(q2[k]);
  Exact x;
  for (int k = 0; k < 3; ++k) {
    const int r = (k + 1) % 3, s = (k + 2) % 3;
    x.n[k] = e1[r] * e2[s] - e1[s] * e2[r];
  }
  const Q orient = x.n[0] * c.n[0] + x.n[1] * c.n[1] + x.n[2] * c.n[2];
  if (sgn(orient) < 0)
    for (Q& v : x.n) v = -v;
  auto h = [&](const std::array<double, 3>& p) -> Q {
    return x.n[0] * (Q(p[0]) - Q(o[0])) + x.n[1] * (Q(p[1]) - Q(o[1])) + x.n[2] * (Q(p[2]) - Q(o[2]));
  };
  for (int i = 0; i < 4; ++i) x.hA[i] = h(A[i]), x.hB[i] = h(B[i]);
  return x;
}

// B pushed along the rigid direction until the depth is `depth` (a shallow contact).
bool shallow(TetVertices& A, TetVertices& B, double depth) {
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  Choice rigid;
  Candidate c;
  if (!sp.exact || !rigid_superset(sp.A, sp.B, rigid, &c) || !(rigid.value > 0)) return false;
  const double pd = std::sqrt(std::ldexp(rigid.value, -2 * sp.e));
  const double t = pd - depth, nn = std::sqrt(c.n[0] * c.n[0] + c.n[1] * c.n[1] + c.n[2] * c.n[2]);
  if (!(t > 0) || !(nn > 0)) return false;
  for (auto& v : B)
    for (int k = 0; k < 3; ++k) v[k] += t * c.n[k] / nn;
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(heights_within_their_bounds) {
  Rng rng(20261124);
  int checked = 0, wrong = 0;
  double worst = 0;  // the largest |error| / bound seen
  for (int trial = 0; trial < 600; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    const int kind = trial % 5;
    if (kind == 1) A[1] = A[0], A[1][0] = std::nextafter(A[1][0], 1e9);           // 1-ulp edge
    if (kind == 2) B[1] = B[0], B[1][0] += A[1][0] - A[0][0], B[1][1] += A[1][1] - A[0][1],
                   B[1][2] += (A[1][2] - A[0][2]) * (1 + 1e-13);                  // nearly parallel edges
    if (kind == 3 && !shallow(A, B, std::ldexp(1.0, -int(rng.integer(10, 40))))) continue;
    if (kind == 4) {
      const int e = rng.integer(-300, 300);
      for (auto* T : {&A, &B})
        for (auto& v : *T)
          for (double& x : v) x = std::ldexp(x, e);
    }
    const detail::ScaledPair sp = detail::power_scaled(A, B);
    if (!sp.exact) continue;
    CandidateSet set;
    if (build_candidates(sp.A, sp.B, set) != BuildStatus::Ok) continue;
    for (int k = 0; k < set.count; ++k) {
      const Candidate c = candidate(set, k);
      detail::CompensatedHeights h;
      if (!detail::compensated_heights(sp.A, sp.B, c, h)) {
        BOOST_TEST(c.parallel);  // the only case it declines on these valid pairs
        continue;
      }
      const Exact x = exact_of(sp.A, sp.B, c);
      auto check = [&](double computed, double bound, const Q& exact) {
        const Q err = abs(Q(computed) - exact);
        if (err > Q(bound)) ++wrong;
        if (bound > 0) worst = std::max(worst, Q(err / Q(bound)).get_d());
        ++checked;
      };
      for (int i = 0; i < 4; ++i) check(h.hA[i], h.eA[i], x.hA[i]), check(h.hB[i], h.eB[i], x.hB[i]);
      for (int j = 0; j < 3; ++j) check(h.n[j], h.e_n, x.n[j]);
    }
  }
  BOOST_TEST(wrong == 0);
  BOOST_TEST(checked > 100000);
  // not vacuous: u |h| is most of each bound, and rounding to nearest reaches about half of it
  BOOST_TEST(worst > 0.25, "worst error / bound " << worst);
  BOOST_TEST(worst <= 1.0);
}

BOOST_AUTO_TEST_CASE(shallow_accel1_certified_and_exact) {
  Rng rng(77);
  int pairs = 0, unique_pairs = 0, certified_fast = 0;
  for (int trial = 0; trial < 600; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    // depth 10^-2.5 .. 10^-12 of the size; the first half of the trials 10^-2.5 .. 10^-4, where
    // the rigid direction is still certified in doubles (superset_depth.h's `unique`) but the
    // double heights certified pdd2_accel1 on about 3 pairs in 4 at 10^-3 and none at 10^-4
    const double depth = 10 * std::pow(10.0, -(trial < 300 ? rng.uniform(2.5, 4) : rng.uniform(4, 12)));
    if (!shallow(A, B, depth)) continue;
    const detail::ScaledPair sp = detail::power_scaled(A, B);
    Choice rigid, accel1;
    Candidate c;
    bool unique = false;
    const bool fast_path = rigid_and_accel1(sp.A, sp.B, rigid, c, accel1);
    Choice r2;
    Candidate c2;
    rigid_superset(sp.A, sp.B, r2, &c2, &unique);
    const Depth d = pdd2_accel(A, B, 1);
    if (d.status != DepthStatus::Ok || !(d.pd2 > 0)) continue;
    ++pairs;
    if (unique) ++unique_pairs, certified_fast += fast_path;
    if (fast_path) BOOST_TEST(accel1.certified);
    // the exact case-2 value along the exact rigid label (exact_candidate.h, on the pair as given)
    const Depth r = rigid_pd2(A, B);
    BOOST_REQUIRE(r.dir.has_value());
    const detail::ExactFrame f = detail::exact_frame(A, B);
    const Q exact = detail::unscaled(f, detail::exact_deformable_value(detail::exact_candidate(f, *r.dir)), 2);
    const Q rel = abs(Q(d.pd2) - exact) / exact;
    BOOST_TEST(rel.get_d() <= 1e-9, "trial " << trial << " depth " << depth << ": " << d.pd2 << " vs "
                                              << exact.get_d());
  }
  BOOST_TEST(pairs > 300);
  BOOST_TEST(unique_pairs > 100);
  BOOST_TEST(certified_fast >= 0.95 * unique_pairs, certified_fast << " of " << unique_pairs);
}

// Each coordinate of compensated_positions against the exact positions P + d* (d* = T*/n.n n*
// of the exact case-2 solution along the same label, direction_qp.h), in units of u max(Q, |q|):
// pdd2's label on shallow contacts and contacts made by rounding, and the parallel and nearly
// parallel edge pairs of a tetrahedron against its copy shifted along an edge (heights by
// expansions, where double words are missing or too coarse). Measured: 12 of those 325 edge
// pairs given (none without the expansions); the others' displacements on the rounded heights
// are too coarse for 2u Q, and the engine takes their positions exactly.
BOOST_AUTO_TEST_CASE(compensated_positions_within_their_bound) {
  Rng rng(5);
  int offered = 0, given = 0, edge_offered = 0, edge_pairs = 0;
  double worst = 0;
  // candidate c's positions, when compensated_positions gives them (returns whether it did)
  auto check_candidate = [&](const detail::ScaledPair& sp, const Candidate& c) {
    Positions<double> qA, qB;
    if (!compensated_positions(sp.A, sp.B, c, qA, qB)) return false;
    const detail::ExactFrame f = detail::exact_frame(sp.A, sp.B);
    const detail::ExactCandidate x = detail::exact_candidate(f, c.label);
    Solution<Q> sol;
    (void)detail::exact_deformable_value(x, &sol);
    double Qmax = 0;
    for (const TetVertices* T : {&sp.A, &sp.B})
      for (const auto& v : *T)
        for (double y : v) Qmax = std::max(Qmax, std::fabs(y));
    auto unit = [Qmax](double q) { return Q(std::ldexp(std::max(Qmax, std::fabs(q)), -53)); };  // u max(Q, |q|)
    for (int i = 0; i < 4; ++i) {
      const Q tA = displacement_below(x.hA[i], (x.conA >> i & 1u) != 0, sol) / x.nn;
      const Q tB = displacement_above(x.hB[i], (x.conB >> i & 1u) != 0, sol) / x.nn;
      for (int k = 0; k < 3; ++k) {
        const Q eA = Q(sp.A[i][k]) + detail::unscaled(f, tA * x.n.x[k], 1);
        const Q eB = Q(sp.B[i][k]) + detail::unscaled(f, tB * x.n.x[k], 1);
        const double e = std::max(Q(abs(Q(qA[i][k]) - eA) / unit(qA[i][k])).get_d(),
                                  Q(abs(Q(qB[i][k]) - eB) / unit(qB[i][k])).get_d());
        worst = std::max(worst, e);
        BOOST_TEST(e <= 3.0, c.label.str() << " vertex " << i << " coordinate " << k << ": " << e << " u Q");
      }
    }
    return true;
  };
  auto check = [&](const TetVertices& A, const TetVertices& B) {
    const detail::ScaledPair sp = detail::power_scaled(A, B);
    CandidateSet set;
    if (!sp.exact || build_candidates(sp.A, sp.B, set) != BuildStatus::Ok || !set.intersecting) return;
    const Choice def = pdd2(set);
    if (def.index < 0 || !def.certified) return;
    ++offered;
    given += check_candidate(sp, candidate(set, def.index));
  };
  for (int trial = 0; trial < 400; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    if (shallow(A, B, 10 * std::pow(10.0, -rng.uniform(3, 12)))) check(A, B);
  }
  const std::vector<TetPair> rounding = pdd::test::rounding_contact_pairs(2, 60);
  BOOST_TEST(rounding.size() == 60u);
  const int shallow_given = given;
  for (const TetPair& p : rounding) check(p.A, p.B);
  BOOST_TEST(given - shallow_given == 60, given - shallow_given << " of the 60 contacts made by rounding");
  // a tetrahedron against its copy moved along one of its edges by (1 - eps) of it (a mesh
  // against a shifted copy: a shallow contact whose edges are parallel to the copy's up to the
  // rounding of the move, eps 1e-4 to 1e-7): every parallel or nearly parallel edge pair of the
  // contact shallow along its own direction (delta² below 1e-6 of the scale's square)
  for (int trial = 0; trial < 300; ++trial) {
    const TetVertices A = random_tet(rng, 10);
    TetVertices B = A;
    const int u = rng.integer(0, 3), v = (u + 1 + rng.integer(0, 2)) % 4;
    const double t = 1 - std::pow(10.0, -rng.uniform(4, 7));
    for (auto& x : B)
      for (int k = 0; k < 3; ++k) x[k] += t * (A[v][k] - A[u][k]);
    const detail::ScaledPair sp = detail::power_scaled(A, B);
    CandidateSet set;
    if (!sp.exact || build_candidates(sp.A, sp.B, set) != BuildStatus::Ok || !set.intersecting) continue;
    for (int k = 0; k < set.count; ++k) {
      const Candidate c = candidate(set, k);
      if (c.label.kind == ContactKind::EE && (c.parallel || c.own_bounds) && set.delta_sq[k] < 1e-6)
        ++edge_offered, edge_pairs += check_candidate(sp, c);
    }
  }
  BOOST_TEST_MESSAGE("compensated positions given for " << given << " of " << offered << " pdd2 labels and "
                                                         << edge_pairs << " of " << edge_offered
                                                         << " shallow parallel edge pairs, worst " << worst << " u Q");
  BOOST_TEST(edge_pairs >= 10);
  BOOST_TEST(given >= 0.9 * offered, given << " of " << offered);
  BOOST_TEST(worst > 0.25);  // not vacuous: the final rounding alone reaches about half a unit
}

BOOST_AUTO_TEST_CASE(shallow_static_values_exact) {
  Rng rng(6);
  std::vector<std::pair<TetVertices, TetVertices>> pairs;
  for (int trial = 0; trial < 300; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    if (shallow(A, B, 10 * std::pow(10.0, -rng.uniform(3, 12)))) pairs.emplace_back(A, B);
  }
  for (const TetPair& p : pdd::test::rounding_contact_pairs(2, 40)) pairs.emplace_back(p.A, p.B);
  int checked = 0;
  for (const auto& [A, B] : pairs) {
    const Depth d = pdd2_static(A, B);
    if (d.status != DepthStatus::Ok || !(d.pd2 > 0)) continue;
    CandidateSet set;
    BOOST_REQUIRE(build_candidates(A, B, set) == BuildStatus::Ok);
    const detail::ExactFrame f = detail::exact_frame(A, B);
    std::optional<Q> best;
    for (int k = 0; k < set.count; ++k) {
      const DirectionLabel l = candidate(set, k).label;
      if (l.orientation != EdgeOrientation::Decided) continue;  // not in case 1's family
      const Q v = detail::exact_static_value(detail::exact_candidate(f, l));
      if (!best || v < *best) best = v;
    }
    BOOST_REQUIRE(best.has_value());
    const Q exact = detail::unscaled(f, *best, 2);
    const Q rel = abs(Q(d.pd2) - exact) / exact;
    BOOST_TEST(rel.get_d() <= 1e-9, d.pd2 << " vs " << exact.get_d());
    ++checked;
  }
  BOOST_TEST(checked > 200);
}

namespace {

// Kuhn cells of a 3^3 grid of side h against those of the same grid shifted by `shift`, the
// pairs whose interiors meet. By default h = 1/8 and the shift (0.37, 0.21, 0.13) h, each
// coordinate rounded once: axis edges exactly parallel, faces and other edges parallel up to
// that rounding (delta² of such candidates ~1e-16 apart relative), several candidates of one
// exact direction.
std::vector<std::pair<TetVertices, TetVertices>> shifted_kuhn_pairs(double h = 0.125,
                                                                    Vec3d shift = {0.37 * 0.125, 0.21 * 0.125,
                                                                                   0.13 * 0.125}) {
  std::vector<TetVertices> A, B;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int perm = 0; perm < 6; ++perm) {
          A.push_back(pdd::test::kuhn_cell_tet({i * h, j * h, k * h}, h, perm));
          B.push_back(pdd::test::kuhn_cell_tet({i * h + shift[0], j * h + shift[1], k * h + shift[2]}, h, perm));
        }
  std::vector<std::pair<TetVertices, TetVertices>> out;
  for (const TetVertices& a : A)
    for (const TetVertices& b : B) {
      const Depth d = rigid_pd2(a, b);
      if (d.status == DepthStatus::Ok && d.pd2 > 0) out.emplace_back(a, b);
    }
  return out;
}

// f(sp, f, c) for every candidate c of every intersecting pair (power_scaled exactly to sp,
// its exact frame f).
template <class F>
void for_each_candidate(const std::vector<std::pair<TetVertices, TetVertices>>& pairs, F each) {
  for (const auto& [A0, B0] : pairs) {
    const detail::ScaledPair sp = detail::power_scaled(A0, B0);
    CandidateSet set;
    if (!sp.exact || build_candidates(sp.A, sp.B, set) != BuildStatus::Ok || !set.intersecting) continue;
    const detail::ExactFrame f = detail::exact_frame(sp.A, sp.B);
    for (int k = 0; k < set.count; ++k) each(sp, f, candidate(set, k));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(compensated_depths_order_near_ties) {
  std::vector<std::pair<TetVertices, TetVertices>> pairs = shifted_kuhn_pairs();
  const std::size_t shifted = pairs.size();
  for (const TetPair& p : pdd::test::rounding_contact_pairs(2, 40)) pairs.emplace_back(p.A, p.B);
  Rng rng(20261129);
  for (int trial = 0; trial < 300; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    if (rigid_pd2(A, B).pd2 > 0) pairs.emplace_back(A, B);
  }
  int bounded = 0, out_of_bound = 0, near_ties = 0, decided = 0, contradicted = 0, named = 0, misnamed = 0;
  long signs = 0, wrong_signs = 0;
  double worst = 0;
  for (const auto& [A0, B0] : pairs) {
    const detail::ScaledPair sp = detail::power_scaled(A0, B0);
    BOOST_REQUIRE(sp.exact);
    CandidateSet set;
    if (build_candidates(sp.A, sp.B, set) != BuildStatus::Ok) continue;
    const detail::ExactFrame f = detail::exact_frame(sp.A, sp.B);
    std::vector<Q> d2(set.count);
    std::vector<std::optional<detail::CompensatedDepth>> cd(set.count);
    for (int k = 0; k < set.count; ++k) {
      const Candidate c = candidate(set, k);
      d2[k] = detail::exact_delta2(detail::exact_candidate(f, c.label));
      detail::CompensatedDepth x;
      if (c.parallel || !detail::compensated_depth(sp.A, sp.B, c.label, x)) continue;
      cd[k] = x;
      const Exact e = exact_of(sp.A, sp.B, c);
      Q top = e.hA[0], bottom = e.hB[0];
      for (int i = 1; i < 4; ++i) top = std::max(top, e.hA[i]), bottom = std::min(bottom, e.hB[i]);
      const Q D = top - bottom, nn = e.n[0] * e.n[0] + e.n[1] * e.n[1] + e.n[2] * e.n[2];
      const Q errD = abs(Q(x.D.hi) + Q(x.D.lo) - D), errN = abs(Q(x.nn.hi) + Q(x.nn.lo) - nn);
      out_of_bound += (errD > Q(x.eD)) + (errN > Q(x.enn));
      worst = std::max({worst, Q(errD / Q(x.eD)).get_d(), Q(errN / Q(x.enn)).get_d()});
      bounded += 2;
    }
    // certain_dot_sign (exact_predicates.h) on the double normals against the exact normals'
    // dot product: first_least_delta2 takes its sign for a direction tie (ExactDirection::
    // same_as(l, side)), so a wrong sign would name a direction that is not the tie's
    std::vector<detail::QV> en(set.count);
    for (int k = 0; k < set.count; ++k) en[k] = detail::exact_candidate(f, candidate(set, k).label).n;
    for (int i = 0; i < set.count; ++i)
      for (int j = i + 1; j < set.count; ++j) {
        const Candidate ci = candidate(set, i), cj = candidate(set, j);
        const ApproxNormal ai{{ci.n[0], ci.n[1], ci.n[2]}, detail::bounds_of(set, i).e_n, ci.parallel};
        const ApproxNormal aj{{cj.n[0], cj.n[1], cj.n[2]}, detail::bounds_of(set, j).e_n, cj.parallel};
        const int s = certain_dot_sign(ai, aj);
        if (s == 0) continue;
        ++signs;
        wrong_signs += s != sgn(detail::dot(en[i], en[j]));
      }
    // the near ties of the least delta² (within 1e-6 of it), in canonical order
    const Q least = *std::min_element(d2.begin(), d2.end());
    std::vector<int> ties;
    for (int k = 0; k < set.count; ++k)
      if (d2[k] <= least * Q(1 + 1e-6)) ties.push_back(k);
    for (std::size_t p = 0; p < ties.size(); ++p)
      for (std::size_t q = p + 1; q < ties.size(); ++q) {
        if (!cd[ties[p]] || !cd[ties[q]]) continue;
        const int exact = cmp(d2[ties[p]], d2[ties[q]]);
        const std::optional<int> s = detail::compare_delta2_compensated(*cd[ties[p]], *cd[ties[q]]);
        if (s) contradicted += (*s > 0 ? 1 : -1) != (exact > 0 ? 1 : exact < 0 ? -1 : 0);
        if (exact != 0) ++near_ties, decided += s.has_value();
      }
    const int first = detail::first_least_delta2(set, ties.data(), int(ties.size()));
    ++named;
    misnamed += first < 0 || d2[ties[first]] != least ||
                std::any_of(ties.begin(), ties.begin() + first, [&](int k) { return d2[k] == least; });
  }
  BOOST_TEST_MESSAGE(bounded << " parts bounded (worst error / bound " << worst << "), " << decided << " of "
                             << near_ties << " near ties decided, " << named << " first least named");
  BOOST_TEST(shifted > 500u);
  BOOST_TEST(out_of_bound == 0);
  BOOST_TEST(bounded > 20000);
  BOOST_TEST(worst > 0.05);  // not vacuous: a bound a tenth as wide fails (0.126 seen)
  BOOST_TEST(contradicted == 0);
  BOOST_TEST(misnamed == 0);
  BOOST_TEST_MESSAGE(signs << " dot signs of candidate normals decided in doubles");
  BOOST_TEST(wrong_signs == 0);
  BOOST_TEST(signs > 100000);
  // the near ties a rounding apart are what the compensated depths are for
  BOOST_TEST(near_ties > 1000);
  BOOST_TEST(decided >= 0.99 * near_ties, decided << " of " << near_ties);
}

namespace {

// An edge pair's exact normal and heights by the definition (definitions §3): n = eB x eA, or
// for parallel edges their common perpendicular (e.e) w - (w.e) e (e = eA, w = r_x - s_u);
// oriented by the rule (A's off-edge vertices below: kept; above: flipped; on both sides: ':+'
// kept, ':-' flipped); heights about A's vertex highest along n (compensated_heights.h).
Exact exact_edge_pair_of(const TetVertices& A, const TetVertices& B, const DirectionLabel& l) {
  const int u = kEdges[l.a][0], v = kEdges[l.a][1], x = kEdges[l.b][0], y = kEdges[l.b][1];
  auto d = [](const Vec3d& p, const Vec3d& q) {
    return std::array<Q, 3>{Q(p[0]) - Q(q[0]), Q(p[1]) - Q(q[1]), Q(p[2]) - Q(q[2])};
  };
  auto dot = [](const std::array<Q, 3>& a, const std::array<Q, 3>& b) -> Q {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const std::array<Q, 3> eA = d(A[v], A[u]), eB = d(B[y], B[x]);
  Exact out;
  for (int k = 0; k < 3; ++k) {
    const int r = (k + 1) % 3, s = (k + 2) % 3;
    out.n[k] = eB[r] * eA[s] - eB[s] * eA[r];
  }
  if (out.n[0] == 0 && out.n[1] == 0 && out.n[2] == 0) {
    const std::array<Q, 3> w = d(B[x], A[u]);
    const Q ee = dot(eA, eA), we = dot(w, eA);
    for (int k = 0; k < 3; ++k) out.n[k] = ee * w[k] - we * eA[k];
  }
  const std::array<Q, 3> n{out.n[0], out.n[1], out.n[2]};
  const int g1 = sgn(dot(n, d(A[kOffEdge[l.a][0]], A[u]))), g2 = sgn(dot(n, d(A[kOffEdge[l.a][1]], A[u])));
  const bool flip = (g1 <= 0 && g2 <= 0) ? false
                    : (g1 >= 0 && g2 >= 0) ? true
                                           : l.orientation == EdgeOrientation::Minus;
  if (flip)
    for (Q& c : out.n) c = -c;
  const std::array<Q, 3> m{out.n[0], out.n[1], out.n[2]};
  for (int i = 0; i < 4; ++i) out.hA[i] = dot(m, d(A[i], A[u])), out.hB[i] = dot(m, d(B[i], A[u]));
  const Q top = std::max({out.hA[0], out.hA[1], out.hA[2], out.hA[3]});
  for (int i = 0; i < 4; ++i) out.hA[i] -= top, out.hB[i] -= top;
  return out;
}

}  // namespace

// expansion_heights (compensated_heights.h): every parallel and nearly parallel edge pair of
// Kuhn cells against copies shifted by a non-dyadic offset (axis edges exactly parallel, the
// others parallel up to the rounding of the shift), of contacts made by rounding (a tenth of a
// cell along (1, 1, 1): diagonal edges parallel up to that rounding, depths ~1e-17 of the
// cell) and of random pairs on a dyadic grid with a copied edge direction (exactly parallel
// edges, and nearly parallel ones one ulp off) gets its heights and normal, each within its
// certified bound of the definition's rationals; and the bounds are not vacuous. Both routes:
// over the pair's integer frame (most of these pairs: each value correctly rounded, bound u of
// it, so the worst error comes near its bound) and by expansions (the random pairs again with a
// coordinate of 2^-75: 75 bits, beyond the frame's 60). Measured: 8,495 parallel and 3,319
// nearly parallel edge pairs (305 of them by expansions), the worst error 0.97 of its bound.
BOOST_AUTO_TEST_CASE(expansion_heights_within_their_bounds) {
  std::vector<std::pair<TetVertices, TetVertices>> pairs = shifted_kuhn_pairs();
  for (const TetPair& p : pdd::test::rounding_contact_pairs(3, 400)) pairs.emplace_back(p.A, p.B);
  Rng rng(20261129);
  for (int trial = 0; trial < 400; ++trial) {
    TetVertices A, B;
    for (auto* T : {&A, &B})
      for (auto& v : *T)
        for (double& x : v) x = std::ldexp(double(rng.integer(0, 1023)), -10);
    for (int k = 0; k < 3; ++k) B[1][k] = B[0][k] + (A[1][k] - A[0][k]);  // exact: eB = eA
    if (trial % 2) B[1][2] = std::nextafter(B[1][2], 2.0);                 // one ulp off
    pairs.emplace_back(A, B);
    B[3][1] = 0x1p-75;  // (coordinates over 75 bits: no integer frame, expansions)
    pairs.emplace_back(A, B);
  }
  int parallel = 0, nearly = 0, wrong = 0, by_expansions = 0;
  double worst = 0;
  for (const auto& [A0, B0] : pairs) {
    const detail::ScaledPair sp = detail::power_scaled(A0, B0);
    CandidateSet set;
    if (!sp.exact || build_candidates(sp.A, sp.B, set) != BuildStatus::Ok) continue;
    const bool framed = detail::IntegerFrame(sp.A, sp.B).usable();
    for (int k = 0; k < set.count; ++k) {
      const Candidate c = candidate(set, k);
      if (c.label.kind != ContactKind::EE || !(c.parallel || c.own_bounds)) continue;
      detail::CompensatedHeights h;
      BOOST_TEST_REQUIRE(detail::expansion_heights(sp.A, sp.B, c, h));
      (c.parallel ? parallel : nearly)++;
      by_expansions += !framed;
      const Exact x = exact_edge_pair_of(sp.A, sp.B, c.label);
      auto check = [&](double computed, double bound, const Q& exact) {
        const Q err = abs(Q(computed) - exact);
        if (err > Q(bound)) ++wrong;
        if (bound > 0) worst = std::max(worst, Q(err / Q(bound)).get_d());
      };
      for (int i = 0; i < 4; ++i) check(h.hA[i], h.eA[i], x.hA[i]), check(h.hB[i], h.eB[i], x.hB[i]);
      for (int j = 0; j < 3; ++j) check(h.n[j], h.e_n, x.n[j]);
    }
  }
  BOOST_TEST_MESSAGE("expansion heights: " << parallel << " parallel and " << nearly
                                           << " nearly parallel edge pairs (" << by_expansions
                                           << " by expansions), worst error / bound " << worst);
  BOOST_TEST(wrong == 0);
  BOOST_TEST(by_expansions > 250);  // both routes
  BOOST_TEST(parallel + nearly - by_expansions > 5000);
  BOOST_TEST(parallel > 4000);
  BOOST_TEST(nearly > 1500);
  // not vacuous: a bound a quarter as wide would fail
  BOOST_TEST(worst > 0.1);
  BOOST_TEST(worst <= 1.0);
}

// Twelve intersecting pairs of a Gmsh transfinite box (cell 1/3, Gmsh's node placement: each
// coordinate a few ulps off the grid) against its copy moved by one cell in x, each a contact
// made by two roundings: pdd2 below 1e-50 (84 of 500 such pairs sampled were).
const std::pair<TetVertices, TetVertices> kTwoRoundingContacts[] = {
    {TetVertices{{{0x1.0000000000000p+1, 0x1.aaaaaaaaaaaacp+0, 0x1.5555555555555p-1}, {0x1.aaaaaaaaaaaacp+0, 0x1.aaaaaaaaaaaa8p+0, 0x1.5555555555557p-1}, {0x1.0000000000000p+1, 0x1.5555555555554p+0, 0x1.0000000000000p+0}, {0x1.aaaaaaaaaaaacp+0, 0x1.aaaaaaaaaaaacp+0, 0x1.0000000000000p+0}}},
     TetVertices{{{0x1.5555555555555p+0, 0x1.aaaaaaaaaaaacp+0, 0x1.0000000000000p+0}, {0x1.5555555555555p+0, 0x1.aaaaaaaaaaaa8p+0, 0x1.5555555555553p-1}, {0x1.5555555555555p+0, 0x1.0000000000000p+1, 0x1.5555555555555p-1}, {0x1.aaaaaaaaaaaadp+0, 0x1.aaaaaaaaaaaa8p+0, 0x1.5555555555557p-1}}}},
    {TetVertices{{{0x1.5555555555556p-1, 0x1.5555555555556p-1, 0x0.0p+0}, {0x1.5555555555553p-1, 0x1.5555555555558p-2, 0x1.5555555555558p-2}, {0x1.5555555555556p-1, 0x1.5555555555559p-1, 0x1.5555555555558p-2}, {0x1.5555555555557p-2, 0x1.5555555555557p-1, 0x1.5555555555558p-2}}},
     TetVertices{{{0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.5555555555556p-1, 0x1.5555555555557p-1, 0x1.5555555555558p-2}, {0x1.0000000000000p+0, 0x1.5555555555556p-1, 0x0.0p+0}, {0x1.0000000000000p+0, 0x1.5555555555559p-1, 0x1.5555555555558p-2}}}},
    {TetVertices{{{0x1.aaaaaaaaaaaacp+0, 0x0.0p+0, 0x1.5555555555555p-1}, {0x1.aaaaaaaaaaaacp+0, 0x0.0p+0, 0x1.5555555555555p-2}, {0x1.5555555555554p+0, 0x1.555555555555ap-2, 0x1.5555555555558p-2}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555555p-2, 0x1.5555555555557p-2}}},
     TetVertices{{{0x1.5555555555555p+0, 0x1.5555555555555p-2, 0x0.0p+0}, {0x1.5555555555555p+0, 0x0.0p+0, 0x1.5555555555555p-2}, {0x1.aaaaaaaaaaaa9p+0, 0x0.0p+0, 0x1.5555555555555p-2}, {0x1.5555555555555p+0, 0x1.5555555555558p-2, 0x1.5555555555558p-2}}}},
    {TetVertices{{{0x1.5555555555556p-1, 0x1.5555555555559p-1, 0x1.5555555555558p-2}, {0x1.5555555555556p-1, 0x1.5555555555556p-1, 0x0.0p+0}, {0x1.5555555555555p-2, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x0.0p+0}}},
     TetVertices{{{0x1.5555555555556p-1, 0x1.5555555555556p-1, 0x1.5555555555558p-1}, {0x1.5555555555556p-1, 0x1.5555555555557p-1, 0x1.5555555555558p-2}, {0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x1.5555555555557p-2}, {0x1.0000000000000p+0, 0x1.5555555555559p-1, 0x1.5555555555558p-2}}}},
    {TetVertices{{{0x0.0p+0, 0x1.5555555555557p-2, 0x1.5555555555557p-2}, {0x0.0p+0, 0x0.0p+0, 0x1.5555555555555p-1}, {0x1.5555555555557p-2, 0x0.0p+0, 0x1.5555555555557p-2}, {0x1.5555555555555p-2, 0x0.0p+0, 0x1.5555555555556p-1}}},
     TetVertices{{{0x1.5555555555555p-2, 0x1.5555555555557p-2, 0x1.5555555555557p-2}, {0x1.5555555555555p-2, 0x0.0p+0, 0x1.5555555555555p-1}, {0x1.5555555555555p-1, 0x0.0p+0, 0x1.5555555555556p-1}, {0x1.5555555555555p-2, 0x1.5555555555555p-2, 0x1.5555555555556p-1}}}},
    {TetVertices{{{0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.5555555555556p-1, 0x1.5555555555559p-1, 0x1.5555555555558p-2}, {0x1.5555555555555p-1, 0x1.0000000000005p+0, 0x1.5555555555557p-2}, {0x1.5555555555555p-2, 0x1.0000000000000p+0, 0x1.5555555555557p-2}}},
     TetVertices{{{0x1.5555555555555p-2, 0x1.5555555555554p+0, 0x1.5555555555555p-2}, {0x1.5555555555555p-2, 0x1.0000000000000p+0, 0x1.5555555555555p-1}, {0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x1.5555555555557p-2}, {0x1.5555555555556p-1, 0x1.0000000000000p+0, 0x1.5555555555556p-1}}}},
    {TetVertices{{{0x1.aaaaaaaaaaaacp+0, 0x1.0000000000000p+0, 0x1.5555555555557p-2}, {0x1.aaaaaaaaaaaacp+0, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.5555555555554p+0, 0x1.5555555555554p+0, 0x0.0p+0}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555554p+0, 0x0.0p+0}}},
     TetVertices{{{0x1.5555555555555p+0, 0x1.5555555555554p+0, 0x0.0p+0}, {0x1.0000000000000p+0, 0x1.5555555555554p+0, 0x0.0p+0}, {0x1.5555555555555p+0, 0x1.0000000000000p+0, 0x1.5555555555553p-2}, {0x1.0000000000000p+0, 0x1.5555555555558p+0, 0x1.5555555555557p-2}}}},
    {TetVertices{{{0x1.5555555555558p+0, 0x1.0000000000000p+0, 0x1.5555555555557p-1}, {0x1.5555555555554p+0, 0x1.5555555555555p-1, 0x1.0000000000000p+0}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555557p-1, 0x1.5555555555555p-1}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555555p-1, 0x1.0000000000000p+0}}},
     TetVertices{{{0x1.aaaaaaaaaaaa9p+0, 0x1.5555555555558p-1, 0x1.555555555555ap-1}, {0x1.aaaaaaaaaaaa9p+0, 0x1.555555555555ap-1, 0x1.555555555555ap-2}, {0x1.5555555555555p+0, 0x1.0000000000000p+0, 0x1.5555555555553p-2}, {0x1.aaaaaaaaaaaa9p+0, 0x1.0000000000000p+0, 0x1.5555555555557p-2}}}},
    {TetVertices{{{0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.5555555555556p-1, 0x1.5555555555559p-1, 0x1.5555555555558p-2}, {0x1.5555555555555p-1, 0x1.0000000000005p+0, 0x1.5555555555557p-2}, {0x1.5555555555555p-2, 0x1.0000000000000p+0, 0x1.5555555555557p-2}}},
     TetVertices{{{0x1.5555555555555p-1, 0x1.5555555555554p+0, 0x0.0p+0}, {0x1.5555555555555p-1, 0x1.0000000000000p+0, 0x1.5555555555557p-2}, {0x1.0000000000000p+0, 0x1.0000000000000p+0, 0x0.0p+0}, {0x1.0000000000000p+0, 0x1.0000000000005p+0, 0x1.5555555555557p-2}}}},
    {TetVertices{{{0x1.0000000000000p+0, 0x1.5555555555554p+0, 0x1.5555555555553p-1}, {0x1.0000000000000p+0, 0x1.5555555555558p+0, 0x1.5555555555553p-2}, {0x1.0000000000000p+0, 0x1.aaaaaaaaaaaa8p+0, 0x1.5555555555553p-2}, {0x1.5555555555554p+0, 0x1.5555555555558p+0, 0x1.5555555555558p-2}}},
     TetVertices{{{0x1.0000000000000p+0, 0x1.5555555555558p+0, 0x1.5555555555557p-2}, {0x1.0000000000001p+0, 0x1.0000000000000p+0, 0x1.5555555555556p-1}, {0x1.5555555555555p+0, 0x1.0000000000000p+0, 0x1.5555555555553p-2}, {0x1.5555555555555p+0, 0x1.0000000000000p+0, 0x1.5555555555553p-1}}}},
    {TetVertices{{{0x1.5555555555554p+0, 0x1.5555555555558p-1, 0x1.555555555555ap-1}, {0x1.5555555555554p+0, 0x1.5555555555555p-2, 0x1.0000000000000p+0}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555557p-2, 0x1.5555555555556p-1}, {0x1.aaaaaaaaaaaacp+0, 0x1.5555555555555p-2, 0x1.0000000000000p+0}}},
     TetVertices{{{0x1.0000000000000p+0, 0x1.5555555555557p-1, 0x1.5555555555559p-1}, {0x1.0000000000000p+0, 0x1.5555555555557p-2, 0x1.0000000000000p+0}, {0x1.5555555555555p+0, 0x1.5555555555555p-2, 0x1.0000000000000p+0}, {0x1.0000000000000p+0, 0x1.5555555555556p-1, 0x1.0000000000000p+0}}}},
    {TetVertices{{{0x1.0000000000000p+0, 0x1.5555555555554p+0, 0x1.5555555555553p-1}, {0x1.0000000000000p+0, 0x1.5555555555558p+0, 0x1.5555555555553p-2}, {0x1.0000000000000p+0, 0x1.aaaaaaaaaaaa8p+0, 0x1.5555555555553p-2}, {0x1.5555555555554p+0, 0x1.5555555555558p+0, 0x1.5555555555558p-2}}},
     TetVertices{{{0x1.5555555555555p+0, 0x1.5555555555554p+0, 0x0.0p+0}, {0x1.5555555555555p+0, 0x1.0000000000000p+0, 0x1.5555555555553p-2}, {0x1.5555555555555p+0, 0x1.5555555555558p+0, 0x1.5555555555553p-2}, {0x1.0000000000000p+0, 0x1.5555555555558p+0, 0x1.5555555555557p-2}}}},
};

// expansion_heights on face labels (compensated_heights.h: over the pair's integer frame): a
// Kuhn grid of cell 1/3 against its copy moved by one cell in x (each coordinate i/3 + 1/3
// rounded once) and the contacts made by two roundings above. Every face candidate's heights and
// normal lie within their certified bounds of the definition's rationals (n = (t1 − t0) × (t2 −
// t0) outward for FV, into B for VF; heights about the face's first vertex, the face's own three
// exactly 0), the bounds not vacuous; and every case-2 value of those candidates below 1e-40 of
// the squared extent (where the double words' 25 u² M term exceeds the heights at the plane) is
// certified on its own (definitions §8) and holds the exact value. Measured: 960 face
// candidates, worst error 0.81 of its bound; 10 case-2 values below 1e-40, every one certified
// (two of them where the double words give no value at all).
BOOST_AUTO_TEST_CASE(face_heights_exact_over_the_frame) {
  const double h = 1.0 / 3;
  int faces = 0, wrong = 0, not_zero = 0, tiny = 0, tiny_certified = 0, outside = 0;
  double worst = 0;
  std::vector<std::pair<TetVertices, TetVertices>> pairs = shifted_kuhn_pairs(h, {h, 0, 0});
  for (const auto& p : kTwoRoundingContacts) pairs.push_back(p);
  for_each_candidate(pairs, [&](const detail::ScaledPair& sp, const detail::ExactFrame& f, const Candidate& c) {
    if (c.label.kind == ContactKind::EE) return;
    const bool fv = c.label.kind == ContactKind::FV;
    const TetVertices& T = fv ? sp.A : sp.B;
    const auto& F = kFace[c.label.a];
    auto d = [](const Vec3d& p, const Vec3d& q) {
      return std::array<Q, 3>{Q(p[0]) - Q(q[0]), Q(p[1]) - Q(q[1]), Q(p[2]) - Q(q[2])};
    };
    auto dot = [](const std::array<Q, 3>& a, const std::array<Q, 3>& b) -> Q {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const std::array<Q, 3> e1 = d(T[F[1]], T[F[0]]), e2 = d(T[F[2]], T[F[0]]);
    std::array<Q, 3> n;
    for (int k = 0; k < 3; ++k) n[k] = e1[(k + 1) % 3] * e2[(k + 2) % 3] - e1[(k + 2) % 3] * e2[(k + 1) % 3];
    const bool outward = sgn(dot(n, d(T[c.label.a], T[F[0]]))) < 0;
    if (outward != fv)  // FV: outward of A; VF: into B
      for (Q& x : n) x = -x;
    detail::CompensatedHeights hh;
    BOOST_TEST_REQUIRE(detail::expansion_heights(sp.A, sp.B, c, hh), c.label.str());
    ++faces;
    auto check = [&](double computed, double bound, const Q& exact) {
      const Q err = abs(Q(computed) - exact);
      if (err > Q(bound)) ++wrong;
      if (bound > 0) worst = std::max(worst, Q(err / Q(bound)).get_d());
    };
    for (int i = 0; i < 4; ++i) {
      check(hh.hA[i], hh.eA[i], dot(n, d(sp.A[i], T[F[0]])));
      check(hh.hB[i], hh.eB[i], dot(n, d(sp.B[i], T[F[0]])));
    }
    for (int k = 0; k < 3; ++k) check(hh.n[k], hh.e_n, n[k]);
    for (int j = 0; j < 3; ++j) not_zero += (fv ? hh.hA[F[j]] : hh.hB[F[j]]) != 0.0;
    const Q exact = detail::unscaled(f, detail::exact_deformable_value(detail::exact_candidate(f, c.label)), 2);
    if (!(exact < Q(1e-40))) return;
    ++tiny;
    double v = 0, r = 0;
    if (!compensated_value(sp.A, sp.B, c, QpKind::Deformable, v, r, nullptr)) return;
    tiny_certified += certified_choice(upper_of(v, r), lower_of(v, r));
    if (exact < Q(lower_of(v, r)) || exact > Q(upper_of(v, r))) ++outside;
  });
  BOOST_TEST_MESSAGE("face heights over the frame: " << faces << " face candidates, worst error / bound " << worst
                                                     << "; " << tiny << " case-2 values below 1e-40, " << tiny_certified
                                                     << " certified");
  BOOST_TEST(wrong == 0);
  BOOST_TEST(not_zero == 0);
  BOOST_TEST(faces > 900);
  BOOST_TEST(worst > 0.1);  // not vacuous: a bound a tenth as wide would fail
  BOOST_TEST(worst <= 1.0);
  BOOST_TEST(tiny >= 10);
  BOOST_TEST(tiny_certified == tiny);
  BOOST_TEST(outside == 0);
}

// compensated_value (deformable_depth.h), the intervals refine.h's contenders certify on: for
// every candidate and each of the three QPs (case 1 where the candidate is in its family, case
// 2, relaxed) on degenerate contacts (a Kuhn grid against its copy shifted half a cell along
// (1, 1, 1)), contacts made by rounding, Kuhn cells shifted by a non-dyadic offset and shallow
// random contacts, the exact value (exact_candidate.h's rationals) lies in [lower_of(v, r),
// upper_of(v, r)], for verified patterns and bracketed values alike; the bracket (weak duality
// around a margin exactly at its threshold) is taken on the degenerate contacts and certifies
// there (its interval within definitions §8 on its own).
BOOST_AUTO_TEST_CASE(compensated_values_contain_the_exact_value) {
  // degenerate contacts: h = 1/4 shifted by half a cell along (1, 1, 1), exactly (B's vertices
  // on A's cube diagonals, B's diagonal faces in A's diagonal planes)
  std::vector<std::pair<TetVertices, TetVertices>> pairs = shifted_kuhn_pairs(0.25, {0.125, 0.125, 0.125});
  const std::size_t half = pairs.size();
  for (const TetPair& p : pdd::test::rounding_contact_pairs(2, 60)) pairs.emplace_back(p.A, p.B);
  for (const auto& p : shifted_kuhn_pairs()) pairs.push_back(p);
  Rng rng(29);
  for (int trial = 0; trial < 200; ++trial) {
    TetVertices A = random_tet(rng, 10), B = random_tet(rng, 10);
    if (shallow(A, B, 10 * std::pow(10.0, -rng.uniform(3, 12)))) pairs.emplace_back(A, B);
  }
  int checked = 0, outside = 0, bracketed = 0, bracketed_certified = 0;
  for_each_candidate(pairs, [&](const detail::ScaledPair& sp, const detail::ExactFrame& f, const Candidate& c) {
    std::optional<detail::ExactCandidate> x;
    for (QpKind kind : {QpKind::Static, QpKind::Deformable, QpKind::Relaxed}) {
      double v = 0, r = 0;
      bool b = false;
      if (!compensated_value(sp.A, sp.B, c, kind, v, r, &b)) continue;
      if (!x) x = detail::exact_candidate(f, c.label);
      const Q q = kind == QpKind::Static       ? detail::exact_static_value(*x)
                  : kind == QpKind::Deformable ? detail::exact_deformable_value(*x)
                                               : detail::exact_relaxed_value(*x);
      const Q exact = detail::unscaled(f, q, 2);
      if (exact < Q(lower_of(v, r)) || exact > Q(upper_of(v, r))) ++outside;
      ++checked;
      if (b) ++bracketed, bracketed_certified += certified_choice(upper_of(v, r), lower_of(v, r));
    }
  });
  BOOST_TEST_MESSAGE("compensated values: " << checked << " on " << pairs.size() << " pairs (" << half
                                            << " degenerate), " << bracketed << " bracketed, "
                                            << bracketed_certified << " of them certified");
  BOOST_TEST(outside == 0);
  BOOST_TEST(checked > 10000);
  BOOST_TEST(bracketed > 100);
  BOOST_TEST(bracketed_certified == bracketed);
}

// compensated_value's edge pairs on contacts made by rounding (a Kuhn grid of cell 0.1 against
// its copy shifted by a quarter cell along (1, 1, 1): edges parallel up to the rounding of the
// shift, case-2 values ~1e-33 to 1e-66 of the squared cell): the double words' u² M term
// exceeds such heights at the plane, and the interval is then taken on the exact heights by
// expansions (expansion_heights), which certifies it on its own (definitions §8) and holds the
// exact value (exact_candidate.h's rationals). Measured: 2,022 such edge-pair values, every one
// certified (2,004 on the double words alone: the 18 others have e_i ~1e-31 beside heights
// ~1e-32 at the plane).
BOOST_AUTO_TEST_CASE(rounding_contact_edge_pairs_certify_on_exact_heights) {
  int tiny = 0, certified = 0, outside = 0;
  for_each_candidate(shifted_kuhn_pairs(0.1, {0.025, 0.025, 0.025}),
                     [&](const detail::ScaledPair& sp, const detail::ExactFrame& f, const Candidate& c) {
    if (c.label.kind != ContactKind::EE) return;
    const Q exact = detail::unscaled(f, detail::exact_deformable_value(detail::exact_candidate(f, c.label)), 2);
    if (!(exact > 0 && exact < Q(1e-30))) return;  // a contact made by rounding
    ++tiny;
    double v = 0, r = 0;
    if (!compensated_value(sp.A, sp.B, c, QpKind::Deformable, v, r, nullptr)) return;
    const double lo = lower_of(v, r), hi = upper_of(v, r);
    if (!certified_choice(hi, lo) || !std::isfinite(hi)) return;  // (r = inf: no bound to check)
    ++certified;
    if (exact < Q(lo) || exact > Q(hi)) ++outside;
  });
  BOOST_TEST_MESSAGE("contacts made by rounding: " << tiny << " edge-pair case-2 values, " << certified
                                                   << " certified on their own");
  BOOST_TEST(outside == 0);
  BOOST_TEST(tiny > 500);
  BOOST_TEST(certified == tiny);
}

// compensated_value's nearly parallel edge pairs on a resting contact: Kuhn blocks resting on
// each other's columns 1e-9 deep, the whole scene turned 0.3 rad about (1, 2, 3), so that B's
// bottom edges are translates of A's top edges only up to a rounding (their exact normal is
// taken by expansion_heights). Relative to A's edge (a cell away from the contact along a
// vertical edge) the heights at the plane would carry u of the cell, ~1e-7 of the depth, and no
// such interval certified on its own; relative to A's vertex highest along the normal they carry
// u of the depth. Every relaxed value of these edge pairs ~1e-20 (the resting contact's, not
// a contact made by rounding's) is certified on its own and holds the exact value.
BOOST_AUTO_TEST_CASE(resting_edge_pairs_certify_near_their_plane) {
  std::vector<std::pair<TetVertices, TetVertices>> pairs;
  for (const TetPair& p : pdd::test::turned_column_resting_pairs(4, 1e-9, 300)) pairs.emplace_back(p.A, p.B);
  int resting = 0, certified = 0, outside = 0;
  for_each_candidate(pairs, [&](const detail::ScaledPair& sp, const detail::ExactFrame& f, const Candidate& c) {
    if (c.label.kind != ContactKind::EE || !(c.parallel || c.own_bounds)) return;
    const Q exact = detail::unscaled(f, detail::exact_relaxed_value(detail::exact_candidate(f, c.label)), 2);
    if (!(exact > Q(1e-25) && exact < Q(1e-15))) return;  // the resting contact's
    ++resting;
    double v = 0, r = 0;
    if (!compensated_value(sp.A, sp.B, c, QpKind::Relaxed, v, r, nullptr)) return;
    const double lo = lower_of(v, r), hi = upper_of(v, r);
    if (exact < Q(lo) || exact > Q(hi)) ++outside;
    certified += certified_choice(hi, lo);
  });
  BOOST_TEST_MESSAGE("resting contact: " << resting << " nearly parallel edge-pair relaxed values, " << certified
                                         << " certified on their own");
  BOOST_TEST(outside == 0);
  BOOST_TEST(resting > 100);
  BOOST_TEST(certified == resting);
}

// value_on_heights' bracket (deformable_depth.cpp) near degeneracy, where the two patterns it
// brackets with differ: random heights (n.n = 1) with constrained sets of each kind (a face of A
// at 0, or an edge of each side, or none), one free vertex moved to its exact threshold (margin
// 0 for the exact solution, direction_qp_impl.h in rationals) and then by delta, |delta| <= e, of
// either sign; that vertex's given height is the rounded threshold and its bound e_i = e, so
// its margin is not certain and its exact status is either. For each of the three QPs the
// reported interval holds the exact value of the exact heights H*, bracketed or not.
BOOST_AUTO_TEST_CASE(bracketed_values_hold_near_degenerate_heights) {
  Rng rng(1129);
  int tried = 0, valued = 0, bracketed = 0, outside = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int shape = trial % 3;  // 0: A's face at 0; 1: an edge each side; 2: none (relaxed)
    const QpKind kind = shape == 2 ? QpKind::Relaxed : (trial / 3) % 2 ? QpKind::Static : QpKind::Deformable;
    const unsigned conA = shape == 0 ? 0x7u : shape == 1 ? 0x3u : 0u, conB = shape == 1 ? 0x3u : 0u;
    detail::ExactCandidate x;
    x.nn = 1;
    x.conA = conA, x.conB = conB;
    double hA[4], hB[4];
    const double hb = rng.uniform(-0.5, 0.5);  // B's constrained height (an edge)
    for (int i = 0; i < 4; ++i) {
      hA[i] = conA >> i & 1u ? 0.0 : rng.uniform(-1, 0.5);
      hB[i] = conB >> i & 1u ? hb : rng.uniform(-0.5, 1);
    }
    for (int i = 0; i < 4; ++i) x.hA[i] = hA[i], x.hB[i] = hB[i];
    // the exact solution, and a free vertex moved to its threshold (its margin C - H + S = 0)
    const Solution<Q> s0 = kind == QpKind::Relaxed ? detail::solve_relaxed_heights(x.hA, x.hB)
                           : kind == QpKind::Static
                               ? detail::solve_static_sides(side_of(x.hA, conA), side_of(x.hB, conB))
                               : detail::solve_deformable_sorted(side_of(x.hA, conA), side_of(x.hB, conB));
    const bool on_a = kind != QpKind::Static && rng.integer(0, 1) == 0;
    const unsigned con = on_a ? conA : conB;
    int v = int(rng.integer(0, 3));
    for (int t = 0; t < 4 && (con >> v & 1u); ++t) v = (v + 1) % 4;
    if (con >> v & 1u) continue;
    const Q threshold = s0.c + (on_a ? s0.sumA : s0.sumB);
    const double rounded = threshold.get_d(), e = 1e-9;
    (on_a ? hA : hB)[v] = rounded;
    (on_a ? x.hA : x.hB)[v] = Q(rounded) + Q(rng.uniform(-e, e));  // H*: the exact heights
    detail::CompensatedHeights h;
    for (int i = 0; i < 4; ++i) h.hA[i] = hA[i], h.hB[i] = hB[i], h.eA[i] = h.eB[i] = 0;
    (on_a ? h.eA : h.eB)[v] = e;
    h.n[0] = 1, h.n[1] = h.n[2] = 0, h.nn = 1, h.e_n = 0;
    ++tried;
    double value = 0, r = 0;
    bool b = false;
    if (!value_on_heights(h, conA, conB, kind, value, r, &b)) continue;
    ++valued;
    bracketed += b;
    const Q exact = kind == QpKind::Static       ? detail::exact_static_value(x)
                    : kind == QpKind::Deformable ? detail::exact_deformable_value(x)
                                                 : detail::exact_relaxed_value(x);
    if (exact < Q(lower_of(value, r)) || exact > Q(upper_of(value, r))) ++outside;
  }
  BOOST_TEST_MESSAGE("near degenerate heights: " << tried << " tried, " << valued << " valued, " << bracketed
                                                 << " bracketed");
  BOOST_TEST(outside == 0);
  BOOST_TEST(bracketed > 1000);
}

// kernel/pair_memo.h: an answer is computed once per pair and key; a pair differing in one
// bit of one coordinate (here -0.0 against 0.0) is another pair; keys beyond its room are
// computed every time, never confused.
// compensated_height_sign against the exact sign of ((p1 − p0) x (q1 − q0)).(p − q) (rationals):
// every face plane of one Kuhn cell against every edge of the other, on grids shifted by an
// offset with no short binary form (edges in the plane up to the rounding of the shift: the
// heights ~1e-17 of the cell that the double words are for), by a dyadic offset (exact zeros:
// never decided) and at scales 2^-300 to 2^300 (underflow's absolute terms; no overflow), and
// random points. Decided only with the exact sign; undecided only near 0.
BOOST_AUTO_TEST_CASE(compensated_height_signs_are_exact) {
  auto exact_sign = [](const Vec3d& p1, const Vec3d& p0, const Vec3d& q1, const Vec3d& q0, const Vec3d& p,
                       const Vec3d& q) {
    Q e[3], f[3], d[3];
    for (int k = 0; k < 3; ++k) e[k] = Q(p1[k]) - Q(p0[k]), f[k] = Q(q1[k]) - Q(q0[k]), d[k] = Q(p[k]) - Q(q[k]);
    Q h = 0;
    for (int k = 0; k < 3; ++k) h += (e[(k + 1) % 3] * f[(k + 2) % 3] - e[(k + 2) % 3] * f[(k + 1) % 3]) * d[k];
    return sgn(h);
  };
  long decided = 0, undecided = 0, zeros = 0, tiny_decided = 0;
  auto check = [&](const TetVertices& A, const TetVertices& B) {
    for (int f = 0; f < 4; ++f) {
      const auto& F = kFace[f];
      const detail::CompensatedNormal n = detail::compensated_normal(A[F[1]], A[F[0]], A[F[2]], A[F[0]]);
      for (int e = 0; e < 6; ++e) {
        const Vec3d &p = B[kEdges[e][1]], &q = B[kEdges[e][0]];
        const int want = exact_sign(A[F[1]], A[F[0]], A[F[2]], A[F[0]], p, q);
        int got = 0;
        if (detail::compensated_height_sign(n, p, q, got)) {
          BOOST_TEST_REQUIRE(got == want);
          ++decided;
          // a height far below the doubles' own bound (u of the products): what they are for
          double m = 0;
          for (int k = 0; k < 3; ++k) m += std::fabs(n.n[k].hi) * std::fabs(p[k] - q[k]);
          const double h = n.n[0].hi * (p[0] - q[0]) + n.n[1].hi * (p[1] - q[1]) + n.n[2].hi * (p[2] - q[2]);
          tiny_decided += std::fabs(h) < 1e-14 * m;
        } else {
          ++undecided;
          zeros += want == 0;
        }
      }
    }
  };
  for (double scale : {1.0, 0x1p-300, 0x1p300})
    for (const Vec3d& shift : {Vec3d{0.37 * 0.125, 0.21 * 0.125, 0.13 * 0.125}, Vec3d{0.1, 0.1, 0.1},
                               Vec3d{0.0625, 0.03125, 0.0}})
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          TetVertices A = pdd::test::kuhn_cell_tet({0, 0, 0}, 0.125, i);
          TetVertices B = pdd::test::kuhn_cell_tet(shift, 0.125, j);
          for (auto* T : {&A, &B})
            for (auto& v : *T)
              for (double& x : v) x *= scale;
          check(A, B);
          check(B, A);
        }
  Rng rng(29);
  for (int t = 0; t < 2000; ++t) check(random_tet(rng, 1.0), random_tet(rng, 1.0));
  BOOST_TEST_MESSAGE("compensated height signs: " << decided << " decided (" << tiny_decided
                     << " below 1e-14 of their terms), " << undecided << " left to the exact sign (" << zeros
                     << " exact zeros)");
  BOOST_TEST(tiny_decided > 100);
  BOOST_TEST(zeros > 100);
}

BOOST_AUTO_TEST_CASE(pair_memo_keys_the_pair) {
  detail::PairMemo<int, 2> memo;
  TetVertices A{}, B{};
  B[3][2] = 1;
  int calls = 0;
  auto get = [&](const TetVertices& b, unsigned key) {
    int v = -1;
    const bool ok = memo.get(A, b, key, v, [&](int& out) {
      ++calls;
      out = int(key) * 10 + int(std::signbit(b[0][0]));
      return key != 3;
    });
    return std::make_pair(ok, v);
  };
  BOOST_TEST((get(B, 1) == std::make_pair(true, 10)));
  BOOST_TEST((get(B, 1) == std::make_pair(true, 10)));
  BOOST_TEST(calls == 1);
  BOOST_TEST((get(B, 3) == std::make_pair(false, 30)));  // a false verdict kept too
  BOOST_TEST((get(B, 3) == std::make_pair(false, 30)));
  BOOST_TEST(calls == 2);
  BOOST_TEST((get(B, 5) == std::make_pair(true, 50)));  // no room: computed each time
  BOOST_TEST((get(B, 5) == std::make_pair(true, 50)));
  BOOST_TEST(calls == 4);
  TetVertices B2 = B;
  B2[0][0] = -0.0;
  BOOST_TEST((get(B2, 1) == std::make_pair(true, 11)));  // another pair: computed afresh
  BOOST_TEST(calls == 5);
  BOOST_TEST((get(B, 1) == std::make_pair(true, 10)));
  BOOST_TEST(calls == 6);
  // a computation that asks the memo of another pair: its answer is not kept for that pair
  int v = 0;
  memo.get(A, B, 7, v, [&](int& out) {
    int w = 0;
    memo.get(A, B2, 8, w, [](int& o) { return o = 1, true; });
    return out = 2, true;
  });
  int again = 0;
  memo.get(A, B2, 7, again, [](int& o) { return o = 3, true; });
  BOOST_TEST(v == 2);
  BOOST_TEST(again == 3);  // computed for B2, not B's answer
}
