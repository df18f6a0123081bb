// near_parallel_bound.cpp — the bound of near_parallel_bound.h (the proof is there).
#include "kernel/near_parallel_bound.h"

#include <array>
#include <cmath>
#include <limits>

#include "certification/double_word.h"
#include "exact/expansion.h"
#include "pdd/tet_tables.h"

namespace pdd::fast::detail {
namespace {

using P3 = std::array<double, 3>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kU = kUnitRoundoff;

P3 vertex(const SupersetLanes& K, int lane) { return {K.X[0][lane], K.X[1][lane], K.X[2][lane]}; }
P3 sub(const P3& p, const P3& q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
P3 cross(const P3& p, const P3& q) {
  return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}
double dot(const P3& p, const P3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
double max_abs(const P3& p) {
  const double x = std::fabs(p[0]), y = std::fabs(p[1]), z = std::fabs(p[2]);
  const double m = x > y ? x : y;
  return m > z ? m : z;  // (NaN: not <= E2, so never "unresolved"; the kernel rejects NaN pairs)
}

// A lower bound of S² = num² / |n|² from the computed num and n.n (header: "Errors"); NaN when
// the numerator is not certainly positive. Where n.n >= 2^80 E2² (|n| far above its error, the
// common case), without a square root: the exact |n| < sqrt(n.n)(1 + 2u) + √3 E2 <=
// sqrt(n.n)(1 + 2u + 1.6e-12), so |n|² < n.n (1 + 4e-12), and the computed
// (num − E3)² / (n.n (1 + 4e-12)) carries at most 6 roundings (each <= u, against the 8u taken).
// The relative slack 4e-12 is far inside the certificate's 9e-10 (value_bounds.h).
double depth2_lower(double num, double nn, const FilterBounds& fb) {
  if (!(num > fb.deg3)) return std::numeric_limits<double>::quiet_NaN();
  const double d = num - fb.deg3;
  if (nn >= 0x1p80 * (fb.deg2 * fb.deg2)) return d * d / (nn * (1.0 + 4e-12)) * (1.0 - 8.0 * kU);
  const double n_up = (std::sqrt(nn) + 1.7321 * fb.deg2) * (1.0 + 8.0 * kU);
  const double s = d / n_up * (1.0 - 4.0 * kU);
  return s * s * (1.0 - 2.0 * kU);
}

}  // namespace

std::uint64_t unresolved_edge_pairs(const SupersetLanes& K, const FilterBounds& fb) {
  // Screen on the kernel's 1/(n.n) (the same n): every |n_k| <= E2 gives n.n <= 3 E2² and, with
  // the roundings of n.n (3u) and of the division (u), inv >= 1/(3 E2² (1 + 4u)) > 0.33/E2².
  const double inv_min = 0.33 / (fb.deg2 * fb.deg2);
  std::uint64_t mask = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      if (!(K.inv[a][b] >= inv_min)) continue;
      const P3 eA = {K.EA[0][a], K.EA[1][a], K.EA[2][a]};
      const P3 eB = {K.EB[0][b], K.EB[1][b], K.EB[2][b]};
      if (max_abs(cross(eB, eA)) <= fb.deg2) mask |= std::uint64_t{1} << (8 * a + b);
    }
  return mask;
}

template <bool kPositiveOnly>
bool bound_of_pair(const SupersetLanes& K, const FilterBounds& fb, int a, int b, double& lo2) {
  const int u = kEdges[a][0], v = kEdges[a][1];
  const int x = kEdges[b][0];
  const P3 su = vertex(K, u), eA = sub(vertex(K, v), su), rx = vertex(K, 4 + x);
  const int offA[2] = {kOffEdge[a][0], kOffEdge[a][1]}, offB[2] = {kOffEdge[b][0], kOffEdge[b][1]};
  P3 dA[2];  // s_k − s_u for A's two other vertices
  for (int i = 0; i < 2; ++i) dA[i] = sub(vertex(K, offA[i]), su);

  // d_x, the only local minimum of S on the circle, certainly not in F.
  const P3 cp = cross(eA, sub(rx, su));
  bool outside = false;
  for (int i = 0; i < 2; ++i) outside = outside || dot(cp, cross(eA, dA[i])) > fb.deg4;
  for (int i = 0; i < 2; ++i)
    outside = outside || dot(cp, cross(eA, sub(vertex(K, 4 + offB[i]), rx))) < -fb.deg4;
  if (!outside) return false;

  double low = kInf;
  // The ends of arc(a): the outward normals of A's faces at edge a (the faces opposite A's two
  // other vertices), unless certainly violating a constraint (r_j certainly deeper than r_x).
  for (int i = 0; i < 2; ++i) {
    const int f = offA[i];
    const double hx = K.H[x][f];
    if (K.H[offB[0]][f] - hx > fb.deg3 || K.H[offB[1]][f] - hx > fb.deg3) continue;
    const double nn = K.NAB[0][f] * K.NAB[0][f] + K.NAB[1][f] * K.NAB[1][f] +
                      K.NAB[2][f] * K.NAB[2][f];
    if (kPositiveOnly) {
      if (!(hx > fb.deg3)) return false;
      continue;
    }
    const double s = depth2_lower(hx, nn, fb);
    if (!(s >= 0.0)) return false;
    low = s < low ? s : low;
  }
  // ±n' for the edges b' = (r_x, r_j) of B, j off edge b.
  for (int i = 0; i < 2; ++i) {
    const int j = offB[i], k = offB[1 - i];  // k: B's vertex off b and b'
    const int w = x < j ? x : j, z = x < j ? j : x;
    const P3 rw = vertex(K, 4 + w);
    const P3 n = cross(sub(vertex(K, 4 + z), rw), eA);
    if (max_abs(n) <= fb.deg2) return false;  // b' unresolved too (a sliver of B)
    const double g0 = dot(n, dA[0]), g1 = dot(n, dA[1]);
    const double h = dot(n, sub(rw, su)), q = dot(n, sub(vertex(K, 4 + k), rw));
    const double nn = dot(n, n);
    for (const double sign : {1.0, -1.0}) {
      if (sign * g0 > fb.deg3 || sign * g1 > fb.deg3) continue;  // certainly off arc(a)
      if (sign * q < -fb.deg3) continue;                          // r_k certainly below r_x
      if (kPositiveOnly) {
        if (!(-sign * h > fb.deg3)) return false;
        continue;
      }
      const double s = depth2_lower(-sign * h, nn, fb);
      if (!(s >= 0.0)) return false;
      low = s < low ? s : low;
    }
  }
  lo2 = low;
  return true;
}

// (p1 − p0) × (q1 − q0) exactly 0, shown in doubles (else false: not known): by structural
// zeros (header), else both vectors are computed exactly (two_sum's error of each coordinate
// difference is 0) and every component e_i f_j − e_j f_i is exactly 0, the two products equal
// as exact products (each as its rounded value and its error fma(x, y, −fl(x y)), the exact
// error of the product: equal pairs, equal products; exact when the factors are 0 or of
// magnitude >= 2^-400, so that no product or its error term underflows, checked). (Built with
// an fma clone, double_word.h: the error terms are one instruction each instead of Dekker's
// splits.)
PDD_FMA_CLONES bool cross_zero_in_doubles(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  if (cross_zero(p0, p1, q0, q1)) return true;
  double e[3], f[3];
  for (int k = 0; k < 3; ++k) {
    double err_e, err_f;
    two_sum(p1[k], -p0[k], e[k], err_e);
    two_sum(q1[k], -q0[k], f[k], err_f);
    if (err_e != 0.0 || err_f != 0.0) return false;
    if ((e[k] != 0.0 && !(std::fabs(e[k]) >= 0x1p-400)) || (f[k] != 0.0 && !(std::fabs(f[k]) >= 0x1p-400)))
      return false;
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if ((f[i] == 0.0 || e[j] == 0.0) && (f[j] == 0.0 || e[i] == 0.0)) continue;  // 0 − 0 (axis edges)
    const double p = f[i] * e[j], q = f[j] * e[i];
    if (p != q || std::fma(f[i], e[j], -p) != std::fma(f[j], e[i], -q)) return false;
  }
  return true;
}

// Parallel edges span no facet of A ⊕ (−B) (their sum is a segment): no orientation of the
// pair is a facet normal, so lo2 = +inf (header). Grids and copies of a mesh are full of them.
bool exactly_parallel(const SupersetLanes& K, int a, int b) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  return cross_zero_in_doubles(vertex(K, u), vertex(K, v), vertex(K, 4 + x), vertex(K, 4 + y));
}

bool near_parallel_bound(const SupersetLanes& K, const FilterBounds& fb, int a, int b, double& lo2) {
  if (exactly_parallel(K, a, b)) {
    lo2 = kInf;
    return true;
  }
  return bound_of_pair<false>(K, fb, a, b, lo2);
}

bool near_parallel_positive(const SupersetLanes& K, const FilterBounds& fb, int a, int b) {
  if (exactly_parallel(K, a, b)) return true;  // no facet normal: nothing to be positive
  double unused;
  return bound_of_pair<true>(K, fb, a, b, unused);
}

}  // namespace pdd::fast::detail
