// certify.h — internal to fast/src: SPEC §8 bounds of the candidates of a list (CandidateSet
// or QuickCandidates), from value_bounds.h. One place for "the root bound of candidate k".
#pragma once

#include <algorithm>
#include <cmath>

#include "candidate_directions.h"
#include "quick_candidates.h"
#include "value_bounds.h"

namespace pdd::fast::detail {

inline bool is_parallel(const CandidateSet& s, int k) { return s.lane[k] < 0 && s.parallel[k]; }
inline bool is_parallel(const QuickCandidates&, int) { return false; }  // quick declines them

// Root bound of delta² of candidate k (value_bounds.h, rigid).
template <class List>
double rigid_rel(const List& s, int k) {
  return rigid_root_rel(s.depth[k], s.nn[k], degree_bounds(s.fb, is_parallel(s, k)));
}

// Largest |height| of a candidate (value_bounds.h: Hm).
inline double max_height(const DirectionGeometry& c) {
  double m = 0.0;
  for (int i = 0; i < 4; ++i) m = std::max(m, std::max(std::fabs(c.hA[i]), std::fabs(c.hB[i])));
  return m;
}

// Root bound of a QP value v = F/(20 n.n) along candidate c.
inline double qp_rel(const Candidate& c, double v, const FilterBounds& fb) {
  return qp_root_rel(v * 20.0 * c.nn, c.nn, max_height(c), degree_bounds(fb, c.parallel));
}

}  // namespace pdd::fast::detail
