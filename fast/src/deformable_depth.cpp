// deformable_depth.cpp — SPEC §5 variants with exact pruning. See the header.
#include "pdd/fast/deformable_depth.h"

#include <limits>

#include "pdd/fast/tie_tolerance.h"

namespace pdd::fast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Sweep in canonical order, skipping candidates whose lower bound coeff·delta² cannot reach
// the best value so far (header), then pick the first tied minimum.
template <class Value>
Choice sweep(const CandidateSet& set, double coeff, int hint, Value value) {
  if (!set.intersecting || set.count == 0) return {};
  double v[kMaxCandidates];
  double best = kInf;
  if (hint >= 0 && hint < set.count) best = v[hint] = value(candidate(set, hint));
  for (int i = 0; i < set.count; ++i) {
    if (i == hint) continue;
    const double bound = coeff * delta2(set, i);
    if (!ties_with_min(bound, best)) {
      v[i] = kInf;
      continue;
    }
    v[i] = value(candidate(set, i));
    best = v[i] < best ? v[i] : best;
  }
  Choice ch;
  ch.index = first_tied_minimum(v, set.count);
  ch.value = v[ch.index];
  ch.code = set.code[ch.index];
  return ch;
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

int accel_order(const CandidateSet& set, int k, int* out) {
  double d[kMaxCandidates];
  for (int i = 0; i < set.count; ++i) d[i] = delta2(set, i);
  const int m = k < set.count ? k : set.count;
  for (int r = 0; r < m; ++r) {
    out[r] = first_tied_minimum(d, set.count);
    d[out[r]] = kInf;  // taken
  }
  return m;
}

Choice pdd2_accel(const CandidateSet& set, int k) {
  if (!set.intersecting || k <= 0) return {};
  if (k == 1) {
    const int i = rigid_pd2(set).index;
    return {deformable_value(candidate(set, i)), i, set.code[i]};
  }
  int order[kMaxCandidates];
  const int m = accel_order(set, k, order);
  if (m <= 0) return {};
  double v[kMaxCandidates];
  for (int r = 0; r < m; ++r) v[r] = deformable_value(candidate(set, order[r]));
  const double vmin = minimum(v, m);
  int best = -1;  // among ties, the first in canonical order
  for (int r = 0; r < m; ++r)
    if (ties_with_min(v[r], vmin) && (best < 0 || order[r] < order[best])) best = r;
  return {v[best], order[best], set.code[order[best]]};
}

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
template <class F>
Choice on_pair(const TetVertices& A, const TetVertices& B, F f) {
  CandidateSet set;
  if (build_candidates(A, B, set) != BuildStatus::Ok || !set.intersecting) return {};
  return f(set);
}
}  // namespace

Choice pdd2_static(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const CandidateSet& s) { return pdd2_static(s, rigid_pd2(s).index); });
}
Choice pdd2(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const CandidateSet& s) { return pdd2(s, rigid_pd2(s).index); });
}
Choice pdd2_relaxed(const TetVertices& A, const TetVertices& B) {
  return on_pair(A, B, [](const CandidateSet& s) { return pdd2_relaxed(s, rigid_pd2(s).index); });
}
Choice pdd2_accel(const TetVertices& A, const TetVertices& B, int k) {
  double rigid = 0.0;
  Candidate best;
  if (k == 1 && quick_rigid(A, B, rigid, best))
    return {deformable_value(best), -1,
            pack_label(best.label.kind, best.label.a, best.label.b, best.label.orientation)};
  return on_pair(A, B, [k](const CandidateSet& s) { return pdd2_accel(s, k); });
}

}  // namespace pdd::fast
