// local_step.cpp — the per-pair projection of a round (local_step.h).
#include "local_step.h"

#include <algorithm>
#include <cmath>

#include "geometry.h"
#include "pdd/global_minimiser.h"

namespace pdd::mesh::detail {
namespace {

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
  if (n[0] != 0 || n[1] != 0 || n[2] != 0) return n;  // (not n.n > 0: ~L^4, it underflows)
  const Vec3d w = sub(B[kEdges[l.b][0]], A[kEdges[l.a][0]]);  // parallel edges
  return sub(w, scaled(e, dot(w, e) / dot(e, e)));
}

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

// The gap between the two sides of a pair's plane, relative to the pair's longest edge: far above
// the rounding of the moved coordinates, small against the element (its cost per pair is at most
// (1e-3 h)^2, a millionth of an element layer's). It lets the rounds finish: the elastic step
// moves a contact vertex short of its target and a pair separated to the plane alone would meet
// again (a gap proportional to each pair's own overlap: boxes 0.1 deep 15 -> 29 rounds, a ball
// among slivers 14 -> 194). Capped by the run's depth scale (the largest overlap met): a contact
// far shallower than the elements (plates pressed 1e-5 into each other, cells of 0.1) is then
// moved by about its depth, not by 1e-3 h (measured 43x the depth, its cost 1,700x the rigid
// push's).
constexpr double kPlaneGap = 1e-3;

// The per-pair rounds' gap mu between a pair's two sides: kMargin of its longest edge plus
// kMarginUlp of its largest |coordinate|: far above the rounding of the moved coordinates
// (2^-52 |x|), and so small against the element that its cost, at most mu^2 per pair and
// mesh, is below 1e-12 of an element layer's.
constexpr double kMargin = 1e-6;
constexpr double kMarginUlp = 1e-12;

// A contact far shallower than the pair's extent E (rigid_pd2 below 1e-24 E^2: a depth below
// 1e-12 of it, as contacts made by rounding are, ~1e-17) is moved along pdd2's plane, as one whose
// pdd2_global is declined: pdd2_global <= pdd2 <= rigid_pd2 / 2 (definitions §5, §9) is then below
// 1e-24 E^2, where a normal rounded to doubles moves the plane by ~1e-16 E, 1e4 times the depth,
// so the fast engine searches exact pieces (~25 ms a pair) and nearly always declines it; and the
// move is the plane gap (kPlaneGap) either way. rigid_pd2 (certified, under a microsecond) tells.
double extent2(const TetVertices& A, const TetVertices& B) {
  double E2 = 0;
  for (const TetVertices* T : {&A, &B})
    for (const Vec3d& x : *T) E2 = std::max(E2, dot(sub(x, A[0]), sub(x, A[0])));
  return E2;
}
bool shallower_than_doubles(const TetVertices& A, const TetVertices& B) {
  const fast::Depth d = fast::rigid_pd2(A, B);
  return d.status == fast::DepthStatus::Ok && d.pd2 < 1e-24 * extent2(A, B);
}

// The global variant's move where it needs no more than pdd2_global: fast::global_minimiser, the
// same bits as solve_pair's pdd2_global fields (global_minimiser.h), without solve_pair's other
// values (rigid_pd2, pdd2_static, pdd2, pdd2_accel1, computed there to keep the record's
// relations) or shallower_than_doubles' rigid_pd2. Taken only where the record's way
// (solve_move_by_record) would take those same fields: a certified value (not bounded, not a
// witness) whose positions make a move, on a pair not shallower than doubles. The last needs
// no rigid_pd2: with g the reported value and G, PD^2 the exact ones, g <= (1 + 1e-9) G,
// G <= PD^2 / 2 (the comment above) and the reported rigid r >= (1 - 1e-9) PD^2, so
// r >= 2 (1 - 1e-9) / (1 + 1e-9) g > g (1 - 4e-9) (computed: one more rounding, far inside);
// g (1 - 4e-9) >= 1e-24 E^2 gives r >= 1e-24 E^2. (The record's other values lie between
// pdd2_global and rigid_pd2, in range with them: it has no error there.) About a third fewer
// instructions a pair solve than the record's way on stacked blocks, aligned (whose rigid_pd2
// takes the candidate set's exact path) or not.
// `shallow`: the minimiser bounded the pair (a depth below about 1e-10 of its size,
// global_minimiser.h) or found only a witness. Such a pair moves along pdd2's plane, as one
// shallower than doubles does (solve_move): certifying its pdd2_global takes the shallow
// certificate, the lone pairs' or the exact pieces (measured: 242 us a pair on the 2,278 such
// pairs of a round of 14,641, a grid of 24 tetrahedra a cube against its copy moved half a
// cell in x and y, 80% of the run), and its move is the plane gap, far above its depth, either
// way.
std::optional<PairMove> global_move(const TetVertices& A, const TetVertices& B, bool& shallow) {
  fast::MinimiserOptions options;
  options.bound_shallow = true;
  const std::optional<fast::GlobalMinimiser> g = fast::global_minimiser(A, B, options);
  shallow = g && (g->bounded || g->witness);
  if (!g || shallow || !(g->pd2 * (1 - 4e-9) >= 1e-24 * extent2(A, B))) return std::nullopt;
  PairMove m = from_positions(g->q1_A, g->q1_B, A, B, g->pd2, g->normal);
  if (!m.ok) return std::nullopt;
  return m;
}

// pdd2's normal (A -> B): its label's axis (definitions §3), along which every displacement of
// q1_A, q1_B lies. Oriented by the displacements (B's forward, A's backward) where their sums
// stand clear of the coordinates' rounding (2^-40 of the largest |coordinate|), else by the
// smaller clearance (a contact made by rounding: displacements ~1e-17 of the pair, below the
// rounding of q1, whose differences point anywhere; taken as the normal they sheared stacked
// blocks half a cell sideways). Nothing (the direction of the displacements' sums, from_positions)
// without a label or a non-zero axis.
std::optional<std::array<double, 3>> pdd2_normal(const PairResult<double>& r, const TetVertices& A,
                                                 const TetVertices& B) {
  if (!r.pdd2_dir) return std::nullopt;
  const std::optional<Vec3d> u = unit(label_axis(*r.pdd2_dir, A, B));
  if (!u) return std::nullopt;
  Vec3d s = {0, 0, 0};
  double coord = 0;
  for (int i = 0; i < 4; ++i) {
    add_to(s, sub(r.q1_B[i], B[i]));
    add_to(s, sub(A[i], r.q1_A[i]));
    for (int k = 0; k < 3; ++k) coord = std::max({coord, std::fabs(A[i][k]), std::fabs(B[i][k])});
  }
  const Vec3d v = scaled(*u, -1);
  const bool forward = std::sqrt(dot(s, s)) > 0x1p-40 * coord ? dot(s, *u) >= 0
                                                              : clearance(*u, A, B) <= clearance(v, A, B);
  const Vec3d n = forward ? *u : v;
  return std::array<double, 3>{n[0], n[1], n[2]};
}

// The record's way (solve_move_by_record); `without_global`: pdd2's plane whatever the variant
// (solve_move's shallow pairs).
PairMove record_move(const TetVertices& A, const TetVertices& B, ResolveVariant variant, bool without_global) {
  if (variant == ResolveVariant::Rigid) return rigid_move(A, B);
  fast::SolveOptions options;
  options.values = kPdd2;  // its positions (and definitions §9's with `global`): no other value
  options.with_global = variant == ResolveVariant::Global && !without_global && !shallower_than_doubles(A, B);
  const PairResult<double> r = fast::solve_pair(TetPair{"", {}, A, B}, options);
  const bool global = options.with_global;
  if (!r.error) {
    if (global && !r.pdd2_global_error && r.pdd2_global_normal) {
      PairMove m = from_positions(r.q1_A_global, r.q1_B_global, A, B, r.pdd2_global, r.pdd2_global_normal);
      if (m.ok) return m;
    }
    PairMove m = from_positions(r.q1_A, r.q1_B, A, B, r.pdd2, pdd2_normal(r, A, B));  // pdd2's positions
    if (m.ok) return m;
  }
  return rigid_move(A, B);
}

}  // namespace

PairMove solve_move(const TetVertices& A, const TetVertices& B, ResolveVariant variant) {
  bool shallow = false;
  if (variant == ResolveVariant::Global)
    if (std::optional<PairMove> m = global_move(A, B, shallow)) return *m;
  return record_move(A, B, variant, shallow);
}

PairMove solve_move_by_record(const TetVertices& A, const TetVertices& B, ResolveVariant variant) {
  return record_move(A, B, variant, false);
}

double overlap_along(const TetVertices& A, const TetVertices& B, const Vec3d& u) {
  double a_hi = -HUGE_VAL, b_lo = HUGE_VAL;
  for (int i = 0; i < 4; ++i) a_hi = std::max(a_hi, dot(u, A[i])), b_lo = std::min(b_lo, dot(u, B[i]));
  return a_hi - b_lo;
}

double plane_targets(const Side& sa, std::size_t ea, const Side& sb, std::size_t eb, const PairMove& m,
                     const Vec3d* along, double depth_scale, std::vector<VertexTarget>& out_a,
                     std::vector<VertexTarget>& out_b) {
  const TetVertices A = element(sa.cur, ea), B = element(sb.cur, eb);
  const Vec3d u = along ? *along : m.u;
  double a_hi = -HUGE_VAL, b_lo = HUGE_VAL, fixed_a = -HUGE_VAL, fixed_b = HUGE_VAL, coord = 0;
  for (int i = 0; i < 4; ++i) {
    a_hi = std::max(a_hi, dot(u, A[i]) + (along ? 0.0 : dot(u, m.da[i])));
    b_lo = std::min(b_lo, dot(u, B[i]) + (along ? 0.0 : dot(u, m.db[i])));
    if (sa.is_fixed(sa.rest->tets[ea][i])) fixed_a = std::max(fixed_a, dot(u, A[i]));
    if (sb.is_fixed(sb.rest->tets[eb][i])) fixed_b = std::min(fixed_b, dot(u, B[i]));
    for (int k = 0; k < 3; ++k) coord = std::max({coord, std::abs(A[i][k]), std::abs(B[i][k])});
  }
  const double edge = std::sqrt(longest_edge2(A, B));
  const double gap = std::max(std::min(kPlaneGap * edge, depth_scale), kMargin * edge + kMarginUlp * coord);
  double lo = (a_hi + b_lo) / 2 - gap / 2, hi = lo + gap;
  if (fixed_a > lo) hi += fixed_a - lo, lo = fixed_a;  // A's fixed vertices stay: B takes it all
  if (fixed_b < hi) lo -= hi - fixed_b, hi = fixed_b;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t va = sa.rest->tets[ea][i], vb = sb.rest->tets[eb][i];
    if (!sa.is_fixed(va) && dot(u, A[i]) > lo) out_a.push_back({va, {scaled(u, -1), -lo}});
    if (!sb.is_fixed(vb) && dot(u, B[i]) < hi) out_b.push_back({vb, {u, hi}});
  }
  return m.value;
}

void finish_move(PairMove& m, const Side& sa, std::size_t ea, const Side& sb, std::size_t eb,
                 const TetVertices& A, const TetVertices& B) {
  std::array<bool, 4> fixed_a, fixed_b;
  double retreat_a = 0, retreat_b = 0, coord = 0;
  for (int i = 0; i < 4; ++i) {
    fixed_a[i] = sa.is_fixed(sa.rest->tets[ea][i]);
    fixed_b[i] = sb.is_fixed(sb.rest->tets[eb][i]);
    if (fixed_a[i]) retreat_a = std::max(retreat_a, -dot(m.da[i], m.u));
    if (fixed_b[i]) retreat_b = std::max(retreat_b, dot(m.db[i], m.u));
    for (int k = 0; k < 3; ++k) coord = std::max({coord, std::abs(A[i][k]), std::abs(B[i][k])});
  }
  const double mu = kMargin * std::sqrt(longest_edge2(A, B)) + kMarginUlp * coord;
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

}  // namespace pdd::mesh::detail
