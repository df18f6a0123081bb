#include "pdd/reference/minkowski_pd.h"

#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

namespace pdd::reference {

std::vector<Point> minkowski_difference_points(const ExactPair& pair) {
  std::vector<Point> pts;
  pts.reserve(16);
  for (const Point& s : pair.A)
    for (const Point& r : pair.B) pts.push_back(CGAL::ORIGIN + (s - r));
  return pts;
}

namespace {

// Orient m outward: every hull point q has m.(q - p) <= 0. The hull is full-dimensional
// (it contains a translate of A, which has volume), so some point is strictly off the plane.
MinkowskiFacet outward_facet(const Point& p0, const Point& p1, const Point& p2,
                             const std::vector<Point>& pts) {
  Vector m = CGAL::cross_product(p1 - p0, p2 - p0);
  for (const Point& q : pts) {
    const CGAL::Sign side = CGAL::sign(m * (q - p0));
    if (side == CGAL::ZERO) continue;
    if (side == CGAL::POSITIVE) m = -m;
    break;
  }
  return {m, m * (p0 - CGAL::ORIGIN)};
}

}  // namespace

MinkowskiPd minkowski_pd(const ExactPair& pair) {
  using Mesh = CGAL::Surface_mesh<Point>;
  const std::vector<Point> pts = minkowski_difference_points(pair);
  Mesh hull;
  CGAL::convex_hull_3(pts.begin(), pts.end(), hull);

  MinkowskiPd out;
  out.intersecting = true;
  for (auto vd : hull.vertices()) out.vertices.push_back(hull.point(vd));
  for (auto f : hull.faces()) {
    std::vector<Point> v;
    for (auto vd : CGAL::vertices_around_face(hull.halfedge(f), hull)) v.push_back(hull.point(vd));
    out.facets.push_back(outward_facet(v[0], v[1], v[2], pts));
    if (out.facets.back().offset <= 0) out.intersecting = false;
  }
  if (!out.intersecting) return out;  // pd2 stays 0
  for (std::size_t k = 0; k < out.facets.size(); ++k) {
    const MinkowskiFacet& f = out.facets[k];
    const Rational d2 = f.offset * f.offset / f.outward_normal.squared_length();
    if (k == 0 || d2 < out.pd2) out.pd2 = d2;
  }
  return out;
}

}  // namespace pdd::reference
