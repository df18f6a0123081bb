// resolve.cpp — pdd::mesh::resolve and resolve_self (mesh.h): the phases of resolve.h in
// order (rounds, then the fallbacks), the exact verdict and the report.
#include <algorithm>
#include <cmath>
#include <optional>

#include "element_quality.h"
#include "resolve.h"
#include "resolve/fallbacks.h"
#include "resolve/geometry.h"
#include "resolve/rounds.h"
#include "resolve/state.h"

namespace pdd::mesh {
namespace detail {
namespace {

// Positions with the number of pairs intersecting there (contact stage).
struct Snapshot {
  std::vector<Vec3d> a, b;
  std::size_t pairs = 0;
};
Snapshot snapshot(Run& run) { return {run.sa.cur.vertices, run.sb.cur.vertices, contacts(run).size()}; }

// The end of each phase that did not clear the contacts, the one with the fewest pairs kept:
// when nothing clears them, the state written (the report then names what remains of it).
// Every phase keeps R2 and R4 (step_limit.h), so any of these ends is a valid state to write.
struct BestEnd {
  std::optional<Snapshot> best;
  void consider(Run& run) {
    Snapshot s = snapshot(run);
    if (!best || s.pairs < best->pairs) best = std::move(s);
  }
  void restore(Run& run) const {
    if (best && best->pairs < contacts(run).size()) run.place(best->a, best->b);
  }
};

// The rounds and the fallbacks (resolve.h) from the rest pose; sets rep.method when one of them
// cleared the contacts (the verdict judges the result either way).
void run_phases(Run& run) {
  const ResolveOptions& o = run.o;
  ResolveReport& rep = run.rep;
  const std::size_t first_budget = std::max<std::size_t>(1, o.max_rounds / 2);
  const auto rounds_left = [&] { return o.max_rounds > rep.rounds.size(); };
  if (run.sa.all_fixed() && (!run.B || run.sb.all_fixed())) {
    rep.stopped_because = "every vertex is fixed: nothing can move";
    return;
  }
  if (run_pd_rounds(run, first_budget, run.B ? OnFewPairs::Exit : OnFewPairs::Continue,
                    run.B ? OnSlowDecay::Exit : OnSlowDecay::Continue)) {
    rep.method = ResolveMethod::Rounds;
    return;
  }
  const auto go_on = [&] { return rep.stopped_because.empty(); };
  BestEnd best_end;
  best_end.consider(run);
  // Two meshes whose rounds stalled on a few pairs: the per-pair rounds from there, before
  // anything starts again from rest. A vertex pulled alone the elastic step moves about a tenth
  // of its pull (its anchor against its neighbours', elastic_step.h), so a pair left alone closes
  // by about that share a round and the rounds stall on a few such pairs; the per-pair rounds
  // move a pair's vertices the whole way (five-tetrahedra blocks against their copy moved off
  // the grid and turned: without them the translation, ~180 rounds, cost 0.228; with them ~30
  // rounds, cost 0.069).
  if (go_on() && run.B && rounds_left() && best_end.best->pairs <= kFewPairs) {
    if (run_pair_rounds(run, std::min(kFinishRounds, o.max_rounds - rep.rounds.size()), o.variant, OnStall::Exit))
      return void(rep.method = ResolveMethod::Rounds);
    best_end.consider(run);
  }
  if (go_on() && !run.B && rounds_left()) {
    run.stop_if_cancelled();
    if (resolve_bodies(run)) return void(rep.method = ResolveMethod::Bodies);
  }
  // Self-contact of one body folded into itself: the contact layers of the two folds can be
  // squeezed to the R4 bounds before the interior follows (the step limit then stalls the
  // rounds with a few pairs left). The rounds again from the rest pose with the weak anchors
  // of ElasticStep::Anchor::Free, within the first budget: the interior follows the contact
  // further from the first round (they cost more where the default anchors succeed, so they
  // are not the first try).
  if (go_on() && !run.B && rounds_left()) {
    run.place(run.A.vertices, {});
    run.sa.anchor = ElasticStep::Anchor::Free;
    if (run_pd_rounds(run, std::min(first_budget, o.max_rounds - rep.rounds.size())))
      return void(rep.method = ResolveMethod::Rounds);
    best_end.consider(run);
  }
  // Self-contact still stalled: the rounds again from the rest pose with pdd2's per-pair planes.
  // pdd2_global gives each pair its own cheapest plane over every direction; where a body is
  // pressed into itself by a large share of an element (a bar of Kuhn cubes wound into a helix
  // whose turns overlap by 0.8 of a cell), neighbouring pairs then choose planes across each
  // other (sideways as often as along the contact normal) and the rounds stall with thousands of
  // pairs, the contact layer squeezed to R4's bound. pdd2 chooses among the pair's face normals
  // and edge crossings, which neighbouring pairs of one contact patch share, so their planes
  // agree. First with the default anchors (on that helix the weak ones end with 4 pairs at the
  // round limit), then, where these stall with the contact layer at R4's bound, again from the
  // rest pose with the weak anchors: on a tighter helix (radius 1.5 bar widths, 720 elements)
  // the default anchors stall at 5 pairs (and the weak ones do not free them from there), the
  // weak ones from rest resolve it.
  if (go_on() && !run.B && o.variant == ResolveVariant::Global && rounds_left()) {
    run.pd_variant = ResolveVariant::Pdd2;
    for (const ElasticStep::Anchor anchor : {ElasticStep::Anchor::Pulled, ElasticStep::Anchor::Free}) {
      run.place(run.A.vertices, {});
      run.sa.anchor = anchor;
      if (go_on() && rounds_left() && run_pd_rounds(run, std::min(first_budget, o.max_rounds - rep.rounds.size())))
        return void(rep.method = ResolveMethod::Pdd2Rounds);
      best_end.consider(run);
    }
    run.pd_variant = o.variant;
  }
  run.sa.anchor = ElasticStep::Anchor::Pulled;
  // Self-contact stalled: the per-pair rounds from the rest pose, within what is left of the
  // first budget. Not for two meshes, whose translation fallback follows: from rest their
  // per-pair rounds resolved none of the cases that reached them (the tests' and bench's deep
  // balls and ball through a plate, scripts/make-resolve-cases.sh's `deep`, Gmsh transfinite and
  // TetGen boxes of 8^3 and 9^3 cells against copies moved off the grid or half a cell, aligned
  // and turned: each stalled after 5 to 10 rounds, 0.5 to 1.3 s a round on the boxes), and the
  // rounds they took were the translation's walk back towards rest.
  if (go_on() && !run.B && first_budget > rep.rounds.size()) {
    run.place(run.A.vertices, {});
    if (run_pair_rounds(run, first_budget - rep.rounds.size(), o.variant, OnStall::Exit))
      return void(rep.method = ResolveMethod::Rounds);
    best_end.consider(run);
  }
  // Two meshes whose rounds stalled: the rounds again from the rest pose with the rigid
  // variant's planes (fallbacks.h), before the translation.
  if (go_on() && run.B && o.variant != ResolveVariant::Rigid && rounds_left()) {
    if (rigid_rounds_from_rest(run, std::min(first_budget, o.max_rounds - rep.rounds.size())))
      return void(rep.method = ResolveMethod::RigidRounds);
    best_end.consider(run);
  }
  if (go_on() && run.B && rounds_left()) {
    if (translate_and_relax(run, o.max_rounds - rep.rounds.size())) return void(rep.method = ResolveMethod::Translation);
    // declined (positions as they were): the rounds go on from there up to max_rounds.
    if (rounds_left() && run_pair_rounds(run, o.max_rounds - rep.rounds.size(), o.variant, OnStall::Continue))
      return void(rep.method = ResolveMethod::Rounds);
  }
  // Self-contact has no separated start: stalled deformable rounds restart from the rest pose
  // with the rigid variant's rounds (which move elements as a whole and do not squeeze them).
  if (go_on() && !run.B && o.variant != ResolveVariant::Rigid && rounds_left()) {
    run.place(run.A.vertices, {});
    if (run_pair_rounds(run, o.max_rounds - rep.rounds.size(), ResolveVariant::Rigid, OnStall::Continue))
      rep.method = ResolveMethod::RigidRounds;
  }
  if (rep.method == ResolveMethod::None && go_on()) best_end.restore(run);
}

// The largest |p - m0.vertices| over finite displacements.
double max_displacement(const Mesh& m0, const std::vector<Vec3d>& p) {
  double d = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3d x = sub(p[i], m0.vertices[i]);
    if (finite(x)) d = std::max(d, std::sqrt(dot(x, x)));
  }
  return d;
}

// The exact verdict on the positions reached, into the report, and the closing row of the
// rounds table: when a fallback undid its last rounds (the last row's cost is not the cost
// written), a row gives the written state's intersecting pairs (0 when resolved) and cost, with
// max_pd2 0 and the verdict's time.
void verdict(Run& run) {
  ResolveReport& rep = run.rep;
  const Mesh* B = run.B;
  const auto t = Clock::now();
  ResolveReport v = B ? check_resolution(run.A, run.sa.cur.vertices, *B, run.sb.cur.vertices, run.sa.fixed,
                                         run.sb.fixed, run.o)
                      : check_resolution_self(run.A, run.sa.cur.vertices, run.sa.fixed, run.o);
  rep.seconds_verify = since(t);
  rep.r1 = v.r1;
  rep.r2 = v.r2;
  rep.r3 = v.r3;
  rep.r4 = v.r4;
  rep.limits = v.limits;
  rep.resolved = v.resolved;
  rep.poor_elements = std::move(v.poor_elements);
  rep.max_volume_ratio = v.max_volume_ratio;
  rep.min_shape_ratio = v.min_shape_ratio;
  rep.volume_ratio_a = std::move(v.volume_ratio_a);
  rep.volume_ratio_b = std::move(v.volume_ratio_b);
  rep.shape_ratio_a = std::move(v.shape_ratio_a);
  rep.shape_ratio_b = std::move(v.shape_ratio_b);
  rep.remaining_pairs = std::move(v.remaining_pairs);
  rep.bad_elements = std::move(v.bad_elements);
  rep.moved_fixed_vertices = std::move(v.moved_fixed_vertices);
  rep.min_volume_ratio = v.min_volume_ratio;
  rep.cost_a = side_cost(run.sa);
  rep.cost_b = B ? side_cost(run.sb) : 0;
  rep.cost = rep.cost_a + rep.cost_b;
  if (!rep.rounds.empty() && rep.rounds.back().cost != rep.cost) {
    ResolveRound last;
    last.round = rep.rounds.size() + 1;
    last.pairs = rep.remaining_pairs.size();
    last.cost = rep.cost;
    last.seconds = rep.seconds_verify;
    rep.rounds.push_back(last);
  }
  rep.max_displacement = max_displacement(run.A, run.sa.cur.vertices);
  if (B) rep.max_displacement = std::max(rep.max_displacement, max_displacement(*B, run.sb.cur.vertices));
}

}  // namespace

Resolution resolve_meshes(const Mesh& A, const Mesh* B, const ResolveOptions& o) {
  const auto t_all = Clock::now();
  if (B && o.fix_a && o.fix_b) throw std::invalid_argument("resolve: fix_a and fix_b are both set; at most one mesh can be fixed");
  if (o.max_rounds < 1) throw std::invalid_argument("resolve: max_rounds must be at least 1");
  Resolution out;
  Run run(A, B, o, out.report);
  run.rep.variant = o.variant;
  check_limits(o);
  init_side(run.sa, A, 'A', o.fix_a, o.fixed_vertices_a, run.rep.skipped);
  if (B) init_side(run.sb, *B, 'B', o.fix_b, o.fixed_vertices_b, run.rep.skipped);
  run.sa.limits = run.sb.limits = o;
  run_phases(run);
  run.stop_if_cancelled();
  verdict(run);
  out.a = std::move(run.sa.cur.vertices);
  if (B) out.b = std::move(run.sb.cur.vertices);
  out.report.seconds_total = since(t_all);
  return out;
}

}  // namespace detail

ResolveVariant parse_resolve_variant(const std::string& name) {
  if (name == "global") return ResolveVariant::Global;
  if (name == "pdd2") return ResolveVariant::Pdd2;
  if (name == "rigid") return ResolveVariant::Rigid;
  throw std::invalid_argument("unknown resolve variant '" + name + "' (global, pdd2, rigid)");
}

const char* resolve_method_name(ResolveMethod m) {
  switch (m) {
    case ResolveMethod::Rounds: return "rounds";
    case ResolveMethod::Translation: return "translation";
    case ResolveMethod::Pdd2Rounds: return "pdd2 rounds";
    case ResolveMethod::RigidRounds: return "rigid rounds";
    case ResolveMethod::Bodies: return "bodies";
    case ResolveMethod::None: return "none";
  }
  return "?";
}

const char* resolve_variant_name(ResolveVariant v) {
  switch (v) {
    case ResolveVariant::Global: return "global";
    case ResolveVariant::Pdd2: return "pdd2";
    case ResolveVariant::Rigid: return "rigid";
  }
  return "?";
}

Resolution resolve(const Mesh& A, const Mesh& B, const ResolveOptions& options) {
  return detail::resolve_meshes(A, &B, options);
}

Resolution resolve_self(const Mesh& A, const ResolveOptions& options) {
  return detail::resolve_meshes(A, nullptr, options);
}

}  // namespace pdd::mesh
