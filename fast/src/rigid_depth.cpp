// rigid_depth.cpp — SPEC §4. See the header.
#include "pdd/fast/rigid_depth.h"

#include <algorithm>

#include "pdd/fast/superset_depth.h"
#include "pdd/fast/tie_tolerance.h"

namespace pdd::fast {

Choice rigid_pd2(const CandidateSet& set) {
  if (!set.intersecting) return {};
  Choice ch;
  ch.index = first_tied_minimum(set.delta_sq, set.count, set.tie_kappa);
  ch.value = set.delta_sq[ch.index];
  ch.code = set.code[ch.index];
  return ch;
}

Choice rigid_pd2(const QuickCandidates& q) {
  Choice ch;
  ch.index = first_tied_minimum(q.delta_sq, q.count, q.tie_kappa);
  ch.value = q.delta_sq[ch.index];
  ch.code = label_code(q, ch.index);
  return ch;
}

double eq11_pd2(const CandidateSet& set) {
  if (!set.intersecting) return 0.0;
  double best = -1.0;  // min overlap²/nn over candidates
  for (int i = 0; i < set.count; ++i) {
    const Candidate c = candidate(set, i);
    const double loA = *std::min_element(c.hA, c.hA + 4), hiA = *std::max_element(c.hA, c.hA + 4);
    const double loB = *std::min_element(c.hB, c.hB + 4), hiB = *std::max_element(c.hB, c.hB + 4);
    const double overlap = (hiA - loA) + (hiB - loB) - (std::max(hiA, hiB) - std::min(loA, loB));
    if (overlap <= 0.0) return 0.0;
    const double v = overlap * overlap / c.nn;
    if (best < 0.0 || v < best) best = v;
  }
  return best;
}

Choice rigid_pd2(const TetVertices& A, const TetVertices& B) {
  Choice ch;
  if (rigid_superset(A, B, ch)) return ch;
  CandidateSet set;
  if (build_candidates(A, B, set) != BuildStatus::Ok) return {};
  return rigid_pd2(set);
}

}  // namespace pdd::fast
