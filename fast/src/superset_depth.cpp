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
PDD_INLINE v8 perm(v8 v, v8l idx) { return __builtin_shuffle(v, idx); }
// Max (min, sum) of the 8 lanes, in lane 0 (max and min are exact in any order).
PDD_INLINE double hmax(v8 v) {
  v = v > perm(v, v8l{4, 5, 6, 7, 0, 1, 2, 3}) ? v : perm(v, v8l{4, 5, 6, 7, 0, 1, 2, 3});
  v = v > perm(v, v8l{2, 3, 0, 1, 6, 7, 4, 5}) ? v : perm(v, v8l{2, 3, 0, 1, 6, 7, 4, 5});
  return v[0] > v[1] ? v[0] : v[1];
}
PDD_INLINE double hmin(v8 v) { return -hmax(-v); }
PDD_INLINE double hsum(v8 v) {
  v = v + perm(v, v8l{4, 5, 6, 7, 0, 1, 2, 3});
  v = v + perm(v, v8l{2, 3, 0, 1, 6, 7, 4, 5});
  return v[0] + v[1];
}
PDD_INLINE v8 vabs(v8 a) { return a < 0.0 ? -a : a; }
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
  v8 EA[3], EB[3];  // edge vectors of A and of B, lanes = edges (padding 0), per coordinate
  v8 NAB[3];        // raw face normals, lanes NA[0..3], NB[0..3], per coordinate
  v8 det;           // lanes 3 and 7: det of A and of B (edges_and_faces)
  v8 dp[6], dm[6];  // D(+n), D(−n) per edge pair (a, b)
  v8 inv[6];        // 1/(n.n)
  v8 val[6];        // min(D(±n))² / (n.n)   (padding: +inf)
  v8 G[4];          // eB[b] . NA[f]
  v8 face_val;      // D²/(n.n) of the faces
  double extent;    // L of filter_bounds.h
  double finite;    // 0 when every coordinate is finite (else NaN)
  double lo;        // min over S of D (positivity)
  double vmin;      // min over S of the value
  double kappa;     // tie band of the pair (tie_tolerance.h)
  double t1, t2;    // tie_threshold(vmin); the bound on tie_threshold(t1) used for the masks
  std::uint8_t face_bits;   // faces with value <= t2
  std::uint64_t lane_bits;  // edge pairs (bit 8a + b) with min(value(±n)) <= t2
};

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define PDD_SUPERSET_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_SUPERSET_CLONES
#endif

// Lane-index tables of the permutations below (x[i] = v[idx[i]], v = the SoA vector
// {s0, s1, s2, s3, r0, r1, r2, r3} of one coordinate, or a table of 8 normals).
constexpr v8l kLoad[3] = {{0, 3, 6, 13, 0, 3, 6, 13}, {1, 4, 7, 14, 1, 4, 7, 14},
                          {2, 5, 12, 15, 2, 5, 12, 15}};  // coordinate k of a[0..7], a[4..11]
constexpr v8l kHalves = {0, 1, 2, 3, 12, 13, 14, 15};
constexpr v8l kEdgeU = {0, 0, 0, 1, 1, 2, 0, 0};  // s_u of edge a (padding s0: eA = 0)
constexpr v8l kEdgeV = {1, 2, 3, 2, 3, 3, 0, 0};
constexpr v8l kEdgeX = {4, 4, 4, 5, 5, 6, 4, 4};  // r_x of edge b (padding r0: eB = 0)
constexpr v8l kEdgeY = {5, 6, 7, 6, 7, 7, 4, 4};
constexpr v8l kFace0 = {1, 0, 0, 0, 5, 4, 4, 4};  // v0, v1, v2 of face f (kFace), A then B
constexpr v8l kFace1 = {2, 2, 1, 1, 6, 6, 5, 5};
constexpr v8l kFace2 = {3, 3, 3, 2, 7, 7, 7, 6};
constexpr v8l kDet0 = {0, 0, 0, 0, 4, 4, 4, 4};   // lanes 3, 7: x3 − x0
constexpr v8l kDet3 = {3, 3, 3, 3, 7, 7, 7, 7};
constexpr v8l kFaceR[4] = {{4, 4, 4, 4, 5, 4, 4, 4}, {5, 5, 5, 5, 5, 4, 4, 4},
                           {6, 6, 6, 6, 5, 4, 4, 4}, {7, 7, 7, 7, 5, 4, 4, 4}};
constexpr v8l kFaceS[4] = {{1, 0, 0, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 1, 1, 1, 1},
                           {1, 0, 0, 0, 2, 2, 2, 2}, {1, 0, 0, 0, 3, 3, 3, 3}};
constexpr v8l kNB2 = {4, 5, 6, 7, 4, 5, 6, 7};    // NB twice
// P_m[b] = sign(b, m) NB[face(b, m)] as a lane of {NB, −NB}.
constexpr long long off_index(int m, int b) {
  return kOff.face[m][b] + (kOff.sign[m][b] < 0 ? 4 : 0);
}
constexpr v8l make_off_index(int m) {
  return v8l{off_index(m, 0), off_index(m, 1), off_index(m, 2), off_index(m, 3),
             off_index(m, 4), off_index(m, 5), 0, 0};
}
constexpr v8l kOffIndex[2] = {make_off_index(0), make_off_index(1)};

PDD_INLINE v8 load8(const double* x) {
  v8 v;
  __builtin_memcpy(&v, x, sizeof v);
  return v;
}
PDD_INLINE v8 splat(v8 v, int i) { return perm(v, v8l{i, i, i, i, i, i, i, i}); }
PDD_INLINE void cross8(const v8* a, const v8* b, v8* o) {  // detail::cross, lane-wise
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

// Edges, face normals, determinants (the arithmetic of edges_and_faces, lane-wise), D, n.n and
// D²/(n.n) of the 8 faces and of both orientations of the 36 edge pairs, and the entries near
// the minimum.
PDD_SUPERSET_CLONES void superset_kernel(const TetVertices& A, const TetVertices& B, Kernel& K) {
  const v8 zero = bc(0.0);
  const v8 pad = {0, 0, 0, 0, 0, 0, kInf, kInf};
  v8 X[3];  // coordinates, structure of arrays: lanes s0..s3, r0..r3
  {
    const double *a = &A[0][0], *b = &B[0][0];  // 12 contiguous doubles each
    const v8 a0 = load8(a), a1 = load8(a + 4), b0 = load8(b), b1 = load8(b + 4);
    for (int k = 0; k < 3; ++k)
      X[k] = __builtin_shuffle(__builtin_shuffle(a0, a1, kLoad[k]),
                               __builtin_shuffle(b0, b1, kLoad[k]), kHalves);
  }
  // extent, largest |coordinate| (tie_tolerance.h), finiteness (x·0 is NaN for inf and NaN)
  K.extent = max2(hmax(X[0]) - hmin(X[0]), max2(hmax(X[1]) - hmin(X[1]), hmax(X[2]) - hmin(X[2])));
  const double R = hmax(vmax(vmax(vabs(X[0]), vabs(X[1])), vabs(X[2])));
  const double kappa = K.kappa = kTieCoeff * kUnitRoundoff * R;
  K.finite = hsum(X[0] * 0.0 + X[1] * 0.0 + X[2] * 0.0);
  // edges, face normals (v1 − v0) × (v2 − v0), det = N_3 . (x3 − x0)
  v8 U[3], V[3], T[3], RX[3];
  for (int k = 0; k < 3; ++k) {
    K.EA[k] = perm(X[k], kEdgeV) - perm(X[k], kEdgeU);
    RX[k] = perm(X[k], kEdgeX);
    K.EB[k] = perm(X[k], kEdgeY) - RX[k];
    const v8 v0 = perm(X[k], kFace0);
    U[k] = perm(X[k], kFace1) - v0;
    V[k] = perm(X[k], kFace2) - v0;
    T[k] = perm(X[k], kDet3) - perm(X[k], kDet0);
  }
  v8* NAB = K.NAB;
  cross8(U, V, NAB);
  K.det = NAB[0] * T[0] + NAB[1] * T[1] + NAB[2] * T[2];
  const v8* EB = K.EB;
  // ---- faces: lane f, heights sigma_f N_f . (r − s) of the other tetrahedron's 4 vertices,
  // D_f = max of them (FV: −min_j s N.(r_j − s_v0); VF: max_i −s N.(r_v0 − s_i), see
  // face_of_A / face_of_B; sigma = −s, exact; o = orientation sign of the tetrahedron).
  const v8 o = perm(K.det, kDet3) > 0.0 ? bc(1.0) : bc(-1.0);
  const v8 sig = o * v8{-1, 1, -1, 1, 1, -1, 1, -1};
  v8 N[3];
  for (int k = 0; k < 3; ++k) N[k] = NAB[k] * sig;
  v8 D = zero;
  for (int j = 0; j < 4; ++j) {
    v8 d[3];  // FV lanes: r_j − s_v0; VF lanes: r_v0 − s_j
    for (int k = 0; k < 3; ++k) d[k] = perm(X[k], kFaceR[j]) - perm(X[k], kFaceS[j]);
    const v8 h = N[0] * d[0] + N[1] * d[1] + N[2] * d[2];
    D = j == 0 ? h : vmax(D, h);
  }
  const v8 fnn = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
  K.face_val = D * D / fnn;
  v8 lo = D, best = K.face_val;

  // ---- edge pairs: n = eB × eA, lanes b, one vector per a.
  v8 P[2][3];  // P_m = sign · NB[face]: q_m = eA . P_m
  const v8 neg_hi = {1, 1, 1, 1, -1, -1, -1, -1};
  for (int k = 0; k < 3; ++k) {
    const v8 nb = perm(NAB[k], kNB2) * neg_hi;  // {NB, −NB}
    P[0][k] = perm(nb, kOffIndex[0]);
    P[1][k] = perm(nb, kOffIndex[1]);
  }
  // Scalars of EA and NAB are broadcast from memory (load ports) rather than permuted: the
  // barrier makes the compiler read them back from K.
  asm volatile("" : : "m"(K.EA), "m"(K.NAB) : "memory");
  for (int f = 0; f < 4; ++f)
    K.G[f] = EB[0] * K.NAB[0][f] + EB[1] * K.NAB[1][f] + EB[2] * K.NAB[2][f];
#pragma GCC unroll 6
  for (int a = 0; a < 6; ++a) {
    const int u = kEdges[a][0], v = kEdges[a][1], k1 = kOther[a][0], k2 = kOther[a][1];
    const double ax = K.EA[0][a], ay = K.EA[1][a], az = K.EA[2][a];
    const v8 m0 = EB[1] * az - EB[2] * ay;
    const v8 m1 = EB[2] * ax - EB[0] * az;
    const v8 m2 = EB[0] * ay - EB[1] * ax;
    const v8 h = m0 * (RX[0] - A[u][0]) + m1 * (RX[1] - A[u][1]) + m2 * (RX[2] - A[u][2]);
    const v8 g1 = double(parity(u, v, k1)) * K.G[6 - u - v - k1];
    const v8 g2 = double(parity(u, v, k2)) * K.G[6 - u - v - k2];
    const v8 q1 = ax * P[0][0] + ay * P[0][1] + az * P[0][2];
    const v8 q2 = ax * P[1][0] + ay * P[1][1] + az * P[1][2];
    const v8 nn = m0 * m0 + m1 * m1 + m2 * m2;
    const v8 dp = vmax(zero, vmax(g1, g2)) - h - vmin(zero, vmin(q1, q2));
    const v8 dm = -vmin(zero, vmin(g1, g2)) + h + vmax(zero, vmax(q1, q2));
    const v8 inv = 1.0 / nn;
    const v8 dd = vmin(dp, dm) + pad;
    const v8 val = dd * dd * inv;
    K.dp[a] = dp;
    K.dm[a] = dm;
    K.inv[a] = inv;
    K.val[a] = val;
    lo = vmin(lo, dd);
    best = vmin(best, val);
  }
  K.lo = hmin(lo);
  const double b = K.vmin = hmin(best);
  // Entries within t2 of the minimum (header): bit f of face_bits, bit 8a + b of lane_bits.
  // One square root: with q = sqrt(vmin), t1 = vmin + kappa q and sqrt(t1) <= q + kappa/2,
  // so tie_threshold(t1) <= t1 + kappa (q + kappa/2); the extra kappa q + kappa²/2 covers the
  // rounding of both thresholds (kappa q >= 128 u R PD >= 4 u t1, as PD <= 4R).
  const double q = std::sqrt(b);
  K.t1 = b + kappa * q;  // = tie_threshold(b, kappa)
  const double t2 = K.t1 + kappa * (q + q + kappa);
  K.t2 = t2;
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
bool near_candidates(const Kernel& K, const FilterBounds& fb, Near* out, int& count) {
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
    const int u = kEdges[a][0], v = kEdges[a][1], k1 = kOther[a][0], k2 = kOther[a][1];
    const double eA[3] = {K.EA[0][a], K.EA[1][a], K.EA[2][a]};
    const double eB[3] = {K.EB[0][b], K.EB[1][b], K.EB[2][b]};
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
void lane_geometry(const TetVertices& A, const TetVertices& B, const Kernel& K, const Near& c,
                   Candidate& g) {
  const int a = c.lane / kLaneStride, b = c.lane % kLaneStride;
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  const int k1 = kOther[a][0], k2 = kOther[a][1];
  const double eA[3] = {K.EA[0][a], K.EA[1][a], K.EA[2][a]};
  const double eB[3] = {K.EB[0][b], K.EB[1][b], K.EB[2][b]};
  const double m[3] = {eB[1] * eA[2] - eB[2] * eA[1], eB[2] * eA[0] - eB[0] * eA[2],
                       eB[0] * eA[1] - eB[1] * eA[0]};
  double w[3];
  sub(B[x], A[u], w);
  const double h = m[0] * w[0] + m[1] * w[1] + m[2] * w[2];
  double q[2];
  for (int j = 0; j < 2; ++j) {
    const int f = 4 + kOff.face[j][b];
    const double nb[3] = {K.NAB[0][f], K.NAB[1][f], K.NAB[2][f]};
    q[j] = kOff.sign[j][b] * dot(eA, nb);
  }
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

// The chosen face candidate: face_geometry over the kernel's normals and determinants.
void face_geometry_of(const TetVertices& A, const TetVertices& B, const Kernel& K, int f,
                      Candidate& g) {
  Precomputed p;  // only the fields face_geometry reads
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      p.NA[i][k] = K.NAB[k][i];
      p.NB[i][k] = K.NAB[k][4 + i];
    }
  p.detA = K.det[3];
  p.detB = K.det[7];
  p.oA = p.detA > 0 ? 1 : -1;
  p.oB = p.detB > 0 ? 1 : -1;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sub(B[j], A[i], p.d[i][j]);
  face_geometry(p, f, g);
}

}  // namespace

bool rigid_superset(const TetVertices& A, const TetVertices& B, Choice& ch, Candidate* geometry) {
  Kernel K;
  superset_kernel(A, B, K);  // (non-finite input: garbage values, rejected next)
  if (!(K.finite == 0.0)) return false;
  const FilterBounds fb = filter_bounds_of_extent(K.extent);
  // valid tetrahedra (orientation trusted by the kernel), clearly intersecting: else exact path
  if (!(std::fabs(K.det[3]) > fb.deg3) || !(std::fabs(K.det[7]) > fb.deg3)) return false;
  if (!(K.lo > fb.deg3)) return false;
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
  if (!geometry) return true;
  if (c.lane >= 0)
    lane_geometry(A, B, K, c, *geometry);
  else
    face_geometry_of(A, B, K, c.face, *geometry);
  geometry->label = unpack_label(c.code);
  return true;
}

}  // namespace pdd::fast
