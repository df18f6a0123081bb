// paper_sample.cpp — see paper_sample.h.
#include "pdd/compare/paper_sample.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "pdd/compare/engine_comparison.h"
#include "pdd/compare/stats.h"
#include "pdd/compare/timing.h"
#include "pdd/io/progress.h"

namespace pdd::compare {
using io::Progress;

ExactSample run_exact_sample(const std::vector<TetPair>& pairs, const std::vector<PairResult<double>>& fast,
                             std::size_t m, std::uint64_t seed) {
  ExactSample s;
  std::vector<std::size_t> all(pairs.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ULL);
  for (std::size_t k = 0; k < std::min(m, all.size()); ++k)  // partial Fisher-Yates
    std::swap(all[k], all[k + rng() % (all.size() - k)]);
  s.indices.assign(all.begin(), all.begin() + std::min(m, all.size()));
  std::sort(s.indices.begin(), s.indices.end());
  s.results.resize(s.indices.size());
  Progress progress("pdd paper: exact sample", s.indices.size());
  s.call_ns = time_each_call(s.indices.size(), [&](std::size_t k) {
    s.results[k] = reference::solve_exact(pairs[s.indices[k]], {QpFormulation::Reduced});
    progress.tick();
  });
  progress.finish();
  for (std::size_t k = 0; k < s.indices.size(); ++k) {
    const auto c = compare_pair(pairs[s.indices[k]], s.results[k], fast[s.indices[k]]);
    s.over_tolerance += c.over_tolerance();
    for (auto l : c.labels) s.labels_differ += (l == LabelVerdict::Differ);
    for (std::size_t v = 0; v < kValueCount; ++v)
      s.max_rel_error[v] = std::max(s.max_rel_error[v], c.rel_error[v]);
  }
  return s;
}

std::size_t figure_pair(const ExactSample& s, const std::vector<TetPair>& pairs) {
  std::vector<double> ratio(s.results.size(), -1);
  std::vector<double> valid;
  for (std::size_t k = 0; k < s.results.size(); ++k)
    if (s.results[k].intersecting)
      valid.push_back(ratio[k] = std::sqrt(CGAL::to_double(s.results[k].pdd2) / CGAL::to_double(s.results[k].rigid_pd2)));
  const double med = median(valid);
  std::size_t best = 0;
  double best_score = -1;
  for (std::size_t k = 0; k < s.results.size(); ++k) {
    if (ratio[k] < 0 || std::abs(ratio[k] - med) > 0.1 * med) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto* t : {&pairs[s.indices[k]].A, &pairs[s.indices[k]].B})
      for (const auto& v : *t)
        for (double x : v) lo = std::min(lo, x), hi = std::max(hi, x);
    const double score = std::sqrt(CGAL::to_double(s.results[k].rigid_pd2)) / (hi - lo);
    if (score > best_score) best_score = score, best = k;
  }
  return best;
}

}  // namespace pdd::compare
