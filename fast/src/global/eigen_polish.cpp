// eigen_polish.cpp — see eigen_polish.h.
#include "global/eigen_polish.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "global/integer_shift.h"

namespace pdd::fast::global {

namespace {
// A double as an integer times 2^e (e the exponent of its last mantissa bit; 0 -> 0, e = 0).
struct ScaledInt {
  mpz_class m;
  long e = 0;
};
ScaledInt scaled_int(double x) {
  ScaledInt s;
  if (x == 0.0) return s;
  int e = 0;
  const double f = std::frexp(x, &e);  // x = f 2^e, 1/2 <= |f| < 1
  s.m = std::ldexp(f, 53);             // exact: an integer below 2^53
  s.e = long(e) - 53;
  return s;
}
}  // namespace

V3 refine(const detail::Q (&h)[3][3], const V3& v0, double mu, long pe) {
  return refine(integer_matrix(h), v0, mu, pe);
}

// The iteration over integers (integer_shift.h): x = adj(M) V with M = L q (h - sigma I) and V =
// 2^-E v integers is a positive multiple of adj(h - sigma I) v, so x_r / max |x| is the same
// rational as on the rationals themselves, rounded by the same conversion: the same doubles.
V3 refine(const IntegerMatrix& h, const V3& v0, double mu, long pe) {
  using detail::Q;
  // (explicit mpz calls on per-thread integers: the exact pieces call this for every suspect
  // and offer, on integers of thousands of bits, where each expression's temporaries would be
  // allocated and freed)
  struct Scratch {
    mpz_class m[3][3], adj[3][3], det, V[3], x[3], big;
    Q q;
  };
  static thread_local Scratch w;
  auto z = [](mpz_class& x) { return x.get_mpz_t(); };
  Q sigma = Q(mu) * (1 - Q(1, 1000000));
  detail::scale_pow2(sigma, pe);  // mu is in the piece's units, 2^-pe of h's
  integer_shift(h, sigma, w.m);
  auto& m = w.m;
  auto& adj = w.adj;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      mpz_mul(z(adj[r][c]), z(m[r1][c1]), z(m[r2][c2]));  // cofactor (c, r)
      mpz_submul(z(adj[r][c]), z(m[r1][c2]), z(m[r2][c1]));
    }
  mpz_mul(z(w.det), z(m[0][0]), z(adj[0][0]));
  mpz_addmul(z(w.det), z(m[0][1]), z(adj[1][0]));
  mpz_addmul(z(w.det), z(m[0][2]), z(adj[2][0]));
  const bool flip = sgn(w.det) < 0;
  V3 v = v0;
  for (int it = 0; it < 3; ++it) {
    ScaledInt s[3] = {scaled_int(v[0]), scaled_int(v[1]), scaled_int(v[2])};
    long E = LONG_MAX;
    for (const ScaledInt& x : s)
      if (sgn(x.m) != 0) E = std::min(E, x.e);
    for (int k = 0; k < 3; ++k) {
      if (sgn(s[k].m) != 0) mpz_mul_2exp(z(w.V[k]), s[k].m.get_mpz_t(), mp_bitcnt_t(s[k].e - E));
      else mpz_set_ui(z(w.V[k]), 0);
    }
    for (int r = 0; r < 3; ++r) {
      mpz_mul(z(w.x[r]), z(adj[r][0]), z(w.V[0]));
      mpz_addmul(z(w.x[r]), z(adj[r][1]), z(w.V[1]));
      mpz_addmul(z(w.x[r]), z(adj[r][2]), z(w.V[2]));
    }
    mpz_set_ui(z(w.big), 0);
    for (mpz_class& c : w.x)
      if (mpz_cmpabs(c.get_mpz_t(), w.big.get_mpz_t()) > 0) mpz_abs(z(w.big), c.get_mpz_t());
    if (sgn(w.big) == 0) return v;
    // x_r / big as mpq_get_d rounds it (towards zero): it divides numerator by denominator
    // (> 0 here: the sign goes on the numerator), so the fraction need not be reduced first (a
    // gcd of integers of thousands of bits: a sixth of the exact pieces' time).
    mpz_set(mpq_denref(w.q.get_mpq_t()), z(w.big));
    for (int r = 0; r < 3; ++r) {
      if (flip) mpz_neg(mpq_numref(w.q.get_mpq_t()), z(w.x[r]));
      else mpz_set(mpq_numref(w.q.get_mpq_t()), z(w.x[r]));
      v[r] = mpq_get_d(w.q.get_mpq_t());
    }
  }
  return v;
}

bool ritz(const detail::Q (&h)[3][3], const V3& e, const V3& f, V3 (&out)[2]) {
  using detail::Q;
  const Q qe[3] = {Q(e[0]), Q(e[1]), Q(e[2])}, qf[3] = {Q(f[0]), Q(f[1]), Q(f[2])};
  Q he[3], hf[3];
  for (int r = 0; r < 3; ++r) {
    he[r] = h[r][0] * qe[0] + h[r][1] * qe[1] + h[r][2] * qe[2];
    hf[r] = h[r][0] * qf[0] + h[r][1] * qf[1] + h[r][2] * qf[2];
  }
  const Q k00 = qe[0] * he[0] + qe[1] * he[1] + qe[2] * he[2];
  const Q k11 = qf[0] * hf[0] + qf[1] * hf[1] + qf[2] * hf[2];
  const Q k01 = qe[0] * hf[0] + qe[1] * hf[1] + qe[2] * hf[2];
  const Q half_diff = (k00 - k11) / 2;
  if (sgn(k01) == 0 && sgn(half_diff) == 0) return false;
  // (the ratio, not the parts: h's entries may lie far outside the double range)
  const double t = sgn(half_diff) == 0 ? (sgn(k01) > 0 ? M_PI / 4 : -M_PI / 4)
                                       : 0.5 * std::atan2(Q(k01 / abs(half_diff)).get_d(), sgn(half_diff) > 0 ? 1.0 : -1.0);
  const double c = std::cos(t), s = std::sin(t);
  out[0] = add(mul(e, c), mul(f, s));
  out[1] = add(mul(e, -s), mul(f, c));
  return true;
}

}  // namespace pdd::fast::global
