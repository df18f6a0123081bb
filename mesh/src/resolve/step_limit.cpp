// step_limit.cpp — the step limit that keeps R2 and R4 along the rounds (step_limit.h).
#include "step_limit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "../element_quality.h"
#include "../resolve.h"
#include "geometry.h"

namespace pdd::mesh::detail {
namespace {

// R4 with a safety margin, in doubles (the step limit's test): the ratios in doubles carry a
// relative error of a few ulps times the element's condition, far below kQualityMargin for
// every element that is not nearly flat at rest, so a state that passes this test passes the
// exact R4 verdict too (which stays the judge: check_resolution decides it afresh).
constexpr double kQualityMargin = 1.0 / 64;
bool usable_with_margin(const QualityLimits& q, const Ratios& r) {
  const double m = 1 + kQualityMargin;
  return r.volume >= q.min_volume_ratio * m && r.volume * q.min_volume_ratio * m <= 1 &&
         r.shape >= q.min_shape_ratio * m;
}

// Halvings of a vertex's step before the step limit sets it to 0 (step_limit.h: the limit then
// ends with every element valid): 2^-24 of a step is below any displacement that matters.
constexpr int kMaxHalvings = 24;

// Element e of s passes R2 (same orientation as at rest) and R4 with the margin.
bool passes(const Side& s, std::size_t e) {
  const TetVertices q = element(s.cur, e);
  return orientation(q[0], q[1], q[2], q[3]) == s.sign[e] && usable_with_margin(s.limits, ratios(s.d0[e], s.s0[e], scaled(q, s.factor[e])));
}

// The valid elements with a vertex v where t[v] > 0: the only ones a step can change.
std::vector<std::size_t> affected_elements(const Side& s, const std::vector<double>& t) {
  std::vector<std::size_t> affected;
  for (std::size_t e : s.elems)
    for (std::size_t v : s.rest->tets[e])
      if (t[v] > 0) {
        affected.push_back(e);
        break;
      }
  return affected;
}

}  // namespace

void accumulate(Side& s, std::size_t e, const std::array<Vec3d, 4>& d, Combine combine) {
  const double w = s.volume[e];
  for (int i = 0; i < 4; ++i) {
    const std::size_t v = s.rest->tets[e][i];
    if (s.is_fixed(v)) continue;
    if (combine == Combine::Longest) {  // acc holds the longest target, weight 1 once set
      if (s.weight[v] == 0 || dot(d[i], d[i]) > dot(s.acc[v], s.acc[v])) s.acc[v] = d[i];
      s.weight[v] = 1;
      continue;
    }
    add_to(s.acc[v], scaled(d[i], w));
    s.weight[v] += w;
  }
}

void move_side(Side& s, double overshoot) {
  const std::size_t nv = s.cur.vertices.size();
  std::vector<Vec3d> D(nv, {0, 0, 0});
  std::vector<double> t(nv, 0);  // the step length of each vertex (0: it stays)
  for (std::size_t v = 0; v < nv; ++v)
    if (s.weight[v] > 0) {
      D[v] = scaled(s.acc[v], 1 / s.weight[v]);
      if (finite(D[v]))
        t[v] = overshoot;
      else
        D[v] = {0, 0, 0};
    }
  const std::vector<Vec3d> before = s.cur.vertices;
  auto place = [&](std::size_t v) { s.cur.vertices[v] = t[v] > 0 ? moved_by(before[v], t[v], D[v]) : before[v]; };
  for (std::size_t v = 0; v < nv; ++v)
    if (t[v] > 0) place(v);
  // Passes of the limit: check the elements in `check` (first every affected one, then those
  // with a vertex whose t the last pass lowered: the others are as they were when they passed).
  std::vector<std::size_t> check = affected_elements(s, t);
  std::vector<char> bad, changed(nv, 0);
  for (int pass = 0; !check.empty(); ++pass) {
    bad.assign(check.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, check.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) bad[k] = !passes(s, check[k]);
                      });
    std::vector<std::size_t> lowered;
    for (std::size_t k = 0; k < check.size(); ++k)
      if (bad[k])
        for (std::size_t v : s.rest->tets[check[k]])
          if (t[v] > 0 && !changed[v]) {
            t[v] = pass < kMaxHalvings ? t[v] / 2 : 0;
            place(v);
            changed[v] = 1;
            lowered.push_back(v);
          }
    check.clear();
    for (std::size_t v : lowered)
      for (std::size_t k = s.vertex_start[v]; k < s.vertex_start[v + 1]; ++k) check.push_back(s.vertex_elems[k]);
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    for (std::size_t v : lowered) changed[v] = 0;
  }
  std::fill(s.acc.begin(), s.acc.end(), Vec3d{0, 0, 0});
  std::fill(s.weight.begin(), s.weight.end(), 0.0);
}

}  // namespace pdd::mesh::detail
