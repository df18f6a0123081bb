// facet_bounds.cpp — see facet_bounds.h.
#include "global/facet_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "exact/expansion.h"
#include "exact/integer_heights.h"
#include "kernel/power_scale.h"

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

// sign(a - b), exactly: from approx_of's intervals where they are apart (distinct vertices'
// heights, most of them), else the exact difference's sign.
int compare(const Expansion& a, const Expansion& b) {
  const detail::Approx x = approx_of(a), y = approx_of(b);
  // (each interval widened by 4u of its magnitude: the roundings of v -+ err themselves)
  const double ex = x.err + 4 * kU * std::fabs(x.v), ey = y.err + 4 * kU * std::fabs(y.v);
  if (x.v - ex > y.v + ey) return 1;
  if (x.v + ex < y.v - ey) return -1;
  return detail::difference(a, b).sign();
}

// The largest (or least) of four exact heights, compared exactly.
const Expansion& extreme(const Expansion (&h)[4], bool largest) {
  int at = 0;
  for (int i = 1; i < 4; ++i) {
    const int s = compare(h[i], h[at]);
    if (largest ? s > 0 : s < 0) at = i;
  }
  return h[at];
}

// The vertices relative to A[0] in doubles, w_i = x_i - a_0 rounded (A's 0..3, B's 4..7): each
// component within u |w~_ik| of its exact value (round to nearest; a subnormal difference is
// exact). big[k]: the largest |w_ik| over the eight vertices.
struct Offsets {
  double w[8][3], big[3] = {0, 0, 0};
  Offsets(const TetVertices& A, const TetVertices& B) {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) w[i][k] = A[i][k] - A[0][k], w[4 + i][k] = B[i][k] - A[0][k];
    for (const auto& x : w)
      for (int k = 0; k < 3; ++k) big[k] = std::max(big[k], std::fabs(x[k]));
  }
};

// D(n) and D(-n) bounded below in doubles, for a direction whose exact n is known within err[k]
// of n~ componentwise; false (out's overlaps untouched) where the bound's slack t exceeds 2^-42
// of the computed overlap, which the exact heights then decide (a contact's own normal: an
// overlap far below |n| |w|). Taken, each bound lies within 2^-41 of the exact overlap (the
// exact arithmetic's are within a few u: facet_bounds.h's "within 1e-12" holds for both).
// Error. h_i = n.w_i exactly, h~_i the computed n~.w~_i. |n~.w~ - n.w| <= sum_k (err_k + |n~_k|
// u (1 + ...)) |w~_k| (n's error, then w's rounding); the dot's own roundings add gamma_3
// sum |n~_k w~_k| (gamma_3 <= 3u (1 + 3u)) and, where a product underflows, 2^-1075 each. So
// |h~_i - h_i| <= sum_k (err_k + 4u |n~_k|) |w~_k| (1 + 3u) + 2^-1072 <= the same sum over
// big_k = max_i |w~_ik| (one bound E for all eight heights); its computed sum of positive terms
// is within 7u below the exact one, and E = s~ (1 + 2^-40) + 2^-1060 covers both. Then D(n) =
// max_A h - min_B h >= (max_A h~ - min_B h~) - 2E, the maximum's and minimum's errors bounded by
// E whichever vertex attains them; the computed difference d~ is within u |d~| of it (1.0001u:
// covered below). t = (2E + 2u |d~|) (1 + 2^-40) then gives D(n) >= d~ - t, and
// fl(fl(d~ - t) (1 - 4u)) lies below d~ - t whenever d~ - t > 0 (two roundings of at most u
// each). Overflow or NaN fails the comparisons: false.
// Why: the exact heights cost ~1.1k instructions a direction over an integer frame and ~10k by
// expansions; the 8 double heights ~60. Only the few directions near the contact's own normal
// need the exact ones.
bool overlaps_in_doubles(const V3& n, const double (&err)[3], const Offsets& o, DirectionBounds& out) {
  double h[8], s = 0;
  for (int i = 0; i < 8; ++i) h[i] = n[0] * o.w[i][0] + n[1] * o.w[i][1] + n[2] * o.w[i][2];
  for (int k = 0; k < 3; ++k) s += (err[k] + 4 * kU * std::fabs(n[k])) * o.big[k];
  const double E = s * (1 + 0x1p-40) + 0x1p-1060;
  const double amax = std::max({h[0], h[1], h[2], h[3]}), amin = std::min({h[0], h[1], h[2], h[3]});
  const double bmax = std::max({h[4], h[5], h[6], h[7]}), bmin = std::min({h[4], h[5], h[6], h[7]});
  const double plus = amax - bmin, minus = bmax - amin;
  const double tp = (2 * E + 2 * kU * std::fabs(plus)) * (1 + 0x1p-40);
  const double tm = (2 * E + 2 * kU * std::fabs(minus)) * (1 + 0x1p-40);
  if (!(tp <= 0x1p-42 * plus) || !(tm <= 0x1p-42 * minus) || !(plus < INFINITY) || !(minus < INFINITY))
    return false;
  out.plus_low = (plus - tp) * (1 - 4 * kU);
  out.minus_low = (minus - tm) * (1 - 4 * kU);
  return true;
}

// false when an expansion overflowed its capacity or an overlap is not certainly positive.
bool direction_bounds(const ExpVec& n, const ExpVec (&xa)[4], const ExpVec (&xb)[4], const Offsets& w,
                      DirectionBounds& out) {
  if (!n.ok()) return false;
  out.zero = n.is_zero();
  if (out.zero) return true;
  ExpVec c;  // n with each component compressed: shorter products below
  for (int k = 0; k < 3; ++k) c.x[k] = detail::compressed(n.x[k]);
  double nn = 0, err[3];
  for (int k = 0; k < 3; ++k) {
    const detail::Approx a = approx_of(c.x[k]);
    out.n[k] = a.v;
    err[k] = a.err;
    const double m = (std::fabs(a.v) + a.err) * (1 + 4 * kU);
    nn += m * m;
  }
  out.nn_up = nn * (1 + 8 * kU);  // the squares' and sums' roundings, upward
  if (overlaps_in_doubles(out.n, err, w, out)) return true;
  Expansion ha[4], hb[4];
  for (int i = 0; i < 4; ++i) {
    ha[i] = detail::compressed(detail::dot(c, xa[i]));
    hb[i] = detail::compressed(detail::dot(c, xb[i]));
    if (!ha[i].ok || !hb[i].ok) return false;
  }
  const Expansion plus = detail::difference(extreme(ha, true), extreme(hb, false));   // D(n)
  const Expansion minus = detail::difference(extreme(hb, true), extreme(ha, false));  // D(-n)
  if (!plus.ok || !minus.ok) return false;
  out.plus_low = lower_of(detail::compressed(plus));
  out.minus_low = lower_of(detail::compressed(minus));
  return out.plus_low > 0 && out.minus_low > 0;
}

// The 44 candidate facet normals of M (SPEC §3's directions): A's and B's face normals (the
// cross product of two edges from one vertex: edges 0-1 and 0-2 for face 012, and so on; any two
// edges of a face span its plane) and the 36 cross products of an edge of A and an edge of B.
// Every facet normal of M is among them (up to orientation: both are bounded).
// Over the pair's integer frame (integer_heights.h: every coordinate X 2^e, |X| < 2^60, the
// normal's components exact in __int128, each height difference n.(p - q) exact in a wide
// integer): the same bounds as direction_bounds' expansions at a tenth of their cost. The extreme
// vertices along n are found by exact signs; D(n) = n.(a_max - b_min) and D(-n) = n.(b_max -
// a_min), each one exact wide integer rounded down (wide_lower); n's components rounded to
// nearest (within u, inside the 4u DirectionBounds promises). Units: n in 2^(2e), D in 2^(3e),
// n.n in 2^(4e), as a double product n.x is. False where a value would leave the normal range.
constexpr double kFramedFloor = 0x1p-900;  // (the smallest scaled value taken: no underflow)

// A lower bound of w = hi 2^64 + lo (lo in [0, 2^64)) times 2^s: hi converted within u |hi|,
// lo within 2^11 (a double below 2^64 has an ulp <= 2^12), the sum within u of itself, so
// |v - w| <= 2u |w| + 2^13 <= 2.1u |v| + 2^13; 8u |v| + 2^14 is taken, the two roundings of
// this line covered by the factor (1 - 4u). NaN-free: |hi| < 2^122.
double wide_lower(const detail::IntegerFrame::Wide& w, int s) {
  const double v = double(w.hi) * 0x1p64 + double(w.lo);  // (the product exact: |hi| < 2^122)
  const double low = (v - (8 * kU * std::fabs(v) + 0x1p14)) * (1 - 4 * kU);
  if (!(low > 0)) return low;
  const double scaled = detail::times_pow2(low, s);
  return scaled >= kFramedFloor ? scaled : 0.0;  // (0: not certainly positive, declined)
}

using Wide = detail::IntegerFrame::Wide;
bool less(const Wide& a, const Wide& b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }
// a - b exactly (|a|, |b| < 2^186: the difference's high part below 2^123)
Wide minus(const Wide& a, const Wide& b) { return Wide{a.hi - b.hi - (a.lo < b.lo ? 1 : 0), a.lo - b.lo}; }

bool direction_bounds_framed(const detail::IntegerFrame& f, const __int128 (&m)[3], const Offsets& w,
                             DirectionBounds& out) {
  out.zero = m[0] == 0 && m[1] == 0 && m[2] == 0;
  if (out.zero) return true;
  const int e = f.unit_exponent();
  double nn = 0, err[3];
  for (int k = 0; k < 3; ++k) {
    out.n[k] = detail::times_pow2(double(m[k]), 2 * e);
    if (out.n[k] != 0 && !(std::fabs(out.n[k]) >= kFramedFloor)) return false;
    err[k] = 2 * kU * std::fabs(out.n[k]);  // (rounded to nearest, then scaled exactly: <= u |n~|)
    const double a = std::fabs(out.n[k]) * (1 + 2 * kU);
    nn += a * a;
  }
  out.nn_up = nn * (1 + 8 * kU);  // the squares' and sums' roundings, upward
  if (overlaps_in_doubles(out.n, err, w, out) && out.plus_low >= kFramedFloor && out.minus_low >= kFramedFloor)
    return true;
  Wide h[8];  // n.(x_i - x_0), exactly (A's vertices 0..3, B's 4..7)
  for (int i = 0; i < 8; ++i) h[i] = f.dot(m, i, 0);
  int amax = 0, amin = 0, bmax = 4, bmin = 4;
  for (int i = 1; i < 4; ++i) {
    if (less(h[amax], h[i])) amax = i;
    if (less(h[i], h[amin])) amin = i;
    if (less(h[bmax], h[4 + i])) bmax = 4 + i;
    if (less(h[4 + i], h[bmin])) bmin = 4 + i;
  }
  out.plus_low = wide_lower(minus(h[amax], h[bmin]), 3 * e);
  out.minus_low = wide_lower(minus(h[bmax], h[amin]), 3 * e);
  return out.plus_low > 0 && out.minus_low > 0;
}

// candidate_bounds over the frame (the same 44 directions in the same order).
bool candidate_bounds_framed(const detail::IntegerFrame& f, DirectionBounds (&out)[kDirections]) {
  const Offsets w(f.a(), f.b());
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  static constexpr int kFaceEdges[4][2] = {{0, 1}, {0, 2}, {1, 2}, {3, 4}};  // faces 012, 013, 023, 123
  __int128 m[3];
  int k = 0;
  for (const auto& fe : kFaceEdges)
    for (const int t : {0, 4}) {  // A's face, then B's
      const auto &e0 = kEdge[fe[0]], &e1 = kEdge[fe[1]];
      f.normal(t + e0[1], t + e0[0], t + e1[1], t + e1[0], m);
      if (!direction_bounds_framed(f, m, w, out[k++])) return false;
    }
  for (const auto& a : kEdge)
    for (const auto& b : kEdge) {
      f.normal(a[1], a[0], 4 + b[1], 4 + b[0], m);
      if (!direction_bounds_framed(f, m, w, out[k++])) return false;
    }
  return true;
}

bool candidate_bounds(const TetVertices& A, const TetVertices& B, DirectionBounds (&out)[kDirections]) {
  if (!detail::in_exact_range(A, B)) return false;
  const Offsets w(A, B);
  ExpVec xa[4], xb[4];  // the vertices relative to A[0], exactly
  for (int i = 0; i < 4; ++i) xa[i] = detail::difference(A[i], A[0]), xb[i] = detail::difference(B[i], A[0]);
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  ExpVec ea[6], eb[6];
  for (int e = 0; e < 6; ++e) {
    ea[e] = detail::difference(A[kEdge[e][1]], A[kEdge[e][0]]);
    eb[e] = detail::difference(B[kEdge[e][1]], B[kEdge[e][0]]);
  }
  static constexpr int kFaceEdges[4][2] = {{0, 1}, {0, 2}, {1, 2}, {3, 4}};  // faces 012, 013, 023, 123
  int k = 0;
  for (const auto& f : kFaceEdges) {
    if (!direction_bounds(detail::cross(ea[f[0]], ea[f[1]]), xa, xb, w, out[k++])) return false;
    if (!direction_bounds(detail::cross(eb[f[0]], eb[f[1]]), xa, xb, w, out[k++])) return false;
  }
  for (const ExpVec& a : ea)
    for (const ExpVec& b : eb)
      if (!direction_bounds(detail::cross(a, b), xa, xb, w, out[k++])) return false;
  return true;
}

}  // namespace

bool FacetBounds::get() {
  if (state_ != 0) return state_ > 0;
  if (arithmetic_ == FacetArithmetic::IntegersWhereExact) {
    detail::IntegerFrame frame(A_, B_);
    by_integers_ = frame.usable() && candidate_bounds_framed(frame, dirs_);
  }
  state_ = by_integers_ || candidate_bounds(A_, B_, dirs_) ? 1 : -1;
  return state_ > 0;
}

bool pd2_lower(FacetBounds& bounds, double& pd2_low) {
  if (!bounds.get()) return false;
  double low = INFINITY;
  for (const DirectionBounds& d : bounds.dirs()) {
    if (d.zero) continue;
    const double m = std::min(d.plus_low, d.minus_low);
    low = std::min(low, m * m / d.nn_up * (1 - 8 * kU));
  }
  if (!(low > 0) || !std::isfinite(low)) return false;
  pd2_low = low;
  return true;
}

bool rigid_depth_squared_lower(const TetVertices& A, const TetVertices& B, double& pd2_low) {
  FacetBounds bounds(A, B);
  return pd2_lower(bounds, pd2_low);
}

namespace {

// Every unit u has u.d >= c0 or D(u) >= d0: the polytope W' = {u : D(u) <= d0, u.d <= c0} lies
// inside the open unit ball. W = {u : D(u) <= d0} is the convex hull of the points d0 n / D(n)
// over M's facet normals n, each orientation (D is M's support function; each such point lies on
// W's boundary, the facets' are its vertices, and every facet normal is a candidate), so every
// vertex of W' is one of those points with p.d <= c0 or the crossing of the plane u.d = c0 with a
// segment from such a point to one beyond it, and |u| is convex: W' lies inside the ball iff those
// do. A crossing lies on its segment, so where both ends pass it does too (|u|^2 convex): only
// the segments to a point beyond the plane and outside the ball are crossed (the few near the
// cap's rim; 88 x 88 segments otherwise). The points are taken with D's lower bound (each moved
// outward along its ray: a larger polytope, the test only stricter) and n rounded (each
// component within 4u of its exact direction's: every point of W within 8u |p| of the computed
// hull, and a point that passes has |p| < 1: ~1e-15, far inside the margin kInside leaves).
// Which side of the plane a point lies on is decided with a tolerance covering p.d's error
// (the direction's rounding, 4u sum |p_k d_k|, the scale's and the dot product's, 4u more: 16u
// taken), a point near the plane taken on both sides; a crossing's t is bounded by an interval
// from its numerator's and denominator's errors, and |p(t)|^2, convex in t, is checked at both
// ends (a crossing lies within ~8u (|v| + t |w|) <= 8u (1 + 2 |p|) of its computed place).
constexpr double kInside = 1 - 0x1p-36;  // |p|^2 <= this (margin ~1.5e-11 >> the roundings)

}  // namespace

namespace {

// The points d0 n / D(n) of M's candidate directions, each orientation, each point once (in the
// order of the directions, first occurrences kept): directions along one line give one point
// (D is M's support function, so d0 n / D(n) does not depend on n's length), and on meshes
// whose faces are parallel (blocks resting on blocks) they repeat: 25 distinct of 81 on the
// resting five-tetrahedra blocks, none repeated on a generic pair. Equal as doubles (+0 and -0
// alike), found through a table of 256 slots on their bits. Returns the count.
int facet_points(const FacetBounds& bounds, double d0, V3 (&pts)[2 * kDirections]) {
  constexpr unsigned kSlots = 256;  // (> 2 * 88: a slot is free within a few probes)
  int slot[kSlots];
  std::fill(slot, slot + kSlots, -1);
  int n = 0;
  auto add = [&](const V3& p) {
    std::uint64_t h = 0;
    for (const double c : p) {
      const double z = c + 0.0;  // (-0 as +0: they compare equal)
      std::uint64_t b;
      std::memcpy(&b, &z, sizeof b);
      h = (h ^ b) * 0x9E3779B97F4A7C15ull;
    }
    for (unsigned k = unsigned(h >> 56);; k = (k + 1) % kSlots) {
      if (slot[k] < 0) {
        slot[k] = n, pts[n++] = p;
        return;
      }
      if (pts[slot[k]] == p) return;
    }
  };
  for (const DirectionBounds& x : bounds.dirs()) {
    if (x.zero) continue;
    add(mul(x.n, d0 / x.plus_low));
    add(mul(x.n, -(d0 / x.minus_low)));
  }
  return n;
}

}  // namespace

bool polytope_inside_ball(FacetBounds& bounds, const V3& d, double c0, double d0) {
  if (!bounds.get()) return false;
  V3 pts[2 * kDirections];
  const int n = facet_points(bounds, d0, pts);
  auto side_error = [&](const V3& p) {  // |fl(p.d) - p_exact.d| bound, and c0's own rounding
    return 16 * kU * (std::fabs(p[0] * d[0]) + std::fabs(p[1] * d[1]) + std::fabs(p[2] * d[2]) + c0);
  };
  auto inside = [](const V3& p) { return dot(p, p) <= kInside; };
  double side[2 * kDirections], err[2 * kDirections];
  int outer[2 * kDirections], m = 0;  // the points beyond the plane (possibly) and outside the ball
  for (int j = 0; j < n; ++j) {
    side[j] = dot(pts[j], d), err[j] = side_error(pts[j]);
    if (side[j] > c0 - err[j] && !inside(pts[j])) outer[m++] = j;
  }
  for (int i = 0; i < n; ++i) {
    const double vi = side[i], ei = err[i];
    if (!(vi <= c0 + ei)) continue;  // (beyond the plane for certain)
    if (!inside(pts[i])) return false;
    for (int k = 0; k < m; ++k) {
      const int j = outer[k];
      const double vj = side[j], ej = err[j];
      const double num = c0 - vi, den = vj - vi, e = ei + ej;
      double lo = 0, hi = 1;
      if (den - e > 0) lo = std::max(0.0, (num - e) / (den + e) * (1 - 4 * kU)),
                       hi = std::min(1.0, (num + e) / (den - e) * (1 + 4 * kU));
      for (const double t : {lo, hi})
        if (!inside(add(pts[i], mul(sub(pts[j], pts[i]), t)))) return false;
    }
  }
  return true;
}

}  // namespace pdd::fast::global

namespace pdd::fast::global {

namespace {

// A point of the clipped polytope's superset, with a bound on its distance from the point it
// stands for (its roundings), and an upper bound on its length.
struct Loose {
  V3 p;
  double r, len;
};
Loose loose(const V3& p, double r) { return {p, r, norm(p) * (1 + 4 * kU)}; }

// |x| + r < sqrt(kInside) / (1 + 4u) (the one plane's test, |x| rounded up), without the square
// root: s_in = sqrt(kInside) (1 - 6u) is below that bound whatever its rounding, and
// fl(x.x) (1 + 4u) >= |x|^2 covers the dot's three roundings and the product's.
const double kSqrtInside = std::sqrt(kInside) * (1 - 6 * kU);
constexpr double kMaxCrossings = 1 << 20;  // (polytope_inside_ball's last plane's crossings)
constexpr double kMaxPoints = 1 << 16;     // (the points a clip keeps: a few thousand where it answers)
// The widening all clips together may leave (drop_inner_cuts): half the margin kInside leaves
// |p| (2^-37), ~30 times the cuts' own bounds on a unit polytope after two clips; shared
// equally among the clips still to come.
constexpr double kSlack = 0x1p-38;
bool inside_at(double xx, double r) {
  const double room = kSqrtInside - r;
  return room > 0 && xx * (1 + 4 * kU) <= room * room * (1 - 4 * kU);
}

// The crossing of the plane u.d = c on the segment from a (value va, error ea; in the plane's
// half-space) to b (vb, eb; beyond it): its parameter t in [lo, hi] (the one plane's
// interval), both ends inside the ball; and, for a later plane, the two ends as points (the
// crossing between them), each within a.r + b.r + 8u (|a| + |w|) <= 8u (2 |a| + |b|) of its
// exact place (w = b - a).
struct Crossing {
  double lo, hi, r;
};
Crossing crossing(const Loose& a, double va, double ea, const Loose& b, double vb, double eb, double c) {
  const double num = c - va, den = vb - va, e = ea + eb;
  Crossing x{0, 1, (a.r + b.r + 8 * kU * (2 * a.len + b.len)) * (1 + 4 * kU)};
  if (den - e > 0) x.lo = std::max(0.0, (num - e) / (den + e) * (1 - 4 * kU)),
                   x.hi = std::min(1.0, (num + e) / (den - e) * (1 + 4 * kU));
  return x;
}
V3 at(const Loose& a, const Loose& b, double t) { return add(a.p, mul(sub(b.p, a.p), t)); }

// The crossings `cuts` of one clip, less those that lie within `budget` of the hull of the
// others; returns a bound on the largest distance dropped (0: none). Each cut stands for a point
// within its bound r (polytope_inside_ball below). A cut q is dropped when a combination y =
// sum w_i k_i of one to three kept cuts, w_i >= 0 as computed, lies near it: q's point lies
// within r_q + max r_i + |y - q| + 3u sum w_i |k_i| of the combination of the kept cuts' points
// with weights w_i / sum w_i (a convex one: the computed weights sum to 1 within 3u), so the
// hull of the kept points, widened by that, holds it (the caller carries the widening). y - q
// and its length are computed within 5u (|q| + sum w_i |k_i|) (three products and sums, a
// difference), the square root's and the bound's own roundings within the last 8u: with the 3u
// above, 15u (|q| + sum w_i |k_i|) taken (|x| <= len, x's bound on its length). How the
// weights are found needs no bound (any weights in the simplex give a valid one): from the
// images L(x) = (x.e1, x.e2) in a basis of the plane, along the two cuts at the ends of the
// first coordinate (a thin section: nearly a segment), else in a triangle of the fan over the
// images' convex hull (Andrew's monotone chain), clamped to the simplex. (A clip keeps every
// segment's crossing, n_in x n_beyond, most of them inside the hull: on contacts made by
// rounding ~300 points after a second plane and ~8000 after a third, nearly all on a segment
// ~1e-16 thick.) Written by hand: the points carry their own bounds, which no hull library
// takes.
double drop_inner_cuts(std::vector<Loose>& cuts, const V3& d, double budget) {
  if (cuts.size() < 8 || !(budget > 0)) return 0;
  const int a = std::fabs(d[0]) <= std::fabs(d[1]) && std::fabs(d[0]) <= std::fabs(d[2]) ? 0
                : std::fabs(d[1]) <= std::fabs(d[2])                                     ? 1
                                                                                         : 2;
  V3 axis{0, 0, 0};
  axis[a] = 1;
  const V3 c1 = cross(d, axis);
  const V3 e1 = mul(c1, 1 / norm(c1)), e2 = cross(mul(d, 1 / norm(d)), e1);
  const std::size_t n = cuts.size();
  struct Image {
    double x, y;
    std::size_t i;
  };
  static thread_local std::vector<Image> img;
  static thread_local std::vector<std::size_t> hull;
  static thread_local std::vector<char> keep;
  img.resize(n);
  for (std::size_t i = 0; i < n; ++i) img[i] = {dot(cuts[i].p, e1), dot(cuts[i].p, e2), i};
  if (!std::all_of(img.begin(), img.end(), [](const Image& p) { return std::isfinite(p.x) && std::isfinite(p.y); }))
    return 0;
  auto orient = [](const Image& p, const Image& q, const Image& s) {
    return (q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x);
  };
  std::sort(img.begin(), img.end(),
            [](const Image& p, const Image& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
  hull.clear();
  for (int pass = 0; pass < 2; ++pass) {  // lower chain left to right, then upper right to left
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = pass == 0 ? k : n - 1 - k;
      while (hull.size() >= base + 2 && !(orient(img[hull[hull.size() - 2]], img[hull.back()], img[i]) > 0))
        hull.pop_back();
      hull.push_back(i);
    }
    hull.pop_back();  // (each chain's last point starts the other)
  }
  keep.assign(n, 0);
  for (const std::size_t h : hull) keep[img[h].i] = 1;
  keep[img[0].i] = keep[img[n - 1].i] = 1;
  // the distance bound of q from the combination of kept cuts k[0..m) with weights l (clamped)
  auto distance = [&](const Loose& q, const std::size_t* k, double* l, int m) {
    double sum = 0;
    for (int j = 0; j < m; ++j) sum += (l[j] = std::clamp(l[j], 0.0, 1.0));
    if (!(sum > 0)) return double(INFINITY);
    V3 y{0, 0, 0};
    double mag = q.len, r = 0;
    for (int j = 0; j < m; ++j) {
      const Loose& x = cuts[k[j]];
      y = add(y, mul(x.p, l[j] / sum));
      mag += x.len * (l[j] / sum) * (1 + 4 * kU), r = std::max(r, x.r);
    }
    return (q.r + r + norm(sub(q.p, y)) + 15 * kU * mag) * (1 + 8 * kU);
  };
  const Image &far0 = img[0], &far1 = img[n - 1];  // (the ends of the first coordinate)
  const double fx = far1.x - far0.x, fy = far1.y - far0.y, ff = fx * fx + fy * fy;
  double dropped = 0;
  for (std::size_t s = 0; s < n; ++s) {
    const Image& q = img[s];
    if (keep[q.i]) continue;
    double best = INFINITY;
    if (ff > 0) {  // along the two ends
      const std::size_t k[2] = {far0.i, far1.i};
      const double t = ((q.x - far0.x) * fx + (q.y - far0.y) * fy) / ff;
      double l[2] = {1 - t, t};
      best = distance(cuts[q.i], k, l, 2);
    }
    for (std::size_t h = 1; h + 1 < hull.size() && !(best <= budget); ++h) {  // in a triangle of the fan
      const Image &p0 = img[hull[0]], &p1 = img[hull[h]], &p2 = img[hull[h + 1]];
      const double area = orient(p0, p1, p2);
      if (!(area > 0)) continue;
      double l[3] = {orient(q, p1, p2) / area, orient(p0, q, p2) / area, orient(p0, p1, q) / area};
      if (!(l[0] >= -1e-9 && l[1] >= -1e-9 && l[2] >= -1e-9)) continue;
      const std::size_t k[3] = {p0.i, p1.i, p2.i};
      best = std::min(best, distance(cuts[q.i], k, l, 3));
    }
    if (best <= budget) dropped = std::max(dropped, best);
    else keep[q.i] = 1;
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) cuts[kept++] = cuts[i];
  cuts.resize(kept);
  return dropped;
}

}  // namespace

// polytope_inside_ball with k planes: W_k = W ∩ {u.d_1 <= c_1} ∩ .. ∩ {u.d_k <= c_k} inside the
// open unit ball. conv(P) ∩ H = conv(P ∩ H, the crossings of the plane with the segments from a
// point of P in H to one beyond it), and any larger set of points of W spans a polytope that
// holds it: so S_1 (every point of S_0 = P not beyond H_1 for certain, and each crossing of a
// segment from one of those to one beyond for certain; a point near the plane is kept, which
// spans its segments' crossings with the others kept) spans a superset of W ∩ H_1 inside W, S_2
// one of W ∩ H_1 ∩ H_2 from S_1 the same way, and so on to S_(k-1); W_k lies inside the ball if
// the points of S_(k-1) in H_k do and the crossings of the last plane on the segments from those
// to the points of S_(k-1) beyond it do: where both ends of a segment are inside, its crossing is
// (|u|^2 convex), so only the segments to a point outside the ball are crossed, as in the one
// plane's test. A crossing of a clip is one point, the middle of its parameter's interval (its
// distance from the crossing in its bound) where the interval is narrow, else the interval's two
// ends, between which it lies (a segment nearly along the plane). Each point carries a bound r on
// its distance from the point it stands for (P's points: their direction's rounding, 8u |p|; a
// crossing: its ends' bounds and its own roundings), which widens every side test by r |d| and
// every ball test to |p| + r. P's points within 2^-20 of 0 (directions far deeper than d0: most
// of them on a shallow contact) are replaced by the corners of the cube [-2^-20, 2^-20]^3, which
// holds them. Each clip's crossings are thinned (drop_inner_cuts): those within a small distance
// of the hull of the others are dropped, and W_t then lies within rho (their distances summed
// over the clips, at most kSlack) of the hull of S_t's points; each later plane is moved out by
// rho |d| and each ball test takes |p| + r + rho (polytope_inside_ball's own comments say why).
// (An edge resting on a collinear edge, two planes: ~450 points in S_1, ~30 of them outside the
// ball and beyond the second plane. Caps about tied minimisers: a cap is ~1e-5 rad wide and few
// points lie beyond it: ~20 points, ~80 after an edge pair's plane, ~1500 after a cap more
// without the thinning, ~15 with it.)
bool polytope_inside_ball(FacetBounds& bounds, const Halfspace* planes, int k, double d0) {
  if (!bounds.get() || k < 1) return false;
  // p.d against c: the value and its error (the direction's rounding and the dot's, 16u, as
  // the one plane's test; the point's own bound r |d|)
  auto side = [](const Loose& x, const V3& d, double nd, double c, double& err) {
    err = 16 * kU * (std::fabs(x.p[0] * d[0]) + std::fabs(x.p[1] * d[1]) + std::fabs(x.p[2] * d[2]) + c) +
          x.r * nd;
    return dot(x.p, d);
  };
  static thread_local std::vector<Loose> s, next, cuts;
  static thread_local std::vector<double> v, e;
  static thread_local std::vector<std::size_t> outer, beyond;
  s.clear();
  V3 pts[2 * kDirections];
  const int n = facet_points(bounds, d0, pts);
  for (int i = 0; i < n; ++i) s.push_back(loose(pts[i], 8 * kU * norm(pts[i])));
  // The points within 2^-20 of 0 (with their bounds: the directions far deeper than d0, most
  // of them on a shallow contact, ~1e-8 from 0 on one 1e-9 deep) lie in the box [lo, lo + w]^3
  // (lo_k the least p_k - r over them, w the widest extent, each rounded outward), and so in
  // the simplex lo, lo + 3w e_k (k = 1..3; a point x of the box has sum (x_k - lo_k) <= 3w):
  // its four corners stand for them (each computed within 8u (|lo| + 3w) of its exact place,
  // its bound), a larger hull with fewer points: each plane's crossings from them number four
  // per point beyond it.
  constexpr double kNear = 0x1p-20;
  auto near = [&](const Loose& x) { return x.len + x.r <= kNear; };
  if (std::count_if(s.begin(), s.end(), near) > 4) {
    V3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const Loose& x : s)
      if (near(x))
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], x.p[c] - x.r), hi[c] = std::max(hi[c], x.p[c] + x.r);
    double w = 0;
    for (int c = 0; c < 3; ++c) {
      lo[c] -= 4 * kU * std::fabs(lo[c]), hi[c] += 4 * kU * std::fabs(hi[c]);
      w = std::max(w, (hi[c] - lo[c]) * (1 + 4 * kU));
    }
    const double r = 8 * kU * (norm(lo) + 3 * w);
    s.erase(std::remove_if(s.begin(), s.end(), near), s.end());
    s.push_back(loose(lo, r));
    for (int c = 0; c < 3; ++c) {
      V3 v = lo;
      v[c] += 3 * w;
      s.push_back(loose(v, r));
    }
  }
  // rho: the widening the dropped cuts leave (drop_inner_cuts): W_t lies within rho of the hull
  // of S_t's points, so W_t's part in {u.d <= c} lies within rho of that hull's part in
  // {u.d <= c + rho |d|} (a point x = y + z, |z| <= rho, x.d <= c has y.d <= c + rho |d|): each
  // later plane is taken that much further out, and every ball test that much stricter.
  double rho = 0;
  auto widened = [&rho](double c, double nd) {  // >= c + rho nd, each rounding covered
    const double w = rho * nd * (1 + 4 * kU);
    return (c + w) + 4 * kU * (std::fabs(c) + w);
  };
  for (int t = 0; t + 1 < k; ++t) {  // S_(t+1) from S_t
    const V3& d = planes[t].d;
    const double nd = norm(d) * (1 + 4 * kU), c = rho > 0 ? widened(planes[t].c, nd) : planes[t].c;
    const std::size_t n = s.size();
    v.resize(n), e.resize(n), beyond.clear();
    for (std::size_t j = 0; j < n; ++j) {
      v[j] = side(s[j], d, nd, c, e[j]);
      if (!(v[j] <= c + e[j])) beyond.push_back(j);  // (beyond the plane for certain)
    }
    next.clear(), cuts.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (!(v[i] <= c + e[i])) continue;
      next.push_back(s[i]);  // (in the half-space, or near its plane: kept either way)
      // The crossings of the segments to the points beyond for certain (a point kept already
      // spans its segments' crossings with the others kept): where the parameter's interval is
      // narrow, one point, its middle, whose distance from the crossing |w| ((hi - lo) / 2 +
      // 2u) is added to the bound (|w| <= |a| + |b|); else its two ends, between which the
      // crossing lies (a segment nearly along the plane: two points near a cap's rim). The
      // crossings are then thinned (drop_inner_cuts).
      if (double(next.size() + cuts.size()) + 2 * double(beyond.size()) > kMaxPoints) return false;
      for (const std::size_t j : beyond) {
        const Crossing x = crossing(s[i], v[i], e[i], s[j], v[j], e[j], c);
        if (x.hi - x.lo <= 0x1p-40) {
          const double half = (s[i].len + s[j].len) * ((x.hi - x.lo) * 0.5 + 2 * kU) * (1 + 4 * kU);
          cuts.push_back(loose(at(s[i], s[j], 0.5 * (x.lo + x.hi)), (x.r + half) * (1 + 2 * kU)));
        } else {
          cuts.push_back(loose(at(s[i], s[j], x.lo), x.r));
          cuts.push_back(loose(at(s[i], s[j], x.hi), x.r));
        }
      }
    }
    rho = (rho + drop_inner_cuts(cuts, d, (kSlack - rho) / (k - 1 - t))) * (1 + 2 * kU);
    next.insert(next.end(), cuts.begin(), cuts.end());
    s.swap(next);
  }
  const V3& d = planes[k - 1].d;
  const double nd = norm(d) * (1 + 4 * kU), c = rho > 0 ? widened(planes[k - 1].c, nd) : planes[k - 1].c;
  const std::size_t m = s.size();
  v.resize(m), e.resize(m), outer.clear();
  for (std::size_t j = 0; j < m; ++j) {
    v[j] = side(s[j], d, nd, c, e[j]);
    if (v[j] > c - e[j] && !inside_at(dot(s[j].p, s[j].p), s[j].r + rho)) outer.push_back(j);
  }
  // (where the crossings would number more than kMaxCrossings, not shown, rather than seconds
  // on one pair; the contacts it is for have ~10^4)
  if (double(m) * double(outer.size()) > kMaxCrossings) return false;
  for (std::size_t i = 0; i < m; ++i) {
    if (!(v[i] <= c + e[i])) continue;
    const Loose& a = s[i];
    if (!inside_at(dot(a.p, a.p), a.r + rho)) return false;
    for (const std::size_t j : outer) {
      const Loose& b = s[j];
      const Crossing x = crossing(a, v[i], e[i], b, v[j], e[j], c);
      const V3 lo = at(a, b, x.lo), hi = at(a, b, x.hi);
      if (!inside_at(dot(lo, lo), x.r + rho) || !inside_at(dot(hi, hi), x.r + rho)) return false;
    }
  }
  return true;
}

unsigned vertices_off_the_contact(FacetBounds& bounds, const TetVertices& A, const TetVertices& B, double d0,
                                  double gamma) {
  if (!bounds.get() || !(gamma > 0) || !std::isfinite(gamma)) return 0;
  unsigned off = 0;
  for (int side = 0; side < 2; ++side) {
    const TetVertices& T = side == 0 ? A : B;
    for (int x = 0; x < 4; ++x) {
      Halfspace planes[3];
      int k = 0;
      for (int a = 0; a < 4; ++a) {
        if (a == x) continue;
        // d = a - x (A) or x - b (B), each component rounded once: |d~ - d| <= u |d~| (1 + u),
        // so u.d <= gamma implies u.d~ <= gamma + 2u |d~| for unit u
        V3 d;
        for (int c = 0; c < 3; ++c) d[c] = side == 0 ? T[a][c] - T[x][c] : T[x][c] - T[a][c];
        planes[k++] = {d, (gamma + 2 * kU * norm(d)) * (1 + 4 * kU)};
      }
      if (polytope_inside_ball(bounds, planes, 3, d0)) off |= 1u << (4 * side + x);
    }
  }
  return off;
}

bool polytope_inside_ball(FacetBounds& bounds, const V3& d1, double c1, const V3& d2, double c2, double d0) {
  const Halfspace planes[2] = {{d1, c1}, {d2, c2}};
  return polytope_inside_ball(bounds, planes, 2, d0);
}

}  // namespace pdd::fast::global
