#include "pdd/compare/paper_experiment.h"

#include "pdd/compare/generate.h"

#include <algorithm>
#include <numeric>

namespace pdd::compare {

RatioStats ratio_stats(std::vector<double> values) {
  RatioStats s;
  s.n = values.size();
  if (s.n == 0) return s;
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(s.n);
  double ss = 0;
  for (double v : values) ss += (v - s.mean) * (v - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / double(s.n - 1)) : 0.0;
  s.values = std::move(values);
  return s;
}

std::vector<double> tetrahedron_volumes(const std::vector<TetPair>& pairs) {
  std::vector<double> out;
  for (const auto& p : pairs) out.push_back(tetrahedron_volume(p.A)), out.push_back(tetrahedron_volume(p.B));
  return out;
}

std::vector<double> quantiles(std::vector<double> values, const std::vector<double>& probabilities) {
  std::vector<double> out;
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  for (double p : probabilities) {
    const double pos = p * double(values.size() - 1);  // linear interpolation between ranks
    const std::size_t lo = std::size_t(pos);
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    out.push_back(values[lo] + (pos - double(lo)) * (values[hi] - values[lo]));
  }
  return out;
}

}  // namespace pdd::compare
