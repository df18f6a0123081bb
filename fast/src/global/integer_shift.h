// integer_shift.h — internal to fast/src/global: a rational 3 x 3 matrix shifted by t, over one
// common denominator.
//
// Input : M (3 x 3 rationals), once as an IntegerMatrix (integers a over one L > 0, the least
//         common multiple of M's denominators: M = a / L); a shift t = p / q (q > 0).
// Output: A = L q (M - t I) = q a - L p I, integers. A is a positive multiple of M - t I: the
//         signs of its characteristic polynomial's coefficients (tr, c1, det scale by (L q),
//         (L q)^2, (L q)^3) and the direction of adj(A) v ((L q)^2 adj(M - t I) v) are those of
//         M - t I. Products of integers need no reduction to lowest terms, which rationals take
//         after every operation (a gcd each: most of the exact pieces' time on rationals); and
//         the matrix's own common denominator is taken once for all the shifts a piece is
//         asked about (the inverse iteration's, the exact eigenvalue counts': tens a piece), so
//         a shift costs no gcd at all.
#pragma once

#include "exact/exact_geometry.h"

namespace pdd::fast::global {

struct IntegerMatrix {
  mpz_class a[3][3];
  mpz_class L;  // > 0
};

template <class Matrix>
IntegerMatrix integer_matrix(const Matrix& M) {
  IntegerMatrix m;
  m.L = 1;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) mpz_lcm(m.L.get_mpz_t(), m.L.get_mpz_t(), M[r][c].get_den_mpz_t());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      mpz_divexact(m.a[r][c].get_mpz_t(), m.L.get_mpz_t(), M[r][c].get_den_mpz_t());
      m.a[r][c] *= M[r][c].get_num();
    }
  return m;
}

inline void integer_shift(const IntegerMatrix& m, const detail::Q& t, mpz_class (&A)[3][3]) {
  const mpz_class& q = t.get_den();
  const mpz_class Lp = m.L * t.get_num();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      mpz_mul(A[r][c].get_mpz_t(), m.a[r][c].get_mpz_t(), q.get_mpz_t());
      if (r == c) A[r][c] -= Lp;
    }
}

}  // namespace pdd::fast::global
