// check_resolution.cpp — the exact verdict R1–R4 on given positions (pdd/mesh/check_resolution.h), the mesh object
// norm mesh_cost, and the contact stage the rounds of resolve share with the verdict
// (resolve.h).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "binary_scale.h"
#include "element_quality.h"
#include "resolve.h"
#include "resolve/state.h"

namespace pdd::mesh {
namespace detail {

Sign orientation(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, const Vec3d& p3) {
  using P = CGAL::Epick::Point_3;
  auto p = [](const Vec3d& v) { return P(v[0], v[1], v[2]); };
  return sign_of(int(CGAL::orientation(p(p0), p(p1), p(p2), p(p3))));  // exact (filtered) predicate
}

std::vector<std::size_t> valid_elements(const Mesh& m, char which, std::vector<SkippedElement>* skipped) {
  std::vector<char> ok(m.tets.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.tets.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) ok[i] = !element_problem(m, i, which);
                    });
  std::vector<std::size_t> out;
  out.reserve(m.tets.size());
  for (std::size_t i = 0; i < m.tets.size(); ++i)
    if (ok[i])
      out.push_back(i);
    else if (skipped)
      skipped->push_back({which, i, *element_problem(m, i, which)});
  return out;
}

std::vector<std::array<std::size_t, 2>> intersecting_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                           const Mesh* B, const std::vector<std::size_t>& eb) {
  BroadphaseOptions bo;
  bo.drop_shared_vertex = !B;
  bo.parallel = B != nullptr;  // as contacts(): the sequential self-intersection is faster
  std::vector<std::array<std::size_t, 2>> cand = B ? box_pairs(A, ea, *B, eb, bo) : box_pairs_self(A, ea, bo);
  const Mesh& BB = B ? *B : A;
  std::vector<char> hit(cand.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        hit[k] = fast::interiors_intersect(element(A, cand[k][0]), element(BB, cand[k][1]));
                    });
  std::vector<std::array<std::size_t, 2>> out;
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (hit[k]) out.push_back(cand[k]);
  return out;  // box_pairs is sorted by (a, b)
}

}  // namespace detail

namespace {

Mesh moved(const Mesh& m, const std::vector<Vec3d>& p, const char* what) {
  if (p.size() != m.vertices.size()) {
    std::ostringstream o;
    o << what << ": " << p.size() << " positions for a mesh of " << m.vertices.size() << " vertices";
    throw std::invalid_argument(o.str());
  }
  Mesh out;
  out.vertices = p;
  out.tets = m.tets;
  return out;
}

bool is_finite(const TetVertices& t) {
  for (const Vec3d& v : t)
    for (double x : v)
      if (!std::isfinite(x)) return false;
  return true;
}

// R2 and R4 over the rest-valid elements `e` of one mesh (element_quality, exact): appends the
// inverted or flat ones to `bad`, every one that falls short of R4 to `poor`, the elements
// usable for the broadphase (finite at P1) to `finite`; fills the per-element ratios (doubles)
// and the report's extremes.
void check_elements(const Mesh& m0, const Mesh& m1, char which, const std::vector<std::size_t>& e,
                    const QualityLimits& limits, ResolveReport& rep, std::vector<std::size_t>& finite,
                    std::vector<double>& volume_ratio, std::vector<double>& shape_ratio) {
  using detail::Quality;
  std::vector<Quality> verdict(e.size());
  volume_ratio.assign(m0.tets.size(), std::nan(""));
  shape_ratio.assign(m0.tets.size(), std::nan(""));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, e.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const TetVertices t0 = element(m0, e[k]), t1 = element(m1, e[k]);
      verdict[k] = detail::element_quality(t0, t1, limits);
      if (verdict[k] == Quality::NonFinite) continue;
      const detail::Ratios q = detail::scaled_ratios(t0, t1);
      // The sign of V1/V0 from the exact verdict (a nearly flat element's volume in doubles can
      // have the wrong sign).
      volume_ratio[e[k]] = verdict[k] == Quality::Inverted ? -std::abs(q.volume) : std::abs(q.volume);
      shape_ratio[e[k]] = q.shape;
    }
  });
  for (std::size_t k = 0; k < e.size(); ++k) {
    const std::size_t i = e[k];
    if (verdict[k] == Quality::Inverted || verdict[k] == Quality::NonFinite) rep.bad_elements.push_back({which, i});
    if (verdict[k] != Quality::Usable) rep.poor_elements.push_back({which, i});
    if (verdict[k] == Quality::NonFinite) continue;
    finite.push_back(i);
    rep.min_volume_ratio = std::min(rep.min_volume_ratio, volume_ratio[i]);
    rep.max_volume_ratio = std::max(rep.max_volume_ratio, volume_ratio[i]);
    rep.min_shape_ratio = std::min(rep.min_shape_ratio, shape_ratio[i]);
  }
}

void check_fixed(const Mesh& m0, const std::vector<Vec3d>& p1, const std::vector<char>& f, char which,
                 std::vector<std::pair<char, std::size_t>>& out) {
  for (std::size_t v = 0; v < f.size(); ++v)
    if (f[v] && std::memcmp(m0.vertices[v].data(), p1[v].data(), sizeof(Vec3d)) != 0) out.push_back({which, v});
}

}  // namespace

namespace {

// check_resolution and check_resolution_self (B0 == nullptr).
ResolveReport verdict(const Mesh& A0, const std::vector<Vec3d>& a1, const Mesh* B0,
                      const std::vector<Vec3d>& b1, const std::vector<char>& fixed_a,
                      const std::vector<char>& fixed_b, const QualityLimits& limits) {
  detail::check_limits(limits);
  detail::check_fixed_flags(fixed_a, A0, 'A');
  if (B0) detail::check_fixed_flags(fixed_b, *B0, 'B');
  const Mesh A1 = moved(A0, a1, "check_resolution, mesh A");
  const Mesh B1 = B0 ? moved(*B0, b1, "check_resolution, mesh B") : Mesh{};
  ResolveReport rep;
  rep.limits = limits;
  const std::vector<std::size_t> ea = detail::valid_elements(A0, 'A', &rep.skipped);
  const std::vector<std::size_t> eb = B0 ? detail::valid_elements(*B0, 'B', &rep.skipped) : std::vector<std::size_t>{};
  std::vector<std::size_t> fa, fb;
  rep.min_volume_ratio = rep.min_shape_ratio = HUGE_VAL;
  rep.max_volume_ratio = -HUGE_VAL;
  check_elements(A0, A1, 'A', ea, limits, rep, fa, rep.volume_ratio_a, rep.shape_ratio_a);
  if (B0) check_elements(*B0, B1, 'B', eb, limits, rep, fb, rep.volume_ratio_b, rep.shape_ratio_b);
  if (rep.min_volume_ratio == HUGE_VAL) rep.min_volume_ratio = rep.max_volume_ratio = rep.min_shape_ratio = 1;  // no element
  check_fixed(A0, a1, fixed_a, 'A', rep.moved_fixed_vertices);
  if (B0) check_fixed(*B0, b1, fixed_b, 'B', rep.moved_fixed_vertices);
  rep.remaining_pairs = detail::intersecting_pairs(A1, fa, B0 ? &B1 : nullptr, fb);
  rep.r1 = rep.remaining_pairs.empty();
  rep.r2 = rep.bad_elements.empty();
  rep.r3 = rep.moved_fixed_vertices.empty();
  rep.r4 = rep.poor_elements.empty();
  rep.resolved = rep.r1 && rep.r2 && rep.r3 && rep.r4;
  return rep;
}

}  // namespace

ResolveReport check_resolution(const Mesh& A0, const std::vector<Vec3d>& a1, const Mesh& B0,
                               const std::vector<Vec3d>& b1, const std::vector<char>& fixed_a,
                               const std::vector<char>& fixed_b, const QualityLimits& limits) {
  return verdict(A0, a1, &B0, b1, fixed_a, fixed_b, limits);
}

ResolveReport check_resolution_self(const Mesh& A0, const std::vector<Vec3d>& a1,
                                    const std::vector<char>& fixed_a, const QualityLimits& limits) {
  return verdict(A0, a1, nullptr, {}, fixed_a, {}, limits);
}

double mesh_cost(const Mesh& m, const std::vector<Vec3d>& p1) {
  if (p1.size() != m.vertices.size()) {
    std::ostringstream o;
    o << "mesh_cost: " << p1.size() << " positions for a mesh of " << m.vertices.size() << " vertices";
    throw std::invalid_argument(o.str());
  }
  struct Sum {
    double weighted = 0, volume = 0;
  };
  // The sums take every coordinate scaled by 2^-scale (the largest |coordinate| of the elements
  // and their positions in [1/2, 1) once scaled), the result scaled back by 2^(2 scale): V_e
  // sigma_e grows as L^5 for a mesh of size L and left the double range beyond L ~ 1e+-61 while
  // the cost itself (~L^2) did not. Scaling by a power of two commutes with every rounding
  // while no value leaves the normal range: at ordinary scales the same bits as the sums on the
  // coordinates as given.
  double largest = 0;
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const TetVertices t0 = element(m, e);
    if (!is_finite(t0)) continue;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k)
        largest = std::max({largest, std::abs(t0[i][k]), std::abs(p1[m.tets[e][i]][k])});
  }
  const int scale = detail::binary_exponent(largest);
  // x 2^-scale: a product by that power of two where it is a normal double (both correctly
  // rounded: the same bits as std::ldexp, a library call a coordinate that took most of the
  // time of a resolve round's cost on a mesh of 5,000 elements).
  const bool power_normal = scale > -1000 && scale < 1000;
  const double power = std::ldexp(1.0, power_normal ? -scale : 0);
  auto scaled = [scale, power_normal, power](double x) { return power_normal ? x * power : std::ldexp(x, -scale); };
  // sigma_e = (sum_i |d_i|^2 + |sum_i d_i|^2) / 20 (definitions §2), weighted by |V_e| at rest;
  // elements with a non-finite rest coordinate are left out (flat ones weigh 0).
  const Sum s = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, m.tets.size(), 4096), Sum{},
      [&](const tbb::blocked_range<std::size_t>& r, Sum acc) {
        for (std::size_t e = r.begin(); e != r.end(); ++e) {
          TetVertices t0 = element(m, e);
          if (!is_finite(t0)) continue;
          for (auto& x : t0)
            for (double& c : x) c = scaled(c);
          const double v = std::abs(detail::volume6(t0)) / 6;
          double sq = 0;
          Vec3d sum = {0, 0, 0};
          for (int i = 0; i < 4; ++i) {
            const Vec3d& q = p1[m.tets[e][i]];
            for (int k = 0; k < 3; ++k) {
              const double d = scaled(q[k]) - t0[i][k];
              sq += d * d;
              sum[k] += d;
            }
          }
          acc.weighted += v * (sq + sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / 20;
          acc.volume += v;
        }
        return acc;
      },
      [](Sum x, const Sum& y) {
        x.weighted += y.weighted;
        x.volume += y.volume;
        return x;
      });
  if (!(s.volume > 0)) return 0;
  // Beyond the double range: +inf above it; NaN for a positive cost below the normal range
  // (not representable: written as null, as an overflowing one is).
  const double in_scale = s.weighted / s.volume, cost = std::ldexp(in_scale, 2 * scale);
  return in_scale > 0 && !(cost >= std::numeric_limits<double>::min()) ? std::numeric_limits<double>::quiet_NaN() : cost;
}

}  // namespace pdd::mesh
