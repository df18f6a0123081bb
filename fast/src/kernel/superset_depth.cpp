// superset_depth.cpp — rigid PD² over the superset of candidate directions: the scan of the
// tie band and the chosen candidate (the proof is in the header, the vector arithmetic in
// superset_kernel.cpp).
#include "kernel/superset_depth.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "certification/compensated_heights.h"
#include "certification/filter_bounds.h"
#include "certification/tie_tolerance.h"
#include "certification/value_bounds.h"
#include "exact/exact_heights.h"
#include "exact/exact_predicates.h"
#include "exact/expansion.h"
#include "exact/integer_depth.h"
#include "exact/integer_heights.h"
#include "kernel/direction_geometry.h"
#include "kernel/near_parallel_bound.h"
#include "kernel/power_scale.h"
#include "kernel/superset_kernel.h"

namespace pdd::fast {
namespace {

using namespace detail;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The edge pairs left out of K's lanes (choice_without_unresolved: nearly or exactly parallel
// edges): their lane bits, each one's certified lower bound lo2 (near_parallel_bound, indexed by
// lane) and the least of those, extra_lo (+inf: none).
struct Unresolved {
  std::uint64_t bits = 0;
  double lo2[64];
  double extra_lo = kInf;
};
// None (the kernel's first pick: every edge pair in its lanes). One constant, not a temporary
// per call: value-initialising lo2 cost the hot path ~70 instructions a call.
constexpr Unresolved kNoUnresolved{};

// An entry of S near the minimum that is a real candidate: its value and label.
struct Near {
  double value;
  LabelCode code;
  int lane;      // 8a + b, or −1 for a face
  int face;      // 0..7 for a face
  double sign;   // orientation of a lane
};

// Entries with value <= t2 that are real candidates, in canonical order. An edge pair whose
// label the doubles cannot decide (n possibly 0, or an orientation sign g within the filter
// bound: definitions §3 names it `EE:a:b` or `EE:a:b:±` by that exact sign) is left out of the
// pick but not out of the certificate (tie-band entries are always among the bound bits:
// tie_and_certify_bits): the pick is then another entry, certified only if its value is within
// definitions §8's bound of every entry's lower bound, this one's included — which §8 allows
// (either side of a near tie may be named). Always true (the signature keeps the caller's test).
bool near_candidates(const SupersetLanes& K, const FilterBounds& fb, Near* out, int& count) {
  const double t2 = K.t2;
  count = 0;
  for (unsigned bits = K.face_bits; bits; bits &= bits - 1) {
    const int f = __builtin_ctz(bits);
    out[count++] = {K.face_val[f],
                    f < 4 ? pack_label(ContactKind::FV, f, 0, EdgeOrientation::Decided)
                          : pack_label(ContactKind::VF, f - 4, 0, EdgeOrientation::Decided),
                    -1, f, 1.0};
  }
  for (std::uint64_t bits = K.lane_bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / kLaneStride, b = lane % kLaneStride;
    double m0, m1, m2;
    edge_pair_normal(K.EA[0][a], K.EA[1][a], K.EA[2][a], K.EB[0][b], K.EB[1][b], K.EB[2][b], m0,
                     m1, m2);
    const double nmax = max2(std::fabs(m0), max2(std::fabs(m1), std::fabs(m2)));
    const double g1 = kOffFaces.eps[a][0] * K.G[kOffFaces.face[a][0]][b];
    const double g2 = kOffFaces.eps[a][1] * K.G[kOffFaces.face[a][1]][b];
    if (nmax <= fb.deg2 || std::fabs(g1) <= fb.deg3 || std::fabs(g2) <= fb.deg3) continue;
    const bool pos1 = g1 > 0.0, pos2 = g2 > 0.0;
    const bool flip = pos1 && pos2, undecidable = pos1 != pos2;
    const double inv = K.inv[a][b];
    const double d2p = K.dp[a][b] * K.dp[a][b] * inv, d2m = K.dm[a][b] * K.dm[a][b] * inv;
    const EdgeOrientation plus = undecidable ? EdgeOrientation::Plus : EdgeOrientation::Decided;
    const EdgeOrientation minus = undecidable ? EdgeOrientation::Minus : EdgeOrientation::Decided;
    if (!flip && d2p <= t2)
      out[count++] = {d2p, pack_label(ContactKind::EE, a, b, plus), lane, -1, 1.0};
    if ((flip || undecidable) && d2m <= t2)
      out[count++] = {d2m, pack_label(ContactKind::EE, a, b, minus), lane, -1, -1.0};
  }
  return true;
}

// The chosen edge-pair candidate, as lane_candidate builds it from the lanes.
inline __attribute__((always_inline)) void lane_geometry(const SupersetLanes& K, const Near& c, Candidate& g) {
  const int a = c.lane / kLaneStride, b = c.lane % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const int k1 = kOffEdge[a][0], k2 = kOffEdge[a][1];
  const double eA[3] = {K.EA[0][a], K.EA[1][a], K.EA[2][a]};
  double m[3];
  edge_pair_normal(eA[0], eA[1], eA[2], K.EB[0][b], K.EB[1][b], K.EB[2][b], m[0], m[1], m[2]);
  double w[3];  // r_x − s_u (sub(B[x], A[u]) on the kernel's copy of the pair)
  for (int k = 0; k < 3; ++k) w[k] = K.X[k][4 + x] - K.X[k][u];
  const double h = edge_pair_dot(m[0], m[1], m[2], w[0], w[1], w[2]);
  double q[2];
  for (int j = 0; j < 2; ++j) {
    const int f = 4 + kOffFaces.face[b][j];
    const double nb[3] = {K.NAB[0][f], K.NAB[1][f], K.NAB[2][f]};
    q[j] = off_sign_B(b, j) * dot(eA, nb);
  }
  const double s = c.sign;
  const double g1 = kOffFaces.eps[a][0] * K.G[kOffFaces.face[a][0]][b];
  const double g2 = kOffFaces.eps[a][1] * K.G[kOffFaces.face[a][1]][b];
  for (int k = 0; k < 3; ++k) g.n[k] = s * m[k];
  g.nn = edge_pair_nn(m[0], m[1], m[2]);
  g.depth = s > 0 ? K.dp[a][b] : K.dm[a][b];
  g.hA[u] = g.hA[v] = 0.0;
  g.hA[k1] = s * g1;
  g.hA[k2] = s * g2;
  g.hB[x] = g.hB[y] = s * h;
  g.hB[kOffEdge[b][0]] = s * (h + q[0]);
  g.hB[kOffEdge[b][1]] = s * (h + q[1]);
  g.conA = edge_mask(a);
  g.conB = edge_mask(b);
}

// definitions §8 (value_bounds.h) over the superset S: every entry's exact value is >= PD²
// (header), so the minimum of the entries' certified lower bounds is a lower bound of PD².
// `unique`: every entry other than the chosen one is certainly above the chosen one's exact value
// (the exact rigid direction is then the chosen candidate: what pdd2_accel(A, B, 1) needs).
// Cost: the root bound of an entry takes a division and a square root, so only the entries of
// the kernel's bound bits are bounded: the others cannot change the verdict or `unique`,
// whatever the pick (the proof is at tie_and_certify_bits in superset_kernel.cpp; tests/fast
// checks the verdict against bounding every entry). The picked entry is always among them.
// Most entries are far inside the filter range, where the root bound is tiny: a products-only
// test (small_root in certify) then stands in a fixed bound kSmallRoot for value_bounds.h's r,
// saving its chain of two divisions and a square root.
// Proof that kSmallRoot >= the r that rigid_root_rel would compute. With D² >= 4.2e22 e_h²
// up to a few roundings (computed: e_h² · 4.2e22 (1 − 2u) <= D² (1 + u); the double 4.2e22 is
// 1e-16 below 4.2e22; faces: D = sqrt(fl(v·nn)), so D² >= 4.2e22 e_h² (1 − 5u) — every such
// factor is ~1e-16 against the margin of 0.8% left below), 2 e_h/|D| <= 0.97590e-11 (1 + 4u),
// so its a = ((2 e_h + u|D|)/|D|, three roundings) <= (0.9759e-11 + u)(1 + 7u) < 0.977e-11.
// With n.n >= 3.2e22 e_n² (faces; lanes: e_n² · 3.2e22 · inv <= 1, inv = fl(1/(n.n)), so
// 3.2e22 e_n² <= (1/inv)(1 + 3u) <= fl(1/inv)(1 + 4u), the nn rigid_root_rel is given),
// rho = sqrt(3) e_n/sqrt(nn) <= sqrt(3/3.2e22)(1 + 2u) = 0.96825e-11 (1 + 2u), computed
// < 0.97e-11. Both are <= 0.01, so r = 1.02 (a + rho + 4u) (three roundings)
// < 1.02 (1.947e-11 + 4.5e-16)(1 + 3u) < 1.987e-11 < kSmallRoot. lower_of and upper_of are
// monotone in r (every rounding is), so lower_of(v, kSmallRoot) <= lower_of(v, r) and
// upper_of(v, kSmallRoot) >= upper_of(v, r): every verdict reached with it is one the exact
// bound would reach too (certified_choice is monotone in both). The cost: a verdict needs
// hi <= (1 + kCertifyRel) lo_all, and (1 + 2e-11)²/(1 − 2e-11)² < 1 + 8.1e-11, far inside
// kCertifyRel = 9e-10; `unique` (hi < lo_other) can fail where the exact r would pass when
// another entry is within ~8e-11 of the pick (2% of fast_superset_test's random pairs have
// such a near-tie): certify() then redoes the verdict with the exact bounds, so its verdict
// is always theirs. NaN: every test false, exact bound. Precondition, as for the kernel's bound
// bits: a rescaled pair (power_scale.h), so that e_h² · 4.2e22 and e_n² · 3.2e22 are normal
// (>= 2^-335; unscaled, they could underflow for L < 2^-167 and the test would be unsound).
// (Checked: every constant re-derived; on 4·10^7 inputs driven onto the tests' boundaries the
// largest rigid_root_rel is 1.98309e-11; both verdicts agree on 874,930 calls.)
constexpr double kSmallRoot = 2e-11;

// with_small: substitute kSmallRoot where small_root holds (else every bound is rigid_root_rel's).
// extra_lo: a lower bound of the values of entries outside K's bound bits (+inf: none).
inline __attribute__((always_inline)) void certify_pass(const SupersetLanes& K, const FilterBounds& fb, const Near& c, Choice& ch,
                  bool* unique, bool with_small, double extra_lo, double& hi_pick) {
  const DegreeBounds db = degree_bounds(fb, false);
  // small_root's thresholds: D² >= eh2k (faces: fl(v·nn), within 3u of the D² that
  // rigid_root_rel's D = sqrt(v·nn) has, inside the margin above); n.n >= en2k (lanes:
  // en2k · inv <= 1).
  const double eh2k = db.e_h * db.e_h * 4.2e22, en2k = db.e_n * db.e_n * 3.2e22;
  double lo_all = extra_lo, lo_other = extra_lo, r_pick = kInf;
  auto entry = [&](double v, bool small_root, auto exact_root, bool picked) {
    const double r = with_small && small_root ? kSmallRoot : exact_root();
    double lo = lower_of(v, r);
    if (!(lo >= 0.0)) lo = 0.0;
    lo_all = lo < lo_all ? lo : lo_all;
    if (picked)
      r_pick = r;
    else
      lo_other = lo < lo_other ? lo : lo_other;
  };
  for (unsigned bits = K.face_bound_bits; bits; bits &= bits - 1) {
    const int f = __builtin_ctz(bits);
    const double nn = K.NAB[0][f] * K.NAB[0][f] + K.NAB[1][f] * K.NAB[1][f] +
                      K.NAB[2][f] * K.NAB[2][f];
    const double v = K.face_val[f];
    entry(v, (eh2k <= v * nn) & (en2k <= nn),
          [&] { return rigid_root_rel(std::sqrt(v * nn), nn, db); }, c.lane < 0 && c.face == f);
  }
  for (std::uint64_t bits = K.lane_bound_bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / kLaneStride, b = lane % kLaneStride;
    const double inv = K.inv[a][b], dp = K.dp[a][b], dm = K.dm[a][b];
    const bool picked_lane = c.lane == lane;
    const bool small_n = en2k * inv <= 1.0;
    entry(dp * dp * inv, small_n & (eh2k <= dp * dp),
          [&] { return rigid_root_rel(dp, 1.0 / inv, db); }, picked_lane && c.sign > 0);
    entry(dm * dm * inv, small_n & (eh2k <= dm * dm),
          [&] { return rigid_root_rel(dm, 1.0 / inv, db); }, picked_lane && c.sign < 0);
  }
  hi_pick = upper_of(ch.value, r_pick);
  ch.certified = certified_choice(hi_pick, lo_all);
  if (unique) *unique = ch.certified && hi_pick < lo_other;
}

// The verdict with kSmallRoot, and where it fails (not certified, or not `unique` when asked)
// the verdict with every bound exact: the same verdict as the exact bounds alone give (a pass
// with kSmallRoot implies one without it, above).
// hi_pick: the pick's certified upper bound (with the exact bound where the second pass ran).
void certify(const SupersetLanes& K, const FilterBounds& fb, const Near& c, Choice& ch,
             bool* unique, double extra_lo, double& hi_pick) {
  certify_pass(K, fb, c, ch, unique, true, extra_lo, hi_pick);
  if (!ch.certified || (unique && !*unique)) certify_pass(K, fb, c, ch, unique, false, extra_lo, hi_pick);
}

// ---- `unique` through exact ties of direction (aligned pairs). A face picked on an aligned
// pair ties exactly with the parallel face of the other tetrahedron and with the edge pairs
// lying in its plane: one direction, one exact delta. When every entry of S that is not
// certainly above the pick (its certified lower bound <= the pick's upper bound hi_pick) points
// exactly the pick's way and comes after it in canonical order, the pick is still the first of
// the exact order (stable in canonical order) over the candidate list: every other entry of S
// is certainly above or tied after it; the list's other candidates (exactly parallel edge pairs,
// left out of S) have exact delta >= PD² = the pick's and, being edge pairs, come after a face.
// Those are the pairs where pdd2_accel1 needs no candidate list.
//
// Exact directions from structural zeros (candidate_directions.cpp's rule: for finite doubles a
// coordinate difference computed as 0 is exactly 0, and a product with an exactly zero factor is
// exactly 0; sufficient, not necessary, so "false" only sends the pair to the list) and signs
// of degree-3 heights that clear their filter bound E3 (every such height and every difference
// of two has computed error <= 108 u L³ < E3: near_parallel_bound.h).

// Component k of the normal (p1 − p0) × (p2 − p0) of face f of A (t = 0) or B (t = 1), p the
// face's vertices (kFace): exactly 0.
bool normal_component_zero(const SupersetLanes& K, int t, int f, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3, o = 4 * t;
  const int p0 = o + kFace[f][0], p1 = o + kFace[f][1], p2 = o + kFace[f][2];
  return ((K.X[i][p1] == K.X[i][p0]) | (K.X[j][p2] == K.X[j][p0])) &
         ((K.X[j][p1] == K.X[j][p0]) | (K.X[i][p2] == K.X[i][p0]));  // (& |: near_parallel_bound.h's cross_zero)
}

// The picked face's plane: exact heights along its normal N = (p1 − p0) × (p2 − p0) (kFace,
// the kernel's scaled coordinates) for the edges whose structural zeros leave N.(y − x) open: a
// face parallel to the pick but not along a coordinate plane (a Kuhn grid's diagonal faces),
// decided by exact_heights.h's expansions. Built on first use; undecided (an expansion over its
// capacity, a coordinate outside in_exact_range) counts as not orthogonal.
class PickPlane {
 public:
  PickPlane(const SupersetLanes& K, int face) : K_(K), t_(face / 4), f_(face % 4) {}
  // N.(y − x) = 0 exactly for vertices x, y (0..7) of the kernel's pair
  bool orthogonal(int x, int y) {
    const int o = 4 * t_;
    // over the pair's integer frame where it has one (integer_heights.h: the kernel's scaling
    // by a power of two keeps it), a few dozen instructions a sign, zeros included
    if (!frame_) {
      for (int v = 0; v < 4; ++v) a_[v] = point(v), b_[v] = point(4 + v);
      frame_.emplace(a_, b_);
    }
    if (frame_->usable())
      return frame_->height_sign(o + kFace[f_][1], o + kFace[f_][0], o + kFace[f_][2], o + kFace[f_][0], y, x) == 0;
    // else most often not: a rounding apart, which double words show (compensated_heights.h)
    if (!dw_)
      dw_ = compensated_normal(point(o + kFace[f_][1]), point(o + kFace[f_][0]), point(o + kFace[f_][2]),
                               point(o + kFace[f_][0]));
    int sign = 0;
    if (compensated_height_sign(*dw_, point(y), point(x), sign)) return false;
    if (!n_) {
      in_range_ = true;
      for (int v = 0; v < 8; ++v)
        for (int k = 0; k < 3; ++k) {
          const double a = std::fabs(K_.X[k][v]);
          in_range_ = in_range_ && (a == 0.0 || (a >= 0x1p-200 && a <= 0x1p200));
        }
      n_.emplace(point(o + kFace[f_][1]), point(o + kFace[f_][0]), point(o + kFace[f_][2]), point(o + kFace[f_][0]));
    }
    if (!in_range_ || !n_->ok) return false;
    bool ok = true;
    const int s = exact_height_sign(*n_, point(y), point(x), ok);
    return ok && s == 0;
  }

 private:
  Vec3d point(int v) const { return {K_.X[0][v], K_.X[1][v], K_.X[2][v]}; }
  const SupersetLanes& K_;
  int t_, f_;
  std::optional<CompensatedNormal> dw_;
  std::optional<LazyNormal> n_;
  bool in_range_ = false;
  TetVertices a_, b_;                    // the kernel's pair, for frame_ (filled on first use)
  std::optional<IntegerFrame> frame_;
};

// Edge e of tetrahedron te exactly orthogonal to the normal of face f of the other one, the
// pick's face (plane): every term of the dot product has an exactly zero factor; else not when
// the kernel's heights of its ends along that normal certainly differ (H, each difference of
// two within E3 of the exact one, above); else exactly.
bool edge_in_face_plane(const SupersetLanes& K, const FilterBounds& fb, int te, int e, int f, PickPlane& plane) {
  const int x = 4 * te + kEdges[e][0], y = 4 * te + kEdges[e][1];
  bool structural = true;  // (& |, not a branch a term: near_parallel_bound.h's cross_zero)
  for (int k = 0; k < 3; ++k) structural &= (K.X[k][y] == K.X[k][x]) | normal_component_zero(K, 1 - te, f, k);
  if (structural) return true;
  const int p = 4 * (1 - te) + f;
  if (!(std::fabs(K.H[kEdges[e][1]][p] - K.H[kEdges[e][0]][p]) <= fb.deg3)) return false;  // (NaN: false)
  return plane.orthogonal(x, y);
}

// Face g (FV:g for g < 4, VF:(g − 4)) points exactly the way of face p of the other tetrahedron.
// Parallel: two edges of g (edges of a triangle, never parallel) orthogonal to p's normal. The
// same way: with heights along p's direction, g's opposite vertex w lies below g's plane when g
// is A's face (FV: outward normal) and above it when g is B's (VF: B on the positive side); in
// the kernel's heights H[.][p] (face_draft: hB = −H for an A face, hA = H for a B face) both read
// H[v0][p] − H[w][p] > 0, v0 a vertex of g.
bool face_along_face(const SupersetLanes& K, const FilterBounds& fb, int p, int g, PickPlane& plane) {
  const int tg = g / 4, w = g % 4;
  if (p / 4 == tg) return false;  // two faces of one tetrahedron are never parallel
  int in_plane = 0;
  for (int e = 0; e < 6 && in_plane < 2; ++e)
    if (kEdges[e][0] != w && kEdges[e][1] != w) in_plane += edge_in_face_plane(K, fb, tg, e, p % 4, plane);
  if (in_plane < 2) return false;
  return K.H[kFace[w][0]][p] - K.H[w][p] > fb.deg3;
}

// Entry (lane, sign s) of S points exactly the way of face p. Its line: the edge of p's
// tetrahedron lies in p (p's opposite vertex is off the edge) and the other edge is orthogonal
// to p's normal, so n = eB × eA is parallel to it (n != 0: the lane is in S, not an exactly
// parallel pair). Its way: p's opposite vertex is below p's plane for an A face (s·g < 0, g its
// height in the lane, lane_geometry), above for a B face (s·q > 0).
bool lane_along_face(const SupersetLanes& K, const FilterBounds& fb, int p, int lane, double s, PickPlane& plane) {
  const int a = lane / kLaneStride, b = lane % kLaneStride;
  if (p < 4) {
    const int m = kOffEdge[a][0] == p ? 0 : kOffEdge[a][1] == p ? 1 : -1;
    if (m < 0 || !edge_in_face_plane(K, fb, 1, b, p, plane)) return false;
    const double g = kOffFaces.eps[a][m] * K.G[kOffFaces.face[a][m]][b];
    return std::fabs(g) > fb.deg3 && s * g < 0.0;
  }
  const int j = p - 4;
  const int m = kOffEdge[b][0] == j ? 0 : kOffEdge[b][1] == j ? 1 : -1;
  if (m < 0 || !edge_in_face_plane(K, fb, 0, a, j, plane)) return false;
  const int f = 4 + kOffFaces.face[b][m];
  const double eA[3] = {K.EA[0][a], K.EA[1][a], K.EA[2][a]};
  const double nb[3] = {K.NAB[0][f], K.NAB[1][f], K.NAB[2][f]};
  const double q = off_sign_B(b, m) * dot(eA, nb);
  return std::fabs(q) > fb.deg3 && s * q > 0.0;
}

// The unresolved edge pairs (un) of a face pick p that are not certainly above it (lo2 <=
// hi_pick): each must have both edges exactly orthogonal to p's normal n_p, so that its normal
// n = eB x eA is 0 (an exactly parallel pair) or along ±n_p. Then:
//  - n = 0: no facet normal of M (two parallel edges sum to a segment), so its candidate in the
//    list ties with PD only along a direction attaining PD; those are facet normals (the nearest
//    point of ∂M to the origin lies inside a facet: a ball inside M touching ∂M at an edge or a
//    vertex of M would touch two facets' planes at one point): an edge pair's candidate, after
//    the face whatever its direction (a face tying along another direction before the pick is
//    the caller's test: it refuses it).
//  - n along +n_p: the same direction, the same delta, an edge pair after the face.
//  - n along −n_p: delta(n_p) + delta(−n_p) is M's width along n_p, at least the height of the
//    pick's tetrahedron T over face p, |det T| / |n_p|; with delta(n_p) <= sqrt(hi_pick) (the
//    pick's exact value is <= hi_pick), delta(−n_p) > delta(n_p) when |det T| > 2 sqrt(hi_pick)
//    |n_p|: certified as (|det~| − E3) > 2 sqrt(hi_pick) (|n~_p| + sqrt(3) E2) (1 + 2^-40) (the
//    kernel's det within E3, n~_p's components within E2: value_bounds.h; the factor covers this
//    test's few roundings). Then −n_p attains no tie with PD either.
// An edge of T is orthogonal to n_p only if it lies in face p (else it joins p's plane to T's
// opposite vertex, off the plane): topology; the other tetrahedron's edge, PickPlane's test.
bool unresolved_along_pick(const SupersetLanes& K, const FilterBounds& fb, int p, double hi_pick,
                           const Unresolved& un, PickPlane& plane) {
  const int t = p / 4, w = p % 4;  // the pick's tetrahedron and its vertex opposite face p
  const double nn = K.NAB[0][p] * K.NAB[0][p] + K.NAB[1][p] * K.NAB[1][p] + K.NAB[2][p] * K.NAB[2][p];
  const double height = std::fabs(K.det[4 * t + 3]) - fb.deg3;
  if (!(height > 2 * std::sqrt(hi_pick) * (std::sqrt(nn) + std::sqrt(3.0) * fb.deg2) * (1 + 0x1p-40))) return false;
  for (std::uint64_t bits = un.bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / kLaneStride, b = lane % kLaneStride;
    if (un.lo2[lane] > hi_pick) continue;
    const int own = t == 0 ? a : b, other = t == 0 ? b : a;
    if (kEdges[own][0] == w || kEdges[own][1] == w) return false;
    if (!edge_in_face_plane(K, fb, 1 - t, other, w, plane)) return false;
  }
  return true;
}

// The kernel's pair (the rescaled pair) as tetrahedra.
void kernel_pair(const SupersetLanes& K, TetVertices& A, TetVertices& B) {
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k) A[v][k] = K.X[k][v], B[v][k] = K.X[k][4 + v];
}

// The list candidates of nearly parallel edge pairs (left out of S) against a bound: the
// pair's normal n = eB × eA taken exactly (over the kernel pair's integer frame, else by
// expansions) and rounded, each component within 3u of its exact value, its heights in doubles
// with their own bounds (value_bounds.h's own_degree_bounds), as candidate_directions.cpp's
// near_parallel_normal builds the list's candidate. above(): both orientations' certified
// lower bounds of delta² exceed hi (whatever definitions §3's rule keeps, and so do the
// pair's facets, which are along ±n); false where it cannot be shown (n exactly 0: the
// common perpendicular of parallel edges is not bounded here; out of the expansions' range).
// parallel(): n exactly 0 over the pair's integer frame (what exactly_parallel could not show
// in doubles; false without a frame).
class UnresolvedNormals {
 public:
  explicit UnresolvedNormals(const SupersetLanes& K) : K_(K), frame_(A_, B_) {
    kernel_pair(K, A_, B_);
    in_range_ = in_exact_range(A_, B_);
  }
  bool above(int a, int b, double hi) {
    const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
    double n[3];
    bool parallel = false;
    if (!in_range_ || !exact_normal(u, v, x, y, n, parallel)) return false;
    double hA[4], hB[4];
    for (int k = 0; k < 4; ++k) {
      hA[k] = n[0] * (A_[k][0] - A_[u][0]) + n[1] * (A_[k][1] - A_[u][1]) + n[2] * (A_[k][2] - A_[u][2]);
      hB[k] = n[0] * (B_[k][0] - A_[u][0]) + n[1] * (B_[k][1] - A_[u][1]) + n[2] * (B_[k][2] - A_[u][2]);
    }
    hA[u] = hA[v] = 0.0;  // exactly: n.eA = 0
    hB[y] = hB[x];        // exactly: n.eB = 0
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const DegreeBounds own = own_degree_bounds(n, K_.extent);
    double hiA = hA[0], loA = hA[0], hiB = hB[0], loB = hB[0];
    for (int k = 1; k < 4; ++k) hiA = max2(hiA, hA[k]), loA = min2(loA, hA[k]), hiB = max2(hiB, hB[k]), loB = min2(loB, hB[k]);
    // D(+n) = max hA − min hB, D(−n) = max hB − min hA (A below the plane along the direction)
    for (const double D : {hiA - loB, hiB - loA})
      if (!(lower_of(D * D / nn, rigid_root_rel(D, nn, own)) > hi)) return false;
    return true;
  }
  // near_parallel_bound's contract for edge pair (a, b) where its doubles cannot show d_x off
  // F (nearly colinear edges: r_x a rounding away from the line of edge a, every degree-4 sign
  // it needs within E4 of 0): over the integer frame, exactly. n = eB × eA exactly 0: parallel
  // edges span no facet, lo2 = +inf. Else ±n is a facet normal of M = A ⊕ (−B) only if A's
  // support along it contains edge a and B's lowest vertices along it contain edge b: for +n,
  // n.(s_k − s_u) <= 0 for A's two vertices s_k off edge a and n.(r_j − r_x) >= 0 for B's two
  // off edge b; for −n the reverse (exact signs, IntegerFrame::dot_sign). An orientation that
  // fails is no facet normal and needs no bound; one that passes is bounded below as above()
  // bounds it (the rounded exact normal, its own degree bounds): lo2 the least of those (+inf
  // when neither passes; 0 when a depth is not certainly positive, which the caller's
  // positivity test then refuses). False without a frame (the caller's other path).
  bool facet_bound(int a, int b, double& lo2) {
    if (!frame_.usable()) return false;
    const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
    __int128 m[3];
    frame_.normal(4 + y, 4 + x, v, u, m);
    lo2 = kInf;
    if (m[0] == 0 && m[1] == 0 && m[2] == 0) return true;
    bool facet[2] = {true, true};  // +n, −n
    for (const int k : {kOffEdge[a][0], kOffEdge[a][1]}) {
      const int sg = frame_.dot_sign(m, k, u);
      facet[0] = facet[0] && sg <= 0, facet[1] = facet[1] && sg >= 0;
    }
    for (const int j : {kOffEdge[b][0], kOffEdge[b][1]}) {
      const int sg = frame_.dot_sign(m, 4 + j, 4 + x);
      facet[0] = facet[0] && sg >= 0, facet[1] = facet[1] && sg <= 0;
    }
    if (!facet[0] && !facet[1]) return true;
    double n[3];
    for (int k = 0; k < 3; ++k) n[k] = times_pow2(double(m[k]), 2 * frame_.unit_exponent());
    double hiA = -kInf, loA = kInf, hiB = -kInf, loB = kInf;
    for (int k = 0; k < 4; ++k) {
      const double hA = n[0] * (A_[k][0] - A_[u][0]) + n[1] * (A_[k][1] - A_[u][1]) + n[2] * (A_[k][2] - A_[u][2]);
      const double hB = n[0] * (B_[k][0] - A_[u][0]) + n[1] * (B_[k][1] - A_[u][1]) + n[2] * (B_[k][2] - A_[u][2]);
      hiA = max2(hiA, hA), loA = min2(loA, hA), hiB = max2(hiB, hB), loB = min2(loB, hB);
    }
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const DegreeBounds own = own_degree_bounds(n, K_.extent);
    for (int o = 0; o < 2; ++o) {
      if (!facet[o]) continue;
      const double D = o == 0 ? hiA - loB : hiB - loA;  // as above()
      lo2 = min2(lo2, D > 0 ? lower_of(D * D / nn, rigid_root_rel(D, nn, own)) : 0.0);
    }
    return true;
  }
  bool parallel(int a, int b) {  // (over the integer frame only: a few instructions; else false)
    if (!frame_.usable()) return false;
    __int128 m[3];
    frame_.normal(4 + kEdges[b][1], 4 + kEdges[b][0], kEdges[a][1], kEdges[a][0], m);
    return m[0] == 0 && m[1] == 0 && m[2] == 0;
  }

 private:
  // n = (r_y − r_x) × (s_v − s_u) exactly, rounded; false when exactly 0 (`parallel`) or out
  // of capacity
  bool exact_normal(int u, int v, int x, int y, double (&n)[3], bool& parallel) {
    if (frame_.usable()) {
      __int128 m[3];
      frame_.normal(4 + y, 4 + x, v, u, m);
      parallel = m[0] == 0 && m[1] == 0 && m[2] == 0;
      if (parallel) return false;
      for (int k = 0; k < 3; ++k) n[k] = times_pow2(double(m[k]), 2 * frame_.unit_exponent());
      return true;
    }
    const ExpVec e = detail::cross(difference(B_[y], B_[x]), difference(A_[v], A_[u]));
    parallel = e.ok() && e.is_zero();
    if (!e.ok() || parallel) return false;
    for (int k = 0; k < 3; ++k) n[k] = e.x[k].approx();
    return true;
  }
  const SupersetLanes& K_;
  TetVertices A_, B_;
  IntegerFrame frame_;
  bool in_range_ = false;
};

// near_parallel_bound's lo2 for the lanes `bits` over the kernel pair's integer frame
// (UnresolvedNormals::facet_bound), added to un; false where one cannot be had. (Not inlined:
// nearly colinear edges are rare outside grids shifted along their own diagonals.)
__attribute__((noinline)) bool facet_bounds(const SupersetLanes& K, std::uint64_t bits, Unresolved& un) {
  UnresolvedNormals normals(K);
  for (; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    double& lo2 = un.lo2[lane];
    if (!normals.facet_bound(lane / kLaneStride, lane % kLaneStride, lo2)) return false;
    un.extra_lo = min2(un.extra_lo, lo2);
    un.bits |= std::uint64_t{1} << lane;
  }
  return true;
}

// un with its pairs whose facets may reach hi_pick (lo2 <= hi_pick) looked at again: an edge
// pair exactly parallel over the kernel pair's integer frame (what exactly_parallel could not
// show in doubles; a grid of decimal cell and its copy) defines no facet, so its lo2 is +inf
// (near_parallel_bound.h's contract). `un` itself where nothing changes, else `out`.
const Unresolved& facets_rechecked(const SupersetLanes& K, const Unresolved& un, double hi_pick, Unresolved& out) {
  if (un.extra_lo > hi_pick) return un;
  std::optional<UnresolvedNormals> normals;
  bool changed = false;
  for (std::uint64_t bits = un.bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    if (un.lo2[lane] > hi_pick) continue;
    if (!normals) normals.emplace(K);
    if (!normals->parallel(lane / kLaneStride, lane % kLaneStride)) continue;
    if (!changed) out = un, changed = true;
    out.lo2[lane] = kInf;
  }
  if (!changed) return un;
  out.extra_lo = kInf;
  for (std::uint64_t bits = out.bits; bits; bits &= bits - 1) out.extra_lo = min2(out.extra_lo, out.lo2[__builtin_ctzll(bits)]);
  return out;
}


// ---- `unique` through exact orders. An entry a rounding away from the pick (a grid against
// its copy shifted by a non-dyadic offset: faces and edges parallel up to the rounding of the
// coordinates, delta² ~1e-16 apart relative), or tied with it exactly (a grid against its copy
// shifted by a dyadic offset: faces and edge pairs of a symmetric group, one delta² along
// different directions), is neither certainly above it in the rounded values nor along it in
// every case; `unique` needs only that no candidate precedes the pick in the stable order of
// the list: every entry before the pick in canonical order strictly above it, every entry
// after it at or above it. An entry (lane, ±) is the direction ±(eB × eA), labelled Plus or
// Minus so that its depth is that orientation's whatever the orientation rule says: every entry
// of S is bounded, a real candidate or not (an orientation the rule discards is no candidate
// and precedes nothing). On the kernel's pair (the rescaled pair):
// - over the pair's integer frame where it has one (integer_depth.h: exact depths and n.n in
//   machine integers, the rule's exact classification): the order itself, ties included;
// - else by the depth parts in double words (compensated_depth, compare_delta2_compensated:
//   compensated_heights.h), which decide all but ties among their bounds; such an entry after
//   the pick ties exactly when it points exactly the pick's way (same_as_labelled,
//   exact_predicates.h: equal directions, equal delta — D is the support function of M along
//   the direction, whatever the label), a real candidate tied after the pick or no candidate
//   (aligned pairs have those along the pick, where A's edge of the lane is parallel to the
//   pick's but off A's support).
// Anything else declines (false).
class PickDepthOrder {
 public:
  PickDepthOrder(const SupersetLanes& K, LabelCode pick) : K_(K), pick_(unpack_label(pick)) {}
  // No candidate l precedes the pick: l's exact delta² is above the pick's, or equal to it and
  // l after the pick in canonical order (after), or l is no candidate.
  bool after_pick(const DirectionLabel& l, bool after) {
    if (frame_usable()) return framed_order(l, after);
    if (state_ == State::Unset) state_ = compensated_depth(A_, B_, pick_, pick_depth_) ? State::Ready : State::Declined;
    CompensatedDepth d;
    if (state_ != State::Ready || !compensated_depth(A_, B_, l, d)) return false;
    const std::optional<int> s = compare_delta2_compensated(d, pick_depth_);
    if (s) return *s > 0;
    if (!after) return false;
    if (!direction_) direction_.emplace(A_, B_, pick_);
    const std::optional<bool> same = direction_->same_as_labelled(l);
    return same && *same;
  }
  bool face_after_pick(int f, bool after) {
    return after_pick(f < 4 ? DirectionLabel::fv(f) : DirectionLabel::vf(f - 4), after);
  }
  bool lane_after_pick(int lane, double sign, bool after) {
    const EdgeOrientation o = sign > 0 ? EdgeOrientation::Plus : EdgeOrientation::Minus;
    return after_pick(DirectionLabel::ee(lane / kLaneStride, lane % kLaneStride, o), after);
  }

 private:
  bool frame_usable() {
    if (!frame_) {
      kernel_pair(K_, A_, B_);
      frame_.emplace(A_, B_);
    }
    return frame_->usable();
  }
  // after_pick over the frame. Where the exact rule keeps the other orientation of an entry
  // (lane, ±), the entry is no candidate; otherwise framed_depth's label (oriented by the rule,
  // ± only where the rule keeps both) is the entry itself.
  bool framed_order(const DirectionLabel& l, bool after) {
    if (l.kind == ContactKind::EE) {
      const EdgePairClass k = classify_edge_pair_framed(*frame_, l.a, l.b);
      if (k.kind != EdgePairKind::Generic) return false;  // (no direction ±(eB × eA))
      if (k.side == EdgePairSide::Keep && l.orientation == EdgeOrientation::Minus) return true;
      if (k.side == EdgePairSide::Flip && l.orientation == EdgeOrientation::Plus) return true;
    }
    if (framed_pick_ == State::Unset)
      framed_pick_ = framed_depth(*frame_, pick_, pick_framed_) ? State::Ready : State::Declined;
    FramedDepth q;
    if (framed_pick_ != State::Ready || !framed_depth(*frame_, l, q)) return false;
    const int c = compare_framed_delta2(q, pick_framed_);
    tied_after_ |= after && c == 0;
    return after ? c >= 0 : c > 0;
  }

 public:
  // A candidate after the pick tied with it exactly over the frame (possibly along another
  // direction): PD is then attained along another direction too.
  bool tied_after() const { return tied_after_; }
  // The exactly parallel pairs among the edge pairs `lanes` (all before an edge-pair pick)
  // strictly above the pick, exactly; after tied_after() only (the frame and the pick's depth
  // are there). Such a pair is no entry of S (no facet: lo2 = +inf); its candidate, the common
  // perpendicular, ties the pick only along a direction attaining PD, which may be a tied
  // entry's other direction: a candidate there, before the pick, would be first. Each
  // orientation the exact rule keeps (both where it keeps both) must lie strictly above.
  bool parallel_pairs_above(std::uint64_t lanes) {
    for (; lanes; lanes &= lanes - 1) {
      const int lane = __builtin_ctzll(lanes), a = lane / kLaneStride, b = lane % kLaneStride;
      const EdgePairClass k = classify_edge_pair_framed(*frame_, a, b);
      if (k.kind != EdgePairKind::Parallel) continue;  // colinear: no candidate; generic: an entry of S
      for (const EdgeOrientation o : {EdgeOrientation::Plus, EdgeOrientation::Minus}) {
        if ((k.side == EdgePairSide::Keep && o == EdgeOrientation::Minus) ||
            (k.side == EdgePairSide::Flip && o == EdgeOrientation::Plus))
          continue;  // (the orientation the rule discards)
        FramedDepth q;
        if (!framed_depth(*frame_, DirectionLabel::ee(a, b, o), q) || compare_framed_delta2(q, pick_framed_) <= 0)
          return false;
      }
    }
    return true;
  }

 private:

  enum class State { Unset, Ready, Declined };
  const SupersetLanes& K_;
  DirectionLabel pick_;
  State state_ = State::Unset;
  TetVertices A_, B_;
  CompensatedDepth pick_depth_;
  std::optional<ExactDirection> direction_;
  std::optional<IntegerFrame> frame_;
  State framed_pick_ = State::Unset;
  FramedDepth pick_framed_;
  bool tied_after_ = false;
};

// Orientation s of edge pair `lane` is the one the orientation rule discards (definitions §3),
// certainly: both of A's off-edge heights g certain in doubles (|g| > E3, near_candidates) and
// on s's side (both > 0: the rule flips, discarding +; both < 0: it keeps, discarding −). Such an
// entry of S is no candidate: it cannot precede the pick in the list, whatever its value.
bool discarded_orientation(const SupersetLanes& K, const FilterBounds& fb, int lane, double s) {
  const int a = lane / kLaneStride, b = lane % kLaneStride;
  const double g1 = kOffFaces.eps[a][0] * K.G[kOffFaces.face[a][0]][b];
  const double g2 = kOffFaces.eps[a][1] * K.G[kOffFaces.face[a][1]][b];
  return s * g1 > fb.deg3 && s * g2 > fb.deg3;
}

// The unresolved edge pairs (un) not certainly above the pick (lo2 <= hi_pick): both
// orientations of each certainly above it (a nearly parallel pair's list candidate is one of
// them, its normal eB × eA taken exactly; an exactly parallel pair has lo2 = +inf).
bool unresolved_above_pick(const Near& c, double hi_pick, const Unresolved& un, PickDepthOrder& order) {
  for (std::uint64_t bits = un.bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    const bool after = c.lane < lane;  // (a face pick: −1)
    if (un.lo2[lane] > hi_pick) continue;
    if (!order.lane_after_pick(lane, 1.0, after) || !order.lane_after_pick(lane, -1.0, after)) return false;
  }
  return true;
}

// `unique` for a pick c whose certificate found entries not certainly above it: true when each
// of them, for a face pick, points exactly the pick's way and comes after it (above), or is no
// candidate, or has an exact delta² above the pick's, or equal and after it (PickDepthOrder). un: the entries left out of K's
// bound bits (unresolved edge pairs), certainly above or along the pick
// (unresolved_along_pick, unresolved_above_pick). Lower bounds as certify's exact pass computes
// them; an orientation the rule certainly discards is no candidate and needs no bound. An
// edge-pair pick is first over the list when every other candidate of S is above it or tied
// after it, the caller's rule for exactly parallel pairs (choice_without_unresolved) applied.
// Without `depth_order` the entries that need PickDepthOrder (a rounding away from the pick)
// are not ordered: Undecided (the caller's tie band may settle them for less).
// (Not inlined: PickPlane's expansions, ~1.2 KB, stay off the frame of pick_and_certify, which
// rigid_pd2's hot path runs on every pair; measured 10 instructions a call less.)
enum class Shared { Yes, No, Undecided };
__attribute__((noinline)) Shared ties_share_direction(const SupersetLanes& K, const FilterBounds& fb, const Near& c,
                                                      double hi_pick, const Unresolved& un, bool depth_order) {
  const bool face_pick = c.lane < 0;
  const DegreeBounds db = degree_bounds(fb, false);
  auto above = [&](double v, double r) { return lower_of(v, r) > hi_pick; };
  PickPlane plane(K, face_pick ? c.face : 0);
  PickDepthOrder order(K, c.code);
  // an entry ordered by depth parts: No when not after the pick, Undecided without the order
  auto ordered = [&](auto after_pick) { return !depth_order ? Shared::Undecided : after_pick() ? Shared::Yes : Shared::No; };
  if (!(un.extra_lo > hi_pick) && !(face_pick && unresolved_along_pick(K, fb, c.face, hi_pick, un, plane))) {
    const Shared s = ordered([&] { return unresolved_above_pick(c, hi_pick, un, order); });
    if (s != Shared::Yes) return s;
  }
  for (unsigned bits = K.face_bound_bits; bits; bits &= bits - 1) {
    const int f = __builtin_ctz(bits);
    if (face_pick && f == c.face) continue;
    const double nn = K.NAB[0][f] * K.NAB[0][f] + K.NAB[1][f] * K.NAB[1][f] +
                      K.NAB[2][f] * K.NAB[2][f];
    const double v = K.face_val[f];
    if (above(v, rigid_root_rel(std::sqrt(v * nn), nn, db))) continue;
    if (face_pick && f > c.face && face_along_face(K, fb, c.face, f, plane)) continue;
    const Shared s = ordered([&] { return order.face_after_pick(f, face_pick && f > c.face); });
    if (s != Shared::Yes) return s;
  }
  for (std::uint64_t bits = K.lane_bound_bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / kLaneStride, b = lane % kLaneStride;
    const double inv = K.inv[a][b], dp = K.dp[a][b], dm = K.dm[a][b];
    for (const double s : {1.0, -1.0}) {
      if (!face_pick && lane == c.lane && s == c.sign) continue;
      const double d = s > 0 ? dp : dm;
      if (above(d * d * inv, rigid_root_rel(d, 1.0 / inv, db))) continue;
      if (discarded_orientation(K, fb, lane, s)) continue;
      if (face_pick && lane_along_face(K, fb, c.face, lane, s, plane)) continue;
      const Shared t = ordered([&] { return order.lane_after_pick(lane, s, c.lane < lane); });
      if (t != Shared::Yes) return t;
    }
  }
  if (!face_pick && order.tied_after() && !order.parallel_pairs_above(un.bits & ((std::uint64_t{1} << c.lane) - 1)))
    return Shared::No;
  return Shared::Yes;
}

bool band_accepted(const SupersetLanes& K, const FilterBounds& fb, const Near& c, double hi_pick,
                   const Unresolved& un, TieBandTest& test, bool settle);

// `unique` for a certified pick that certify could not show alone: exact directions first
// (structural zeros: cheap on aligned pairs), then the band (where given) where the rest needs
// depth parts in double words, then those, with the unresolved pairs' facets rechecked for exact
// parallelism, and last the band settled where its test disagreed (TieBandTest::settle). (Not
// inlined: off the hot path's frame.)
__attribute__((noinline)) bool unique_after_ties(const SupersetLanes& K, const FilterBounds& fb, const Near& c,
                                                 double hi_pick, const Unresolved& un, TieBandTest* band) {
  Shared s = band && band->always ? Shared::Undecided : ties_share_direction(K, fb, c, hi_pick, un, !band);
  if (s != Shared::Undecided || (band->accepted = band_accepted(K, fb, c, hi_pick, un, *band, false)))
    return s == Shared::Yes;
  Unresolved rechecked;
  const Unresolved& r = facets_rechecked(K, un, hi_pick, rechecked);
  if (ties_share_direction(K, fb, c, hi_pick, r, true) == Shared::Yes) return true;
  if (band && band->disagreed) band->accepted = band_accepted(K, fb, c, hi_pick, r, *band, true);
  return false;
}

// The pick among the entries of K's tie band (face_bits, lane_bits) and its certificate
// (K's bound bits, and un for entries outside them). `band`: asked where `unique` needs depth
// parts in double words (superset_depth.h).
bool pick_and_certify(const SupersetLanes& K, const FilterBounds& fb, const Unresolved& un, Choice& ch,
                      Candidate* geometry, bool* unique, bool with_certificate, TieBandTest* band = nullptr) {
  Near near[kMaxCandidates];
  int count = 0;
  if (!near_candidates(K, fb, near, count)) return false;
  double vmin = kInf;
  for (int i = 0; i < count; ++i) vmin = min2(vmin, near[i].value);
  if (!(vmin <= K.t1)) return false;
  const double threshold = vmin == K.vmin ? K.t1 : tie_threshold(vmin, K.kappa);
  int pick = 0;
  while (!(near[pick].value <= threshold)) ++pick;
  const Near& c = near[pick];
  ch.value = c.value;
  ch.index = -1;
  ch.code = c.code;
  if (with_certificate) {
    double hi_pick = kInf;
    certify(K, fb, c, ch, unique, un.extra_lo, hi_pick);
    if (unique && ch.certified && !*unique) *unique = unique_after_ties(K, fb, c, hi_pick, un, band);
  }
  if (!geometry) return true;
  if (c.lane >= 0)
    lane_geometry(K, c, *geometry);
  else
  {
    Draft d;
    face_draft(K, c.face, d);
    finish_face(d, *geometry);
  }
  geometry->label = unpack_label(c.code);
  return true;
}

// K without the edge pairs of `unresolved` (near_parallel_bound.h): positivity, minimum, tie
// band and bound bits of the rest, by the kernel's rules (tie_and_certify_bits: the same
// thresholds t1, t2 from the new minimum, the same far-entry skip, whose proof needs only that
// the pick is <= t2 and a skipped entry passes the three tests): drop_lanes, lane-wise.
bool drop_edge_pairs(SupersetLanes& K, const FilterBounds& fb, std::uint64_t unresolved) {
  const DegreeBounds db = degree_bounds(fb, false);
  const double eh = kFarBoundScale * db.e_h, en = kFarBoundScale * db.e_n;
  return drop_lanes(K, fb.deg3, eh * eh, en * en, unresolved);
}

// The list candidates of the unresolved edge pairs `bits` certainly point elsewhere than the
// edge-pair pick l, n = eB_b × eA_a (a, b: l's edges). Each one's direction d is orthogonal to
// its edges (definitions §3: eB' × eA', or for parallel edges their common perpendicular), so n
// not orthogonal to eA' or to eB' rules a tie of direction out: |n.e| > E3 (a cross product of
// two differences dotted with a third: computed within 48 u L³ < E3, near_parallel_bound.h).
// For exactly parallel edges (d in the plane of eA' and w = r_x' − s_u', orthogonal to eA'), n
// orthogonal to eA' is along d only if it is orthogonal to eA' × w too: |n.(eA' × w)| > E4 (a
// dot of two cross products of differences: within 132 u L⁴ < E4) rules it out. Where the
// doubles cannot tell, exactly: neither orientation of the pair's candidate (same_as_labelled:
// ±d whatever the rule says) points the pick's way. (A colinear pair is no candidate: its d is
// 0, never the pick's way.)
bool unresolved_off_pick(const SupersetLanes& K, const FilterBounds& fb, std::uint64_t bits, const DirectionLabel& l) {
  double n[3];
  edge_pair_normal(K.EA[0][l.a], K.EA[1][l.a], K.EA[2][l.a], K.EB[0][l.b], K.EB[1][l.b], K.EB[2][l.b], n[0], n[1], n[2]);
  auto dot_n = [&n](const double* v) { return n[0] * v[0] + n[1] * v[1] + n[2] * v[2]; };
  TetVertices A, B;
  std::optional<ExactDirection> exact;
  for (; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), e = lane / kLaneStride, f = lane % kLaneStride;
    const double eA[3] = {K.EA[0][e], K.EA[1][e], K.EA[2][e]}, eB[3] = {K.EB[0][f], K.EB[1][f], K.EB[2][f]};
    if (std::fabs(dot_n(eA)) > fb.deg3 || std::fabs(dot_n(eB)) > fb.deg3) continue;
    if (exactly_parallel(K, e, f)) {
      const int u = kEdges[e][0], x = kEdges[f][0];
      const double w[3] = {K.X[0][4 + x] - K.X[0][u], K.X[1][4 + x] - K.X[1][u], K.X[2][4 + x] - K.X[2][u]};
      const double m[3] = {eA[1] * w[2] - eA[2] * w[1], eA[2] * w[0] - eA[0] * w[2], eA[0] * w[1] - eA[1] * w[0]};
      if (std::fabs(dot_n(m)) > fb.deg4) continue;
    }
    if (!exact) kernel_pair(K, A, B), exact.emplace(A, B, l);
    for (const EdgeOrientation o : {EdgeOrientation::Plus, EdgeOrientation::Minus}) {
      const std::optional<bool> same = exact->same_as_labelled(DirectionLabel::ee(e, f, o));
      if (!same || *same) return false;
    }
  }
  return true;
}


// ---- The tie band (superset_depth.h's TieBand) of a certified pick c that is not `unique`, and
// why it holds the exact first x* of the list (the first in canonical order among the
// candidates whose exact delta² is PD²). Every candidate attaining PD points along a facet
// normal of M attaining it (the nearest point of ∂M to the origin lies inside a facet:
// ties_share_direction above). The entries of S outside K's bound bits are certainly above
// the pick (certify), and so are those whose certified lower bound exceeds hi_pick, the pick's
// upper bound (>= PD²): the rest, less the orientations the rule certainly discards (no
// candidates), are the band with the pick; they are the list's face and lane candidates,
// geometry included (lane_geometry, face_draft). The list's other candidates are those of the
// unresolved edge pairs (un, left out of S). One of them is no exact minimiser when its
// candidate (both orientations) is certainly above hi_pick (UnresolvedNormals); that is
// required where the pair's facets may reach hi_pick (lo2 <= hi_pick, near_parallel_bound.h).
// Otherwise its facets are above hi_pick and its candidate attains PD only along the facet
// normal of a band entry e attaining it: if e is a face, x* is a face (faces precede every edge
// pair), in the band; if e is an edge pair, the unresolved candidate precedes e only from a
// lower lane, and unresolved_off_pick shows it points elsewhere than e (as
// choice_without_unresolved does for an edge-pair pick). So x* is in the band, and its case-2
// value is one of the band's.
// More than TieBand::kMax entries, the test's disagreement, an unresolved pair whose facets may
// reach hi_pick and whose candidate is not shown above it, or one not shown off a band edge
// pair of a higher lane: false.
// (Not inlined: the band, ~1 KB, stays off the frame of pick_and_certify.)
__attribute__((noinline)) bool band_accepted(const SupersetLanes& K, const FilterBounds& fb, const Near& c,
                                             double hi_pick, const Unresolved& un, TieBandTest& test, bool settle) {
  const DegreeBounds db = degree_bounds(fb, false);
  auto above = [&](double v, double r) { return lower_of(v, r) > hi_pick; };
  TieBand band;
  std::uint64_t lanes = 0;  // the band's edge-pair lanes
  auto add_face = [&](int f, LabelCode code) {
    Draft d;
    face_draft(K, f, d);
    Candidate& g = band.entry[band.count++];
    finish_face(d, g);
    g.label = unpack_label(code);
  };
  auto add_lane = [&](const Near& e) {  // labelled EE:a:b:+ for +(eB × eA), EE:a:b:- for −(eB × eA)
    const EdgeOrientation o = e.sign > 0 ? EdgeOrientation::Plus : EdgeOrientation::Minus;
    Candidate& g = band.entry[band.count++];
    lane_geometry(K, e, g);
    g.label = DirectionLabel::ee(e.lane / kLaneStride, e.lane % kLaneStride, o);
    lanes |= std::uint64_t{1} << e.lane;
  };
  if (c.lane < 0)
    add_face(c.face, c.code);
  else
    add_lane(c);
  for (unsigned bits = K.face_bound_bits; bits; bits &= bits - 1) {
    const int f = __builtin_ctz(bits);
    if (c.lane < 0 && f == c.face) continue;
    const double nn = K.NAB[0][f] * K.NAB[0][f] + K.NAB[1][f] * K.NAB[1][f] + K.NAB[2][f] * K.NAB[2][f];
    const double v = K.face_val[f];
    if (above(v, rigid_root_rel(std::sqrt(v * nn), nn, db))) continue;
    if (band.count == TieBand::kMax) return false;
    add_face(f, f < 4 ? pack_label(ContactKind::FV, f, 0, EdgeOrientation::Decided)
                      : pack_label(ContactKind::VF, f - 4, 0, EdgeOrientation::Decided));
  }
  for (std::uint64_t bits = K.lane_bound_bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits), a = lane / kLaneStride, b = lane % kLaneStride;
    const double inv = K.inv[a][b], dp = K.dp[a][b], dm = K.dm[a][b];
    for (const double s : {1.0, -1.0}) {
      if (lane == c.lane && s == c.sign) continue;
      const double d = s > 0 ? dp : dm;
      if (above(d * d * inv, rigid_root_rel(d, 1.0 / inv, db))) continue;
      if (discarded_orientation(K, fb, lane, s)) continue;
      if (band.count == TieBand::kMax) return false;
      add_lane(Near{d * d * inv, LabelCode{0}, lane, -1, s});
    }
  }
  // the caller's test first (a few closed forms), then the unresolved pairs (exact normals)
  kernel_pair(K, band.A, band.B);
  if (!(settle ? test.settle(band, fb) : test.agree(band, fb))) return false;
  // An unresolved pair is no exact first when its list candidate is certainly above hi_pick
  // (UnresolvedNormals: required where its facets may reach hi_pick, lo2 <= hi_pick), or
  // else when it points elsewhere than every band edge pair of a higher lane.
  std::optional<UnresolvedNormals> normals;
  auto shown_above = [&](int lane) {
    if (!normals) normals.emplace(K);
    return normals->above(lane / kLaneStride, lane % kLaneStride, hi_pick);
  };
  const int top = lanes ? 63 - __builtin_clzll(lanes) : -1;  // the band's highest lane
  for (std::uint64_t bits = un.bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    const bool facets_below = !(un.lo2[lane] > hi_pick);
    if (!facets_below && lane > top) continue;  // no band edge pair after it
    if (shown_above(lane)) continue;
    if (facets_below) return false;
    for (std::uint64_t after = lanes & ~((std::uint64_t{2} << lane) - 1); after; after &= after - 1) {
      const int l = __builtin_ctzll(after);
      for (int i = 0; i < band.count; ++i) {
        const DirectionLabel& e = band.entry[i].label;
        if (e.kind != ContactKind::EE || kLaneStride * e.a + e.b != l) continue;
        if (!unresolved_off_pick(K, fb, std::uint64_t{1} << lane, e)) return false;
      }
    }
  }
  return true;
}

// The choice when edge pairs the doubles cannot resolve (`unresolved`: unresolved_edge_pairs,
// nearly or exactly parallel edges: an aligned pair) spoil the kernel's screens: those pairs
// bounded by near_parallel_bound (nearly colinear ones, which it cannot bound, by facet_bounds),
// the choice made among the others. True only with a certified choice (then in ch, geometry,
// unique); K is changed either way.
// `unique` here: the pick is certainly below every entry of S (near_parallel_bound's lo2 bounds
// the ±n entries of the nearly parallel pairs) — and the candidate list has one more kind of
// candidate, that of an exactly parallel pair (its normal ⊥ both edges, definitions §3), which S
// leaves out (lo2 = +inf: no facet). Its exact delta is >= PD², and equal only along a direction
// attaining PD: a facet normal of M (the nearest point of ∂M to the origin lies inside a facet,
// where the supporting plane is tangent to the ball B(0, PD)). (An orientation skipped as
// discarded by the rule hides no such direction: an outward facet normal has A's off-edge
// heights <= 0 along itself, so the rule never discards it.) A face pick (FV, VF) comes before
// every edge pair. An edge-pair pick is still first unless such a candidate precedes its lane
// and ties with it: where `unique` accepts ties only along the pick's own direction (no integer
// frame), PD is attained along that direction alone, and an unresolved pair before the lane
// that may point the pick's way refuses it (unresolved_off_pick); over the frame, ties after
// the pick along other directions are accepted too, and then the exactly parallel pairs before
// the lane are ordered against the pick exactly (PickDepthOrder::parallel_pairs_above).
// un: the bounds of the lanes in un.bits (near_parallel_bound), kept for a second call with
// more lanes; `unresolved` a superset of un.bits.
bool choice_without_unresolved(SupersetLanes& K, const FilterBounds& fb, std::uint64_t unresolved, Unresolved& un,
                               Choice& ch, Candidate* geometry, bool* unique, TieBandTest* band) {
  if (!unresolved) return false;
  // the lanes left first (vectorised, cheap): their least depth must clear E3
  if (!drop_edge_pairs(K, fb, unresolved)) return false;
  std::uint64_t colinear = 0;  // the lanes near_parallel_bound leaves to facet_bounds
  for (std::uint64_t bits = unresolved & ~un.bits; bits; bits &= bits - 1) {
    const int lane = __builtin_ctzll(bits);
    double& lo2 = un.lo2[lane];
    if (!near_parallel_bound(K, fb, lane / kLaneStride, lane % kLaneStride, lo2)) {
      colinear |= std::uint64_t{1} << lane;
      continue;
    }
    un.extra_lo = min2(un.extra_lo, lo2);
    un.bits |= std::uint64_t{1} << lane;
  }
  if (colinear && !facet_bounds(K, colinear, un)) return false;
  if (!(un.extra_lo > 0.0)) return false;
  Choice c;
  Candidate g;
  bool u = false;
  if (!pick_and_certify(K, fb, un, c, geometry ? &g : nullptr, unique ? &u : nullptr, true, band) ||
      !c.certified)
    return false;
  const DirectionLabel l = c.label();
  if (u && l.kind == ContactKind::EE &&
      !unresolved_off_pick(K, fb, unresolved & ((std::uint64_t{1} << (kLaneStride * l.a + l.b)) - 1), l))
    u = false;
  ch = c;
  if (geometry) *geometry = g;
  if (unique) *unique = u;
  return true;
}

// The edge pairs (bit 8a + b) whose own bounds are too loose to certify a tie: in either
// orientation the root's relative bound (rigid_root_rel, as certify_pass takes it) exceeds
// kLooseRel, or the depth is not certainly positive. Nearly parallel edges whose n clears E2 but
// is short (|n| ~ 1e-13 L²: a depth ~ |n| times the overlap, a few E3) are of this kind; stacked
// blocks are full of them (edges parallel up to the rounding of a shift), each an exact tie of
// the pick whose loose bound refuses the certificate. Taken as unresolved they are bounded by
// near_parallel_bound instead, whose argument uses no n (its bound holds for every edge pair),
// and the exact n of such a pair (within E2 of the computed one, ⊥ eA) is one of the
// directions an unresolved pair is allowed to have. kLooseRel: a tie certifies only when each
// bound is within ~5e-10 of its value (certified_choice: 1e-9 between the pick's upper and the
// others' lower bounds).
constexpr double kLooseRel = 1e-10;
std::uint64_t loose_edge_pairs(const SupersetLanes& K, const FilterBounds& fb) {
  const DegreeBounds db = degree_bounds(fb, false);
  std::uint64_t mask = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const double inv = K.inv[a][b], d = min2(K.dp[a][b], K.dm[a][b]);
      if (!(d > fb.deg3) || !(rigid_root_rel(d, 1.0 / inv, db) <= kLooseRel))
        mask |= std::uint64_t{1} << (kLaneStride * a + b);
    }
  return mask;
}

// The choice from the kernel's lanes K (K is changed where unresolved edge pairs are dropped).
// With a certificate and no `unique` asked, a choice the kernel's screens cannot certify is
// retried without the edge pairs the doubles cannot resolve; when that fails too, the first
// choice stands (uncertified) or the pair is declined, as the screens said.
bool choice_of_lanes(SupersetLanes& K, Choice& ch, Candidate* geometry, bool* unique,
                     bool with_certificate, bool* unresolved = nullptr, TieBandTest* band = nullptr) {
  if (!(K.finite == 0.0)) return false;
  const FilterBounds fb = filter_bounds_of_extent(K.extent);
  // valid tetrahedra (orientation trusted by the kernel), clearly intersecting: else exact path
  if (!(std::fabs(K.det[3]) > fb.deg3) || !(std::fabs(K.det[7]) > fb.deg3)) return false;
  const bool chosen =
      K.lo > fb.deg3 && pick_and_certify(K, fb, kNoUnresolved, ch, geometry, unique, with_certificate, band);
  if (chosen && (!with_certificate || ch.certified)) return true;
  if (!unresolved && !with_certificate) return chosen;
  const std::uint64_t un = unresolved_edge_pairs(K, fb);
  if (unresolved) *unresolved = un != 0;
  if (!with_certificate) return chosen;
  Unresolved bounds;  // (lo2 filled lane by lane: no value-initialisation)
  if (choice_without_unresolved(K, fb, un, bounds, ch, geometry, unique, band)) return true;
  // then without the edge pairs whose own bounds are loose as well (loose_edge_pairs): only
  // where the first attempt failed, which keeps every choice it makes
  const std::uint64_t loose = loose_edge_pairs(K, fb) & ~un;
  if (loose && choice_without_unresolved(K, fb, un | loose, bounds, ch, geometry, unique, band)) return true;
  return chosen;
}

bool superset_choice(const TetVertices& A, const TetVertices& B, Choice& ch, Candidate* geometry,
                     bool* unique, bool with_certificate, TieBandTest* band = nullptr) {
  SupersetLanes K;
  superset_kernel(A, B, K, nullptr);  // (non-finite input: garbage values, rejected next)
  return choice_of_lanes(K, ch, geometry, unique, with_certificate, nullptr, band);
}

}  // namespace

bool rigid_superset_scaled(const TetVertices& A, const TetVertices& B, Choice& ch, int& e,
                           Candidate* geometry, bool* unique, double* extent, bool* kernel_ran,
                           bool* unresolved, TieBandTest* band) {
  SupersetLanes K;
  const bool ran = superset_kernel_scaled(A, B, K, e);
  if (kernel_ran) *kernel_ran = ran;
  if (unresolved) *unresolved = false;
  if (!ran) return false;
  if (extent) *extent = K.extent;
  return choice_of_lanes(K, ch, geometry, unique, true, unresolved, band);
}

bool rigid_superset(const TetVertices& A, const TetVertices& B, Choice& ch, Candidate* geometry,
                    bool* unique, TieBandTest* band) {
  return superset_choice(A, B, ch, geometry, unique, true, band);
}

bool rigid_superset_of_kernel(SupersetLanes& K, Choice& ch, Candidate* geometry, bool* unique, bool* unresolved,
                              TieBandTest* band) {
  if (unresolved) *unresolved = false;
  return choice_of_lanes(K, ch, geometry, unique, true, unresolved, band);
}

bool rigid_superset_uncertified(const TetVertices& A, const TetVertices& B, Choice& ch) {
  return superset_choice(A, B, ch, nullptr, nullptr, false);
}

}  // namespace pdd::fast
