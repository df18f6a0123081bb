// integer_shift.h — internal to fast/src/global: a rational 3 x 3 matrix shifted by t, over one
// common denominator.
//
// Input : M (3 x 3 rationals), t.
// Output: A = L (M - t I), integers, L > 0 the least common multiple of the entries'
//         denominators and t's. A is a positive multiple of M - t I: the signs of its characteristic
//         polynomial's coefficients (tr, c1, det scale by L, L^2, L^3) and the direction of
//         adj(A) v (L^2 adj(M - t I) v) are those of M - t I. Products of integers need no
//         reduction to lowest terms, which rationals take after every operation (a gcd each:
//         most of the exact pieces' time on rationals).
#pragma once

#include "exact/exact_geometry.h"

namespace pdd::fast::global {

template <class Matrix>
void integer_shift(const Matrix& M, const detail::Q& t, mpz_class (&A)[3][3]) {
  mpz_class L = t.get_den();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) mpz_lcm(L.get_mpz_t(), L.get_mpz_t(), M[r][c].get_den_mpz_t());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const detail::Q x = r == c ? detail::Q(M[r][c] - t) : M[r][c];
      mpz_divexact(A[r][c].get_mpz_t(), L.get_mpz_t(), x.get_den_mpz_t());
      A[r][c] *= x.get_num();
    }
}

}  // namespace pdd::fast::global
