#include "pdd/reference/exact_kernel.h"

#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace pdd::reference {

ExactTet to_exact(const TetVertices& tet) {
  ExactTet out;
  for (int i = 0; i < 4; ++i)
    out[i] = Point(Rational(tet[i][0]), Rational(tet[i][1]), Rational(tet[i][2]));
  return out;
}

ExactPair to_exact(const TetPair& pair) { return {to_exact(pair.A), to_exact(pair.B)}; }

std::string to_string(const Rational& q) {
  // Gmpq is kept canonical (lowest terms, positive denominator), as mpq_get_str expects.
  std::unique_ptr<char, void (*)(void*)> s(mpq_get_str(nullptr, 10, q.mpq()), free);
  return std::string(s.get());
}

QpNumber to_qp_number(const Rational& q) {
  const mpz_srcptr den = mpq_denref(q.mpq());
  const mp_bitcnt_t shift = mpz_scan1(den, 0);  // den = 2^shift exactly iff popcount is 1
  if (mpz_popcount(den) != 1) throw std::logic_error("to_qp_number: non-dyadic rational");
  // x = num * 2^-shift, built from exact factors 2^-k (each a normal double, k <= 1000).
  QpNumber x{CGAL::Gmpz(mpq_numref(q.mpq()))};
  for (mp_bitcnt_t left = shift; left > 0;) {
    const int step = static_cast<int>(std::min<mp_bitcnt_t>(left, 1000));
    x = x * QpNumber(std::ldexp(1.0, -step));
    left -= static_cast<mp_bitcnt_t>(step);
  }
  return x;
}

Rational to_rational(const QpNumber& x) {
  Rational q{CGAL::Gmpz(x.man())};
  const long e = x.exp();
  if (e >= 0) mpq_mul_2exp(q.mpq(), q.mpq(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(q.mpq(), q.mpq(), static_cast<mp_bitcnt_t>(-e));
  return q;
}

}  // namespace pdd::reference
