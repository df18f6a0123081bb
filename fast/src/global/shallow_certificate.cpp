// shallow_certificate.cpp — see shallow_certificate.h for the argument.
#include "global/shallow_certificate.h"

#include "certification/double_word.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <gmpxx.h>

#include "exact/expansion.h"

namespace pdd::fast::global {
namespace {


// The vertices at the plane (direction_qp.h: A's i when T_i = C - H_i < -S_A, B's j when
// C - H_j > -S_B), bit i of ma / mb.
void active_sets(const Evaluation& ev, unsigned& ma, unsigned& mb) {
  ma = mb = 0;
  for (int i = 0; i < 4; ++i) {
    if (ev.hA[i] > ev.sol.c + ev.sol.sumA) ma |= 1u << i;
    if (ev.hB[i] < ev.sol.c + ev.sol.sumB) mb |= 1u << i;
  }
}

// Two vectors across v, each of v's length (a frame for the tilt; any such pair will do).
void frame(const V3& v, V3& e1, V3& e2) {
  int k = 0;
  for (int j = 1; j < 3; ++j)
    if (std::fabs(v[j]) < std::fabs(v[k])) k = j;
  V3 axis{0, 0, 0};
  axis[k] = 1;
  e1 = cross(v, axis);
  e1 = mul(e1, norm(v) / norm(e1));
  e2 = mul(cross(v, e1), 1 / norm(v));
}

// The least of F on S's piece along v + E y (shallow_certificate.h): v moved, or false when
// S's positions across v do not fix the tilt (fewer than three of them off one line).
bool tilt_step(const Problem& P, const Evaluation& ev, unsigned ma, unsigned mb, V3& v, V3& lo) {
  V3 e1, e2;
  frame(v, e1, e2);
  const int mA = __builtin_popcount(ma), mB = __builtin_popcount(mb);
  const double wA = 1.0 / (5 - mA), wB = 1.0 / (5 - mB), k = 10 - mA - mB;
  double SAh = 0, SBh = 0, SA[2] = {0, 0}, SB[2] = {0, 0};
  for (int i = 0; i < 4; ++i) {
    if (ma >> i & 1u) SAh += ev.hA[i], SA[0] += dot(e1, P.relA[i]), SA[1] += dot(e2, P.relA[i]);
    if (mb >> i & 1u) SBh += ev.hB[i], SB[0] += dot(e1, P.relB[i]), SB[1] += dot(e2, P.relB[i]);
  }
  const double W = mA * wA + mB * wB;
  const double ch = (wA * SAh + wB * SBh) / W;
  const double cx[2] = {(wA * SA[0] + wB * SB[0]) / W, (wA * SA[1] + wB * SB[1]) / W};
  double M[3] = {0, 0, 0}, r[2] = {0, 0};  // M: xx xy yy
  auto term = [&](double eta, double x0, double x1, double w) {
    M[0] += w * x0 * x0, M[1] += w * x0 * x1, M[2] += w * x1 * x1;
    r[0] += w * x0 * eta, r[1] += w * x1 * eta;
  };
  double tau = 0, tx[2] = {0, 0};
  for (int i = 0; i < 4; ++i) {
    if (ma >> i & 1u) {
      const double x0 = dot(e1, P.relA[i]) - cx[0], x1 = dot(e2, P.relA[i]) - cx[1];
      term(ev.hA[i] - ch, x0, x1, 1);
      tau -= ev.hA[i] - ch, tx[0] -= x0, tx[1] -= x1;
    }
    if (mb >> i & 1u) term(ev.hB[i] - ch, dot(e1, P.relB[i]) - cx[0], dot(e2, P.relB[i]) - cx[1], 1);
  }
  term(wA * tau, wA * tx[0], wA * tx[1], k);
  const double det = M[0] * M[2] - M[1] * M[1];
  if (!(det > 1e-12 * (M[0] + M[2]) * (M[0] + M[2]))) return false;
  const double y0 = -(M[2] * r[0] - M[1] * r[1]) / det, y1 = -(M[0] * r[1] - M[1] * r[0]) / det;
  const V3 t = add(mul(e1, y0), mul(e2, y1));
  for (int k = 0; k < 3; ++k) {
    const detail::dw::DW x = detail::dw::two_sum(v[k], lo[k] + t[k]);  // v + lo + t in double words
    v[k] = x.hi, lo[k] = x.lo;
  }
  return std::isfinite(v[0] + v[1] + v[2]) && std::isfinite(lo[0] + lo[1] + lo[2]);
}


// v moved to the least of its pieces' charts until its active set stays (at most 8 steps, each
// kept only where it lowers the certified value), v + lo in double words (a tilt below v's
// rounding: a contact plane off the axes; lo stays 0 where each step's sum is a double). False
// when an evaluation is not certified or a side has no vertex at the plane.
bool find_normal(const TetVertices& A, const TetVertices& B, const Problem& P, V3& v, V3& lo, Evaluation& ev) {
  ev = evaluate_tight(A, B, P, v, lo);
  if (!(ev.error <= kGlobalRel)) return false;
  unsigned ma, mb;
  active_sets(ev, ma, mb);
  for (int step = 0; step < 8; ++step) {
    if (!ma || !mb) return false;
    V3 w = v, wl = lo;
    // (no tilt: S's positions across v on one line, as a lone pair's two; v stays, and the
    // certificate below decides it)
    if (!tilt_step(P, ev, ma, mb, w, wl)) return true;
    const Evaluation ew = evaluate_tight(A, B, P, w, wl);
    if (!(ew.error <= kGlobalRel) || !(ew.value <= ev.value)) return true;
    unsigned na, nb;
    active_sets(ew, na, nb);
    v = w, lo = wl, ev = ew;
    if (na == ma && nb == mb) return true;
    ma = na, mb = nb;
  }
  return true;
}

// The best multipliers for the cap about v, in doubles (the exact step below makes them exact):
// the dual of relaxed over the plane across v,
//     max q(w) = sum_p delta_p w_p - kappa(w)  over w >= 0 with sum_A l = sum_B m, g.e1 = g.e2 = 0,
// delta_p the overlap of vertex p at the evaluation's plane (A's height above it, B's below it;
// g.v = sum_p delta_p w_p when sum l = sum m). By weak duality (shallow_certificate.h) every such
// w bounds relaxed on the cap, and its optimum, (g.v)^2 / (4 kappa) = 20 v.v B0, is the least of
// F*(n) = 20 |n|^2 relaxed(n / |n|) over the plane n.v = v.v (strong duality: a convex QP): where
// v is that plane's minimiser, B0 = relaxed(v) and the cap's bound is as tight as it can be. The
// multipliers of the evaluation at v give the same only where v lies inside one piece of the
// relaxed value (one active set about it); at a minimiser where pieces meet (a contact by
// rounding: several vertices at the plane, one of them with a multiplier ~0) they can fall short
// by a factor of two. Solved by its KKT system on each support S of the vertices within 1e-6 of
// the size from the plane (both sides non-empty): [2 K_S, E_S^T; E_S, 0] (w_S, mu) = (delta_S,
// 0), E's rows (s_p, s_p xi_p) (s = +1 on A, -1 on B; xi the positions across v over sigma =
// |v| scale), by its 3 x 3 Schur complement ((2 K_S)^-1 in closed form), kept where w_S > 0, the
// best q taken (any w >= 0 is valid: the exact step decides). Written out rather than with a
// QP library: 8 variables, at most 2^8 supports, ~100 operations each, and the result only a
// start for the exact step. mu's tilt part is the plane's minimiser: n = v + y1 e1 + y2 e2 with
// y = -(mu_1, mu_2) / sigma (along n the overlaps are delta_p + s_p sigma y.xi_p), returned in
// tilt.
struct PlaneDual {
  double w[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  double q = -INFINITY;
  V3 tilt{0, 0, 0};
};
bool plane_dual(const Problem& P, const Evaluation& ev, const V3& v, PlaneDual& out) {
  V3 e1, e2;
  frame(v, e1, e2);
  const double sigma = norm(v) * P.scale;  // the positions across v scaled to ~1
  if (!(sigma > 0) || !std::isfinite(sigma)) return false;
  double delta[8], xi[8][2], side[8];
  unsigned near = 0;
  for (int i = 0; i < 4; ++i) {
    side[i] = 1, side[4 + i] = -1;
    delta[i] = ev.hA[i] - ev.sol.c, delta[4 + i] = ev.sol.c - ev.hB[i];
    xi[i][0] = dot(e1, P.relA[i]) / sigma, xi[i][1] = dot(e2, P.relA[i]) / sigma;
    xi[4 + i][0] = dot(e1, P.relB[i]) / sigma, xi[4 + i][1] = dot(e2, P.relB[i]) / sigma;
  }
  for (int p = 0; p < 8; ++p)
    if (delta[p] > -1e-6 * sigma) near |= 1u << p;
  for (unsigned S = 1; S < 256; ++S) {
    if ((S & ~near) || !(S & 0x0fu) || !(S & 0xf0u)) continue;
    // G = (2 K_S)^-1 by sides: ((I - J/5) / 2)^-1 = 2 (I + J / (5 - k)) on a side of k members;
    // M = E G E^T and b = E G delta, summed over the sides; then M mu = b, w = G (delta - E^T mu)
    double M[3][3] = {}, b[3] = {};
    for (int s = 0; s < 2; ++s) {
      double e1s[3] = {0, 0, 0}, ds = 0;
      int k = 0;
      for (int p = 4 * s; p < 4 * s + 4; ++p) {
        if (!(S >> p & 1u)) continue;
        const double e[3] = {side[p], side[p] * xi[p][0], side[p] * xi[p][1]};
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) M[r][c] += 2 * e[r] * e[c];
          b[r] += 2 * e[r] * delta[p];
          e1s[r] += e[r];
        }
        ds += delta[p], ++k;
      }
      const double f = 2.0 / (5 - k);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) M[r][c] += f * e1s[r] * e1s[c];
        b[r] += f * e1s[r] * ds;
      }
    }
    const double c00 = M[1][1] * M[2][2] - M[1][2] * M[2][1], c01 = M[1][2] * M[2][0] - M[1][0] * M[2][2],
                 c02 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
    const double det = M[0][0] * c00 + M[0][1] * c01 + M[0][2] * c02;
    if (!(det > 1e-12 * M[0][0] * M[1][1] * M[2][2])) continue;  // (M is a Gram matrix: det >= 0)
    double mu[3];
    for (int c = 0; c < 3; ++c) {  // Cramer's rule
      double Mc[3][3];
      for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 3; ++j) Mc[r][j] = j == c ? b[r] : M[r][j];
      mu[c] = (Mc[0][0] * (Mc[1][1] * Mc[2][2] - Mc[1][2] * Mc[2][1]) -
               Mc[0][1] * (Mc[1][0] * Mc[2][2] - Mc[1][2] * Mc[2][0]) +
               Mc[0][2] * (Mc[1][0] * Mc[2][1] - Mc[1][1] * Mc[2][0])) / det;
    }
    double w[8] = {0, 0, 0, 0, 0, 0, 0, 0}, q = 0;
    bool positive = true;
    for (int s = 0; s < 2; ++s) {
      double res[4], sum = 0;
      int k = 0;
      for (int p = 4 * s; p < 4 * s + 4; ++p) {
        if (!(S >> p & 1u)) continue;
        res[p - 4 * s] = delta[p] - side[p] * (mu[0] + mu[1] * xi[p][0] + mu[2] * xi[p][1]);
        sum += res[p - 4 * s], ++k;
      }
      for (int p = 4 * s; p < 4 * s + 4; ++p) {
        if (!(S >> p & 1u)) continue;
        w[p] = 2 * (res[p - 4 * s] + sum / (5 - k));
        positive = positive && w[p] > 0;
        q += delta[p] * w[p] / 2;  // at the KKT point q = delta.w - w K w = delta.w / 2
      }
    }
    if (!positive || !(q > out.q) || !std::isfinite(q)) continue;
    out.q = q;
    for (int p = 0; p < 8; ++p) out.w[p] = w[p];
    out.tilt = add(mul(e1, -mu[1] / sigma), mul(e2, -mu[2] / sigma));
  }
  return out.q > 0;
}

// Exact integers over a power of two: x = X 2^e for every double x of a set, e the least of
// their exponents (a double's 53-bit mantissa times 2^(exponent - 53)). Products and sums of
// such integers need no reduction to lowest terms (rationals take a gcd after every
// operation: 70% of this certificate's time with them). Written with GMP's mpz calls on a
// per-thread workspace (fused multiply-adds, no temporaries: allocation was ~40% of the time
// with gmpxx's expressions).
long low_exponent(double x) {
  int e = 0;
  std::frexp(x, &e);
  return x == 0 ? LONG_MAX : long(e) - 53;
}
void to_integer(double x, long e, mpz_class& out) {
  if (x == 0) {
    out = 0;
    return;
  }
  int ex = 0;
  const double m = std::frexp(x, &ex);
  mpz_set_d(out.get_mpz_t(), m * 0x1p53);  // an integer below 2^53: exact
  mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<unsigned long>(long(ex) - 53 - e));
}

using ZV = std::array<mpz_class, 3>;
mpz_ptr z(mpz_class& x) { return x.get_mpz_t(); }
mpz_srcptr z(const mpz_class& x) { return x.get_mpz_t(); }
void zdot(mpz_class& r, const ZV& a, const ZV& b) {
  mpz_mul(z(r), z(a[0]), z(b[0]));
  mpz_addmul(z(r), z(a[1]), z(b[1]));
  mpz_addmul(z(r), z(a[2]), z(b[2]));
}
void zcross(ZV& r, const ZV& a, const ZV& b) {  // (r not a or b)
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    mpz_mul(z(r[k]), z(a[i]), z(b[j]));
    mpz_submul(z(r[k]), z(a[j]), z(b[i]));
  }
}
// The cofactors of a 3x3 matrix, cof[r][c] = (-1)^(r+c) times the minor of entry (r, c): then
// det m = sum_r m[r][0] cof[r][0], and the determinant of m with column c replaced by b is
// sum_r b[r] cof[r][c] (Laplace along that column), so Cramer's rule needs these nine products
// of two entries once instead of a determinant per column.
void cofactors(mpz_class (&cof)[3][3], const mpz_class (&m)[3][3]) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      // (cyclic order: the sign (-1)^(r+c) comes with the rows and columns taken cyclically)
      mpz_mul(z(cof[r][c]), z(m[r1][c1]), z(m[r2][c2]));
      mpz_submul(z(cof[r][c]), z(m[r1][c2]), z(m[r2][c1]));
    }
}

// The exact part's integers, kept per thread (their limbs reused from pair to pair).
struct Workspace {
  ZV x[8], V, e1, e2, g;
  mpz_class o[3], y, col[8][3], res[3], M[8], M0[8], m[3][3], cof[3][3], d, change[3];
  mpz_class sl, sm, ql, qm, K, gv, vv, num, den;
};

bool move_three(const int (&best)[3], Workspace& w);
bool g_along_v(Workspace& w);

// The evaluation's multipliers (direction_qp.h's KKT: l_i = -2 (T_i + S_A) at A's vertices at
// the plane, m_j = 2 (T_j + S_B) at B's, 0 elsewhere), [0..3] A's, [4..7] B's.
void multipliers_of(const Evaluation& ev, double (&l)[8]) {
  for (int i = 0; i < 4; ++i) {
    l[i] = std::max(0.0, 2 * (ev.hA[i] - ev.sol.c - ev.sol.sumA));
    l[4 + i] = std::max(0.0, 2 * (ev.sol.c + ev.sol.sumB - ev.hB[i]));
  }
}

// Multipliers l (multipliers_of's, or plane_dual's), moved exactly so that sum l = sum m and
// g = sum l_i a_i - sum m_j b_j is parallel to v (shallow_certificate.h), as integers w.M (a
// positive multiple of them: B0 does not change when every multiplier is scaled by one s > 0);
// [0..3] A's, [4..7] B's. w.x: the positions relative to A[0] as integers (one power of two),
// w.V: v's components as integers. False when no triple tried gives a regular system keeping
// every multiplier >= 0.
bool parallel_multipliers(const double (&l)[8], Workspace& w) {
  long el = LONG_MAX;
  for (double y : l) el = std::min(el, low_exponent(y));
  if (el == LONG_MAX) return false;
  // e1, e2 across v, exactly
  int k = 0;
  for (int j = 1; j < 3; ++j)
    if (mpz_cmpabs(z(w.V[j]), z(w.V[k])) < 0) k = j;
  ZV axis{mpz_class(0), mpz_class(0), mpz_class(0)};
  axis[k] = 1;
  zcross(w.e1, w.V, axis);
  zcross(w.e2, w.V, w.e1);
  // columns (s_p, s_p x_p.e1, s_p x_p.e2), s = +1 on A, -1 on B (each row in its own power of
  // two, which Cramer's rule cancels); the residual of the double multipliers
  double cd[8][3];
  for (mpz_class& r : w.res) r = 0;
  for (int p = 0; p < 8; ++p) {
    const int s = p < 4 ? 1 : -1;
    w.col[p][0] = s;
    zdot(w.col[p][1], w.x[p], w.e1);
    zdot(w.col[p][2], w.x[p], w.e2);
    if (s < 0) mpz_neg(z(w.col[p][1]), z(w.col[p][1])), mpz_neg(z(w.col[p][2]), z(w.col[p][2]));
    if (l[p] > 0) to_integer(l[p], el, w.M[p]);
    else w.M[p] = 0;
    for (int r = 0; r < 3; ++r) mpz_addmul(z(w.res[r]), z(w.M[p]), z(w.col[p][r])), cd[p][r] = w.col[p][r].get_d();
  }
  // The rows in comparable units for the conditioning below: row 0 is +-1, rows 1 and 2 the
  // positions times |V| and |V|^2 in V's integer units (~2^110 and 2^220 for a normal in double
  // words), each scaled to at most 1. (A row's scale multiplies every determinant by one factor
  // but the column norms unevenly: unscaled, |det| / norms goes as 1 / |V|, below the 1e-8
  // filter for every triple once V's integers are large, and no triple with a zero multiplier
  // would be tried: on 300 contacts by rounding of 24-tetrahedra grids against their copy moved
  // a quarter cell along (1, 1, 1), 175 on the exact pieces unscaled, 156 scaled.)
  for (int r = 1; r < 3; ++r) {
    double big = 0;
    for (int p = 0; p < 8; ++p) big = std::max(big, std::fabs(cd[p][r]));
    if (big > 0 && std::isfinite(big))
      for (int p = 0; p < 8; ++p) cd[p][r] /= big;
  }
  // The triple to move (in doubles: a choice, the exact part below decides): first the three
  // largest multipliers whose columns are best conditioned; where the change turns one of them
  // negative (a vertex at the plane with a multiplier ~0: a minimiser where pieces meet), any
  // other triple, zero multipliers included (the dual allows a multiplier on every vertex, active
  // or not), best conditioned first; at most kTriples of them.
  constexpr int kTriples = 12;
  struct Triple {
    double score;
    int p[3];
  };
  Triple order[56];
  int count = 0;
  double norm[8];  // each column's length
  for (int p = 0; p < 8; ++p) norm[p] = std::sqrt(cd[p][0] * cd[p][0] + cd[p][1] * cd[p][1] + cd[p][2] * cd[p][2]);
  for (int p = 0; p < 8; ++p)
    for (int q = p + 1; q < 8; ++q)
      for (int r = q + 1; r < 8; ++r) {
        double d = 0;
        for (int row = 0; row < 3; ++row) {
          const int r1 = (row + 1) % 3, r2 = (row + 2) % 3;
          d += cd[p][row] * (cd[q][r1] * cd[r][r2] - cd[q][r2] * cd[r][r1]);
        }
        const double n = norm[p] * norm[q] * norm[r];
        const double cond = std::fabs(d) / n;
        if (l[p] > 0 && l[q] > 0 && l[r] > 0) {  // positive scores: the moved multipliers all > 0
          const double score = cond * std::min({l[p], l[q], l[r]});
          if (score > 0) order[count++] = {score, {p, q, r}};
        } else if (cond > 1e-8) {  // negative: after every positive one, best conditioned first
          // (a triple whose columns are nearly dependent, |det| below 1e-8 of their norms'
          // product, would move its multipliers by ~1e8 of the residual: skipped as hopeless;
          // the exact step decides every triple tried)
          order[count++] = {-1 / cond, {p, q, r}};
        }
      }
  // Tried in descending score, equal scores in the order listed (a stable sort's order), each
  // picked when its turn comes: the first usually succeeds, so the rest are never ordered.
  for (int p = 0; p < 8; ++p) w.M0[p] = w.M[p];
  bool tried[56] = {};
  for (int t = 0; t < std::min(count, kTriples); ++t) {
    int next = -1;
    for (int i = 0; i < count; ++i)
      if (!tried[i] && (next < 0 || order[i].score > order[next].score)) next = i;
    tried[next] = true;
    if (move_three(order[next].p, w) && g_along_v(w)) return true;
  }
  return false;
}

// parallel_multipliers' exact step on one triple: w.M = |d| w.M0 + the change of the three
// (Cramer's rule on their columns against the residual); false when singular or one turns
// negative.
bool move_three(const int (&best)[3], Workspace& w) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) w.m[r][c] = w.col[best[c]][r];
  cofactors(w.cof, w.m);
  mpz_mul(z(w.d), z(w.m[0][0]), z(w.cof[0][0]));
  mpz_addmul(z(w.d), z(w.m[1][0]), z(w.cof[1][0]));
  mpz_addmul(z(w.d), z(w.m[2][0]), z(w.cof[2][0]));
  const int sd = sgn(w.d);
  if (sd == 0) return false;
  // Cramer: change_c = det(m with column c replaced by -res) / d = -sum_r res_r cof[r][c] / d;
  // M scaled by |d|
  for (int c = 0; c < 3; ++c) {
    mpz_mul(z(w.change[c]), z(w.res[0]), z(w.cof[0][c]));
    mpz_addmul(z(w.change[c]), z(w.res[1]), z(w.cof[1][c]));
    mpz_addmul(z(w.change[c]), z(w.res[2]), z(w.cof[2][c]));
    if (sd > 0) mpz_neg(z(w.change[c]), z(w.change[c]));
  }
  mpz_abs(z(w.d), z(w.d));
  for (int p = 0; p < 8; ++p) mpz_mul(z(w.M[p]), z(w.M0[p]), z(w.d));
  for (int c = 0; c < 3; ++c) {
    mpz_add(z(w.M[best[c]]), z(w.M[best[c]]), z(w.change[c]));
    if (sgn(w.M[best[c]]) < 0) return false;
  }
  return true;
}

// g = sum_A M a - sum_B M b (over 2^ex) of the moved multipliers w.M, and w.gv = g.V; true when
// g.v > 0 (the bound (1) of the header holds only on that side: a triple whose g points away
// from v proves nothing, and parallel_multipliers tries the next).
bool g_along_v(Workspace& w) {
  for (mpz_class& y : w.g) y = 0;
  for (int p = 0; p < 8; ++p)
    for (int k = 0; k < 3; ++k) {
      if (p < 4) mpz_addmul(z(w.g[k]), z(w.M[p]), z(w.x[p][k]));
      else mpz_submul(z(w.g[k]), z(w.M[p]), z(w.x[p][k]));
    }
  zdot(w.gv, w.g, w.V);
  return sgn(w.gv) > 0;
}

// A lower bound on the signed distance of a point q from the plane through x1 spanned by a and b,
// positive on the side o points to; given a, b, o (each component the rounded difference of two
// doubles, or a double itself) and c = x1 - q (likewise). The cross product and the dot product
// in doubles, each within 16u of their permanents (the differences rounded once, products and
// sums rounded: 8u, doubled for room), the norm bounded above. -inf when the side of o is not
// certain.
double plane_distance_lower(const V3& a, const V3& b, const V3& c, const V3& o) {
  const V3 N = cross(a, b);
  V3 pn;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    pn[k] = std::fabs(a[i] * b[j]) + std::fabs(a[j] * b[i]);
  }
  auto perm = [&pn](const V3& y) {
    return (pn[0] * std::fabs(y[0]) + pn[1] * std::fabs(y[1]) + pn[2] * std::fabs(y[2])) * (1 + 8 * kU);
  };
  const double no = dot(N, o), eo = 16 * kU * perm(o);
  if (!(std::fabs(no) > eo)) return -INFINITY;
  const double side = no < 0 ? 1 : -1;  // side N: away from o
  const double num = side * dot(N, c) - 16 * kU * perm(c);
  const double den = (norm(N) * (1 + 3 * kU) + 5 * kU * norm(pn)) * (1 + 4 * kU);
  if (!(num > 0) || !(den > 0)) return -INFINITY;
  return num / den * (1 - 4 * kU);
}

// A bound on |vh - n/|n||, vh = v/|v| rounded and n = v + lo (the cap's axis): vh within 8u of
// v/|v|, and alpha (overlap_off_cap's) between v/|v| and n/|n|.
double cap_slack(const V3& v, const V3& lo) {
  const double alpha = 2 * std::sqrt(3.0) * std::fmax(std::fabs(lo[0]), std::fmax(std::fabs(lo[1]), std::fabs(lo[2]))) /
                       (norm(v) * (1 - 3 * kU)) * (1 + 8 * kU);
  return (8 * kU + alpha) * (1 + 4 * kU);
}

// Off the cap u.v/|v| < c0 (c0 >= the cosine of the cap's radius, rounded up): D(u) >= d0 for
// every such unit u, from four points of M = A - B, each the rounded difference w of a vertex
// of A and one of B (within delta of the exact point: D(u) >= max_k u.w_k - delta).
//  - u.v >= 0 (angle theta to v in [theta0, pi/2], cos(theta0) = c0): u = cos(theta) vh +
//    sin(theta) t, t unit across v. Three points of M's face beneath the contact whose
//    projection across v holds a disc of radius rho about 0 (each side's line at least rho from
//    0: the distance of 0 from the plane through the side along v) and whose heights along vh
//    are >= -Z give D(u) >= -Z cos(theta) + rho sin(theta) - delta, increasing in theta on
//    [0, pi/2]: >= rho sin(theta0) - Z - delta.
//  - u.v <= 0: a ball B(q, R1) inside the simplex of those three and the point deepest along
//    v, q = -R vh (R a power of two: exact), gives D(u) >= u.q + R1 - delta >= R1 - R e - delta
//    (e: vh within 8u of v/|v|, so u.vh <= e).
bool overlap_off_cap(const TetVertices& A, const TetVertices& B, const V3& v, const V3& lo, double c0, double d0) {
  const V3 vh = mul(v, 1 / norm(v));  // within 8u of v/|v|
  // alpha >= |v/|v| - n/|n||, n = v + lo (2 |lo| / |v|): the tests below run along v; across n
  // a point p's projection moves by <= 2 alpha |p| and its height by <= alpha |p|
  const double alpha = 2 * std::sqrt(3.0) * std::fmax(std::fabs(lo[0]), std::fmax(std::fabs(lo[1]), std::fabs(lo[2]))) /
                       (norm(v) * (1 - 3 * kU)) * (1 + 8 * kU);
  const double e = 8 * kU + alpha;
  V3 w[16];
  double z[16], zmax = -INFINITY, zmin = INFINITY, wmax = 0;
  int apex = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const int p = 4 * i + j;
      for (int k = 0; k < 3; ++k) w[p][k] = A[i][k] - B[j][k];
      z[p] = dot(vh, w[p]);
      wmax = std::max(wmax, norm(w[p]));
      zmax = std::max(zmax, z[p]);
      if (z[p] < zmin) zmin = z[p], apex = p;
    }
  const double delta = 2 * kU * wmax;  // |w - (a - b)| (each component rounded once)
  if (!(zmax - zmin > 0)) return false;
  // the top points (M's face beneath the contact) and their triangle whose projection across v
  // holds the largest disc about 0 (a choice in doubles; the bounds below decide)
  V3 e1, e2;
  frame(vh, e1, e2);
  int top[16], nt = 0;
  for (int p = 0; p < 16; ++p)
    if (z[p] >= zmax - 1e-6 * (zmax - zmin)) top[nt++] = p;
  double best = 0;
  int tri[3] = {-1, -1, -1};
  for (int a = 0; a < nt; ++a)
    for (int b = a + 1; b < nt; ++b)
      for (int c = b + 1; c < nt; ++c) {
        const int t[3] = {top[a], top[b], top[c]};
        double px[3], py[3];
        for (int s = 0; s < 3; ++s) px[s] = dot(e1, w[t[s]]), py[s] = dot(e2, w[t[s]]);
        const double area = (px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]);
        if (!(area != 0)) continue;
        double r = INFINITY;
        for (int s = 0; s < 3; ++s) {
          const int s1 = (s + 1) % 3;
          const double ex = px[s1] - px[s], ey = py[s1] - py[s];
          r = std::min(r, (area > 0 ? 1 : -1) * (ex * (0 - py[s]) - ey * (0 - px[s])) / std::sqrt(ex * ex + ey * ey));
        }
        if (r > best && std::isfinite(r)) best = r, tri[0] = t[0], tri[1] = t[1], tri[2] = t[2];
      }
  if (tri[0] < 0) return false;
  const V3 &x1 = w[tri[0]], &x2 = w[tri[1]], &x3 = w[tri[2]], &x4 = w[apex];
  // u.v >= 0: rho (each side's plane along v from 0, the third point's side positive) and Z
  const V3 x[3] = {x1, x2, x3};
  double rho = INFINITY, Z = 0;
  const double vn_low = norm(v) * (1 - 3 * kU);
  for (int s = 0; s < 3; ++s) {
    const V3 &p = x[s], &p1 = x[(s + 1) % 3], &p2 = x[(s + 2) % 3];
    rho = std::min(rho, plane_distance_lower(sub(p1, p), v, p, sub(p2, p)) - 2 * alpha * norm(p) * (1 + 4 * kU));
    // -vh.p <= (-(v.p) + 4u sum |v_k p_k|) / |v|
    const double err = 4 * kU * (std::fabs(v[0] * p[0]) + std::fabs(v[1] * p[1]) + std::fabs(v[2] * p[2]));
    Z = std::max(Z, (err - dot(v, p)) / vn_low * (1 + 2 * kU) + alpha * norm(p) * (1 + 4 * kU));
  }
  // sin(theta0) >= sqrt((1 - c0)(1 + c0)) rounded down (1 - c0 exact: c0 in [1/2, 1])
  if (!(c0 >= 0.5) || !(rho > 0)) return false;
  const double s0 = std::sqrt((1 - c0) * (1 + c0) * (1 - 2 * kU)) * (1 - 2 * kU);
  if (!(rho * s0 * (1 - 2 * kU) - Z * (1 + 2 * kU) - delta >= d0 * (1 + 2 * kU))) return false;
  // u.v <= 0: a ball about q = -R vh, R a power of two from rho / 2 down
  for (double R = std::exp2(std::floor(std::log2(rho))) / 2, stop = R / 64; R >= stop; R /= 2) {
    const V3 q = mul(vh, -R);
    const double R1 = std::min({plane_distance_lower(sub(x2, x1), sub(x3, x1), sub(x1, q), sub(x4, x1)),
                                plane_distance_lower(sub(x2, x1), sub(x4, x1), sub(x1, q), sub(x3, x1)),
                                plane_distance_lower(sub(x3, x1), sub(x4, x1), sub(x1, q), sub(x2, x1)),
                                plane_distance_lower(sub(x3, x2), sub(x4, x2), sub(x2, q), sub(x1, x2))});
    if ((R1 - R * e - delta) * (1 - 2 * kU) >= d0) return true;
  }
  return false;
}

}  // namespace

namespace {

// The cap of one attempt (certify_shallow): the walk's normal in double words; cap.c0
// >= sqrt(L / B0) and cap.d0 >= sqrt(32 L), L = cap.result.lower.
struct Cap {
  ShallowResult result;
  double c0 = 1, d0 = 0;
};
// The cap about v + lo from multipliers l (parallel_multipliers), ev the evaluation there.
bool cap_at(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v, const V3& lo,
            const Evaluation& ev, const double (&l)[8], Cap& cap) {
  const double V = ev.value;
  if (!(V >= 0x1p-900 * P.scale * P.scale) || !std::isfinite(V)) return false;
  // exact: positions relative to A[0] over 2^ex, v over 2^ev, the multipliers (integers)
  long ex = LONG_MAX, ev_ = LONG_MAX;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) ex = std::min({ex, low_exponent(A[i][k]), low_exponent(B[i][k])});
  for (int k = 0; k < 3; ++k) ev_ = std::min({ev_, low_exponent(v[k]), low_exponent(lo[k])});
  if (ex == LONG_MAX || ev_ == LONG_MAX) return false;
  static thread_local Workspace w;
  for (int k = 0; k < 3; ++k) {  // V = v + lo exactly
    to_integer(A[0][k], ex, w.o[k]), to_integer(v[k], ev_, w.V[k]), to_integer(lo[k], ev_, w.y);
    w.V[k] += w.y;
  }
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      to_integer(A[i][k], ex, w.y), mpz_sub(z(w.x[i][k]), z(w.y), z(w.o[k]));
      to_integer(B[i][k], ex, w.y), mpz_sub(z(w.x[4 + i][k]), z(w.y), z(w.o[k]));
    }
  if (!parallel_multipliers(l, w)) return false;
  // K = 20 kappa (over the multipliers' unit squared), g and g.v from parallel_multipliers:
  // B0 = (g.v)^2 / (v.v 80 kappa) = 2^(2 ex) gv^2 / (4 vv K)
  for (mpz_class* y : {&w.sl, &w.sm, &w.ql, &w.qm}) *y = 0;
  for (int p = 0; p < 8; ++p) {
    mpz_add(z(p < 4 ? w.sl : w.sm), z(p < 4 ? w.sl : w.sm), z(w.M[p]));
    mpz_addmul(z(p < 4 ? w.ql : w.qm), z(w.M[p]), z(w.M[p]));
  }
  mpz_mul_ui(z(w.K), z(w.ql), 5);             // K = 5 ql - sl^2 + 5 qm - sm^2
  mpz_addmul_ui(z(w.K), z(w.qm), 5);
  mpz_submul(z(w.K), z(w.sl), z(w.sl));
  mpz_submul(z(w.K), z(w.sm), z(w.sm));
  zdot(w.vv, w.V, w.V);
  if (sgn(w.K) <= 0) return false;
  const double L = V * (1 - kShallowGap);
  // L / B0 = Lm 2^le 4 vv K / (2^(2 ex) gv^2), Lm the integer of L over 2^le
  const long le = low_exponent(L);
  to_integer(L, le, w.num);
  mpz_mul(z(w.num), z(w.num), z(w.vv));
  mpz_mul(z(w.num), z(w.num), z(w.K));
  mpz_mul_2exp(z(w.num), z(w.num), 2);
  mpz_mul(z(w.den), z(w.gv), z(w.gv));
  const long shift = le - 2 * ex;  // L / B0 = num 2^shift / den
  {
    // L <= B0: num 2^shift <= den (the shift on a copy)
    mpz_class& scaled = w.y;
    if (shift >= 0) {
      mpz_mul_2exp(z(scaled), z(w.num), static_cast<unsigned long>(shift));
      if (mpz_cmp(z(scaled), z(w.den)) > 0) return false;
    } else {
      mpz_mul_2exp(z(scaled), z(w.den), static_cast<unsigned long>(-shift));
      if (mpz_cmp(z(w.num), z(scaled)) > 0) return false;
    }
  }
  // c0 >= sqrt(L / B0): mpz_get_d_2exp truncates; the numerator rounded up, the quotient and
  // the root each rounded up
  long en = 0, ed = 0;
  const double fn = std::nextafter(mpz_get_d_2exp(&en, z(w.num)), 2.0);
  const double fd = mpz_get_d_2exp(&ed, z(w.den));
  const double ratio = std::ldexp(std::nextafter(fn / fd, 4.0), int(std::clamp(en - ed + shift, -2000L, 2000L)));
  const double c0 = std::nextafter(std::sqrt(ratio), 2.0);
  if (!(c0 < 1)) return false;
  cap.result.normal = v, cap.result.low = lo, cap.result.eval = ev, cap.result.lower = L;
  cap.c0 = c0, cap.d0 = std::sqrt(32 * L) * (1 + 4 * kU);
  return true;
}

// The walk's normal and its evaluation's multipliers; where their bound falls short, the
// plane's dual (plane_dual): v moved to the plane's minimiser, its multipliers there.
bool cap_of(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v0, Cap& cap) {
  V3 v = v0, lo{0, 0, 0};
  Evaluation ev;
  if (!find_normal(A, B, P, v, lo, ev)) return false;
  double l[8];
  multipliers_of(ev, l);
  if (cap_at(A, B, P, v, lo, ev, l, cap)) return true;
  PlaneDual d;
  if (!plane_dual(P, ev, v, d)) return false;
  for (int k = 0; k < 3; ++k) {
    const detail::dw::DW x = detail::dw::two_sum(v[k], lo[k] + d.tilt[k]);  // v + lo + tilt
    v[k] = x.hi, lo[k] = x.lo;
  }
  ev = evaluate_tight(A, B, P, v, lo);
  if (!(ev.error <= kGlobalRel)) return false;
  PlaneDual e;
  return plane_dual(P, ev, v, e) && cap_at(A, B, P, v, lo, ev, e.w, cap);
}

// The off-cap region of a cap as a half-space: u.vh <= cv covers every unit u with u.(v + lo) /
// |v + lo| <= c0 (vh's rounding and lo's angle in cap_slack).
Halfspace off_cap(const Cap& cap) {
  const V3& v = cap.result.normal;
  return {mul(v, 1 / norm(v)), (cap.c0 + cap_slack(v, cap.result.low)) * (1 + 2 * kU)};
}

// Vertices resting on edges (shallow_certificate.h, "A vertex on an edge"): multipliers on a
// vertex and an edge's ends whose g is the vertex's offset across the edge; at most
// kMaxIncidences, each bound's plane beside a cap's.
constexpr int kMaxIncidences = 6;
struct Incidence {
  V3 g{};           // g = sum l_i a_i - sum m_j b_j, rounded componentwise
  double err = 0;   // >= |g - g~| (the exact g, from expansions)
  double k80 = 0;   // >= 80 kappa
  double w[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // the multipliers (A's l, then B's m), rounded
  double werr = 0;                         // >= |w - w~| (2-norm)
};

// g rounded componentwise, with a bound on |g - g~|.
bool rounded_incidence(const detail::ExpVec& g, Incidence& out) {
  double e2 = 0;
  for (int k = 0; k < 3; ++k) {
    if (!g.x[k].ok) return false;
    const detail::Expansion c = detail::compressed(g.x[k]);
    const detail::Approx r = detail::approx_of(c);
    out.g[k] = r.v;
    e2 += r.err * r.err;
  }
  out.err = std::sqrt(e2) * (1 + 4 * kU) + 0x1p-1074;
  return nonzero(out.g) && std::isfinite(out.err);
}

// A vertex W of one side on the edge E0 E1 of the other (e = E1 - E0, w = W - E0, exact): the
// multipliers e.e - w.e and w.e on the edge's ends, e.e on the vertex (w.e / e.e its exact
// fraction along the edge, in (0, 1)), so that g = +-((w.e) e - (e.e) w) = -+(e.e) w_perp: the
// vertex's offset across the edge, exactly (the sign: A's minus B's). 80 kappa =
// 20 ((e.e - w.e)^2 + (w.e)^2 + 3/5 (e.e)^2), rounded up from the three values' bounds. The
// multipliers rounded, at the ends' and the vertex's slots (0..3: A's, 4..7: B's).
bool vertex_on_edge(const Vec3d& E0, const Vec3d& E1, const Vec3d& W, bool edge_on_A, const int (&slot)[3],
                    Incidence& out) {
  using namespace detail;
  const ExpVec e = difference(E1, E0), w = difference(W, E0);
  const Expansion ee = compressed(dot(e, e)), we = compressed(dot(w, e));
  if (!ee.ok || !we.ok) return false;
  const Expansion rest = compressed(difference(ee, we));  // e.e - w.e
  if (we.sign() <= 0 || rest.sign() <= 0 || !rest.ok) return false;
  ExpVec g = difference(scaled(e, we), scaled(w, ee));
  if (!edge_on_A) g = negated(g);
  if (!rounded_incidence(g, out)) return false;
  auto up = [](const Expansion& x) { const Approx a = approx_of(x); return std::fabs(a.v) + a.err; };
  const double l1 = up(rest), l2 = up(we), m = up(ee);
  out.k80 = 20 * (l1 * l1 + l2 * l2 + 0.6 * m * m) * (1 + 16 * kU);
  const Approx w0 = approx_of(rest), w1 = approx_of(we), w2 = approx_of(ee);
  out.w[slot[0]] = w0.v, out.w[slot[1]] = w1.v, out.w[slot[2]] = w2.v;
  out.werr = (w0.err + w1.err + w2.err) * (1 + 4 * kU);
  return std::isfinite(out.k80) && out.k80 > 0 && std::isfinite(out.werr);
}

// The vertices of one side within 2^-24 of the pair's scale of an edge of the other and farther
// than that from both its ends (a guess of where the minimiser's multipliers are: any
// multipliers bound). A vertex that near an end rests on a vertex: there the multiplier w.e
// is about the depth, the plane's g as small, and its test a wasted clip (five-tetrahedra
// blocks resting on columns: up to six such guesses a pair, each tried from every start).
int incidences(const TetVertices& A, const TetVertices& B, const Problem& P, Incidence (&out)[kMaxIncidences]) {
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  if (!detail::in_exact_range(A, B)) return 0;
  const double near = 0x1p-24 * P.scale;
  int k = 0;
  for (int side = 0; side < 2; ++side) {
    const V3* E = side == 0 ? P.relA : P.relB;  // the edge's tetrahedron
    const V3* W = side == 0 ? P.relB : P.relA;  // the vertex's
    const TetVertices& TE = side == 0 ? A : B;
    const TetVertices& TW = side == 0 ? B : A;
    for (const auto& e : kEdge) {
      const V3 d = sub(E[e[1]], E[e[0]]);
      const double dd = dot(d, d);
      if (!(dd > 0)) continue;
      const double end = near / std::sqrt(dd);  // (the fraction of the edge that is `near`)
      for (int j = 0; j < 4 && k < kMaxIncidences; ++j) {
        const V3 w = sub(W[j], E[e[0]]);
        const double t = dot(w, d) / dd;
        if (!(t > end && t < 1 - end)) continue;
        const V3 off = sub(w, mul(d, t));
        if (!(std::fabs(off[0]) <= near && std::fabs(off[1]) <= near && std::fabs(off[2]) <= near)) continue;
        const int edge = side == 0 ? 0 : 4, vertex = side == 0 ? 4 : 0;
        const int slot[3] = {edge + e[0], edge + e[1], vertex + j};
        if (vertex_on_edge(TE[e[0]], TE[e[1]], TW[j], side == 0, slot, out[k])) ++k;
      }
    }
  }
  return k;
}

// The incidence's plane for the bound L: relaxed(u) >= (u.g)^2 / (80 kappa) >= L where u.g >=
// sqrt(80 kappa L), so where u.g~ >= that + err (unit u); the uncovered side u.g~ <= c.
Halfspace incidence_plane(const Incidence& x, double L) {
  return {x.g, (std::sqrt(x.k80 * L) * (1 + 4 * kU) + x.err) * (1 + 4 * kU)};
}

// Two incidences' multipliers together, w_i + r w_j (r > 0): again multipliers >= 0 with sum l =
// sum m, so their bound holds too (shallow_certificate.h, (1)), and it is sharper than either
// alone where the minimiser's own multipliers mix them: an edge resting on a collinear edge (a
// grid placed up to a rounding against its copy moved along an axis) has a vertex of each on
// the other's edge, and the multipliers that balance the four vertices' moments along the line
// (g across it) are these two incidences' combinations; across the whole arc of directions
// about the line where the overlap is as small as the depth, the one best at the cap's normal
// bounds relaxed above L (on a Kuhn pair: 1.000024 L at the cap's rim, 1.48 L a quarter of
// the arc away). r, the best for the direction d: (d.g)^2 / kappa, with g = g_i + r g_j and
// kappa = c0 + 2 r c1 + r^2 c2 (the multipliers' form, below), is largest at
// r = (a c1 - b c0) / (b c1 - a c2), a = d.g_i, b = d.g_j (computed: any r > 0 gives a valid
// bound). g~ = g~_i + r g~_j within err_i + r err_j + 2u sum_k (|g~_i,k| + r |g~_j,k|). The
// multipliers w~ = w~_i + r w~_j within werr = werr_i + r werr_j + 4u |w~| (each sum's
// rounding, 2u (|w~_i| + r |w~_j|) <= 4u |w~|, all terms >= 0); 80 kappa = 20 Q(w) with Q(x) =
// x^T M x, M = I - J/5 on each side (0 <= M <= I): Q(w) <= Q(w~) + 2 |w~| werr + werr^2, and the
// computed Q(w~) (sums of squares and of the multipliers, each within a few u of ql + qm,
// which |w~|^2 is) within 32u |w~|^2.
// x^T M y, M = I - J/5 on each side (the multipliers' form: kappa = Q(w) / 4, Q(w) = w^T M w)
double multiplier_form(const double (&x)[8], const double (&y)[8]) {
  double q = 0;
  for (int s = 0; s < 8; s += 4) {
    double sx = 0, sy = 0;
    for (int p = s; p < s + 4; ++p) q += x[p] * y[p], sx += x[p], sy += y[p];
    q -= sx * sy / 5;
  }
  return q;
}
bool combined_incidence(const Incidence& xi, const Incidence& xj, double r, Incidence& out) {
  if (!(r > 0) || !std::isfinite(r)) return false;
  double gm = 0;
  for (int k = 0; k < 3; ++k) out.g[k] = xi.g[k] + r * xj.g[k], gm += std::fabs(xi.g[k]) + r * std::fabs(xj.g[k]);
  out.err = (xi.err + r * xj.err + 2 * kU * gm) * (1 + 4 * kU);
  double ww = 0;
  for (int p = 0; p < 8; ++p) out.w[p] = xi.w[p] + r * xj.w[p], ww += out.w[p] * out.w[p];
  const double n = std::sqrt(ww) * (1 + 4 * kU);
  out.werr = (xi.werr + r * xj.werr + 4 * kU * n) * (1 + 4 * kU);
  out.k80 = 20 * (multiplier_form(out.w, out.w) + 2 * n * out.werr + out.werr * out.werr + 32 * kU * ww) * (1 + 8 * kU);
  return nonzero(out.g) && std::isfinite(out.err) && std::isfinite(out.k80) && out.k80 > 0;
}

// The region off the given planes (a cap's, or several caps') covered with the incidences'
// planes beside them: one incidence at a time, then all of them (fewer planes keep the clip's
// points few), then each two of them combined (combined_incidence), best at each given plane's
// direction (a cap's normal).
bool covered_with_incidences(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds,
                             const Halfspace* given, int k, double L, double d0) {
  Incidence x[kMaxIncidences];
  const int m = incidences(A, B, P, x);
  constexpr int kRoom = 16;
  if (m == 0 || k + m > kRoom) return false;
  Halfspace planes[kRoom];
  std::copy(given, given + k, planes);
  for (int i = 0; i < m; ++i) {
    planes[k] = incidence_plane(x[i], L);
    if (polytope_inside_ball(bounds, planes, k + 1, d0)) return true;
  }
  for (int i = 0; i < m; ++i) planes[k + i] = incidence_plane(x[i], L);
  if (m > 1 && polytope_inside_ball(bounds, planes, k + m, d0)) return true;
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j) {
      const double c0 = multiplier_form(x[i].w, x[i].w), c1 = multiplier_form(x[i].w, x[j].w),
                   c2 = multiplier_form(x[j].w, x[j].w);
      int n = k;
      for (int t = 0; t < k && n < kRoom; ++t) {
        const double a = dot(given[t].d, x[i].g), b = dot(given[t].d, x[j].g);
        Incidence c;
        if (combined_incidence(x[i], x[j], (a * c1 - b * c0) / (b * c1 - a * c2), c)) planes[n++] = incidence_plane(c, L);
      }
      if (n > k && polytope_inside_ball(bounds, planes, n, d0)) return true;
    }
  return false;
}

// The mean offset d = (a + a2 - b - b2) / 2 of A's two vertices highest and B's two lowest along
// an evaluation's normal (the contact's vertices at its plane), for which relaxed(u) >=
// (u.d)^2 / 12 wherever u.d >= 0 (lone_pair_certificate.h, "Edge pairs": any two vertices a
// side, the relaxed QP kept to their four constraints). Rounded: d~ = ((a - b) + (a2 - b2)) / 2
// per component, within u (|a_k - b_k| + |a2_k - b2_k|) of d_k (two differences and a sum, each
// rounded once; the halving exact), so |u.(d~ - d)| <= err = the sum of those over k (unit u),
// taken with room (3u). False where an evaluation's heights are not finite.
bool active_offset(const TetVertices& A, const TetVertices& B, const Evaluation& ev, V3& d, double& err) {
  int a[4] = {0, 1, 2, 3}, b[4] = {0, 1, 2, 3};
  for (int i = 0; i < 4; ++i)
    if (!std::isfinite(ev.hA[i]) || !std::isfinite(ev.hB[i])) return false;
  std::sort(a, a + 4, [&](int x, int y) { return ev.hA[x] > ev.hA[y] || (ev.hA[x] == ev.hA[y] && x < y); });
  std::sort(b, b + 4, [&](int x, int y) { return ev.hB[x] < ev.hB[y] || (ev.hB[x] == ev.hB[y] && x < y); });
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double x = A[a[0]][k] - B[b[0]][k], y = A[a[1]][k] - B[b[1]][k];
    d[k] = (x + y) * 0.5;
    sum += std::fabs(x) + std::fabs(y);
  }
  err = 3 * kU * sum;
  return nonzero(d) && std::isfinite(err);
}

// Minimisers tied at a vertex of M (several facets through it at the same distance from 0:
// blocks cut into five tetrahedra a cube whose cuts alternate across the contact, resting on
// each other's columns, where a vertex rests on a vertex and the overlap is least along two to
// four facet normals of M, ~1e-8 apart in value): one cap does not cover the others, where
// D(u) is the depth itself. A cap about each: the facet directions (either orientation) whose
// point d0 n / D(n) lies outside the ball and off every cap so far, the least deep first, each
// the start of a walk to its own minimiser (whose cap must then hold that direction); then,
// with L the least of the caps' bounds, every unit u off all of them has D(u) >= sqrt(32 L)
// (polytope_inside_ball with their planes): relaxed(u) >= L_i >= L on cap i, >= D(u)^2 / 32
// >= L off them. The least cap's value is reported, its own bound being L.
constexpr int kMaxCaps = 6;
bool tied_caps(const TetVertices& A, const TetVertices& B, const Problem& P, FacetBounds& bounds, const Cap& first,
               const V3* edge_d, ShallowResult& out) {
  if (!bounds.get()) return false;
  Cap caps[kMaxCaps];
  Halfspace planes[kMaxCaps + 1];
  caps[0] = first, planes[0] = off_cap(first);
  int k = 1, least = 0;
  bool every = true;  // every direction outside the ball off the caps has a cap of its own
  auto off_caps = [&](const V3& p) {
    const double np = norm(p);
    for (int i = 0; i < k; ++i)
      if (dot(p, planes[i].d) > planes[i].c * np) return false;
    return true;
  };
  for (;;) {
    const double d0 = caps[least].d0;
    V3 start{0, 0, 0};
    double far = 1 - 0x1p-30;  // (|p|^2 beyond the ball less the test's margin; the largest first)
    for (const DirectionBounds& x : bounds.dirs()) {
      if (x.zero) continue;
      for (const double s : {1.0, -1.0}) {
        const V3 p = mul(x.n, s * d0 / (s > 0 ? x.plus_low : x.minus_low));
        const double pp = dot(p, p);
        if (pp > far && pp < INFINITY && off_caps(p)) far = pp, start = p;
      }
    }
    if (!nonzero(start)) break;
    // (a walk that finds no cap, or leaves its start's direction: that direction is left to the
    // mean offset's plane below)
    if (k == kMaxCaps || !cap_of(A, B, P, start, caps[k])) {
      every = false;
      break;
    }
    planes[k] = off_cap(caps[k]);
    ++k;
    if (caps[k - 1].result.lower < caps[least].result.lower) least = k - 1;
    if (off_caps(start)) {
      every = false;
      break;
    }
  }
  if (k == 1) return false;  // (one cap, beside each plane: attempt's tests)
  const ShallowResult& r = caps[least].result;
  if (every && (polytope_inside_ball(bounds, planes, k, caps[least].d0) ||
                covered_with_incidences(A, B, P, bounds, planes, k, r.lower, caps[least].d0))) {
    out = r;
    return true;
  }
  // With a mean offset's plane (relaxed(u) >= (u.d)^2 / 12 >= L where u.d >= sqrt(12 L)): the
  // edge pair's, as attempt's (two caps on either side of an edge resting on a collinear edge,
  // the overlap between them as small as the depth), else each cap's contact vertices'
  // (active_offset: a face or an edge resting on a face, the overlap between the caps below
  // sqrt(32 L)). That plane first: beyond it lie many of the points, and the last plane's
  // crossings number the points kept times those beyond it, few beyond a cap.
  std::rotate(planes, planes + k, planes + k + 1);
  const double c = std::sqrt(12 * r.lower) * (1 + 4 * kU);
  if (edge_d) {
    planes[0] = {*edge_d, c};
    if (!polytope_inside_ball(bounds, planes, k + 1, caps[least].d0)) return false;
    out = r;
    return true;
  }
  for (int i = 0; i < k; ++i) {
    V3 d;
    double err = 0;
    if (!active_offset(A, B, caps[(least + i) % k].result.eval, d, err)) continue;
    planes[0] = {d, (c + err) * (1 + 2 * kU)};
    if (polytope_inside_ball(bounds, planes, k + 1, caps[least].d0)) {
      out = r;
      return true;
    }
  }
  return false;
}

// How an attempt ended: certified; no cap (the walk or its multipliers failed: B0 below L, no
// regular triple); or a cap whose off-cap region the overlap tests did not cover.
enum class Attempt { Certified, NoCap, NotCovered };

// One attempt (certify_shallow): the cap, then the overlap off it.
Attempt attempt(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v0,
                ShallowResult& out, FacetBounds* bounds, const V3* edge_d) {
  Cap cap;
  if (!cap_of(A, B, P, v0, cap)) return Attempt::NoCap;
  const ShallowResult& r = cap.result;
  if (!overlap_off_cap(A, B, r.normal, r.low, cap.c0, cap.d0)) {
    if (!bounds) return Attempt::NotCovered;
    const Halfspace h = off_cap(cap);
    // (a mean offset's plane: relaxed(u) >= (u.d)^2 / 12 >= L where u.d >= sqrt(12 L), rounded
    // up; the edge pair's, else the cap's contact vertices', its rounding added: tied_caps)
    const double c = std::sqrt(12 * r.lower) * (1 + 4 * kU);
    V3 d;
    double err = 0;
    if (polytope_inside_ball(*bounds, h.d, h.c, cap.d0) ||
        (edge_d && polytope_inside_ball(*bounds, h.d, h.c, *edge_d, c, cap.d0)) ||
        (!edge_d && active_offset(A, B, r.eval, d, err) &&
         polytope_inside_ball(*bounds, h.d, h.c, d, (c + err) * (1 + 2 * kU), cap.d0))) {
      out = r;
      return Attempt::Certified;
    }
    if (covered_with_incidences(A, B, P, *bounds, &h, 1, r.lower, cap.d0)) {
      out = r;
      return Attempt::Certified;
    }
    return tied_caps(A, B, P, *bounds, cap, edge_d, out) ? Attempt::Certified : Attempt::NotCovered;
  }
  out = r;
  return Attempt::Certified;
}

}  // namespace

bool certify_shallow(const TetVertices& A, const TetVertices& B, const Problem& P, const V3& v0, ShallowResult& out,
                     FacetBounds* bounds, const V3* edge_d) {
  if (!nonzero(v0) || !(P.scale >= 0x1p-100 && P.scale <= 0x1p100)) return false;
  // Where the start gives no cap, again from the start scaled to unit length, then to three
  // units: the same direction, other roundings. The walk's normal and the multipliers moved on
  // it follow the start's bits, and at a vertex resting 1e-10 deep those can leave the dual bound
  // B0 below L by less than the gap (Kuhn blocks on columns, 768 pairs: 46 certified from the
  // start at unit length, 50 more at three units). Not where a cap was found but the overlap off
  // it was not covered: the other roundings move the walk's normal and the cap by about a
  // rounding, while what the coverage misses is the overlap's own shape off the cap (a vertex
  // resting on a vertex or an edge, the overlap there as small as the depth); of 16,500 such
  // retries on five-tetrahedra blocks resting on columns, Kuhn grids against copies shifted a
  // quarter cell along (1, 1, 1) or half a cell along x and y, and a Gmsh ball against its copy
  // moved by 1e-9, none was certified.
  Attempt a = attempt(A, B, P, v0, out, bounds, edge_d);
  const V3 u = mul(v0, 1 / norm(v0));
  for (const double scale : {1.0, 3.0}) {
    if (a != Attempt::NoCap) break;
    const V3 w = mul(u, scale);
    if (w != v0) a = attempt(A, B, P, w, out, bounds, edge_d);
  }
  return a == Attempt::Certified;
}

}  // namespace pdd::fast::global
