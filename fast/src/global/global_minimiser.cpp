// global_minimiser.cpp — pdd/global_minimiser.h: solve_pair's definitions §9 fields alone
// (fast/src/solve_pair.cpp's solve_record with `global`, restricted to its common double path).
#include "pdd/global_minimiser.h"
#include "pdd/pdd.h"

#include <cmath>

#include "exact/exact_candidate.h"
#include "global/global_depth.h"
#include "kernel/candidate_directions.h"
#include "kernel/direction_geometry.h"
#include "kernel/power_scale.h"
#include "kernel/quick_candidates.h"
#include "kernel/rigid_depth.h"
#include "qp/deformable_depth.h"

namespace pdd::fast {

namespace {

// A value within kClampMargin of pdd2_relaxed (the pair's best plane is, or is close to,
// pdd2_relaxed's candidate): solve_pair's record computes the rest of the chain of definitions
// §5 and lowers along it (value_relations.h's keep_exact_relations, on the values scaled back).
// The same here, from the same choices: pdd2_static and pdd2 from the lane sweeps (else the
// list's sweeps: the list gives the set's results, quick_candidates.h), pdd2_accel1 from the
// list; false (decline) when one of them is not certified
// or leaves the double range, where solve_pair would take its exact path.
// (solve_pair takes a lane choice only when its label is one of the list's candidates.)
int index_of(const QuickCandidates& q, LabelCode code) {  // the first candidate with that label, or -1
  for (int k = 0; k < q.count; ++k)
    if (label_code(q, k) == code) return k;
  return -1;
}
bool listed(const QuickCandidates& q, const Choice& ch) { return index_of(q, ch.code) >= 0; }

// The chain's choices, certified, lowered as keep_exact_relations lowers them (its order;
// pdd2_global depends on pdd2_relaxed, pdd2, pdd2_static, pdd2_accel1 and rigid_pd2 there).
bool lower_along_chain(int e, const Choice& rigid, const Choice& st, const Choice& accel1,
                       const Choice& def, const Choice& rel, double& value) {
  if (!st.certified || !def.certified || !accel1.certified) return false;
  bool ok = true;
  auto back = [&](double v) { return detail::unscaled(v, 2 * -e, ok); };
  const double r = back(rigid.value), a1 = back(accel1.value);
  double s = back(st.value), d = back(def.value), x = back(rel.value);
  if (!ok) return false;
  auto at_most = [](double& v, double b) {
    if (v > b) v = b;
  };
  at_most(s, r);  // keep_exact_relations, in its order
  at_most(d, s);
  at_most(d, a1);
  if (std::isnormal(r / 2)) at_most(d, r / 2);
  at_most(x, d);
  at_most(value, x);
  return true;
}

// (every sweep hinted by the rigid choice, as solve_pair's: fill_intersecting says why)
bool lower_at_tie(const QuickCandidates& q, int e, const Choice& rigid, const Choice& rel, double& value) {
  Choice st, def;
  if (!pdd2_static_lanes(q, st) || !listed(q, st)) st = pdd2_static(q, rigid.index);
  const Choice accel1 = pdd2_accel(q, 1);
  if (!pdd2_lanes(q, def) || !listed(q, def)) def = pdd2(q, rigid.index);
  return lower_along_chain(e, rigid, st, accel1, def, rel, value);
}

// The same on the candidate set, with solve_pair's calls where it has no lanes
// (fill_intersecting: every choice from the set's sweeps).
bool lower_at_tie(const CandidateSet& set, int e, const Choice& rigid, const Choice& rel, double& value) {
  const Choice st = pdd2_static(set, rigid.index);
  const Choice accel1 = pdd2_accel(set, 1);
  const Choice def = pdd2(set, rigid.index);
  return lower_along_chain(e, rigid, st, accel1, def, rel, value);
}

// g's positions and normal on the pair as given (m's value set): the positions scaled back by
// 2^-e, the normal power-normalised. std::nullopt where a position leaves the double range.
std::optional<GlobalMinimiser> placed_back(const GlobalOptimum& g, const detail::ScaledPair& sp, GlobalMinimiser& m) {
  // x 2^-e: a product with a normal power of two is rounded once, as ldexp rounds (the same
  // bits, subnormal results included), without a libm call per coordinate.
  const double unit = std::ldexp(1.0, -sp.e);
  const bool by_product = std::isnormal(unit);
  auto back = [&](double x) { return by_product ? x * unit : std::ldexp(x, -sp.e); };
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      m.q1_A[i][k] = back(g.q1_A[i][k]);
      m.q1_B[i][k] = back(g.q1_B[i][k]);
      if (!std::isfinite(m.q1_A[i][k]) || !std::isfinite(m.q1_B[i][k])) return std::nullopt;
    }
  m.normal = g.normal;
  detail::power_normalized(m.normal);
  return m;
}

// A bounded optimum (global_depth.h: face_bound, or global_depth's bound_shallow): its estimate
// and upper bound scaled back by the power of two, exactly where both are normal doubles (else
// declined), and its positions.
std::optional<GlobalMinimiser> bounded_back(const GlobalOptimum& g, const detail::ScaledPair& sp) {
  bool in_range = true;
  GlobalMinimiser m;
  m.bounded = true;
  m.pd2 = detail::unscaled(g.value, 2 * -sp.e, in_range);
  m.upper = detail::unscaled(g.upper, 2 * -sp.e, in_range);
  if (!in_range || !std::isnormal(m.pd2) || !std::isnormal(m.upper)) return std::nullopt;
  return placed_back(g, sp, m);
}

// definitions §9 from the relaxed choice `rel` (a candidate `c` of the list or set `cands`,
// certified, its label) and the certified rigid choice, on the rescaled pair: solve_pair's
// fill_global, its scaling back and its relations (above). std::nullopt where solve_pair's
// fields could differ (header).
template <class Candidates>
std::optional<GlobalMinimiser> minimiser_from(const TetVertices& A, const TetVertices& B, const detail::ScaledPair& sp,
                                              const Candidates& cands, const Choice& rigid, const Choice& rel,
                                              const Candidate& c, const MinimiserOptions& o) {
  const double start[3] = {c.n[0], c.n[1], c.n[2]};
  const DirectionLabel label = rel.label();
  const TetVertices &As = sp.A, &Bs = sp.B;
  const ExactStart exact_start = [&]() -> std::array<double, 3> {
    return detail::rounded_normal(detail::exact_candidate(detail::exact_frame(As, Bs), label).n);
  };
  const GlobalOptimum g = global_depth(As, Bs, start, rel.value, exact_start, rigid.value, o.bound_shallow);
  if (!g.certified && !g.witness && !g.bounded) return std::nullopt;
  if (!(g.normal[0] != 0 || g.normal[1] != 0 || g.normal[2] != 0)) return std::nullopt;
  if (g.bounded) {
    if (std::optional<GlobalMinimiser> m = bounded_back(g, sp)) return m;
    return minimiser_from(A, B, sp, cands, rigid, rel, c, MinimiserOptions{});  // certified instead
  }
  bool in_range = true;
  GlobalMinimiser m;
  m.witness = g.witness;
  // Computed in rationals (global_depth's exact pieces: a depth far below the pair's size): its
  // value in the rescaled units may have left the double range, so solve_pair takes it again,
  // exactly, on the pair as given along the same normal, and declines it where that is not 0
  // or a normal double; the same here (global_depth.h's exact_relaxed_value). Declining such a
  // pair instead made the caller's solve_pair redo the whole exact enumeration (~7 M
  // instructions a pair on the shallow contacts of the tilted stacked blocks).
  // A witness's value (exact, rounded down once in the rescaled units) is scaled back by the
  // power of two, exactly where it is a normal double there.
  m.pd2 = g.witness        ? (std::isnormal(g.value) ? detail::unscaled(g.value, 2 * -sp.e, in_range) : NAN)
          : g.exact_value ? exact_relaxed_value(A, B, g.normal, in_range)
                          : detail::unscaled(g.value, 2 * -sp.e, in_range);
  const double relaxed = detail::unscaled(rel.value, 2 * -sp.e, in_range);
  if (!in_range || !(m.pd2 == 0 || std::isnormal(m.pd2))) return std::nullopt;
  if (!(m.pd2 <= (1 - kClampMargin) * relaxed) && !lower_at_tie(cands, sp.e, rigid, rel, m.pd2))
    return std::nullopt;
  return placed_back(g, sp, m);
}

// Pairs whose quick lanes decline (parallel edges, coplanar faces: the aligned pairs of
// structured meshes, stacked blocks): solve_pair then builds its candidate set and takes every
// choice from the set's sweeps (fill_intersecting without lanes), and its definitions §9 fields
// come from fill_global on them whether or not the rest of its record is certified (the exact
// path replaces candidate-based values only). The same here: the set (build_candidates on the
// same rescaled pair: the same candidates in the same order), rigid_pd2 over it, pdd2_relaxed's
// sweep over it (its choice does not depend on the hint: the rigid choice seeds it, as above).
// Declined where solve_pair's inputs to fill_global could differ: a choice not certified.
// Measured on the stacked Kuhn blocks of `pdd bench energy` (1728 pairs, every one declined by
// the lanes): solve_pair ~250 us a pair there (its exact path for the rest of the record on
// about one pair in six), this route ~25 us.
std::optional<GlobalMinimiser> minimiser_from_set(const TetVertices& A, const TetVertices& B,
                                                  const detail::ScaledPair& sp, const MinimiserOptions& o) {
  // One set per thread (~20 KB: off TBB's worker stacks); build_candidates sets what is read.
  if (o.bound_shallow) {
    // bounded only where the pair is valid and its interiors intersect (the exact decision, the
    // candidate set's: every other pair is declined below, as without the option), checked
    // after the bound (~0.2 us) since it costs more (~1 us on a contact made by rounding)
    const GlobalOptimum g = face_bound(sp.A, sp.B);
    if (g.bounded && interiors_intersect(sp.A, sp.B))
      if (std::optional<GlobalMinimiser> m = bounded_back(g, sp)) return m;
  }
  static thread_local CandidateSet set;
  if (build_candidates(sp.A, sp.B, set) != BuildStatus::Ok || !set.intersecting) return std::nullopt;
  const Choice rigid = rigid_pd2(set);
  if (!rigid.certified) return std::nullopt;
  const Choice rel = pdd2_relaxed(set, rigid.index);
  if (!rel.certified || !(rel.value > 0) || rel.index < 0) return std::nullopt;
  return minimiser_from(A, B, sp, set, rigid, rel, candidate(set, rel.index), o);
}

std::optional<GlobalMinimiser> minimiser_as_given(const TetVertices& A, const TetVertices& B,
                                                  const MinimiserOptions& o) {
  if (!detail::all_finite(A) || !detail::all_finite(B)) return std::nullopt;
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  if (!sp.exact) return std::nullopt;
  // solve_pair: the quick lanes (valid, intersecting, every filter verdict clear), pdd2_relaxed
  // from their sweep, rigid_pd2 over the candidates (QuickCandidates gives the same candidates,
  // in the same order, bit for bit, as the set solve_pair builds: quick_candidates.h).
  // One list per thread (~8 KB: off TBB's worker stacks; allocated per call it cost ~2% of
  // global_minimiser on the energy's pairs). quick_lanes sets every field read below, and
  // global_minimiser does not recurse.
  static thread_local QuickCandidates list;
  QuickCandidates* q = &list;
  if (!quick_lanes(sp.A, sp.B, *q)) return minimiser_from_set(A, B, sp, o);
  Choice rel;
  const bool rel_lanes = pdd2_relaxed_lanes(*q, rel);
  quick_edge_list(*q);  // (appends the edge candidates; the lanes and faces the sweeps read stay)
  const Choice rigid = rigid_pd2(*q);
  if (!rigid.certified) return std::nullopt;
  int index = rel_lanes ? index_of(*q, rel.code) : -1;  // the choice's candidate, as solve_pair finds it
  if (index < 0) {
    // solve_pair's route when the sweep cannot decide: the list's sweep, hinted by the rigid
    // choice as there (fill_intersecting).
    rel = pdd2_relaxed(*q, rigid.index);
    index = index_of(*q, rel.code);
  }
  if (!rel.certified || !(rel.value > 0)) return std::nullopt;
  if (index < 0) return std::nullopt;
  return minimiser_from(A, B, sp, *q, rigid, rel, candidate(*q, index), o);
}

}  // namespace

// On the anchored pair where there is one, its positions moved back (pdd.h, "Translation", as
// solve_pair: the same fields bit for bit).
bool move_positions(GlobalMinimiser& g, const AnchoredPair& m, const TetVertices& A, const TetVertices& B) {
  PairResult<double> r;  // move_positions' fields: q1_* the rest pose, moved back exactly
  r.q1_A = m.A, r.q1_B = m.B, r.q1_A_global = g.q1_A, r.q1_B_global = g.q1_B;
  if (!move_positions(r, m, A, B)) return false;
  g.q1_A = r.q1_A_global, g.q1_B = r.q1_B_global;
  return true;
}

std::optional<GlobalMinimiser> global_minimiser(const TetVertices& A, const TetVertices& B,
                                                const MinimiserOptions& options) {
  const std::optional<AnchoredPair> m = anchored_pair(A, B);
  if (!m) return minimiser_as_given(A, B, options);
  std::optional<GlobalMinimiser> g = minimiser_as_given(m->A, m->B, options);
  if (g && !move_positions(*g, *m, A, B)) return minimiser_as_given(A, B, options);
  return g;
}

}  // namespace pdd::fast
