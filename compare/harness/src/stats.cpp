#include "pdd/compare/stats.h"

#include <algorithm>
#include <limits>

namespace pdd::compare {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return quantiles(std::move(values), {0.5}).front();
}

std::vector<double> quantiles(std::vector<double> values, const std::vector<double>& probabilities) {
  std::vector<double> out;
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  for (double p : probabilities) {
    const double pos = p * double(values.size() - 1);  // linear interpolation between ranks
    const std::size_t lo = std::size_t(pos);
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    const double frac = pos - double(lo);
    // frac == 0 or equal neighbours: the value itself (also when it is infinite)
    out.push_back(frac == 0 || values[hi] == values[lo] ? values[lo]
                                                        : values[lo] + frac * (values[hi] - values[lo]));
  }
  return out;
}

}  // namespace pdd::compare
