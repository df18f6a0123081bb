// rounds.cpp — the rounds of resolve (rounds.h).
#include "rounds.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "../resolve.h"
#include "geometry.h"
#include "local_step.h"
#include "patch_direction.h"
#include "step_limit.h"

namespace pdd::mesh::detail {
namespace {

// ---- the projective-dynamics rounds

// kStallRounds rounds without progress on the best round before count as stalled: the pair
// count falls unevenly (planes of neighbouring pairs disagree for a few rounds), and on the
// one-layer Gmsh balls plateaus of up to 6 rounds end resolved. Progress is a count below
// (1 - kMinProgress) of the best: one pair fewer below 100 pairs, 1% above. A count that falls
// by less than 1% in 20 rounds would still be at 90% of itself after 200 rounds (the default
// budget): on the deep plate case (15k pairs shrinking by a few a round) the rounds gave way to
// the fallbacks after 94 rounds instead of 44, and no case the rounds resolve has such a plateau.
constexpr std::size_t kStallRounds = 20;
constexpr double kMinProgress = 0.01;
// A deep overlap shows early: at round kProbeRounds the rounds that go on to resolve have cut
// the first round's count to 1-8% (scripts/make-resolve-cases.sh: one-layer balls and box 5%,
// the thin plate under a ball 1%, two bodies in one file 3%, the wound bar (coil) 6%; three
// balls in one file 8%), the ones that stall hold more than half of it (ball through the plate
// 58%, three balls pushed deep 52%, the Kuhn helix pressed 0.8 cell 54%, 96% on its tight
// twin). More than half of the largest count so far after kProbeRounds counts as stalled: the
// fallbacks start 10 to 50 rounds earlier, and a walk back towards rest (fallbacks.h) drops a
// step that re-created a deep contact after 10 rounds instead of 20. The largest count, not the
// first: where blocks of prisms rest on each other a third of a cell deep, the first round's
// moves put the contact layer's vertices against their neighbours' elements and the count grows
// before it falls (6 x 6 x 3 cubes cut into two prisms of three tetrahedra, tests/mesh's
// prism_grid: 432 pairs, 974 in the second round, 245 in the eleventh, resolved in 20 rounds;
// against the first count the probe sent it to the translation fallback, 148 rounds); the cases
// above peak in their first round (the same rounds and results with either rule).
// Only from kProbeMinPairs pairs in the first round (every case above has 500 or more): a few
// pairs fall one at a time with plateaus between (the tiny fixture meshes: 1 pair for 9 rounds
// before resolving), which the plateau rule above judges.
constexpr std::size_t kProbeRounds = 10, kProbeMinPairs = 100;
// Two meshes' first rounds (OnSlowDecay::Exit): a slow decay is a stall too (decays_too_slowly,
// rounds.h). Past kProbeRounds, at the rate the count fell over the last kRateWindow rounds
// (geometric, as a plateau's counts fall, from the window's largest count: a count that grows
// before it falls is measured from its peak), the rounds left in the budget would not bring it
// down to kFewPairs, where the per-pair rounds finish. Prism blocks of 8^3 cubes resting a third
// of a cell deep go 768, 1,919 in the second round, 693 in the eleventh, 5 in the twentieth:
// from the peak the rate says 37 more rounds (from the first count it said 366). Two blocks
// nearly one in the other (a Gmsh transfinite box of 9^3 cubes against its copy moved (0.37,
// 0.21, 0.13) of a cell, turned 0.3 rad) fall from 57,364 pairs to ~3,200 by round 18 and then
// ~0.6% a round: 1% progress every 20 rounds kept them going to round 63 (2,689 pairs, 0.065 s
// a round) before the fallbacks, whose result the rounds never reach; the rate ends them at
// round 18. Not in the walk back towards rest (fallbacks.h), whose steps of 20 rounds it would
// judge on a few rounds: a step cut one round short of clearing changes the walk (five a cube,
// 10^3 cells of 0.1, against its copy moved a quarter cell along (1, 1, 1): cost 0.480 -> 0.544),
// and the walk takes the rounds the first ones leave. Not for self-contact either: there the rate
// misjudges (three deep balls in one mesh, rigid variant, fall slowly and then faster, resolved
// in 193 rounds at cost 0.0062; stopped at round 10 the bodies' fallback resolves them at 0.22).
constexpr std::size_t kRateWindow = 10;
// Rounds without fewer pairs, at kFewPairs pairs or fewer, before the rounds give way to the
// per-pair rounds (OnFewPairs::Exit; plateaus of up to 6 rounds on the Gmsh balls end resolved).
constexpr std::size_t kFewPairsRounds = 8;
// A vertex is pulled kOvershoot times the way to its half-spaces: the elastic step moves a
// contact vertex only part of its pull (elastic_step.h), and the overshoot makes up for it
// (the step limit cuts where it would break R2 or R4). Measured on the one-layer Gmsh balls
// (both free / A fixed): at kAnchor 0.2, overshoot 1: 23 / 22 rounds; 1.5: 16 rounds / stalled;
// 2: 11 rounds / stalled (it overshoots the pair's plane and chatters); at kAnchor 0.1 (the
// value used), 1.5: 22 / 18 rounds.
constexpr double kOvershoot = 1.5;
// The elastic displacement decays away from the contacts but is nowhere zero; a vertex whose
// displacement is below this share of the largest one stays where it is (bit for bit, so its
// elements keep the state the last step limit accepted). It saves the step limit from checking
// every element of the mesh each round; the jump it leaves at the edge of the moved region, at
// most 1e-4 of the largest move, is inside elements the step limit checks.
constexpr double kNegligibleShare = 1e-4;

// The latest half-space each vertex of a side held (a vertex once in contact stays constrained).
using Held = std::vector<std::optional<HalfSpace>>;

// y projected onto the half-space h when it violates it.
Vec3d project(Vec3d y, const HalfSpace& h) {
  const double d = h.b - dot(h.n, y);
  if (d > 0) add_to(y, scaled(h.n, d));
  return y;
}

// The pulls y_v - x_v of one side: a vertex with targets this round is projected onto each in
// turn (one sweep) and pulled kOvershoot times the way, keeping the most violated half-space as
// the one it holds; a vertex without targets is pulled back into the half-space it holds.
std::vector<Vec3d> pulls(const Side& s, std::vector<VertexTarget>& targets, Held& held) {
  std::sort(targets.begin(), targets.end(), [](const VertexTarget& x, const VertexTarget& y) { return x.vertex < y.vertex; });
  std::vector<Vec3d> pull(s.cur.vertices.size(), Vec3d{0, 0, 0});
  std::vector<char> touched(s.cur.vertices.size(), 0);
  for (std::size_t k = 0; k < targets.size();) {
    const std::size_t v = targets[k].vertex;
    Vec3d y = s.cur.vertices[v];
    double worst = 0;
    for (; k < targets.size() && targets[k].vertex == v; ++k) {
      const double d = targets[k].h.b - dot(targets[k].h.n, s.cur.vertices[v]);
      if (d >= worst) worst = d, held[v] = targets[k].h;
      y = project(y, targets[k].h);
    }
    pull[v] = scaled(sub(y, s.cur.vertices[v]), kOvershoot);
    touched[v] = 1;
  }
  for (std::size_t v = 0; v < pull.size(); ++v)
    if (!touched[v] && held[v]) pull[v] = sub(project(s.cur.vertices[v], *held[v]), s.cur.vertices[v]);
  return pull;
}

// The global step (elastic_step.h) with the side's anchors, and the step limit of one side.
void elastic_move(Side& s, const ElasticStep& elastic, const std::vector<Vec3d>& pull) {
  std::vector<Vec3d> delta;
  if (!elastic.solve(pull, delta, s.anchor)) return;
  double largest = 0;
  for (const Vec3d& d : delta)
    if (finite(d)) largest = std::max(largest, dot(d, d));
  const double negligible = kNegligibleShare * kNegligibleShare * largest;
  for (std::size_t v = 0; v < delta.size(); ++v)
    if (dot(delta[v], delta[v]) > negligible && finite(delta[v])) propose(s, v, delta[v]);
  move_side(s, 1);  // the elastic step's own overshoot is in its pull (kOvershoot)
}

// The local step over all pairs: their half-space targets per side (self-contact: all in a) and
// each pair's squared depth (0: no solution).
std::vector<double> local_step(Run& run, const std::vector<std::array<std::size_t, 2>>& pairs,
                               std::vector<VertexTarget>& targets_a, std::vector<VertexTarget>& targets_b) {
  std::vector<std::vector<VertexTarget>> ta(pairs.size()), tb(pairs.size());
  std::vector<double> value(pairs.size(), 0);
  std::vector<PairMove> moves(pairs.size());
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    if (run.cancelled()) return;
    moves[k] = solve_move(element(run.sa.cur, pairs[k][0]), element(run.second().cur, pairs[k][1]), run.pd_variant);
  });
  run.stop_if_cancelled();
  const std::vector<std::optional<Vec3d>> along = patch_directions(run, pairs, moves);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (moves[k].ok)
      run.depth_scale = std::max(run.depth_scale, overlap_along(element(run.sa.cur, pairs[k][0]),
                                                                element(run.second().cur, pairs[k][1]),
                                                                along[k] ? *along[k] : moves[k].u));
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    if (!moves[k].ok) return;
    const Vec3d* u = along[k] ? &*along[k] : nullptr;
    value[k] = plane_targets(run.sa, pairs[k][0], run.second(), pairs[k][1], moves[k], u, run.depth_scale, ta[k],
                             tb[k]);
  });
  auto& into_b = run.B ? targets_b : targets_a;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    targets_a.insert(targets_a.end(), ta[k].begin(), ta[k].end());
    into_b.insert(into_b.end(), tb[k].begin(), tb[k].end());
  }
  return value;
}

// One projective-dynamics round on the given pairs; false (with rep.stopped_because) when no
// pair has a solution.
bool pd_round(Run& run, const std::vector<std::array<std::size_t, 2>>& pairs, Held& held_a, Held& held_b,
              ResolveRound& rr) {
  auto t = Clock::now();
  std::vector<VertexTarget> targets_a, targets_b;
  const std::vector<double> value = local_step(run, pairs, targets_a, targets_b);
  run.stop_if_cancelled();
  if (std::none_of(value.begin(), value.end(), [](double x) { return x > 0; })) {
    run.rep.stopped_because = "none of the " + std::to_string(pairs.size()) +
                              " intersecting pairs has a finite per-pair solution (coordinates too large to square in doubles?)";
    return false;
  }
  const std::vector<Vec3d> pull_a = pulls(run.sa, targets_a, held_a);
  const std::vector<Vec3d> pull_b = run.B ? pulls(run.sb, targets_b, held_b) : std::vector<Vec3d>{};
  run.rep.seconds_solve += since(t);
  t = Clock::now();
  elastic_move(run.sa, *run.elastic_a, pull_a);
  run.stop_if_cancelled();
  if (run.B) elastic_move(run.sb, *run.elastic_b, pull_b);
  run.rep.seconds_move += since(t);
  rr.pairs = pairs.size();
  rr.max_pd2 = *std::max_element(value.begin(), value.end());
  return true;
}

// ---- the per-pair rounds

// How the per-pair rounds combine a vertex's targets, per variant: global and pdd2 take the
// longest target with overshoot omega = 1.2 and push a pair found in more than two consecutive
// rounds by its rigid translation (on the balls 1.99 apart, 693 pairs: 9 rounds (global) and
// 7 (pdd2); with the weighted mean and omega 1.5 both stalled with a few pairs left after 100
// rounds, elements nearly flat); rigid (the baseline) takes the rest-volume-weighted mean with
// omega = 1.5 (with the longest target it diverged).
struct RoundRule {
  double overshoot;  // omega
  Combine combine;
  int rigid_after;   // rounds before a pair is pushed by its rigid translation (0: never)
};
RoundRule round_rule(ResolveVariant variant) {
  if (variant == ResolveVariant::Rigid) return {1.5, Combine::WeightedMean, 0};
  return {1.2, Combine::Longest, 2};
}

// The per-pair rounds' stall rule: after kPairStallRounds rounds still half of the first round's
// pairs, or kPairStallRounds rounds without fewer pairs than the best round before; or, from
// kProbeMinPairs pairs in the first round (fewer fall one at a time with plateaus between, as in
// the projective-dynamics rounds), not one pair fewer than the first after kPairHopelessRounds
// rounds, by when the pairs found in three rounds running have been pushed by their rigid
// translations (RoundRule::rigid_after): a Gmsh transfinite box of 8^3 cubes against its copy
// moved by (0.37, 0.21, 0.13) of a cell, two blocks nearly one in the other, goes 37,679 ->
// 39,123 -> 40,515 -> 41,605 -> 42,011 -> 42,399 pairs from rest and holds ~42,000 to round 10,
// 0.45 s a round.
constexpr std::size_t kPairStallRounds = 10, kPairHopelessRounds = 5;

struct StallWatch {
  std::size_t first = 0, best = 0, best_round = 0;
  // Takes round r's pair count; true when the rounds count as stalled.
  bool stalled(std::size_t r, std::size_t pairs) {
    if (r == 0) first = best = pairs;
    if (pairs < best) best = pairs, best_round = r;
    return (r >= kPairStallRounds && 2 * pairs >= first) || r >= best_round + kPairStallRounds ||
           (first >= kProbeMinPairs && r >= kPairHopelessRounds && pairs >= first);
  }
};

// Consecutive rounds each pair has been found in (RoundRule::rigid_after), from last round's.
struct PairAges {
  std::vector<std::array<std::size_t, 2>> pairs;
  std::vector<int> age;
  std::vector<int> next(const std::vector<std::array<std::size_t, 2>>& now) const {
    std::vector<int> a(now.size(), 1);
    for (std::size_t k = 0; k < now.size(); ++k) {
      const auto it = std::lower_bound(pairs.begin(), pairs.end(), now[k]);
      if (it != pairs.end() && *it == now[k]) a[k] = age[std::size_t(it - pairs.begin())] + 1;
    }
    return a;
  }
};

// One per-pair round on the given pairs (their ages as PairAges::next).
void pair_round(Run& run, const std::vector<std::array<std::size_t, 2>>& pairs, const std::vector<int>& age,
                ResolveVariant variant, ResolveRound& rr) {
  const RoundRule rule = round_rule(variant);
  auto t = Clock::now();
  Side &sa = run.sa, &sB = run.second();
  std::vector<PairMove> moves(pairs.size());
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const TetVertices Ta = element(sa.cur, pairs[k][0]), Tb = element(sB.cur, pairs[k][1]);
    const bool rigid = rule.rigid_after > 0 && age[k] > rule.rigid_after;
    PairMove m = solve_move(Ta, Tb, rigid ? ResolveVariant::Rigid : variant);
    if (m.ok) finish_move(m, sa, pairs[k][0], sB, pairs[k][1], Ta, Tb);
    moves[k] = m;
  });
  run.rep.seconds_solve += since(t);
  run.stop_if_cancelled();
  t = Clock::now();
  rr.pairs = pairs.size();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!moves[k].ok) continue;
    rr.max_pd2 = std::max(rr.max_pd2, moves[k].value);
    accumulate(sa, pairs[k][0], moves[k].da, rule.combine);
    accumulate(sB, pairs[k][1], moves[k].db, rule.combine);
  }
  move_side(sa, rule.overshoot);
  if (run.B) move_side(run.sb, rule.overshoot);
  run.rep.seconds_move += since(t);
}

}  // namespace

std::vector<std::array<std::size_t, 2>> contacts(Run& run) {
  const auto t = Clock::now();
  // Two meshes: the fresh broadphase prunes to the boxes near the other mesh (a few thousand of
  // 2e5 on the large one-layer case) and costs less than keeping the list over every element
  // (measured 2.8 s against 3.3 s CPU on that case). Self-contact: every neighbour pair
  // overlaps, nothing prunes, and the list saves most of the stage.
  auto pairs = run.B ? intersecting_pairs(run.sa.cur, run.sa.elems, &run.sb.cur, run.sb.elems)
                     : run.contact_list.pairs(run.sa.cur, run.sa.elems, nullptr, {});
  run.rep.seconds_contacts += since(t);
  return pairs;
}

bool decays_too_slowly(const std::vector<std::size_t>& counts, std::size_t budget) {
  if (counts.empty()) return false;
  const std::size_t r = counts.size() - 1, now = counts[r];
  if (r < std::max(kProbeRounds, kRateWindow) || now <= kFewPairs) return false;
  const std::size_t before = *std::max_element(counts.end() - 1 - kRateWindow, counts.end() - 1);
  if (now >= before) return false;  // (no decay: the plateau rule judges it)
  const double rate = std::log(double(before) / double(now)) / double(kRateWindow);  // per round
  return double(r) + std::log(double(now) / double(kFewPairs)) / rate > double(budget);
}

bool run_pd_rounds(Run& run, std::size_t budget, OnFewPairs on_few, OnSlowDecay on_slow) {
  const auto t = Clock::now();
  if (!run.elastic_a) run.elastic_a.emplace(run.A, run.sa.elems, run.sa.fixed);
  if (run.B && !run.elastic_b) run.elastic_b.emplace(*run.B, run.sb.elems, run.sb.fixed);
  run.rep.seconds_solve += since(t);
  Held held_a(run.A.vertices.size()), held_b(run.B ? run.B->vertices.size() : 0);
  run.patch_memory.clear();
  std::size_t first = 0, peak = 0, best = 0, best_round = 0;
  std::vector<std::size_t> counts;
  for (std::size_t r = 0; r < budget; ++r) {
    run.stop_if_cancelled();
    const auto t_round = Clock::now();
    const std::vector<std::array<std::size_t, 2>> pairs = contacts(run);
    if (pairs.empty()) return true;
    counts.push_back(pairs.size());
    if (on_slow == OnSlowDecay::Exit && decays_too_slowly(counts, budget)) return false;
    if (r == 0) first = pairs.size();
    peak = std::max(peak, pairs.size());
    if (r == 0 || double(pairs.size()) < double(best) * (1 - kMinProgress)) best = pairs.size(), best_round = r;
    if (r >= best_round + kStallRounds || (r >= kProbeRounds && first >= kProbeMinPairs && 2 * pairs.size() > peak)) return false;
    if (on_few == OnFewPairs::Exit && pairs.size() <= kFewPairs && r >= best_round + kFewPairsRounds) return false;
    run.stop_if_cancelled();
    ResolveRound rr;
    if (!pd_round(run, pairs, held_a, held_b, rr)) return false;
    rr.round = run.rep.rounds.size() + 1;
    rr.cost = run.cost();
    rr.seconds = since(t_round);
    run.record(rr);
  }
  return false;
}

bool run_pair_rounds(Run& run, std::size_t budget, ResolveVariant variant, OnStall on_stall) {
  PairAges last;
  StallWatch watch;
  for (std::size_t r = 0; r < budget; ++r) {
    run.stop_if_cancelled();
    const auto t_round = Clock::now();
    std::vector<std::array<std::size_t, 2>> pairs = contacts(run);
    if (pairs.empty()) return true;
    if (watch.stalled(r, pairs.size()) && on_stall == OnStall::Exit) return false;
    run.stop_if_cancelled();
    std::vector<int> age = last.next(pairs);
    ResolveRound rr;
    rr.round = run.rep.rounds.size() + 1;
    pair_round(run, pairs, age, variant, rr);
    last.pairs = std::move(pairs);
    last.age = std::move(age);
    rr.cost = run.cost();
    rr.seconds = since(t_round);
    run.record(rr);
  }
  return false;
}

}  // namespace pdd::mesh::detail
