// candidate_directions.cpp — definitions §3 candidate set with filtered exact decisions (the full
// path: any input, exact fallbacks). See the header; shared arithmetic in direction_geometry.h.
#include "kernel/candidate_directions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>

#include "certification/compensated_heights.h"
#include "certification/filter_bounds.h"
#include "certification/tie_tolerance.h"
#include "certification/value_bounds.h"
#include "exact/exact_predicates.h"
#include "exact/expansion.h"
#include "exact/integer_depth.h"
#include "exact/integer_heights.h"
#include "kernel/direction_geometry.h"
#include "kernel/edge_pair_formula.h"
#include "kernel/near_parallel_bound.h"
#include "kernel/power_scale.h"
#include "kernel/quick_candidates.h"

namespace pdd::fast {
namespace {

using namespace detail;

Sign orientation(const TetVertices& T, double det, double bound3) {
  if (det > bound3) return Sign::Positive;
  if (det < -bound3) return Sign::Negative;
  return orientation_sign_exact(T);
}

// Parallel edges: n = (e.e) w − (w.e) e (division-free form of definitions §3), heights directly.
void parallel_heights(const TetVertices& A, const Precomputed& p, int a, int b, Draft& c) {
  const int u = kEdges[a][0], x = kEdges[b][0];
  const double* e = p.eA[a];
  const double* w = p.d[u][x];
  const double ee = dot(e, e), we = dot(w, e);
  for (int k = 0; k < 3; ++k) c.n[k] = ee * w[k] - we * e[k];
  for (int k = 0; k < 4; ++k) {
    double sk[3];
    sub(A[k], A[u], sk);
    c.hA[k] = dot(c.n, sk);
    c.hB[k] = dot(c.n, p.d[u][k]);
  }
  const int v = kEdges[a][1], y = kEdges[b][1];
  c.hA[v] = c.hA[u] = 0.0;  // exactly: n.e = 0
  c.hB[y] = c.hB[x];        // exactly: n.(r_y − r_x) = 0 (parallel to e)
}

// (p1 − p0) × (q1 − q0) exactly non-zero, decided by a filter on the computed components, for
// pairs in the expansions' exact range (expansion.h: every coordinate difference and every
// product of two is then 0 or a normal double, so each operation below has relative error
// <= u = 2^-53). With d = p1 − p0, e = q1 − q0 and, for a component, P = fl(d~_i e~_j),
// Q = fl(d~_j e~_i), m~ = fl(P − Q): d~_i e~_j (1 + delta) = P gives P = d_i e_j (1 + t),
// |t| <= g3 = 3u/(1 − 3u), and likewise Q, so |m~/(1 + delta) − m| <= g3 (|d_i e_j| + |d_j e_i|)
// <= g3/(1 − g3) (|P| + |Q|). If m = 0 then |m~| <= (1 + u) g3/(1 − g3) (|P| + |Q|)
// < 3.01u (|P| + |Q|) < 8u (1 − u)(|P| + |Q|) <= 8u fl(|P| + |Q|) (the scaling by 8u = 2^-50
// exact). So |m~| > 8u fl(|P| + |Q|) for one component proves m != 0. "false": not decided.
bool cross_nonzero_filtered(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  double d[3], e[3];
  sub(p1, p0, d);
  sub(q1, q0, e);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double P = d[i] * e[j], Q = d[j] * e[i];
    if (std::fabs(P - Q) > 0x1p-50 * (std::fabs(P) + std::fabs(Q))) return true;
  }
  return false;
}

// For each face f of A, an edge a on it and the slot m of the lanes (g1 or g2) that holds
// eps G = eB.N_f on edge a's lanes (kOffFaces.face[a][m] == f).
struct FaceSlot {
  int a, m;
};
constexpr std::array<FaceSlot, 4> make_face_slots() {
  std::array<FaceSlot, 4> t{};
  for (int f = 0; f < 4; ++f)
    for (int a = 5; a >= 0; --a)
      for (int m = 1; m >= 0; --m)
        if (kOffFaces.face[a][m] == f) t[f] = FaceSlot{a, m};
  return t;
}
inline constexpr std::array<FaceSlot, 4> kFaceSlot = make_face_slots();

struct Builder {
  // A constructor, not an aggregate: face_normal stays uninitialised (filled where first
  // needed, face_normal_known says which) instead of zeroing four expansions per build.
  Builder(const TetVertices& a, const TetVertices& b, const FilterBounds& bounds, const Precomputed& pre,
          CandidateSet& set, double L)
      : A(a), B(b), fb(bounds), p(pre), out(set), extent(L) {
    out.delta_lower_known = false;
  }
  const TetVertices& A;
  const TetVertices& B;
  const FilterBounds& fb;
  const DegreeBounds generic = degree_bounds(fb, false);  // a generic candidate's bounds
  const Precomputed& p;
  CandidateSet& out;
  double extent;  // L (filter_bounds.h)
  bool in_range = in_exact_range(A, B);  // expansion.h's exact range
  int face_edge_sign[6][4] = {{2, 2, 2, 2}, {2, 2, 2, 2}, {2, 2, 2, 2},
                              {2, 2, 2, 2}, {2, 2, 2, 2}, {2, 2, 2, 2}};  // g_sign_exact; 2: not yet, 3: too long
  double face_sign[6][4];          // fill_face_signs: the exact sign of eB_b.N_f, as a double
  unsigned face_sign_unknown = 0;  // bit 4b + f: that sign beyond the expansions' reach
  ExpVec face_normal[4];  // A's raw face normals, exactly, as g_sign_exact needs them
  bool face_normal_known[4] = {false, false, false, false};
  std::optional<CompensatedNormal> face_normal_dw[4];  // the same in double words
  // parallel_heights of edge pair (a, b) as exactly_parallel computed them, lane 8a + b in
  // parallel_lane (−1: none); edge_pair_general takes them instead of computing them again
  // (the same function of the same inputs: the same bits).
  Draft parallel_draft;
  int parallel_lane = -1;
  // The pair's integer frame (integer_heights.h), found at its first use: where it exists the
  // exact signs below are taken over integers (a few dozen instructions each, exact zeros
  // included) before the double words and the expansions.
  detail::IntegerFrame frame{A, B};

  // Exact sign of candidate k's depth when the filter cannot decide it; false if <= 0.
  // D > 0 for candidate k: its computed depth beyond the bound, else compensated_depth's D
  // certainly positive (a contact made by rounding, D ~1e-17 of the size: ~1,500 instructions
  // where the expansions take ~6,000), else the exact sign.
  bool depth_positive(int k, double bound) {
    if (out.depth[k] > bound) return true;
    if (out.depth[k] < -bound) return false;
    // An edge pair along face f of A (along_face) has FV:f's oriented direction times a positive
    // number, and delta(n) is a function of the oriented direction (definitions §4): its depth
    // has FV:f's sign, found positive before any edge pair is built (run, run_on: a face with
    // depth <= 0 ends the scan). A mesh against a copy of itself moved by a rounding has most of
    // its touching edge pairs so (each ~1,400 instructions over the frame's integers).
    if (out.along_face[k] >= 0) return true;
    if (frame.usable()) {
      detail::FramedDepth d;
      if (!detail::framed_depth(frame, label(out, k), d) || d.D_sign != 1) return false;
      double v = 0, r = 0;
      if (detail::framed_delta2(frame, d, v, r)) {
        if (!out.delta_lower_known) std::fill(std::begin(out.delta_lower), std::end(out.delta_lower), 0.0);
        out.delta_lower_known = true;
        out.delta_lower[k] = lower_of(v, r);
      }
      return true;
    }
    detail::CompensatedDepth d;
    if (out.parallel[k] != 1 && detail::compensated_depth(A, B, label(out, k), d)) return true;
    return depth_sign_exact(A, B, label(out, k)) == Sign::Positive;
  }

  // Stores draft oriented by s (= ±1) in full as the next candidate; false if separating.
  // cls: 0 generic, 1 parallel, 2 nearly parallel with its own bounds `own` (CandidateSet).
  // along: CandidateSet::along_face (a decided edge pair's), else −1.
  bool emit(const Draft& d, double s, LabelCode code, double bound, int cls, const DegreeBounds& own,
            std::int16_t along = -1) {
    const int k = out.count++;
    out.parallel[k] = std::int16_t(cls);
    out.along_face[k] = along;
    const DegreeBounds e = cls == 2 ? own : degree_bounds(fb, cls == 1);
    out.e_h[k] = e.e_h;
    out.e_n[k] = e.e_n;
    DirectionGeometry& c = out.explicit_[k];
    orient_draft(d, s, c);
    out.code[k] = code;
    out.depth[k] = c.depth;
    out.nn[k] = c.nn;
    out.delta_sq[k] = c.depth * c.depth / c.nn;
    out.lane[k] = -1;
    out.sign[k] = 1;
    return depth_positive(k, bound);
  }

  // Nearly parallel edges (n~ below kExactNormalBelow E2): n = eB × eA exactly (expansion.h);
  // when it is not 0, the draft is redone along n rounded (n~_k within 3u|n_k|) with heights
  // along it, and `own` gets their bounds (value_bounds.h, own_degree_bounds). False when n is
  // exactly 0 (parallel or colinear) or the pair is outside the expansions' exact range.
  // `parallel` is set when n is exactly 0.
  bool near_parallel_normal(int a, int b, Draft& c, DegreeBounds& own, bool& parallel) {
    parallel = false;
    if (!in_range) return false;
    const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
    if (!exact_normal(a, b, c.n, parallel) || parallel) return false;
    for (int k = 0; k < 4; ++k) {
      double sk[3];
      sub(A[k], A[u], sk);
      c.hA[k] = dot(c.n, sk);
      c.hB[k] = dot(c.n, p.d[u][k]);
    }
    c.hA[u] = c.hA[v] = 0.0;  // exactly: n.eA = 0
    c.hB[y] = c.hB[x];        // exactly: n.eB = 0
    own = own_degree_bounds(c.n, extent);
    return true;
  }

  // The edge pair's exact kind and rule: over the frame's integers, else exact_predicates.h's.
  EdgePairClass classify_exact(int a, int b) {
    return frame.usable() ? detail::classify_edge_pair_framed(frame, a, b) : classify_edge_pair_exact(A, B, a, b);
  }

  // n = eB × eA of edge pair (a, b) exactly, rounded (each n~_k within 3u |n_k|): over the frame's
  // integers (converted with one rounding, then scaled by a power of two: exact, the pair being in
  // the expansions' range, so that 2^(2e) >= 2^-520), else by expansions. `parallel`: n = 0.
  // False where the expansions exceed their capacity (the exact classification then decides).
  bool exact_normal(int a, int b, double (&n)[3], bool& parallel) {
    const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
    if (frame.usable()) {
      __int128 m[3];
      frame.normal(4 + y, 4 + x, v, u, m);
      parallel = m[0] == 0 && m[1] == 0 && m[2] == 0;
      for (int k = 0; k < 3; ++k) n[k] = detail::times_pow2(double(m[k]), 2 * frame.unit_exponent());
      return true;
    }
    const ExpVec e = detail::cross(difference(B[y], B[x]), difference(A[v], A[u]));
    if (!e.ok()) return false;
    parallel = e.is_zero();
    for (int k = 0; k < 3; ++k) n[k] = e.x[k].approx();
    return true;
  }

  // Exact sign of g_i = n.(s_i − s_u), n = eB × eA, for an off-edge vertex i of edge a (u, v):
  // n.(s_i − s_u) = eB.((s_v − s_u) × (s_i − s_u)) and that cross product is ±N, N the raw
  // normal of A's face {u, v, i} (kFace order; + for an even permutation of it, a cross
  // product of a triangle's edges being invariant under cyclic shifts), so sign(g_i) =
  // ±sign(eB.N). The 24 signs eB.N (6 edges of B, 4 faces of A) are cached: aligned pairs
  // ask for the same few many times. Each is taken in double words where they certify it
  // (compensated_heights.h: the same N and eB, a non-zero sign; a mesh against its shifted
  // copy has B's edges in A's face planes up to a rounding: ~140 instructions a sign and ~230
  // a face's normal, where the expansions take thousands), else by expansions. Precondition: the pair is in the expansions'
  // range. Returns 3 when the expansions exceed their capacity (expansion.h).
  int g_sign_exact(int a, int b, int i) {
    const int u = kEdges[a][0], v = kEdges[a][1];
    const int f = kOffEdge[a][0] == i ? kOffEdge[a][1] : kOffEdge[a][0];  // {u, v, i} = face f
    const int s = face_edge_sign_exact(b, f);
    if (s == 3) return 3;
    // parity of (u, v, i) against the increasing order (u < v always): inversions of i
    const int inversions = (i < u) + (i < v);
    return inversions == 1 ? -s : s;
  }

  // The exact sign of eB.N_f (g_sign_exact's s, cached), 3 beyond the expansions' capacity.
  int face_edge_sign_exact(int b, int f) {
    int& s = face_edge_sign[b][f];
    if (s == 2 && (triple_zero(b, f) || edge_copy_in_face(b, f))) s = 0;
    if (s == 2 && frame.usable()) {
      const auto& F = kFace[f];
      s = frame.height_sign(F[1], F[0], F[2], F[0], 4 + kEdges[b][1], 4 + kEdges[b][0]);
    }
    if (s == 2) {
      const auto& F = kFace[f];
      if (!face_normal_dw[f]) face_normal_dw[f] = compensated_normal(A[F[1]], A[F[0]], A[F[2]], A[F[0]]);
      int sign = 0;
      if (compensated_height_sign(*face_normal_dw[f], B[kEdges[b][1]], B[kEdges[b][0]], sign)) s = sign;
    }
    if (s == 2) {
      if (!face_normal_known[f]) {
        const auto& F = kFace[f];
        face_normal[f] = detail::cross(difference(A[F[1]], A[F[0]]), difference(A[F[2]], A[F[0]]));
        face_normal_known[f] = true;
      }
      const ExpVec& N = face_normal[f];
      const Expansion g = dot(difference(B[kEdges[b][1]], B[kEdges[b][0]]), N);
      s = g.ok ? g.sign() : 3;  // 3: beyond the expansions' capacity
    }
    return s;
  }

  // eB = ± an edge of A's face f, both differences exact in doubles (two_sum's error 0) and
  // equal: eB lies in f's plane, so eB.N_f = 0 exactly. A mesh against its copy shifted by an
  // offset whose roundings cancel at both ends of an edge (most edges of such a copy).
  bool edge_copy_in_face(int b, int f) const {
    double e[3];
    if (!exact_difference(B[kEdges[b][1]], B[kEdges[b][0]], e)) return false;
    const auto& F = kFace[f];
    for (int m = 0; m < 3; ++m) {
      double d[3];
      if (!exact_difference(A[F[(m + 1) % 3]], A[F[m]], d)) continue;
      const bool plus = d[0] == e[0] && d[1] == e[1] && d[2] == e[2];
      const bool minus = d[0] == -e[0] && d[1] == -e[1] && d[2] == -e[2];
      if (plus || minus) return true;
    }
    return false;
  }
  static bool exact_difference(const Vec3d& p, const Vec3d& q, double d[3]) {
    for (int k = 0; k < 3; ++k) {
      double err;
      two_sum(p[k], -q[k], d[k], err);
      if (err != 0.0) return false;
    }
    return true;
  }

  // eB.N_f certainly 0 by structural zeros (triple_zero), asked through g_sign_exact's cache.
  bool g_zero(int b, int f) {
    int& s = face_edge_sign[b][f];
    if (s == 2 && triple_zero(b, f)) s = 0;
    return s == 0;
  }

  // The face f of A on edge a whose plane holds edge b's direction, eB.N_f = 0 exactly (the g of
  // f's third vertex), else −1: CandidateSet::along_face of edge pair (a, b) where its n is not
  // 0 (not both: A is valid). Precondition: fill_face_signs has run.
  std::int16_t along_face_of(int a, int b) const {
    const int f0 = kOffFaces.face[a][0], f1 = kOffFaces.face[a][1];
    const bool zero0 = ((face_sign_unknown >> (4 * b + f0)) & 1u) == 0 && face_sign[b][f0] == 0.0;
    const bool zero1 = ((face_sign_unknown >> (4 * b + f1)) & 1u) == 0 && face_sign[b][f1] == 0.0;
    return std::int16_t(zero0 ? f0 : zero1 ? f1 : -1);
  }

  // Lane i = (a, b) unclear only through the signs of its g's (a face of A whose plane holds
  // eB's direction, or nearly: aligned pairs, and meshes whose grid a generator placed up to a
  // rounding, most of their unclear lanes): n clear of the nearly parallel test and the depths
  // the orientation uses beyond their bounds, each g's exact sign known (fill_face_signs, as
  // classify() decides it through g_sign_exact: structural zeros, the integer frame, double
  // words, expansions; g_m = eps_m eB.N_f). classify() would give the side these
  // signs give (a 0 counts on neither side: Keep when no g > 0, Flip when no g < 0, else both
  // orientations) and edge_pair_general would store the lane's own heights and n, with the
  // bounds it gives a generic pair (fb.deg3): so the lane is written as a clear one, its
  // orientation `flip` and `undecidable` set here. False where a sign is beyond the
  // expansions' reach or the lane is unclear otherwise (edge_pair_general decides it). (EdgeLanes'
  // verdict stays unclear: the quick lists, which read g's computed signs, still decline the pair.)
  // Precondition: fill_face_signs has run on these lanes. Branch-free (edge_pairs).
  // `along`: along_face_of(a, b), meaningful where the lane is clear (n != 0).
  bool clear_but_g(int a, int b, int i, bool& flip, bool& undecidable, std::int16_t& along) const {
    const EdgeLanes& L = out.edges;
    const double e3 = fb.deg3;
    const double n[3] = {L.n0[i], L.n1[i], L.n2[i]};
    const int f0 = kOffFaces.face[a][0], f1 = kOffFaces.face[a][1];
    const double s0 = kOffFaces.eps[a][0] * face_sign[b][f0], s1 = kOffFaces.eps[a][1] * face_sign[b][f1];
    const bool known = (((face_sign_unknown >> (4 * b + f0)) | (face_sign_unknown >> (4 * b + f1))) & 1u) == 0;
    const bool pos = (s0 > 0.0) | (s1 > 0.0), neg = (s0 < 0.0) | (s1 < 0.0);
    flip = pos & !neg;
    undecidable = pos & neg;
    along = along_face_of(a, b);
    return (max_abs3(n) > kExactNormalBelow * fb.deg2) & known & ((L.dplus[i] > e3) | flip) &
           ((L.dminus[i] > e3) | !(flip | undecidable));
  }

  // The signs clear_but_g reads: face_sign[b][f], the exact sign of G = eB_b.N_f (A's raw face
  // normal f, kFace order) as a double, −1, 0 or 1, for all 24 (b, f) at once. The lanes hold
  // G bit for bit (g_m = eps_m G, edge_pair_formula.h's kOffFaces: a product by ±1, exact), so
  // |G| beyond the degree-3 bound gives the computed sign; within it the sign is decided as
  // g_sign_exact decides it (a computed 0 shown exact by structural zeros, else, in the
  // expansions' range, face_edge_sign_exact), and face_sign_unknown gets bit 4b + f where that
  // is beyond reach. Filled before the lanes are written, so that each unclear lane's verdict is
  // a few loads and no branch on its own data (the lanes of an aligned pair are unclear in
  // no pattern a branch predictor follows).
  void fill_face_signs() {
    const EdgeLanes& L = out.edges;
    const double e3 = fb.deg3;
    unsigned open = 0;
    double G[6][4];
    for (int b = 0; b < 6; ++b)
      for (int f = 0; f < 4; ++f) {
        const FaceSlot& t = kFaceSlot[f];
        const double* g = t.m == 0 ? L.g1 : L.g2;
        G[b][f] = kOffFaces.eps[t.a][t.m] * g[kLaneStride * t.a + b];
        face_sign[b][f] = double((G[b][f] > 0.0) - (G[b][f] < 0.0));
        open |= unsigned(!(std::fabs(G[b][f]) > e3)) << (4 * b + f);
      }
    face_sign_unknown = 0;
    for (unsigned bits = open; bits; bits &= bits - 1) {
      const int j = __builtin_ctz(bits), b = j / 4, f = j % 4;
      int s = 3;
      if (G[b][f] == 0.0 && g_zero(b, f)) s = 0;
      else if (in_range) s = face_edge_sign_exact(b, f);
      if (s == 3) face_sign_unknown |= 1u << j;
      else face_sign[b][f] = double(s);
    }
  }

  // eB.N exactly 0 (structural zeros, see cross_zero), N = (s_F1 − s_F0) × (s_F2 − s_F0) the raw
  // normal of A's face f (kFace order) and eB = r_y − r_x edge b of B: every term eB_k N_k has
  // an exactly zero factor.
  bool triple_zero(int b, int f) const {
    const auto& F = kFace[f];
    const Vec3d &x = B[kEdges[b][0]], &y = B[kEdges[b][1]];
    bool zero = true;  // (& over the three terms, not a branch each: see cross_zero)
    for (int k = 0; k < 3; ++k) zero &= (y[k] == x[k]) | cross_component_zero(A[F[0]], A[F[1]], A[F[0]], A[F[2]], k);
    return zero;
  }

  // own.e_h > 0: the draft was redone by near_parallel_normal and its heights have error
  // <= own.e_h; else the filter bounds apply.
  // Exactly parallel edges (n = 0, in the expansions' range): colinear iff w × e = 0 exactly
  // (the parallel normal (e.e) w − (w.e) e = e × (w × e) has length |e| |w × e|); else the
  // orientation rule on the parallel heights (error <= E4/4, value_bounds.h) when they clear it.
  EdgePairClass exactly_parallel(int a, int b) {
    const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0];
    EdgePairClass k;
    if (cross_zero(A[u], B[x], A[u], A[v])) {  // (r_x − s_u) × e exactly 0: colinear
      k.kind = EdgePairKind::Colinear;
      return k;
    }
    if (!cross_nonzero_filtered(A[u], B[x], A[u], A[v])) {
      if (frame.usable()) return classify_exact(a, b);
      const ExpVec m = detail::cross(difference(B[x], A[u]), difference(A[v], A[u]));
      if (!m.ok()) return classify_exact(a, b);
      if (m.is_zero()) {
        k.kind = EdgePairKind::Colinear;
        return k;
      }
    }
    k.kind = EdgePairKind::Parallel;
    Draft& d = parallel_draft;
    parallel_heights(A, p, a, b, d);
    parallel_lane = kLaneStride * a + b;
    int lo = 0, hi = 0;
    for (int i : kOffEdge[a]) {
      const double g = d.hA[i];
      if (std::fabs(g) <= fb.deg4 / 4) return classify_exact(a, b);
      lo += g < 0;
      hi += g > 0;
    }
    k.side = hi == 0 ? EdgePairSide::Keep : lo == 0 ? EdgePairSide::Flip : EdgePairSide::Undecidable;
    return k;
  }

  EdgePairClass classify(int a, int b, Draft& c, DegreeBounds& own) {
    own = DegreeBounds{0.0, 0.0};
    bool parallel = false;
    // n = eB × eA exactly 0 by structural zeros: parallel or colinear without the expansions
    // (exactly_parallel's precondition, the expansions' range, as near_parallel_normal's).
    // (or by exact products: a copy of an edge whose coordinate differences are exact)
    if (in_range && max_abs3(c.n) <= fb.deg2 &&
        cross_zero_in_doubles(B[kEdges[b][0]], B[kEdges[b][1]], A[kEdges[a][0]], A[kEdges[a][1]]))
      return exactly_parallel(a, b);
    // n~ small (value_bounds.h, kExactNormalBelow): taken exactly, with its own bounds; where
    // the expansions cannot, n~ within the degree-2 filter is classified exactly, and a larger
    // one (certainly not 0) keeps the filter bounds
    if (max_abs3(c.n) <= kExactNormalBelow * fb.deg2 && !near_parallel_normal(a, b, c, own, parallel) &&
        (parallel || max_abs3(c.n) <= fb.deg2))
      return parallel ? exactly_parallel(a, b) : classify_exact(a, b);
    const double eg = own.e_h > 0.0 ? own.e_h : fb.deg3;
    EdgePairClass k;
    int lo = 0, hi = 0;
    for (int i : kOffEdge[a]) {
      int g = c.hA[i] > 0.0 ? 1 : -1;
      if (std::fabs(c.hA[i]) <= eg) {
        if (!in_range) return classify_exact(a, b);
        g = g_sign_exact(a, b, i);
        if (g == 3) return classify_exact(a, b);
      }
      lo += g < 0;
      hi += g > 0;
    }
    k.side = hi == 0 ? EdgePairSide::Keep : lo == 0 ? EdgePairSide::Flip : EdgePairSide::Undecidable;
    return k;
  }

  // Any edge pair, with the exact classification when the filter cannot decide (slow path).
  bool edge_pair_general(int a, int b) {
    Draft c;
    lane_heights(out.edges, a, b, c);
    DegreeBounds own;
    const EdgePairClass k = classify(a, b, c, own);
    if (k.kind == EdgePairKind::Colinear) return true;  // no direction (definitions §3)
    double bound = fb.deg3;
    int cls = 0;
    if (k.kind == EdgePairKind::Parallel) {
      if (parallel_lane == kLaneStride * a + b) {  // n, hA, hB: parallel_heights(A, p, a, b, c)
        std::memcpy(c.n, parallel_draft.n, sizeof c.n);
        std::memcpy(c.hA, parallel_draft.hA, sizeof c.hA);
        std::memcpy(c.hB, parallel_draft.hB, sizeof c.hB);
      } else {
        parallel_heights(A, p, a, b, c);
      }
      bound = fb.deg4;
      cls = 1;
    } else if (own.e_h > 0.0) {
      // |D~ − D| <= 2 e_h + u|D| (value_bounds.h) < |D~| when |D~| > 4 e_h
      bound = 4 * own.e_h;
      cls = 2;
    }
    const LabelCode decided = pack_label(ContactKind::EE, a, b, EdgeOrientation::Decided);
    // (n exactly not 0 unless parallel; the face signs are filled: this lane was unclear)
    const std::int16_t along = cls == 1 ? std::int16_t(-1) : along_face_of(a, b);
    if (k.side == EdgePairSide::Keep) return emit(c, 1.0, decided, bound, cls, own, along);
    if (k.side == EdgePairSide::Flip) return emit(c, -1.0, decided, bound, cls, own, along);
    return emit(c, 1.0, pack_label(ContactKind::EE, a, b, EdgeOrientation::Plus), bound, cls, own) &&
           emit(c, -1.0, pack_label(ContactKind::EE, a, b, EdgeOrientation::Minus), bound, cls, own);
  }

  // Lane i = (a, b) written as candidate k and, branch-free, the ':-' one after it; returns the
  // count after it (k + 2 only for an undecidable pair). first: delta² of the orientation kept.
  int write_lane(int k, int a, int b, int i, bool flip, bool undecidable, double first, std::int16_t along) {
    static_assert(int(EdgeOrientation::Decided) == 0 && int(EdgeOrientation::Plus) == 1);
    const EdgeLanes& L = out.edges;
    const double* const depth_of[2] = {L.dplus, L.dminus};  // (indexed, not a branch: see edge_pairs)
    out.code[k] = pack_label(ContactKind::EE, a, b, EdgeOrientation(int(undecidable)));
    out.code[k + 1] = pack_label(ContactKind::EE, a, b, EdgeOrientation::Minus);
    out.depth[k] = depth_of[flip][i];
    out.depth[k + 1] = L.dminus[i];
    out.delta_sq[k] = first;
    out.delta_sq[k + 1] = L.d2minus[i];
    out.nn[k] = out.nn[k + 1] = L.nn[i];
    out.sign[k] = std::int16_t(1 - 2 * int(flip));
    out.sign[k + 1] = -1;
    out.lane[k] = out.lane[k + 1] = std::int16_t(i);
    out.parallel[k] = out.parallel[k + 1] = 0;
    out.e_h[k] = out.e_h[k + 1] = generic.e_h;
    out.e_n[k] = out.e_n[k + 1] = generic.e_n;
    out.along_face[k] = along;
    out.along_face[k + 1] = -1;
    return k + 1 + undecidable;
  }

  // All edge pairs in canonical order. A lane with clear filter verdicts (edge_lanes) is written
  // from its lane (its g's are not 0: flip when both are > 0, undecidable when their signs
  // differ, its verdict's `first`); so is a lane unclear only through its g's signs
  // (clear_but_g), by the rule on their exact signs, a 0 on neither side; any other unclear lane
  // goes to edge_pair_general. In three passes: every lane's orientation from its computed g's,
  // the unclear lanes' from their exact signs (or marked for edge_pair_general), then the lanes
  // written in canonical order. The verdicts are data no branch predictor follows on an aligned
  // pair (~26 of the 36 lanes unclear, in no pattern), so they are not branched on per lane:
  // the clear ones are not visited in the second pass, and the third branches only on the lanes
  // edge_pair_general takes.
  bool edge_pairs() {
    const EdgeLanes& L = out.edges;
    bool flip[kLanes], undecidable[kLanes];
    double first[kLanes];
    std::int16_t along[kLanes];
    std::uint64_t unclear = 0;  // bit i: lane i unclear
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        const int i = kLaneStride * a + b;
        const bool pos1 = L.g1[i] > 0.0, pos2 = L.g2[i] > 0.0;
        flip[i] = pos1 & pos2;
        undecidable[i] = pos1 ^ pos2;
        first[i] = L.first[i];
        along[i] = -1;  // (a clear lane's g's are certainly not 0)
        unclear |= std::uint64_t(L.unclear[i] != 0.0) << i;
      }
    std::uint64_t general = 0;  // bit i: lane i goes to edge_pair_general
    if (unclear != 0) {
      const double* const d2_of[2] = {L.d2plus, L.d2minus};
      fill_face_signs();
      for (std::uint64_t bits = unclear; bits; bits &= bits - 1) {
        const int i = __builtin_ctzll(bits);
        bool f = false, u = false;
        const bool clear = clear_but_g(i / kLaneStride, i % kLaneStride, i, f, u, along[i]);
        flip[i] = f;
        undecidable[i] = u;
        first[i] = d2_of[f][i];
        general |= std::uint64_t(!clear) << i;
      }
    }
    int k = out.count;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        const int i = kLaneStride * a + b;
        if ((general >> i & 1u) == 0) {
          k = write_lane(k, a, b, i, flip[i], undecidable[i], first[i], along[i]);
          continue;
        }
        out.count = k;
        if (!edge_pair_general(a, b)) return false;
        k = out.count;
      }
    out.count = k;
    return true;
  }

  // The faces and lanes of a quick list (a face's depth > E3 is depth_positive's first test;
  // the others, of a list with faces_filled, are decided as run() decides them), then the edge
  // pairs as run() does.
  bool run_on(const QuickCandidates& q) {
    for (int f = 0; f < 8; ++f) {
      const int k = out.count++;
      out.explicit_[k] = q.faces[f];
      out.code[k] = f < 4 ? pack_label(ContactKind::FV, f, 0, EdgeOrientation::Decided)
                          : pack_label(ContactKind::VF, f - 4, 0, EdgeOrientation::Decided);
      out.depth[k] = q.depth[f];
      out.nn[k] = q.nn[f];
      out.delta_sq[k] = q.delta_sq[f];
      out.lane[k] = -1;
      out.sign[k] = 1;
      out.parallel[k] = 0;
      out.e_h[k] = generic.e_h, out.e_n[k] = generic.e_n;
      out.along_face[k] = -1;
      if (!depth_positive(k, fb.deg3)) return false;
    }
    out.edges = q.edges;
    return edge_pairs();
  }

  bool run() {
    for (int f = 0; f < 8; ++f) {
      const int k = out.count++;
      DirectionGeometry& c = out.explicit_[k];
      face_geometry(p, f, c);
      out.code[k] = f < 4 ? pack_label(ContactKind::FV, f, 0, EdgeOrientation::Decided)
                          : pack_label(ContactKind::VF, f - 4, 0, EdgeOrientation::Decided);
      out.depth[k] = c.depth;
      out.nn[k] = c.nn;
      out.delta_sq[k] = c.depth * c.depth / c.nn;
      out.lane[k] = -1;
      out.sign[k] = 1;
      out.parallel[k] = 0;
      out.e_h[k] = generic.e_h, out.e_n[k] = generic.e_n;
      out.along_face[k] = -1;
      if (!depth_positive(k, fb.deg3)) return false;
    }
    // (a lane whose n~ is small is unclear: edge_pair_general takes its n exactly)
    edge_lanes(p, kExactNormalBelow * fb.deg2, fb.deg3, out.edges);
    return edge_pairs();
  }
};

}  // namespace

BuildStatus build_candidates(const TetVertices& A, const TetVertices& B, CandidateSet& out) {
  out.count = 0;
  out.intersecting = false;
  out.A = &A;
  out.B = &B;
  if (!all_finite(A)) return BuildStatus::NonFiniteA;
  if (!all_finite(B)) return BuildStatus::NonFiniteB;
  const FilterBounds fb = filter_bounds(A, B);
  out.tie_kappa = tie_kappa(A, B);
  out.fb = fb;
  Precomputed p;
  precompute(A, B, p);
  p.oA = orientation(A, p.detA, fb.deg3);
  if (p.oA == Sign::Zero) return BuildStatus::DegenerateA;
  p.oB = orientation(B, p.detB, fb.deg3);
  if (p.oB == Sign::Zero) return BuildStatus::DegenerateB;
  out.intersecting = Builder(A, B, fb, p, out, pair_extent(A, B)).run();
  return BuildStatus::Ok;
}

BuildStatus build_candidates(const QuickCandidates& q, CandidateSet& out) {
  const TetVertices& A = *q.A;
  const TetVertices& B = *q.B;
  out.count = 0;
  out.intersecting = false;
  out.A = &A;
  out.B = &B;
  out.tie_kappa = q.tie_kappa;
  out.fb = q.fb;
  // What the Builder reads of Precomputed besides the faces and lanes: A's edge vectors and the
  // differences r_j − s_i (parallel and nearly parallel edge pairs), as precompute computes them.
  Precomputed p;
  for (int a = 0; a < 6; ++a) sub(A[kEdges[a][1]], A[kEdges[a][0]], p.eA[a]);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sub(B[j], A[i], p.d[i][j]);
  out.intersecting = Builder(A, B, q.fb, p, out, pair_extent(A, B)).run_on(q);
  return BuildStatus::Ok;
}

namespace {

bool same_bits(const TetVertices& x, const TetVertices& y) {
  return std::memcmp(x.data(), y.data(), sizeof(TetVertices)) == 0;
}

struct LastBuild {
  bool valid = false;  // set and status are build_candidates(A, B)'s
  BuildStatus status = BuildStatus::Ok;
  TetVertices A, B;
  CandidateSet set;
};

}  // namespace

int exact_lanes(const CandidateSet& set) {
  int m = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) m += set.edges.unclear[kLaneStride * a + b] != 0.0;
  return m;
}

const CandidateSet& build_candidates_reusing(const TetVertices& A, const TetVertices& B, BuildStatus& status,
                                             const QuickCandidates* declined) {
  thread_local LastBuild last;  // (~20 KB: off the stack, once per thread)
  if (!(last.valid && same_bits(last.A, A) && same_bits(last.B, B))) {
    last.valid = false;
    last.status = declined ? build_candidates(*declined, last.set) : build_candidates(A, B, last.set);
    last.A = A;
    last.B = B;
    last.valid = true;
  }
  last.set.A = &A;
  last.set.B = &B;
  status = last.status;
  return last.set;
}

Candidate candidate(const CandidateSet& set, int k) {
  Candidate c;
  c.label = label(set, k);
  if (set.lane[k] < 0) {
    static_cast<DirectionGeometry&>(c) = set.explicit_[k];
    c.parallel = set.parallel[k] == 1;
    c.own_bounds = set.parallel[k] == 2;
    if (c.own_bounds) c.own_eh = set.e_h[k], c.own_en = set.e_n[k];
    return c;
  }
  detail::lane_candidate(set.edges, set.lane[k], set.sign[k], c);
  return c;
}

}  // namespace pdd::fast
