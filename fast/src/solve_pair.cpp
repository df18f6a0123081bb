// solve_pair.cpp — definitions §6 record of one pair, certified (definitions §8), and the parallel
// batch. See the header.
#include "pdd/pdd.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "certification/value_bounds.h"
#include "certification/value_relations.h"
#include "exact/exact_candidate.h"
#include "exact/exact_path.h"
#include "exact/exact_predicates.h"
#include "global/global_depth.h"
#include "kernel/anchor.h"
#include "kernel/candidate_directions.h"
#include "kernel/direction_geometry.h"
#include "kernel/power_scale.h"
#include "kernel/rigid_depth.h"
#include "kernel/superset_depth.h"
#include "kernel/superset_kernel.h"
#include "pdd/rejection.h"
#include "qp/deformable_depth.h"

namespace pdd::fast {
namespace {

// definitions §1 with the shared wording (pdd/rejection.h); flatness decided exactly here.
std::optional<std::string> rejection_of(const TetVertices& T, char which) {
  if (auto reason = non_finite_reason(T, which)) return reason;
  if (orientation_sign_exact(T) == Sign::Zero) return flat_reason(which);
  return std::nullopt;
}
std::optional<std::string> rejection_of(const TetPair& p) {
  return pair_rejection(rejection_of(p.A, 'A'), rejection_of(p.B, 'B'));
}

std::optional<DirectionLabel> label_of(const CandidateSet& s, const Choice& c) {
  if (c.index < 0) return std::nullopt;
  return label(s, c.index);
}

// The deformed positions attain `value` (definitions §8): their object norm, evaluated from the
// computed displacements (each difference q − x exact to u|q − x|, the norm to 12 u), must be
// within kContractRel − kCertifyRel − 1e-11 of the certified value.
bool positions_attain(const TetPair& pair, const PairResult<double>& r, double value) {
  double sigma = 0.0;
  for (int t = 0; t < 2; ++t) {
    const TetVertices& X = t ? pair.B : pair.A;
    const Positions<double>& Q = t ? r.q1_B : r.q1_A;
    double sum[3] = {0, 0, 0}, sq = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        const double d = Q[i][k] - X[i][k];
        sum[k] += d;
        sq += d * d;
      }
    sigma += (sq + sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / 20.0;
  }
  return std::fabs(sigma - value) <= (kContractRel - kCertifyRel - 1e-11) * value;
}

// Which quantities of a record the double path could not certify (definitions §8).
constexpr unsigned kRigid = 1;
constexpr unsigned kEq11 = 2;
constexpr unsigned kStatic = 4;
constexpr unsigned kAccel6 = 8;
constexpr unsigned kAccel1 = 16;
constexpr unsigned kDeformable = 32;
constexpr unsigned kRelaxed = 64;
constexpr unsigned kPositions = 128;
constexpr unsigned kGlobal = 256;  // pdd2_global not representable (global_depth.h)

// SolveOptions::values' bits: the value kValueKeys[k] of pair_result.h.
enum ValueIndex : unsigned { kIdxRigid, kIdxEq11, kIdxStatic, kIdxPdd2, kIdxRelaxed, kIdxAccel1, kIdxAccel6 };
constexpr unsigned bit(ValueIndex k) { return 1u << k; }
constexpr unsigned kAllValues = (1u << kValueCount) - 1;

// The values computed for the asked ones (solve_options.h): with every value each one is kept
// against (value_relations.h's order), so that the asked ones are the full record's bit for
// bit; definitions §9 is kept below pdd2_relaxed and started from its choice.
unsigned computed_values(unsigned asked, bool global) {
  unsigned c = (asked & kAllValues) | bit(kIdxRigid);
  if (global) c |= bit(kIdxRelaxed);
  if (c & (bit(kIdxRelaxed) | bit(kIdxAccel6))) c |= bit(kIdxPdd2);
  if (c & bit(kIdxPdd2)) c |= bit(kIdxStatic) | bit(kIdxAccel1);
  return c;
}

// The values not asked: 0 and no label; q1 the rest pose when pdd2 is not asked.
void leave_out(const TetPair& pair, unsigned asked, PairResult<double>& r) {
  for (std::size_t k = 0; k < kValueCount; ++k)
    if (!(asked >> k & 1u)) {
      record_value(r, k) = 0;
      if (kLabelOfValue[k] >= 0) record_label(r, std::size_t(kLabelOfValue[k])).reset();
    }
  if (!(asked & bit(kIdxPdd2))) r.q1_A = pair.A, r.q1_B = pair.B;
}

// definitions §9 from the relaxed choice `rel` (its candidate's normal and label, when the double
// path has one): value, normal, positions. Returns false when the value is not certified (not
// representable).
bool fill_global(const TetPair& pair, const Choice& rel, const CandidateSet& set, double rigid_pd2,
                 PairResult<double>& r, bool* slow) {
  double start[3] = {0, 0, 0};
  if (rel.index >= 0) {
    const Candidate c = candidate(set, rel.index);
    for (int k = 0; k < 3; ++k) start[k] = c.n[k];
  }
  // The exact start (rare: a depth far below the pair's size): the label's exact normal (a
  // candidate of the pair even when the choice is not certified: only a start), else the exact
  // path's pdd2_relaxed normal.
  const ExactStart exact_start = [&] {
    if (const std::optional<DirectionLabel> l = label_of(set, rel))
      return detail::rounded_normal(detail::exact_candidate(detail::exact_frame(pair.A, pair.B), *l).n);
    return detail::solve_pair_exact_path(pair.A, pair.B).relaxed_normal;
  };
  const GlobalOptimum g = global_depth(pair.A, pair.B, start, rel.certified ? rel.value : INFINITY,
                                       exact_start, rigid_pd2);
  r.pdd2_global = g.value;
  r.pdd2_global_normal = g.normal;
  r.q1_A_global = g.q1_A;
  r.q1_B_global = g.q1_B;
  if (slow && g.exact_value) *slow = true;
  return g.certified;
}

// The double path on a rescaled pair; returns the quantities that are not certified.
// `refined`: some quantity was certified by refine.h (a few candidates evaluated exactly);
// `exact_q1`: q1 must be the exact solution's (solve_pair): neither the double positions nor
// the compensated ones meet the contract;
// `global_slow`: pdd2_global's value was computed in rationals (global_depth.h).
// `lanes`: the pair's quick lanes (quick_lanes), or null when they decline: pdd2_static, pdd2 and
// pdd2_relaxed are then first taken from the lane sweeps of the functions over raw tetrahedra
// (deformable_depth.h), which see the same rescaled pair, so that both report the same values
// and labels; the set's sweeps where those cannot decide (their results do not depend on the
// hint, so the choice is the hot functions' fallback's too).
// `kernel`: the superset kernel's lanes of the pair (quick_lanes ran it). rigid_pd2, its label and
// pdd2_accel1 are the hot functions' (rigid_and_accel1_of_rescaled: their routes on the same
// rescaled pair), so that a record and rigid_pd2(A, B), pdd2_accel(A, B, 1) agree bit for bit
// whatever else is asked. The set's choice and the superset's agree on a pick the superset
// certifies with every edge pair in its lanes; where it certifies one only after leaving out
// the edge pairs the doubles cannot resolve (nearly or exactly parallel edges, edge pairs with
// loose bounds), the set still holds those along their own normals and at a near tie (either
// side of which definitions §8 allows) may name one of them, a few ulps away; and pdd2_accel1's
// routes (the superset's tie band, its compensated value, the quick list) certify its value
// along other roundings than the set's. The set's own rigid choice (`rigid` below) stays the
// sweeps' hint and pdd2_global's lower bound.
// `computed` (computed_values): the values to compute; the others stay 0 and uncounted.
unsigned fill_intersecting(const TetPair& pair, const CandidateSet& set, const QuickCandidates* lanes,
                           detail::SupersetLanes& kernel, PairResult<double>& r, bool& refined, bool& exact_q1,
                           bool& global_slow, bool global, unsigned computed) {
  auto asked = [computed](ValueIndex k) { return (computed & bit(k)) != 0; };
  // a lane choice as a choice of the set (its index: the same label; same candidates, same order)
  auto from_lanes = [&](bool (*sweep)(const QuickCandidates&, Choice&), Choice& ch) {
    if (!lanes || !sweep(*lanes, ch)) return false;
    for (int k = 0; k < set.count; ++k)
      if (set.code[k] == ch.code) {
        ch.index = k;
        return true;
      }
    return false;
  };
  unsigned missing = 0;
  const Choice rigid = rigid_pd2(set);
  Choice hot, hot_accel1;
  rigid_and_accel1_of_rescaled(pair.A, pair.B, kernel, set, rigid, asked(kIdxAccel1), hot, hot_accel1);
  if (hot.certified) {
    r.rigid_pd2 = hot.value;
    r.rigid_dir = hot.label();
  } else {
    r.rigid_pd2 = rigid.value;
    r.rigid_dir = label_of(set, rigid);
    missing |= rigid.certified ? 0 : kRigid;
  }
  bool e11_ok = false, e11_refined = false;
  if (asked(kIdxEq11)) {
    r.eq11_pd2 = eq11_pd2(set, &e11_ok, &e11_refined);
    missing |= e11_ok ? 0 : kEq11;
  }
  // pdd2_static, pdd2 and pdd2_relaxed: the lane sweep's choice, else the set's, hinted by the
  // rigid choice, as the hot functions (deformable_depth.h: rigid_hint) and
  // global_minimiser.cpp: a sweep's choice does not depend on its hint, but its certificate may
  // (a candidate it skips is bounded from delta² alone), and with it whether the value is the
  // double or the refined one: one hint keeps the bits the same whatever values are asked.
  auto labelled = [&](bool (*lanes_sweep)(const QuickCandidates&, Choice&), auto set_sweep, double& value,
                      std::optional<DirectionLabel>& dir, unsigned bit) {
    Choice ch;
    if (!from_lanes(lanes_sweep, ch)) ch = set_sweep(set, rigid.index);
    value = ch.value;
    dir = label_of(set, ch);
    missing |= ch.certified ? 0 : bit;
    return ch;
  };
  Choice st, accel6, accel1, def, rel;
  if (asked(kIdxStatic))
    st = labelled(pdd2_static_lanes, [](const CandidateSet& s, int h) { return pdd2_static(s, h); },
                  r.pdd2_static, r.pdd2_static_dir, kStatic);
  if (asked(kIdxAccel6)) {
    accel6 = pdd2_accel(set, kAccelWide);
    r.pdd2_accel6 = accel6.value;
    missing |= accel6.certified ? 0 : kAccel6;
  }
  if (asked(kIdxAccel1)) {
    accel1 = hot_accel1;
    r.pdd2_accel1 = accel1.value;
    missing |= accel1.certified ? 0 : kAccel1;
  }
  if (asked(kIdxPdd2))
    def = labelled(pdd2_lanes, [](const CandidateSet& s, int h) { return pdd2(s, h); }, r.pdd2, r.pdd2_dir,
                   kDeformable);
  if (asked(kIdxRelaxed))
    rel = labelled(pdd2_relaxed_lanes, [](const CandidateSet& s, int h) { return pdd2_relaxed(s, h); },
                   r.pdd2_relaxed, r.pdd2_relaxed_dir, kRelaxed);
  refined = rigid.refined || e11_refined || st.refined || accel6.refined || accel1.refined ||
            def.refined || rel.refined;
  exact_q1 = false;
  if (asked(kIdxPdd2) && def.index >= 0 && def.certified) {
    deformed_positions(pair.A, pair.B, candidate(set, def.index), r.q1_A, r.q1_B);
    // the double positions where their cost is the reported value's (positions_attain: the
    // exact cost of the rounded positions, to its own roundings; a refined choice's too, its
    // label being the one solved); else on compensated heights where they give them
    // (deformable_depth.h), else the exact ones for the label
    if (!positions_attain(pair, r, def.value)) {
      refined = true;
      exact_q1 = !compensated_positions(pair.A, pair.B, candidate(set, def.index), r.q1_A, r.q1_B);
    }
  } else if (asked(kIdxPdd2)) {
    missing |= kPositions;
  }
  if (global && !fill_global(pair, rel, set, rigid.certified ? rigid.value : 0.0, r, &global_slow))
    missing |= kGlobal;
  return missing;
}

// q1 of definitions §8 for the reported pdd2 label: the exact case-2 solution of that candidate
// (exact_candidate.h), which attains its exact value — the reported value's to the contract
// (exactly so when the choice was refined). False when a coordinate is not representable.
bool exact_positions_of(const TetPair& pair, const DirectionLabel& l, PairResult<double>& r) {
  const detail::ExactFrame f = detail::exact_frame(pair.A, pair.B);
  const detail::ExactCandidate c = detail::exact_candidate(f, l);
  Solution<detail::Q> sol;
  (void)detail::exact_deformable_value(c, &sol);
  bool ok = true;
  detail::exact_positions(pair.A, pair.B, f, c, sol, r.q1_A, r.q1_B, ok);
  return ok;
}

// Replaces the uncertified quantities of r by the exact path's (rounded once). pdd2, its label
// and q1 go together, so that the positions attain the reported value for the reported label.
bool substitute_exact(const TetPair& pair, unsigned missing, PairResult<double>& r) {
  const detail::ExactPathResult e = detail::solve_pair_exact_path(pair.A, pair.B);
  if (!e.representable) return false;
  const PairResult<double>& x = e.result;
  if (missing & kRigid) { r.rigid_pd2 = x.rigid_pd2; r.rigid_dir = x.rigid_dir; }
  if (missing & kEq11) r.eq11_pd2 = x.eq11_pd2;
  if (missing & kStatic) { r.pdd2_static = x.pdd2_static; r.pdd2_static_dir = x.pdd2_static_dir; }
  if (missing & kAccel6) r.pdd2_accel6 = x.pdd2_accel6;
  if (missing & kAccel1) r.pdd2_accel1 = x.pdd2_accel1;
  if (missing & (kDeformable | kPositions)) {
    r.pdd2 = x.pdd2;
    r.pdd2_dir = x.pdd2_dir;
    r.q1_A = x.q1_A;
    r.q1_B = x.q1_B;
  }
  if (missing & kRelaxed) {
    r.pdd2_relaxed = x.pdd2_relaxed;
    r.pdd2_relaxed_dir = x.pdd2_relaxed_dir;
  }
  return true;
}

// Scales the values of r by 2^(2k) and the positions by 2^k; false if a certified value leaves
// the normal range (the others are replaced by substitute_exact).
bool unscale(PairResult<double>& r, int k, unsigned missing) {
  bool ok = true;
  const std::pair<double*, unsigned> values[] = {
      {&r.rigid_pd2, kRigid},        {&r.eq11_pd2, kEq11},       {&r.pdd2_static, kStatic},
      {&r.pdd2, kDeformable},        {&r.pdd2_relaxed, kRelaxed}, {&r.pdd2_accel1, kAccel1},
      {&r.pdd2_accel6, kAccel6},     {&r.pdd2_global, kGlobal}};
  for (const auto& [v, bit] : values) {
    bool in_range = true;
    *v = detail::unscaled(*v, 2 * k, in_range);
    if (!(missing & bit)) ok = ok && in_range;
  }
  for (Positions<double>* q : {&r.q1_A, &r.q1_B, &r.q1_A_global, &r.q1_B_global})
    for (auto& x : *q)
      for (double& c : x) c = detail::times_pow2(c, k);
  return ok;
}

// pdd2_global's value is 0 or a normal double and its positions are finite.
bool global_representable(const PairResult<double>& r) {
  if (!(r.pdd2_global == 0 || std::isnormal(r.pdd2_global))) return false;
  for (const Positions<double>* q : {&r.q1_A_global, &r.q1_B_global})
    for (const auto& x : *q)
      for (double c : x)
        if (!std::isfinite(c)) return false;
  return true;
}

// pdd2_global alone cannot be had: the record keeps its other values; the definitions §9 fields
// become NaN (no normal), so that none of them reads as a depth, and `why` is recorded.
void decline_global(PairResult<double>& r, const char* why) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  r.pdd2_global = nan;
  r.pdd2_global_normal.reset();
  for (Positions<double>* q : {&r.q1_A_global, &r.q1_B_global})
    for (auto& x : *q) x = {nan, nan, nan};
  r.pdd2_global_error = why;
}

PairResult<double> exact_path(const TetPair& pair, PairResult<double> r, bool global) {
  detail::ExactPathResult e = detail::solve_pair_exact_path(pair.A, pair.B);
  if (!e.representable) {
    r.error = kNotRepresentable;
    return r;
  }
  e.result.name = r.name;
  PairResult<double>& x = e.result;
  x.q1_A_global = pair.A, x.q1_B_global = pair.B;
  if (x.intersecting && global) {  // definitions §9, started at pdd2_relaxed's normal
    const GlobalOptimum g = global_depth(pair.A, pair.B, e.relaxed_normal.data(), x.pdd2_relaxed, {}, x.rigid_pd2);
    x.pdd2_global = g.value, x.pdd2_global_normal = g.normal;
    x.q1_A_global = g.q1_A, x.q1_B_global = g.q1_B;
    if (!g.certified || !(g.normal[0] != 0 || g.normal[1] != 0 || g.normal[2] != 0))
      decline_global(x, kGlobalNotRepresentable);  // no double normal found (global_depth.h)
    else if (!global_representable(x))
      decline_global(x, kGlobalOutOfRange);
    if (x.pdd2_global_normal) detail::power_normalized(*x.pdd2_global_normal);
  }
  return x;
}

// The record without the gradient; *slow_path, *refined_out: its stats (pdd.h). `computed`
// (computed_values): the values to compute; on return the values the record holds (every one
// where the exact path gave the record).
PairResult<double> solve_record(const TetPair& pair, bool* slow_path, bool* refined_out, bool global,
                                unsigned& computed) {
  PairResult<double> r;
  r.name = pair.name;
  if (!detail::all_finite(pair.A) || !detail::all_finite(pair.B)) {
    r.error = rejection_of(pair);
    return r;
  }
  const detail::ScaledPair sp = detail::power_scaled(pair.A, pair.B);
  if (!sp.exact) {  // a coordinate would leave the normal range when rescaled: exact path only
    r.error = rejection_of(pair);
    if (r.error) return r;
    if (slow_path) *slow_path = true;
    computed = kAllValues;
    return exact_path(pair, r, global);
  }
  // ~20 KB and ~8 KB: once per thread, off TBB worker stacks (solve_record does not recurse:
  // nothing below calls solve_pair or waits on other tasks)
  static thread_local CandidateSet set_storage;
  static thread_local QuickCandidates lanes_storage;
  static thread_local detail::SupersetLanes kernel_storage;
  CandidateSet* const set = &set_storage;
  // The quick lanes first: where they hold the pair's faces (the orientations certain) the set
  // is built from them (candidate_directions.h: the same set, the kernel not run twice);
  // `have_lanes` where every face depth and lane is clear too (an edge lane through the exact
  // path makes quick_lanes decline).
  QuickCandidates* const lanes = &lanes_storage;
  const bool have_lanes = quick_lanes(sp.A, sp.B, *lanes, true, &kernel_storage);
  const BuildStatus built =
      lanes->faces_filled ? build_candidates(*lanes, *set) : build_candidates(sp.A, sp.B, *set);
  if (built != BuildStatus::Ok) {
    r.error = rejection_of(pair);  // flat (decided exactly); the scaling preserves flatness
    return r;
  }
  r.q1_A = pair.A;
  r.q1_B = pair.B;
  r.q1_A_global = pair.A, r.q1_B_global = pair.B;
  r.intersecting = set->intersecting;
  if (!r.intersecting) return r;
  TetPair scaled;
  scaled.A = sp.A;
  scaled.B = sp.B;
  bool refined = false, exact_q1 = false, global_slow = false;
  unsigned missing = fill_intersecting(scaled, *set, have_lanes ? lanes : nullptr, kernel_storage, r, refined,
                                       exact_q1, global_slow, global, computed);
  PairResult<double> bad;
  bad.name = pair.name;
  bad.error = kNotRepresentable;
  // pdd2_global computed in rationals: its value in the rescaled units may have left the double
  // range (a depth of 1e-37 at coordinates 1e192 is 1e-422 there); taken again, exactly, on the
  // pair as given along the same normal (a normal does not change with a uniform scale).
  const bool global_exact = global_slow && !(missing & kGlobal) && r.pdd2_global_normal;
  if (global_exact) r.pdd2_global = 0;
  if (!unscale(r, -sp.e, missing | kGlobal)) return bad;  // pdd2_global: checked below
  if (!global) r.q1_A_global = pair.A, r.q1_B_global = pair.B;  // definitions §9 skipped: rest pose
  if (missing & kGlobal) {
    decline_global(r, kGlobalNotRepresentable);  // no double normal found (global_depth.h)
    missing &= ~kGlobal;  // the exact path below replaces candidate-based values only
  } else if (global_exact) {
    bool ok = true;
    r.pdd2_global = exact_relaxed_value(pair.A, pair.B, *r.pdd2_global_normal, ok);
    if (!ok) decline_global(r, kGlobalOutOfRange);
  }
  if (!r.pdd2_global_error && !global_representable(r)) decline_global(r, kGlobalOutOfRange);
  if (r.pdd2_global_normal) detail::power_normalized(*r.pdd2_global_normal);
  if (global_slow && slow_path) *slow_path = true;
  if (exact_q1 && !(missing & kDeformable) && !exact_positions_of(pair, *r.pdd2_dir, r))
    missing |= kPositions;
  if (refined_out) *refined_out = (refined || exact_q1) && !missing && !global_slow;  // exclusive of slow_path
  if (missing) {
    if (slow_path) *slow_path = true;
    if (!substitute_exact(pair, missing, r)) return bad;
  }
  return r;
}

// The gradient of pdd2_global (definitions §9): -d sigma/d d at d = q1_global - rest, per tetrahedron
// (d sigma/d d_i = (d_i + sum_k d_k) / 10); NaN where pdd2_global is declined (q1_*_global are
// NaN then), 0 when not intersecting (q1_*_global is the rest pose).
// Accuracy. The arithmetic here adds little: d_i = q_i - p_i is within u |d_i| (u = 2^-53), the
// sum and the division add about 5 u, so each component is within ~6 u |g| of the gradient of
// the positions as given. What bounds the result is how far those positions are from the
// minimiser: they attain pdd2_global to the accuracy contract, sigma(Q - P) <= (1 + eps) f with
// eps <= 2e-9 (1e-9 to the exact value, itself within 1e-12 of the minimum f). Measure
// gradients in the dual object norm |g|_* = max over W of <g, W> / sqrt(sigma(W)) (|g|_* =
// 2 sqrt(f) for the true gradient g). If pdd2_global lies above its tangent model minus
// K sigma(W) around P (K >= 0: 0 where the separated set is locally convex, larger where its
// boundary bends sharply), then (*) of definitions §9 ("The gradient of pdd2_global") at Q against that lower model gives, minimising
// over W, |g_Q - g|_*^2 <= 4 (1 + K) eps f, that is |g_Q - g|_* <= sqrt((1 + K) eps) |g|_*:
// 4.5e-5 |g|_* for K <= 0 at the contract's worst, 6.3e-5 for K <= 1. The positions are
// separated only up to tau = 1e-9 R (definitions §8): translating B by tau along the normal
// separates them and adds at most 2 sqrt(f) tau + tau^2 to sigma, so eps f becomes
// eps f + 2 sqrt(f) tau + tau^2 above, which dominates on contacts far shallower than R. In practice the
// positions come from a normal polished to about 1e-16 and the gradient agrees with the exact
// engine's far closer (tests/fast/fast_global_gradient_test.cpp).
PairGradient<double> global_gradient(const TetPair& pair, const PairResult<double>& r) {
  PairGradient<double> g{};
  for (int t = 0; t < 2; ++t) {
    const TetVertices& P = t ? pair.B : pair.A;
    const Positions<double>& Q = t ? r.q1_B_global : r.q1_A_global;
    double d[4][3], sum[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        d[i][k] = Q[i][k] - P[i][k];
        sum[k] += d[i][k];
      }
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) g[4 * t + i][k] = (0.0 - (d[i][k] + sum[k])) / 10;  // 0, not -0, at rest
  }
  return g;
}

// The record of the pair as given, without the gradient.
PairResult<double> solve_as_given(const TetPair& pair, const SolveOptions& options) {
  bool slow = false, refined = false;
  unsigned computed = computed_values(options.values, options.with_global);
  PairResult<double> r = solve_record(pair, &slow, &refined, options.with_global, computed);
  if (!r.error && r.intersecting) {
    keep_exact_relations(r, computed);
    leave_out(pair, options.values, r);
  }
  r.stats.slow_path = slow;
  r.stats.refined = refined;
  return r;
}

}  // namespace

std::optional<AnchoredPair> anchored_pair(const TetVertices& A, const TetVertices& B) {
  AnchoredPair m;
  if (!detail::anchored(A, B, m.A, m.B)) return std::nullopt;
  m.origin = A[0];
  return m;
}

bool move_positions(PairResult<double>& r, const AnchoredPair& m, const TetVertices& A, const TetVertices& B) {
  bool ok = true;
  auto move = [&](Positions<double>& q, const TetVertices& rest_m, const TetVertices& rest) {
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) {
        double& x = q[v][k];
        if (std::memcmp(&x, &rest_m[v][k], sizeof x) == 0) {
          x = rest[v][k];
          continue;
        }
        const double moved = x + m.origin[k];
        ok = ok && (std::isfinite(moved) || !std::isfinite(x));
        x = moved;
      }
  };
  move(r.q1_A, m.A, A), move(r.q1_B, m.B, B);
  move(r.q1_A_global, m.A, A), move(r.q1_B_global, m.B, B);
  return ok;
}

// On the anchored pair where there is one (pdd.h, "Translation"), moved back.
PairResult<double> solve_pair(const TetPair& pair, const SolveOptions& options) {
  PairResult<double> r;
  if (const std::optional<AnchoredPair> m = anchored_pair(pair.A, pair.B)) {
    r = solve_as_given(TetPair{"", {}, m->A, m->B}, options);
    if (!move_positions(r, *m, pair.A, pair.B)) r = solve_as_given(pair, options);
    r.name = pair.name;
  } else {
    r = solve_as_given(pair, options);
  }
  if (options.gradient && options.with_global && !r.error) r.pdd2_global_grad = global_gradient(pair, r);
  return r;
}

std::vector<PairResult<double>> solve_batch(const std::vector<TetPair>& pairs, const SolveOptions& options) {
  std::vector<PairResult<double>> out(pairs.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size()),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i != range.end(); ++i) out[i] = solve_pair(pairs[i], options);
                    });
  return out;
}

}  // namespace pdd::fast
