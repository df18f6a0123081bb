// check_resolution.cpp — the exact verdict R1–R3 on given positions (mesh.h), the mesh object
// norm mesh_cost, and the contact stage the rounds of resolve share with the verdict
// (resolve.h).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "resolve.h"

namespace pdd::mesh {
namespace detail {

int orientation(const Vec3d& p0, const Vec3d& p1, const Vec3d& p2, const Vec3d& p3) {
  using P = CGAL::Epick::Point_3;
  auto p = [](const Vec3d& v) { return P(v[0], v[1], v[2]); };
  return int(CGAL::orientation(p(p0), p(p1), p(p2), p(p3)));  // exact (filtered) predicate
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
  std::vector<std::array<std::size_t, 2>> cand = box_pairs(A, ea, B, eb, bo);
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

double signed_volume6(const TetVertices& t) {
  const Vec3d u = {t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]};
  const Vec3d v = {t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]};
  const Vec3d w = {t[3][0] - t[0][0], t[3][1] - t[0][1], t[3][2] - t[0][2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

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

void check_flags(const std::vector<char>& f, const Mesh& m, char which) {
  if (!f.empty() && f.size() != m.vertices.size()) {
    std::ostringstream o;
    o << "fixed-vertex flags of mesh " << which << ": " << f.size() << " flags for " << m.vertices.size()
      << " vertices";
    throw std::invalid_argument(o.str());
  }
}

bool is_finite(const TetVertices& t) {
  for (const Vec3d& v : t)
    for (double x : v)
      if (!std::isfinite(x)) return false;
  return true;
}

// R2 over the rest-valid elements `e` of one mesh: appends bad ones, returns the smallest
// V1 / V0 and the elements usable for the broadphase (finite at P1).
double check_orientation(const Mesh& m0, const Mesh& m1, char which, const std::vector<std::size_t>& e,
                         std::vector<std::pair<char, std::size_t>>& bad, std::vector<std::size_t>& finite) {
  std::vector<char> flag(e.size());  // 0 ok, 1 inverted or flat, 2 non-finite
  std::vector<double> ratio(e.size(), HUGE_VAL);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, e.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const TetVertices t0 = element(m0, e[k]), t1 = element(m1, e[k]);
      if (!is_finite(t1)) {
        flag[k] = 2;
        continue;
      }
      const int s0 = detail::orientation(t0[0], t0[1], t0[2], t0[3]);
      const int s1 = detail::orientation(t1[0], t1[1], t1[2], t1[3]);
      flag[k] = s1 != s0;  // s0 != 0: e holds the elements valid at rest
      // |V1| / |V0| in doubles, signed by the exact verdict (a nearly flat element's volume
      // in doubles can have the wrong sign).
      ratio[k] = std::abs(signed_volume6(t1) / signed_volume6(t0)) * (s1 == s0 ? 1 : s1 == 0 ? 0 : -1);
    }
  });
  double lo = HUGE_VAL;
  for (std::size_t k = 0; k < e.size(); ++k) {
    if (flag[k]) bad.push_back({which, e[k]});
    if (flag[k] != 2) finite.push_back(e[k]);
    lo = std::min(lo, ratio[k]);
  }
  return lo;
}

void check_fixed(const Mesh& m0, const std::vector<Vec3d>& p1, const std::vector<char>& f, char which,
                 std::vector<std::pair<char, std::size_t>>& out) {
  for (std::size_t v = 0; v < f.size(); ++v)
    if (f[v] && std::memcmp(m0.vertices[v].data(), p1[v].data(), sizeof(Vec3d)) != 0) out.push_back({which, v});
}

}  // namespace

ResolveReport check_resolution(const Mesh& A0, const std::vector<Vec3d>& a1, const Mesh* B0,
                               const std::vector<Vec3d>& b1, const std::vector<char>& fixed_a,
                               const std::vector<char>& fixed_b) {
  check_flags(fixed_a, A0, 'A');
  if (B0) check_flags(fixed_b, *B0, 'B');
  const Mesh A1 = moved(A0, a1, "check_resolution, mesh A");
  const Mesh B1 = B0 ? moved(*B0, b1, "check_resolution, mesh B") : Mesh{};
  ResolveReport rep;
  const std::vector<std::size_t> ea = detail::valid_elements(A0, 'A', &rep.skipped);
  const std::vector<std::size_t> eb = B0 ? detail::valid_elements(*B0, 'B', &rep.skipped) : std::vector<std::size_t>{};
  std::vector<std::size_t> fa, fb;
  rep.min_volume_ratio = check_orientation(A0, A1, 'A', ea, rep.bad_elements, fa);
  if (B0) rep.min_volume_ratio = std::min(rep.min_volume_ratio, check_orientation(*B0, B1, 'B', eb, rep.bad_elements, fb));
  if (rep.min_volume_ratio == HUGE_VAL) rep.min_volume_ratio = 1;  // no element
  check_fixed(A0, a1, fixed_a, 'A', rep.moved_fixed_vertices);
  if (B0) check_fixed(*B0, b1, fixed_b, 'B', rep.moved_fixed_vertices);
  rep.remaining_pairs = detail::intersecting_pairs(A1, fa, B0 ? &B1 : nullptr, fb);
  rep.r1 = rep.remaining_pairs.empty();
  rep.r2 = rep.bad_elements.empty();
  rep.r3 = rep.moved_fixed_vertices.empty();
  rep.resolved = rep.r1 && rep.r2 && rep.r3;
  return rep;
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
  // sigma_e = (sum_i |d_i|^2 + |sum_i d_i|^2) / 20 (definitions §2), weighted by |V_e| at rest;
  // elements with a non-finite rest coordinate are left out (flat ones weigh 0).
  const Sum s = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, m.tets.size(), 4096), Sum{},
      [&](const tbb::blocked_range<std::size_t>& r, Sum acc) {
        for (std::size_t e = r.begin(); e != r.end(); ++e) {
          const TetVertices t0 = element(m, e);
          if (!is_finite(t0)) continue;
          const double v = std::abs(signed_volume6(t0)) / 6;
          double sq = 0;
          Vec3d sum = {0, 0, 0};
          for (int i = 0; i < 4; ++i) {
            const Vec3d& q = p1[m.tets[e][i]];
            for (int k = 0; k < 3; ++k) {
              const double d = q[k] - t0[i][k];
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
  return s.volume > 0 ? s.weighted / s.volume : 0;
}

}  // namespace pdd::mesh
