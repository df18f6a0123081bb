// superset_depth.cpp — rigid PD² over the superset of candidate directions. See the header for
// the proof; this file is the arithmetic.
//
// Layout: 8-wide vectors (GCC vector extensions; one zmm with AVX-512, two ymm with AVX2, four
// xmm otherwise — clones chosen at run time). Edge pairs: one vector per edge a of A, lane b =
// edge of B (lanes 6, 7 padding). Faces: one vector, lane f = FV:0..3, VF:0..3.
// Every value is computed with the same IEEE operations in the same order as
// direction_geometry (no FMA: ISO mode; no reassociation), so it is bit-identical to the list.
#include "pdd/fast/superset_depth.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "direction_geometry.h"
#include "pdd/fast/filter_bounds.h"
#include "pdd/fast/tie_tolerance.h"

namespace pdd::fast {
namespace {

using namespace detail;

// The helpers below are always inlined, so the ABI of passing v8 by value never arises.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v8 __attribute__((vector_size(64)));
#define PDD_INLINE static inline __attribute__((always_inline))

constexpr double kInf = std::numeric_limits<double>::infinity();

typedef long long v8l __attribute__((vector_size(64)));
PDD_INLINE long long horizontal_or(v8l v) {
  return (v[0] | v[1]) | (v[2] | v[3]) | ((v[4] | v[5]) | (v[6] | v[7]));
}
PDD_INLINE v8 bc(double x) { return v8{x, x, x, x, x, x, x, x}; }
PDD_INLINE v8 vmax(v8 a, v8 b) { return a > b ? a : b; }  // max2 lane-wise
PDD_INLINE v8 vmin(v8 a, v8 b) { return a < b ? a : b; }  // min2 lane-wise

// Lanes b = 0..5 of t[idx[b]][k], padding 0.
PDD_INLINE v8 edge_lanes_of(const V3* t, int k) {
  return v8{t[0][k], t[1][k], t[2][k], t[3][k], t[4][k], t[5][k], 0.0, 0.0};
}

// For lane b (edge (x, y) of B) and its m-th vertex j off the edge: the sign and face of
// n.(r_j − r_x) = sign · eA.NB_face (direction_geometry.cpp, OffEdge).
struct OffEdgeTable {
  double sign[2][8];
  int face[2][8];
};
constexpr OffEdgeTable make_off_edge() {
  OffEdgeTable t{};
  for (int b = 0; b < 6; ++b)
    for (int m = 0; m < 2; ++m) {
      const int x = kEdges[b][0], y = kEdges[b][1], j = kOther[b][m];
      t.sign[m][b] = -parity(x, y, j);
      t.face[m][b] = 6 - x - y - j;
    }
  return t;
}
constexpr OffEdgeTable kOff = make_off_edge();

// Output of the vector kernel.
struct alignas(64) Kernel {
  v8 dp[6], dm[6];  // D(+n), D(−n) per edge pair (a, b)
  v8 inv[6];        // 1/(n.n)
  v8 val[6];        // min(D(±n))² / (n.n)   (padding: +inf)
  v8 G[4];          // eB[b] . NA[f]
  v8 face_val;      // D²/(n.n) of the faces
  double lo;        // min over S of D (positivity)
  double vmin;      // min over S of the value
  double kappa;     // tie band of the pair (tie_tolerance.h)
  double t1;        // tie threshold of vmin
  std::uint8_t face_bits;   // faces with value <= t2
  std::uint64_t lane_bits;  // edge pairs (bit 8a + b) with min(value(±n)) <= t2
};

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define PDD_SUPERSET_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_SUPERSET_CLONES
#endif

// D, n.n and D²/(n.n) of the 8 faces and of both orientations of the 36 edge pairs.
PDD_SUPERSET_CLONES void superset_kernel(const TetVertices& A, const TetVertices& B,
                                         const Precomputed& p, double kappa, Kernel& K) {
  const v8 zero = bc(0.0);
  const v8 pad = {0, 0, 0, 0, 0, 0, kInf, kInf};
  // ---- faces: lane f, heights sigma_f N_f . (r − s) of the other tetrahedron's 4 vertices,
  // D_f = max of them (FV: −min_j s N.(r_j − s_v0); VF: max_i −s N.(r_v0 − s_i), see
  // face_of_A / face_of_B; sigma = −s, exact).
  const double oA = p.oA, oB = p.oB;
  const v8 sig = {-oA, oA, -oA, oA, oB, -oB, oB, -oB};
  v8 N[3];
  for (int k = 0; k < 3; ++k)
    N[k] = v8{p.NA[0][k], p.NA[1][k], p.NA[2][k], p.NA[3][k],
              p.NB[0][k], p.NB[1][k], p.NB[2][k], p.NB[3][k]} * sig;
  v8 D = zero;
  for (int j = 0; j < 4; ++j) {
    v8 X[3];
    for (int k = 0; k < 3; ++k) {
      const double r = B[j][k], s = A[j][k];
      const v8 R = {r, r, r, r, B[1][k], B[0][k], B[0][k], B[0][k]};
      const v8 S = {A[1][k], A[0][k], A[0][k], A[0][k], s, s, s, s};
      X[k] = R - S;
    }
    const v8 h = N[0] * X[0] + N[1] * X[1] + N[2] * X[2];
    D = j == 0 ? h : vmax(D, h);
  }
  const v8 fnn = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
  K.face_val = D * D / fnn;
  v8 lo = D, best = K.face_val;

  // ---- edge pairs: n = eB × eA, lanes b, one vector per a.
  const v8 EBx = edge_lanes_of(p.eB, 0), EBy = edge_lanes_of(p.eB, 1), EBz = edge_lanes_of(p.eB, 2);
  v8 RX[3];
  for (int k = 0; k < 3; ++k)
    RX[k] = v8{B[0][k], B[0][k], B[0][k], B[1][k], B[1][k], B[2][k], 0.0, 0.0};
  for (int f = 0; f < 4; ++f) K.G[f] = EBx * p.NA[f][0] + EBy * p.NA[f][1] + EBz * p.NA[f][2];
  v8 P[2][3];  // sign · NB[face] per lane: q_m = eA . P_m
  for (int m = 0; m < 2; ++m)
    for (int k = 0; k < 3; ++k) {
      v8 t = zero;
      for (int b = 0; b < 6; ++b) t[b] = kOff.sign[m][b] * p.NB[kOff.face[m][b]][k];
      P[m][k] = t;
    }
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) {
    const int u = kEdges[a][0], v = kEdges[a][1], k1 = kOther[a][0], k2 = kOther[a][1];
    const double ax = p.eA[a][0], ay = p.eA[a][1], az = p.eA[a][2];
    const v8 m0 = EBy * az - EBz * ay;
    const v8 m1 = EBz * ax - EBx * az;
    const v8 m2 = EBx * ay - EBy * ax;
    const v8 h = m0 * (RX[0] - A[u][0]) + m1 * (RX[1] - A[u][1]) + m2 * (RX[2] - A[u][2]);
    const v8 g1 = double(parity(u, v, k1)) * K.G[6 - u - v - k1];
    const v8 g2 = double(parity(u, v, k2)) * K.G[6 - u - v - k2];
    const v8 q1 = ax * P[0][0] + ay * P[0][1] + az * P[0][2];
    const v8 q2 = ax * P[1][0] + ay * P[1][1] + az * P[1][2];
    const v8 nn = m0 * m0 + m1 * m1 + m2 * m2;
    const v8 dp = vmax(zero, vmax(g1, g2)) - h - vmin(zero, vmin(q1, q2));
    const v8 dm = -vmin(zero, vmin(g1, g2)) + h + vmax(zero, vmax(q1, q2));
    const v8 inv = 1.0 / nn;
    const v8 d = vmin(dp, dm) + pad;
    const v8 val = d * d * inv;
    K.dp[a] = dp;
    K.dm[a] = dm;
    K.inv[a] = inv;
    K.val[a] = val;
    lo = vmin(lo, d);
    best = vmin(best, val);
  }
  double l = lo[0], b = best[0];
  for (int i = 1; i < 8; ++i) {
    l = min2(l, lo[i]);
    b = min2(b, best[i]);
  }
  K.lo = l;
  K.vmin = b;
  // Entries within t2 of the minimum (header): bit f of face_bits, bit 8a + b of lane_bits.
  K.t1 = tie_threshold(b, kappa);
  const double t2 = tie_threshold(K.t1, kappa);
  const v8l one = {1, 2, 4, 8, 16, 32, 64, 128};
  v8l bits = (K.face_val <= t2) & one;
  K.face_bits = std::uint8_t(horizontal_or(bits));
  bits = v8l{};
  for (int a = 0; a < 6; ++a) bits |= (K.val[a] <= t2) & (one << (8 * a));
  K.lane_bits = std::uint64_t(horizontal_or(bits));
}

// An entry of S near the minimum that is a real candidate: its value and label.
struct Near {
  double value;
  LabelCode code;
  int lane;      // 8a + b, or −1 for a face
  int face;      // 0..7 for a face
  double sign;   // orientation of a lane
};

// Entries with value <= t2 that are real candidates, in canonical order; false when an
// orientation decision is unclear (filter) — then the caller declines.
bool near_candidates(const Precomputed& p, const Kernel& K, const FilterBounds& fb, Near* out,
                     int& count) {
  const double t2 = tie_threshold(K.t1, K.kappa);
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
    const int u = kEdges[a][0], v = kEdges[a][1], k1 = kOther[a][0], k2 = kOther[a][1];
    const double* eA = p.eA[a];
    const double* eB = p.eB[b];
    const double m0 = eB[1] * eA[2] - eB[2] * eA[1];
    const double m1 = eB[2] * eA[0] - eB[0] * eA[2];
    const double m2 = eB[0] * eA[1] - eB[1] * eA[0];
    const double nmax = max2(std::fabs(m0), max2(std::fabs(m1), std::fabs(m2)));
    const double g1 = parity(u, v, k1) * K.G[6 - u - v - k1][b];
    const double g2 = parity(u, v, k2) * K.G[6 - u - v - k2][b];
    if (nmax <= fb.deg2 || std::fabs(g1) <= fb.deg3 || std::fabs(g2) <= fb.deg3) return false;
    const bool pos1 = g1 > 0.0, pos2 = g2 > 0.0;
    const bool flip = pos1 && pos2, undecidable = pos1 != pos2;
    const double inv = K.inv[a][b];
    const double d2p = K.dp[a][b] * K.dp[a][b] * inv, d2m = K.dm[a][b] * K.dm[a][b] * inv;
    const EdgeOrientation plus = undecidable ? EdgeOrientation::Plus : EdgeOrientation::Decided;
    const EdgeOrientation minus = undecidable ? EdgeOrientation::Minus : EdgeOrientation::Decided;
    if (!flip && d2p <= t2) out[count++] = {d2p, pack_label(ContactKind::EE, a, b, plus), lane, -1, 1.0};
    if ((flip || undecidable) && d2m <= t2)
      out[count++] = {d2m, pack_label(ContactKind::EE, a, b, minus), lane, -1, -1.0};
  }
  return true;
}

// The chosen edge-pair candidate, as lane_candidate builds it from the lanes.
void lane_geometry(const TetVertices& A, const TetVertices& B, const Precomputed& p,
                   const Kernel& K, const Near& c, Candidate& g) {
  const int a = c.lane / kLaneStride, b = c.lane % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const int k1 = kOther[a][0], k2 = kOther[a][1];
  const double* eA = p.eA[a];
  const double* eB = p.eB[b];
  const double m[3] = {eB[1] * eA[2] - eB[2] * eA[1], eB[2] * eA[0] - eB[0] * eA[2],
                       eB[0] * eA[1] - eB[1] * eA[0]};
  double w[3];
  sub(B[x], A[u], w);
  const double h = m[0] * w[0] + m[1] * w[1] + m[2] * w[2];
  double q[2];
  for (int j = 0; j < 2; ++j)
    q[j] = kOff.sign[j][b] * dot(eA, p.NB[kOff.face[j][b]]);
  const double s = c.sign;
  const double g1 = parity(u, v, k1) * K.G[6 - u - v - k1][b];
  const double g2 = parity(u, v, k2) * K.G[6 - u - v - k2][b];
  for (int k = 0; k < 3; ++k) g.n[k] = s * m[k];
  g.nn = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
  g.depth = s > 0 ? K.dp[a][b] : K.dm[a][b];
  g.hA[u] = g.hA[v] = 0.0;
  g.hA[k1] = s * g1;
  g.hA[k2] = s * g2;
  g.hB[x] = g.hB[y] = s * h;
  g.hB[kOther[b][0]] = s * (h + q[0]);
  g.hB[kOther[b][1]] = s * (h + q[1]);
  g.conA = edge_mask(a);
  g.conB = edge_mask(b);
}

}  // namespace

bool rigid_superset(const TetVertices& A, const TetVertices& B, Choice& ch, Candidate* geometry) {
  if (!all_finite(A) || !all_finite(B)) return false;
  const FilterBounds fb = filter_bounds(A, B);
  Precomputed p;
  edges_and_faces(A, p.eA, p.NA, &p.detA);
  edges_and_faces(B, p.eB, p.NB, &p.detB);
  if (!(std::fabs(p.detA) > fb.deg3) || !(std::fabs(p.detB) > fb.deg3)) return false;
  p.oA = p.detA > 0 ? 1 : -1;
  p.oB = p.detB > 0 ? 1 : -1;
  Kernel K;
  K.kappa = tie_kappa(A, B);
  superset_kernel(A, B, p, K.kappa, K);
  if (!(K.lo > fb.deg3)) return false;  // not clearly intersecting: exact path decides
  Near near[kMaxCandidates];
  int count = 0;
  if (!near_candidates(p, K, fb, near, count)) return false;
  double vmin = kInf;
  for (int i = 0; i < count; ++i) vmin = min2(vmin, near[i].value);
  if (!(vmin <= K.t1)) return false;
  int pick = 0;
  while (!ties_with_min(near[pick].value, vmin, K.kappa)) ++pick;
  const Near& c = near[pick];
  ch.value = c.value;
  ch.index = -1;
  ch.code = c.code;
  if (!geometry) return true;
  geometry->label = unpack_label(c.code);
  if (c.lane >= 0) {
    lane_geometry(A, B, p, K, c, *geometry);
    return true;
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sub(B[j], A[i], p.d[i][j]);
  face_geometry(p, c.face, *geometry);
  return true;
}

}  // namespace pdd::fast
