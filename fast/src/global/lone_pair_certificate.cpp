// lone_pair_certificate.cpp — see lone_pair_certificate.h for what is certified and why.
#include "global/lone_pair_certificate.h"

#include <algorithm>
#include <cmath>

#include "exact/expansion.h"

namespace pdd::fast::global {
namespace {

using detail::approx_of;
using detail::Expansion;
using detail::ExpVec;

// A lower bound of an exact expansion's value: approx_of's value less its error bound, less 4u of
// their magnitudes for the rounding of v - err itself.
double lower_of(const Expansion& e) {
  const detail::Approx a = approx_of(e);
  return (a.v - a.err) - 4 * kU * (std::fabs(a.v) + a.err);
}

// The largest (or least) of four exact heights, compared exactly.
const Expansion& extreme(const Expansion (&h)[4], bool largest) {
  int at = 0;
  for (int i = 1; i < 4; ++i) {
    const int s = detail::difference(h[i], h[at]).sign();
    if (largest ? s > 0 : s < 0) at = i;
  }
  return h[at];
}

// PD^2 along the exact direction n, rounded down: min(D(n), D(-n))^2 / n.n, each overlap a
// lower bound of its exact value, n.n an upper bound. +inf when n = 0 (parallel edges: no
// facet of M); false when an expansion overflowed its capacity or an overlap is not positive.
bool direction_lower(const ExpVec& n, const ExpVec (&xa)[4], const ExpVec (&xb)[4], double& out) {
  if (!n.ok()) return false;
  if (n.is_zero()) {
    out = INFINITY;
    return true;
  }
  ExpVec c;  // n with each component compressed: shorter products below
  for (int k = 0; k < 3; ++k) c.x[k] = detail::compressed(n.x[k]);
  Expansion ha[4], hb[4];
  for (int i = 0; i < 4; ++i) {
    ha[i] = detail::compressed(detail::dot(c, xa[i]));
    hb[i] = detail::compressed(detail::dot(c, xb[i]));
    if (!ha[i].ok || !hb[i].ok) return false;
  }
  const Expansion plus = detail::difference(extreme(ha, true), extreme(hb, false));   // D(n) |n|
  const Expansion minus = detail::difference(extreme(hb, true), extreme(ha, false));  // D(-n) |n|
  if (!plus.ok || !minus.ok) return false;
  const double d = std::min(lower_of(detail::compressed(plus)), lower_of(detail::compressed(minus)));
  if (!(d > 0)) return false;
  double nn = 0;
  for (int k = 0; k < 3; ++k) {
    const detail::Approx a = approx_of(c.x[k]);
    const double m = (std::fabs(a.v) + a.err) * (1 + 4 * kU);
    nn += m * m;
  }
  nn *= 1 + 8 * kU;  // the squares' and sums' roundings, upward
  out = d * d / nn * (1 - 8 * kU);
  return true;
}

}  // namespace

bool rigid_depth_squared_lower(const TetVertices& A, const TetVertices& B, double& pd2_low) {
  if (!detail::in_exact_range(A, B)) return false;
  ExpVec xa[4], xb[4];  // the vertices relative to A[0], exactly
  for (int i = 0; i < 4; ++i) xa[i] = detail::difference(A[i], A[0]), xb[i] = detail::difference(B[i], A[0]);
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  ExpVec ea[6], eb[6];
  for (int e = 0; e < 6; ++e) {
    ea[e] = detail::difference(A[kEdge[e][1]], A[kEdge[e][0]]);
    eb[e] = detail::difference(B[kEdge[e][1]], B[kEdge[e][0]]);
  }
  double low = INFINITY, x = 0;
  // Face normals (the cross product of two edges from one vertex: edges 0-1 and 0-2 for face
  // 012, and so on; any two edges of a face span its plane).
  static constexpr int kFaceEdges[4][2] = {{0, 1}, {0, 2}, {1, 2}, {3, 4}};  // faces 012, 013, 023, 123
  for (const auto& f : kFaceEdges) {
    if (!direction_lower(detail::cross(ea[f[0]], ea[f[1]]), xa, xb, x)) return false;
    low = std::min(low, x);
    if (!direction_lower(detail::cross(eb[f[0]], eb[f[1]]), xa, xb, x)) return false;
    low = std::min(low, x);
  }
  for (const ExpVec& a : ea)
    for (const ExpVec& b : eb) {
      if (!direction_lower(detail::cross(a, b), xa, xb, x)) return false;
      low = std::min(low, x);
    }
  if (!(low > 0) || !std::isfinite(low)) return false;
  pd2_low = low;
  return true;
}

namespace {

// Vertex pairs closer than this (relative to the pair's scale, in every coordinate) are taken
// as lone pairs: the certificate needs |a - b| / size far below its 8e-10 (header).
constexpr double kNear = 0x1p-24;
// Candidate normals evaluated (the shallowest by (v.d)^2 / v.v): one holds the minimiser where
// the certificate applies; a second covers a near tie of two extreme rays.
constexpr int kEvaluated = 2;
// The nudge of an extreme ray into its cone (radians, about): its two vertices move off their
// bounds by ~2^-40 of their distance to the plane (~1e-13 of a cell, far above the normal's
// rounding, ~1e-17), and (v.d)^2 / v.v by at most ~2^-39 relative (the least of the cone moves
// at first order along it), below the certificate's 8e-10.
constexpr double kNudge = 0x1p-40;

struct Candidate {
  V3 v;
  double key;
};

// The extreme rays of the lone pair (a = A's vertex i, b = B's vertex j)'s cone (header): each
// oriented so that A's other vertices lie below p_A and B's above p_B (within a loose
// tolerance: only a guess), and d = a - b points along it; kept sorted by (v.d)^2 / v.v.
void lone_pair_rays(const Problem& P, int i, int j, Candidate (&best)[kEvaluated], int& kept) {
  const V3 d = sub(P.relA[i], P.relB[j]);
  const V3 mid = mul(add(P.relA[i], P.relB[j]), 0.5);
  const V3 pA = sub(mid, mul(d, 0.125)), pB = add(mid, mul(d, 0.125));
  V3 u[6];
  bool onA[6];
  int m = 0;
  for (int k = 0; k < 4; ++k)
    if (k != i) u[m] = sub(P.relA[k], pA), onA[m++] = true;
  for (int k = 0; k < 4; ++k)
    if (k != j) u[m] = sub(P.relB[k], pB), onA[m++] = false;
  for (int s = 0; s < 6; ++s)
    for (int t = s + 1; t < 6; ++t) {
      V3 v = cross(u[s], u[t]);
      const double n = norm(v), ns = norm(u[s]), nt = norm(u[t]);
      if (!(n > 0 && ns > 0 && nt > 0) || !std::isfinite(n)) continue;
      if (dot(v, d) < 0) v = mul(v, -1.0);
      // Nudged into the cone (header: the ray's two vertices exactly at their bounds; the
      // normal's rounding, ~u size in height, would put either across by a fraction of the
      // depth): each moved away from the plane by ~kNudge |u|, the value moved by ~kNudge
      // relative.
      v = mul(v, 1 / n);
      v = add(v, mul(u[s], (onA[s] ? -kNudge : kNudge) / ns));
      v = add(v, mul(u[t], (onA[t] ? -kNudge : kNudge) / nt));
      const double vv = dot(v, v);
      const double tol = 1e-9 * std::sqrt(vv) * P.scale;
      bool inside = dot(v, d) > 0;
      bool clear = true;  // every vertex but the ray's two off its bound by more than ~2^-30
      for (int q = 0; q < 6 && inside; ++q) {
        const double slack = onA[q] ? -dot(v, u[q]) : dot(v, u[q]);
        inside = slack >= -tol;
        if (q != s && q != t) clear = clear && slack > 0x1p-30 * norm(u[q]);
      }
      if (!inside) continue;
      // A third vertex at its bound (the ray where three planes meet, as on grids) leaves the
      // lone pair to the rounding of the heights: such rays are evaluated after the clear ones.
      const double vd = dot(v, d), key = vd * vd / vv * (clear ? 1 : 2);
      if (kept == kEvaluated && !(key < best[kept - 1].key)) continue;
      int at = kept < kEvaluated ? kept++ : kept - 1;
      for (; at > 0 && best[at - 1].key > key; --at) best[at] = best[at - 1];
      best[at] = {v, key};
    }
}

}  // namespace

bool certify_lone_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out) {
  Candidate best[kEvaluated];
  int kept = 0;
  const double near = kNear * P.scale;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const V3 d = sub(P.relA[i], P.relB[j]);
      if (std::fabs(d[0]) <= near && std::fabs(d[1]) <= near && std::fabs(d[2]) <= near)
        lone_pair_rays(P, i, j, best, kept);
    }
  if (kept == 0) return false;
  Evaluation ev;
  V3 v{};
  for (int c = 0; c < kept; ++c) {
    const Evaluation e = evaluate_tight(A, B, P, best[c].v);
    if (e.error <= kGlobalRel && e.value < ev.value) ev = e, v = best[c].v;
  }
  if (!(ev.value < INFINITY)) return false;
  double pd2_low = 0;
  if (!rigid_depth_squared_lower(A, B, pd2_low)) return false;
  const double lower = pd2_low * kDeformableBoundCoeff;  // (an exact power of two)
  if (!(ev.value * (1 + kGlobalRel) <= lower * (1 + 8e-10))) return false;
  out.normal = v;
  out.eval = ev;
  out.lower = lower;
  return true;
}

}  // namespace pdd::fast::global
