// paper_sample.h — the exact side of `pdd paper` (the paper's Sec. VI experiment): the paper's
// own Table I for the side-by-side columns, the exact engine on a random sample of the pairs
// (values, definitions §8 verdicts of the fast engine, single-call timings), and the pair
// drawn in Fig. 2.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pdd/pair_result.h"
#include "pdd/reference/solve_exact.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

// The paper's Table I (Kim & Kim, Sec. VI), for the side-by-side columns.
struct PaperColumn {
  const char* time;
  const char* ratio;
};
inline const std::array<PaperColumn, 5> kPaperTableI = {{{"32.26 ms", "43.59% (13.17%)"},
                                                  {"46.29 ms", "27.94% (3.15%)"},
                                                  {"1.07 ms", "29.39% (3.47%)"},
                                                  {"-", "-"},
                                                  {"-", "-"}}};
// Which timed fast variant belongs to each kPaperVariants column.
inline const std::array<const char*, 5> kTimedVariant = {"pdd2_static", "pdd2", "pdd2_accel1", "pdd2_accel6", "pdd2_relaxed"};

struct ExactSample {
  std::vector<std::size_t> indices;  // into the pairs, ascending
  std::vector<reference::ExactResult> results;
  std::vector<double> call_ns;  // per pair: timing.h's single-call protocol (one core, in order)
  std::size_t over_tolerance = 0, labels_differ = 0;
  std::array<double, kValueCount> max_rel_error{};  // per kValueKeys
};

// The exact engine on m pairs drawn without replacement (seeded), compared with `fast`.
ExactSample run_exact_sample(const std::vector<TetPair>& pairs,
                             const std::vector<PairResult<double>>& fast, std::size_t m,
                             std::uint64_t seed);

// Index (into the sample) of the pair drawn in Fig. 2: among the pairs whose def/def ratio is
// within 10% of the sample median (a typical pair), the one with the largest PD relative to its
// extent, so that the deformation is visible at the scale of the picture.
std::size_t figure_pair(const ExactSample& s, const std::vector<TetPair>& pairs);

}  // namespace pdd::compare
