// direction_geometry.h — internal to fast/src: the arithmetic shared by build_candidates
// (candidate_directions.cpp) and quick_candidates (quick_candidates.cpp).
//
// Sharing of work (all identities exact in real arithmetic, see comments at each use):
//   raw face normal  N_f = (v1 − v0) × (v2 − v0) over the face opposite f, vertices increasing;
//   triple products  (eB × eA).w = eB.(eA × w) = −eA.(eB × w);
//   eA × (s_k − s_u) = eps(u,v,k) · NA_f  with f the vertex not in {u,v,k} and eps the sign of
//   the permutation sorting (u,v,k), because (p1 − p0) × (p2 − p0) is alternating in (p0,p1,p2).
// So all 72 values g_k of the edge pairs come from 24 dots eB.NA_f, and all 72 B-side offsets
// n.(r_j − r_x) from 24 dots eA.NB_f. The per-lane arithmetic (edge_lanes) is branch-free over
// structure-of-arrays; on x86-64 GCC also emits AVX-512 and AVX2 clones chosen at run time
// (ifunc). All clones perform the same IEEE operations in the same order (no FMA contraction, no
// reassociation), so results are identical on every machine.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "kernel/candidate_directions.h"
#include "pdd/sign.h"

namespace pdd::fast::detail {

using V3 = double[3];

inline void sub(const Vec3d& a, const Vec3d& b, double* o) {
  o[0] = a[0] - b[0];
  o[1] = a[1] - b[1];
  o[2] = a[2] - b[2];
}
inline void cross(const double* a, const double* b, double* o) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double max2(double a, double b) { return a > b ? a : b; }
inline double min2(double a, double b) { return a < b ? a : b; }
inline double max_abs3(const double* a) {
  return max2(std::fabs(a[0]), max2(std::fabs(a[1]), std::fabs(a[2])));
}

// kFace, kOffEdge, kEdges: pdd/tet_tables.h.
// eps(u,v,k) for edge a = (u,v), u < v: +1 if (u,v,k) is an even permutation of sorted order.
constexpr int parity(int u, int v, int k) { return (k > u && k < v) ? -1 : 1; }

struct Precomputed {
  V3 eA[6], eB[6];    // edge vectors s_v − s_u, r_y − r_x
  V3 NA[4], NB[4];    // raw face normals
  V3 d[4][4];         // d[i][j] = r_j − s_i
  double detA, detB;  // det[x1 − x0, x2 − x0, x3 − x0]
  Sign oA, oB;        // exact signs of detA, detB
  double GA[6][4];    // eB[b] . NA[f]
  double QB[6][4];    // eA[a] . NB[f]
  // lane-ordered copies (b = 0..7, padding 0) for the vectorised edge lanes
  alignas(32) double eBx[kLaneStride], eBy[kLaneStride], eBz[kLaneStride];
  alignas(32) double W[3][3][kLaneStride];     // W[u][k][b] = (r_x(b) − s_u)_k
  alignas(32) double G[4][kLaneStride];        // G[f][b] = eB[b] . NA[f]
  alignas(32) double Q[6][2][kLaneStride];     // Q[a][m][b] = n.(r_jm − r_x) (see lane_heights)
};

// Edge vectors e[a] = x_v − x_u, raw face normals N[f] (see kFace) and det of one tetrahedron.
void edges_and_faces(const TetVertices& T, V3* e, V3* N, double* det);

// Edge vectors, face normals, determinants, differences and the lane tables of a pair.
// (Orientations oA, oB are left to the caller: filtered, with or without exact fallback.)
void precompute(const TetVertices& A, const TetVertices& B, Precomputed& p);

// All 36 edge pairs as lanes (EdgeLanes), with filter verdicts against bounds e2, e3.
void edge_lanes(const Precomputed& p, double e2, double e3, EdgeLanes& L);

// The filter verdicts (unclear, first, second) of lanes whose n, g, D and D²/(n.n) are set.
void finish_lanes(double e2, double e3, EdgeLanes& L);

// Verdicts of one lane (EdgeLanes): orientation rule on the signs of g1, g2 and the filter.
struct LaneVerdict {
  double unclear, first, second;
};
inline LaneVerdict lane_verdict(double m0, double m1, double m2, double g1, double g2, double dp,
                                double dm, double d2p, double d2m, double e2, double e3) {
  const double nmax = max2(std::fabs(m0), max2(std::fabs(m1), std::fabs(m2)));
  const bool pos1 = g1 > 0.0, pos2 = g2 > 0.0;
  const bool flip = pos1 & pos2, undecidable = pos1 ^ pos2;
  const bool unclear = (nmax <= e2) | (std::fabs(g1) <= e3) | (std::fabs(g2) <= e3) |
                       ((!(dp > e3)) & (!flip)) | ((!(dm > e3)) & (flip | undecidable));
  return {unclear ? 1.0 : 0.0, flip ? d2m : d2p,
          undecidable ? d2m : std::numeric_limits<double>::infinity()};
}

bool all_finite(const TetVertices& T);

constexpr std::uint8_t mask_without(int f) { return std::uint8_t(0xF & ~(1u << f)); }
constexpr std::uint8_t edge_mask(int a) {
  return std::uint8_t((1u << kEdges[a][0]) | (1u << kEdges[a][1]));
}

// A direction under construction (faces and exactly decided edge pairs), in locals.
struct Draft {
  double n[3];
  double hA[4], hB[4];
  std::uint8_t conA, conB;
};

// FV:i — n = sigma NA_i outward. n.(s_i − s_v0) = (−1)^(i+1) detA (permutation (v0,v1,v2,i)),
// so sigma = oA (−1)^i makes it −|detA| < 0.
inline void face_of_A(const Precomputed& p, int i, Draft& c) {
  const double s = ((i & 1) ? -1.0 : 1.0) * to_int(p.oA);
  const int v0 = kFace[i][0];
  for (int k = 0; k < 3; ++k) c.n[k] = s * p.NA[i][k];
  for (int k = 0; k < 4; ++k) c.hA[k] = 0.0;
  c.hA[i] = -std::fabs(p.detA);
  for (int j = 0; j < 4; ++j) c.hB[j] = s * dot(p.NA[i], p.d[v0][j]);  // n.(r_j − s_v0)
  c.conA = mask_without(i);
  c.conB = 0;
}

// VF:j — n = tau NB_j into B: n.(r_j − r_v0) = tau (−1)^(j+1) detB > 0 for tau = oB (−1)^(j+1).
inline void face_of_B(const Precomputed& p, int j, Draft& c) {
  const double s = ((j & 1) ? 1.0 : -1.0) * to_int(p.oB);
  const int v0 = kFace[j][0];
  for (int k = 0; k < 3; ++k) c.n[k] = s * p.NB[j][k];
  for (int k = 0; k < 4; ++k) c.hB[k] = 0.0;
  c.hB[j] = std::fabs(p.detB);
  for (int i = 0; i < 4; ++i) c.hA[i] = -s * dot(p.NB[j], p.d[i][v0]);  // n.(s_i − r_v0)
  c.conA = 0;
  c.conB = mask_without(j);
}

// Face candidate f (FV:f for f < 4, VF:(f − 4) otherwise) computed in locals and written once:
// a Draft round trip through memory costs store-forwarding stalls on this hot path. Same
// arithmetic as face_of_A / face_of_B followed by orient_draft(·, 1).
inline void finish_face(const Draft& d, DirectionGeometry& c);
inline void face_geometry(const Precomputed& p, int f, DirectionGeometry& c) {
  Draft d;
  if (f < 4) face_of_A(p, f, d); else face_of_B(p, f - 4, d);
  finish_face(d, c);
}

// A face's draft (oriented by construction) written as a candidate: depth = max hA − min hB.
inline void finish_face(const Draft& d, DirectionGeometry& c) {
  double hi = d.hA[0], lo = d.hB[0];
  for (int m = 1; m < 4; ++m) {
    hi = max2(hi, d.hA[m]);
    lo = min2(lo, d.hB[m]);
  }
  for (int m = 0; m < 4; ++m) {
    c.hA[m] = d.hA[m];
    c.hB[m] = d.hB[m];
  }
  for (int m = 0; m < 3; ++m) c.n[m] = d.n[m];
  c.nn = dot(d.n, d.n);
  c.conA = d.conA;
  c.conB = d.conB;
  c.depth = hi - lo;
}

// Heights of edge pair (a, b) from its lane, unoriented (layout of EdgeLanes).
inline void lane_heights(const EdgeLanes& L, int a, int b, Draft& c) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const int i = kLaneStride * a + b;
  c.n[0] = L.n0[i];
  c.n[1] = L.n1[i];
  c.n[2] = L.n2[i];
  c.hA[u] = c.hA[v] = 0.0;
  c.hA[kOffEdge[a][0]] = L.g1[i];
  c.hA[kOffEdge[a][1]] = L.g2[i];
  c.hB[x] = c.hB[y] = L.hx[i];
  c.hB[kOffEdge[b][0]] = L.hx[i] + L.q1[i];
  c.hB[kOffEdge[b][1]] = L.hx[i] + L.q2[i];
  c.conA = edge_mask(a);
  c.conB = edge_mask(b);
}

// Orients a draft by s into a full candidate.
inline void orient_draft(const Draft& d, double s, DirectionGeometry& c) {
  double hi = s * d.hA[0], lo = s * d.hB[0];  // running max of s·hA, min of s·hB
  for (int m = 0; m < 4; ++m) {
    c.hA[m] = s * d.hA[m];
    c.hB[m] = s * d.hB[m];
    hi = max2(hi, c.hA[m]);
    lo = min2(lo, c.hB[m]);
  }
  for (int m = 0; m < 3; ++m) c.n[m] = s * d.n[m];
  c.nn = dot(d.n, d.n);
  c.conA = d.conA;
  c.conB = d.conB;
  c.depth = hi - lo;
}

// Candidate of lane i oriented by s (the arithmetic of candidate(set, k)).
inline void lane_candidate(const EdgeLanes& L, int i, double s, Candidate& c) {
  const int a = i / kLaneStride, b = i % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  c.n[0] = s * L.n0[i];
  c.n[1] = s * L.n1[i];
  c.n[2] = s * L.n2[i];
  c.nn = L.nn[i];
  c.depth = s > 0 ? L.dplus[i] : L.dminus[i];
  c.hA[u] = c.hA[v] = 0.0;
  c.hA[kOffEdge[a][0]] = s * L.g1[i];
  c.hA[kOffEdge[a][1]] = s * L.g2[i];
  c.hB[x] = c.hB[y] = s * L.hx[i];
  c.hB[kOffEdge[b][0]] = s * (L.hx[i] + L.q1[i]);
  c.hB[kOffEdge[b][1]] = s * (L.hx[i] + L.q2[i]);
  c.conA = edge_mask(a);
  c.conB = edge_mask(b);
}

}  // namespace pdd::fast::detail
