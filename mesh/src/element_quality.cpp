// element_quality.cpp — the exact R4 verdict per element (element_quality.h).
#include "element_quality.h"

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "binary_scale.h"
#include "resolve.h"

namespace pdd::mesh::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;  // rounding set outward by the caller's protector

// a >= b, or nullopt when intervals cannot tell.
std::optional<bool> at_least(const Interval& a, const Interval& b) {
  const CGAL::Uncertain<bool> r = a >= b;
  if (CGAL::is_certain(r)) return CGAL::get_certain(r);
  return std::nullopt;
}
std::optional<bool> at_least(const Rational& a, const Rational& b) { return a >= b; }

template <class NT>
NT det6(const TetVertices& t) {
  NT e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) e[i][k] = NT(t[i + 1][k]) - NT(t[0][k]);
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

template <class NT>
NT edge_sum(const TetVertices& t) {
  NT s(0);
  for (const auto& ed : kEdges)
    for (int k = 0; k < 3; ++k) {
      const NT d = NT(t[ed[1]][k]) - NT(t[ed[0]][k]);
      s += d * d;
    }
  return s;
}

// R4's three comparisons in NT, for an element whose orientation is kept (sign0 = sign D0 =
// sign D1); nullopt when NT cannot decide one of them.
template <class NT>
std::optional<Quality> decide(const TetVertices& t0, const TetVertices& t1, int sign0, const QualityLimits& q) {
  const NT a0 = NT(sign0) * det6<NT>(t0), a1 = NT(sign0) * det6<NT>(t1);  // |D0|, |D1|
  const NT rho(q.min_volume_ratio), kappa(q.min_shape_ratio);
  const auto low = at_least(a1, rho * a0);
  if (!low) return std::nullopt;
  if (!*low) return Quality::Crushed;
  const auto high = at_least(a0, rho * a1);
  if (!high) return std::nullopt;
  if (!*high) return Quality::Swollen;
  const NT s0 = edge_sum<NT>(t0), s1 = edge_sum<NT>(t1);
  const auto shape = at_least(a1 * a1 * s0 * s0 * s0, kappa * kappa * kappa * a0 * a0 * s1 * s1 * s1);
  if (!shape) return std::nullopt;
  return *shape ? Quality::Usable : Quality::Distorted;
}

bool finite(const TetVertices& t) {
  for (const Vec3d& v : t)
    for (double x : v)
      if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

void check_limits(const QualityLimits& q) {
  for (const auto& [name, v] : {std::pair{"min_volume_ratio", q.min_volume_ratio},
                                std::pair{"min_shape_ratio", q.min_shape_ratio}})
    if (!(v > 0 && v <= 1)) {
      std::ostringstream o;
      o << "resolve: " << name << " must be in (0, 1]; got " << v;
      throw std::invalid_argument(o.str());
    }
}

Quality element_quality(const TetVertices& t0, const TetVertices& t1, const QualityLimits& q) {
  if (!finite(t1)) return Quality::NonFinite;
  const Sign s0 = orientation(t0[0], t0[1], t0[2], t0[3]);
  if (orientation(t1[0], t1[1], t1[2], t1[3]) != s0 || s0 == Sign::Zero) return Quality::Inverted;
  const int sign0 = s0 == Sign::Positive ? 1 : -1;
  {
    CGAL::Protect_FPU_rounding<true> outward;  // Interval_nt<false> needs rounding towards +inf
    if (const auto r = decide<Interval>(t0, t1, sign0, q)) return *r;
  }
  return *decide<Rational>(t0, t1, sign0, q);  // exact: always decides
}

double volume6(const TetVertices& t) { return det6<double>(t); }
double edge_square_sum(const TetVertices& t) { return edge_sum<double>(t); }

Ratios ratios(double d0, double s0, const TetVertices& t1) {
  const double d1 = volume6(t1), s1 = edge_square_sum(t1);
  const double v = d1 / d0;
  // eta1/eta0 = (|V1|/|V0|)^(2/3) S0 / S1
  return {v, std::cbrt(v * v) * s0 / s1};
}

double edge_scale(const TetVertices& t0) {
  double largest = 0;
  for (int i = 1; i < 4; ++i)
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(t0[i][k] - t0[0][k]));
  return std::ldexp(1.0, -binary_exponent(largest));
}

TetVertices scaled(const TetVertices& t, double factor) {
  TetVertices s = t;
  for (auto& x : s)
    for (double& c : x) c *= factor;
  return s;
}

Ratios scaled_ratios(const TetVertices& t0, const TetVertices& t1) {
  const double f = edge_scale(t0);
  const TetVertices s0 = scaled(t0, f);
  return ratios(volume6(s0), edge_square_sum(s0), scaled(t1, f));
}

}  // namespace pdd::mesh::detail
