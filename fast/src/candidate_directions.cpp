// candidate_directions.cpp — SPEC §3 candidates with filtered exact decisions. See the header.
//
// Sharing of work (all identities exact in real arithmetic, see comments at each use):
//   raw face normal  N_f = (v1 − v0) × (v2 − v0) over the face opposite f, vertices increasing;
//   triple products  (eB × eA).w = eB.(eA × w) = −eA.(eB × w);
//   eA × (s_k − s_u) = eps(u,v,k) · NA_f  with f the vertex not in {u,v,k} and eps the sign of
//   the permutation sorting (u,v,k), because (p1 − p0) × (p2 − p0) is alternating in (p0,p1,p2).
// So all 72 values g_k of the edge pairs come from 24 dots eB.NA_f, and all 72 B-side offsets
// n.(r_j − r_x) from 24 dots eA.NB_f.
#include "pdd/fast/candidate_directions.h"

#include <cmath>

#include "pdd/fast/exact_predicates.h"
#include "pdd/fast/filter_bounds.h"

namespace pdd::fast {
namespace {

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

// Vertices of the face opposite f, increasing.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
// The two vertices not on edge a, increasing.
constexpr int kOther[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};
// eps(u,v,k) for edge a = (u,v), u < v: +1 if (u,v,k) is an even permutation of sorted order.
constexpr int parity(int u, int v, int k) { return (k > u && k < v) ? -1 : 1; }

struct Precomputed {
  V3 eA[6], eB[6];    // edge vectors s_v − s_u, r_y − r_x
  V3 NA[4], NB[4];    // raw face normals
  V3 d[4][4];         // d[i][j] = r_j − s_i
  double detA, detB;  // det[x1 − x0, x2 − x0, x3 − x0]
  int oA, oB;         // exact signs of detA, detB
  double GA[6][4];    // eB[b] . NA[f]
  double QB[6][4];    // eA[a] . NB[f]
};

void edges_and_faces(const TetVertices& T, V3* e, V3* N, double* det) {
  for (int a = 0; a < 6; ++a) sub(T[kEdges[a][1]], T[kEdges[a][0]], e[a]);
  // face f's (v1 − v0, v2 − v0) are edge vectors: faces 3,2,1 start at vertex 0, face 0 at 1.
  cross(e[3], e[4], N[0]);  // (s2 − s1) × (s3 − s1)
  cross(e[1], e[2], N[1]);  // (s2 − s0) × (s3 − s0)
  cross(e[0], e[2], N[2]);  // (s1 − s0) × (s3 − s0)
  cross(e[0], e[1], N[3]);  // (s1 − s0) × (s2 − s0)
  *det = dot(N[3], e[2]);   // ((s1 − s0) × (s2 − s0)) . (s3 − s0)
}

int orientation(const TetVertices& T, double det, double bound3) {
  if (det > bound3) return 1;
  if (det < -bound3) return -1;
  return orientation_sign_exact(T);
}

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
}

constexpr std::uint8_t mask_without(int f) { return std::uint8_t(0xF & ~(1u << f)); }
constexpr std::uint8_t edge_mask(int a) {
  return std::uint8_t((1u << kEdges[a][0]) | (1u << kEdges[a][1]));
}

// A direction under construction, kept in locals so every value is written to the set once
// (read-modify-write of the set's memory cost more than the arithmetic).
struct Draft {
  double n[3];
  double hA[4], hB[4];
  std::uint8_t conA, conB;
};

// FV:i — n = sigma NA_i outward. n.(s_i − s_v0) = (−1)^(i+1) detA (permutation (v0,v1,v2,i)),
// so sigma = oA (−1)^i makes it −|detA| < 0.
void face_of_A(const Precomputed& p, int i, Draft& c) {
  const double s = ((i & 1) ? -1.0 : 1.0) * p.oA;
  const int v0 = kFace[i][0];
  for (int k = 0; k < 3; ++k) c.n[k] = s * p.NA[i][k];
  for (int k = 0; k < 4; ++k) c.hA[k] = 0.0;
  c.hA[i] = -std::fabs(p.detA);
  for (int j = 0; j < 4; ++j) c.hB[j] = s * dot(p.NA[i], p.d[v0][j]);  // n.(r_j − s_v0)
  c.conA = mask_without(i);
  c.conB = 0;
}

// VF:j — n = tau NB_j into B: n.(r_j − r_v0) = tau (−1)^(j+1) detB > 0 for tau = oB (−1)^(j+1).
void face_of_B(const Precomputed& p, int j, Draft& c) {
  const double s = ((j & 1) ? 1.0 : -1.0) * p.oB;
  const int v0 = kFace[j][0];
  for (int k = 0; k < 3; ++k) c.n[k] = s * p.NB[j][k];
  for (int k = 0; k < 4; ++k) c.hB[k] = 0.0;
  c.hB[j] = std::fabs(p.detB);
  for (int i = 0; i < 4; ++i) c.hA[i] = -s * dot(p.NB[j], p.d[i][v0]);  // n.(s_i − r_v0)
  c.conA = 0;
  c.conB = mask_without(j);
}

// Heights of a general (non-parallel) edge pair relative to s_u, unoriented (n = eB × eA).
void edge_pair_heights(const Precomputed& p, int a, int b, Draft& c) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  c.hA[u] = c.hA[v] = 0.0;
  for (int k : kOther[a]) c.hA[k] = parity(u, v, k) * p.GA[b][6 - u - v - k];  // g_k
  const double hx = dot(c.n, p.d[u][x]);                                        // n.(r_x − s_u)
  c.hB[x] = c.hB[y] = hx;
  // n.(r_j − r_x) = −eA.((r_y − r_x) × (r_j − r_x)) = −eps(x,y,j) eA.NB_f
  for (int j : kOther[b]) c.hB[j] = hx - parity(x, y, j) * p.QB[a][6 - x - y - j];
}

// Parallel edges: n = (e.e) w − (w.e) e (division-free form of SPEC §3), heights directly.
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

struct Builder {
  const TetVertices& A;
  const TetVertices& B;
  const FilterBounds& fb;
  const Precomputed& p;
  CandidateSet& out;

  // Writes draft oriented by s (= ±1) as the next candidate and checks the sign of its depth
  // D = max hA − min hB; false if exactly separating.
  bool emit(const Draft& d, double s, const DirectionLabel& label, double bound) {
    Candidate& c = out.c[out.count++];
    c.label = label;
    double hi = s * d.hA[0], lo = s * d.hB[0];  // running max of s·hA, min of s·hB
    for (int k = 0; k < 4; ++k) {
      const double a = s * d.hA[k], b = s * d.hB[k];
      c.hA[k] = a;
      c.hB[k] = b;
      hi = max2(hi, a);
      lo = min2(lo, b);
    }
    for (int k = 0; k < 3; ++k) c.n[k] = s * d.n[k];
    c.nn = dot(d.n, d.n);
    c.conA = d.conA;
    c.conB = d.conB;
    c.depth = hi - lo;
    if (c.depth > bound) return true;
    if (c.depth < -bound) return false;
    return depth_sign_exact(A, B, label) > 0;
  }

  EdgePairClass classify(int a, int b, const Draft& c) {
    if (max_abs3(c.n) <= fb.deg2) return classify_edge_pair_exact(A, B, a, b);
    EdgePairClass k;
    int lo = 0, hi = 0;
    for (int i : kOther[a]) {
      const double g = c.hA[i];
      if (std::fabs(g) <= fb.deg3) return classify_edge_pair_exact(A, B, a, b);
      lo += g < 0;
      hi += g > 0;
    }
    k.side = hi == 0 ? EdgePairSide::Keep : lo == 0 ? EdgePairSide::Flip : EdgePairSide::Undecidable;
    return k;
  }

  bool edge_pair(int a, int b) {
    Draft c;
    cross(p.eB[b], p.eA[a], c.n);
    edge_pair_heights(p, a, b, c);
    const EdgePairClass k = classify(a, b, c);
    if (k.kind == EdgePairKind::Colinear) return true;  // no direction (SPEC §3)
    double bound = fb.deg3;
    if (k.kind == EdgePairKind::Parallel) {
      parallel_heights(A, p, a, b, c);
      bound = fb.deg4;
    }
    c.conA = edge_mask(a);
    c.conB = edge_mask(b);
    if (k.side == EdgePairSide::Keep) return emit(c, 1.0, DirectionLabel::ee(a, b), bound);
    if (k.side == EdgePairSide::Flip) return emit(c, -1.0, DirectionLabel::ee(a, b), bound);
    return emit(c, 1.0, DirectionLabel::ee(a, b, EdgeOrientation::Plus), bound) &&
           emit(c, -1.0, DirectionLabel::ee(a, b, EdgeOrientation::Minus), bound);
  }

  bool run() {
    Draft d;
    for (int i = 0; i < 4; ++i) {
      face_of_A(p, i, d);
      if (!emit(d, 1.0, DirectionLabel::fv(i), fb.deg3)) return false;
    }
    for (int j = 0; j < 4; ++j) {
      face_of_B(p, j, d);
      if (!emit(d, 1.0, DirectionLabel::vf(j), fb.deg3)) return false;
    }
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        if (!edge_pair(a, b)) return false;
    return true;
  }
};

bool all_finite(const TetVertices& T) {
  for (const auto& v : T)
    for (double x : v)
      if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

BuildStatus build_candidates(const TetVertices& A, const TetVertices& B, CandidateSet& out) {
  out.count = 0;
  out.intersecting = false;
  if (!all_finite(A)) return BuildStatus::NonFiniteA;
  if (!all_finite(B)) return BuildStatus::NonFiniteB;
  const FilterBounds fb = filter_bounds(A, B);
  Precomputed p;
  precompute(A, B, p);
  p.oA = orientation(A, p.detA, fb.deg3);
  if (p.oA == 0) return BuildStatus::DegenerateA;
  p.oB = orientation(B, p.detB, fb.deg3);
  if (p.oB == 0) return BuildStatus::DegenerateB;
  out.intersecting = Builder{A, B, fb, p, out}.run();
  return BuildStatus::Ok;
}

}  // namespace pdd::fast
