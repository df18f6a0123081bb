// stats.h — the summary statistics of compare/, defined once: median and quantiles.
//
//   quantiles(v, p)  for each probability p in [0, 1], the value at position p·(n−1) of v
//                    sorted ascending, interpolated linearly between the two ranks around it
//                    (Hyndman & Fan's type 7, R's and NumPy's default); empty for an empty v.
//   median(v)        quantile 0.5: the middle value of v sorted, or for an even count the mean
//                    of the two middle values; NaN for an empty v (no median exists: a caller
//                    that prints one says what it prints instead).
// Every median that `pdd compare`, `pdd paper` and `pdd bench` report is this one.
#pragma once

#include <vector>

namespace pdd::compare {

double median(std::vector<double> values);
std::vector<double> quantiles(std::vector<double> values, const std::vector<double>& probabilities);

}  // namespace pdd::compare
