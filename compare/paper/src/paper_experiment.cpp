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

}  // namespace pdd::compare
