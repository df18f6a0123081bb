// eigen_polish.cpp — see eigen_polish.h.
#include "global/eigen_polish.h"

#include <algorithm>
#include <cmath>

namespace pdd::fast::global {

V3 refine(const detail::Q (&h)[3][3], const V3& v0, double mu, long pe) {
  using detail::Q;
  Q sigma = Q(mu) * (1 - Q(1, 1000000));
  detail::scale_pow2(sigma, pe);  // mu is in the piece's units, 2^-pe of h's
  Q m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = h[r][c] - (r == c ? sigma : Q(0));
  Q adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
    }
  const Q det = m[0][0] * adj[0][0] + m[0][1] * adj[1][0] + m[0][2] * adj[2][0];
  V3 v = v0;
  for (int it = 0; it < 3; ++it) {
    Q x[3];
    for (int r = 0; r < 3; ++r) x[r] = adj[r][0] * Q(v[0]) + adj[r][1] * Q(v[1]) + adj[r][2] * Q(v[2]);
    Q big = 0;
    for (const Q& c : x) big = std::max(big, Q(abs(c)));
    if (sgn(big) == 0) return v;
    if (sgn(det) < 0) big = -big;
    v = {Q(x[0] / big).get_d(), Q(x[1] / big).get_d(), Q(x[2] / big).get_d()};
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
