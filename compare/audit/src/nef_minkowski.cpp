// CGAL's Nef-polyhedron Minkowski sum, as an independent check of minkowski_pd's hull.
// Kept in its own translation unit: Nef_polyhedron_3 is heavy to compile.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/minkowski_sum_3.h>

#include <gmpxx.h>

#include <algorithm>

#include "pdd/compare/theorem_audit.h"
#include "pdd/reference/minkowski_pd.h"

namespace pdd::compare {
namespace {

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Nef = CGAL::Nef_polyhedron_3<Epeck>;
using Polyhedron = CGAL::Polyhedron_3<Epeck>;

// Exact conversions between our Rational (CGAL::Gmpq) and Epeck's exact type (GMP mpq).
reference::Rational exact_of(const Epeck::FT& x) {
  return reference::Rational(mpq_class(CGAL::exact(x)).get_mpq_t());
}
Epeck::FT epeck_of(const reference::Rational& q) { return Epeck::FT(mpq_class(q.mpq())); }

Nef nef_tetrahedron(const reference::ExactTet& t, int sign) {
  std::vector<Epeck::Point_3> pts;
  for (const auto& p : t)
    pts.emplace_back(epeck_of(sign * p.x()), epeck_of(sign * p.y()), epeck_of(sign * p.z()));
  Polyhedron poly;
  CGAL::convex_hull_3(pts.begin(), pts.end(), poly);
  return Nef(poly);
}

using Key = std::array<reference::Rational, 3>;
Key key(const reference::Rational& x, const reference::Rational& y, const reference::Rational& z) {
  return {x, y, z};
}

}  // namespace

bool nef_minkowski_equals_hull(const reference::ExactPair& pair) {
  Nef a = nef_tetrahedron(pair.A, 1), minus_b = nef_tetrahedron(pair.B, -1);
  const Nef sum = CGAL::minkowski_sum_3(a, minus_b);
  std::vector<Key> nef_vertices;
  for (auto v = sum.vertices_begin(); v != sum.vertices_end(); ++v)
    nef_vertices.push_back(key(exact_of(v->point().x()), exact_of(v->point().y()), exact_of(v->point().z())));

  std::vector<Key> hull_vertices;
  for (const auto& p : reference::minkowski_pd(pair).vertices) hull_vertices.push_back(key(p.x(), p.y(), p.z()));
  std::sort(nef_vertices.begin(), nef_vertices.end());
  std::sort(hull_vertices.begin(), hull_vertices.end());
  return nef_vertices == hull_vertices;
}

}  // namespace pdd::compare
