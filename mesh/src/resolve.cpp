// resolve.cpp — pdd::mesh::resolve and resolve_self (mesh.h): rounds of contact-space
// projection with the deformable metric; the method and its arguments are in resolve.h.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "check_indices.h"
#include "elastic_step.h"
#include "element_quality.h"
#include "resolve.h"

namespace pdd::mesh {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d scaled(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
void add_to(Vec3d& a, const Vec3d& b) {
  for (int k = 0; k < 3; ++k) a[k] += b[k];
}
bool finite(const Vec3d& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }
// a / |a|, or nullopt when a is zero or not finite.
std::optional<Vec3d> unit(const Vec3d& a) {
  const double n = std::sqrt(dot(a, a));
  if (!(n > 0) || !std::isfinite(n)) return std::nullopt;
  return scaled(a, 1 / n);
}

// How far B must move along the unit u for its projections to clear A's: max u.s - min u.r.
double clearance(const Vec3d& u, const TetVertices& A, const TetVertices& B) {
  double hi = -HUGE_VAL, lo = HUGE_VAL;
  for (int i = 0; i < 4; ++i) {
    hi = std::max(hi, dot(u, A[i]));
    lo = std::min(lo, dot(u, B[i]));
  }
  return hi - lo;
}

// The axis of a candidate direction (definitions §3's vectors, up to sign).
Vec3d label_axis(const DirectionLabel& l, const TetVertices& A, const TetVertices& B) {
  auto face = [](const TetVertices& T, int i) {
    const auto& f = kFace[i];
    return cross(sub(T[f[1]], T[f[0]]), sub(T[f[2]], T[f[0]]));
  };
  switch (l.kind) {
    case ContactKind::FV: return face(A, l.a);
    case ContactKind::VF: return face(B, l.a);
    case ContactKind::EE: break;
  }
  const Vec3d e = sub(A[kEdges[l.a][1]], A[kEdges[l.a][0]]);
  const Vec3d f = sub(B[kEdges[l.b][1]], B[kEdges[l.b][0]]);
  const Vec3d n = cross(f, e);
  if (dot(n, n) > 0) return n;
  const Vec3d w = sub(B[kEdges[l.b][0]], A[kEdges[l.a][0]]);  // parallel edges
  return sub(w, scaled(e, dot(w, e) / dot(e, e)));
}

// One pair's local step: target displacements of its eight vertices, all along u (A -> B).
struct PairMove {
  std::array<Vec3d, 4> da{}, db{};
  Vec3d u{};
  double value = 0;  // the variant's squared depth used (max_pd2)
  bool ok = false;
};

// The rigid translation along the unit u that clears the pair, half to each side.
PairMove translation(const Vec3d& u, const TetVertices& A, const TetVertices& B) {
  PairMove m;
  const double d = std::max(0.0, clearance(u, A, B));
  for (int i = 0; i < 4; ++i) {
    m.da[i] = scaled(u, -d / 2);
    m.db[i] = scaled(u, d / 2);
  }
  m.u = u;
  m.value = d * d;
  m.ok = std::isfinite(d);
  return m;
}

PairMove rigid_move(const TetVertices& A, const TetVertices& B) {
  const fast::Depth r = fast::rigid_pd2(A, B);
  if (r.status == fast::DepthStatus::Ok && r.dir) {
    if (const auto u = unit(label_axis(*r.dir, A, B))) {
      // The label fixes the axis; of its two signs the one with the smaller clearance is the
      // rigid direction (the other would push B through A). Decided in doubles: the value is
      // only a target, the next round's exact decision judges the outcome.
      const Vec3d v = scaled(*u, -1);
      PairMove m = translation(clearance(*u, A, B) <= clearance(v, A, B) ? *u : v, A, B);
      m.value = r.pd2;
      if (m.ok) return m;
    }
  }
  // No certified rigid value: any direction separates after its clearance; use the centroids'.
  Vec3d c = {0, 0, 0};
  for (int i = 0; i < 4; ++i) add_to(c, sub(B[i], A[i]));
  if (const auto u = unit(c)) return translation(*u, A, B);
  return translation({1, 0, 0}, A, B);
}

PairMove from_positions(const Positions<double>& qa, const Positions<double>& qb, const TetVertices& A,
                        const TetVertices& B, double value, const std::optional<std::array<double, 3>>& normal) {
  PairMove m;
  Vec3d sa = {0, 0, 0}, sb = {0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    m.da[i] = sub(qa[i], A[i]);
    m.db[i] = sub(qb[i], B[i]);
    if (!finite(m.da[i]) || !finite(m.db[i])) return m;
    add_to(sa, m.da[i]);
    add_to(sb, m.db[i]);
  }
  // The normal (A -> B): given, or the direction of sum d_B - sum d_A (every displacement of a
  // per-direction solution is along its normal, B's sum forward, A's backward).
  const auto u = unit(normal ? Vec3d{(*normal)[0], (*normal)[1], (*normal)[2]} : sub(sb, sa));
  if (!u) return m;
  m.u = *u;
  m.value = value;
  m.ok = true;
  return m;
}

PairMove solve_move(const TetVertices& A, const TetVertices& B, ResolveVariant variant) {
  if (variant == ResolveVariant::Rigid) return rigid_move(A, B);
  const bool global = variant == ResolveVariant::Global;
  fast::SolveOptions options;
  options.with_global = global;
  const PairResult<double> r = fast::solve_pair(TetPair{"", {}, A, B}, options);
  if (!r.error) {
    if (global && !r.pdd2_global_error && r.pdd2_global_normal) {
      PairMove m = from_positions(r.q1_A_global, r.q1_B_global, A, B, r.pdd2_global, r.pdd2_global_normal);
      if (m.ok) return m;
    }
    PairMove m = from_positions(r.q1_A, r.q1_B, A, B, r.pdd2, std::nullopt);  // pdd2's positions
    if (m.ok) return m;
  }
  return rigid_move(A, B);
}

// R4 with a safety margin, in doubles (the step limit's test): the ratios in doubles carry a
// relative error of a few ulps times the element's condition, far below kQualityMargin for
// every element that is not nearly flat at rest, so a state that passes this test passes the
// exact R4 verdict too (which stays the judge: check_resolution decides it afresh).
constexpr double kQualityMargin = 1.0 / 64;
bool usable_with_margin(const QualityLimits& q, const detail::Ratios& r) {
  const double m = 1 + kQualityMargin;
  return r.volume >= q.min_volume_ratio * m && r.volume * q.min_volume_ratio * m <= 1 &&
         r.shape >= q.min_shape_ratio * m;
}

// One mesh's state during the rounds.
struct Side {
  const Mesh* rest = nullptr;
  char which = 'A';
  Mesh cur;
  std::vector<char> fixed;          // per vertex
  std::vector<std::size_t> elems;   // valid at rest
  QualityLimits limits;             // R4's bounds, kept by the step limit
  std::vector<Sign> sign;           // rest orientation per element (Zero: not valid)
  std::vector<double> d0, s0;       // per element: rest 6V and sum of squared edge lengths
  std::vector<double> volume;       // |rest volume| per element
  std::vector<Vec3d> acc;           // per vertex: sum of w * displacement this round
  std::vector<double> weight;       // per vertex: sum of w this round
  // The valid elements of each vertex (CSR: vertex_elems[vertex_start[v] .. vertex_start[v+1])).
  std::vector<std::size_t> vertex_start, vertex_elems;
};

void init_side(Side& s, const Mesh& m, char which, bool fix_all, const std::vector<char>& flags,
               std::vector<SkippedElement>& skipped) {
  detail::check_indices(m, which);
  if (!flags.empty() && flags.size() != m.vertices.size()) {
    std::ostringstream o;
    o << "fixed-vertex flags of mesh " << which << ": " << flags.size() << " flags for " << m.vertices.size()
      << " vertices";
    throw std::invalid_argument(o.str());
  }
  s.rest = &m;
  s.which = which;
  s.cur = m;
  s.fixed = fix_all ? std::vector<char>(m.vertices.size(), 1)
                    : flags.empty() ? std::vector<char>(m.vertices.size(), 0) : flags;
  s.elems = detail::valid_elements(m, which, &skipped);
  s.sign.assign(m.tets.size(), Sign::Zero);
  s.d0.assign(m.tets.size(), 0);
  s.s0.assign(m.tets.size(), 0);
  s.volume.assign(m.tets.size(), 0);
  tbb::parallel_for(std::size_t{0}, s.elems.size(), [&](std::size_t k) {
    const std::size_t e = s.elems[k];
    const TetVertices t = element(m, e);
    s.sign[e] = detail::orientation(t[0], t[1], t[2], t[3]);
    s.d0[e] = detail::volume6(t);
    s.s0[e] = detail::edge_square_sum(t);
    const Vec3d u = sub(t[1], t[0]), v = sub(t[2], t[0]), w = sub(t[3], t[0]);
    s.volume[e] = std::abs(dot(u, cross(v, w))) / 6;
  });
  s.vertex_start.assign(m.vertices.size() + 1, 0);
  for (std::size_t e : s.elems)
    for (std::size_t v : m.tets[e]) ++s.vertex_start[v + 1];
  for (std::size_t v = 0; v < m.vertices.size(); ++v) s.vertex_start[v + 1] += s.vertex_start[v];
  s.vertex_elems.resize(s.vertex_start.back());
  std::vector<std::size_t> fill(s.vertex_start.begin(), s.vertex_start.end() - 1);
  for (std::size_t e : s.elems)
    for (std::size_t v : m.tets[e]) s.vertex_elems[fill[v]++] = e;
  s.acc.assign(m.vertices.size(), {0, 0, 0});
  s.weight.assign(m.vertices.size(), 0);
}

// Adds one element's share of a pair's move (fixed vertices take no displacement).
void accumulate(Side& s, std::size_t e, const std::array<Vec3d, 4>& d, bool longest) {
  const double w = s.volume[e];
  for (int i = 0; i < 4; ++i) {
    const std::size_t v = s.rest->tets[e][i];
    if (s.fixed[v]) continue;
    if (longest) {  // acc holds the longest target, weight 1 once set
      if (s.weight[v] == 0 || dot(d[i], d[i]) > dot(s.acc[v], s.acc[v])) s.acc[v] = d[i];
      s.weight[v] = 1;
      continue;
    }
    add_to(s.acc[v], scaled(d[i], w));
    s.weight[v] += w;
  }
}

// The per-pair rounds' gap mu between a pair's two sides: kMargin of its longest edge plus
// kMarginUlp of its largest |coordinate|: far above the rounding of the moved coordinates
// (2^-52 |x|), and so small against the element that its cost, at most mu^2 per pair and
// mesh, is below 1e-12 of an element layer's.
constexpr double kMargin = 1e-6;
constexpr double kMarginUlp = 1e-12;

// Fixed vertices and the margin (resolve.h): the fixed vertices' retreat along u goes to the
// other side as a translation, and the two sides are pushed mu further apart.
void finish_move(PairMove& m, const std::array<char, 4>& fixed_a, const std::array<char, 4>& fixed_b,
                 const TetVertices& A, const TetVertices& B) {
  double retreat_a = 0, retreat_b = 0, edge = 0, coord = 0;
  for (int i = 0; i < 4; ++i) {
    if (fixed_a[i]) retreat_a = std::max(retreat_a, -dot(m.da[i], m.u));
    if (fixed_b[i]) retreat_b = std::max(retreat_b, dot(m.db[i], m.u));
    for (int k = 0; k < 3; ++k) coord = std::max({coord, std::abs(A[i][k]), std::abs(B[i][k])});
  }
  for (const auto& e : kEdges) {
    edge = std::max(edge, dot(sub(A[e[1]], A[e[0]]), sub(A[e[1]], A[e[0]])));
    edge = std::max(edge, dot(sub(B[e[1]], B[e[0]]), sub(B[e[1]], B[e[0]])));
  }
  const double mu = kMargin * std::sqrt(edge) + kMarginUlp * coord;
  for (int i = 0; i < 4; ++i) {
    if (fixed_a[i])
      m.da[i] = {0, 0, 0};
    else
      add_to(m.da[i], scaled(m.u, -(retreat_b + mu / 2)));
    if (fixed_b[i])
      m.db[i] = {0, 0, 0};
    else
      add_to(m.db[i], scaled(m.u, retreat_a + mu / 2));
  }
}

std::array<char, 4> fixed_of(const Side& s, std::size_t e) {
  std::array<char, 4> f;
  for (int i = 0; i < 4; ++i) {
    const std::size_t v = s.rest->tets[e][i];
    f[i] = s.fixed[v];
  }
  return f;
}

// Halvings of a vertex's step before the step limit sets it to 0 (resolve.h: the limit then ends
// with every element valid): 2^-24 of a step is below any displacement that matters.
constexpr int kMaxHalvings = 24;

// The global step and the step limit on one side (resolve.h, steps 3 and 4): moves the
// vertices with a displacement, then clears the accumulators.
void move_side(Side& s, double overshoot) {
  const std::size_t nv = s.cur.vertices.size();
  std::vector<Vec3d> D(nv, {0, 0, 0});
  std::vector<double> alpha(nv, 0);
  std::vector<char> moving(nv, 0);
  for (std::size_t v = 0; v < nv; ++v)
    if (s.weight[v] > 0) {
      D[v] = scaled(s.acc[v], 1 / s.weight[v]);
      moving[v] = finite(D[v]);
      if (!moving[v]) D[v] = {0, 0, 0};
    }
  for (std::size_t v = 0; v < nv; ++v)
    if (moving[v]) alpha[v] = overshoot;
  // Elements with a moved vertex: the only ones whose orientation can change.
  std::vector<std::size_t> affected;
  for (std::size_t e : s.elems)
    for (std::size_t v : s.rest->tets[e])
      if (alpha[v] > 0) {
        affected.push_back(e);
        break;
      }
  const std::vector<Vec3d> before = s.cur.vertices;
  auto place = [&](std::size_t v) {
    s.cur.vertices[v] = alpha[v] > 0 ? Vec3d{before[v][0] + alpha[v] * D[v][0], before[v][1] + alpha[v] * D[v][1],
                                             before[v][2] + alpha[v] * D[v][2]}
                                     : before[v];
  };
  for (std::size_t v = 0; v < nv; ++v)
    if (alpha[v] > 0) place(v);
  // Passes of the limit: check the elements in `check` (first every affected one, then those
  // with a vertex whose alpha the last pass lowered: the others are as they were when they passed).
  std::vector<std::size_t> check = affected;
  std::vector<char> bad, changed(nv, 0);
  for (int pass = 0; !check.empty(); ++pass) {
    bad.assign(check.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, check.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k != r.end(); ++k) {
                          const std::size_t e = check[k];
                          const TetVertices q = element(s.cur, e);
                          bad[k] = detail::orientation(q[0], q[1], q[2], q[3]) != s.sign[e] ||
                                   !usable_with_margin(s.limits, detail::ratios(s.d0[e], s.s0[e], q));
                        }
                      });
    std::vector<std::size_t> lowered;
    for (std::size_t k = 0; k < check.size(); ++k)
      if (bad[k])
        for (std::size_t v : s.rest->tets[check[k]])
          if (alpha[v] > 0 && !changed[v]) {
            alpha[v] = pass < kMaxHalvings ? alpha[v] / 2 : 0;
            place(v);
            changed[v] = 1;
            lowered.push_back(v);
          }
    check.clear();
    for (std::size_t v : lowered)
      for (std::size_t k = s.vertex_start[v]; k < s.vertex_start[v + 1]; ++k) check.push_back(s.vertex_elems[k]);
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    for (std::size_t v : lowered) changed[v] = 0;
  }
  std::fill(s.acc.begin(), s.acc.end(), Vec3d{0, 0, 0});
  std::fill(s.weight.begin(), s.weight.end(), 0.0);
}

double side_cost(const Side& s) { return mesh_cost(*s.rest, s.cur.vertices); }

// ---------------------------------------------------------------------------------------------
// Projective-dynamics rounds (resolve.h): contacts, local step, global step, step limit.

// Rounds without fewer intersecting pairs than the best round before the rounds count as
// stalled: the pair count falls unevenly (planes of neighbouring pairs disagree for a few
// rounds), and on the one-layer Gmsh balls plateaus of up to 6 rounds end resolved.
constexpr std::size_t kStallRounds = 20;
// A vertex is pulled kOvershoot times the way to its half-spaces: the elastic step moves a
// contact vertex only part of its pull (elastic_step.h), and the overshoot makes up for it
// (the step limit cuts where it would break R2 or R4). Measured on the one-layer Gmsh balls
// (both free / A fixed): at kAnchor 0.2, overshoot 1: 23 / 22 rounds; 1.5: 16 rounds / stalled;
// 2: 11 rounds / stalled (it overshoots the pair's plane and chatters); at kAnchor 0.1 (the
// value used), 1.5: 22 / 18 rounds.
constexpr double kOvershoot = 1.5;

// A half-space n.x >= b that a vertex must reach (n of unit length).
struct HalfSpace {
  Vec3d n{};
  double b = 0;
};
struct VertexTarget {
  std::size_t vertex = 0;
  HalfSpace h;
};

// The gap between the two sides of a pair's plane, relative to the pair's longest edge: far above
// the rounding of the moved coordinates, small against the element (its cost per pair is at most
// (1e-3 h)^2, a millionth of an element layer's).
constexpr double kPlaneGap = 1e-3;

// The local step of one pair: its separating plane u.x = c from the variant's solution (the plane
// midway between q1_A and q1_B along the solution's normal u, A -> B), opened by the gap and
// shifted past the fixed vertices of either side, and a half-space for each free vertex on the
// wrong side (A's: u.x <= c - gap/2, B's: u.x >= c + gap/2). Returns the variant's squared depth.
double pair_targets(const Side& sa, std::size_t ea, const Side& sb, std::size_t eb, ResolveVariant variant,
                    std::vector<VertexTarget>& out_a, std::vector<VertexTarget>& out_b) {
  const TetVertices A = element(sa.cur, ea), B = element(sb.cur, eb);
  const PairMove m = solve_move(A, B, variant);
  if (!m.ok) return 0;
  double a_hi = -HUGE_VAL, b_lo = HUGE_VAL, edge = 0, fixed_a = -HUGE_VAL, fixed_b = HUGE_VAL;
  for (int i = 0; i < 4; ++i) {
    a_hi = std::max(a_hi, dot(m.u, A[i]) + dot(m.u, m.da[i]));
    b_lo = std::min(b_lo, dot(m.u, B[i]) + dot(m.u, m.db[i]));
    if (sa.fixed[sa.rest->tets[ea][i]]) fixed_a = std::max(fixed_a, dot(m.u, A[i]));
    if (sb.fixed[sb.rest->tets[eb][i]]) fixed_b = std::min(fixed_b, dot(m.u, B[i]));
  }
  for (const auto& e : kEdges)
    edge = std::max({edge, dot(sub(A[e[1]], A[e[0]]), sub(A[e[1]], A[e[0]])),
                     dot(sub(B[e[1]], B[e[0]]), sub(B[e[1]], B[e[0]]))});
  const double gap = kPlaneGap * std::sqrt(edge);
  double lo = (a_hi + b_lo) / 2 - gap / 2, hi = lo + gap;
  if (fixed_a > lo) hi += fixed_a - lo, lo = fixed_a;  // A's fixed vertices stay: B takes it all
  if (fixed_b < hi) lo -= hi - fixed_b, hi = fixed_b;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t va = sa.rest->tets[ea][i], vb = sb.rest->tets[eb][i];
    if (!sa.fixed[va] && dot(m.u, A[i]) > lo) out_a.push_back({va, {scaled(m.u, -1), -lo}});
    if (!sb.fixed[vb] && dot(m.u, B[i]) < hi) out_b.push_back({vb, {m.u, hi}});
  }
  return m.value;
}

// y = x projected in turn onto every half-space it violates (one sweep).
Vec3d project(Vec3d y, const HalfSpace& h) {
  const double d = h.b - dot(h.n, y);
  if (d > 0) add_to(y, scaled(h.n, d));
  return y;
}

// The pulls y_v - x_v of one side from this round's targets and the half-spaces its vertices
// hold from earlier rounds (a vertex once in contact stays constrained by its latest plane).
std::vector<Vec3d> pulls(const Side& s, std::vector<VertexTarget>& targets, std::vector<std::optional<HalfSpace>>& held) {
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

// The elastic displacement decays away from the contacts but is nowhere zero; a vertex whose
// displacement is below this share of the largest one stays where it is (bit for bit, so its
// elements keep the state the last step limit accepted). It saves the step limit from checking
// every element of the mesh each round; the jump it leaves at the edge of the moved region, at
// most 1e-4 of the largest move, is inside elements the step limit checks.
constexpr double kNegligibleShare = 1e-4;

// The global step (elastic_step.h) and the step limit (move_side) of one side.
void elastic_move(Side& s, const detail::ElasticStep& elastic, const std::vector<Vec3d>& pull) {
  std::vector<Vec3d> delta;
  if (!elastic.solve(pull, delta)) return;
  double largest = 0;
  for (const Vec3d& d : delta)
    if (finite(d)) largest = std::max(largest, dot(d, d));
  const double negligible = kNegligibleShare * kNegligibleShare * largest;
  for (std::size_t v = 0; v < delta.size(); ++v)
    if (dot(delta[v], delta[v]) > negligible && finite(delta[v])) s.acc[v] = delta[v], s.weight[v] = 1;
  move_side(s, 1);  // the elastic step's own overshoot is in its pull (kOvershoot)
}

// The translation fallback (resolve.h): after the translation, steps back towards rest of
// gamma (from kFirstGamma, halved on every rejected step, down to kLastGamma) of every free
// vertex's way back, each followed by at most kDescendInner per-pair rounds; the separating
// distance is bisected to kBisection of its bracket.
constexpr double kFirstGamma = 0.5, kLastGamma = 1.0 / 64, kBisection = 1e-3;
constexpr std::size_t kDescendInner = 20;

// Returns true when it ends at a resolved state (R1 by
// the contact stage, R2 kept by the step limit); false, with the positions unchanged, when it
// does not apply (both meshes have fixed vertices, no separating translation found, or the
// translated rest pose flips an element by rounding).
template <class Rounds, class Stop>
bool descend(const Mesh& A, const Mesh& B, Side& sa, Side& sb, std::size_t budget, const detail::RoundRule& rule,
             ResolveReport& rep, const Rounds& run_rounds, const Stop& stop) {
  const bool fixed_a = std::find(sa.fixed.begin(), sa.fixed.end(), 1) != sa.fixed.end();
  const bool fixed_b = std::find(sb.fixed.begin(), sb.fixed.end(), 1) != sb.fixed.end();
  if (fixed_a && fixed_b) return false;
  const double share_a = fixed_a ? 0 : fixed_b ? -1 : -0.5, share_b = fixed_b ? 0 : fixed_a ? 1 : 0.5;
  auto centroid = [](const Mesh& m, Vec3d& lo, Vec3d& hi) {
    Vec3d c = {0, 0, 0};
    std::size_t n = 0;
    for (const Vec3d& v : m.vertices)
      if (finite(v)) {
        add_to(c, v);
        ++n;
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
      }
    return n ? scaled(c, 1.0 / double(n)) : c;
  };
  Vec3d lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  const Vec3d ca = centroid(A, lo, hi), cb = centroid(B, lo, hi);
  const Vec3d u = unit(sub(cb, ca)).value_or(Vec3d{1, 0, 0});
  const std::vector<Vec3d> keep_a = sa.cur.vertices, keep_b = sb.cur.vertices;
  auto place = [&](double t) {
    for (std::size_t v = 0; v < A.vertices.size(); ++v)
      sa.cur.vertices[v] = sa.fixed[v] ? A.vertices[v] : Vec3d{A.vertices[v][0] + share_a * t * u[0],
                                                                A.vertices[v][1] + share_a * t * u[1],
                                                                A.vertices[v][2] + share_a * t * u[2]};
    for (std::size_t v = 0; v < B.vertices.size(); ++v)
      sb.cur.vertices[v] = sb.fixed[v] ? B.vertices[v] : Vec3d{B.vertices[v][0] + share_b * t * u[0],
                                                                B.vertices[v][1] + share_b * t * u[1],
                                                                B.vertices[v][2] + share_b * t * u[2]};
  };
  auto separated = [&] {
    stop();
    const auto t0 = Clock::now();
    const bool ok = detail::intersecting_pairs(sa.cur, sa.elems, &sb.cur, sb.elems).empty();
    rep.seconds_contacts += since(t0);
    return ok;
  };
  auto valid = [&](const Side& s) {
    for (std::size_t e : s.elems) {
      const TetVertices q = element(s.cur, e);
      if (detail::orientation(q[0], q[1], q[2], q[3]) != s.sign[e]) return false;
    }
    return true;
  };
  auto restore = [&] {
    sa.cur.vertices = keep_a;
    sb.cur.vertices = keep_b;
  };
  double t_hi = 0;
  for (int k = 0; k < 3; ++k) t_hi += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  t_hi = 2 * std::sqrt(t_hi);  // more than the extent of both meshes along any line
  place(t_hi);
  if (!(t_hi > 0) || !separated()) return restore(), false;
  double t_lo = 0;
  while (t_hi - t_lo > kBisection * t_hi) {
    const double mid = (t_lo + t_hi) / 2;
    place(mid);
    (separated() ? t_hi : t_lo) = mid;
  }
  place(t_hi);
  if (!valid(sa) || !valid(sb)) return restore(), false;
  double cost = side_cost(sa) + side_cost(sb);
  double gamma = kFirstGamma;
  std::size_t used = 0;
  while (used < budget && gamma >= kLastGamma) {
    stop();
    const std::vector<Vec3d> save_a = sa.cur.vertices, save_b = sb.cur.vertices;
    for (Side* s : {&sa, &sb})
      for (std::size_t v = 0; v < s->cur.vertices.size(); ++v)
        if (!s->fixed[v]) {
          const Vec3d d = scaled(sub(s->rest->vertices[v], s->cur.vertices[v]), gamma);
          if (finite(d) && dot(d, d) > 0) s->acc[v] = d, s->weight[v] = 1;
        }
    const auto t0 = Clock::now();
    move_side(sa, 1);
    move_side(sb, 1);
    rep.seconds_move += since(t0);
    const std::size_t before = rep.rounds.size();
    const bool ok = run_rounds(std::min(kDescendInner, budget - used), rule, false, rep.variant);
    used += rep.rounds.size() - before + 1;
    const double c = side_cost(sa) + side_cost(sb);
    if (ok && c < cost) {
      cost = c;
    } else {
      sa.cur.vertices = save_a;
      sb.cur.vertices = save_b;
      gamma /= 2;
    }
  }
  return true;
}

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

}  // namespace

namespace detail {

// resolve_tuned's body fallback (self-contact): at the rest pose, the intersecting pairs must
// all join two different bodies, and each body may touch at most one other (then the body pairs
// are independent: resolving one moves no body of another). Each contacting pair of bodies is cut
// out as two meshes (its vertices, elements and fixed flags) and resolved from rest as A x B, and
// its positions written back; every other body stays at rest. True when every body pair ended
// resolved (the caller's exact verdict on the whole mesh judges the result); false, positions
// unchanged, otherwise.
bool resolve_bodies(const Mesh& A, Side& sa, const ResolveOptions& o, ResolveReport& rep) {
  const auto [body, count] = bodies(A, sa.elems);
  if (count < 2) return false;
  const auto pairs = intersecting_pairs(A, sa.elems, nullptr, {});
  std::vector<std::ptrdiff_t> partner(count, -1);
  for (const auto& p : pairs) {
    const std::ptrdiff_t i = body[A.tets[p[0]][0]], j = body[A.tets[p[1]][0]];
    if (i == j) return false;  // a body against itself
    for (auto [x, y] : {std::pair{i, j}, std::pair{j, i}}) {
      if (partner[std::size_t(x)] >= 0 && partner[std::size_t(x)] != y) return false;  // three bodies meet
      partner[std::size_t(x)] = y;
    }
  }
  std::vector<Vec3d> result = A.vertices;
  for (std::size_t i = 0; i < count; ++i) {
    const std::ptrdiff_t j = partner[i];
    if (j < std::ptrdiff_t(i)) continue;  // no partner, or done as (j, i)
    // Body k as a mesh of its own: `index` maps its vertices to A's.
    const auto cut = [&](std::size_t k, std::vector<std::size_t>& index, std::vector<char>& fixed) {
      Mesh m;
      std::vector<std::size_t> local(A.vertices.size(), SIZE_MAX);
      for (std::size_t v = 0; v < A.vertices.size(); ++v)
        if (body[v] == std::ptrdiff_t(k)) local[v] = index.size(), index.push_back(v), m.vertices.push_back(A.vertices[v]),
                                           fixed.push_back(sa.fixed[v]);
      for (std::size_t e : sa.elems)
        if (body[A.tets[e][0]] == std::ptrdiff_t(k))
          m.tets.push_back({local[A.tets[e][0]], local[A.tets[e][1]], local[A.tets[e][2]], local[A.tets[e][3]]});
      return m;
    };
    std::vector<std::size_t> index_a, index_b;
    ResolveOptions sub = o;
    sub.fix_a = sub.fix_b = false;
    sub.fixed_vertices_a.clear();
    sub.fixed_vertices_b.clear();
    const Mesh ma = cut(i, index_a, sub.fixed_vertices_a), mb = cut(std::size_t(j), index_b, sub.fixed_vertices_b);
    sub.max_rounds = std::max<std::size_t>(1, o.max_rounds - std::min(o.max_rounds - 1, rep.rounds.size()));
    const std::size_t before = rep.rounds.size();
    sub.progress = [&](const ResolveRound& r) {
      ResolveRound q = r;
      q.round = before + r.round;
      if (o.progress) o.progress(q);
    };
    const Resolution r = resolve_tuned(ma, &mb, sub);
    for (ResolveRound q : r.report.rounds) q.round += before, rep.rounds.push_back(q);
    rep.seconds_contacts += r.report.seconds_contacts;
    rep.seconds_solve += r.report.seconds_solve;
    rep.seconds_move += r.report.seconds_move + r.report.seconds_verify;
    if (!r.report.resolved) return false;
    for (std::size_t v = 0; v < index_a.size(); ++v) result[index_a[v]] = r.a[v];
    for (std::size_t v = 0; v < index_b.size(); ++v) result[index_b[v]] = r.b[v];
  }
  sa.cur.vertices = result;
  return true;
}

RoundRule round_rule(ResolveVariant variant) {
  if (variant == ResolveVariant::Rigid) return {1.5, false, 0};
  return {1.2, true, 2};
}

// The per-pair rounds' stall rule (as kStallRounds for the projective-dynamics rounds).
constexpr std::size_t kPairStallRounds = 10;

Resolution resolve_tuned(const Mesh& A, const Mesh* B, const ResolveOptions& o) {
  const RoundRule rule = round_rule(o.variant);
  const auto t_all = Clock::now();
  if (B && o.fix_a && o.fix_b) throw std::invalid_argument("resolve: fix_a and fix_b are both set; at most one mesh can be fixed");
  if (o.max_rounds < 1) throw std::invalid_argument("resolve: max_rounds must be at least 1");
  const auto stop_if_cancelled = [&] {
    if (o.cancel && o.cancel->load(std::memory_order_relaxed)) throw Cancelled();
  };
  Resolution out;
  ResolveReport& rep = out.report;
  rep.variant = o.variant;
  Side sa, sb;
  detail::check_limits(o);
  init_side(sa, A, 'A', o.fix_a, o.fixed_vertices_a, rep.skipped);
  if (B) init_side(sb, *B, 'B', o.fix_b, o.fixed_vertices_b, rep.skipped);
  sa.limits = sb.limits = o;
  Side& sB = B ? sb : sa;  // the side of a pair's second element

  // Projective-dynamics rounds (resolve.h) from the current positions, at most `budget`; true
  // when a contact stage found no pair; false when they stall (kStallRounds rounds without fewer
  // pairs than the best round) or the budget ends.
  std::optional<detail::ElasticStep> elastic_a, elastic_b;
  const auto run_pd_rounds = [&](std::size_t budget) {
    auto t = Clock::now();
    if (!elastic_a) elastic_a.emplace(A, sa.elems, sa.fixed);
    if (B && !elastic_b) elastic_b.emplace(*B, sb.elems, sb.fixed);
    rep.seconds_solve += since(t);
    std::vector<std::optional<HalfSpace>> held_a(A.vertices.size()), held_b(B ? B->vertices.size() : 0);
    std::size_t best = SIZE_MAX, best_round = 0;
    for (std::size_t r = 0; r < budget; ++r) {
      stop_if_cancelled();
      const auto t_round = Clock::now();
      t = Clock::now();
      const std::vector<std::array<std::size_t, 2>> pairs =
          intersecting_pairs(sa.cur, sa.elems, B ? &sb.cur : nullptr, sb.elems);
      rep.seconds_contacts += since(t);
      if (pairs.empty()) return true;
      if (pairs.size() < best) best = pairs.size(), best_round = r;
      if (r >= best_round + kStallRounds) return false;
      stop_if_cancelled();
      t = Clock::now();
      std::vector<std::vector<VertexTarget>> ta(pairs.size()), tb(pairs.size());
      std::vector<double> value(pairs.size(), 0);
      tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
        if (o.cancel && o.cancel->load(std::memory_order_relaxed)) return;
        value[k] = pair_targets(sa, pairs[k][0], sB, pairs[k][1], o.variant, ta[k], tb[k]);
      });
      stop_if_cancelled();
      if (std::none_of(value.begin(), value.end(), [](double x) { return x > 0; })) {
        rep.stopped_because = "none of the " + std::to_string(pairs.size()) +
                              " intersecting pairs has a finite per-pair solution (coordinates too large to square in doubles?)";
        return false;
      }
      std::vector<VertexTarget> targets_a, targets_b;
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        targets_a.insert(targets_a.end(), ta[k].begin(), ta[k].end());
        (B ? targets_b : targets_a).insert((B ? targets_b : targets_a).end(), tb[k].begin(), tb[k].end());
      }
      const std::vector<Vec3d> pull_a = pulls(sa, targets_a, held_a);
      const std::vector<Vec3d> pull_b = B ? pulls(sb, targets_b, held_b) : std::vector<Vec3d>{};
      rep.seconds_solve += since(t);
      t = Clock::now();
      elastic_move(sa, *elastic_a, pull_a);
      stop_if_cancelled();
      if (B) elastic_move(sb, *elastic_b, pull_b);
      rep.seconds_move += since(t);
      ResolveRound rr;
      rr.round = rep.rounds.size() + 1;
      rr.pairs = pairs.size();
      rr.max_pd2 = *std::max_element(value.begin(), value.end());
      rr.cost = side_cost(sa) + (B ? side_cost(sb) : 0);
      rr.seconds = since(t_round);
      rep.rounds.push_back(rr);
      if (o.progress) o.progress(rr);
    }
    return false;
  };

  // Rounds (resolve.h, steps 1-4) from the current positions, at most `budget`; true when a
  // contact stage found no pair.
  const auto run_rounds = [&](std::size_t budget, const RoundRule& rule, bool stall_exit,
                              ResolveVariant variant) {
    std::vector<std::array<std::size_t, 2>> last_pairs;
    std::size_t first_pairs = 0, best_pairs = 0, best_round = 0;
    std::vector<int> last_age;
    for (std::size_t r = 0; r < budget; ++r) {
      const std::size_t round = rep.rounds.size() + 1;
      stop_if_cancelled();
      const auto t_round = Clock::now();
      auto t = Clock::now();
      std::vector<std::array<std::size_t, 2>> pairs =
          intersecting_pairs(sa.cur, sa.elems, B ? &sb.cur : nullptr, sb.elems);
      rep.seconds_contacts += since(t);
      if (pairs.empty()) return true;
      // Stalled: after kPairStallRounds rounds still half of the first round's pairs, or
      // kPairStallRounds rounds without fewer pairs than before.
      if (r == 0) first_pairs = best_pairs = pairs.size();
      if (pairs.size() < best_pairs) best_pairs = pairs.size(), best_round = r;
      if (stall_exit && ((r >= kPairStallRounds && 2 * pairs.size() >= first_pairs) || r >= best_round + kPairStallRounds))
        return false;
      stop_if_cancelled();

      t = Clock::now();
      // Consecutive rounds each pair has been found in (RoundRule::rigid_after).
      std::vector<int> age(pairs.size(), 1);
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        const auto it = std::lower_bound(last_pairs.begin(), last_pairs.end(), pairs[k]);
        if (it != last_pairs.end() && *it == pairs[k]) age[k] = last_age[std::size_t(it - last_pairs.begin())] + 1;
      }
      std::vector<PairMove> moves(pairs.size());
      tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
        const TetVertices Ta = element(sa.cur, pairs[k][0]), Tb = element(sB.cur, pairs[k][1]);
        const bool rigid = rule.rigid_after > 0 && age[k] > rule.rigid_after;
        PairMove m = solve_move(Ta, Tb, rigid ? ResolveVariant::Rigid : variant);
        if (m.ok)
          finish_move(m, fixed_of(sa, pairs[k][0]), fixed_of(sB, pairs[k][1]), Ta, Tb);
        moves[k] = m;
      });
      rep.seconds_solve += since(t);
      last_pairs = pairs;
      last_age = age;
      stop_if_cancelled();

      t = Clock::now();
      ResolveRound rr;
      rr.round = round;
      rr.pairs = pairs.size();
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        if (!moves[k].ok) continue;
        rr.max_pd2 = std::max(rr.max_pd2, moves[k].value);
        accumulate(sa, pairs[k][0], moves[k].da, rule.longest);
        accumulate(sB, pairs[k][1], moves[k].db, rule.longest);
      }
      move_side(sa, rule.overshoot);
      if (B) move_side(sb, rule.overshoot);
      rep.seconds_move += since(t);
      rr.cost = side_cost(sa) + (B ? side_cost(sb) : 0);
      rr.seconds = since(t_round);
      rep.rounds.push_back(rr);
      if (o.progress) o.progress(rr);
    }
    return false;
  };

  // Deep overlaps (the translation fallback): when the rounds did not clear the contacts,
  // start again from a separated configuration and walk back towards the rest pose.
  const std::size_t first_budget = std::max<std::size_t>(1, o.max_rounds / 2);
  const auto all_fixed = [](const Side& s) { return std::find(s.fixed.begin(), s.fixed.end(), 0) == s.fixed.end(); };
  if (all_fixed(sa) && (!B || all_fixed(sb))) rep.stopped_because = "every vertex is fixed: nothing can move";
  bool clear = rep.stopped_because.empty() && run_pd_rounds(first_budget);
  if (clear) rep.method = ResolveMethod::Rounds;
  const auto go_on = [&] { return !clear && rep.stopped_because.empty(); };
  // Bodies: two bodies of one mesh in contact are resolved as two meshes (every fallback of
  // A x B, the translation included), each contacting body pair on its own.
  if (go_on() && !B && o.max_rounds > rep.rounds.size()) {
    stop_if_cancelled();
    if (resolve_bodies(A, sa, o, rep)) clear = true, rep.method = ResolveMethod::Bodies;
  }
  // Stalled: the per-pair rounds from the rest pose, within what is left of the first budget.
  if (go_on() && first_budget > rep.rounds.size()) {
    sa.cur.vertices = A.vertices;
    if (B) sb.cur.vertices = B->vertices;
    clear = run_rounds(first_budget - rep.rounds.size(), rule, true, o.variant);
    if (clear) rep.method = ResolveMethod::Rounds;
  }
  if (go_on() && B && o.max_rounds > rep.rounds.size()) {
    clear = descend(A, *B, sa, sb, o.max_rounds - rep.rounds.size(), rule, rep, run_rounds, stop_if_cancelled);
    if (clear) rep.method = ResolveMethod::Translation;
  }
  // descend declined (both meshes with fixed vertices, or no usable translation; it leaves the
  // positions as they were): the rounds go on from there up to max_rounds, without the stall exit.
  if (go_on() && B && o.max_rounds > rep.rounds.size()) {
    clear = run_rounds(o.max_rounds - rep.rounds.size(), rule, false, o.variant);
    if (clear) rep.method = ResolveMethod::Rounds;
  }
  // Self-contact has no separated start: stalled deformable rounds restart from the rest pose
  // with the rigid variant's rounds (which move elements as a whole and do not squeeze them).
  if (go_on() && !B && o.variant != ResolveVariant::Rigid && o.max_rounds > rep.rounds.size()) {
    sa.cur.vertices = A.vertices;
    clear = run_rounds(o.max_rounds - rep.rounds.size(), round_rule(ResolveVariant::Rigid), false,
                       ResolveVariant::Rigid);
    if (clear) rep.method = ResolveMethod::RigidRounds;
  }
  stop_if_cancelled();

  auto t = Clock::now();
  ResolveReport v = check_resolution(A, sa.cur.vertices, B, B ? sb.cur.vertices : std::vector<Vec3d>{}, sa.fixed,
                                     B ? sb.fixed : std::vector<char>{}, o);
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
  rep.cost_a = side_cost(sa);
  rep.cost_b = B ? side_cost(sb) : 0;
  rep.cost = rep.cost_a + rep.cost_b;
  // The rounds table ends with the state written: when a fallback undid its last rounds (the
  // last row's cost is not the cost written), a closing row gives that state's intersecting
  // pairs (0 when resolved) and cost, with max_pd2 0 and the verdict's time.
  if (!rep.rounds.empty() && rep.rounds.back().cost != rep.cost) {
    ResolveRound last;
    last.round = rep.rounds.size() + 1;
    last.pairs = rep.remaining_pairs.size();
    last.cost = rep.cost;
    last.seconds = rep.seconds_verify;
    rep.rounds.push_back(last);
  }
  auto max_disp = [](const Mesh& m0, const std::vector<Vec3d>& p) {
    double d = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3d x = sub(p[i], m0.vertices[i]);
      if (finite(x)) d = std::max(d, std::sqrt(dot(x, x)));
    }
    return d;
  };
  rep.max_displacement = max_disp(A, sa.cur.vertices);
  if (B) rep.max_displacement = std::max(rep.max_displacement, max_disp(*B, sb.cur.vertices));
  out.a = std::move(sa.cur.vertices);
  if (B) out.b = std::move(sb.cur.vertices);
  rep.seconds_total = since(t_all);
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
  return detail::resolve_tuned(A, &B, options);
}

Resolution resolve_self(const Mesh& A, const ResolveOptions& options) {
  return detail::resolve_tuned(A, nullptr, options);
}

}  // namespace pdd::mesh
