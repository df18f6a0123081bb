// fast_candidates_test — the candidate set of definitions §3 against exact (GMP) decisions.
#define BOOST_TEST_MODULE fast_candidates
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "certification/value_bounds.h"
#include "exact/exact_candidate.h"
#include "exact/exact_predicates.h"
#include "fast_test_util.h"
#include "kernel/candidate_directions.h"
#include "kernel/quick_candidates.h"
#include "structured_cells.h"

using namespace pdd;
using namespace pdd::fast;
using namespace pdd::fast::test;

namespace {

// Expected EE labels of edge pair (a, b) from the exact classification.
int expected_ee_count(const EdgePairClass& c) {
  if (c.kind == EdgePairKind::Colinear) return 0;
  return c.side == EdgePairSide::Undecidable ? 2 : 1;
}

// Edge pairs marked along a face of A (CandidateSet::along_face), over every set checked.
int along_face_checked = 0;

// Candidate k marked along face f of A: a decided edge pair whose edge a lies on face f, its
// exact direction FV:f's (same_direction_exact) and so its depth's sign, and each variant's exact value at or above
// FV:f's (deformable_depth.h's proof, on the rationals of exact_candidate.h).
void check_along_face(const TetPair& p, const CandidateSet& set, int k) {
  const int f = set.along_face[k];
  const DirectionLabel l = label(set, k), face = DirectionLabel::fv(f);
  BOOST_TEST((l.kind == ContactKind::EE && l.orientation == EdgeOrientation::Decided));
  BOOST_TEST((kEdges[l.a][0] != f && kEdges[l.a][1] != f));  // edge a on the face opposite s_f
  const std::optional<bool> same = same_direction_exact(p.A, p.B, l, face);
  BOOST_TEST((same.has_value() && *same), l.str() << " along " << face.str());
  // build_candidates takes its depth's sign from FV:f's instead of deciding it (depth_positive)
  BOOST_TEST((depth_sign_exact(p.A, p.B, l) == depth_sign_exact(p.A, p.B, face)), l.str());
  const detail::ExactFrame frame = detail::exact_frame(p.A, p.B);
  const detail::ExactCandidate e = detail::exact_candidate(frame, l), c = detail::exact_candidate(frame, face);
  BOOST_TEST(detail::exact_static_value(e) >= detail::exact_static_value(c));
  BOOST_TEST(detail::exact_deformable_value(e) >= detail::exact_deformable_value(c));
  BOOST_TEST(detail::exact_relaxed_value(e) >= detail::exact_relaxed_value(c));
  ++along_face_checked;
}

// Walks the set in order and checks every label against the exact classification; returns
// the number of candidates accounted for.
void check_against_exact(const TetPair& p, const CandidateSet& set, bool check_depths) {
  for (int k = 0; k < set.count; ++k)
    if (set.along_face[k] >= 0) check_along_face(p, set, k);
  int idx = 0;
  for (int i = 0; i < 4; ++i) BOOST_TEST(label(set, idx++).str() == "FV:" + std::to_string(i));
  for (int j = 0; j < 4; ++j) BOOST_TEST(label(set, idx++).str() == "VF:" + std::to_string(j));
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const EdgePairClass c = classify_edge_pair_exact(p.A, p.B, a, b);
      const int m = expected_ee_count(c);
      if (m == 1) BOOST_TEST(label(set, idx) == DirectionLabel::ee(a, b));
      if (m == 2) {
        BOOST_TEST(label(set, idx) == DirectionLabel::ee(a, b, EdgeOrientation::Plus));
        BOOST_TEST(label(set, idx + 1) == DirectionLabel::ee(a, b, EdgeOrientation::Minus));
      }
      idx += m;
    }
  BOOST_TEST(idx == set.count);
  if (!check_depths) return;
  for (int k = 0; k < set.count; ++k)
    BOOST_TEST((depth_sign_exact(p.A, p.B, label(set, k)) == (set.depth[k] > 0 ? Sign::Positive : Sign::Negative)));
}

// Kuhn tetrahedron m of the cube of side h at o (the path 0 -> e_p0 -> e_p0 + e_p1 -> (1, 1, 1)
// for the m-th permutation p of the axes), vertex v's coordinate k then moved by ulps(v, k) ulps.
template <class Ulps>
TetVertices kuhn_tet(int m, const std::array<double, 3>& o, double h, Ulps ulps) {
  static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  TetVertices T;
  double d[3] = {0, 0, 0};
  for (int v = 0; v < 4; ++v) {
    if (v > 0) d[kPerm[m][v - 1]] = h;
    for (int k = 0; k < 3; ++k) {
      double x = o[k] + d[k];
      for (int u = ulps(v, k); u != 0; u += u > 0 ? -1 : 1) x = std::nextafter(x, u > 0 ? HUGE_VAL : -HUGE_VAL);
      T[v][k] = x;
    }
  }
  return T;
}

// The pair's candidate set against the exact classification (check_against_exact); then
// lane(set, k, l) for each edge candidate k written from a lane l whose filter verdict was
// unclear. Returns 1 when the pair intersects (checked), else 0.
template <class Lane>
int checked_unclear_lanes(const TetPair& p, Lane lane) {
  CandidateSet set;
  BOOST_TEST((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
  if (!set.intersecting) return 0;
  check_against_exact(p, set, true);
  for (int k = 8; k < set.count; ++k) {
    const int l = set.lane[k];
    if (l >= 0 && set.edges.unclear[l] != 0.0) lane(set, k, l);
  }
  return 1;
}

}  // namespace

// Random intersecting pairs: labels, order, count = 44 + undecidable − colinear, and the sign
// of every depth D against the exact engine's arithmetic.
BOOST_AUTO_TEST_CASE(random_pairs_match_exact_decisions) {
  int undecidable = 0;
  for (const TetPair& p : random_pairs(40, 3, true)) {
    CandidateSet set;
    BOOST_TEST((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
    BOOST_TEST(set.intersecting);
    check_against_exact(p, set, true);
    undecidable += set.count - 44;
  }
  BOOST_TEST(undecidable > 0);  // the random set exercises the ':+'/':-' branch
}

// exact_candidate(frame, label) builds a label's normal, n.n, heights and D on the frame's
// integers (mpz); the same candidate from exact_geometry.h's rational formulas (face normals,
// edge-pair normal with its parallel case, the orientation rule) through the rational
// overload must be equal, component for component: random pairs, Kuhn cells with parallel and
// colinear edges, and pairs scaled by 2^300 and 2^-300 (the frame's shift negative and large).
BOOST_AUTO_TEST_CASE(exact_candidates_on_integers_equal_the_rationals) {
  std::vector<TetPair> pairs = random_pairs(20, 7, false);
  const double h = 0.25;
  auto kuhn = [&](int m, const std::array<double, 3>& o) { return kuhn_tet(m, o, h, [](int, int) { return 0; }); };
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; j += 5) pairs.push_back(tet_pair(kuhn(i, {0, 0, 0}), kuhn(j, {h / 2, 0, h / 4})));
  for (const double scale : {0x1p300, 0x1p-300})
    for (int k = 0; k < 6; ++k) {
      TetPair q = pairs[std::size_t(k)];
      for (auto* T : {&q.A, &q.B})
        for (auto& v : *T)
          for (double& x : v) x *= scale;
      pairs.push_back(q);
    }
  int compared = 0, parallel = 0;
  for (const TetPair& p : pairs) {
    const detail::ExactFrame f = detail::exact_frame(p.A, p.B);
    auto check = [&](const DirectionLabel& l, const detail::QV& n, unsigned conA, unsigned conB) {
      const detail::ExactCandidate z = detail::exact_candidate(f, l), q = detail::exact_candidate(f, l, n, conA, conB);
      bool same = z.nn == q.nn && z.D == q.D && z.conA == q.conA && z.conB == q.conB;
      for (int k = 0; k < 3; ++k) same = same && z.n.x[k] == q.n.x[k];
      for (int i = 0; i < 4; ++i) same = same && z.hA[i] == q.hA[i] && z.hB[i] == q.hB[i];
      BOOST_TEST(same, p.name << " " << l.str());
      ++compared;
    };
    for (int a = 0; a < 4; ++a) {
      check(DirectionLabel::fv(a), detail::face_normal_out_of(f.s, a), detail::mask_without(a), 0);
      check(DirectionLabel::vf(a), detail::face_normal_into(f.r, a), 0, detail::mask_without(a));
    }
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        EdgePairKind kind;
        const detail::QV n = detail::edge_pair_normal(f.s, f.r, a, b, &kind);
        if (kind == EdgePairKind::Colinear) continue;  // (no direction: no label)
        parallel += kind == EdgePairKind::Parallel;
        const bool flip = detail::side_rule(f.s, n, a) == EdgePairSide::Flip;
        const unsigned conA = detail::edge_mask(a), conB = detail::edge_mask(b);
        check(DirectionLabel::ee(a, b, EdgeOrientation::Decided), flip ? detail::negated(n) : n, conA, conB);
        check(DirectionLabel::ee(a, b, EdgeOrientation::Plus), n, conA, conB);
        check(DirectionLabel::ee(a, b, EdgeOrientation::Minus), detail::negated(n), conA, conB);
      }
  }
  BOOST_TEST(parallel > 0);  // the Kuhn cells' parallel edges took the common perpendicular
  BOOST_TEST_MESSAGE("exact candidates compared: " << compared << ", parallel edge pairs " << parallel);
}

// Crafted: A = unit corner tet; B has edge r0r1 on A's edge line s0s1 (the x axis: colinear,
// EE:0:0 has no direction) and edge r2r3 parallel to A's edge s2s3 (direction (0,−1,1)).
// Parallel normal (definitions §3): e = s3 − s2 = (0,−1,1), w = r2 − s2 = (1/4,−3/4,1/4),
// n = (e.e) w − (w.e) e = 2w − e = (1/2,−1/2,−1/2); g for s0: n.(s0 − s2) = 1/2, for s1: 1
// (both >= 0: flip), so EE:5:5 uses n = (−1/2, 1/2, 1/2).
BOOST_AUTO_TEST_CASE(parallel_and_colinear_edges) {
  const TetPair p = tet_pair({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                              {{{-0.5, 0, 0}, {0.5, 0, 0}, {0.25, 0.25, 0.25}, {0.25, -0.25, 0.75}}});
  CandidateSet set;
  BOOST_TEST((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
  BOOST_TEST(set.intersecting);
  check_against_exact(p, set, true);
  bool found55 = false;
  for (int k = 0; k < set.count; ++k) {
    BOOST_TEST(!(label(set, k).kind == ContactKind::EE && label(set, k).a == 0 &&
                 label(set, k).b == 0));
    if (label(set, k) == DirectionLabel::ee(5, 5)) {
      found55 = true;
      const Candidate c = candidate(set, k);
      const double* n = c.n;
      BOOST_TEST(n[0] == -0.5);
      BOOST_TEST(n[1] == 0.5);
      BOOST_TEST(n[2] == 0.5);
    }
  }
  BOOST_TEST(found55);
}

// Exact zeros: A's free vertex s3 lies in the plane of an EE direction (g = 0 exactly), and
// faces with decimal coordinates whose floating-point orientation is a rounding residue
// (A and B share a face: the fast set must equal the exact decisions everywhere).
BOOST_AUTO_TEST_CASE(exact_zero_decisions) {
  const TetVertices A = {{{0.1, 0.2, 0.3}, {1.7, 0.4, 0.9}, {0.3, 1.9, 0.7}, {0.9, 0.8, 2.1}}};
  TetVertices B = A;
  for (int k = 0; k < 3; ++k) B[3][k] = (A[0][k] + A[1][k] + A[2][k]) / 3 * 0.9 + A[3][k] * 0.1;
  const TetPair p = tet_pair(A, B);
  CandidateSet set;
  BOOST_TEST((build_candidates(p.A, p.B, set) == BuildStatus::Ok));
  BOOST_TEST(set.intersecting);
  check_against_exact(p, set, true);
  // g = 0: A = unit corner, B's edge r0r1 along z through (0.25, 0.25): for A's edge s0s1 the
  // normal eB × eA is along y, and A's free s3 = (0,0,1) has g = 0 exactly.
  const TetPair q = tet_pair({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                              {{{0.25, 0.25, -1}, {0.25, 0.25, 1}, {0.5, -0.5, 0}, {-0.5, 0.5, 0.1}}});
  BOOST_TEST((build_candidates(q.A, q.B, set) == BuildStatus::Ok));
  if (set.intersecting) check_against_exact(q, set, true);
}

// Aligned pairs: Kuhn tetrahedra of a cube of side h = 1/4 (the path 0 -> e_p0 -> e_p0 + e_p1
// -> (1,1,1) for the 6 permutations p) against those of a cube shifted by t. Their edges share
// axis, face-diagonal and body-diagonal directions (exactly parallel edges, n = eB × eA = 0 with
// zero products), their faces lie in shared coordinate planes (g = 0 exactly), and the shifts
// along one axis put edges on common lines (colinear). Every label and depth sign must equal
// the exact classification.
BOOST_AUTO_TEST_CASE(aligned_kuhn_pairs_match_exact_decisions) {
  const double h = 0.25;
  auto kuhn = [&](int m, const std::array<double, 3>& o) { return kuhn_tet(m, o, h, [](int, int) { return 0; }); };
  const std::array<double, 3> shifts[] = {
      {0, 0, 0}, {h / 2, 0, 0}, {0, 0, h / 4}, {0.37 * h, 0.21 * h, 0.13 * h}, {0.37 * h, 0, 0}};
  // Lanes whose verdict is unclear only through their g's (within their bound: exactly 0 where a
  // face of A holds eB's direction, else a rounding off it) are written from their lanes
  // (build_candidates' clear_but_g): counted, those flipped with a g = 0 apart (the rule a clear
  // lane's g's never meet: 0 on neither side).
  int zero_g = 0, zero_g_flipped = 0;
  along_face_checked = 0;
  for (const auto& t : shifts) {
    int checked = 0;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        checked += checked_unclear_lanes(tet_pair(kuhn(i, {0, 0, 0}), kuhn(j, t)), [&](const CandidateSet& set, int k, int l) {
          ++zero_g;
          zero_g_flipped += set.sign[k] < 0 && label(set, k).orientation == EdgeOrientation::Decided &&
                            (set.edges.g1[l] == 0.0 || set.edges.g2[l] == 0.0);
        });
      }
    BOOST_TEST(checked > 0);  // every shift has intersecting pairs (A and B share a corner region)
  }
  BOOST_TEST_MESSAGE("lanes unclear through their g's written from their lanes: " << zero_g << ", flipped " << zero_g_flipped);
  BOOST_TEST(zero_g > 100);
  BOOST_TEST(zero_g_flipped > 10);
  // Most of those lanes lie along a face of A (the g of the face's third vertex exactly 0):
  // each checked in check_along_face (measured: 1,176 of the 1,390).
  BOOST_TEST_MESSAGE("edge pairs along a face of A: " << along_face_checked);
  BOOST_TEST(along_face_checked > 100);
  // Colinear along a body diagonal: r0 r1 lies on the line of s0 s1 = (1,1,1) (no zero
  // coordinate difference: the exact path decides w × e = (1/2,1/2,1/2) × (1,1,1) = 0).
  const TetPair q = tet_pair({{{0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {0, 1, 0}}},
                              {{{0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}, {0.5, 0.375, 0.125}, {0.375, 0.625, 0.25}}});
  CandidateSet set;
  BOOST_TEST((build_candidates(q.A, q.B, set) == BuildStatus::Ok));
  BOOST_TEST(set.intersecting);
  check_against_exact(q, set, true);
  BOOST_TEST((classify_edge_pair_exact(q.A, q.B, 0, 0).kind == EdgePairKind::Colinear));
}

// A grid a mesh generator placed up to a rounding (Gmsh's transfinite boxes: 0.1 as
// 0.09999999999999992 ... 0.1000000000000001, each node its own): the Kuhn pairs above with
// every coordinate moved by up to two ulps. Faces of A then hold B's edge directions only
// nearly: g within its filter bound but not 0, its sign decided exactly, and the lane written
// from its lane by that sign (build_candidates' clear_but_g). Every label and depth sign must
// equal the exact classification; the lanes so written are counted.
BOOST_AUTO_TEST_CASE(grid_placed_up_to_a_rounding_matches_exact_decisions) {
  const double h = 0.1;
  auto kuhn = [&](int m, const std::array<double, 3>& o, int seed) {
    return kuhn_tet(m, o, h, [seed](int v, int k) { return (seed + 7 * v + 3 * k) % 5 - 2; });
  };
  const std::array<double, 3> shifts[] = {{0.37 * h, 0.21 * h, 0.13 * h}, {h / 2, h / 2, 0}, {0, 0, h / 3}};
  int decided_g = 0, checked = 0;
  for (const auto& t : shifts)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        const TetPair p = tet_pair(kuhn(i, {0.3, 0.3, 0.3}, i), kuhn(j, {0.3 + t[0], 0.3 + t[1], 0.3 + t[2]}, j + 1));
        checked += checked_unclear_lanes(p, [&](const CandidateSet& set, int, int l) {
          const double g1 = set.edges.g1[l], g2 = set.edges.g2[l], e3 = set.fb.deg3;
          decided_g += (g1 != 0.0 && std::fabs(g1) <= e3) || (g2 != 0.0 && std::fabs(g2) <= e3);
        });
      }
  BOOST_TEST_MESSAGE("pairs checked: " << checked << "; lanes written by g signs decided exactly: " << decided_g);
  // (measured: 56 intersecting pairs, 1,491 such lanes; a lane is written so only where every g
  // within its bound has its exact sign, so none where the signs went to edge_pair_general)
  BOOST_TEST(checked > 40);
  BOOST_TEST(decided_g > 1000);
}

// Orientation / validity: exactly coplanar (decided exactly) vs. one ulp off the plane.
BOOST_AUTO_TEST_CASE(degenerate_and_nearly_degenerate) {
  const TetVertices good = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const TetVertices flat = {{{0, 0, 0.1}, {1, 0, 0.1}, {0, 1, 0.1}, {0.3, 0.3, 0.1}}};
  TetVertices almost = flat;
  almost[3][2] = std::nextafter(0.1, 1.0);
  // decimal coplanar: s3 = s0 + (s1 − s0) + (s2 − s0) computed exactly (dyadic values)
  const TetVertices dyadic_flat = {{{0.5, 0.25, 0.75}, {1.5, 0.75, 1.0}, {0.75, 1.25, 0.5},
                                    {1.75, 1.75, 0.75}}};
  CandidateSet set;
  BOOST_TEST((build_candidates(flat, good, set) == BuildStatus::DegenerateA));
  BOOST_TEST((build_candidates(good, flat, set) == BuildStatus::DegenerateB));
  BOOST_TEST((build_candidates(dyadic_flat, good, set) == BuildStatus::DegenerateA));
  BOOST_TEST((build_candidates(almost, good, set) == BuildStatus::Ok));
  BOOST_TEST((orientation_sign_exact(almost) != Sign::Zero));
}

// quick_candidates (the hot-path list, built by the superset kernel) must reproduce
// build_candidates bit for bit: same count, same labels in the same order, same delta², same
// tie band, and every materialised candidate equal (n, n.n, D, heights, constrained masks).
BOOST_AUTO_TEST_CASE(quick_candidates_match_the_set) {
  int quick = 0, intersecting = 0;
  for (const TetPair& p : random_pairs(600, 37, false)) {
    CandidateSet set;
    build_candidates(p.A, p.B, set);
    intersecting += set.intersecting;
    QuickCandidates q;
    if (!quick_candidates(p.A, p.B, q)) continue;  // callers then use the set
    ++quick;
    BOOST_REQUIRE(set.intersecting);
    BOOST_REQUIRE(q.count == set.count);
    BOOST_TEST(q.tie_kappa == set.tie_kappa);  // same tie band (tie_tolerance.h)
    for (int k = 0; k < set.count; ++k) {
      const Candidate a = candidate(q, k), c = candidate(set, k);
      BOOST_TEST(q.delta_sq[k] == set.delta_sq[k]);
      BOOST_TEST(a.label == c.label);
      BOOST_TEST((a.depth == c.depth && a.nn == c.nn && a.conA == c.conA && a.conB == c.conB));
      for (int m = 0; m < 4; ++m) BOOST_TEST((a.hA[m] == c.hA[m] && a.hB[m] == c.hB[m]));
      for (int m = 0; m < 3; ++m) BOOST_TEST(a.n[m] == c.n[m]);
    }
  }
  // every intersecting random pair is decided quickly (no degeneracy), the others are not
  BOOST_TEST(quick == intersecting);
  BOOST_TEST(quick > 100);
}

// build_candidates on a quick list must be build_candidates on the pair, bit for bit: the same
// status, count, tie band and filter bounds, the same label, depth, n.n, delta², lane, sign,
// class and own bounds for each candidate, every lane's verdict, and every materialised
// candidate equal — for a list that declined on its lanes alone (aligned pairs: exactly
// parallel edges, g's and depths within their bounds), one filled with some face depth within
// its bound (quick_lanes' all_faces: faces touching, contacts made by rounding), and a clear one
// (solve_pair builds every set from its quick lanes where they hold the faces). Pairs: the six
// Kuhn and the ten five-cut tetrahedra of a cube of decimal side 0.1 at a decimal corner,
// against those of cubes shifted by offsets that are not multiples of the side (a mesh against
// its shifted copy, stacked blocks touching), and random pairs.
BOOST_AUTO_TEST_CASE(sets_built_from_quick_lanes_match) {
  const double h = 0.1;
  const Vec3d o = {0.3, -0.7, 1.1};
  auto add_cube = [&](const Vec3d& c) {
    std::vector<TetVertices> out;
    for (int m = 0; m < 6; ++m) out.push_back(pdd::test::kuhn_cell_tet(c, h, m));
    for (int w = 0; w < 5; ++w)
      for (bool odd : {false, true}) out.push_back(pdd::test::five_cell_tet(c, h, w, odd));
    return out;
  };
  const std::vector<TetVertices> A = add_cube(o);
  const Vec3d shifts[] = {{0.025, 0, 0}, {0.05, 0.05, 0}, {0, 0, 0.1 - 0.03}, {0.025, 0.025, 0.025},
                          {0.1 / 3, 0.1 / 7, 0}, {0.1, 0.1, 0.0375}};
  std::vector<std::pair<TetVertices, TetVertices>> pairs;
  for (const Vec3d& t : shifts) {
    const std::vector<TetVertices> B = add_cube({o[0] + t[0], o[1] + t[1], o[2] + t[2]});
    for (const TetVertices& a : A)
      for (const TetVertices& b : B) pairs.push_back({a, b});
  }
  for (const TetPair& p : random_pairs(300, 17, false)) pairs.push_back({p.A, p.B});
  int declined = 0, faces_open = 0, clear = 0, intersecting = 0, exact_lanes_seen = 0, classes[3] = {0, 0, 0};
  for (const auto& [a, b] : pairs) {
    QuickCandidates q;
    const bool lanes_clear = quick_lanes(a, b, q, true);
    if (!q.faces_filled) continue;
    clear += lanes_clear;
    declined += !lanes_clear && q.count == 8;
    faces_open += q.count != 8;
    CandidateSet from_q, direct;
    BOOST_TEST((build_candidates(q, from_q) == BuildStatus::Ok));
    BOOST_TEST((build_candidates(a, b, direct) == BuildStatus::Ok));
    BOOST_REQUIRE(from_q.intersecting == direct.intersecting);
    if (!direct.intersecting) continue;
    ++intersecting;
    exact_lanes_seen += exact_lanes(direct);
    BOOST_REQUIRE(from_q.count == direct.count);
    BOOST_TEST(from_q.tie_kappa == direct.tie_kappa);
    BOOST_TEST((from_q.fb.deg2 == direct.fb.deg2 && from_q.fb.deg3 == direct.fb.deg3 &&
                from_q.fb.deg4 == direct.fb.deg4));
    for (int i = 0; i < kLanes; ++i) BOOST_TEST(from_q.edges.unclear[i] == direct.edges.unclear[i]);
    for (int k = 0; k < direct.count; ++k) {
      BOOST_TEST((from_q.code[k] == direct.code[k] && from_q.lane[k] == direct.lane[k] &&
                  from_q.sign[k] == direct.sign[k]));
      BOOST_TEST((from_q.depth[k] == direct.depth[k] && from_q.nn[k] == direct.nn[k] &&
                  from_q.delta_sq[k] == direct.delta_sq[k]));
      // (every candidate's class and bounds: lanes generic, their class's bounds unless own)
      BOOST_TEST(from_q.parallel[k] == direct.parallel[k]);
      if (direct.lane[k] >= 0) BOOST_TEST(direct.parallel[k] == 0);
      if (direct.lane[k] < 0 && k >= 8) ++classes[direct.parallel[k]];
      BOOST_TEST((from_q.e_h[k] == direct.e_h[k] && from_q.e_n[k] == direct.e_n[k]));
      if (direct.parallel[k] != 2) {
        const DegreeBounds cls = degree_bounds(direct.fb, direct.parallel[k] == 1);
        BOOST_TEST((direct.e_h[k] == cls.e_h && direct.e_n[k] == cls.e_n));
      }
      const Candidate x = candidate(from_q, k), y = candidate(direct, k);
      BOOST_TEST((x.conA == y.conA && x.conB == y.conB && x.parallel == y.parallel && x.own_bounds == y.own_bounds));
      for (int m = 0; m < 4; ++m) BOOST_TEST((x.hA[m] == y.hA[m] && x.hB[m] == y.hB[m]));
      for (int m = 0; m < 3; ++m) BOOST_TEST(x.n[m] == y.n[m]);
    }
  }
  BOOST_TEST_MESSAGE("declined on lanes: " << declined << " pairs, a face depth open: " << faces_open
                                           << ", clear: " << clear << "; " << intersecting << " intersecting, "
                                           << exact_lanes_seen << " lanes decided exactly; edge candidates stored in full: "
                                           << classes[0] << " generic, " << classes[1] << " parallel, " << classes[2]
                                           << " nearly parallel");
  BOOST_TEST(intersecting > 200);
  BOOST_TEST(exact_lanes_seen > 2000);
  for (int c : classes) BOOST_TEST(c > 50);
  BOOST_TEST((declined > 100 && faces_open > 100 && clear > 100));
}
