// deformable_depth.cpp — SPEC §5 variants with exact pruning. See the header.
#include "pdd/fast/deformable_depth.h"

#include <limits>

#include "pdd/fast/superset_depth.h"
#include "pdd/fast/tie_tolerance.h"

namespace pdd::fast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline bool usable(const CandidateSet& set) { return set.intersecting && set.count > 0; }
inline bool usable(const QuickCandidates& q) { return q.count > 0; }  // intersecting by contract

// Sweep in canonical order, skipping candidates whose lower bound coeff·delta² cannot reach
// the best value so far (header), then pick the first tied minimum. List: CandidateSet or
// QuickCandidates (same candidates, same order, same values).
template <class List, class Value>
Choice sweep(const List& set, double coeff, int hint, Value value) {
  if (!usable(set)) return {};
  double v[kMaxCandidates];
  double best = kInf, threshold = kInf;  // threshold = tie_threshold(best) >= the final one
  if (hint >= 0 && hint < set.count) {
    best = v[hint] = value(candidate(set, hint));
    threshold = tie_threshold(best, set.tie_kappa);
  }
  for (int i = 0; i < set.count; ++i) {
    if (i == hint) continue;
    const double bound = coeff * delta2(set, i);
    if (!(bound <= threshold)) {
      v[i] = kInf;
      continue;
    }
    v[i] = value(candidate(set, i));
    if (v[i] < best) {
      best = v[i];
      threshold = tie_threshold(best, set.tie_kappa);
    }
  }
  Choice ch;
  ch.index = first_tied_minimum(v, set.count, set.tie_kappa);
  ch.value = v[ch.index];
  ch.code = label_code(set, ch.index);
  return ch;
}

template <class List>
int accel_order_of(const List& set, int k, int* out) {
  double d[kMaxCandidates];
  for (int i = 0; i < set.count; ++i) d[i] = delta2(set, i);
  const int m = k < set.count ? k : set.count;
  for (int r = 0; r < m; ++r) {
    out[r] = first_tied_minimum(d, set.count, set.tie_kappa);
    d[out[r]] = kInf;  // taken
  }
  return m;
}

template <class List>
Choice accel_of(const List& set, int k) {
  if (!usable(set) || k <= 0) return {};
  if (k == 1) {
    const int i = rigid_pd2(set).index;
    return {deformable_value(candidate(set, i)), i, label_code(set, i)};
  }
  int order[kMaxCandidates];
  const int m = accel_order_of(set, k, order);
  if (m <= 0) return {};
  double v[kMaxCandidates];
  for (int r = 0; r < m; ++r) v[r] = deformable_value(candidate(set, order[r]));
  const double vmin = minimum(v, m);
  int best = -1;  // among ties, the first in canonical order
  for (int r = 0; r < m; ++r)
    if (ties_with_min(v[r], vmin, set.tie_kappa) && (best < 0 || order[r] < order[best])) best = r;
  return {v[best], order[best], label_code(set, order[best])};
}

}  // namespace

SideProblem side_problem(const double h[4], std::uint8_t constrained) {
  SideProblem s;
  for (int i = 0; i < 4; ++i) {
    if (constrained >> i & 1u) {
      ++s.ncon;
      s.hcon = h[i];
    } else {
      s.hfree[s.nfree++] = h[i];
    }
  }
  return s;
}

double static_value(const Candidate& c) {
  if (c.label.orientation != EdgeOrientation::Decided) return kInf;  // infeasible (SPEC §5)
  const DirectionSolution s = solve_static(side_problem(c.hA, c.conA), side_problem(c.hB, c.conB));
  return s.cost / (20.0 * c.nn);
}

double deformable_value(const Candidate& c) {
  const DirectionSolution s =
      solve_deformable(side_problem(c.hA, c.conA), side_problem(c.hB, c.conB));
  return s.cost / (20.0 * c.nn);
}

double relaxed_value(const Candidate& c) { return solve_relaxed(c.hA, c.hB).cost / (20.0 * c.nn); }

Choice pdd2_static(const CandidateSet& set, int hint) {
  return sweep(set, kStaticBoundCoeff, hint, static_value);
}
Choice pdd2(const CandidateSet& set, int hint) {
  return sweep(set, kDeformableBoundCoeff, hint, deformable_value);
}
Choice pdd2_relaxed(const CandidateSet& set, int hint) {
  return sweep(set, kDeformableBoundCoeff, hint, relaxed_value);
}
Choice pdd2_static(const QuickCandidates& q, int hint) {
  return sweep(q, kStaticBoundCoeff, hint, static_value);
}
Choice pdd2(const QuickCandidates& q, int hint) {
  return sweep(q, kDeformableBoundCoeff, hint, deformable_value);
}
Choice pdd2_relaxed(const QuickCandidates& q, int hint) {
  return sweep(q, kDeformableBoundCoeff, hint, relaxed_value);
}

int accel_order(const CandidateSet& set, int k, int* out) { return accel_order_of(set, k, out); }
Choice pdd2_accel(const CandidateSet& set, int k) { return accel_of(set, k); }
Choice pdd2_accel(const QuickCandidates& q, int k) { return accel_of(q, k); }

void deformed_positions(const TetVertices& A, const TetVertices& B, const Candidate& c,
                        Positions<double>& qA, Positions<double>& qB) {
  const DirectionSolution s =
      solve_deformable(side_problem(c.hA, c.conA), side_problem(c.hB, c.conB));
  for (int i = 0; i < 4; ++i) {
    const double tA = displacement_below(c.hA[i], c.conA >> i & 1u, s) / c.nn;
    const double tB = displacement_above(c.hB[i], c.conB >> i & 1u, s) / c.nn;
    for (int k = 0; k < 3; ++k) {
      qA[i][k] = A[i][k] + tA * c.n[k];
      qB[i][k] = B[i][k] + tB * c.n[k];
    }
  }
}

namespace {
// The quick list when it decides, else the full candidate set (both on the stack).
template <class F>
Choice on_pair(const TetVertices& A, const TetVertices& B, F f) {
  QuickCandidates q;
  if (quick_candidates(A, B, q)) return f(q);
  CandidateSet set;
  if (build_candidates(A, B, set) != BuildStatus::Ok || !set.intersecting) return {};
  return f(set);
}
}  // namespace

Choice pdd2_static(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const auto& s) { return pdd2_static(s, rigid_pd2(s).index); });
}
Choice pdd2(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const auto& s) { return pdd2(s, rigid_pd2(s).index); });
}
Choice pdd2_relaxed(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const auto& s) { return pdd2_relaxed(s, rigid_pd2(s).index); });
}
Choice pdd2_accel(const TetVertices& A, const TetVertices& B, int k) {
  Choice rigid;
  Candidate c;
  if (k == 1 && rigid_superset(A, B, rigid, &c)) return {deformable_value(c), -1, rigid.code};
  return on_pair(A, B, [k](const auto& s) { return pdd2_accel(s, k); });
}

}  // namespace pdd::fast
