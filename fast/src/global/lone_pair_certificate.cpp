// lone_pair_certificate.cpp — see lone_pair_certificate.h for what is certified and why.
#include "global/lone_pair_certificate.h"

#include <algorithm>
#include <cmath>

#include "exact/expansion.h"

namespace pdd::fast::global {
namespace {

using detail::Expansion;
using detail::ExpVec;

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
  V3 d;      // the offset a - b of the pair it was built for (an edge pair's mean offset, rounded)
  V3 nudge;  // v = the extreme ray + nudge (into the lone pair's cone)
  double d_error = 0;  // |d - the exact offset| <= d_error (an edge pair's mean rounded)
  bool translate = true;  // a vertex pair, or an edge pair of translates (d exact)
};

// best[0 .. kept) sorted by key, the kEvaluated least kept.
void keep_shallowest(Candidate (&best)[kEvaluated], int& kept, const Candidate& c) {
  if (kept == kEvaluated && !(c.key < best[kept - 1].key)) return;
  int at = kept < kEvaluated ? kept++ : kept - 1;
  for (; at > 0 && best[at - 1].key > c.key; --at) best[at] = best[at - 1];
  best[at] = c;
}

// The least certified evaluation among the candidates (value +inf when none).
Evaluation least_evaluation(const TetVertices& A, const TetVertices& B, const Problem& P,
                            const Candidate (&best)[kEvaluated], int kept, Candidate& chosen) {
  Evaluation ev;
  for (int c = 0; c < kept; ++c) {
    const Evaluation e = evaluate_tight(A, B, P, best[c].v);
    if (e.error <= kGlobalRel && e.value < ev.value) ev = e, chosen = best[c];
  }
  return ev;
}

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
      const V3 nudge = add(mul(u[s], (onA[s] ? -kNudge : kNudge) / ns), mul(u[t], (onA[t] ? -kNudge : kNudge) / nt));
      v = add(v, nudge);
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
      const double vd = dot(v, d);
      keep_shallowest(best, kept, {v, vd * vd / vv * (clear ? 1 : 2), d, nudge});
    }
}

bool lone_pair(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds,
               LonePairResult& out) {
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
  Candidate chosen{};
  const Evaluation ev = least_evaluation(A, B, P, best, kept, chosen);
  if (!(ev.value < INFINITY)) return false;
  double pd2_low = 0;
  if (!pd2_lower(bounds, pd2_low)) return false;
  const double lower = pd2_low * kDeformableBoundCoeff;  // (an exact power of two)
  if (!(ev.value * (1 + kGlobalRel) <= lower * (1 + 8e-10))) {
    // the ray nudged out of the cone instead: its two vertices just across their bounds, in the
    // neighbouring piece, whose chart holds the minimiser when it lies there
    out.near_minimiser = sub(chosen.v, mul(chosen.nudge, 2.0));
    return false;
  }
  out.normal = chosen.v;
  out.eval = ev;
  out.lower = lower;
  return true;
}


// A's vertices i -> i2 and B's j -> j2 whose offsets d1 = A[i] - B[j] and d2 = A[i2] - B[j2]
// are exact in doubles: d the mean offset (d1 + d2) / 2 rounded, within d_error of it (each
// component's sum rounded once, its error from two_sum, halved exactly but for a subnormal sum;
// the 1-norm of the errors bounds their 2-norm), and l = A[i2] - A[i]
// (rounded: a guess for the rays). translate: A[i2] - A[i] = B[j2] - B[j] exactly (the same
// edge vector, l exact), so that d1 = d2 = d exactly.
struct EdgeOffsets {
  V3 l{}, d{};
  double d_error = 0;
  bool translate = true;
};
bool edge_offsets(const TetVertices& A, const TetVertices& B, int i, int i2, int j, int j2, EdgeOffsets& o) {
  double err = 0;
  for (int k = 0; k < 3; ++k) {
    if (detail::difference(A[i][k], B[j][k]).n > 1 || detail::difference(A[i2][k], B[j2][k]).n > 1)
      return false;  // (an offset is not a double)
    const Expansion ea = detail::difference(A[i2][k], A[i][k]), eb = detail::difference(B[j2][k], B[j][k]);
    o.translate = o.translate && ea.n <= 1 && detail::difference(ea, eb).sign() == 0;
    o.l[k] = A[i2][k] - A[i][k];
    double x, y;
    detail::two_sum(A[i][k] - B[j][k], A[i2][k] - B[j2][k], x, y);
    o.d[k] = 0.5 * x;
    err += 0.5 * std::fabs(y) + (x != 0 && std::fabs(x) < 0x1p-1020 ? 0x1p-1074 : 0.0);  // (halving a subnormal)
  }
  o.d_error = err * (1 + 4 * kU);
  return std::isfinite(o.d_error);
}

// Where l has no zero component: v's components i and j (k the largest of l's) on the grid of
// 2^-40 of the larger of them, and v_k = -(v_i l_i + v_j l_j) / l_k in doubles, kept where the
// triple's dot product with l is exactly 0 (its three products summed exactly: expansion.h).
// On the diagonal edges of grids of cubes (|l_i| = |l_j| = |l_k|) the sum and the quotient are
// exact; the grid moves v by at most 2^-40 of itself, within the perpendicular plane (the nudge
// covers it). false where the dot product is not 0.
bool exactly_across_solved(const V3& l, V3& v) {
  int k = 0;
  for (int q = 1; q < 3; ++q)
    if (std::fabs(l[q]) > std::fabs(l[k])) k = q;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double big = std::fmax(std::fabs(v[i]), std::fabs(v[j]));
  if (!(big > 0) || !std::isfinite(big)) return false;
  int e = 0;
  std::frexp(big, &e);
  const double grid = std::ldexp(1.0, e - 40);
  V3 w;
  w[i] = std::nearbyint(v[i] / grid) * grid, w[j] = std::nearbyint(v[j] / grid) * grid;
  w[k] = -(w[i] * l[i] + w[j] * l[j]) / l[k];
  if (!std::isfinite(w[k]) || !(grid > 0)) return false;
  detail::Expansion dot_wl;
  for (int q = 0; q < 3; ++q) {
    double x, y;
    detail::two_product(w[q], l[q], x, y);
    detail::grow(dot_wl, y), detail::grow(dot_wl, x);
  }
  if (!dot_wl.ok || dot_wl.sign() != 0) return false;
  v = w;
  return true;
}

// v turned, within its plane through l's normal, into a double triple exactly perpendicular to
// l: where l has a zero component k, (l_j, -l_i) in the other two (times a power of two: exact)
// plus t e_k is, for every double t (its dot with l is l_j l_i - l_i l_j = 0 exactly). A tilt
// along l of u |v| would split the two edges' heights by ~u size, a fraction of the depth (the
// value then ~1e-3 off); within the perpendicular plane t's rounding only moves the normal along
// the regime (the nudge covers it). Else exactly_across_solved.
bool exactly_across(const V3& l, V3& v) {
  int k = -1;
  for (int q = 0; q < 3 && k < 0; ++q)
    if (l[q] == 0) k = q;
  if (k < 0) return exactly_across_solved(l, v);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double ri = l[j], rj = -l[i];  // l turned a quarter in the plane (i, j)
  const double a = (v[i] * ri + v[j] * rj) / (ri * ri + rj * rj);  // v's part along (ri, rj)
  if (!(a != 0) || !std::isfinite(a)) return false;
  int e = 0;
  std::frexp(a, &e);
  const double sa = a > 0 ? 1.0 : -1.0;  // v ~ a (ri, rj) + v_k e_k, scaled by 2^e / |a| in (1, 2]
  V3 w;
  w[i] = sa * std::ldexp(ri, e), w[j] = sa * std::ldexp(rj, e), w[k] = std::ldexp(v[k] / std::fabs(a), e);
  if (!std::isfinite(w[i]) || !std::isfinite(w[j]) || !std::isfinite(w[k])) return false;
  v = w;
  return true;
}

// The normals perpendicular to the edge vector l where a third vertex x reaches its bound (the
// midpoint m of a and b, less d/3 for A's, plus d/3 for B's: the two free vertices of a
// tetrahedron whose other two move by t follow by -2t/3), nudged into the regime in the plane
// perpendicular to l (a tilt along l splits the edges' heights), oriented along d.
void edge_pair_rays(const Problem& P, int i, int i2, int j, int j2, const EdgeOffsets& o,
                    Candidate (&best)[kEvaluated], int& kept) {
  const V3 &l = o.l, &d = o.d;
  const double ll = dot(l, l);
  if (!(ll > 0)) return;
  const V3 mid = mul(add(P.relA[i], P.relB[j]), 0.5);
  const V3 pA = sub(mid, mul(d, 1.0 / 3)), pB = add(mid, mul(d, 1.0 / 3));
  V3 u[4];
  bool onA[4];
  int m = 0;
  for (int k = 0; k < 4; ++k)
    if (k != i && k != i2) u[m] = sub(P.relA[k], pA), onA[m++] = true;
  for (int k = 0; k < 4; ++k)
    if (k != j && k != j2) u[m] = sub(P.relB[k], pB), onA[m++] = false;
  for (int s = 0; s < m; ++s) {
    V3 v = cross(l, u[s]);
    const double nv = norm(v);
    if (!(nv > 0) || !std::isfinite(nv)) continue;
    if (dot(v, d) < 0) v = mul(v, -1.0);
    const V3 w = sub(u[s], mul(l, dot(u[s], l) / ll));  // u[s] across l
    const double nw = norm(w);
    if (!(nw > 0)) continue;
    v = add(mul(v, 1 / nv), mul(w, (onA[s] ? -kNudge : kNudge) / nw));
    // (edges that are translates only up to a rounding have no common perpendicular: the
    // double normal is taken as it is, its tilt along them ~u of the edge's length, far below
    // a depth the certificate reaches, ~1e-9 of the size, where the value moves by its square)
    if (o.translate && !exactly_across(l, v)) continue;
    const double vv = dot(v, v), tol = 1e-9 * std::sqrt(vv) * P.scale;
    bool ok = dot(v, d) > 0;
    for (int q = 0; q < m && ok; ++q) ok = (onA[q] ? -dot(v, u[q]) : dot(v, u[q])) >= -tol;
    if (!ok) continue;
    const double vd = dot(v, d);
    keep_shallowest(best, kept, {v, vd * vd / vv, d, V3{0, 0, 0}, o.d_error, o.translate});
  }
}

bool edge_pair(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds, LonePairResult& out) {
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  const double near = kNear * P.scale;
  Candidate best[kEvaluated];
  int kept = 0;
  for (const auto& ea : kEdge)
    for (const auto& eb : kEdge)
      for (int flip = 0; flip < 2; ++flip) {
        const int i = ea[0], i2 = ea[1], j = flip ? eb[1] : eb[0], j2 = flip ? eb[0] : eb[1];
        auto close = [&](int a, int b) {
          return std::fabs(A[a][0] - B[b][0]) <= near && std::fabs(A[a][1] - B[b][1]) <= near &&
                 std::fabs(A[a][2] - B[b][2]) <= near;
        };
        if (!close(i, j) || !close(i2, j2)) continue;
        EdgeOffsets o;
        if (edge_offsets(A, B, i, i2, j, j2, o)) edge_pair_rays(P, i, i2, j, j2, o, best, kept);
      }
  if (kept == 0) return false;
  Candidate chosen{};
  const Evaluation ev = least_evaluation(A, B, P, best, kept, chosen);
  if (!(ev.value < INFINITY)) return false;
  if (!bounds.get()) return false;
  // L = V (1 - 9e-10): the reported V then lies within 9e-10 / (1 - 9e-10) < 1e-9 above every
  // lower bound, and below the minimum by at most its own kGlobalRel.
  const double lower = ev.value * (1 - 9e-10) * (1 - 2 * kU);
  // (u.d >= u.d~ - |d~ - d| for unit u: the slab widened by d_error)
  const double c0 = (std::sqrt(12 * lower) * (1 + 4 * kU) + chosen.d_error) * (1 + 2 * kU);
  const double d0 = std::sqrt(32 * lower) * (1 + 4 * kU);
  if (!(lower > 0) || !polytope_inside_ball(bounds, chosen.d, c0, d0)) {
    // For the shallow certificate's next starts: the candidate normal, and d where it is exact
    // (the shallow certificate takes its plane as given).
    if (chosen.d_error == 0) out.edge_d = chosen.d;
    out.edge_v = chosen.v;
    out.edge_translate = chosen.translate;
    return false;
  }
  out.normal = chosen.v;
  out.eval = ev;
  out.lower = lower;
  return true;
}

}  // namespace

bool certify_lone_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out) {
  FacetBounds bounds(A, B);
  return lone_pair(A, B, P, bounds, out);
}

bool certify_edge_pair(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out) {
  FacetBounds bounds(A, B);
  return edge_pair(A, B, P, bounds, out);
}

bool certify_lone_pairs(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds,
                        LonePairResult& out) {
  return lone_pair(A, B, P, bounds, out) || edge_pair(A, B, P, bounds, out);
}

bool certify_lone_pairs(const TetVertices& A, const TetVertices& B, const Problem& P, LonePairResult& out) {
  FacetBounds bounds(A, B);
  return certify_lone_pairs(A, B, P, bounds, out);
}

}  // namespace pdd::fast::global
