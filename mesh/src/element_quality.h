// element_quality.h — R4 of definitions §11 for one element: is the deformed tetrahedron t1
// still usable by a simulator, compared with its rest shape t0?
//
// Inputs:  t0, t1  the element's four vertices at rest and deformed (doubles);
//          limits  rho (min_volume_ratio) and kappa (min_shape_ratio), each in (0, 1].
// Outputs: the exact verdict (Quality), and the ratios in doubles for display and for the
//          resolver's step limit.
//
// With D = 6 V = det[p1 - p0, p2 - p0, p3 - p0] (signed) and S = sum of the six squared edge
// lengths, the mean-ratio shape quality is eta = 12 (3|V|)^(2/3) / S, so
//     eta1 / eta0 >= kappa   <=>   |D1|^2 S0^3 >= kappa^3 |D0|^2 S1^3        (cube both sides)
// and, for an element that keeps its orientation (sign D1 == sign D0 != 0, R2),
//     V1/V0 >= rho   <=>  |D1| >= rho |D0|,        V1/V0 <= 1/rho  <=>  rho |D1| <= |D0|.
// These polynomials (degree 12 at most) are decided exactly on the doubles: first in interval
// arithmetic (CGAL::Interval_nt with outward rounding), and where an interval straddles the
// comparison, again in the project's exact type (pdd::Rational, GMP); rho and kappa are read as
// the exact rationals their doubles are.
#pragma once

#include "pdd/mesh.h"

namespace pdd::mesh::detail {

// The exact verdict on one element, first failure in this order.
enum class Quality {
  Usable,         // R2 and R4 hold
  Inverted,       // orientation changed or flat (R2 fails)
  NonFinite,      // a deformed coordinate is not finite
  Crushed,        // V1/V0 < rho
  Swollen,        // V1/V0 > 1/rho
  Distorted,      // eta1/eta0 < kappa
};

// Throws std::invalid_argument naming the option when a limit is outside (0, 1] or not finite.
void check_limits(const QualityLimits& limits);

// t0 must be valid at rest (finite, not flat).
Quality element_quality(const TetVertices& t0, const TetVertices& t1, const QualityLimits& limits);

// D = 6 V (signed) and S = sum of squared edge lengths, in doubles.
double volume6(const TetVertices& t);
double edge_square_sum(const TetVertices& t);

// V1/V0 (signed) and eta1/eta0 in doubles, from the rest element's D0 and S0.
struct Ratios {
  double volume = 0, shape = 0;
};
Ratios ratios(double d0, double s0, const TetVertices& t1);
// 2^-k, k such that the rest element's largest |edge vector entry| times it lies in [1/2, 1),
// and t times such a factor. D (~L^3) and S (~L^2) of elements scaled so stay in the double range
// whatever the mesh's size L, and the ratios of scaled elements (rest and deformed by the same
// factor) are the unscaled ones bit for bit wherever those are in range (a power of two commutes
// with every rounding of normal values); unscaled, D leaves the range beyond L ~ 1e+-102.
double edge_scale(const TetVertices& t0);
TetVertices scaled(const TetVertices& t, double factor);
// ratios() of t1 against the rest element t0, each scaled by edge_scale(t0).
Ratios scaled_ratios(const TetVertices& t0, const TetVertices& t1);

}  // namespace pdd::mesh::detail
