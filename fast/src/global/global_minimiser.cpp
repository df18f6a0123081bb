// global_minimiser.cpp — pdd/global_minimiser.h: solve_pair's definitions §9 fields alone
// (fast/src/solve_pair.cpp's solve_record with `global`, restricted to its common double path).
#include "pdd/global_minimiser.h"

#include <cmath>
#include <memory>

#include "exact/exact_candidate.h"
#include "global/global_depth.h"
#include "kernel/direction_geometry.h"
#include "kernel/power_scale.h"
#include "kernel/quick_candidates.h"
#include "kernel/rigid_depth.h"
#include "qp/deformable_depth.h"

namespace pdd::fast {

std::optional<GlobalMinimiser> global_minimiser(const TetVertices& A, const TetVertices& B) {
  if (!detail::all_finite(A) || !detail::all_finite(B)) return std::nullopt;
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  if (!sp.exact) return std::nullopt;
  // solve_pair: the quick lanes (valid, intersecting, every filter verdict clear), pdd2_relaxed
  // from their sweep, rigid_pd2 over the candidates (QuickCandidates gives the same candidates,
  // in the same order, bit for bit, as the set solve_pair builds: quick_candidates.h).
  std::unique_ptr<QuickCandidates> q(new QuickCandidates);  // ~8 KB: off TBB's worker stacks
  if (!quick_lanes(sp.A, sp.B, *q)) return std::nullopt;
  Choice rel;
  if (!pdd2_relaxed_lanes(*q, rel) || !rel.certified || !(rel.value > 0)) return std::nullopt;
  quick_edge_list(*q);
  const Choice rigid = rigid_pd2(*q);
  if (!rigid.certified) return std::nullopt;
  int index = -1;  // the relaxed choice's candidate (its label, as solve_pair finds it)
  for (int k = 0; k < q->count && index < 0; ++k)
    if (label_code(*q, k) == rel.code) index = k;
  if (index < 0) return std::nullopt;
  const Candidate c = candidate(*q, index);
  const double start[3] = {c.n[0], c.n[1], c.n[2]};
  const DirectionLabel label = rel.label();
  const TetVertices &As = sp.A, &Bs = sp.B;
  const ExactStart exact_start = [&]() -> std::array<double, 3> {
    return detail::rounded_normal(detail::exact_candidate(detail::exact_frame(As, Bs), label).n);
  };
  const GlobalOptimum g = global_depth(As, Bs, start, rel.value, exact_start, rigid.value);
  if (!g.certified || g.exact_value) return std::nullopt;
  if (!(g.normal[0] != 0 || g.normal[1] != 0 || g.normal[2] != 0)) return std::nullopt;
  bool in_range = true;
  GlobalMinimiser m;
  m.pd2 = detail::unscaled(g.value, 2 * -sp.e, in_range);
  const double relaxed = detail::unscaled(rel.value, 2 * -sp.e, in_range);
  if (!in_range || !(m.pd2 == 0 || std::isnormal(m.pd2))) return std::nullopt;
  if (!(m.pd2 <= (1 - kClampMargin) * relaxed)) return std::nullopt;  // (the header: a tie)
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      m.q1_A[i][k] = std::ldexp(g.q1_A[i][k], -sp.e);
      m.q1_B[i][k] = std::ldexp(g.q1_B[i][k], -sp.e);
      if (!std::isfinite(m.q1_A[i][k]) || !std::isfinite(m.q1_B[i][k])) return std::nullopt;
    }
  m.normal = g.normal;
  detail::power_normalized(m.normal);
  return m;
}

}  // namespace pdd::fast
