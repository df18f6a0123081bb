// paper_experiment.h — the statistics of the paper's Sec. VI experiment (Table I, the
// direction statistics, Fig. 3), from either engine's results.
//
// Input : the results of a set of intersecting pairs (non-intersecting or rejected ones are
//         skipped and counted).
// Output: PD_d / PD = sqrt(pdd2_x / rigid_pd2) per variant, mean and sample standard deviation
//         (Table I's "PD_d/PD"); the same over eq. 11's value in place of PD, so the reader sees
//         what the paper's formula would have given; the fraction of pairs whose rigid
//         direction is the case-2 optimal direction (paper: 52.33%) and whose case-2 optimum
//         lies among the first six candidates in depth order (pdd2_accel6 == pdd2; paper:
//         "more than 90%").
#pragma once

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pdd/pair_result.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

struct RatioStats {
  double mean = 0, std = 0;
  std::size_t n = 0;
  std::vector<double> values;  // for histograms
};

// The variants of Table I and ours, in report order.
inline const std::array<const char*, 5> kPaperVariants = {"static/def", "def/def", "accelerated (1)",
                                                          "accelerated (6)", "relaxed"};

struct PaperStats {
  std::size_t pairs = 0, skipped = 0;
  std::array<RatioStats, 5> over_pd;   // PD_d / PD, per kPaperVariants
  std::array<RatioStats, 5> over_e11;  // PD_d / E11
  std::size_t rigid_is_optimal = 0;    // rigid_dir == pdd2_dir
  std::size_t optimum_in_first_six = 0;
};

RatioStats ratio_stats(std::vector<double> values);

// R: double (fast engine) or an exact rational type with a to_double conversion `to_d`.
template <class R, class ToDouble>
PaperStats paper_statistics(const std::vector<PairResult<R>>& results, ToDouble to_d) {
  PaperStats s;
  std::array<std::vector<double>, 5> pd, e11;
  for (const auto& r : results) {
    if (r.error || !r.intersecting) {
      ++s.skipped;
      continue;
    }
    ++s.pairs;
    const std::array<double, 5> v = {to_d(r.pdd2_static), to_d(r.pdd2), to_d(r.pdd2_accel1),
                                     to_d(r.pdd2_accel6), to_d(r.pdd2_relaxed)};
    for (int k = 0; k < 5; ++k) {
      pd[k].push_back(std::sqrt(v[k] / to_d(r.rigid_pd2)));
      e11[k].push_back(std::sqrt(v[k] / to_d(r.eq11_pd2)));
    }
    s.rigid_is_optimal += (r.rigid_dir == r.pdd2_dir);
    s.optimum_in_first_six += (r.pdd2_accel6 == r.pdd2);
  }
  for (int k = 0; k < 5; ++k) {
    s.over_pd[k] = ratio_stats(std::move(pd[k]));
    s.over_e11[k] = ratio_stats(std::move(e11[k]));
  }
  return s;
}

// definitions §9: what the paper's restriction to the candidate directions costs. Per intersecting
// pair: PD_d_global / PD = sqrt(pdd2_global / rigid_pd2); the squared ratios pdd2 / pdd2_global
// and pdd2_relaxed / pdd2_global (>= 1; the values of RatioStats hold them for medians,
// maxima and histograms); whether the global optimum is a candidate's (pdd2_relaxed within
// 1e-9 of pdd2_global: the best relaxed candidate attains it); and the angle, in degrees,
// between pdd2_global_normal and the nearest oriented candidate direction (definitions §3).
struct GlobalStats {
  std::size_t pairs = 0;
  RatioStats global_over_pd, pdd2_over_global, relaxed_over_global, angle_degrees;
  std::size_t at_candidate = 0;
};

// `candidate_normals(pair)` returns the pair's oriented candidate directions (any length).
template <class R, class ToDouble, class Candidates>
GlobalStats global_statistics(const std::vector<TetPair>& pairs, const std::vector<PairResult<R>>& results,
                              ToDouble to_d, Candidates candidate_normals) {
  GlobalStats s;
  std::vector<double> over_pd, pdd2_ratio, relaxed_ratio, angle;
  for (std::size_t i = 0; i < results.size() && i < pairs.size(); ++i) {
    const auto& r = results[i];
    if (r.error || !r.intersecting || !r.pdd2_global_normal) continue;
    const double g = to_d(r.pdd2_global);
    if (!(g > 0)) continue;
    ++s.pairs;
    over_pd.push_back(std::sqrt(g / to_d(r.rigid_pd2)));
    pdd2_ratio.push_back(to_d(r.pdd2) / g);
    relaxed_ratio.push_back(to_d(r.pdd2_relaxed) / g);
    s.at_candidate += (to_d(r.pdd2_relaxed) <= g * (1 + 1e-9));
    // Both vectors divided by their largest component first (in R for the normal): an exact
    // normal of a pair far from the unit scale need not fit a double, and squares of a
    // candidate's components of 1e205 overflow.
    const auto& nr = *r.pdd2_global_normal;
    auto magnitude = [](const R& x) { return x < R(0) ? R(-x) : x; };
    const R big = std::max({magnitude(nr[0]), magnitude(nr[1]), magnitude(nr[2])});
    const double n[3] = {to_d(nr[0] / big), to_d(nr[1] / big), to_d(nr[2] / big)};
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double best = -1;
    for (std::array<double, 3> c : candidate_normals(pairs[i])) {
      const double cm = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2])});
      if (!(cm > 0 && cm <= std::numeric_limits<double>::max())) continue;
      for (double& x : c) x /= cm;
      const double cc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      best = std::max(best, (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / (nn * cc));
    }
    angle.push_back(std::acos(std::min(1.0, std::max(-1.0, best))) * 180.0 / M_PI);
  }
  s.global_over_pd = ratio_stats(std::move(over_pd));
  s.pdd2_over_global = ratio_stats(std::move(pdd2_ratio));
  s.relaxed_over_global = ratio_stats(std::move(relaxed_ratio));
  s.angle_degrees = ratio_stats(std::move(angle));
  return s;
}

// Tetrahedron volumes (A and B pooled); their quantiles: stats.h.
std::vector<double> tetrahedron_volumes(const std::vector<TetPair>& pairs);

}  // namespace pdd::compare
