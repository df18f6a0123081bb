// fallbacks.cpp — the translation, body-pair and body-spread fallbacks of resolve (fallbacks.h).
#include "fallbacks.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include "../resolve.h"
#include "geometry.h"
#include "local_step.h"
#include "rounds.h"
#include "step_limit.h"

namespace pdd::mesh::detail {
namespace {

// ---- the translation fallback

// After the translation, steps back towards rest of gamma (from kFirstGamma, halved on every
// rejected step, down to kLastGamma) of every free vertex's way back, each followed by at most
// kRelaxRounds projective-dynamics rounds: half the way first (a step that keeps the pairs apart is kept, so
// halving converges on the closest state the rounds can hold), and below 1/64 of the way a step
// saves at most 1/32 of the translation's cost (cost ~ distance^2), not worth its rounds.
// Where the rounds go: the translation (or spread) is bisected to touching, so every step back
// re-creates contact over the whole interface, and a step is kept only when the rounds clear it
// again. On the deep cases most steps are rejected after their full kRelaxRounds (ball through
// the plate: 1 of 7 kept; three balls pushed deep: 6 of 10, the walk ending at the round
// limit), so these cases use most of max_rounds here; past the first two (halving from 1/2) a
// rejected step ends on a plateau of 12 to 982 pairs that the rounds no longer reduce.
constexpr double kFirstGamma = 0.5, kLastGamma = 1.0 / 64;
constexpr std::size_t kRelaxRounds = 20;
// The separating distance is bisected until its bracket is below kBisection of the upper end:
// the translation's cost is then within 0.2% of the smallest along the line.
constexpr double kBisection = 1e-3;

// How each mesh shares a translation t u: the fixed one stays, else half each way.
struct Shares {
  double a = -0.5, b = 0.5;
};

// The vertex centroid of m (finite vertices), growing the box [lo, hi] by its vertices.
Vec3d centroid(const Mesh& m, Vec3d& lo, Vec3d& hi) {
  Vec3d c = {0, 0, 0};
  std::size_t n = 0;
  for (const Vec3d& v : m.vertices)
    if (finite(v)) {
      add_to(c, v);
      ++n;
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
    }
  return n ? scaled(c, 1.0 / double(n)) : c;
}

// Side s at its rest pose translated by share * t * u (fixed vertices at rest).
void translate(Side& s, double share_t, const Vec3d& u) {
  const Mesh& m = *s.rest;
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    s.cur.vertices[v] = s.is_fixed(v) ? m.vertices[v] : moved_by(m.vertices[v], share_t, u);
}

// Every valid element of s keeps its rest orientation (exact).
bool oriented(const Side& s) {
  for (std::size_t e : s.elems) {
    const TetVertices q = element(s.cur, e);
    if (orientation(q[0], q[1], q[2], q[3]) != s.sign[e]) return false;
  }
  return true;
}

// Both sides at the rest pose translated by t u, shared as `share` says.
void place_translation(Run& run, const Vec3d& u, const Shares& share, double t) {
  translate(run.sa, share.a * t, u);
  translate(run.sb, share.b * t, u);
}

// The smallest t in (0, t_hi] (to kBisection) at which the rest pose translated by t u
// separates (contact stage: exact), placed; nullopt when t_hi does not separate.
std::optional<double> separating_translation(Run& run, const Vec3d& u, const Shares& share, double t_hi) {
  const auto separated_at = [&](double t) {
    place_translation(run, u, share, t);
    run.stop_if_cancelled();
    return contacts(run).empty();
  };
  if (!(t_hi > 0) || !separated_at(t_hi)) return std::nullopt;
  double t_lo = 0;
  while (t_hi - t_lo > kBisection * t_hi) {
    const double mid = (t_lo + t_hi) / 2;
    (separated_at(mid) ? t_hi : t_lo) = mid;
  }
  place_translation(run, u, share, t_hi);
  return t_hi;
}

// The candidate directions of the translation (B's way, A's the opposite), in the order tried:
//   - the line of the meshes' vertex centroids (A -> B);
//   - the mean of the per-pair pdd2 normals (A -> B) of the pairs intersecting at rest: where
//     the contact region as a whole wants B to go;
//   - both signs of the three principal axes of the contact region (the vertices of the
//     elements in intersecting pairs at rest), smallest variance first: for a body pushed
//     through a plate the contact region is a slab of the plate and its thinnest axis the plate
//     normal, the short way out.
// Each is only a candidate: the bisection's contact stage (exact) decides which separate.
std::vector<Vec3d> candidate_directions(Run& run, const Vec3d& centroid_line) {
  std::vector<Vec3d> dirs = {centroid_line};
  run.place(run.A.vertices, run.B->vertices);
  const std::vector<std::array<std::size_t, 2>> pairs = contacts(run);
  if (pairs.empty()) return dirs;
  std::vector<Vec3d> normal(pairs.size(), Vec3d{0, 0, 0});
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const PairMove m = solve_move(element(run.A, pairs[k][0]), element(*run.B, pairs[k][1]), ResolveVariant::Pdd2);
    if (m.ok) normal[k] = m.u;
  });
  Vec3d mean = {0, 0, 0};
  for (const Vec3d& n : normal) add_to(mean, n);
  if (const auto u = unit(mean)) dirs.push_back(*u);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const auto& p : pairs)
    for (const TetVertices& t : {element(run.A, p[0]), element(*run.B, p[1])})
      for (const Vec3d& v : t) {
        const Eigen::Vector3d x(v[0], v[1], v[2]);
        c += x, second += x * x.transpose(), ++n;
      }
  c /= double(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second / double(n) - c * c.transpose());
  if (eig.info() != Eigen::Success) return dirs;
  for (int k = 0; k < 3; ++k) {  // eigenvalues in increasing order
    const Eigen::Vector3d a = eig.eigenvectors().col(k);
    if (const auto u = unit(Vec3d{a[0], a[1], a[2]})) {
      dirs.push_back(*u);
      dirs.push_back(scaled(*u, -1));
    }
  }
  return dirs;
}

// The cheapest separating translation over the candidate directions (a translation by t costs
// t^2 times the shares' squares along any direction, so the shortest t wins), placed; false
// when none separates within t_hi. A direction is bisected only when it separates at the best
// t so far (else it cannot be shorter, up to the bisection's bracket).
bool cheapest_translation(Run& run, const std::vector<Vec3d>& dirs, const Shares& share, double t_hi) {
  std::optional<std::pair<Vec3d, double>> best;
  for (const Vec3d& u : dirs) {
    const std::optional<double> t = separating_translation(run, u, share, best ? best->second : t_hi);
    if (t && (!best || *t < best->second)) best = {u, *t};
  }
  if (!best) return false;
  place_translation(run, best->first, share, best->second);  // separated: seen by the bisection
  return true;
}

// Steps back towards rest (above) from a resolved state, within `budget` rounds.
void relax_towards_rest(Run& run, std::size_t budget) {
  double cost = run.cost();
  double gamma = kFirstGamma;
  std::size_t used = 0;
  while (used < budget && gamma >= kLastGamma) {
    run.stop_if_cancelled();
    const std::vector<Vec3d> save_a = run.sa.cur.vertices, save_b = run.sb.cur.vertices;
    for (Side* s : {&run.sa, &run.sb})
      for (std::size_t v = 0; v < s->cur.vertices.size(); ++v)
        if (!s->is_fixed(v)) {
          const Vec3d d = scaled(sub(s->rest->vertices[v], s->cur.vertices[v]), gamma);
          if (finite(d) && dot(d, d) > 0) propose(*s, v, d);
        }
    const auto t0 = Clock::now();
    move_side(run.sa, 1);
    move_side(run.sb, 1);
    run.rep.seconds_move += since(t0);
    const std::size_t before = run.rep.rounds.size();
    bool ok = run_pd_rounds(run, std::min(kRelaxRounds, budget - used), run.B ? OnFewPairs::Exit : OnFewPairs::Continue);
    // Two meshes whose rounds stopped on a few pairs: finished per pair, as resolve.cpp finishes
    // the first rounds (the rounds close a pair left alone by about a tenth a round; steps of the
    // walk ended on 4 to 16 pairs after their 20 rounds and were undone: the ball through the
    // fixed plate of make-resolve-cases.sh --small ends at cost 0.0581 instead of 0.0597, the
    // Gmsh transfinite box of 8^3 cubes against its copy moved off the grid at 0.319, not 0.329).
    const std::size_t taken = run.rep.rounds.size() - before;
    if (!ok && run.B && run.rep.stopped_because.empty() && used + taken < budget && contacts(run).size() <= kFewPairs)
      ok = run_pair_rounds(run, std::min(kFinishRounds, budget - used - taken), run.o.variant, OnStall::Exit);
    used += run.rep.rounds.size() - before + 1;
    const double c = run.cost();
    if (ok && c < cost) {
      cost = c;
    } else {
      run.place(save_a, save_b);
      gamma /= 2;
    }
  }
}

// ---- the body fallback

// Bodies (definitions §11): the connected components of the valid elements, vertices shared
// between elements joining them (union-find). Returns the body of each vertex (-1: in no valid
// element) and the number of bodies.
std::pair<std::vector<std::ptrdiff_t>, std::size_t> bodies(const Mesh& m, const std::vector<std::size_t>& elems) {
  std::vector<std::size_t> parent(m.vertices.size());
  for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = v;
  const auto root = [&](std::size_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::size_t e : elems)
    for (int i = 1; i < 4; ++i) parent[root(m.tets[e][i])] = root(m.tets[e][0]);
  std::vector<std::ptrdiff_t> body(m.vertices.size(), -1), id(m.vertices.size(), -1);
  std::size_t n = 0;
  for (std::size_t e : elems)
    for (std::size_t v : m.tets[e]) {
      const std::size_t r = root(v);
      if (id[r] < 0) id[r] = std::ptrdiff_t(n++);
      body[v] = id[r];
    }
  return {body, n};
}

// The contact graph of the bodies (an edge per pair of bodies with an intersecting element pair
// at rest), 2-coloured: side[k] is 0 or 1 for a body in contact (its group), -1 for a body in no
// contact; group[k] numbers the connected components of the graph. nullopt when a body meets
// itself or the graph has an odd cycle (three bodies meeting pairwise): no two groups hold it.
struct BodyGroups {
  std::vector<int> side;
  std::vector<std::ptrdiff_t> group;
  std::size_t groups = 0;
};
std::optional<BodyGroups> body_groups(const Mesh& A, const std::vector<std::ptrdiff_t>& body, std::size_t count,
                                      const std::vector<std::array<std::size_t, 2>>& pairs) {
  std::vector<std::vector<std::size_t>> next(count);
  for (const auto& p : pairs) {
    const std::size_t i = std::size_t(body[A.tets[p[0]][0]]), j = std::size_t(body[A.tets[p[1]][0]]);
    if (i == j) return std::nullopt;  // a body against itself
    next[i].push_back(j);
    next[j].push_back(i);
  }
  BodyGroups g;
  g.side.assign(count, -1);
  g.group.assign(count, -1);
  for (std::size_t start = 0; start < count; ++start) {
    if (g.side[start] >= 0 || next[start].empty()) continue;
    std::vector<std::size_t> todo = {start};
    g.side[start] = 0;
    g.group[start] = std::ptrdiff_t(g.groups);
    while (!todo.empty()) {
      const std::size_t k = todo.back();
      todo.pop_back();
      for (std::size_t m : next[k]) {
        if (g.side[m] == g.side[k]) return std::nullopt;  // odd cycle
        if (g.side[m] < 0) g.side[m] = 1 - g.side[k], g.group[m] = g.group[k], todo.push_back(m);
      }
    }
    ++g.groups;
  }
  return g;
}

// The bodies of group `group` on side `side` as one mesh: `index` maps its vertices to the
// side's, `fixed` gets their flags.
Mesh cut_bodies(const Side& s, const std::vector<std::ptrdiff_t>& body, const BodyGroups& g, std::size_t group,
                int side, std::vector<std::size_t>& index, std::vector<char>& fixed) {
  const Mesh& A = *s.rest;
  const auto in = [&](std::size_t v) {
    const std::ptrdiff_t k = body[v];
    return k >= 0 && g.group[std::size_t(k)] == std::ptrdiff_t(group) && g.side[std::size_t(k)] == side;
  };
  Mesh m;
  std::vector<std::size_t> local(A.vertices.size(), SIZE_MAX);
  for (std::size_t v = 0; v < A.vertices.size(); ++v)
    if (in(v)) {
      local[v] = index.size();
      index.push_back(v);
      m.vertices.push_back(A.vertices[v]);
      fixed.push_back(s.fixed[v]);
    }
  for (std::size_t e : s.elems)
    if (in(A.tets[e][0]))
      m.tets.push_back({local[A.tets[e][0]], local[A.tets[e][1]], local[A.tets[e][2]], local[A.tets[e][3]]});
  return m;
}

// The two sides of one group resolved from rest as two meshes, within what is left of the run's
// rounds; their positions written into `result` when resolved.
bool resolve_group(Run& run, const std::vector<std::ptrdiff_t>& body, const BodyGroups& g, std::size_t group,
                   std::vector<Vec3d>& result) {
  const ResolveOptions& o = run.o;
  ResolveReport& rep = run.rep;
  std::vector<std::size_t> index_a, index_b;
  ResolveOptions sub = o;
  sub.fix_a = sub.fix_b = false;
  sub.fixed_vertices_a.clear();
  sub.fixed_vertices_b.clear();
  const Mesh ma = cut_bodies(run.sa, body, g, group, 0, index_a, sub.fixed_vertices_a);
  const Mesh mb = cut_bodies(run.sa, body, g, group, 1, index_b, sub.fixed_vertices_b);
  sub.max_rounds = std::max<std::size_t>(1, o.max_rounds - std::min(o.max_rounds - 1, rep.rounds.size()));
  const std::size_t before = rep.rounds.size();
  sub.progress = [&](const ResolveRound& r) {
    ResolveRound q = r;
    q.round = before + r.round;
    if (o.progress) o.progress(q);
  };
  const Resolution r = resolve_meshes(ma, &mb, sub);
  for (ResolveRound q : r.report.rounds) q.round += before, rep.rounds.push_back(q);
  rep.seconds_contacts += r.report.seconds_contacts;
  rep.seconds_solve += r.report.seconds_solve;
  rep.seconds_move += r.report.seconds_move + r.report.seconds_verify;
  if (!r.report.resolved) return false;
  for (std::size_t v = 0; v < index_a.size(); ++v) result[index_a[v]] = r.a[v];
  for (std::size_t v = 0; v < index_b.size(); ++v) result[index_b[v]] = r.b[v];
  return true;
}

// ---- the body spread (contact graphs that two colours cannot hold)

// The spread of the bodies in contact (clusters: the connected components of the bodies'
// contact graph): each body of a cluster translated by t times its way out, its vertex centroid
// minus the cluster's centre, one factor t per cluster. The centre is the cluster's vertex
// centroid, or the vertex centroid of its one body with fixed vertices (whose way is then zero:
// it stays). Every centroid difference within a cluster grows by (1 + t): far enough out, every
// two bodies whose centroids differ lie apart.
struct Spread {
  std::vector<std::ptrdiff_t> cluster;  // per body: its cluster, -1 for a body in no contact
  std::vector<Vec3d> way;               // per body: its way out (zero outside the clusters)
  std::vector<double> t_hi;             // per cluster: a first upper end for the bisection
  std::size_t clusters = 0;
};

// The clusters of the bodies joined by `pairs` (union-find over bodies); nullopt when a body
// meets itself (no translation of bodies parts it).
std::optional<std::pair<std::vector<std::ptrdiff_t>, std::size_t>> body_clusters(
    const Mesh& A, const std::vector<std::ptrdiff_t>& body, std::size_t count,
    const std::vector<std::array<std::size_t, 2>>& pairs) {
  std::vector<std::size_t> parent(count);
  for (std::size_t k = 0; k < count; ++k) parent[k] = k;
  const auto root = [&](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  std::vector<char> touching(count, 0);
  for (const auto& p : pairs) {
    const std::size_t i = std::size_t(body[A.tets[p[0]][0]]), j = std::size_t(body[A.tets[p[1]][0]]);
    if (i == j) return std::nullopt;
    touching[i] = touching[j] = 1;
    parent[root(i)] = root(j);
  }
  std::vector<std::ptrdiff_t> cluster(count, -1), id(count, -1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < count; ++k)
    if (touching[k]) {
      const std::size_t r = root(k);
      if (id[r] < 0) id[r] = std::ptrdiff_t(n++);
      cluster[k] = id[r];
    }
  return std::make_pair(cluster, n);
}

// The spread of side s's bodies in contact (above); nullopt when a body meets itself, a
// cluster holds two bodies with fixed vertices (neither may move), or two bodies in contact
// share their centroid (the spread does not part them).
std::optional<Spread> body_spread(const Side& s, const std::vector<std::ptrdiff_t>& body, std::size_t count,
                                  const std::vector<std::array<std::size_t, 2>>& pairs) {
  const Mesh& A = *s.rest;
  const auto clusters = body_clusters(A, body, count, pairs);
  if (!clusters) return std::nullopt;
  Spread sp;
  sp.cluster = clusters->first;
  sp.clusters = clusters->second;
  // Per body: vertex sum and count, whether it has fixed vertices; per cluster: the same and its box.
  std::vector<Vec3d> sum(count, Vec3d{0, 0, 0}), csum(sp.clusters, Vec3d{0, 0, 0});
  std::vector<std::size_t> n(count, 0), cn(sp.clusters, 0);
  std::vector<char> has_fixed(count, 0);
  std::vector<Vec3d> lo(sp.clusters, Vec3d{HUGE_VAL, HUGE_VAL, HUGE_VAL}), hi(sp.clusters, Vec3d{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  for (std::size_t v = 0; v < A.vertices.size(); ++v) {
    const std::ptrdiff_t k = body[v];
    if (k < 0 || sp.cluster[std::size_t(k)] < 0 || !finite(A.vertices[v])) continue;
    const std::size_t c = std::size_t(sp.cluster[std::size_t(k)]);
    add_to(sum[std::size_t(k)], A.vertices[v]), ++n[std::size_t(k)];
    add_to(csum[c], A.vertices[v]), ++cn[c];
    if (s.is_fixed(v)) has_fixed[std::size_t(k)] = 1;
    for (int i = 0; i < 3; ++i)
      lo[c][i] = std::min(lo[c][i], A.vertices[v][i]), hi[c][i] = std::max(hi[c][i], A.vertices[v][i]);
  }
  std::vector<Vec3d> centre(sp.clusters), centroid(count, Vec3d{0, 0, 0});
  std::vector<int> fixed_bodies(sp.clusters, 0);
  for (std::size_t c = 0; c < sp.clusters; ++c) centre[c] = scaled(csum[c], 1.0 / double(cn[c]));
  for (std::size_t k = 0; k < count; ++k) {
    if (sp.cluster[k] < 0) continue;
    const std::size_t c = std::size_t(sp.cluster[k]);
    centroid[k] = scaled(sum[k], 1.0 / double(n[k]));
    if (has_fixed[k]) {
      if (++fixed_bodies[c] > 1) return std::nullopt;
      centre[c] = centroid[k];
    }
  }
  sp.way.assign(count, Vec3d{0, 0, 0});
  for (std::size_t k = 0; k < count; ++k)
    if (sp.cluster[k] >= 0 && !has_fixed[k]) sp.way[k] = sub(centroid[k], centre[std::size_t(sp.cluster[k])]);
  // t_hi: every body lies within the cluster box's diagonal `diag` of its centroid, so two
  // bodies whose centroids lie d apart at rest are apart once (1 + t) d > 2 diag; over the
  // pairs in contact, t = 2 diag / (smallest such d). Bodies of a cluster not in contact at
  // rest, and bodies outside it, can still be met on the way: the bisection's contact stage
  // decides (and its upper end grows while it does not separate).
  std::vector<double> closest(sp.clusters, HUGE_VAL);
  for (const auto& p : pairs) {
    const std::size_t i = std::size_t(body[A.tets[p[0]][0]]), j = std::size_t(body[A.tets[p[1]][0]]);
    const Vec3d d = sub(centroid[i], centroid[j]);
    double& m = closest[std::size_t(sp.cluster[i])];
    m = std::min(m, std::sqrt(dot(d, d)));
  }
  sp.t_hi.resize(sp.clusters);
  for (std::size_t c = 0; c < sp.clusters; ++c) {
    const Vec3d e = sub(hi[c], lo[c]);
    sp.t_hi[c] = 2 * std::sqrt(dot(e, e)) / closest[c];
    if (!(closest[c] > 0) || !std::isfinite(sp.t_hi[c])) return std::nullopt;
  }
  return sp;
}

// Cluster c of side s at its rest pose spread by factor t (fixed vertices at rest; the other
// clusters as they are). False when a moved coordinate leaves the doubles (extreme scales).
bool place_spread(Side& s, const std::vector<std::ptrdiff_t>& body, const Spread& sp, std::size_t c, double t) {
  const Mesh& m = *s.rest;
  bool ok = true;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const std::ptrdiff_t k = body[v];
    if (k < 0 || sp.cluster[std::size_t(k)] != std::ptrdiff_t(c)) continue;
    s.cur.vertices[v] = s.is_fixed(v) ? m.vertices[v] : moved_by(m.vertices[v], t, sp.way[std::size_t(k)]);
    ok = ok && finite(s.cur.vertices[v]);
  }
  return ok;
}

// The smallest factor (to kBisection) at which cluster c, spread, meets nothing (contact stage:
// exact; no intersecting pair has an element in the cluster), placed; false, the cluster at
// rest, when no factor up to kSpreadGrowths doublings of its t_hi does (or the moved
// coordinates would leave the doubles).
constexpr int kSpreadGrowths = 4;
bool spread_cluster(Run& run, const std::vector<std::ptrdiff_t>& body, const Spread& sp, std::size_t c) {
  const Mesh& A = run.A;
  bool finite_at = true;  // the last placement stayed within the doubles
  const auto apart_at = [&](double t) {
    finite_at = place_spread(run.sa, body, sp, c, t);
    if (!finite_at) return false;
    run.stop_if_cancelled();
    for (const auto& p : contacts(run))
      for (std::size_t e : p)
        if (sp.cluster[std::size_t(body[A.tets[e][0]])] == std::ptrdiff_t(c)) return false;
    return true;
  };
  double t_hi = sp.t_hi[c];
  for (int growths = 0; !apart_at(t_hi); ++growths) {
    if (growths == kSpreadGrowths || !finite_at) {
      place_spread(run.sa, body, sp, c, 0);
      return false;
    }
    t_hi *= 2;
  }
  double t_lo = 0;
  while (t_hi - t_lo > kBisection * t_hi) {
    const double mid = (t_lo + t_hi) / 2;
    (apart_at(mid) ? t_hi : t_lo) = mid;
  }
  place_spread(run.sa, body, sp, c, t_hi);
  return true;
}

// The body spread from rest, cluster by cluster, then walked back towards the rest pose as the
// translation fallback is (relax_towards_rest). True when it ends resolved (R1 by the contact
// stage); false, positions unchanged, when it does not apply (body_spread) or does not separate
// everything with every element keeping its orientation.
bool spread_bodies(Run& run, const std::vector<std::ptrdiff_t>& body, std::size_t count,
                   const std::vector<std::array<std::size_t, 2>>& pairs, std::size_t budget) {
  const std::optional<Spread> sp = body_spread(run.sa, body, count, pairs);
  if (!sp) return false;
  const std::vector<Vec3d> keep = run.sa.cur.vertices;
  run.sa.cur.vertices = run.A.vertices;
  bool ok = true;
  for (std::size_t c = 0; ok && c < sp->clusters; ++c) ok = spread_cluster(run, body, *sp, c);
  if (!ok || !contacts(run).empty() || !oriented(run.sa)) {
    run.sa.cur.vertices = keep;
    return false;
  }
  relax_towards_rest(run, budget);
  return true;
}

}  // namespace

bool rigid_rounds_from_rest(Run& run, std::size_t budget) {
  const double depth_scale = run.depth_scale;
  run.place(run.A.vertices, run.B->vertices);
  run.pd_variant = ResolveVariant::Rigid;
  const std::size_t before = run.rep.rounds.size();
  bool ok = run_pd_rounds(run, budget, OnFewPairs::Exit, OnSlowDecay::Exit);
  const std::size_t used = run.rep.rounds.size() - before;
  if (!ok && run.rep.stopped_because.empty() && used < budget && contacts(run).size() <= kFewPairs)
    ok = run_pair_rounds(run, std::min(kFinishRounds, budget - used), ResolveVariant::Rigid, OnStall::Exit);
  run.pd_variant = run.o.variant;
  if (!ok) run.depth_scale = depth_scale;
  return ok;
}

bool translate_and_relax(Run& run, std::size_t budget) {
  Side &sa = run.sa, &sb = run.sb;
  const bool fixed_a = sa.any_fixed(), fixed_b = sb.any_fixed();
  if (fixed_a && fixed_b) return false;
  Shares share;
  if (fixed_a) share = {0, 1};
  if (fixed_b) share = {-1, 0};
  Vec3d lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  const Vec3d ca = centroid(run.A, lo, hi), cb = centroid(*run.B, lo, hi);
  const Vec3d u = unit(sub(cb, ca)).value_or(Vec3d{1, 0, 0});
  const std::vector<Vec3d> keep_a = sa.cur.vertices, keep_b = sb.cur.vertices;
  double t_hi = 0;
  for (int k = 0; k < 3; ++k) t_hi += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  t_hi = 2 * std::sqrt(t_hi);  // more than the extent of both meshes along any line
  if (!cheapest_translation(run, candidate_directions(run, u), share, t_hi) || !oriented(sa) || !oriented(sb)) {
    run.place(keep_a, keep_b);
    return false;
  }
  relax_towards_rest(run, budget);
  return true;
}

bool resolve_bodies(Run& run) {
  const Mesh& A = run.A;
  // Named, not a structured binding: the lambdas below capture them (C++17 cannot capture a
  // structured binding; clang rejects it).
  const std::pair<std::vector<std::ptrdiff_t>, std::size_t> found = bodies(A, run.sa.elems);
  const std::vector<std::ptrdiff_t>& body = found.first;
  const std::size_t count = found.second;
  if (count < 2) return false;
  const std::vector<std::array<std::size_t, 2>> pairs = intersecting_pairs(A, run.sa.elems, nullptr, {});
  const std::optional<BodyGroups> g = body_groups(A, body, count, pairs);
  const auto two_meshes = [&] {
    std::vector<Vec3d> result = A.vertices;
    std::size_t k = 0;
    while (k < g->groups && resolve_group(run, body, *g, k, result)) ++k;
    if (k < g->groups) return false;
    run.sa.cur.vertices = result;
    return true;
  };
  const auto spread = [&] {
    return spread_bodies(run, body, count, pairs, run.o.max_rounds - std::min(run.o.max_rounds, run.rep.rounds.size()));
  };
  // Two bodies: the two meshes' translation tries several directions, the spread only the
  // centroid line. Larger groups: the two meshes are rigid wholes of bodies on both sides (a
  // chain's two outer bodies against its middle one need a translation across the chain), the
  // spread moves every body its own way.
  bool pairs_only = bool(g);
  if (g) {
    std::vector<std::size_t> size(g->groups, 0);
    for (std::ptrdiff_t k : g->group)
      if (k >= 0) ++size[std::size_t(k)];
    pairs_only = std::all_of(size.begin(), size.end(), [](std::size_t n) { return n == 2; });
  }
  if (pairs_only) return two_meshes() || spread();
  return spread() || (g && two_meshes());
}

}  // namespace pdd::mesh::detail
