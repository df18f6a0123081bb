// integer_depth.cpp — classification, depth and delta² order over machine integers. See
// integer_depth.h.
#include "exact/integer_depth.h"

#include <cfloat>
#include <cmath>
#include <cstring>

#include "kernel/pair_memo.h"
#include "kernel/power_scale.h"
#include "pdd/tet_tables.h"

namespace pdd::fast::detail {

static_assert(GMP_NUMB_BITS == 64 && sizeof(mp_limb_t) == 8, "64-bit limbs without nails");

namespace {

using Wide = IntegerFrame::Wide;

bool less(const Wide& a, const Wide& b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }

// a − b (|a − b| < 2^187: the high part fits).
Wide minus(const Wide& a, const Wide& b) { return Wide{a.hi - b.hi - (a.lo < b.lo ? 1 : 0), a.lo - b.lo}; }

int sign_of_wide(const Wide& x) { return x.hi != 0 ? (x.hi > 0 ? 1 : -1) : (x.lo != 0 ? 1 : 0); }

// |x| as limbs (least significant first); |x| < 2^191.
void magnitude(const Wide& x, mp_limb_t* out) {
  Wide m = x;
  if (x.hi < 0) m = Wide{-x.hi - (x.lo != 0 ? 1 : 0), 0 - x.lo};
  out[0] = m.lo;
  out[1] = mp_limb_t(std::uint64_t(m.hi));
  out[2] = mp_limb_t(std::uint64_t(m.hi >> 64));
}

// Signed 256-bit integers, two's complement in four 64-bit words (least significant first): a
// parallel edge pair's heights (ee (w.q) − we (e.q), below 2^249 in magnitude) and their
// differences (below 2^250). Written by hand: each height is two 128 x 128-bit products and a
// subtraction, a few dozen instructions; with a general fixed-width integer type
// (boost::multiprecision's int256_t and int512_t) a parallel edge pair's framed_depth took
// ~7,500 instructions, with these ~3,100 (callgrind, 8,753 such pairs of aligned grids).
using U128 = unsigned __int128;
struct I256 {
  std::uint64_t w[4] = {0, 0, 0, 0};
};

// a b as 256 bits (hi 2^128 + lo), for any unsigned 128-bit a, b.
void product(U128 a, U128 b, U128& hi, U128& lo) {
  const std::uint64_t a0 = std::uint64_t(a), a1 = std::uint64_t(a >> 64), b0 = std::uint64_t(b),
                      b1 = std::uint64_t(b >> 64);
  const U128 p00 = U128(a0) * b0, p01 = U128(a0) * b1, p10 = U128(a1) * b0, p11 = U128(a1) * b1;
  const U128 mid = (p00 >> 64) + std::uint64_t(p01) + std::uint64_t(p10);  // < 3 2^64: no carry out
  lo = (mid << 64) | std::uint64_t(p00);
  hi = p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64);
}

U128 magnitude_of(__int128 a) { return a < 0 ? U128(0) - U128(a) : U128(a); }

[[gnu::always_inline]] inline I256 negated(const I256& x) {
  I256 r;
  unsigned carry = 1;
  for (int i = 0; i < 4; ++i) {
    const std::uint64_t v = ~x.w[i];
    r.w[i] = v + carry;
    carry = carry && r.w[i] == 0;
  }
  return r;
}

// a b exactly, for |a|, |b| < 2^127: the unsigned product of their two's-complement words less
// b~ 2^128 where a < 0 and a~ 2^128 where b < 0 (a = a~ − 2^128 there), modulo 2^256, which
// holds the product (below 2^254 in magnitude) exactly.
[[gnu::always_inline]] inline I256 times(__int128 a, __int128 b) {
  const U128 ua = U128(a), ub = U128(b);
  U128 hi, lo;
  product(ua, ub, hi, lo);
  hi -= (a < 0 ? ub : 0) + (b < 0 ? ua : 0);
  I256 r;
  r.w[0] = std::uint64_t(lo), r.w[1] = std::uint64_t(lo >> 64), r.w[2] = std::uint64_t(hi), r.w[3] = std::uint64_t(hi >> 64);
  return r;
}

// x − y (the callers' values keep it below 2^255 in magnitude): word by word with the borrow,
// each difference in (−2^65, 2^64) wrapping modulo 2^128, so its high word is 0 or all ones.
I256 minus(const I256& x, const I256& y) {
  I256 r;
  U128 borrow = 0;
  for (int i = 0; i < 4; ++i) {
    const U128 t = U128(x.w[i]) - y.w[i] - borrow;
    r.w[i] = std::uint64_t(t);
    borrow = (t >> 64) != 0;
  }
  return r;
}

int sign_of(const I256& x) {
  if (std::int64_t(x.w[3]) < 0) return -1;
  return (x.w[0] | x.w[1] | x.w[2] | x.w[3]) != 0 ? 1 : 0;
}

bool less(const I256& x, const I256& y) { return sign_of(minus(x, y)) < 0; }  // (|x|, |y| < 2^254)

// |x| as four limbs.
void magnitude(const I256& x, mp_limb_t* out) {
  const I256 m = sign_of(x) < 0 ? negated(x) : x;
  for (int i = 0; i < 4; ++i) out[i] = mp_limb_t(m.w[i]);
}

// The orientation rule on the two signs g_k of the normal at edge a's off-edge vertices.
EdgePairSide side_rule(int g1, int g2) {
  if (g1 <= 0 && g2 <= 0) return EdgePairSide::Keep;
  if (g1 >= 0 && g2 >= 0) return EdgePairSide::Flip;
  return EdgePairSide::Undecidable;
}

bool flipped(EdgePairSide side, EdgeOrientation o) {
  return side == EdgePairSide::Flip || (side == EdgePairSide::Undecidable && o == EdgeOrientation::Minus);
}

// The common perpendicular of parallel edges a of A and b of B (exact_predicates.cpp's
// edge_pair_normal_exp): n = (e.e) w − (w.e) e, e = s_v − s_u, w = r_x − s_u, kept as e, w and
// the two dot products (its components, of degree 3, need 187 bits): n.q = (e.e)(w.q) −
// (w.e)(e.q), each factor below 2^124 (differences below 2^61), each product below 2^248; and
// n.n = (e.e)^2 (w.w) − 2 (e.e)(w.e)^2 + (w.e)^2 (e.e) = (e.e) |e × w|^2 (Lagrange's identity),
// zero exactly when w is parallel to e (colinear edges).
struct ParallelNormal {
  std::int64_t e[3], w[3];
  __int128 ee = 0, we = 0;
  bool flip = false;  // the normal is −n
  __int128 ew[3];     // e × w (each component below 2^123)
  bool zero() const { return ew[0] == 0 && ew[1] == 0 && ew[2] == 0; }
  // n.(p − q), vertices by frame index
  I256 dot(const IntegerFrame& f, int p, int q) const {
    const auto &P = f.vertex(p), &Q = f.vertex(q);
    __int128 wq = 0, eq = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t d = P[k] - Q[k];
      wq += __int128(w[k]) * d, eq += __int128(e[k]) * d;
    }
    return flip ? minus(times(we, eq), times(ee, wq)) : minus(times(ee, wq), times(we, eq));
  }
};
ParallelNormal parallel_normal(const IntegerFrame& f, int a, int b) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0];
  const auto &U = f.vertex(u), &V = f.vertex(v), &X = f.vertex(4 + x);
  ParallelNormal p;
  for (int k = 0; k < 3; ++k) {
    p.e[k] = V[k] - U[k], p.w[k] = X[k] - U[k];
    p.ee += __int128(p.e[k]) * p.e[k], p.we += __int128(p.w[k]) * p.e[k];
  }
  f.normal(v, u, 4 + x, u, p.ew);
  return p;
}

EdgePairSide parallel_side(const IntegerFrame& f, const ParallelNormal& p, int a) {
  const int u = kEdges[a][0];
  return side_rule(sign_of(p.dot(f, kOffEdge[a][0], u)), sign_of(p.dot(f, kOffEdge[a][1], u)));
}

// The outward normal of face i of the tetrahedron whose vertices are frame indices o..o+3
// (face_normal_out_of_exp): (p1 − p0) × (p2 − p0), negated when the opposite vertex is on its
// positive side.
void face_normal_out_of(const IntegerFrame& f, int o, int i, __int128 (&n)[3]) {
  const auto& F = kFace[i];
  f.normal(o + F[1], o + F[0], o + F[2], o + F[0], n);
  if (f.dot_sign(n, o + i, o + F[0]) > 0)
    for (__int128& x : n) x = -x;
}

// n.n of a normal of degree 2 as four limbs: each |n_k| = h 2^64 + l < 2^123 (h < 2^59) squared,
// h² 2^128 + 2hl 2^64 + l² (2hl < 2^124), summed (< 2^248) in two 128-bit halves with carries.
void norm2(const __int128 (&n)[3], mp_limb_t* out) {
  using U = unsigned __int128;
  U lo = 0, hi = 0;
  for (const __int128 x : n) {
    const U m = x < 0 ? -static_cast<U>(x) : static_cast<U>(x);
    const std::uint64_t h = std::uint64_t(m >> 64), l = std::uint64_t(m);
    const U ll = U(l) * l, hl2 = 2 * (U(h) * l);
    lo += ll;
    hi += lo < ll;  // carry
    const U mid = hl2 << 64;
    lo += mid;
    hi += (hl2 >> 64) + (lo < mid) + U(h) * h;
  }
  out[0] = mp_limb_t(std::uint64_t(lo)), out[1] = mp_limb_t(std::uint64_t(lo >> 64));
  out[2] = mp_limb_t(std::uint64_t(hi)), out[3] = mp_limb_t(std::uint64_t(hi >> 64));
}

// The vertices that may attain A's largest height along a label's oriented normal (bit i: s_i)
// and B's least (bit j: r_j): a face of A holds A's largest (the opposite vertex is below its
// outward normal), a face of B B's least, a decided edge pair's edge of A A's largest (the rule
// puts both off-edge vertices at or below it); else every vertex.
struct Extremes {
  unsigned A = 0xFu, B = 0xFu;
};

// D and n.n along a normal of degree 2 (a face or a generic edge pair), heights from s0.
void depth_of(const IntegerFrame& f, const __int128 (&n)[3], const Extremes& x, FramedDepth& out) {
  bool firstA = true, firstB = true;
  Wide hi{0, 0}, lo{0, 0};
  for (int i = 0; i < 4; ++i) {
    if (x.A >> i & 1) {
      const Wide a = i == 0 ? Wide{0, 0} : f.dot(n, i, 0);
      if (firstA || less(hi, a)) hi = a;
      firstA = false;
    }
    if (x.B >> i & 1) {
      const Wide b = f.dot(n, 4 + i, 0);
      if (firstB || less(b, lo)) lo = b;
      firstB = false;
    }
  }
  const Wide D = minus(hi, lo);
  out.D_sign = sign_of_wide(D);
  magnitude(D, out.D);
  out.D[3] = 0;
  norm2(n, out.nn);
  out.nn[4] = out.nn[5] = 0;
  out.has_normal = true;
  std::memcpy(out.n, n, sizeof n);
}

// The same along a parallel edge pair's oriented normal: n.n = (e.e) |e × w|^2 (ParallelNormal),
// |e × w|^2 < 2^248 in four limbs (norm2) times e.e < 2^124 in two: below 2^372, six limbs.
void depth_of(const IntegerFrame& f, const ParallelNormal& p, FramedDepth& out) {
  I256 hi, lo = p.dot(f, 4, 0);
  for (int i = 1; i < 4; ++i) {
    const I256 a = p.dot(f, i, 0), b = p.dot(f, 4 + i, 0);
    if (less(hi, a)) hi = a;
    if (less(b, lo)) lo = b;
  }
  const I256 D = minus(hi, lo);
  out.D_sign = sign_of(D);
  magnitude(D, out.D);
  mp_limb_t cross2[4], ee[2];
  norm2(p.ew, cross2);
  const U128 m = U128(p.ee);
  ee[0] = mp_limb_t(std::uint64_t(m)), ee[1] = mp_limb_t(std::uint64_t(m >> 64));
  std::memset(out.nn, 0, sizeof out.nn);
  mpn_mul(out.nn, cross2, 4, ee, 2);
  out.parallel = true;
  out.has_normal = false;
}

// The significant limbs of x[0..k) (at least one).
int size_of(const mp_limb_t* x, int k) {
  while (k > 1 && x[k - 1] == 0) --k;
  return k;
}

// x² y as 14 limbs (x: 4, y: 6, zero-padded).
void square_times(const mp_limb_t* x, const mp_limb_t* y, mp_limb_t (&out)[14]) {
  const int nx = size_of(x, 4), ny = size_of(y, 6);
  mp_limb_t x2[8];
  mpn_sqr(x2, x, nx);
  std::memset(out, 0, sizeof out);
  if (2 * nx >= ny) mpn_mul(out, x2, 2 * nx, y, ny);
  else mpn_mul(out, y, ny, x2, 2 * nx);
}

// A K-limb magnitude (least significant limb first) as a double: Horner from the top limb,
// each step exact but for the limb's conversion and the sum (non-negative terms: relative
// error below (2K − 1) u, with the roundings compounded 1.0001 times that).
template <int K>
double to_double(const mp_limb_t (&x)[K]) {
  double t = 0.0;
  for (int i = K - 1; i >= 0; --i) t = t * 0x1p64 + double(x[i]);
  return t;
}

}  // namespace

EdgePairClass classify_edge_pair_framed(const IntegerFrame& f, int a, int b) {
  const int u = kEdges[a][0], v = kEdges[a][1], x = kEdges[b][0], y = kEdges[b][1];
  EdgePairClass c;
  __int128 n[3];
  f.normal(4 + y, 4 + x, v, u, n);
  if (n[0] != 0 || n[1] != 0 || n[2] != 0) {
    c.side = side_rule(f.dot_sign(n, kOffEdge[a][0], u), f.dot_sign(n, kOffEdge[a][1], u));
    return c;
  }
  const ParallelNormal p = parallel_normal(f, a, b);
  c.kind = p.zero() ? EdgePairKind::Colinear : EdgePairKind::Parallel;
  if (c.kind == EdgePairKind::Parallel) c.side = parallel_side(f, p, a);
  return c;
}

namespace {

// The label's oriented normal when it has degree 2 (a face or a generic edge pair) and the
// vertices that may hold the extreme heights; false for a parallel or colinear edge pair.
bool oriented_normal(const IntegerFrame& f, const DirectionLabel& label, __int128 (&n)[3], Extremes& x) {
  switch (label.kind) {
    case ContactKind::FV:
      face_normal_out_of(f, 0, label.a, n);
      x.A = 1u << kFace[label.a][0];
      return true;
    case ContactKind::VF:
      face_normal_out_of(f, 4, label.a, n);
      for (__int128& v : n) v = -v;
      x.B = 1u << kFace[label.a][0];
      return true;
    case ContactKind::EE: break;
  }
  const int u = kEdges[label.a][0], v = kEdges[label.a][1];
  f.normal(4 + kEdges[label.b][1], 4 + kEdges[label.b][0], v, u, n);
  if (n[0] == 0 && n[1] == 0 && n[2] == 0) return false;
  const EdgePairSide side = side_rule(f.dot_sign(n, kOffEdge[label.a][0], u), f.dot_sign(n, kOffEdge[label.a][1], u));
  if (flipped(side, label.orientation))
    for (__int128& c : n) c = -c;
  if (side != EdgePairSide::Undecidable) x.A = 1u << u;
  return true;
}

// A parallel edge pair's oriented normal; false when colinear.
bool oriented_parallel_normal(const IntegerFrame& f, const DirectionLabel& label, ParallelNormal& p) {
  p = parallel_normal(f, label.a, label.b);
  if (p.zero()) return false;
  if (flipped(parallel_side(f, p, label.a), label.orientation)) p.flip = true;
  return true;
}

}  // namespace

namespace {
bool framed_depth_computed(const IntegerFrame& f, const DirectionLabel& label, FramedDepth& out) {
  __int128 n[3] = {0, 0, 0};
  Extremes x;
  out.parallel = false;
  if (oriented_normal(f, label, n, x)) {
    depth_of(f, n, x, out);
    return true;
  }
  ParallelNormal p;
  if (label.kind != ContactKind::EE || !oriented_parallel_normal(f, label, p)) return false;
  depth_of(f, p, out);
  return true;
}

// The values of one pair ask the same labels' depths again (kernel/pair_memo.h): the candidate
// set's depth signs, then the refinement's intervals and exact order of the same contenders
// (a contact made by rounding: ~7 of them, ~1,300 instructions each), and pdd2_accel's after
// rigid_pd2's. The depth is a function of the pair and the label alone (the frame's units are
// the pair's).
thread_local PairMemo<FramedDepth, 48> framed_memo;
}  // namespace

bool framed_depth(const IntegerFrame& f, const DirectionLabel& label, FramedDepth& out) {
  return framed_memo.get(f.a(), f.b(), label_key(label), out,
                         [&](FramedDepth& d) { return framed_depth_computed(f, label, d); });
}

int framed_depth_sign(const IntegerFrame& f, const DirectionLabel& label) {
  FramedDepth d;
  return framed_depth(f, label, d) ? d.D_sign : 2;
}

namespace {

// A signed integer given by its magnitude's limbs, times 2^k, rounded to the nearest double
// once: the 64 bits from the highest set bit down, the bits below folded into the lowest as a
// sticky bit (which keeps round-to-nearest-even at bit 11 exact), converted, then scaled by a
// power of two (exact where the result is a normal double; else false; 0 is exact). Its error
// |v − V| <= u |V| <= u |v| (1 + 2^-40) is returned in e.
bool rounded_scaled(const mp_limb_t (&mag)[4], int sign, int k, double& v, double& e) {
  constexpr double u = 0x1p-53;
  int top = 3;
  while (top > 0 && mag[top] == 0) --top;
  if (sign == 0 || mag[top] == 0) return v = 0, e = 0, true;
  const int lz = __builtin_clzll(mag[top]);
  std::uint64_t bits = mag[top] << lz, sticky = 0;
  if (top > 0) {
    if (lz > 0) bits |= mag[top - 1] >> (64 - lz), sticky = mag[top - 1] << lz;
    else sticky = mag[top - 1];
    for (int i = 0; i < top - 1; ++i) sticky |= mag[i];
  }
  v = times_pow2(double(bits | (sticky != 0 ? 1u : 0u)), 64 * top - lz + k);
  if (!(std::fabs(v) >= DBL_MIN && std::fabs(v) <= DBL_MAX)) return false;
  e = u * std::fabs(v) * (1 + 0x1p-40);
  if (sign < 0) v = -v;
  return true;
}

bool rounded_scaled(const Wide& x, int k, double& v, double& e) {
  mp_limb_t m[4] = {0, 0, 0, 0};
  magnitude(x, m);
  return rounded_scaled(m, sign_of_wide(x), k, v, e);
}

bool rounded_scaled(const I256& x, int k, double& v, double& e) {
  mp_limb_t m[4];
  magnitude(x, m);
  return rounded_scaled(m, sign_of(x), k, v, e);
}

}  // namespace

namespace {
// The vertex of A (0..3) of greatest exact height among its four heights relative to one of
// them (the first such in ties).
template <class H>
int highest_of_a(const H& h0, const H& h1, const H& h2, const H& h3) {
  const H* h[4] = {&h0, &h1, &h2, &h3};
  int t = 0;
  for (int i = 1; i < 4; ++i)
    if (less(*h[t], *h[i])) t = i;
  return t;
}
}  // namespace

bool framed_heights(const IntegerFrame& f, const DirectionLabel& label, FramedHeights& out) {
  const int e = f.unit_exponent(), u = label.kind == ContactKind::EE ? kEdges[label.a][0] : 0;
  __int128 n[3];
  Extremes x;
  bool ok = true;
  if (oriented_normal(f, label, n, x)) {
    out.e_n = 0;
    for (int k = 0; k < 3; ++k) {
      Wide w{n[k] >> 64, std::uint64_t(n[k])};  // (n_k as hi 2^64 + lo)
      double err = 0;
      ok = ok && rounded_scaled(w, 2 * e, out.n[k], err);
      out.e_n = std::fmax(out.e_n, err);
    }
    const int t = label.kind == ContactKind::FV   ? kFace[label.a][0]
                  : label.kind == ContactKind::VF ? 4 + kFace[label.a][0]
                                                  : highest_of_a(f.dot(n, 0, u), f.dot(n, 1, u), f.dot(n, 2, u), f.dot(n, 3, u));
    for (int i = 0; i < 8 && ok; ++i) ok = rounded_scaled(f.dot(n, i, t), 3 * e, out.h[i], out.e[i]);
    return ok;
  }
  ParallelNormal p;
  if (!oriented_parallel_normal(f, label, p)) return false;
  out.e_n = 0;
  for (int k = 0; k < 3; ++k) {
    I256 c = minus(times(p.ee, p.w[k]), times(p.we, p.e[k]));
    if (p.flip) c = negated(c);
    double err = 0;
    ok = ok && rounded_scaled(c, 3 * e, out.n[k], err);
    out.e_n = std::fmax(out.e_n, err);
  }
  const int t = highest_of_a(p.dot(f, 0, u), p.dot(f, 1, u), p.dot(f, 2, u), p.dot(f, 3, u));
  for (int i = 0; i < 8 && ok; ++i) ok = rounded_scaled(p.dot(f, i, t), 4 * e, out.h[i], out.e[i]);
  return ok;
}

int compare_framed_delta2(const FramedDepth& p, const FramedDepth& q) {
  auto sign = [](int c) { return c > 0 ? 1 : c < 0 ? -1 : 0; };
  const bool same_D = std::memcmp(p.D, q.D, sizeof p.D) == 0, same_nn = std::memcmp(p.nn, q.nn, sizeof p.nn) == 0;
  if (same_D && same_nn) return 0;
  if (same_nn) return sign(mpn_cmp(p.D, q.D, 4));                         // m (D_p² − D_q²)
  if (same_D) return p.D_sign == 0 ? 0 : sign(mpn_cmp(q.nn, p.nn, 6));  // D² (n_q.n_q − n_p.n_p)
  mp_limb_t a[14], b[14];
  square_times(p.D, q.nn, a);  // D_p² n_q.n_q
  square_times(q.D, p.nn, b);  // D_q² n_p.n_p
  return sign(mpn_cmp(a, b, 14));
}

namespace {

// x y = z t exactly, for |x|, |y|, |z|, |t| < 2^127: signs, then the 256-bit magnitudes.
bool products_equal(__int128 x, __int128 y, __int128 z, __int128 t) {
  const int sxy = (x > 0) - (x < 0), syy = (y > 0) - (y < 0), szt = (z > 0) - (z < 0), stt = (t > 0) - (t < 0);
  if (sxy * syy != szt * stt) return false;
  if (sxy * syy == 0) return true;
  U128 h1, l1, h2, l2;
  product(magnitude_of(x), magnitude_of(y), h1, l1);
  product(magnitude_of(z), magnitude_of(t), h2, l2);
  return h1 == h2 && l1 == l2;
}

// b = s a for some s > 0 (a, b non-zero): every component of one sign in both, and a × b = 0.
bool same_direction(const __int128 (&a)[3], const __int128 (&b)[3]) {
  for (int k = 0; k < 3; ++k)
    if ((a[k] > 0) != (b[k] > 0) || (a[k] < 0) != (b[k] < 0)) return false;
  return products_equal(a[0], b[1], a[1], b[0]) && products_equal(a[1], b[2], a[2], b[1]) &&
         products_equal(a[0], b[2], a[2], b[0]);
}

}  // namespace

// A contender whose oriented normal has the direction of an earlier one's (a face of A and a face
// of B in one plane, an edge pair in a face's plane: most ties of an aligned pair) has the same
// delta² as that one, so it is not strictly below the least so far: it is passed over without its
// depth (~600 instructions, where framed_memo does not hold it) or a comparison (~700). The
// normals are the degree-2 ones (oriented_normal, kept with the depth); a parallel edge pair's
// is compared by its depth.
int first_least_delta2_framed(const IntegerFrame& f, const DirectionLabel* l, int n) {
  if (n <= 0) return -1;
  constexpr int kSeen = 16;
  __int128 seen[kSeen][3];
  int m = 0, w = 0;
  FramedDepth least, p;
  auto repeat = [&](const __int128 (&nk)[3]) {
    for (int j = 0; j < m; ++j)
      if (same_direction(seen[j], nk)) return true;
    if (m < kSeen) std::memcpy(seen[m++], nk, sizeof nk);
    return false;
  };
  for (int k = 0; k < n; ++k) {
    FramedDepth& d = k == 0 ? least : p;
    bool ok = false;
    if (framed_memo.find(f.a(), f.b(), label_key(l[k]), d, ok)) {
      if (ok && d.has_normal && repeat(d.n)) continue;
    } else {
      __int128 nk[3];
      Extremes x;
      if (oriented_normal(f, l[k], nk, x)) {
        if (repeat(nk)) continue;
        ok = framed_memo.get(f.a(), f.b(), label_key(l[k]), d, [&](FramedDepth& o) {
          o.parallel = false;
          depth_of(f, nk, x, o);
          return true;
        });
      } else {
        ok = framed_depth(f, l[k], d);
      }
    }
    if (!ok) return -1;
    if (k > 0 && compare_framed_delta2(p, least) < 0) w = k, least = p;  // strictly below: a tie keeps the earlier
  }
  return w;
}

bool framed_delta2(const IntegerFrame& f, const FramedDepth& p, double& v, double& r) {
  constexpr double u = 0x1p-53, rho = 16 * u;
  if (p.D_sign == 0) return false;
  const double D = to_double(p.D), nn = to_double(p.nn);
  // D² / n.n in units 2^(2e) (2^(6e) / 2^(4e), or 2^(8e) / 2^(6e)); the scaling is exact while the
  // result is normal
  v = times_pow2(D * D / nn, 2 * f.unit_exponent());
  r = 1.02 * (rho + rho + 4 * u);
  return std::isnormal(v);
}

}  // namespace pdd::fast::detail
