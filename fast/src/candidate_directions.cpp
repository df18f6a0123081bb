// candidate_directions.cpp — SPEC §3 candidates with filtered exact decisions. See the header.
//
// Sharing of work (all identities exact in real arithmetic, see comments at each use):
//   raw face normal  N_f = (v1 − v0) × (v2 − v0) over the face opposite f, vertices increasing;
//   triple products  (eB × eA).w = eB.(eA × w) = −eA.(eB × w);
//   eA × (s_k − s_u) = eps(u,v,k) · NA_f  with f the vertex not in {u,v,k} and eps the sign of
//   the permutation sorting (u,v,k), because (p1 − p0) × (p2 − p0) is alternating in (p0,p1,p2).
// So all 72 values g_k of the edge pairs come from 24 dots eB.NA_f, and all 72 B-side offsets
// n.(r_j − r_x) from 24 dots eA.NB_f. The per-lane arithmetic (edge_lanes) is branch-free over
// structure-of-arrays; on x86-64 GCC also emits an AVX2 clone chosen at run time (ifunc). Both
// clones perform the same IEEE operations in the same order (no FMA contraction, no
// reassociation), so results are identical on every machine.
#include "pdd/fast/candidate_directions.h"

#include <cmath>
#include <limits>

#include "pdd/fast/exact_predicates.h"
#include "pdd/fast/filter_bounds.h"
#include "pdd/fast/tie_tolerance.h"

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
  // lane-ordered copies (b = 0..7, padding 0) for the vectorised edge lanes
  alignas(32) double eBx[kLaneStride], eBy[kLaneStride], eBz[kLaneStride];
  alignas(32) double W[3][3][kLaneStride];     // W[u][k][b] = (r_x(b) − s_u)_k
  alignas(32) double G[4][kLaneStride];        // G[f][b] = eB[b] . NA[f]
  alignas(32) double Q[6][2][kLaneStride];     // Q[a][m][b] = n.(r_jm − r_x) (see lane_heights)
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

// For lane b and its m-th vertex j off edge b = (x, y): −eps(x,y,j) and the face f' = 6−x−y−j,
// so that n.(r_j − r_x) = −eA.((r_y − r_x) × (r_j − r_x)) = −eps(x,y,j) eA.NB_f'.
struct OffEdge {
  int sign[6][2], face[6][2];
};
constexpr OffEdge make_off_edge() {
  OffEdge t{};
  for (int b = 0; b < 6; ++b)
    for (int m = 0; m < 2; ++m) {
      const int x = kEdges[b][0], y = kEdges[b][1], j = kOther[b][m];
      t.sign[b][m] = -parity(x, y, j);
      t.face[b][m] = 6 - x - y - j;
    }
  return t;
}
constexpr OffEdge kOffEdge = make_off_edge();

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
      for (int m = 0; m < 2; ++m) p.Q[a][m][b] = kOffEdge.sign[b][m] * p.QB[a][kOffEdge.face[b][m]];
  }
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
  lane_tables(p);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define PDD_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PDD_VECTOR_CLONES
#endif

// All 36 edge pairs at once (lane 8a + b), unoriented n = eB × eA, heights relative to s_u:
//   g_k = eps(u,v,k) eB.NA_f (A's free vertices), hx = n.(r_x − s_u), hx + q_m (B's free),
//   D(+n) = max(0, g1, g2) − hx − min(0, q1, q2),  D(−n) = −min(0, g1, g2) + hx + max(0, q1, q2),
// and the filter verdicts (EdgeLanes). Branch-free (& and | on bools) so that it vectorises.
PDD_VECTOR_CLONES void edge_lanes(const Precomputed& __restrict p, double e2, double e3,
                                  EdgeLanes& __restrict L) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 6; ++a) {
    const int u = kEdges[a][0], v = kEdges[a][1], k1 = kOther[a][0], k2 = kOther[a][1];
    const double ax = p.eA[a][0], ay = p.eA[a][1], az = p.eA[a][2];
    const double s1 = parity(u, v, k1), s2 = parity(u, v, k2);
    const double* G1 = p.G[6 - u - v - k1];
    const double* G2 = p.G[6 - u - v - k2];
    const double* Q1 = p.Q[a][0];
    const double* Q2 = p.Q[a][1];
    const double *wx = p.W[u][0], *wy = p.W[u][1], *wz = p.W[u][2];
    const int o = kLaneStride * a;
    for (int b = 0; b < kLaneStride; ++b) {
      const double m0 = p.eBy[b] * az - p.eBz[b] * ay;
      const double m1 = p.eBz[b] * ax - p.eBx[b] * az;
      const double m2 = p.eBx[b] * ay - p.eBy[b] * ax;
      const double h = m0 * wx[b] + m1 * wy[b] + m2 * wz[b];
      const double g1 = s1 * G1[b], g2 = s2 * G2[b], q1 = Q1[b], q2 = Q2[b];
      const double nn = m0 * m0 + m1 * m1 + m2 * m2;
      const double dp = max2(0.0, max2(g1, g2)) - h - min2(0.0, min2(q1, q2));
      const double dm = -min2(0.0, min2(g1, g2)) + h + max2(0.0, max2(q1, q2));
      // one division per lane (padding lanes: 1/0, never read)
      const double inv = 1.0 / nn, d2p = dp * dp * inv, d2m = dm * dm * inv;
      const double nmax = max2(std::fabs(m0), max2(std::fabs(m1), std::fabs(m2)));
      const bool pos1 = g1 > 0.0, pos2 = g2 > 0.0;
      const bool flip = pos1 & pos2, undecidable = pos1 ^ pos2;
      const bool unclear = (nmax <= e2) | (std::fabs(g1) <= e3) | (std::fabs(g2) <= e3) |
                           ((!(dp > e3)) & (!flip)) | ((!(dm > e3)) & (flip | undecidable));
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
      L.unclear[o + b] = unclear ? 1.0 : 0.0;
      L.first[o + b] = flip ? d2m : d2p;
      L.second[o + b] = undecidable ? d2m : kInf;
    }
  }
}

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
inline void face_of_B(const Precomputed& p, int j, Draft& c) {
  const double s = ((j & 1) ? 1.0 : -1.0) * p.oB;
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
inline void face_geometry(const Precomputed& p, int f, DirectionGeometry& c) {
  Draft d;
  if (f < 4) face_of_A(p, f, d); else face_of_B(p, f - 4, d);
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
void lane_heights(const EdgeLanes& L, int a, int b, Draft& c) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const int i = kLaneStride * a + b;
  c.n[0] = L.n0[i];
  c.n[1] = L.n1[i];
  c.n[2] = L.n2[i];
  c.hA[u] = c.hA[v] = 0.0;
  c.hA[kOther[a][0]] = L.g1[i];
  c.hA[kOther[a][1]] = L.g2[i];
  c.hB[x] = c.hB[y] = L.hx[i];
  c.hB[kOther[b][0]] = L.hx[i] + L.q1[i];
  c.hB[kOther[b][1]] = L.hx[i] + L.q2[i];
  c.conA = edge_mask(a);
  c.conB = edge_mask(b);
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

// Orients a draft by s into a full candidate.
void orient_draft(const Draft& d, double s, DirectionGeometry& c) {
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

struct Builder {
  const TetVertices& A;
  const TetVertices& B;
  const FilterBounds& fb;
  const Precomputed& p;
  CandidateSet& out;

  // Exact sign of candidate k's depth when the filter cannot decide it; false if <= 0.
  bool depth_positive(int k, double bound) {
    if (out.depth[k] > bound) return true;
    if (out.depth[k] < -bound) return false;
    return depth_sign_exact(A, B, label(out, k)) > 0;
  }

  // Stores draft oriented by s (= ±1) in full as the next candidate; false if separating.
  bool emit(const Draft& d, double s, LabelCode code, double bound) {
    const int k = out.count++;
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

  // Any edge pair, with the exact classification when the filter cannot decide (slow path).
  bool edge_pair_general(int a, int b) {
    Draft c;
    lane_heights(out.edges, a, b, c);
    const EdgePairClass k = classify(a, b, c);
    if (k.kind == EdgePairKind::Colinear) return true;  // no direction (SPEC §3)
    double bound = fb.deg3;
    if (k.kind == EdgePairKind::Parallel) {
      parallel_heights(A, p, a, b, c);
      bound = fb.deg4;
    }
    const LabelCode decided = pack_label(ContactKind::EE, a, b, EdgeOrientation::Decided);
    if (k.side == EdgePairSide::Keep) return emit(c, 1.0, decided, bound);
    if (k.side == EdgePairSide::Flip) return emit(c, -1.0, decided, bound);
    return emit(c, 1.0, pack_label(ContactKind::EE, a, b, EdgeOrientation::Plus), bound) &&
           emit(c, -1.0, pack_label(ContactKind::EE, a, b, EdgeOrientation::Minus), bound);
  }

  // All edge pairs in canonical order. A lane with clear filter verdicts (edge_lanes) is
  // written from its lane: the candidate and, branch-free, the ':-' one after it, the count
  // advancing by 2 only for an undecidable pair; an unclear lane goes to edge_pair_general.
  bool edge_pairs() {
    const EdgeLanes& L = out.edges;
    int k = out.count;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        const int i = kLaneStride * a + b;
        if (L.unclear[i] != 0.0) {
          out.count = k;
          if (!edge_pair_general(a, b)) return false;
          k = out.count;
          continue;
        }
        const bool pos1 = L.g1[i] > 0.0, pos2 = L.g2[i] > 0.0;
        const bool flip = pos1 & pos2, undecidable = pos1 ^ pos2;
        out.code[k] = pack_label(ContactKind::EE, a, b,
                                 undecidable ? EdgeOrientation::Plus : EdgeOrientation::Decided);
        out.code[k + 1] = pack_label(ContactKind::EE, a, b, EdgeOrientation::Minus);
        out.depth[k] = flip ? L.dminus[i] : L.dplus[i];
        out.depth[k + 1] = L.dminus[i];
        out.delta_sq[k] = L.first[i];
        out.delta_sq[k + 1] = L.d2minus[i];
        out.nn[k] = out.nn[k + 1] = L.nn[i];
        out.sign[k] = flip ? -1 : 1;
        out.sign[k + 1] = -1;
        out.lane[k] = out.lane[k + 1] = std::int16_t(i);
        k += 1 + undecidable;
      }
    out.count = k;
    return true;
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
      if (!depth_positive(k, fb.deg3)) return false;
    }
    edge_lanes(p, fb.deg2, fb.deg3, out.edges);
    return edge_pairs();
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

Candidate candidate(const CandidateSet& set, int k) {
  Candidate c;
  c.label = label(set, k);
  if (set.lane[k] < 0) {
    static_cast<DirectionGeometry&>(c) = set.explicit_[k];
    return c;
  }
  // the heights of lane_heights, oriented by the candidate's sign, written once
  const EdgeLanes& L = set.edges;
  const int i = set.lane[k], a = i / kLaneStride, b = i % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const double s = set.sign[k];
  c.n[0] = s * L.n0[i];
  c.n[1] = s * L.n1[i];
  c.n[2] = s * L.n2[i];
  c.nn = set.nn[k];
  c.depth = set.depth[k];
  c.hA[u] = c.hA[v] = 0.0;
  c.hA[kOther[a][0]] = s * L.g1[i];
  c.hA[kOther[a][1]] = s * L.g2[i];
  c.hB[x] = c.hB[y] = s * L.hx[i];
  c.hB[kOther[b][0]] = s * (L.hx[i] + L.q1[i]);
  c.hB[kOther[b][1]] = s * (L.hx[i] + L.q2[i]);
  c.conA = edge_mask(a);
  c.conB = edge_mask(b);
  return c;
}

namespace {

// Candidate of lane i oriented by s (the arithmetic of candidate(set, k)).
void lane_candidate(const EdgeLanes& L, int i, double s, Candidate& c) {
  const int a = i / kLaneStride, b = i % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  c.n[0] = s * L.n0[i];
  c.n[1] = s * L.n1[i];
  c.n[2] = s * L.n2[i];
  c.nn = L.nn[i];
  c.depth = s > 0 ? L.dplus[i] : L.dminus[i];
  c.hA[u] = c.hA[v] = 0.0;
  c.hA[kOther[a][0]] = s * L.g1[i];
  c.hA[kOther[a][1]] = s * L.g2[i];
  c.hB[x] = c.hB[y] = s * L.hx[i];
  c.hB[kOther[b][0]] = s * (L.hx[i] + L.q1[i]);
  c.hB[kOther[b][1]] = s * (L.hx[i] + L.q2[i]);
  c.conA = edge_mask(a);
  c.conB = edge_mask(b);
}

bool lanes_clear(const EdgeLanes& L) {
  double any = 0.0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) any += L.unclear[kLaneStride * a + b];
  return any == 0.0;
}

// The canonical list of the lanes (Builder::edge_pairs without labels): delta² and source.
void quick_edge_list(const EdgeLanes& L, QuickCandidates& q) {
  int k = q.count;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int i = kLaneStride * a + b;
      const bool pos1 = L.g1[i] > 0.0, pos2 = L.g2[i] > 0.0;
      const bool flip = pos1 & pos2, undecidable = pos1 ^ pos2;
      q.delta_sq[k] = L.first[i];
      q.delta_sq[k + 1] = L.d2minus[i];
      q.src[k] = std::int16_t(8 + 2 * i + flip);
      q.src[k + 1] = std::int16_t(8 + 2 * i + 1);
      k += 1 + undecidable;
    }
  q.count = k;
}

}  // namespace

bool quick_candidates(const TetVertices& A, const TetVertices& B, QuickCandidates& q) {
  q.count = 0;
  if (!all_finite(A) || !all_finite(B)) return false;
  const FilterBounds fb = filter_bounds(A, B);
  Precomputed p;
  precompute(A, B, p);
  if (!(std::fabs(p.detA) > fb.deg3) || !(std::fabs(p.detB) > fb.deg3)) return false;
  p.oA = p.detA > 0 ? 1 : -1;
  p.oB = p.detB > 0 ? 1 : -1;
  for (int f = 0; f < 8; ++f) {
    DirectionGeometry& g = q.faces[f];
    face_geometry(p, f, g);
    if (!(g.depth > fb.deg3)) return false;
    q.delta_sq[f] = g.depth * g.depth / g.nn;
    q.src[f] = std::int16_t(f);
  }
  q.count = 8;
  edge_lanes(p, fb.deg2, fb.deg3, q.edges);
  if (!lanes_clear(q.edges)) return false;
  quick_edge_list(q.edges, q);
  return true;
}

LabelCode label_code(const QuickCandidates& q, int k) {
  const int src = q.src[k];
  if (src < 8)
    return src < 4 ? pack_label(ContactKind::FV, src, 0, EdgeOrientation::Decided)
                   : pack_label(ContactKind::VF, src - 4, 0, EdgeOrientation::Decided);
  const int i = (src - 8) / 2;
  const bool minus = (src - 8) % 2;
  const bool undecidable = (q.edges.g1[i] > 0.0) != (q.edges.g2[i] > 0.0);
  return pack_label(ContactKind::EE, i / kLaneStride, i % kLaneStride,
                    !undecidable ? EdgeOrientation::Decided
                    : minus      ? EdgeOrientation::Minus
                                 : EdgeOrientation::Plus);
}

Candidate candidate(const QuickCandidates& q, int k) {
  Candidate c;
  c.label = unpack_label(label_code(q, k));
  const int src = q.src[k];
  if (src < 8) {
    static_cast<DirectionGeometry&>(c) = q.faces[src];
    return c;
  }
  lane_candidate(q.edges, (src - 8) / 2, (src - 8) % 2 ? -1.0 : 1.0, c);
  return c;
}

}  // namespace pdd::fast
