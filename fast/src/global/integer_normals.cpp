// integer_normals.cpp — see integer_normals.h.
#include "global/integer_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace pdd::fast::global {

// A double triple rounded from a unit vector misses y's direction by ~u, and along a generic
// direction (a contact not along a coordinate plane) the neighbouring doubles do no better; but
// the normal need not be a unit vector. With y_m its largest component and alpha_i = y_i / y_m
// (|alpha_i| <= 1), the triple c (alpha_0, alpha_1, alpha_2) with c an integer below 2^53 and the other two
// components rounded to integers is a double triple (every integer up to 2^53 is) whose
// direction misses y's by (frac distance of c alpha_i) / c: for the c among `tries` consecutive
// integers below 2^53 where both fractional parts are small (they are equidistributed: the best
// of M tries has both within ~1/sqrt(M)), that angle is ~1/sqrt(M) of a rounded unit vector's.
// The fractional parts are tracked in 64-bit fixed point (wrapping arithmetic is arithmetic mod
// 1): the first exactly, then minus alpha_i 2^64 rounded down per step, so after j steps they
// are off by < j 2^-64, beside the ~2^-9 that selects; the chosen triples' integers are then
// computed exactly. Only a search: each triple is evaluated exactly by the caller.
void integer_normals(const detail::Q (&y)[3], int tries, int keep, std::vector<V3>& out) {
  using detail::Q;
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (abs(y[i]) > abs(y[m])) m = i;
  if (sgn(y[m]) == 0) return;
  const int idx[2] = {(m + 1) % 3, (m + 2) % 3};
  const std::uint64_t c0 = (std::uint64_t(1) << 53) - 1;
  Q alpha[2];
  std::uint64_t A[2], F[2];
  for (int t = 0; t < 2; ++t) {
    alpha[t] = y[idx[t]] / y[m];
    auto frac64 = [&](unsigned long c) {  // floor(c alpha 2^64) mod 2^64
      mpz_class num = alpha[t].get_num() * c, q, r;
      mpz_mul_2exp(num.get_mpz_t(), num.get_mpz_t(), 64);
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), alpha[t].get_den_mpz_t());
      mpz_fdiv_r_2exp(r.get_mpz_t(), q.get_mpz_t(), 64);  // in [0, 2^64)
      return std::uint64_t(mpz_get_ui(r.get_mpz_t()));
    };
    A[t] = frac64(1), F[t] = frac64(static_cast<unsigned long>(c0));
  }
  // (metric, c), the `keep` best in increasing metric, a new one before equal ones. An array
  // with insertion in place: along a direction a rounding away from a coordinate plane or a
  // diagonal (a contact made by rounding), the fractional parts drift by ~1e-17 a try and
  // nearly every try improves on the last, so the insertion runs on most of the 2^18 tries.
  constexpr int kKeepMax = 8;
  keep = std::min(keep, kKeepMax);
  std::pair<double, std::uint64_t> top[kKeepMax];
  int kept = 0;
  // The distance to the nearest integer, times 2^64: f below 2^63, else 2^64 - f, as a double.
  // Read as a signed integer s (two's complement), that is |s| (2^63 for s = -2^63), and
  // round-to-nearest is symmetric, so |double(s)| is the same double: one signed conversion
  // (the unsigned one takes a branch and several instructions without AVX-512).
  auto dist = [](std::uint64_t f) { return std::fabs(double(std::int64_t(f))); };
  double worst = INFINITY;  // the largest kept metric once `keep` are kept (else +inf)
  for (int j = 0; j < tries; ++j) {
    const double d0 = dist(F[0]), d1 = dist(F[1]), metric = d0 * d0 + d1 * d1;
    if (metric < worst) {
      int i = kept < keep ? kept++ : keep - 1;  // (full: the last one goes)
      for (; i > 0 && top[i - 1].first >= metric; --i) top[i] = top[i - 1];
      top[i] = {metric, c0 - std::uint64_t(j)};
      if (kept == keep) worst = top[keep - 1].first;
    }
    F[0] -= A[0], F[1] -= A[1];  // c -> c - 1 (mod 2^64: mod 1)
  }
  const double s = sgn(y[m]) > 0 ? 1.0 : -1.0;
  for (int r = 0; r < kept; ++r) {
    const std::uint64_t c = top[r].second;
    V3 v;
    v[m] = s * double(c);
    for (int t = 0; t < 2; ++t) {  // round(c alpha) = floor((2 c num + den) / (2 den)), exactly
      mpz_class num = alpha[t].get_num(), den = alpha[t].get_den(), q;
      num *= static_cast<unsigned long>(c);
      num = 2 * num + den;
      den *= 2;
      mpz_fdiv_q(q.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
      v[idx[t]] = s * q.get_d();  // |q| <= c < 2^53: exact
    }
    out.push_back(v);
  }
}

}  // namespace pdd::fast::global
