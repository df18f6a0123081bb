// minkowski_pd.h — rigid penetration depth through the Minkowski difference (definitions §4).
//
// Input : an exact pair (A, B).
// Output: M = A (+) (-B) = conv{ s_i - r_j } as CGAL's exact 3D convex hull of the 16
//         differences; each facet as an outward normal m and offset h = m.p (p on the facet);
//         intersecting <=> the origin is strictly inside M <=> every h > 0;
//         PD^2 = min over facets of h^2 / m.m (squared distance from the origin to the
//         facet's plane), 0 when not intersecting (touching counts as not intersecting).
#pragma once

#include <vector>

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

struct MinkowskiFacet {
  Vector outward_normal;  // unnormalised
  Rational offset;        // outward_normal . p for any point p of the facet
};

struct MinkowskiPd {
  bool intersecting = false;
  Rational pd2;               // 0 when not intersecting
  std::vector<MinkowskiFacet> facets;  // triangulated hull facets
  std::vector<Point> vertices;         // the hull's vertices (extreme differences)
};

// The 16 points s_i - r_j, i-major.
std::vector<Point> minkowski_difference_points(const ExactPair& pair);

MinkowskiPd minkowski_pd(const ExactPair& pair);

}  // namespace pdd::reference
