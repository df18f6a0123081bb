// global_depth.cpp — the driver of global_depth (see global_depth.h for the method and its
// argument): the start's offer and one descent step, the pieces enumerated in doubles
// (piece_enumeration.h) or, where doubles cannot resolve the depth, certified without them
// (shallow_certificate.h, lone_pair_certificate.h) or else exactly; the winning
// offer chosen among near ties, its value certified (relaxed_value.h's bounds) or recomputed
// in rationals, and on the exact pieces the suspects settled (suspect_proof.h).
#include "global/global_depth.h"

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <vector>

#include "global/best_offer.h"
#include "global/eigen_polish.h"
#include "global/integer_normals.h"
#include "global/lone_pair_certificate.h"
#include "global/piece_enumeration.h"
#include "global/relaxed_value.h"
#include "global/shallow_certificate.h"
#include "global/suspect_proof.h"

namespace pdd::fast {
namespace {

using detail::kPopcount;
using global::add;
using global::cross;
using global::Best;
using global::certify_shallow;
using global::integer_normals;
using global::FacetBounds;
using global::LonePairResult;
using global::ShallowResult;
using global::dot;
using global::enumerate_pieces;
using global::evaluate_tight;
using global::Evaluation;
using global::kGlobalRel;
using global::kU;
using global::kUnrepresentedDepth;
using global::mul;
using global::near_extent_sq;
using global::nonzero;
using global::Problem;
using global::refine;
using global::relaxed_exact;
using global::Search;
using global::sub;
using global::represented;
using global::Representation;
using global::V3;

// One step from v towards a local minimum (double path, before the enumeration): v's active
// set S (its solution s, direction_qp.h: A's vertices at or above C + S_A, B's at or below
// C + S_B) has G = n^T H_S n on S's piece (enumerate_pieces' H_S, here from the centred
// vertices directly), and H_S's smallest eigenvector, oriented as v (two steps of inverse
// iteration from v), is where G would be least if the piece reached that far. It is only
// offered: an offer only ever lowers the best value,
// and a lower best prunes more pieces (the screen's and consider_piece's windows). Measured on
// the paper's pairs: 41 -> 30 pieces screened, 2.3 -> 1.4 to the eigensolver, ~0.3 us saved
// per pair (Eigen's solver in place of the inverse iteration: 0.1 us more); a second step
// costs more than it saves. Zero when S has an empty side.
V3 descent_step(const Problem& P, const V3& v, const DirectionSolution& s) {
  unsigned ma = 0, mb = 0;
  for (int i = 0; i < 4; ++i) {
    if (dot(v, P.relA[i]) >= s.c + s.sumA) ma |= 1u << i;
    if (dot(v, P.relB[i]) <= s.c + s.sumB) mb |= 1u << i;
  }
  if (!ma || !mb) return {0, 0, 0};
  const int mA = kPopcount[ma], mB = kPopcount[mb];
  const double wA = 1.0 / (5 - mA), wB = 1.0 / (5 - mB);
  // (each vertex added with weight 1 or 0, not under a test: the tests mispredicted; a term
  // weighted 0 is +0 or -0, which leaves a sum unchanged unless the sum is -0, and these sums
  // start at +0 and are never -0: a rounded sum is -0 only when both terms are)
  V3 SA{0, 0, 0}, SB{0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    SA = add(SA, mul(P.pA[i], double(ma >> i & 1u)));
    SB = add(SB, mul(P.pB[i], double(mb >> i & 1u)));
  }
  const V3 C = mul(add(mul(SA, wA), mul(SB, wB)), 1 / (mA * wA + mB * wB));
  const V3 TA = mul(sub(mul(C, mA), SA), wA);
  double H[3][3] = {};  // 20 H_S: the same eigenvectors
  auto add_outer = [&H](const V3& d, double w) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) H[r][c] += w * d[r] * d[c];
  };
  for (int i = 0; i < 4; ++i) {
    add_outer(sub(C, P.pA[i]), double(ma >> i & 1u));
    add_outer(sub(C, P.pB[i]), double(mb >> i & 1u));
  }
  add_outer(TA, 10 - mA - mB);
  // Its smallest eigenvector by inverse iteration from v (refine with shift 0: x <- adj(H) x,
  // H^-1 up to the determinant's factor, the projector onto the kernel when H is singular),
  // oriented as v: cheaper than an eigensolver, and v, the start, is usually near it.
  return refine(H, v, 0.0, 0);
}

constexpr double kCompactTiny = 1e-18;  // global_depth(): the compact pairs' exact-pieces depth
// Bounds (bound_shallow, face_bound) are returned only below kBoundedDepth scale^2 (a depth below
// ~1e-10 of the pair's size; a contact made by rounding's are ~1e-30): the positions returned
// move the vertices by an object norm below sqrt(upper), as the minimiser's do, so a gradient
// taken from them (-(d_i + sum d) / 10 per vertex, |d_i| <= sqrt(20 sigma)) is within ~5e-10 of
// the pair's scale of the minimiser's, in absolute terms.
constexpr double kBoundedDepth = 1e-20;

// One global_depth() call: the pair, the evaluations' problem, the offers and the bounds.
struct GlobalRun {
  GlobalRun(const TetVertices& A, const TetVertices& B) : A(A), B(B) {}
  const TetVertices& A;
  const TetVertices& B;
  Problem P;
  Best best;
  double lower = 0;          // every G(u) >= lower (the pair's units)
  double lower_scaled = 0;   // the exact path's floor in its units
  bool exact_pieces = false;  // the pieces were built exactly
  bool tiny_start = false;    // ... because the start's value is below their depth
  bool shallow_first = false;  // ... or to try the shallow certificate first (shallow_first())
  double tiny_rel = 0;         // the double pieces' floor, relative to scale^2 (needs_exact_pieces)
  GlobalOptimum shallow;      // report_shallow's result
};

// No start given (a caller whose candidate list could not be built: the pair has parallel
// edges or coplanar faces, the aligned pairs of structured meshes): the enumeration would
// prune nothing until its first offer and send every one of the 225 pieces to the eigensolver
// (measured on `pdd generate --family aligned`: all 225 kept, ~100 solved, 80 us a pair). So
// the pair's own candidate directions are ranked and the shallowest offered first: the 8 face
// normals and the 36 cross products of A's and B's edges (definitions §3's directions, from
// the rounded relative coordinates), each oriented A -> B by its rigid overlap D(d) = max_A d.a
// - min_B d.b (the smaller of d's and -d's), ranked by D(d)^2 / d.d. The rigid depth's
// direction is among them, and relaxed(u) >= D(u)^2 / 32 (global_depth.h), so the shallowest
// are where relaxed() is small. The ranking is only a heuristic: any double normal is a valid
// offer (its value is relaxed() along that very normal, with its own error bound, and an offer
// only lowers the best), so a rounded or misranked direction costs pruning, never accuracy.
// kGeometricStarts offers: about the start the callers with a list give (their rigid
// direction), for ~1/10 of the cost of offering all 44.
constexpr int kGeometricStarts = 3;

void offer_geometric_starts(GlobalRun& g) {
  const Problem& P = g.P;
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  V3 top[kGeometricStarts];
  double key[kGeometricStarts];
  int kept = 0;
  auto consider = [&](const V3& d) {
    const double dd = dot(d, d);
    if (!(dd > 0) || !std::isfinite(dd)) return;
    double maxA = -INFINITY, minA = INFINITY, maxB = -INFINITY, minB = INFINITY;
    for (int i = 0; i < 4; ++i) {
      const double a = dot(d, P.relA[i]), b = dot(d, P.relB[i]);
      maxA = std::max(maxA, a), minA = std::min(minA, a), maxB = std::max(maxB, b), minB = std::min(minB, b);
    }
    const double plus = maxA - minB, minus = maxB - minA;  // overlaps along d and along -d
    const double D = std::min(plus, minus);
    const double k = D * D / dd;
    if (!(k >= 0)) return;  // (NaN)
    if (kept == kGeometricStarts && !(k < key[kept - 1])) return;
    int at = kept < kGeometricStarts ? kept++ : kept - 1;
    for (; at > 0 && key[at - 1] > k; --at) top[at] = top[at - 1], key[at] = key[at - 1];
    top[at] = plus <= minus ? d : mul(d, -1.0), key[at] = k;
  };
  for (const V3* T : {P.relA, P.relB})
    for (const auto& f : kFace) consider(cross(sub(T[f[1]], T[f[0]]), sub(T[f[2]], T[f[0]])));
  for (const auto& ea : kEdge) {
    const V3 a = sub(P.relA[ea[1]], P.relA[ea[0]]);
    for (const auto& eb : kEdge) consider(cross(a, sub(P.relB[eb[1]], P.relB[eb[0]])));
  }
  for (int i = 0; i < kept; ++i) g.best.offer(P, top[i]);
}

// The problem (coordinates relative to A[0] and about the centroid), the lower bound, and the
// start's offer (or, with none, the pair's candidate directions).
void set_up(GlobalRun& g, const double start_normal[3], double rigid_pd2) {
  // G >= PD^2 / 32 (global_depth.h), with the given PD^2's 1e-8: a lower bound on every G(u).
  g.lower = std::isfinite(rigid_pd2) && rigid_pd2 > 0 ? rigid_pd2 * (1 - 1e-8) * kDeformableBoundCoeff : 0.0;
  Problem& P = g.P = global::problem_of(g.A, g.B);
  g.best.value = INFINITY;
  g.best.n = {start_normal[0], start_normal[1], start_normal[2]};
  if (nonzero(g.best.n)) g.best.offer(P, g.best.n);
  else offer_geometric_starts(g);
}

// The double pieces (the enumeration in doubles); true where they cannot certify the result and
// the pieces must be built exactly (then the double offers are dropped): a depth below
// tiny_rel scale^2 found, or a result above the start's certified value (the doubles could not
// evaluate even the start's normal: its components not accurate enough beside a far vertex), or
// an eigenpair the doubles could not resolve.
bool double_pieces_fail(GlobalRun& g, double start_value, double tiny_rel) {
  const Problem& P = g.P;
  Best& best = g.best;
  std::array<std::array<double, 3>, 4> dA, dB;
  for (int i = 0; i < 4; ++i) dA[i] = P.pA[i], dB[i] = P.pB[i];
  enumerate_pieces(dA, dB, Search{P, best, g.lower});
  if (!(best.value >= tiny_rel * P.scale * P.scale) || best.value > start_value * (1 + 1e-9) || best.needs_exact) {
    best.offers.clear();
    return true;
  }
  return false;
}

// Which route certifies a shallow pair sooner (measured: docs/performance.md, "Resting contacts:
// the route by their depth and their faces"). Below kShallowFirst scale^2 (a depth ~1e-8 of the
// size or less) with a face of A parallel to a face of B within kParallelFaces (sin^2 of their
// angle: blocks resting on each other, as structured meshes stack), the double pieces go to the
// double-word matrices for ~15 pieces whose eigenvalues lie within their error of zero
// (coplanar active vertices), ~25 us; the shallow certificate takes ~18 us. Without parallel
// faces the double pieces are the cheaper route (~8 us against ~12 us), so they stay first.
// Only the order of two certified routes depends on it: global_depth() runs the double pieces
// where the shallow certificate declines.
constexpr double kShallowFirst = 1e-16;
constexpr double kParallelFaces = 1e-16;
bool shallow_first(const GlobalRun& g) {
  const Problem& P = g.P;
  if (!(g.best.value < kShallowFirst * P.scale * P.scale)) return false;
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  V3 na[4], nb[4];
  for (int f = 0; f < 4; ++f) {
    const auto& t = kFace[f];
    na[f] = cross(sub(P.relA[t[1]], P.relA[t[0]]), sub(P.relA[t[2]], P.relA[t[0]]));
    nb[f] = cross(sub(P.relB[t[1]], P.relB[t[0]]), sub(P.relB[t[2]], P.relB[t[0]]));
  }
  for (const V3& a : na)
    for (const V3& b : nb) {
      const V3 c = cross(a, b);
      if (dot(c, c) <= kParallelFaces * dot(a, a) * dot(b, b)) return true;
    }
  return false;
}

// Doubles or rationals for the pieces (the enumeration is the same). The value along a
// computed eigenvector exceeds its stationary value by about E^2 / gap (E the error of H and of
// the solver): consider_piece's estimate 2 E^2 / gap <= 1e-11 mu is checked for every in-window
// eigenvalue, on H built in doubles (E ~2^-39 of the moments: passes down to mu ~1e-12 scale^2)
// and, where that fails, on H built to its own rounding (accurate_piece_matrix.h; E a few u |H|,
// the solver's part bounded from its residuals: down to mu ~1e-18 |H| where the gap is ~|H|);
// where it fails on both, the pair goes to the exact pieces. Two limits
// that estimate does not see: (1) a double normal represents the minimiser only to its own
// rounding, the value along the rounded eigenvector exceeding mu by ~|H| u^2, which is below
// 1e-12 of mu while mu >= 1e-18 |H| (further down, the exact path's suspects settle it:
// suspect_proof.h); (2) a far vertex (depth ~1e-11 scale^2 with a vertex 3e4 away) can put the
// minimiser on the wall of a steep piece, which only the exact path's wall offers reach (the
// fuzzer found a miss of 1.6e-8 there). So below 1e-10 scale^2 a pair with a far vertex is
// built exactly, with the wall offers, and its eigenvectors polished; a compact pair (the
// smaller tetrahedron's extent >= scale / 16: no vertex far from the others, so every piece's
// |H| <= 12 L^2 with centred |coordinates| L <= 2 scale, <= 48 scale^2: no steep piece, and
// |H| u^2 <= 6e-13 of a value >= kCompactTiny scale^2) keeps the doubles down to kCompactTiny
// = 1e-18 scale^2, a depth ~1e-9 of its size (the resting contacts of a simulation: ~1e-15
// scale^2 in examples/soft_body.py, ~7 ms a pair on the exact pieces).
// The double pieces also need the pair's own scale within [2^-100, 2^100] (solve_pair and
// pdd2_global pass pairs rescaled to it; an unscaled pair, spanning more of the double range
// than any rescaling can bring into it, arrives through the exact path): H ~ scale^2 and its
// determinant ~ scale^6 then neither overflow nor underflow. When the double enumeration
// finds a depth below that (1e-10 or, compact, 1e-18 scale^2), it is done again exactly.
// Returns whether global_depth() takes the branch of the exact pieces: the pieces must be built
// exactly (then the double offers are dropped), or shallow_first() prefers the shallow
// certificate (g.shallow_first: the double pieces follow there where it declines).
bool needs_exact_pieces(GlobalRun& g, double start_value) {
  const Problem& P = g.P;
  Best& best = g.best;
  const double tiny_rel = g.tiny_rel = near_extent_sq(g.A, g.B) >= P.scale * P.scale / 256 ? kCompactTiny : 1e-10;
  auto tiny = [&](double value) { return !(value >= tiny_rel * P.scale * P.scale); };
  if (!(P.scale >= 0x1p-100 && P.scale <= 0x1p100)) return true;
  if (tiny(best.value)) return g.tiny_start = true;
  if (nonzero(best.n) && std::isfinite(best.value)) best.offer(P, descent_step(P, best.n, best.last));
  // An offer only lowers the best, so a descent step already below the depth makes the
  // enumeration's result tiny too: the pieces are built exactly without it (a resting contact
  // ~1e-9 of its size deep, where the enumeration cost ~25 us and its result was dropped).
  if (tiny(best.value)) {
    best.offers.clear();
    return true;
  }
  if (shallow_first(g)) return g.shallow_first = true;
  return double_pieces_fail(g, start_value, tiny_rel);
}

// The exact pieces are built on the coordinates relative to A[0] times 2^-unit (exact), with
// 2^unit the largest of them (a pair spanning 1e-302..1e308 reaches this branch unscaled,
// through solve_pair's exact path; its H would overflow in doubles). A uniform scale leaves
// the normals unchanged and multiplies every value by 2^-2unit (Best::unit). The near
// vertices' pieces beside a far vertex are still ~(size / R)^2: each piece's H and each
// condition is scaled again by its own power of two before rounding (enumerate_pieces).
// Only the pieces whose vertices at the plane may be there at a stationary value below the best
// are visited. At a stationary point along the unit u, of value mu, in a piece that holds A's
// vertex x at the plane, x and A's highest vertex are both at the plane (T = C - H: direction_qp.h),
// so their heights differ by |T_x - T_top| <= sqrt(2 (T_x^2 + T_top^2)) <= sqrt(2 F) =
// sqrt(40 mu) (F = 20 mu the unit normal's cost), and D(u)^2 <= 32 mu (deformable_depth.h's
// bound). So with b at least the best value, a vertex more than sqrt(40 b) below A's highest
// along every unit u with D(u) <= sqrt(32 b) is at the plane in no piece that holds a stationary
// value below the best (facet_bounds.h's vertices_off_the_contact shows it), and likewise B's;
// the minimiser's own piece is visited, and an offer is a value along a normal, never below the
// minimum. On a contact made by rounding the vertices away from the contact (~the size from it,
// against sqrt(40 b) ~ the depth) drop most of the 225 pieces.
void enumerate_exact(GlobalRun& g, const ExactStart& exact_start, FacetBounds* bounds) {
  using detail::Q;
  const TetVertices &A = g.A, &B = g.B;
  Best& best = g.best;
  std::array<std::array<Q, 3>, 4> qA, qB;
  long unit = LONG_MIN;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      qA[i][k] = Q(A[i][k]) - Q(A[0][k]), qB[i][k] = Q(B[i][k]) - Q(A[0][k]);
      unit = std::max({unit, detail::log2_estimate(qA[i][k]), detail::log2_estimate(qB[i][k])});
    }
  if (unit == LONG_MIN) unit = 0;  // not reached: a valid pair has a non-zero edge
  for (auto* side : {&qA, &qB})
    for (auto& x : *side)
      for (Q& c : x) detail::scale_pow2(c, -unit);
  Problem Ps = g.P;  // the conditions' floor in the scaled units
  Ps.scale = 4.0;    // |x| 2^-unit < 4 (bit lengths give log2 |x| within 1)
  best.A = &A, best.B = &B, best.unit = unit, best.pair_scale = g.P.scale;
  best.value = INFINITY;
  best.offer(Ps, best.n);
  if (exact_start) best.offer(Ps, exact_start());
  g.lower_scaled = std::ldexp(g.lower, int(std::clamp(-2 * unit, -4000L, 4000L)));
  // Wall offers for a pair with a vertex far from the others only (compact: needs_exact_pieces'
  // class, every piece's |H| <= 48 scale^2, no steep piece; Search::walls).
  const bool compact = near_extent_sq(A, B) >= g.P.scale * g.P.scale / 256;
  Search search{Ps, best, g.lower_scaled, !compact};
  if (bounds && best.have_q) {
    // b: the best's exact value rounded up (get_d truncates), with room
    const double b = std::nextafter(best.qvalue.get_d(), INFINITY) * (1 + 0x1p-20);
    const double d0 = std::sqrt(32 * b) * (1 + 4 * kU), gamma = std::sqrt(40 * b) * (1 + 4 * kU);
    if (b > 0 && std::isfinite(b)) search.contact &= ~vertices_off_the_contact(*bounds, A, B, d0, gamma);
  }
  enumerate_pieces(qA, qB, search);
  // (lower is in the pair's units; each piece takes it, and the best value, in its own)
}

// Which offer wins (double path). Each double value carries value_error's loose bound; offers
// whose intervals meet the winner's are contenders (every other offer is certainly above the
// winner). When every contender's bounds together stay below kCompare, the double winner is
// within kCompare of the true best offer; otherwise the same test on the contenders with
// evaluate_tight's values and bounds (its winner, likewise, is within kCompare of the best
// contender), and where that fails too the contenders are compared exactly.
constexpr double kCompare = 4e-10;

// evaluate_tight's bounds (doubles): value_error's are wider than kCompare where the depth is
// far below the pair's size, and two offers of one stationary point (the descent's and the
// enumeration's) tie within them. True (best.n set) when they separate the winner.
bool tight_winner(GlobalRun& g, double win_err) {
  Best& best = g.best;
  // One buffer per thread (as Best's offers): no allocation per pair; global_depth() does not
  // recurse.
  static thread_local std::vector<std::pair<Evaluation, V3>> contenders;
  contenders.clear();
  for (const auto& o : best.offers)
    if (!(o.value > best.value * (1 + 2 * (win_err + o.error))))  // inf band (or NaN): every offer
      contenders.push_back({evaluate_tight(g.A, g.B, g.P, o.n), o.n});
  std::size_t w = 0;
  for (std::size_t i = 1; i < contenders.size(); ++i)
    if (contenders[i].first.value < contenders[w].first.value) w = i;
  bool separated = !contenders.empty();
  for (std::size_t i = 0; i < contenders.size(); ++i) {
    const Evaluation &x = contenders[w].first, &y = contenders[i].first;
    if (i != w && !(y.value > x.value * (1 + 2 * (x.error + y.error))) && !(x.error + y.error <= kCompare))
      separated = false;
  }
  if (separated) best.n = contenders[w].second;
  return separated;
}

// The contenders compared exactly.
void exact_winner(GlobalRun& g, double win_err) {
  Best& best = g.best;
  detail::Q bestq;
  bool have = false;
  for (const auto& o : best.offers) {
    const double band = 2 * (win_err + o.error);
    if (o.value > best.value * (1 + band)) continue;  // inf band (or NaN): every offer
    detail::Q hA[4], hB[4];
    Solution<detail::Q> sq;
    const detail::Q x = relaxed_exact(g.A, g.B, o.n, hA, hB, sq);
    if (!have || x < bestq) bestq = x, best.n = o.n, have = true;
  }
}

void choose_offer(GlobalRun& g) {
  Best& best = g.best;
  double win_err = INFINITY;
  for (const auto& o : best.offers)
    if (o.n == best.n) win_err = std::min(win_err, o.error);
  bool separated = true;
  for (const auto& o : best.offers)
    if (o.n != best.n && !(o.value > best.value * (1 + 2 * (win_err + o.error))) &&
        !(win_err + o.error <= kCompare))
      separated = false;
  if (!separated) separated = tight_winner(g, win_err);
  if (!separated) exact_winner(g, win_err);
}

// The deformed positions along the normal v (A -> B; a reference: it follows the best normal)
// from a solution s of the relaxed QP with heights hA, hB: q1 = x + t / v.v v.
struct Placement {
  const TetVertices& A;
  const TetVertices& B;
  const V3& v;
  double vv;
  GlobalOptimum& out;
  template <class S, class Heights, class ToDouble>
  void operator()(const S& s, const Heights& heights_A, const Heights& heights_B, ToDouble to_d) const {
    for (int i = 0; i < 4; ++i) {
      const double tA = to_d(displacement_below(heights_A[i], false, s));
      const double tB = to_d(displacement_above(heights_B[i], false, s));
      for (int k = 0; k < 3; ++k) {
        out.q1_A[i][k] = A[i][k] + tA / vv * v[k];
        out.q1_B[i][k] = B[i][k] + tB / vv * v[k];
      }
    }
  }
};

// The reported value (double path): the offer's own when value_error's bound meets the budget
// (the common case: ~3e-11 on the paper's pairs), else evaluate_tight's when its bound does.
// False when neither does.
bool report_double(const GlobalRun& g, const Placement& place) {
  const Best& best = g.best;
  GlobalOptimum& out = place.out;
  const V3& v = best.n;
  if (best.win.n == v && best.win.error <= kGlobalRel) {
    out.value = best.value;
    place(best.win.sol, best.win.hA, best.win.hB, [](double x) { return x; });
    out.certified = true;
    return true;
  }
  const Evaluation ev = evaluate_tight(g.A, g.B, g.P, v);
  if (ev.error <= kGlobalRel) {
    out.value = ev.value;
    place(ev.sol, ev.hA, ev.hB, [](double x) { return x; });
    out.certified = true;
    return true;
  }
  return false;
}

// The value certified along the witness (suspect_proof.h) alone: its value, and its normal and
// positions q1 = x + t / n.n n rounded (each coordinate rounded once from its exact value).
void report_witness(const GlobalRun& g, GlobalOptimum& out) {
  using detail::Q;
  const Best::Witness& w = *g.best.witness;
  out.value = w.value.get_d();
  const Q nn = w.n[0] * w.n[0] + w.n[1] * w.n[1] + w.n[2] * w.n[2];
  for (int i = 0; i < 4; ++i) {
    const Q tA = displacement_below(w.hA[i], false, w.sol) / nn;
    const Q tB = displacement_above(w.hB[i], false, w.sol) / nn;
    for (int k = 0; k < 3; ++k) {
      out.q1_A[i][k] = Q(Q(g.A[i][k]) + tA * w.n[k]).get_d();
      out.q1_B[i][k] = Q(Q(g.B[i][k]) + tB * w.n[k]).get_d();
    }
  }
  for (int k = 0; k < 3; ++k) out.normal[k] = w.n[k].get_d();  // integers below 2^256: finite
  out.exact_value = true;
  out.witness = std::isfinite(out.value);
}

// Slow path: the same closed form in rationals along the same (exact) normal.
void report_exact(GlobalRun& g, Placement& place, double start_value) {
  using detail::Q;
  Best& best = g.best;
  GlobalOptimum& out = place.out;
  const V3& v = best.n;
  Q hA[4], hB[4];
  Solution<Q> qs;
  Q value = relaxed_exact(g.A, g.B, v, hA, hB, qs);
  // A depth below unrepresented()'s class on the exact pieces: its suspects are settled, and the
  // offers that settle them may lower the best (a new normal: value and positions along it).
  bool missed = false;
  if (g.exact_pieces && value.get_d() < kUnrepresentedDepth * near_extent_sq(g.A, g.B)) {
    const V3 before = best.n;
    const Representation r = represented(best, g.lower_scaled);
    if (r == Representation::ByWitness) return report_witness(g, out);
    missed = r == Representation::None;
    if (best.n != before) {
      out.normal = best.n;
      place.vv = dot(v, v);
      value = relaxed_exact(g.A, g.B, v, hA, hB, qs);
    }
  }
  out.value = value.get_d();
  place(qs, hA, hB, [](const Q& x) { return x.get_d(); });
  out.exact_value = true;
  // Not even the start's certified value reached (rare: a pair whose depth is below about 1e-7
  // of its extent, where no double normal near the start's exact one reproduces it, and the
  // walls did not help): the normal is not given (kGlobalNotRepresentable).
  out.certified = std::isfinite(out.value) &&
                  !(std::isfinite(start_value) && value > detail::Q(start_value) * detail::Q(1 + 1e-9)) &&
                  !missed;
}

// A contact far shallower than the pair certified without the pieces (shallow_certificate.h):
// its value, normal and the positions along it.
bool report_shallow(GlobalRun& g, const V3& start, FacetBounds& bounds, GlobalOptimum& out,
                    const V3* edge_d = nullptr) {
  ShallowResult r;
  if (!certify_shallow(g.A, g.B, g.P, start, r, &bounds, edge_d)) return false;
  // Along a normal in double words: a double normal v near it where relaxed(v) is within
  // definitions §8 of the proved bound (exact minimum in [L, relaxed(v)]: relaxed(v) (1 +
  // kGlobalRel) <= L (1 + 8e-10) puts the value reported, within kGlobalRel of relaxed(v),
  // within 8e-10 + 1e-10 < 1e-9 of the minimum): the rounding and its neighbours one ulp away
  // per component (27 double normals); then the integer normals along v + lo (integer_normals.h,
  // the exact pieces' own search along a minimiser: a generic direction off the axes); then the
  // 27 about v + lo scaled to a largest component of 1 and of just below 2, and M's facet
  // directions whose overlap allows the value. Else the
  // value is certified along v + lo alone, which no double triple near it represents: a witness
  // (global_depth.h), its normal v (the rounding of v + lo) and the positions along v, without
  // the exact pieces, whose search tries the same kinds of normals along the exact minimiser
  // (its rounding, its neighbours, these integer normals). Measured, that found one on none of
  // the pairs where these find none while the cap lay about the minimiser (docs/performance.md,
  // "Contacts by rounding on diagonal planes"); with the vertex-on-edge planes the cap may lie
  // beside it, and on 104 of the 23,396 pairs of two decimal grids it finds one where these do not
  // ("A vertex on an edge by rounding").
  if (nonzero(r.low)) {
    const V3 n = r.normal, lo = r.low;
    auto offer = [&](const V3& w) {
      const Evaluation ev = evaluate_below(g.A, g.B, g.P, w, r.lower * (1 + 8e-10));
      if (ev.error <= kGlobalRel && ev.value * (1 + kGlobalRel) <= r.lower * (1 + 8e-10))
        r.eval = ev, r.normal = w, r.low = {0, 0, 0};
    };
    auto around = [&](const V3& c) {
      for (int m = 0; m < 27 && nonzero(r.low); ++m) {
        V3 w = c;
        for (int k = 0, q = m; k < 3; ++k, q /= 3)
          if (q % 3) w[k] = std::nextafter(c[k], q % 3 == 1 ? INFINITY : -INFINITY);
        offer(w);
      }
    };
    around(n);
    if (nonzero(r.low)) {
      const detail::Q y[3] = {detail::Q(n[0]) + detail::Q(lo[0]), detail::Q(n[1]) + detail::Q(lo[1]),
                              detail::Q(n[2]) + detail::Q(lo[2])};
      std::vector<V3> normals;
      integer_normals(y, 1 << 18, 4, normals);
      for (std::size_t i = 0; i < normals.size() && nonzero(r.low); ++i) offer(normals[i]);
    }
    // then v + lo scaled so that its largest component is exactly 1, then just below 2, in
    // magnitude: components just below a power of two lie on the finest grid of their binade
    // (a normal near (1, -1, -1) or (-1, 2, -1), as grids' diagonal contacts have, is found there)
    double big = 0;
    for (int k = 0; k < 3; ++k) big = std::max(big, std::fabs(n[k]));
    for (const double top : {1.0, 2 - 0x1p-51}) {
      if (!nonzero(r.low) || !(big > 0) || !std::isfinite(big)) break;
      V3 c;
      for (int k = 0; k < 3; ++k) {  // (n_k + lo_k) top / big, rounded about once
        const double q = n[k] / big;
        const detail::dw::DW p = detail::dw::two_prod(q, big);
        c[k] = (q + (((n[k] - p.hi) - p.lo) + lo[k]) / big) * top;
      }
      if (c != n) around(c);
    }
    // then the candidate directions of M where the overlap allows the value (relaxed(u) >=
    // D(u)^2 / 32: only where D <= sqrt(32 L (1 + 8e-10))): the minimiser at a facet normal of M
    // whose rounding is exact (grids' edges' cross products), beside the certificate's normal
    // or at a tie of it (symmetric contacts)
    if (nonzero(r.low) && bounds.get()) {
      const double d2 = 32 * r.lower * (1 + 1e-9);
      for (const global::DirectionBounds& x : bounds.dirs()) {
        if (x.zero) continue;
        for (const double sgn : {1.0, -1.0}) {
          const double over = sgn > 0 ? x.plus_low : x.minus_low;  // (D(n) |n| from below)
          if (nonzero(r.low) && !(over > 0 && over * over > d2 * x.nn_up)) offer(mul(x.n, sgn));
        }
      }
    }
  }
  out.normal = r.normal;
  Placement place{g.A, g.B, r.normal, dot(r.normal, r.normal), out};
  place(r.eval.sol, r.eval.hA, r.eval.hB, [](double x) { return x; });
  out.value = r.eval.value;
  out.certified = !nonzero(r.low);
  out.witness = !out.certified && std::isfinite(out.value);
  return true;
}

// A minimiser moving one vertex of each side, certified by the rigid depth's bound, or an edge
// of each on translates of one line (lone_pair_certificate.h): its value, normal and the
// positions along it.
// declined: where a lone pair's candidate was evaluated but its value lies above the bound (a
// minimiser where the lone pair's cone meets a neighbouring piece, ~1e-8 above PD^2 / 32 on
// blocks resting 1e-9 deep on each other's columns), that normal, else 0.
bool report_lone_pair(GlobalRun& g, FacetBounds& bounds, GlobalOptimum& out, LonePairResult& r) {
  if (!global::certify_lone_pairs(g.A, g.B, g.P, bounds, r)) return false;
  out = GlobalOptimum{};
  out.normal = r.normal;
  Placement place{g.A, g.B, r.normal, dot(r.normal, r.normal), out};
  place(r.eval.sol, r.eval.hA, r.eval.hB, [](double x) { return x; });
  out.value = r.eval.value;
  out.certified = true;
  return true;
}

// Starts for the shallow certificate where the pair's own fail: the candidate directions of M
// (either orientation) whose overlap lies within 1e-6 of the least or below `tiny`, the least
// first, one a direction (kept: up to four). Where the least overlap is tied between facets of M
// through one vertex (a vertex of five-tetrahedra cells resting on a vertex), a walk from one of
// them may find no multipliers (its active set degenerate there) while from another it does,
// and certify_shallow's caps then cover the others. Where a vertex rests on an edge by rounding
// (a grid against its copy moved along its cells' diagonals), the overlap stays that small over
// an arc of normals about the edge, and the walk from a normal on the arc finds no multipliers
// (the active vertices across it on one line: plane_dual's system is singular) while from the
// facet directions at the arc's ends, where a fourth vertex reaches the plane, it does. (Taken
// only where two or more qualify: a single least direction is where the pair's own start lies.)
constexpr double kTinyOverlap = 0x1p-40;  // (of the pair's size: contacts by rounding, ~2^-53)
int least_overlap_starts(FacetBounds& bounds, V3 (&out)[4], double tiny) {
  if (!bounds.get()) return 0;
  struct Oriented {
    V3 n;
    double overlap;
  };
  Oriented all[2 * global::kDirections];
  int m = 0;
  double least = INFINITY;
  for (const global::DirectionBounds& x : bounds.dirs()) {
    if (x.zero) continue;
    const double len = std::sqrt(x.nn_up);
    for (const double s : {1.0, -1.0}) {
      all[m] = {mul(x.n, s), (s > 0 ? x.plus_low : x.minus_low) / len};
      least = std::min(least, all[m++].overlap);
    }
  }
  // (the least overlaps first: with the tiny ones more than four may qualify)
  std::stable_sort(all, all + m, [](const Oriented& a, const Oriented& b) { return a.overlap < b.overlap; });
  int k = 0;
  for (int i = 0; i < m && k < 4; ++i) {
    if (!(all[i].overlap <= std::max(least * (1 + 1e-6), tiny))) break;
    const V3 u = mul(all[i].n, 1 / global::norm(all[i].n));
    bool seen = false;
    for (int j = 0; j < k; ++j) seen |= dot(u, out[j]) > 1 - 1e-9;
    if (!seen) out[k++] = u;
  }
  return k;
}

// A certified upper bound on the exact relaxed value along v from compensated heights
// (relaxed_upper_compensated, deformable_depth.h), +inf where they do not apply (a pair outside
// the double pieces' scale range [2^-100, 2^100], as Best::certainly_above). On a contact made
// by rounding the heights at the plane are exact to the vertices' own u, so this bound is about
// the value itself, where value_upper's (~(2^12 u size)^2) is a depth bound.
double compensated_upper(const Problem& P, const TetVertices& A, const TetVertices& B, const V3& v) {
  double upper = INFINITY;
  if (!(P.scale >= 0x1p-100 && P.scale <= 0x1p100) || !relaxed_upper_compensated(A, B, v, upper)) return INFINITY;
  return upper;
}

// The double offers' best, bounded (global_depth.h's bound_shallow): its certified upper bound
// (the smaller of value_upper's and compensated_upper's), its estimate and the positions along
// its normal. False where the bound is not finite.
bool report_bound(const GlobalRun& g, GlobalOptimum& out) {
  const Best& best = g.best;
  const V3& v = best.n;
  if (!nonzero(v) || !(best.win.n == v)) return false;
  out.upper = std::min(value_upper(g.P, v), compensated_upper(g.P, g.A, g.B, v));
  if (!(out.upper < kBoundedDepth * g.P.scale * g.P.scale)) return false;  // (NaN, +inf: false)
  out.value = best.value > 0 && best.value <= out.upper ? best.value : out.upper;
  out.normal = v;
  Placement place{g.A, g.B, v, dot(v, v), out};
  place(best.win.sol, best.win.hA, best.win.hB, [](double x) { return x; });
  out.bounded = true;
  return true;
}

GlobalOptimum report(GlobalRun& g, double start_value) {
  GlobalOptimum out;
  out.normal = g.best.n;
  const V3& v = g.best.n;
  Placement place{g.A, g.B, v, dot(v, v), out};
  // No normal at all (no start and no stationary point passed: coordinates spanning the whole
  // double range, the caller's exact-path branch): not certified; the caller reports it
  // (found by the fast_engine fuzzer: the exact evaluation along a zero normal divided by 0).
  if (!nonzero(v) || !std::isfinite(place.vv)) return out;
  if (!g.exact_pieces && report_double(g, place)) return out;
  report_exact(g, place, start_value);
  return out;
}

}  // namespace

double exact_relaxed_value(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& n,
                           bool& ok) {
  detail::Q hA[4], hB[4];
  Solution<detail::Q> s;
  return detail::rounded_value(relaxed_exact(A, B, n, hA, hB, s), ok);
}

GlobalOptimum face_bound(const TetVertices& A, const TetVertices& B) {
  GlobalOptimum out;
  const Problem P = global::problem_of(A, B);
  if (!(P.scale >= 0x1p-100 && P.scale <= 0x1p100)) return out;
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double least = INFINITY;
  V3 n{0, 0, 0};
  for (const V3* T : {P.relA, P.relB})
    for (const auto& f : kFace) {
      V3 d = cross(sub(T[f[1]], T[f[0]]), sub(T[f[2]], T[f[0]]));
      double maxA = -INFINITY, minA = INFINITY, maxB = -INFINITY, minB = INFINITY;
      for (int i = 0; i < 4; ++i) {
        const double a = dot(d, P.relA[i]), b = dot(d, P.relB[i]);
        maxA = std::max(maxA, a), minA = std::min(minA, a), maxB = std::max(maxB, b), minB = std::min(minB, b);
      }
      double D = maxA - minB;  // the overlap along d; along -d: maxB - minA
      if (maxB - minA < D) D = maxB - minA, d = mul(d, -1.0);
      const double dd = dot(d, d);
      // (a subnormal d.d or square would round by more than the slack below: such a face is
      // skipped, as one with no bound)
      if (!(dd >= DBL_MIN) || !std::isfinite(dd) || !std::isfinite(D)) continue;
      // D_up = (|D~| (1 + u) + 2 e_h) (1 + 8u): the bound above and its own roundings (< 8u);
      // its square over d.d (3u) and the square and quotient (2u) within the final (1 + 8u),
      // which one more rounding (< u) leaves above
      const double e_h = 5 * kU * (std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2])) * P.scale;
      const double D_up = (std::fabs(D) * (1 + kU) + 2 * e_h) * (1 + 8 * kU);
      const double square = D_up * D_up;
      if (!(square >= DBL_MIN)) continue;
      const double upper = square / dd * (1 + 8 * kU);
      if (upper < least) least = upper, n = d;
    }
  if (!(least < kBoundedDepth * P.scale * P.scale) || !(least >= DBL_MIN)) return out;
  // D_up's 2 e_h (~10 u |d| scale) dominates it on a contact made by rounding, whose overlap is
  // ~u of the size: the relaxed value along the same d (>= pdd2_global, global_depth.h) on
  // compensated heights bounds it about its value instead
  least = std::min(least, compensated_upper(P, A, B, n));
  DirectionSolution sol;
  double hA[4], hB[4];
  const double x = global::relaxed_at(P, n, &sol, nullptr, hA, hB);
  out.upper = least;
  out.value = x > 0 && x <= least ? x : least;
  out.normal = n;
  Placement place{A, B, n, dot(n, n), out};
  place(sol, hA, hB, [](double v) { return v; });
  out.bounded = true;
  return out;
}

GlobalOptimum global_depth(const TetVertices& A, const TetVertices& B, const double start_normal[3],
                           double start_value, const ExactStart& exact_start, double rigid_pd2,
                           bool bound_shallow) {
  GlobalRun g(A, B);
  set_up(g, start_normal, rigid_pd2);
  g.exact_pieces = needs_exact_pieces(g, start_value);
  // (not after the double enumeration: a pair found that shallow only there, a resting contact
  // ~1e-9 of its size deep, has a bound about its value, which a sum rarely lets stand, and
  // certifying it again from the start would cost the enumeration twice)
  if (g.exact_pieces && g.tiny_start && bound_shallow) {
    GlobalOptimum bounded;
    if (report_bound(g, bounded)) return bounded;
  }
  if (g.exact_pieces) {
    // Without the pieces where a certificate applies: the shallow one (a contact whose overlap
    // lies under a face of A - B), else the lone pairs' (a vertex on a vertex, an edge on a
    // collinear edge); a witness of the shallow one (certified along a normal in double words
    // only) after those fail.
    FacetBounds bounds(g.A, g.B);  // (M's facet bounds: computed once, where first needed)
    bool shallow = report_shallow(g, g.best.n, bounds, g.shallow);
    if (shallow && g.shallow.certified) return g.shallow;
    // (the shallow certificate tried first by shallow_first(): where it declines, the double
    // pieces, and the rest of this branch only where they cannot certify, from their best normal)
    if (g.shallow_first) {
      const V3 tried = g.best.n;
      if (!double_pieces_fail(g, start_value, g.tiny_rel)) {
        g.exact_pieces = false;
        choose_offer(g);
        return report(g, start_value);
      }
      GlobalOptimum again;
      if (g.best.n != tried && report_shallow(g, g.best.n, bounds, again)) {
        if (again.certified) return again;
        if (!shallow) g.shallow = again, shallow = true;  // (a witness kept, as below)
      }
    }
    GlobalOptimum lone;
    LonePairResult declined;
    if (report_lone_pair(g, bounds, lone, declined)) return lone;
    // the shallow certificate again from the lone pair's ray: the start's walk may end in
    // another piece's chart, while the ray lies next to a minimiser where the lone pair's cone
    // meets a neighbouring piece; with an edge pair's bound beside its own where one was found
    // (an edge on a collinear edge: the overlap between the two caps is as small as the depth),
    // the pair's start again with that bound, and the edge pair's normal (exactly across the
    // edge): the walk's multipliers move from these where the ray's nudge leaves them none
    // (a start's witness kept where none was found before it: the first one is reported where
    // no start certifies a double normal)
    // Edges that are translates only up to a rounding (a turned scene's resting edges) give
    // their starts for a certified normal only: a witness from them is not kept, so that such a
    // pair goes on to the exact pieces, which may find a double normal attaining its value.
    const V3* edge_d = nonzero(declined.edge_d) ? &declined.edge_d : nullptr;
    bool witness = shallow;
    auto certified_from = [&](const V3& start, bool keep_witness) {
      if (!nonzero(start) || !report_shallow(g, start, bounds, lone, edge_d)) return false;
      if (lone.certified) return true;
      if (!witness && keep_witness) g.shallow = lone, witness = true;
      return false;
    };
    const V3 none{0, 0, 0};
    const bool edge_witness = declined.edge_translate;
    if (certified_from(edge_d ? g.best.n : none, edge_witness) || certified_from(declined.near_minimiser, true) ||
        certified_from(declined.edge_v, edge_witness))
      return lone;
    V3 tied[4];
    const int k = least_overlap_starts(bounds, tied, kTinyOverlap * g.P.scale);
    for (int i = 0; i < k && k > 1; ++i)
      if (certified_from(tied[i], true)) return lone;
    if (witness) return g.shallow;
    enumerate_exact(g, exact_start, &bounds);
  } else {
    choose_offer(g);
  }
  return report(g, start_value);
}

}  // namespace pdd::fast
