// direction_geometry.cpp — precomputation and vectorised edge-pair lanes. See the header.
#include "kernel/direction_geometry.h"

#include "kernel/edge_pair_formula.h"

#include <limits>

namespace pdd::fast::detail {

void edges_and_faces(const TetVertices& T, V3* e, V3* N, double* det) {
  for (int a = 0; a < 6; ++a) sub(T[kEdges[a][1]], T[kEdges[a][0]], e[a]);
  // face f's (v1 − v0, v2 − v0) are edge vectors: faces 3,2,1 start at vertex 0, face 0 at 1.
  cross(e[3], e[4], N[0]);  // (s2 − s1) × (s3 − s1)
  cross(e[1], e[2], N[1]);  // (s2 − s0) × (s3 − s0)
  cross(e[0], e[2], N[2]);  // (s1 − s0) × (s3 − s0)
  cross(e[0], e[1], N[3]);  // (s1 − s0) × (s2 − s0)
  *det = dot(N[3], e[2]);   // ((s1 − s0) × (s2 − s0)) . (s3 − s0)
}

namespace {

void lane_tables(Precomputed& p) {
  for (int b = 0; b < kLaneStride; ++b) {  // padding lanes 6, 7: zeros, never read
    p.eBx[b] = p.eBy[b] = p.eBz[b] = 0.0;
    for (int u = 0; u < 3; ++u)
      for (int k = 0; k < 3; ++k) p.W[u][k][b] = 0.0;
    for (int f = 0; f < 4; ++f) p.G[f][b] = 0.0;
    for (int a = 0; a < 6; ++a) p.Q[a][0][b] = p.Q[a][1][b] = 0.0;
  }
  for (int b = 0; b < 6; ++b) {
    p.eBx[b] = p.eB[b][0];
    p.eBy[b] = p.eB[b][1];
    p.eBz[b] = p.eB[b][2];
    for (int u = 0; u < 3; ++u)
      for (int k = 0; k < 3; ++k) p.W[u][k][b] = p.d[u][kEdges[b][0]][k];
    for (int f = 0; f < 4; ++f) p.G[f][b] = p.GA[b][f];
    for (int a = 0; a < 6; ++a)
      for (int m = 0; m < 2; ++m) p.Q[a][m][b] = off_sign_B(b, m) * p.QB[a][kOffFaces.face[b][m]];
  }
}

}  // namespace

void precompute(const TetVertices& A, const TetVertices& B, Precomputed& p) {
  edges_and_faces(A, p.eA, p.NA, &p.detA);
  edges_and_faces(B, p.eB, p.NB, &p.detB);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sub(B[j], A[i], p.d[i][j]);
  for (int e = 0; e < 6; ++e)
    for (int f = 0; f < 4; ++f) {
      p.GA[e][f] = dot(p.eB[e], p.NA[f]);
      p.QB[e][f] = dot(p.eA[e], p.NB[f]);
    }
  lane_tables(p);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)  // as superset_kernel.cpp
#define PDD_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_VECTOR_CLONES
#endif

// All 36 edge pairs at once (lane 8a + b), unoriented n = eB × eA, heights relative to s_u:
//   g_k = eps(u,v,k) eB.NA_f (A's free vertices), hx = n.(r_x − s_u), hx + q_m (B's free),
//   D(+n) = max(0, g1, g2) − hx − min(0, q1, q2),  D(−n) = −min(0, g1, g2) + hx + max(0, q1, q2),
// and the filter verdicts (EdgeLanes). Branch-free (& and | on bools) so that it vectorises.
PDD_VECTOR_CLONES void edge_lanes(const Precomputed& __restrict p, double e2, double e3,
                                  EdgeLanes& __restrict L) {
  for (int a = 0; a < 6; ++a) {
    const int u = kEdges[a][0];
    const double ax = p.eA[a][0], ay = p.eA[a][1], az = p.eA[a][2];
    const double s1 = kOffFaces.eps[a][0], s2 = kOffFaces.eps[a][1];
    const double* G1 = p.G[kOffFaces.face[a][0]];
    const double* G2 = p.G[kOffFaces.face[a][1]];
    const double* Q1 = p.Q[a][0];
    const double* Q2 = p.Q[a][1];
    const double *wx = p.W[u][0], *wy = p.W[u][1], *wz = p.W[u][2];
    const int o = kLaneStride * a;
    for (int b = 0; b < kLaneStride; ++b) {
      double m0, m1, m2, dp, dm;
      edge_pair_normal(ax, ay, az, p.eBx[b], p.eBy[b], p.eBz[b], m0, m1, m2);
      const double h = edge_pair_dot(m0, m1, m2, wx[b], wy[b], wz[b]);
      const double g1 = s1 * G1[b], g2 = s2 * G2[b], q1 = Q1[b], q2 = Q2[b];
      const double nn = edge_pair_nn(m0, m1, m2);
      edge_pair_depths(g1, g2, h, q1, q2, dp, dm);
      // one division per lane (padding lanes: 1/0, never read)
      const double inv = 1.0 / nn, d2p = dp * dp * inv, d2m = dm * dm * inv;
      const LaneVerdict verdict = lane_verdict(m0, m1, m2, g1, g2, dp, dm, d2p, d2m, e2, e3);
      L.n0[o + b] = m0;
      L.n1[o + b] = m1;
      L.n2[o + b] = m2;
      L.nn[o + b] = nn;
      L.hx[o + b] = h;
      L.g1[o + b] = g1;
      L.g2[o + b] = g2;
      L.q1[o + b] = q1;
      L.q2[o + b] = q2;
      L.dplus[o + b] = dp;
      L.dminus[o + b] = dm;
      L.d2plus[o + b] = d2p;
      L.d2minus[o + b] = d2m;
      L.unclear[o + b] = verdict.unclear;
      L.first[o + b] = verdict.first;
      L.second[o + b] = verdict.second;
    }
  }
}

PDD_VECTOR_CLONES void finish_lanes(double e2, double e3, EdgeLanes& __restrict L) {
  for (int i = 0; i < kLanes; ++i) {
    const LaneVerdict v = lane_verdict(L.n0[i], L.n1[i], L.n2[i], L.g1[i], L.g2[i], L.dplus[i],
                                       L.dminus[i], L.d2plus[i], L.d2minus[i], e2, e3);
    L.unclear[i] = v.unclear;
    L.first[i] = v.first;
    L.second[i] = v.second;
  }
}

bool all_finite(const TetVertices& T) {
  bool ok = true;  // x − x is 0 for a finite x, NaN for ±inf and NaN; no early exit (vectorises)
  for (const auto& v : T)
    for (double x : v) ok &= (x - x) == 0.0;
  return ok;
}

}  // namespace pdd::fast::detail
