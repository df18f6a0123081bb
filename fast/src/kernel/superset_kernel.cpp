// superset_kernel.cpp — the vectorised superset arithmetic (superset_kernel.h); the proof that
// the superset gives PD is in superset_depth.h.
//
// Layout: 8-wide vectors, each two 4-lane halves (edge_pair_formula.h: two ymm with AVX2 and
// AVX-512, four xmm otherwise — clones chosen at run time). Coordinates as structure of arrays (lanes s0..s3,
// r0..r3, one vector per axis); edges and face normals by lane permutations of them. Edge pairs:
// one vector per edge a of A, lane b = edge of B (lanes 6, 7 padding). Faces: one vector, lane
// f = FV:0..3, VF:0..3. Every value is computed with the same IEEE operations in the same order
// as direction_geometry (no FMA: -ffp-contract=off; no reassociation), so it is bit-identical to
// the candidate list.
//
// Work per pair (arithmetic flops = add, sub, mul, div, sqrt on useful lanes; min/max/abs and
// selects counted apart):
//   edges 36, face normals 48 + 72, determinants 10                              166
//   faces: oriented normals 24, differences 96, 32 heights 160, n.n 40, D²/n.n 16  336
//   tables: {NB, −NB} 24, G = eB.NA 120, r_x − s_u 54                            198
//   QB = eA.NB for 6 × 4 (edge, face) pairs (q1, q2 are permuted lanes of {QB, −QB})  120
//   36 edge pairs × (n 9, hx 5, g 2, n.n 5, D(±n) 5, 1/n.n 1, +pad 1, value 2 = 30) 1080
//   total ≈ 1900 flops, plus ≈ 550 min/max/abs/selects (36 × 11 in the lanes, 24 face maxima,
//   the extent, R and finiteness reductions) — ≈ 2450 lane operations, 3300 counting padding.
// The AVX2 clone of the rigid kernel has ≈ 950 vector FP instructions on 4-lane halves
// (≈ 300 mul, 290 add/sub, 14 div, ≈ 300 min/max/compare/blend) and ≈ 100 permutes, plus
// spills (16 ymm registers): ≈ 2000 instructions, ≈ 650 cycles at the measured IPC of ≈ 3 on
// an AMD EPYC (Zen) core, ≈ 240 ns. `pdd bench` measures the whole call on the machine at hand
// (one machine's numbers live in issue notes, not here).
#include "kernel/superset_kernel.h"

#include "kernel/lane_shuffle.h"

#include <cmath>
#include <limits>

#include "certification/filter_bounds.h"
#include "certification/tie_tolerance.h"
#include "certification/value_bounds.h"
#include "kernel/power_scale.h"

namespace pdd::fast::detail {
namespace {

#define PDD_INLINE static inline __attribute__((always_inline))

constexpr double kInf = std::numeric_limits<double>::infinity();

// Lane-wise (a > t) & bits, (a >= t) & bits: ordered comparisons (false for NaN).
PDD_INLINE v8l gt_bits(v8 a, double t, v8l bits) {
  return {(a.lo > t) & bits.lo, (a.hi > t) & bits.hi};
}
PDD_INLINE v8l ge_bits(v8 a, double t, v8l bits) {
  return {(a.lo >= t) & bits.lo, (a.hi >= t) & bits.hi};
}
PDD_INLINE long long horizontal_or(v8l v) {
  const v4hl m = v.lo | v.hi;
  return (m[0] | m[1]) | (m[2] | m[3]);
}
// x[i] = v[idx[i]]: per output half one two-source 4-lane permute of v's halves (constant
// masks: vpermpd / vshufpd / vblendpd / vperm2f128 on AVX2).
PDD_INLINE v8 perm(v8 v, v8l idx) {
  return {shuffle(v.lo, v.hi, idx.lo & 7), shuffle(v.lo, v.hi, idx.hi & 7)};
}
// Max (min, sum) of the 8 lanes, in lane 0 (max and min are exact in any order).
PDD_INLINE double hmax(v8 v) {
  // (the maximum of the lanes in any order: max is exact; max2 on halves, edge_pair_formula.h)
  v4h m = v.lo > v.hi ? v.lo : v.hi;
  const v4h s = shuffle(m, v4hl{2, 3, 0, 1});
  m = m > s ? m : s;
  return m[0] > m[1] ? m[0] : m[1];
}
PDD_INLINE double hmin(v8 v) { return -hmax(-v); }
PDD_INLINE double hsum(v8 v) {  // (only tested against 0: the order is immaterial)
  v4h m = v.lo + v.hi;
  m = m + shuffle(m, v4hl{2, 3, 0, 1});
  return m[0] + m[1];
}
PDD_INLINE v8 vabs(v8 a) {
  return {a.lo < 0.0 ? -a.lo : a.lo, a.hi < 0.0 ? -a.hi : a.hi};
}
// A scalar in every lane (one 4-lane splat, used for both halves).
PDD_INLINE v8 bc(double x) {
  const v4h h = {x, x, x, x};
  return {h, h};
}

// A v8 stored as its two 32-byte halves (put: into K; store8: into the candidate list's
// lanes). With an aggregate assignment or one 64-byte memcpy, GCC's AVX-512 clone copies the
// struct with one 64-byte move, which it builds by spilling both halves to the stack and
// reloading them as one zmm: a store-forwarding stall per store (perf: the hottest
// instructions of the kernel on a Zen 4). Same bits, only the moves differ.
PDD_INLINE void store8(double* p, v8 v) {
  __builtin_memcpy(p, &v.lo, sizeof v.lo);
  __builtin_memcpy(p + 4, &v.hi, sizeof v.hi);
}
PDD_INLINE void put(v8& dst, v8 v) {
  dst.lo = v.lo;
  dst.hi = v.hi;
}

// Run-time dispatch on x86-64 with GCC (ifunc, glibc). The clones compute the same IEEE
// operations (no FMA: -ffp-contract=off), so results do not depend on the machine. Not with
// clang 14: its target_clones here ran AVX-512 code on a machine without it (SIGILL in
// tests/fast), so clang builds get the baseline x86-64 code of the kernel.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PDD_SUPERSET_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define PDD_SUPERSET_CLONES
#endif

// Lane-index tables of the permutations below (x[i] = v[idx[i]], v = the SoA vector
// {s0, s1, s2, s3, r0, r1, r2, r3} of one coordinate, or a table of 8 normals).
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
  return kOffFaces.face[b][m] + (off_sign_B(b, m) < 0 ? 4 : 0);
}
constexpr v8l make_off_index(int m) {
  return v8l{off_index(m, 0), off_index(m, 1), off_index(m, 2), off_index(m, 3),
             off_index(m, 4), off_index(m, 5), 0, 0};
}
constexpr v8l kOffIndex[2] = {make_off_index(0), make_off_index(1)};

PDD_INLINE void cross8(const v8* a, const v8* b, v8* o) {  // detail::cross, lane-wise
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

// Coordinates as structure of arrays: X[k] = {s0, s1, s2, s3, r0, r1, r2, r3} of axis k.
PDD_INLINE void soa_coordinates(const TetVertices& A, const TetVertices& B, v8* X) {
  for (int k = 0; k < 3; ++k)
    X[k] = {v4h{A[0][k], A[1][k], A[2][k], A[3][k]}, v4h{B[0][k], B[1][k], B[2][k], B[3][k]}};
}

// Extent L (filter_bounds.h), kappa = kTieCoeff u R (tie_tolerance.h, R = max |coordinate|)
// and finiteness (x·0 is NaN for inf and NaN).
PDD_INLINE void pair_scales(const v8* X, SupersetLanes& K) {
  K.extent = max2(hmax(X[0]) - hmin(X[0]), max2(hmax(X[1]) - hmin(X[1]), hmax(X[2]) - hmin(X[2])));
  const double R = hmax(max2(max2(vabs(X[0]), vabs(X[1])), vabs(X[2])));
  K.kappa = kTieCoeff * kUnitRoundoff * R;
  K.finite = hsum(X[0] * 0.0 + X[1] * 0.0 + X[2] * 0.0);
}

// Edges EA, EB (and r_x of B's edges), face normals NAB = (v1 − v0) × (v2 − v0) and
// det = N_3 . (x3 − x0): the arithmetic of edges_and_faces, lane-wise.
PDD_INLINE void edges_and_normals(const v8* X, SupersetLanes& K, v8* RX) {
  v8 U[3], V[3], T[3];
  for (int k = 0; k < 3; ++k) {
    put(K.EA[k], perm(X[k], kEdgeV) - perm(X[k], kEdgeU));
    RX[k] = perm(X[k], kEdgeX);
    put(K.EB[k], perm(X[k], kEdgeY) - RX[k]);
    const v8 v0 = perm(X[k], kFace0);
    U[k] = perm(X[k], kFace1) - v0;
    V[k] = perm(X[k], kFace2) - v0;
    T[k] = perm(X[k], kDet3) - perm(X[k], kDet0);
  }
  v8 nab[3];
  cross8(U, V, nab);
  for (int k = 0; k < 3; ++k) put(K.NAB[k], nab[k]);
  put(K.det, nab[0] * T[0] + nab[1] * T[1] + nab[2] * T[2]);
}

// Faces, lane f: heights H_j = sigma_f N_f . (r − s) of the other tetrahedron's 4 vertices and
// D_f = max_j H_j (FV: −min_j s N.(r_j − s_v0); VF: max_i −s N.(r_v0 − s_i), see face_of_A /
// face_of_B; sigma = −s, exact; o = orientation sign of the tetrahedron); value D²/(n.n).
// Returns D.
PDD_INLINE v8 face_values(const v8* X, SupersetLanes& K, v8& fnn) {
  const v8 dh = perm(K.det, kDet3);
  const v4h plus = {1.0, 1.0, 1.0, 1.0}, minus = -plus;
  const v8 o = {dh.lo > 0.0 ? plus : minus, dh.hi > 0.0 ? plus : minus};
  const v8 sig = o * v8{-1, 1, -1, 1, 1, -1, 1, -1};
  v8 N[3];
  for (int k = 0; k < 3; ++k) N[k] = K.NAB[k] * sig;
  v8 D = bc(0.0);
  for (int j = 0; j < 4; ++j) {
    v8 d[3];  // FV lanes: r_j − s_v0; VF lanes: r_v0 − s_j
    for (int k = 0; k < 3; ++k) d[k] = perm(X[k], kFaceR[j]) - perm(X[k], kFaceS[j]);
    const v8 h = N[0] * d[0] + N[1] * d[1] + N[2] * d[2];
    put(K.H[j], h);
    D = j == 0 ? h : max2(D, h);
  }
  fnn = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
  put(K.face_val, D * D / fnn);
  return D;
}

constexpr v8l kOne = {1, 2, 4, 8, 16, 32, 64, 128};
// The thresholds of tie_and_certify_bits' tests that do not depend on the minimum: D² >= D_min2 and
// n.n >= nn_min, made in the edge loop where D² and 1/(n.n) are at hand.
struct SmallBounds {
  double D_min2, nn_min;
};
PDD_INLINE SmallBounds small_bounds(double extent) {
  const DegreeBounds db = degree_bounds(filter_bounds_of_extent(extent), false);
  const double eh = kFarBoundScale * db.e_h, en = kFarBoundScale * db.e_n;
  return {eh * eh, en * en};
}

// Edge pairs, n = eB × eA, lanes b, one vector per a (edge_lanes' arithmetic): D(±n), 1/(n.n),
// the lane's value min(D(±n))²/(n.n) (padding +inf); running minima of D and of the value.
// kFull: also the candidate list's lanes (superset_kernel.h), verdicts by finish_lanes.
// pA: the factor of A's coordinates (the fused scaling, kernel_body; 1 otherwise, not applied).
template <bool kFull, bool kScaled>
PDD_INLINE void edge_pair_values(const TetVertices& A, double pA, const v8* RX, SupersetLanes& K,
                                 EdgeLanes* full, v8& lo, v8& best, const SmallBounds& sb,
                                 v8l& small) {
  const v8 pad = {0, 0, 0, 0, 0, 0, kInf, kInf};
  const v8* EB = K.EB;
  v8 NB2[3];  // {NB, −NB} per axis: eA . NB2 = {QB, −QB}, q_m = sign · QB[face] a lane of it
  const v8 neg_hi = {1, 1, 1, 1, -1, -1, -1, -1};
  for (int k = 0; k < 3; ++k) NB2[k] = perm(K.NAB[k], kNB2) * neg_hi;
  // Scalars of EA and NAB are broadcast from memory (load ports) rather than permuted: the
  // barrier makes the compiler read them back from K. An empty GNU asm statement (GCC and
  // clang, any target): it emits no instruction and changes no value, only the schedule.
  asm volatile("" : : "m"(K.EA), "m"(K.NAB) : "memory");
  for (int f = 0; f < 4; ++f)
    put(K.G[f], EB[0] * bc(K.NAB[0][f]) + EB[1] * bc(K.NAB[1][f]) + EB[2] * bc(K.NAB[2][f]));
  v8 W[3][3];  // W[u] = r_x(b) − s_u, u = 0, 1, 2 (the first vertex of every edge of A)
  for (int u = 0; u < 3; ++u)
    for (int k = 0; k < 3; ++k) W[u][k] = RX[k] - bc(kScaled ? A[u][k] * pA : A[u][k]);
#pragma GCC unroll 6  // clang reads it as its own unroll pragma
  for (int a = 0; a < 6; ++a) {
    const int u = kEdges[a][0];
    const v8 ax = bc(K.EA[0][a]), ay = bc(K.EA[1][a]), az = bc(K.EA[2][a]);
    v8 m0, m1, m2, dp, dm;
    edge_pair_normal(ax, ay, az, EB[0], EB[1], EB[2], m0, m1, m2);
    const v8* w = W[u];
    const v8 h = edge_pair_dot(m0, m1, m2, w[0], w[1], w[2]);
    const v8 g1 = bc(kOffFaces.eps[a][0]) * K.G[kOffFaces.face[a][0]];
    const v8 g2 = bc(kOffFaces.eps[a][1]) * K.G[kOffFaces.face[a][1]];
    const v8 qb = ax * NB2[0] + ay * NB2[1] + az * NB2[2];
    const v8 q1 = perm(qb, kOffIndex[0]), q2 = perm(qb, kOffIndex[1]);
    const v8 nn = edge_pair_nn(m0, m1, m2);
    edge_pair_depths(g1, g2, h, q1, q2, dp, dm);
    const v8 inv = 1.0 / nn;
    const v8 dd = min2(dp, dm) + pad;
    const v8 d2 = dd * dd;
    const v8 val = d2 * inv;  // = dd * dd * inv
    small |= ge_bits(d2, sb.D_min2, kOne << (8 * a)) & le_bits(inv * sb.nn_min, 1.0, kOne << (8 * a));
    put(K.dp[a], dp);
    put(K.dm[a], dm);
    put(K.inv[a], inv);
    put(K.val[a], val);
    if (kFull) {
      const int o = kLaneStride * a;
      store8(full->n0 + o, m0);
      store8(full->n1 + o, m1);
      store8(full->n2 + o, m2);
      store8(full->nn + o, nn);
      store8(full->hx + o, h);
      store8(full->g1 + o, g1);
      store8(full->g2 + o, g2);
      store8(full->q1 + o, q1);
      store8(full->q2 + o, q2);
      store8(full->dplus + o, dp);
      store8(full->dminus + o, dm);
      store8(full->d2plus + o, dp * dp * inv);
      store8(full->d2minus + o, dm * dm * inv);
    }
    lo = min2(lo, dd);
    best = min2(best, val);
  }
}

// tie_and_certify_bits: the tie masks and the bound bits.
// Entries within t2 of the minimum (superset_depth.h): bit f of face_bits, bit 8a + b of
// lane_bits. One square root: with q = sqrt(vmin), t1 = vmin + kappa q and sqrt(t1) <=
// q + kappa/2, so tie_threshold(t1) <= t1 + kappa (q + kappa/2); the extra kappa q + kappa²/2
// covers the rounding of both thresholds (kappa q >= 128 u R PD >= 4 u t1, as PD <= 4R).
// Entries certify() (superset_depth.cpp) must bound: all but those that cannot change its
// verdict whatever it picks. Proof. certify() computes lo_all = min of the bounded entries'
// lower_of(v, r) and certifies when hi = upper_of(v~, r_pick) <= (1 + kCertifyRel) lo_all
// (computed: <= (1 + 1e-9)(1 + u) lo_all), lo_all > 0; `unique` adds hi < lo_other.
// The picked value v~ is <= t2 (near_candidates in superset_depth.cpp admits only entries
// with value <= t2), and lo_all <= lo_pick <= v~ (lower_of multiplies by factors <= 1:
// monotone roundings). So a certified verdict has
// hi <= (1 + 1e-9)(1 + u) t2 < 1.0001 t2, and an entry whose exact-value lower bound
// lo >= 1.0001 t2 can change neither the verdict (certified_choice is monotone in lo_min and
// holds for lo >= hi) nor `unique` (lo > hi): it is skipped. Test (products only, no division or
// square root): v > far = 1.001 t2 (computed: >= 1.001 (1 − u) t2), D² >= (K e_h)² and
// n.n >= (K e_n)² with K = 10^5 (test for lanes: inv·(K e_n)² <= 1, a rounding of 1/(n.n)
// times a rounded product: n.n >= (1 − 3u)(K e_n)², a margin far below the one used next).
// Then value_bounds.h's root bound is r = 1.02 (a + rho + 4u) with a <= (2 e_h + u|D|)/|D|
// (1 + 3u) <= 2/K + 2u and rho <= sqrt(3)(1 + 4u)/K: r <= 1.02 (3.7321e-5 + 6u)(1 + 4u)
// < 3.81e-5 (finite: a, rho <= 0.01), and lower_of(v, r) >= v (1 − r)² (1 − 3u)
// > 1.001 (1 − u)(1 − 7.63e-5)(1 − 3u) t2 > 1.00092 t2 >= 1.0001 t2. (On the paper's
// protocol this leaves 1.01 bounded entries per pair, against 6.2 with the earlier test
// v > 2 t2, K = 400: each bounded entry costs a division and a square root.)
// Per edge lane the test is made on dd = min(D(+n), D(−n)) and val = dd·dd·inv: D(±n) >= dd and
// both are > 0 here (else the pair is declined), so both orientations' D² and values are >= dd²,
// val (rounding is monotone): both are skipped. Faces: n.n = N.N with N = ±NAB (the same
// squares). NaN anywhere: every comparison is false, kept. No underflow in (K e_h)² or
// (K e_n)² (an underflow to 0 would make its test vacuous): certify()'s verdict is used only on
// pairs rescaled by power_scale.h (largest |coordinate| in [1, 2); hot_path.h) that passed the
// orientation filter; a coordinate c of magnitude in [1, 2) has another vertex of its
// tetrahedron at a different value on that axis (else the tetrahedron is flat), at distance
// >= 2^-53, so L >= 2^-53, e_h >= 128 u L³ >= 2^-205, e_n >= 64 u L² >= 2^-153, and
// (K = 1e5 > 2^16.6) (K e_h)² >= 2^-377, (K e_n)² >= 2^-273, both normal.
// The tests D² >= (K e_h)² and n.n >= (K e_n)² of the lanes are made in the edge loop, where D²
// and 1/(n.n) are at hand (`small`: the lanes passing both, SmallBounds); here only v > far, in
// the same pass over the values as the tie masks. Ordered comparisons (gt_bits, ge_bits,
// le_bits): false for NaN, so a NaN entry is never skipped. (Measured: 10 ns of the kernel's
// 158 ns on the paper's pairs against two passes that reloaded D.)
PDD_INLINE void tie_and_certify_bits(SupersetLanes& K, const v8& fnn, const SmallBounds& sb,
                                     v8l small) {
  const double b = K.vmin, kappa = K.kappa;
  const double q = std::sqrt(b);
  K.t1 = b + kappa * q;  // = tie_threshold(b, kappa)
  const double t2 = K.t2 = K.t1 + kappa * (q + q + kappa);
  const double far = kFarFactor * t2;
  const v8 fv = K.face_val, fd2 = fv * fnn;
  K.face_bits = std::uint8_t(horizontal_or(le_bits(fv, t2, kOne)));
  const v8l skip = gt_bits(fv, far, kOne) & ge_bits(fd2, sb.D_min2, kOne) &
                   ge_bits(fnn, sb.nn_min, kOne);
  K.face_bound_bits = std::uint8_t(~horizontal_or(skip) & 0xff);
  v8l tie{}, far_bits{};
  for (int a = 0; a < 6; ++a) {
    const v8 v = K.val[a];
    const v8l lane = kOne << (8 * a);
    tie |= le_bits(v, t2, lane);
    far_bits |= gt_bits(v, far, lane);
  }
  K.lane_bits = std::uint64_t(horizontal_or(tie));
  K.lane_bound_bits = std::uint64_t(~horizontal_or(far_bits & small)) & 0x3f3f3f3f3f3fULL;
}

// power_scale.h's scaling of the pair, fused (kernel_rigid_scaling): its two reductions on the
// coordinate vectors (the maxima and minima are exact, so the lanes' order does not matter and
// hs, ls are power_scaled's), its rule (common_scale), and the products x·2^e (the same
// correctly rounded products). False, X unchanged: not the common case, or not exact.
PDD_INLINE bool scale_coordinates(v8* X, int& e, double& p) {
  const v4hl abs = {0x7fffffffffffffffll, 0x7fffffffffffffffll, 0x7fffffffffffffffll,
                    0x7fffffffffffffffll};
  const v4h zero = {0.0, 0.0, 0.0, 0.0}, dmax = {DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX};
  v4h hi = zero, lo = dmax;
  for (int k = 0; k < 3; ++k)
    for (const v4h half : {X[k].lo, X[k].hi}) {
      const v4hl a = (v4hl)half & abs;
      const v4h h = (v4h)(a >> 1), l = (v4h)(a - 1);
      hi = h > hi ? h : hi;
      lo = l < lo ? l : lo;  // (NaN l is never taken: power_scale.h)
    }
  const v4h hs2 = shuffle(hi, v4hl{2, 3, 0, 1}), ls2 = shuffle(lo, v4hl{2, 3, 0, 1});
  hi = hs2 > hi ? hs2 : hi;
  lo = ls2 < lo ? ls2 : lo;
  const double hs = hi[1] > hi[0] ? hi[1] : hi[0], ls = lo[1] < lo[0] ? lo[1] : lo[0];
  bool exact = false;
  if (!common_scale(hs, ls, e, p, exact) || !exact) return false;
  const v8 pv = bc(p);
  for (int k = 0; k < 3; ++k) X[k] = X[k] * pv;
  return true;
}

// The whole kernel. kFull: also the candidate list's lanes. A template, so that the rigid
// kernel carries no trace of the extra stores (registers, code size). kScaled: on the pair
// power_scaled(A, B) (scale_coordinates; false when that is not its common exact case).
template <bool kFull, bool kScaled = false>
PDD_INLINE bool kernel_body(const TetVertices& A, const TetVertices& B, SupersetLanes& K,
                            EdgeLanes* full, int* e = nullptr) {
  v8 X[3], RX[3];
  soa_coordinates(A, B, X);
  double pA = 1.0;
  if (kScaled && !scale_coordinates(X, *e, pA)) return false;
  for (int k = 0; k < 3; ++k) put(K.X[k], X[k]);
  pair_scales(X, K);
  edges_and_normals(X, K, RX);
  const SmallBounds sb = small_bounds(K.extent);
  v8 fnn;
  v8 lo = face_values(X, K, fnn), best = K.face_val;
  v8l small{};
  edge_pair_values<kFull, kScaled>(A, pA, RX, K, full, lo, best, sb, small);
  if (kFull) {
    const FilterBounds fb = filter_bounds_of_extent(K.extent);
    finish_lanes(kExactNormalBelow * fb.deg2, fb.deg3, *full);  // (as build_candidates: the same verdicts)
  }
  K.lo = hmin(lo);
  K.vmin = hmin(best);
  tie_and_certify_bits(K, fnn, sb, small);
  return true;
}

PDD_SUPERSET_CLONES void kernel_rigid(const TetVertices& A, const TetVertices& B, SupersetLanes& K) {
  kernel_body<false>(A, B, K, nullptr);
}
PDD_SUPERSET_CLONES void kernel_full(const TetVertices& A, const TetVertices& B, SupersetLanes& K,
                                     EdgeLanes* full) {
  kernel_body<true>(A, B, K, full);
}
PDD_SUPERSET_CLONES bool kernel_rigid_scaling(const TetVertices& A, const TetVertices& B,
                                              SupersetLanes& K, int* e) {
  return kernel_body<false, true>(A, B, K, nullptr, e);
}

// drop_lanes (header), lane-wise: the lanes of edge a are one v8 (b = 0..7, padding 6, 7
// never kept), a kept lane's entries taken, a dropped one's replaced by +inf in the minima.
PDD_SUPERSET_CLONES bool drop_lanes_body(SupersetLanes& K, double deg3, double D_min2, double nn_min,
                                         std::uint64_t unresolved) {
  const std::uint64_t kept = 0x3f3f3f3f3f3fULL & ~unresolved;
  const v8 inf = bc(kInf);
  v8 lo = max2(max2(K.H[0], K.H[1]), max2(K.H[2], K.H[3]));  // per face f: D = max_j H[j][f]
  v8 best = K.face_val;
  v8l keep[6];
  for (int a = 0; a < 6; ++a) {
    const long long k = (long long)(kept >> (8 * a) & 0xffu);
    const v8l m = v8l{k, k, k, k, k, k, k, k} & kOne;
    keep[a] = m;
    const v4hl on_lo = m.lo != 0, on_hi = m.hi != 0;
    const v8 dd = min2(K.dp[a], K.dm[a]);
    lo = min2(lo, v8{on_lo ? dd.lo : inf.lo, on_hi ? dd.hi : inf.hi});
    best = min2(best, v8{on_lo ? K.val[a].lo : inf.lo, on_hi ? K.val[a].hi : inf.hi});
  }
  const double lo_min = hmin(lo);
  if (!(lo_min > deg3)) return false;
  const double vmin = hmin(best);
  K.lo = lo_min;
  K.vmin = vmin;
  const double q = std::sqrt(vmin);
  K.t1 = vmin + K.kappa * q;  // = tie_threshold(vmin, kappa)
  const double t2 = K.t2 = K.t1 + K.kappa * (q + q + K.kappa), far = kFarFactor * t2;
  const v8 fv = K.face_val, fnn = K.NAB[0] * K.NAB[0] + K.NAB[1] * K.NAB[1] + K.NAB[2] * K.NAB[2];
  K.face_bits = std::uint8_t(horizontal_or(le_bits(fv, t2, kOne)));
  const v8l skip = gt_bits(fv, far, kOne) & ge_bits(fv * fnn, D_min2, kOne) & ge_bits(fnn, nn_min, kOne);
  K.face_bound_bits = std::uint8_t(~horizontal_or(skip) & 0xff);
  v8l tie{}, bound{};
  for (int a = 0; a < 6; ++a) {
    const v8 v = K.val[a], dd = min2(K.dp[a], K.dm[a]);
    const v8l lane = keep[a] << (8 * a);
    tie |= le_bits(v, t2, lane);
    bound |= lane & ~(gt_bits(v, far, lane) & ge_bits(dd * dd, D_min2, lane) & le_bits(K.inv[a] * nn_min, 1.0, lane));
  }
  K.lane_bits = std::uint64_t(horizontal_or(tie));
  K.lane_bound_bits = std::uint64_t(horizontal_or(bound));
  return true;
}

}  // namespace

bool drop_lanes(SupersetLanes& K, double deg3, double D_min2, double nn_min, std::uint64_t unresolved) {
  return drop_lanes_body(K, deg3, D_min2, nn_min, unresolved);
}

void superset_kernel(const TetVertices& A, const TetVertices& B, SupersetLanes& K, EdgeLanes* full) {
  if (full)
    kernel_full(A, B, K, full);
  else
    kernel_rigid(A, B, K);
}

bool superset_kernel_scaled(const TetVertices& A, const TetVertices& B, SupersetLanes& K, int& e) {
  return kernel_rigid_scaling(A, B, K, &e);
}

void face_draft(const SupersetLanes& K, int f, Draft& d) {
  const int t = f < 4 ? 3 : 7;  // lane of the tetrahedron's det
  const int o = K.det[t] > 0 ? 1 : -1;
  const double det = std::fabs(K.det[t]);
  for (int m = 0; m < 4; ++m) d.hA[m] = d.hB[m] = 0.0;
  if (f < 4) {  // face_of_A: s = (−1)^f oA; hB_j = s N.(r_j − s_v0) = −H_j (sigma = −s)
    const double s = ((f & 1) ? -1.0 : 1.0) * o;
    for (int k = 0; k < 3; ++k) d.n[k] = s * K.NAB[k][f];
    d.hA[f] = -det;
    for (int j = 0; j < 4; ++j) d.hB[j] = -K.H[j][f];
    d.conA = mask_without(f);
    d.conB = 0;
  } else {  // face_of_B: s = −(−1)^j oB; hA_i = −s N.(r_v0 − s_i) = H_i
    const int j = f - 4;
    const double s = ((j & 1) ? 1.0 : -1.0) * o;
    for (int k = 0; k < 3; ++k) d.n[k] = s * K.NAB[k][f];
    d.hB[j] = det;
    for (int i = 0; i < 4; ++i) d.hA[i] = K.H[i][f];
    d.conA = 0;
    d.conB = mask_without(j);
  }
}

}  // namespace pdd::fast::detail
