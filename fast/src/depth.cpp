// depth.cpp — the public hot-path functions of pdd.h (Depth over raw vertices) on top of the
// engine's certified choices (rigid_depth.h, deformable_depth.h): status and label only; every
// value is the choice's own.
#include <cmath>
#include <limits>

#include "exact/exact_candidate.h"
#include "exact/exact_predicates.h"
#include "global/global_depth.h"
#include "kernel/anchor.h"
#include "kernel/candidate_directions.h"
#include "kernel/direction_geometry.h"
#include "kernel/power_scale.h"
#include "kernel/quick_candidates.h"
#include "kernel/rigid_depth.h"
#include "kernel/superset_depth.h"
#include "pdd/pdd.h"
#include "qp/deformable_depth.h"

namespace pdd::fast {
namespace {

bool rejected(const TetVertices& T) { return !detail::all_finite(T) || orientation_sign_exact(T) == Sign::Zero; }

Depth depth_of(const Choice& ch, const TetVertices& A, const TetVertices& B, bool labelled) {
  Depth d;
  if (std::isnan(ch.value)) {  // certified_hot_path: not representable after scaling back
    d.pd2 = std::numeric_limits<double>::quiet_NaN();
    d.status = DepthStatus::NotRepresentable;
    return d;
  }
  if (ch.value == 0.0) {  // not intersecting, or rejected: tell which (rare work only here)
    if (rejected(A) || rejected(B)) {
      d.status = DepthStatus::Rejected;
      d.pd2 = std::numeric_limits<double>::quiet_NaN();  // never readable as "not intersecting"
    }
    return d;
  }
  d.pd2 = ch.value;
  if (labelled) d.dir = ch.label();
  return d;
}

// The pair the engine computes on (pdd.h, "Translation"): the anchored pair where there is one.
// No function here returns positions, so nothing is moved back.
template <class F>
auto on_anchored(const TetVertices& A, const TetVertices& B, F f) {
  TetVertices As, Bs;
  if (detail::anchored(A, B, As, Bs)) return f(As, Bs);
  return f(A, B);
}

}  // namespace

Depth rigid_pd2(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, [](const TetVertices& a, const TetVertices& b) {
    return depth_of(rigid_pd2_choice(a, b), a, b, true);
  });
}
Depth pdd2_static(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, [](const TetVertices& a, const TetVertices& b) {
    return depth_of(pdd2_static_choice(a, b), a, b, true);
  });
}
Depth pdd2(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, [](const TetVertices& a, const TetVertices& b) {
    return depth_of(pdd2_choice(a, b), a, b, true);
  });
}
Depth pdd2_relaxed(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, [](const TetVertices& a, const TetVertices& b) {
    return depth_of(pdd2_relaxed_choice(a, b), a, b, true);
  });
}
Depth pdd2_accel(const TetVertices& A, const TetVertices& B, int k) {
  if (k != 1 && k != kAccelWide) {
    Depth d;
    d.status = DepthStatus::Rejected;
    d.pd2 = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  return on_anchored(A, B, [k](const TetVertices& a, const TetVertices& b) {
    return depth_of(pdd2_accel_choice(a, b, k), a, b, false);
  });
}

RigidAndAccel1 rigid_pd2_and_accel1(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, [](const TetVertices& a, const TetVertices& b) {
    Choice rigid, accel1;
    rigid_and_accel1_choices(a, b, rigid, accel1);
    return RigidAndAccel1{depth_of(rigid, a, b, true), depth_of(accel1, a, b, false)};
  });
}

namespace {

// pdd2_global's start where the quick list declines (parallel edges, coplanar faces): one
// candidate set on the scaled pair (as solve_pair builds it), the certified rigid choice over it
// (the enumeration's lower bound), pdd2_relaxed's choice over it (its candidate's normal the
// start, its certified value an upper bound on pdd2_global: global_depth.h's check, or +inf), its
// candidate. Without it the fallback below builds the set twice (rigid_pd2_choice, then
// pdd2_relaxed) and the enumeration has no start: on the aligned family of `pdd generate`
// ~57k instructions a pair before the enumeration, ~40k here (callgrind). false: the rigid
// choice not certified, or no relaxed candidate.
bool relaxed_on_set(const detail::ScaledPair& sp, Choice& rigid, Choice& rel, Candidate& c) {
  static thread_local CandidateSet set;  // (~20 KB: off TBB's worker stacks)
  if (build_candidates(sp.A, sp.B, set) != BuildStatus::Ok || !set.intersecting) return false;
  rigid = rigid_pd2(set);
  if (!rigid.certified || rigid.index < 0) return false;
  rel = pdd2_relaxed(set, rigid.index);
  if (rel.index < 0) return false;
  // Not certified (a tie the doubles cannot order, on shallow contacts): the candidate still
  // starts the search, with no upper bound (+inf), as solve_pair's fill_global takes it;
  // the fallback below would compute pdd2_relaxed on the exact path for that bound alone
  // (~2 M instructions a pair on the slowest aligned pairs).
  if (!rel.certified) rel.value = INFINITY;
  c = candidate(set, rel.index);
  return true;
}


NormalDepth pdd2_global_as_given(const TetVertices& A, const TetVertices& B) {
  NormalDepth d;
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  // The hot path: on the exactly scaled pair, the rigid value (the enumeration's lower bound
  // PD^2 / 32, global_depth.h), the start and a certified upper bound, from rigid_superset
  // and the case-2 value along its direction (case2_upper, deformable_depth.h: ~0.3 us; any
  // direction's value bounds pdd2_global, so the superset's `unique`, which pdd2_accel1 needs,
  // is not asked), or where they do not certify, from one quick candidate list (~1.1 us; the
  // same values, label and normal: superset_depth.h). The start: the rigid direction's
  // normal, whose relaxed value prunes every piece whose eigenvalues lie above it (with no
  // start, nothing is pruned until the first offer). Measured on the paper's pairs: starting
  // from the six shallowest candidates, or from pdd2_relaxed's candidate (its sweep costs
  // ~2 us), prunes a few more pieces but costs more than it saves. The bound: the case-2
  // value along the rigid direction, certified, >= relaxed along it >= pdd2_global
  // (global_depth.h's check of the double enumeration).
  if (sp.finite && sp.exact) {
    Choice rigid, accel1;
    Candidate c;
    // The upper bound: the certified case-2 value along the candidate, or +inf.
    bool have = rigid_superset(sp.A, sp.B, rigid, &c) && rigid.certified;
    if (have) accel1.value = case2_upper(sp.A, sp.B, c);
    if (!have) {
      QuickCandidates q;
      if (quick_candidates(sp.A, sp.B, q)) {
        rigid = rigid_pd2(q);
        accel1 = pdd2_accel(q, 1);
        have = rigid.certified && accel1.certified && rigid.index >= 0;
        if (have) c = candidate(q, rigid.index);
      }
    }
    // Where the list declines too (parallel edges, coplanar faces: the aligned pairs of
    // structured meshes), from the candidate set (relaxed_on_set): accel1 then holds pdd2_relaxed's
    // choice, the start its candidate and label.
    const Choice* labelled = &rigid;  // the exact start: this choice's label's exact normal
    if (!have && relaxed_on_set(sp, rigid, accel1, c)) have = true, labelled = &accel1;
    if (have && rigid.value > 0 && accel1.value > 0) {
      const TetVertices &As = sp.A, &Bs = sp.B;
      // (one pointer captured: std::function keeps it inline instead of allocating per call)
      const std::pair<const detail::ScaledPair*, const Choice*> start{&sp, labelled};
      const ExactStart rigid_start = [&start]() -> std::array<double, 3> {
        const detail::ScaledPair& p = *start.first;
        return detail::rounded_normal(detail::exact_candidate(detail::exact_frame(p.A, p.B), start.second->label()).n);
      };
      const GlobalOptimum g = global_depth(As, Bs, c.n, accel1.value, rigid_start, rigid.value);
      bool in_range = true;
      const double value = g.exact_value ? exact_relaxed_value(A, B, g.normal, in_range)
                                         : detail::unscaled(g.value, 2 * -sp.e, in_range);
      if (g.certified && in_range && std::isnormal(value) && value > 0) {
        d.pd2 = value;
        d.normal = g.normal;
        detail::power_normalized(d.normal);
        return d;
      }
      // Certified along a rational witness only (global_depth.h): no double normal attains the
      // value, here or in the search below (the same suspects): declined without it.
      if (g.witness) {
        d.pd2 = std::numeric_limits<double>::quiet_NaN();
        d.status = DepthStatus::NotRepresentable;
        return d;
      }
    }
  }
  const Depth rigid = depth_of(rigid_pd2_choice(A, B), A, B, false);  // intersecting, exactly
  d.status = rigid.status;
  if (rigid.status != DepthStatus::Ok || rigid.pd2 == 0.0) {
    if (rigid.status != DepthStatus::Ok) d.pd2 = std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  const double none[3] = {0, 0, 0};
  // pdd2_relaxed (certified): its value checks the double enumeration (global_depth.h), its
  // exact normal starts the exact one.
  const Depth rel = pdd2_relaxed(A, B);
  const double rel_value = rel.status == DepthStatus::Ok && rel.pd2 > 0 ? rel.pd2 : INFINITY;
  const ExactStart relaxed_start = [&]() -> std::array<double, 3> {
    if (!rel.dir) return {0, 0, 0};
    return detail::rounded_normal(detail::exact_candidate(detail::exact_frame(A, B), *rel.dir).n);
  };
  const GlobalOptimum g = sp.exact ? global_depth(sp.A, sp.B, none, std::ldexp(rel_value, 2 * sp.e), relaxed_start,
                                                  std::ldexp(rigid.pd2, 2 * sp.e))
                                   : global_depth(A, B, none, rel_value, relaxed_start, rigid.pd2);
  bool in_range = true;
  // computed in rationals: taken again on the pair as given (solve_pair.cpp says why)
  const double value = g.exact_value && sp.exact ? exact_relaxed_value(A, B, g.normal, in_range)
                       : sp.exact                ? detail::unscaled(g.value, 2 * -sp.e, in_range)
                                                 : g.value;
  if (!g.certified || !in_range || !std::isnormal(value) || !(value > 0)) {
    d.pd2 = std::numeric_limits<double>::quiet_NaN();
    d.status = DepthStatus::NotRepresentable;
    return d;
  }
  d.pd2 = value;
  d.normal = g.normal;
  detail::power_normalized(d.normal);
  return d;
}

}  // namespace

NormalDepth pdd2_global(const TetVertices& A, const TetVertices& B) {
  return on_anchored(A, B, pdd2_global_as_given);
}

}  // namespace pdd::fast
