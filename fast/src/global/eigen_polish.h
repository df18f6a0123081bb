// eigen_polish.h — internal to fast/src/global: a piece's computed eigenvectors polished on its
// matrix, in doubles or on the exact matrix.
//
// Input : a piece's symmetric h (doubles, or exact rationals scaled by 2^pe against the double
//         image the eigenvalue mu is measured on), a computed eigenvector v0 (or two, e and f,
//         spanning a near-double eigenvalue's plane).
// Output: refine: inverse iteration with shift sigma = mu (1 - 1e-6),
//             v <- adj(h - sigma I) v   (= det (h - sigma I)^-1 v),
//         each step rounded to doubles (normalised in doubles; componentwise on the exact h,
//         which keeps every component's relative accuracy), oriented as v0;
//         ritz: the Rayleigh-Ritz vectors of h on span(e, f): with K = [e f]^T h [e f] (exact),
//         cos t e + sin t f and -sin t e + cos t f, tan 2t = 2 K01 / (K00 - K11); false when K
//         is a multiple of I.
#pragma once

#include <cmath>

#include "exact/exact_geometry.h"
#include "global/integer_shift.h"
#include "global/vec3.h"

namespace pdd::fast::global {

// Inverse iteration on the exact H (slow path): x = (H - sigma I)^-1 v by the adjugate, twice,
// each time rounded componentwise to doubles. Eigen's vectors carry an absolute error of
// u |v| in every component; a tiny component of the true eigenvector (a normal tilted by
// 2^-60 from an axis) then has no correct digit, and the relaxed value along it, of order
// |H| u^2, swamps a depth of 1e-38. Rounded componentwise, every component keeps its relative
// accuracy. sigma = mu (1 - 1e-6): the iteration contracts by about 1e-6 towards mu's vector.
V3 refine(const detail::Q (&h)[3][3], const V3& v0, double mu, long pe);
// The same on h as integers over one denominator (integer_shift.h; a piece refined more than
// once builds it once): the same doubles.
V3 refine(const IntegerMatrix& h, const V3& v0, double mu, long pe);

// Rayleigh-Ritz on the plane of e and f (consider_piece's exact path): K = [e f]^T h [e f] in
// rationals; its eigenvectors make the angles t and t + pi/2 with e, tan 2t = 2 K01 / (K00 -
// K11), taken from K01 and (K00 - K11) / 2 rounded once. false when K is a multiple of I (every
// vector of the plane is an eigenvector: e and f are offered already).
bool ritz(const detail::Q (&h)[3][3], const V3& e, const V3& f, V3 (&out)[2]);

// Double path: two steps of inverse iteration in doubles, x = adj(H - sigma I) v with sigma =
// mu (1 - 1e-6), normalised. The closed-form solver's vectors are the cross products of rows
// of H - mu I: beside a vertex 10^4 away (|H| ~ 1e9, a depth ~ 1) their error along the large
// eigenvector, ~ u |H| / mu, costs |H| (u |H| / mu)^2 ~ 1e-5 of the value. Each step damps that
// component by (mu - sigma) / (lambda_big - sigma); the vector's rounding then leaves u.
inline V3 refine(const double (&h)[3][3], const V3& v0, double mu, long) {
  const double sigma = mu * (1 - 1e-6);
  double m[3][3], adj[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = h[r][c] - (r == c ? sigma : 0.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      adj[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];  // cofactor (c, r)
    }
  V3 v = v0;
  for (int it = 0; it < 2; ++it) {
    V3 x;
    for (int r = 0; r < 3; ++r) x[r] = adj[r][0] * v[0] + adj[r][1] * v[1] + adj[r][2] * v[2];
    const double nx = norm(x);
    if (!(nx > 0) || !std::isfinite(nx)) return v;
    x = mul(x, 1 / nx);
    if (dot(x, v) < 0) x = mul(x, -1.0);  // keep the orientation
    v = x;
  }
  return v;
}

}  // namespace pdd::fast::global
