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
  Q sigma = Q(mu) * (1 - Q(1, 1000000));
  detail::scale_pow2(sigma, pe);  // mu is in the piece's units, 2^-pe of h's
  mpz_class m[3][3];
  integer_shift(h, sigma, m);
  mpz_class adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
    }
  const mpz_class det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
  V3 v = v0;
  for (int it = 0; it < 3; ++it) {
    ScaledInt s[3] = {scaled_int(v[0]), scaled_int(v[1]), scaled_int(v[2])};
    long E = LONG_MAX;
    for (const ScaledInt& x : s)
      if (sgn(x.m) != 0) E = std::min(E, x.e);
    mpz_class V[3];
    for (int k = 0; k < 3; ++k)
      if (sgn(s[k].m) != 0) mpz_mul_2exp(V[k].get_mpz_t(), s[k].m.get_mpz_t(), mp_bitcnt_t(s[k].e - E));
    mpz_class x[3];
    for (int r = 0; r < 3; ++r) x[r] = adj[r][0] * V[0] + adj[r][1] * V[1] + adj[r][2] * V[2];
    mpz_class big = 0;
    for (const mpz_class& c : x)
      if (mpz_cmpabs(c.get_mpz_t(), big.get_mpz_t()) > 0) big = abs(c);
    if (sgn(big) == 0) return v;
    // x_r / big as mpq_get_d rounds it (towards zero): it divides numerator by denominator
    // (> 0 here: the sign goes on the numerator), so the fraction need not be reduced first (a
    // gcd of integers of thousands of bits: a sixth of the exact pieces' time).
    const bool flip = sgn(det) < 0;
    for (int r = 0; r < 3; ++r) {
      Q q;
      q.get_num() = flip ? mpz_class(-x[r]) : x[r];
      q.get_den() = big;
      v[r] = q.get_d();
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
