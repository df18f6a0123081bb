// suspect_proof.cpp — see suspect_proof.h for the argument.
#include "global/suspect_proof.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <vector>

#include "global/eigen_polish.h"
#include "global/integer_normals.h"
#include "global/integer_shift.h"

namespace pdd::fast::global {
namespace {

// The number of eigenvalues of the symmetric M below t, exactly. N = M - tI has the
// characteristic polynomial x^3 - tr(N) x^2 + c1 x - det(N) (c1: the sum of N's principal 2x2
// minors); its roots are N's eigenvalues, all real, so by Descartes' rule (exact for real-rooted
// polynomials, zero coefficients skipped) N's negative eigenvalues, the positive roots of
// -(x^3 + tr(N) x^2 + c1 x + det(N)), number the sign changes of (1, tr N, c1, det N).
// An eigenvalue equal to t is not counted (it is not below t) unless `or_equal`: then each
// eigenvalue equal to t (a zero root of the polynomial: its trailing zero coefficients) is.
int eigenvalues_below(const IntegerMatrix& M, const detail::Q& t, bool or_equal = false) {
  // (explicit mpz calls on per-thread integers: called tens of times a suspect, on integers of
  // thousands of bits, where each expression's temporaries would be allocated and freed)
  struct Scratch {
    mpz_class a[3][3], tr, c1, det, u;
  };
  static thread_local Scratch w;
  auto z = [](mpz_class& x) { return x.get_mpz_t(); };
  mpz_class(&a)[3][3] = w.a;  // L q (M - t I), L q > 0 (integer_shift.h): the same signs
  integer_shift(M, t, a);
  mpz_add(z(w.tr), z(a[0][0]), z(a[1][1]));
  mpz_add(z(w.tr), z(w.tr), z(a[2][2]));
  // c1: the principal 2x2 minors; det by the first row's cofactors (the last minor is one)
  mpz_mul(z(w.c1), z(a[0][0]), z(a[1][1]));
  mpz_submul(z(w.c1), z(a[0][1]), z(a[1][0]));
  mpz_addmul(z(w.c1), z(a[0][0]), z(a[2][2]));
  mpz_submul(z(w.c1), z(a[0][2]), z(a[2][0]));
  mpz_mul(z(w.u), z(a[1][1]), z(a[2][2]));
  mpz_submul(z(w.u), z(a[1][2]), z(a[2][1]));
  mpz_add(z(w.c1), z(w.c1), z(w.u));
  mpz_mul(z(w.det), z(a[0][0]), z(w.u));
  mpz_mul(z(w.u), z(a[1][0]), z(a[2][2]));
  mpz_submul(z(w.u), z(a[1][2]), z(a[2][0]));
  mpz_submul(z(w.det), z(a[0][1]), z(w.u));
  mpz_mul(z(w.u), z(a[1][0]), z(a[2][1]));
  mpz_submul(z(w.u), z(a[1][1]), z(a[2][0]));
  mpz_addmul(z(w.det), z(a[0][2]), z(w.u));
  int changes = 0, last = 1;
  for (const mpz_class* c : {&w.tr, &w.c1, &w.det}) {
    const int sg = sgn(*c);
    if (sg == 0) continue;
    if (sg != last) ++changes;
    last = sg;
  }
  if (or_equal)
    for (const mpz_class* c : {&w.det, &w.c1, &w.tr}) {
      if (sgn(*c) != 0) break;
      ++changes;
    }
  return changes;
}

// One suspect in the window (above): true when its eigenvalue is proved not to be a stationary
// value of G (both unit eigenvectors outside the cone); else lo (a proved lower bound of the
// eigenvalue, at least `bottom`) and the offers, as above.
// The eigenvector x: Eigen's on h rounded (scaled by a power of two), polished by inverse
// iteration on the exact h (refine: each step rounded componentwise to doubles) shifted by the
// exact Rayleigh quotient of Eigen's; then y = one exact step more (below). The proof holds
// for any non-zero vector y (x, tried first as it is cheap, or y): with rho = y^T h y / y^T y
// and R2 = |h y - rho y|^2 / y^T y (exact rationals), and g > 0 such that h has exactly one
// eigenvalue, the k-th, in (rho - g, rho + g) (counted exactly by eigenvalues_below, with multiplicity: so that
// eigenvalue mu is simple and every other lambda_j has |lambda_j - rho| >= g). Write y / |y| =
// sum c_j e_j in h's orthonormal eigenvectors, sum c_j^2 = 1. Then R2 = sum c_j^2 (lambda_j -
// rho)^2 >= g^2 sum_{j != k} c_j^2 = g^2 sin^2 t (t the angle between y and e = +-e_k chosen
// with e.y >= 0, t <= pi/2), so sin^2 t <= s2 = R2 / g^2 (the sin theta theorem).
// (a) Cone: |y/|y| - e|^2 = 2 - 2 cos t <= 2 sin^2 t for t <= pi/2, so |l.y/|y| - l.e| <=
// |l| sqrt(2 s2) for each condition l: when sign l.y < 0 and (l.y)^2 > 2 |l|^2 |y|^2 s2,
// sign l.e < 0 and e is outside the cone; when sign l.y > 0 and the same, -e is. Both outside
// (the only unit eigenvectors of the simple mu): not a stationary value of its piece, dropped.
// (b) Bound: sum c_j^2 (lambda_j - rho) = 0 (rho's definition), so c_k^2 |mu - rho| =
// |sum_{j != k} c_j^2 (lambda_j - rho)| <= sum_{j != k} c_j^2 (lambda_j - rho)^2 / g <= R2 / g,
// and c_k^2 = cos^2 t >= 1 - s2: mu >= rho - R2 / (g (1 - s2)) when s2 < 1. lo is that,
// checked once more by counting (#at_or_below(lo) <= k, i.e. mu > lo), when above `bottom`.
// Where a step fails (no gap, s2 >= 1, a count disagrees), lo = bottom: still a lower bound
// (the eigenvalue lies in the window), which no offer meets unless its value is as low as the
// floor (0, or ~PD^2 / 32 <= G): in practice the pair is then rejected. The offers are tried
// in order of cost (x itself; the 26 triples one ulp away; integer normals along y) until q
// meets lo to kGlobalRel (below).
// represent_suspect's exact arithmetic on one suspect (its argument above): the eigenvector x
// (Eigen's, polished), y (one exact step more), the Rayleigh quotient rho of the last vector
// given to rayleigh() with R2 = |h q - rho q|^2 / q.q and q.q, and what settle() proved.
// Every vector is kept as integers, a positive multiple of the direction it stands for (h =
// a / L over the suspect's IntegerMatrix): everything above depends on a vector only through
// its direction and orientation (rho, R2 and the bound are ratios of degree 0 in it, each
// condition's test is of degree 2 on both sides, the shortened vector is v / |v_m|, and an
// adjugate of a positive multiple of h - t I is a positive multiple of adj(h - t I)), so the
// integers give the rationals' results while no product is reduced to lowest terms (on
// rationals, a gcd after every operation: ~60% of this proof's time on contacts made by
// rounding, callgrind). rho and R2 are rationals, each reduced once.
class SuspectProof {
  using Q = detail::Q;
  using Z = mpz_class;
  using ZV = Z[3];
  static mpz_ptr z(Z& x) { return x.get_mpz_t(); }
  static mpz_srcptr z(const Z& x) { return x.get_mpz_t(); }

 public:
  explicit SuspectProof(const Best::Suspect& s) : s(s) {}

  // h (exact), its double image H = h 2^-pe and Eigen's eigenpairs of H; the conditions' squared
  // norms; false when h = 0 or the solver fails.
  bool setup() {
    pe = LONG_MIN;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pe = std::max(pe, detail::log2_estimate(s.h[r][c]));
    if (pe == LONG_MIN) return false;  // h = 0 (no eigenvalue in the window: not reached)
    Eigen::Matrix3d H;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        Q x = s.h[r][c];
        detail::scale_pow2(x, -pe);
        H(r, c) = x.get_d();
      }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
    if (eig.info() != Eigen::Success) return false;
    mu_d = eig.eigenvalues();  // in units of 2^pe
    e0 = eig.eigenvectors().col(s.k);
    for (int c = 0; c < 8; ++c) {
      for (int k = 0; k < 3; ++k) li[c][k] = s.l[c][k];
      dot(ll[c], li[c], li[c]);
    }
    return true;
  }

  // x: Eigen's vector polished by refine, shifted by its exact Rayleigh quotient; then rho and
  // R2 of x. false when a vector vanishes.
  bool polish() {
    if (!integers_of(V3{e0(0), e0(1), e0(2)}, qx)) return false;
    rayleigh(qx);
    x = refine(s.hi, V3{e0(0), e0(1), e0(2)}, in_units(rho), pe);
    if (!integers_of(x, qx)) return false;
    rayleigh(qx);
    return true;
  }

  // The Rayleigh quotient rho of q, R2 = |h q - rho q|^2 / q.q and q.q, exactly: with h = a / L,
  // t = q.(a q), rho = t / (L q.q) and h q - rho q = (q.q a q - t q) / (L q.q), so R2 =
  // |q.q a q - t q|^2 / (L^2 (q.q)^3).
  void rayleigh(const ZV& q) {
    ZV aq;
    for (int r = 0; r < 3; ++r) {
      mpz_mul(z(aq[r]), z(s.hi.a[r][0]), z(q[0]));
      mpz_addmul(z(aq[r]), z(s.hi.a[r][1]), z(q[1]));
      mpz_addmul(z(aq[r]), z(s.hi.a[r][2]), z(q[2]));
    }
    dot(qq, q, q);
    Z t;
    dot(t, q, aq);
    Z den = s.hi.L * qq;
    mpq_set_num(rho.get_mpq_t(), z(t));
    mpq_set_den(rho.get_mpq_t(), z(den));
    rho.canonicalize();
    Z res, sum = 0;
    for (int r = 0; r < 3; ++r) {
      mpz_mul(z(res), z(qq), z(aq[r]));
      mpz_submul(z(res), z(t), z(q[r]));
      mpz_addmul(z(sum), z(res), z(res));
    }
    mpz_mul(z(den), z(s.hi.L), z(qq));  // L^2 (q.q)^3
    mpz_mul(z(den), z(den), z(den));
    mpz_mul(z(den), z(den), z(qq));
    mpq_set_num(R2.get_mpq_t(), z(sum));
    mpq_set_den(R2.get_mpq_t(), z(den));
    R2.canonicalize();
  }

  // (a) and (b) above for the vector q of the last rayleigh(): which orientations are proved
  // outside the cone (excluded_pos, excluded_neg), and the bound rho - R2 / (g (1 - s2));
  // false where g or s2 fails (gap()). A condition's test (l.q)^2 > 2 |l|^2 q.q s2 with s2 =
  // n / d: (l.q)^2 d > 2 |l|^2 q.q n.
  bool settle(const ZV& q) {
    excluded_pos = excluded_neg = false;
    undecided = 0;
    Q g;
    if (!gap(g)) return false;
    const Q s2 = R2 / (g * g);
    if (!(s2 < 1)) return false;
    Z p, left, right;
    Z rq = qq * s2.get_num();  // q.q n
    mpz_mul_2exp(z(rq), z(rq), 1);
    for (int c = 0; c < 8; ++c) {
      dot(p, li[c], q);  // (the condition's sign is in li)
      mpz_mul(z(left), z(p), z(p));
      mpz_mul(z(left), z(left), s2.get_den_mpz_t());
      mpz_mul(z(right), z(ll[c]), z(rq));
      if (mpz_cmp(z(left), z(right)) > 0) (sgn(p) < 0 ? excluded_pos : excluded_neg) = true;
      else if (sgn(p) != 0) ++undecided;
    }
    bound = rho - R2 / (g * (1 - s2));
    return true;
  }
  bool excluded() const { return excluded_pos && excluded_neg; }
  // settle(): the conditions l with l.y != 0 whose sign at the eigenvector it left open (a
  // vector nearer the eigenvector, smaller s2, may decide them).
  int undecided = 0;
  // lo within 2^-40 of the last Rayleigh quotient (the bound as tight as the contract needs).
  bool tight(const Q& lo) const {
    Q slack = rho;
    detail::scale_pow2(slack, -40);
    return rho - lo <= slack;
  }

  // g > 0 with exactly one eigenvalue of h, the k-th, in (rho - g, rho + g), counted exactly;
  // false when no guess passes. Guesses: half the distance from rho to the solver's nearest
  // other eigenvalue; then |rho| 2^-j, j = 1..kGapHalvings (the solver's small eigenvalues are
  // its own rounding, ~u |H|, where an eigenvalue rho ~1e-31 |H| lies just above a zero one,
  // or beside another as small: a contact made by rounding, the piece's two or three active
  // vertices giving H a structural zero, or two nearly so).
  static constexpr int kGapHalvings = 8;
  bool gap(Q& g) const {
    const double rho_d = in_units(rho);
    double gap_d = INFINITY;
    for (int j = 0; j < 3; ++j)
      if (j != s.k) gap_d = std::min(gap_d, std::fabs(mu_d(j) - rho_d));
    double guesses[1 + kGapHalvings] = {gap_d / 2};
    for (int j = 1; j <= kGapHalvings; ++j) guesses[j] = std::ldexp(std::fabs(rho_d), -j);
    for (const double guess : guesses) {
      if (!(guess > 0) || !std::isfinite(guess)) continue;  // (no gap, or rho underflowed)
      g = Q(guess);
      detail::scale_pow2(g, pe);
      if (eigenvalues_below(s.hi, rho - g, true) == s.k && eigenvalues_below(s.hi, rho + g) == s.k + 1) return true;
    }
    return false;
  }

  // y = adj(h - rho I) x: one more step of inverse iteration, exact, shifted by x's Rayleigh
  // quotient. It damps x's components along the other eigenvectors by |mu - rho| /
  // |lambda_j - rho| (rho is within ~|H| u^2 of mu), so y's direction is far more accurate than
  // x's (x is rounded to doubles: its Rayleigh quotient, and the bound from it, would miss mu
  // by ~|H| u^2, not small beside a depth of 1e-26 |H|). Oriented as x. Then rho and R2 of y.
  void exact_step() { step_from(qx); }

  // One more step from y (shortened: its components grow with every exact step), shifted by
  // y's Rayleigh quotient: where mu lies next to an eigenvalue closer than |H| u^2 (a zero one
  // beside mu ~1e-33 |H|), x's quotient is no shift near mu (measured: 4 mu) and one step damps
  // the neighbour's component by a factor ~0.8 only; each further step is a Rayleigh quotient
  // iteration step (cubic).
  void next_step() {
    ZV v;
    shortened(y, v);
    rayleigh(v);
    step_from(v);
  }

  // Where that iteration heads for a neighbour (two eigenvalues within ~|H| u^2 of each other,
  // a zero one and mu ~1e-33 |H|: the solver's vector is any mix of the two, or exactly the
  // zero one's, and the quotients converge to whichever dominates), mu is located by exact
  // counts instead: a power of two t_lo = 2^e with #at_or_below(t_lo) <= k < #below(2 t_lo)
  // (t_hi = 2 t_lo), e found by bisection on [pe - 1100, pe + 3] (h's entries are below 2^(pe + 1),
  // its eigenvalues below 2^(pe + 3); the window's floor is far above 2^(pe - 1100) in this
  // class), then kBisections halvings of [t_lo, t_hi]. With sigma at the middle, the column of
  // adj(h - sigma I) (= det (h - sigma I)^-1) of largest norm is y: each column is that inverse
  // applied to a unit vector, which amplifies its component along mu's eigenvector by 1 / |mu -
  // sigma| (>= 2^kBisections / mu) against 1 / |lambda_j - sigma| for the others; one of the
  // three unit vectors has a component along it. (Not from x: an x that is exactly another
  // eigenvector stays one.) false where the ends' counts do not bracket mu.
  static constexpr int kBisections = 12;
  bool locate_and_step() {
    auto pow2 = [](long e) {
      Q t(1);
      detail::scale_pow2(t, e);
      return t;
    };
    long lo_e = pe - 1100, hi_e = pe + 3;  // #at_or_below(2^lo_e) <= k < #below(2^hi_e)
    if (eigenvalues_below(s.hi, pow2(lo_e), true) > s.k || eigenvalues_below(s.hi, pow2(hi_e)) <= s.k) return false;
    while (hi_e - lo_e > 1) {
      const long mid = lo_e + (hi_e - lo_e) / 2;
      (eigenvalues_below(s.hi, pow2(mid)) > s.k ? hi_e : lo_e) = mid;
    }
    Q lo_t = pow2(lo_e), hi = pow2(hi_e);
    for (int i = 0; i < kBisections; ++i) {
      const Q mid = (lo_t + hi) / 2;
      (eigenvalues_below(s.hi, mid) > s.k ? hi : lo_t) = mid;
    }
    Z adj[3][3];
    adjugate_shifted((lo_t + hi) / 2, adj);
    int best_c = -1;
    Z best_norm, norm;
    for (int c = 0; c < 3; ++c) {
      mpz_mul(z(norm), z(adj[0][c]), z(adj[0][c]));
      mpz_addmul(z(norm), z(adj[1][c]), z(adj[1][c]));
      mpz_addmul(z(norm), z(adj[2][c]), z(adj[2][c]));
      if (best_c < 0 || norm > best_norm) best_c = c, best_norm = norm;
    }
    if (sgn(best_norm) == 0) return false;
    for (int r = 0; r < 3; ++r) y[r] = adj[r][best_c];
    rayleigh(y);
    return true;
  }

  // adj(m) for m = L q (h - t I) (integer_shift.h, t = p / q: a positive multiple of h - t I,
  // whose adjugate is then a positive multiple of adj(h - t I)); m symmetric: cofactors.
  void adjugate_shifted(const Q& t, Z (&adj)[3][3]) const {
    Z m[3][3];
    integer_shift(s.hi, t, m);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        mpz_mul(z(adj[r][c]), z(m[r1][c1]), z(m[r2][c2]));  // cofactor (c, r)
        mpz_submul(z(adj[r][c]), z(m[r1][c2]), z(m[r2][c1]));
      }
  }

  // y = adj(h - rho I) v, rho the Rayleigh quotient of the last rayleigh(); oriented as v (v
  // itself when orthogonal to adj's range); then rho and R2 of y.
  void step_from(const ZV& v) {
    Z adj[3][3];
    adjugate_shifted(rho, adj);
    ZV w;
    for (int r = 0; r < 3; ++r) {
      mpz_mul(z(w[r]), z(adj[r][0]), z(v[0]));
      mpz_addmul(z(w[r]), z(adj[r][1]), z(v[1]));
      mpz_addmul(z(w[r]), z(adj[r][2]), z(v[2]));
    }
    Z wv;
    dot(wv, w, v);
    for (int c = 0; c < 3; ++c) {
      if (sgn(wv) == 0) y[c] = v[c];
      else if (sgn(wv) < 0) mpz_neg(z(y[c]), z(w[c]));
      else y[c] = w[c];
    }
    rayleigh(y);
  }

  // v's direction as integers of at most kShortBits bits: v_c 2^b / |v_m| rounded down, v_m the
  // largest component, b = kShortBits - 1 (the largest is then exactly +-2^b); the angle to v
  // is below sqrt(2) 2^-b (~1e-77). Every proof above holds for any non-zero vector.
  static constexpr int kShortBits = 256;
  static void shortened(const ZV& v, ZV& out) {
    int m = 0;
    for (int c = 1; c < 3; ++c)
      if (mpz_cmpabs(z(v[c]), z(v[m])) > 0) m = c;
    Z vm;
    mpz_abs(z(vm), z(v[m]));
    Z t;
    for (int c = 0; c < 3; ++c) {
      mpz_mul_2exp(z(t), z(v[c]), kShortBits - 1);
      mpz_fdiv_q(z(out[c]), z(t), z(vm));
    }
  }

  // Offers, each stage only while the bound lo is not met (met() below): x in each orientation
  // not excluded; integer normals along y (a generic direction); the 26 triples one ulp away
  // from x in some components (nextafter each way: a direction near an axis, where x's small
  // components carry their own exponents and integer normals would round them coarsely).
  // bounded: lo is a proved bound (else lo = bottom, which no offer meets).
  void offer_near(Best& best, const Q& lo, bool bounded) const {
    Problem none;  // (the exact offers do not read it)
    Q scale_top(1);
    detail::scale_pow2(scale_top, -2 * best.unit);
    // The offers go on until q (1 + 2^-53) <= lo (1 + kGlobalRel), q in the suspects' units: the
    // double path's budget, a tenth of what represented() accepts (definitions §8's 1e-9), so
    // that a value accepted there is not needlessly near the contract's edge where a better normal
    // is cheap to find.
    auto met = [&] {
      return bounded && best.qvalue * scale_top * (Q(1) + Q(1, 1ul << 53)) <= lo * (Q(1) + Q(kGlobalRel));
    };
    auto offer = [&](const V3& v) {
      for (double sg : {1.0, -1.0})
        if (!(sg > 0 ? excluded_pos : excluded_neg)) best.offer(none, mul(v, sg));
    };
    offer(x);
    if (!bounded || met()) return;  // (unbounded: lo = bottom, which no offer meets)
    std::vector<V3> normals;
    const Q yq[3] = {Q(y[0]), Q(y[1]), Q(y[2])};
    integer_normals(yq, 1 << 18, 4, normals);
    for (const V3& v : normals) offer(v);
    for (int m = 0; m < 27 && !met(); ++m) {
      if (m == 13) continue;  // all three components as they are: x
      V3 v = x;
      for (int c = 0, mm = m; c < 3; ++c, mm /= 3)
        if (mm % 3 != 1) v[c] = std::nextafter(v[c], mm % 3 == 0 ? -INFINITY : INFINITY);
      offer(v);
    }
    if (met()) return;
    // No double normal meets lo: y itself, shortened (witness() below), is the rational
    // witness (Best::offer_witness: kept apart from the double offers).
    const QNormal w = witness();
    for (int sg : {1, -1})
      if (!(sg > 0 ? excluded_pos : excluded_neg))
        best.offer_witness(sg > 0 ? w : QNormal{-w[0], -w[1], -w[2]});
  }

  // y shortened (kShortBits), as a normal.
  QNormal witness() const {
    ZV w;
    shortened(y, w);
    return {Q(w[0]), Q(w[1]), Q(w[2])};
  }

  ZV qx, y;
  Q bound;  // settle()'s bound, when it succeeded

 private:
  double in_units(const Q& v) const {  // v 2^-pe as a double
    Q t = v;
    detail::scale_pow2(t, -pe);
    return t.get_d();
  }
  static void dot(Z& out, const ZV& a, const ZV& b) {
    mpz_mul(z(out), z(a[0]), z(b[0]));
    mpz_addmul(z(out), z(a[1]), z(b[1]));
    mpz_addmul(z(out), z(a[2]), z(b[2]));
  }
  // v's components as integers over one power of two (the least of their exponents: a
  // positive multiple of v, exactly); false when v = 0.
  static bool integers_of(const V3& v, ZV& out) {
    int e = INT_MAX;
    for (double c : v)
      if (c != 0) {
        int ex = 0;
        std::frexp(c, &ex);
        e = std::min(e, ex - 53);
      }
    if (e == INT_MAX) return false;
    for (int c = 0; c < 3; ++c) {
      int ex = 0;
      const double m = std::frexp(v[c], &ex);  // v[c] = m 2^ex, |m| in [1/2, 1) (0 for 0)
      mpz_set_d(z(out[c]), std::ldexp(m, 53));  // an integer below 2^53: exact
      if (v[c] != 0) mpz_mul_2exp(z(out[c]), z(out[c]), static_cast<unsigned long>(ex - 53 - e));
    }
    return true;
  }

  const Best::Suspect& s;
  long pe = LONG_MIN;
  Eigen::Vector3d mu_d, e0;
  ZV li[8];  // the conditions (Best::Suspect::l: integers, each with its sign)
  Z ll[8];   // |li|^2
  Q rho, R2;
  Z qq;
  V3 x{};
  bool excluded_pos = false, excluded_neg = false;
};

// Steps after the first exact step, at most: mu located by counts, then Rayleigh quotient
// iteration (SuspectProof::locate_and_step, next_step).
constexpr int kMoreSteps = 4;

bool represent_suspect(Best& best, const Best::Suspect& s, const detail::Q& bottom, detail::Q& lo) {
  lo = bottom;
  SuspectProof p(s);
  if (!p.setup() || !p.polish()) return false;
  // x alone usually proves a spurious suspect outside its cone (its conditions are violated
  // far beyond x's error, ~u): no exact step needed.
  if (p.settle(p.qx) && p.excluded()) return true;
  p.exact_step();
  bool bounded = false;
  for (int step = 0;; ++step) {
    if (p.settle(p.y)) {
      if (p.excluded()) return true;
      if (eigenvalues_below(s.hi, p.bound, true) <= s.k && p.bound > bottom) lo = p.bound, bounded = true;
    }
    // Further steps while the bound is missing or looser than 2^-40 of rho, or a condition is
    // left open (a vector y still far from the eigenvector: a condition ~1e-17 of its scale
    // at the eigenvector, an eigenvector outside the cone whose witness's value lies far above
    // mu): mu located by counts, then Rayleigh quotient iteration.
    if (step == kMoreSteps || (bounded && p.tight(lo) && p.undecided == 0)) break;
    if (step > 0 || !p.locate_and_step()) p.next_step();
  }
  p.offer_near(best, lo, bounded);
  return false;
}

}  // namespace

Representation represented(Best& best, double floor_scaled) {
  using detail::Q;
  if (!best.have_q || best.suspects.empty()) return Representation::ByDouble;
  // top: the reported value, qvalue rounded to a double (<= qvalue (1 + 2^-53)), is within
  // 1e-9 of every stationary value mu >= top (qvalue (1 + 2^-53) <= mu (1 + 1e-9)). (Was
  // qvalue (1 - 1e-9): it let the rounded value exceed such a mu by up to 1e-9 + 1.2e-16.)
  Q top = best.qvalue * (Q(1) + Q(1, 1ul << 53)) / (Q(1) + Q(1, 1000000000));
  detail::scale_pow2(top, -2 * best.unit);
  const Q bottom(floor_scaled);
  std::vector<std::size_t> window;
  for (std::size_t i = 0; i < best.suspects.size(); ++i) {  // eigenvalue k (ascending) in (bottom, top)?
    const Best::Suspect& s = best.suspects[i];
    const int below_top = eigenvalues_below(s.hi, top), below_floor = eigenvalues_below(s.hi, bottom, true);
    const int k = s.k;
    if (below_floor <= k && k < below_top) window.push_back(i);
  }
  if (window.empty()) return Representation::ByDouble;
  std::vector<Q> lows;  // the settled suspects' lower bounds
  for (std::size_t i : window) {
    Q lo;
    if (!represent_suspect(best, best.suspects[i], bottom, lo)) lows.push_back(lo);
  }
  // The suspects just above the window, in [top, q0 (1 + 2^-53) / (1 + kGlobalRel)), q0 the
  // best now: within 1e-9 of the value already (the argument above needs nothing of them), but
  // more than kGlobalRel below it, and their offers may come closer (a generic direction's
  // rounded eigenvector misses by up to that 1e-9). Offers only: they lower the best and leave
  // every bound above as it is. (Only where the window was not empty: a pair accepted without
  // it keeps its value.)
  Q q0 = best.qvalue * (Q(1) + Q(1, 1ul << 53)) / (Q(1) + Q(kGlobalRel));
  detail::scale_pow2(q0, -2 * best.unit);
  for (std::size_t i = 0; i < best.suspects.size(); ++i) {
    const Best::Suspect& s = best.suspects[i];
    if (eigenvalues_below(s.hi, top) <= s.k && s.k < eigenvalues_below(s.hi, q0)) {
      Q lo;
      represent_suspect(best, best.suspects[i], top, lo);
    }
  }
  // q (1 + 2^-53) <= lo (1 + 1e-9) for every settled suspect, q the best double offer's value,
  // else the witness's (Best::witness: below the double offers' best, or absent).
  auto meets = [&](const Q& value) {
    Q q = value * (Q(1) + Q(1, 1ul << 53));
    detail::scale_pow2(q, -2 * best.unit);
    for (const Q& lo : lows)
      if (q > lo * (Q(1) + Q(1, 1000000000))) return false;
    return true;
  };
  if (meets(best.qvalue)) return Representation::ByDouble;
  if (best.witness && meets(best.witness->value)) return Representation::ByWitness;
  return Representation::None;
}

double near_extent_sq(const TetVertices& A, const TetVertices& B) {
  double L = INFINITY;  // the smaller tetrahedron's extent (largest coordinate range)
  for (const TetVertices* T : {&A, &B}) {
    double e = 0;
    for (int k = 0; k < 3; ++k) {
      double lo = (*T)[0][k], hi = lo;
      for (int i = 1; i < 4; ++i) lo = std::min(lo, (*T)[i][k]), hi = std::max(hi, (*T)[i][k]);
      e = std::max(e, hi - lo);
    }
    L = std::min(L, e);
  }
  return L * L;
}

}  // namespace pdd::fast::global
