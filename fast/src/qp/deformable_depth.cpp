// deformable_depth.cpp — definitions §5 variants with exact pruning. See the header.
#include "qp/deformable_depth.h"

#include "exact/exact_predicates.h"
#include "exact/integer_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "certification/certify.h"
#include "certification/compensated_heights.h"
#include "certification/compensated_displacements.h"
#include "certification/qp_lower_bound.h"
#include "certification/refine.h"
#include "certification/tie_tolerance.h"
#include "certification/tight_delta.h"
#include "certification/value_bounds.h"
#include "hot_path.h"
#include "kernel/superset_depth.h"
#include "kernel/superset_kernel.h"
#include "qp/direction_qp_impl.h"

namespace pdd::fast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline bool usable(const CandidateSet& set) { return set.intersecting && set.count > 0; }
inline bool usable(const QuickCandidates& q) { return q.count > 0; }  // intersecting by contract

// The solver's displacement error of value_bounds.h for a computed solution, dT = coeff u H:
// the tight one when every free vertex's KKT margin (A: C − H + S_A, B: C − H + S_B; its sign
// is the vertex's status) exceeds twice the wide bound, so that no status can differ from the
// exact solution's — then H = Ha, the largest of |C| and the heights that enter the closed form
// (constrained vertices, active free ones: A's with margin < 0, B's with margin > 0); else the
// wide one with H = Hm (every height). `below_free`/`above_free`: bit i set for a free vertex
// that the solver moves (A's, B's).
struct SolverBound {
  double coeff, H;
};
SolverBound solver_bound(const Candidate& c, const DirectionSolution& s, unsigned below_free,
                         unsigned above_free) {
  const double Hm = detail::max_height(c);
  const SolverBound wide{kSolverDisplacementCoeff, Hm};
  const double margin = 2 * kSolverDisplacementCoeff * kUnitRoundoff * Hm;
  double Ha = std::fabs(s.c);
  for (int i = 0; i < 4; ++i) {
    if (below_free >> i & 1u) {
      const double m = s.c - c.hA[i] + s.sumA;
      if (!(std::fabs(m) > margin)) return wide;
      if (m < 0) Ha = std::max(Ha, std::fabs(c.hA[i]));
    }
    if (above_free >> i & 1u) {
      const double m = s.c - c.hB[i] + s.sumB;
      if (!(std::fabs(m) > margin)) return wide;
      if (m > 0) Ha = std::max(Ha, std::fabs(c.hB[i]));
    }
    if (c.conA >> i & 1u) Ha = std::max(Ha, std::fabs(c.hA[i]));
    if (c.conB >> i & 1u) Ha = std::max(Ha, std::fabs(c.hB[i]));
  }
  return {kSolverDisplacementCoeffTight, Ha};
}

struct Valued {
  double v, r;  // value and its root bound (value_bounds.h); r = 0 when v = +inf
};

Valued valued(const Candidate& c, const DirectionSolution& s, const SolverBound& sb,
              const FilterBounds& fb) {
  const double v = s.cost / (20.0 * c.nn);
  return {v, qp_root_rel(s.cost, c.nn, sb.H, degree_bounds_of(fb, c), sb.coeff)};
}

// pdd2_accel(A, B, 1)'s value (only its own interval is used, so kTinyQpRoot may stand in for
// the root bound where its products-only test passes: value_bounds.h; the wide solver bound
// (kSolverDisplacementCoeff, Hm) covers whichever solver_bound would return).
Valued deformable_valued(const Candidate& c, const FilterBounds& fb) {
  const DirectionSolution s =
      solve_deformable(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
  if (qp_root_rel_tiny(s.cost, c.nn, detail::max_height(c), degree_bounds_of(fb, c)))
    return {s.cost / (20.0 * c.nn), kTinyQpRoot};  // valued()'s value
  return valued(c, s, solver_bound(c, s, 0xFu & ~c.conA, 0xFu & ~c.conB), fb);
}


// direction_qp.h's closed form for one status pattern: bit i of atA (atB) set for A's (B's)
// vertices at the plane, constrained or active; case 1 (a_static): C = 0, A's constrained
// height (compensated_heights.h puts the origin on it), S_A = 0. The same operations as the
// solver's last step (direction_qp_impl.h: P summed over the vertices at the plane, C = (P_A
// (5 - m_B) + P_B (5 - m_A)) / den, side_cost), so value_bounds.h's tight bounds hold: C within
// 60 u Ha, S within 350 u Ha, every T within 2^9 u Ha (Ha = max |C| and the heights at the
// plane). False when no vertex is at the plane on either side (den = 0).
bool closed_form(const double hA[4], const double hB[4], unsigned atA, unsigned atB, bool a_static,
                 DirectionSolution& s, double c_static = 0) {
  double fa[4], fb[4], PA = 0, PB = 0;
  int mA = 0, mB = 0;
  for (int i = 0; i < 4; ++i) {
    if (atA >> i & 1u) fa[mA++] = hA[i], PA += hA[i];
    if (atB >> i & 1u) fb[mB++] = hB[i], PB += hB[i];
  }
  s = DirectionSolution{};
  if (a_static) {
    s.c = c_static;
  } else {
    const int den = mA * (5 - mB) + mB * (5 - mA);
    if (den == 0) return false;
    s.c = (PA * (5 - mB) + PB * (5 - mA)) / den;
  }
  const double costA = a_static ? 0.0 : detail::side_cost(0, 0.0, fa, mA, s.c, &s.sumA);
  s.cost = costA + detail::side_cost(0, 0.0, fb, mB, s.c, &s.sumB);
  return true;
}

// The QP value of candidate c on compensated_heights.h's heights (each within e_i of the exact
// one) and its root bound (value_bounds.h), for a candidate whose double heights cannot
// certify it: a shallow contact, their errors ~u L^3 beside a value ~|n| depth (a contact
// made by rounding alone, ~1e-17 of the size deep, has no correct digit in doubles).
// Argument. The solver's statuses (a free vertex of A is at the plane when its margin C - h +
// S_A < 0, one of B when C - h + S_B > 0) give a pattern; closed_form evaluates it afresh and
// each free vertex's margin there is checked against its own error, <= (2^9 u Ha + 2u |h_i| +
// 2u |m_i|) (C's 60 u Ha and S's 350 u Ha, the two subtractions' roundings). (1) Every margin's
// sign certain and matching the pattern: the pattern satisfies KKT for the heights H~
// (direction_qp.h), so it is the exact optimum's for H~ (strictly convex), and only its closed
// form is rounded: the tight solver bound 2^9 u Ha, which does not grow with the far
// vertices' heights (the walk's running sums would: value_bounds.h's wide 2^12 u Hm). (2)
// Under the fixed pattern C is a convex combination of the heights at the plane (weights 5 -
// m_B and 5 - m_A summing to den; 0 exactly in case 1), so the exact heights H* move it by <=
// e_act (the largest e_i at the plane); S = (m C - P)/(5 - m) by <= 8 e_act; a margin by <= 9
// e_act + e_i. Required: |m_i| > error + 9 e_act + e_i, so the pattern is optimal for H* too,
// and for H'' (H* at the plane, H~ elsewhere); the closed form ignores the other heights, so
// Phi(H*) = Phi(H''), and value_bounds.h's Lipschitz argument on H~ and H'' (which differ by
// <= e_act) gives |Phi(H*) - Phi(H~)| <= 2 e_act: qp_root_rel's e_h; e_n the compensated
// normal's.
// Case 1 (Static): A does not move, so only B's free vertices have margins; undecidable edge
// pairs (not in case 1's family) are declined. With C_A empty (VF) C = max(max_i H_A,i, the
// root of S_B) (direction_qp.h); taken only where it is A's highest height (largest(), within
// e_c, the error of the heights within reach of the top, tight_delta.h) and S_B there is
// certainly positive, |S_B| > 2^9 u Ha + 8 e_act (the closed form's rounding, and S's move
// under the exact heights): then S_B* (C*) > 0 too, the root lies below the exact top height
// and C* = max_i H*_A,i. C plays the part of a height at the plane (within e_c, counted in
// e_act), so the argument above holds as written. Relaxed: every vertex free.
// Precondition: a pair rescaled by power_scale.h (every caller's); a cost or n.n below 2^-900
// (an unscaled list of a tiny pair, where the solver's values underflow) is declined.
// Returns false when not applicable or a margin is too small (the caller's next path decides).
// Degenerate contacts (a vertex exactly at the threshold between free and at the plane: a
// margin exactly 0, common where B's vertices lie on A's diagonal planes) leave a margin
// within its error whatever the precision. With `bracket`, the value is then bracketed by weak
// duality instead (direction_qp.h's Lagrangian L): let U be the vertices whose margins are not
// certain, every other one certainly consistent with the pattern. A pattern's closed form
// satisfies stationarity (dL/dT = 0 defines the multipliers l_i = -2 (T_i + S_A) of A's
// vertices at the plane and m_j = 2 (T_j + S_B) of B's, 0 for free ones; dL/dC = 10 (S_A +
// S_B) = 0 is how C is chosen), and L is convex, so the dual function there is L = F (every
// constraint term vanishes: at the plane H + T = C, free ones have zero multipliers). With U
// free (P_dual), every vertex still at the plane certainly of the multiplier's sign (A's margin
// < 0, B's > 0): dual feasible, F(P_dual) <= the optimum. With U at the plane (P_primal), every
// free vertex certainly on its side (A's margin > 0, B's < 0): primal feasible, F(P_primal) >=
// the optimum. Each closed form's value at the exact heights lies within its own root bound
// (the argument (2) above, per pattern: it uses only the fixed pattern's closed form and its
// margins), so the exact value lies in [lower_of(v_dual, r_dual), upper_of(v_primal,
// r_primal)]: reported as v_primal with the root bound covering both ends (no pattern: none is
// verified). Case 2 and relaxed; case 1 with A's constrained vertex fixing C (not VF, whose C is
// itself decided by a sign).
// The same on given compensated heights h (constrained vertices conA, conB), with the solution
// of the verified pattern in s; `pattern` (optional): that pattern (the vertices at the plane),
// Ha and e_act (left as it is when the value is bracketed).
struct VerifiedPattern {
  unsigned atA = 0, atB = 0;
  double Ha = 0, e_act = 0;
};
bool valued_on_heights(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, QpKind kind,
                       Valued& out, DirectionSolution& s, VerifiedPattern* pattern = nullptr,
                       bool bracket = false);
bool compensated_valued(const TetVertices& A, const TetVertices& B, const Candidate& c, QpKind kind,
                        Valued& out, VerifiedPattern* pattern = nullptr);

// The heights moved by one of them, t = A's highest: a common shift of every height moves the
// QP's plane offset with it and leaves its cost and displacements as they are, while the
// solver's rounding, bounded relative to the heights at the plane (check_pattern's Ha), then
// scales with the contact's depth instead of the heights' distance from the frame's origin (a
// resting contact 1e-6 deep at heights ~0.5: intervals 3.6e-8 wide before, within definitions
// §8 after). Each x - t rounded once (exact by Sterbenz where x lies within a factor 2 of t),
// its error u |x - t| added to the height's own. Only where no pattern is kept (a verified
// pattern's Ha is read with the heights as given).
detail::CompensatedHeights shifted_heights(const detail::CompensatedHeights& h) {
  detail::CompensatedHeights s = h;
  double t = h.hA[0];
  for (int i = 1; i < 4; ++i) t = std::max(t, h.hA[i]);
  for (int i = 0; i < 4; ++i) {
    s.hA[i] = h.hA[i] - t, s.eA[i] = h.eA[i] + kUnitRoundoff * std::fabs(s.hA[i]) * (1 + 0x1p-40);
    s.hB[i] = h.hB[i] - t, s.eB[i] = h.eB[i] + kUnitRoundoff * std::fabs(s.hB[i]) * (1 + 0x1p-40);
  }
  return s;
}

bool compensated_valued(const TetVertices& A, const TetVertices& B, const Candidate& c, QpKind kind,
                        Valued& out, VerifiedPattern* pattern) {
  const bool a_static = kind == QpKind::Static;
  if (a_static && c.label.orientation != EdgeOrientation::Decided) return false;
  detail::CompensatedHeights h;
  const unsigned conA = kind == QpKind::Relaxed ? 0u : c.conA, conB = kind == QpKind::Relaxed ? 0u : c.conB;
  DirectionSolution s;
  const VerifiedPattern given = pattern ? *pattern : VerifiedPattern{};  // (bracketed: left as given)
  const bool words = detail::compensated_heights(A, B, c, h) &&
                     valued_on_heights(pattern ? h : shifted_heights(h), conA, conB, kind, out, s, pattern, true);
  if (words && certified_choice(upper_of(out.v, out.r), lower_of(out.v, out.r))) return true;
  // The heights by expansions (compensated_heights.h's expansion_heights: each within a few u
  // of its own exact value): parallel and nearly parallel edges, which have no double words,
  // and a contact made by rounding whose double words' u² M term exceeds the heights at the
  // plane (depths ~1e-17 of the size on a grid against its copy shifted by a quarter cell along
  // the diagonal, on any label ~1e-31 where two roundings made it): their value's interval, too
  // wide for definitions §8, is replaced by the exact heights' where those give one.
  if (!(c.parallel || c.own_bounds || words || c.label.kind != ContactKind::EE)) return false;
  detail::CompensatedHeights x;
  Valued v;
  DirectionSolution t;
  VerifiedPattern p = given;
  if (!detail::expansion_heights(A, B, c, x) ||
      !valued_on_heights(pattern ? x : shifted_heights(x), conA, conB, kind, v, t, pattern ? &p : nullptr, true))
    return words;
  out = v;
  if (pattern) *pattern = p;
  return true;
}

namespace {
// One pattern's closed form on heights h, its value and root bound, and the verdict on each
// vertex's margin (valued_on_heights' argument): bit i of unsure* set when its sign is not
// certain, of wrong* when it is certainly of the other status. False when the closed form does
// not apply (no vertex at the plane) or is out of range.
struct PatternCheck {
  DirectionSolution s;
  Valued v;
  double Ha = 0, e_act = 0;
  unsigned unsureA = 0, unsureB = 0, wrongA = 0, wrongB = 0;
};
bool check_pattern(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, bool a_static,
                   const detail::Extreme& top, unsigned atA, unsigned atB, PatternCheck& pc) {
  DirectionSolution& s = pc.s;
  if (!closed_form(h.hA, h.hB, atA, atB, a_static, s, top.value)) return false;
  if (!(s.cost >= 0x1p-900) || !(h.nn >= 0x1p-900)) return false;  // (precondition, above)
  double Ha = std::fabs(s.c), e_act = top.error;
  for (int i = 0; i < 4; ++i) {
    if (atA >> i & 1u) Ha = std::max(Ha, std::fabs(h.hA[i])), e_act = std::max(e_act, h.eA[i]);
    if (atB >> i & 1u) Ha = std::max(Ha, std::fabs(h.hB[i])), e_act = std::max(e_act, h.eB[i]);
  }
  pc.Ha = Ha, pc.e_act = e_act;
  // margin m of a free vertex of height hv and error ev: its sign certain, and whether it is
  // `at` (at the plane when m < 0 on A, m > 0 on B)
  auto verdict = [&](double hv, double ev, double m, bool at_if_negative, bool at, unsigned bit, unsigned& unsure,
                     unsigned& wrong) {
    const double err = (512 * kUnitRoundoff * Ha + 2 * kUnitRoundoff * (std::fabs(hv) + std::fabs(m))) * (1 + 0x1p-40);
    if (!(std::fabs(m) > err + 9 * e_act + ev)) unsure |= bit;  // (NaN: unsure)
    else if (((m < 0) == at_if_negative) != at) wrong |= bit;
  };
  pc.unsureA = pc.unsureB = pc.wrongA = pc.wrongB = 0;
  for (int i = 0; i < 4; ++i) {
    if (!a_static && !(conA >> i & 1u))
      verdict(h.hA[i], h.eA[i], s.c - h.hA[i] + s.sumA, true, atA >> i & 1u, 1u << i, pc.unsureA, pc.wrongA);
    if (!(conB >> i & 1u))
      verdict(h.hB[i], h.eB[i], s.c - h.hB[i] + s.sumB, false, atB >> i & 1u, 1u << i, pc.unsureB, pc.wrongB);
  }
  pc.v = {s.cost / (20.0 * h.nn), qp_root_rel(s.cost, h.nn, Ha, DegreeBounds{e_act, h.e_n}, kSolverDisplacementCoeffTight)};
  return true;
}

// The bracket of valued_on_heights (header): U free (dual) and U at the plane (primal).
bool bracketed(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, bool a_static, unsigned atA,
               unsigned atB, unsigned uA, unsigned uB, Valued& out, DirectionSolution& s) {
  const detail::Extreme none{0.0, 0.0};
  PatternCheck dual, primal;
  const unsigned dA = atA & ~uA, dB = atB & ~uB, pA = atA | uA, pB = atB | uB;
  if (!check_pattern(h, conA, conB, a_static, none, dA, dB, dual) ||
      !check_pattern(h, conA, conB, a_static, none, pA, pB, primal))
    return false;
  // dual: every vertex at the plane (not constrained) certain; primal: every free one
  const unsigned freeA = ~conA & 0xFu, freeB = ~conB & 0xFu;
  if (((dual.unsureA | dual.wrongA) & dA & freeA) || ((dual.unsureB | dual.wrongB) & dB & freeB)) return false;
  if (((primal.unsureA | primal.wrongA) & ~pA & freeA) || ((primal.unsureB | primal.wrongB) & ~pB & freeB))
    return false;
  const double lo = lower_of(dual.v.v, dual.v.r), hi = upper_of(primal.v.v, primal.v.r), v = primal.v.v;
  if (!(dual.v.r < 1) || !(lo > 0) || !(hi >= lo) || !(v > 0)) return false;  // (NaN: false)
  // v (1 - r)^2 <= lo and v (1 + r)^2 >= hi, with the roundings of these expressions
  // (finish_root_rel's 4u) and of r's own (2^-40 relative) covered
  const double r = std::max(1 - std::sqrt(lo / v), std::sqrt(hi / v) - 1) * (1 + 0x1p-40) + 8 * kUnitRoundoff;
  if (!(r <= 0.01)) return false;
  out = {v, r};
  s = primal.s;
  return true;
}
}  // namespace

bool valued_on_heights(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, QpKind kind,
                       Valued& out, DirectionSolution& s, VerifiedPattern* pattern, bool bracket) {
  const bool a_static = kind == QpKind::Static;
  s = kind == QpKind::Relaxed ? solve_relaxed(h.hA, h.hB)
                        : a_static              ? solve_static(side_of(h.hA, conA), side_of(h.hB, conB))
                                                : solve_deformable(side_of(h.hA, conA), side_of(h.hB, conB));
  // case 1 without a constrained vertex of A (VF): C is A's highest height (above), e_c its error
  const bool top_pinned = a_static && conA == 0;
  const detail::Extreme top = top_pinned ? detail::largest(h.hA, h.eA) : detail::Extreme{0.0, 0.0};
  if (top_pinned && s.c != top.value) return false;  // the double solution is at S_B's root
  unsigned atA = conA, atB = conB;
  for (int i = 0; i < 4; ++i) {
    if (!a_static && s.c - h.hA[i] + s.sumA < 0) atA |= 1u << i;
    if (s.c - h.hB[i] + s.sumB > 0) atB |= 1u << i;
  }
  PatternCheck pc;
  if (!check_pattern(h, conA, conB, a_static, top, atA, atB, pc)) return false;
  // The double solver's pattern certainly wrong at some vertex (its sums rounded beside heights
  // a rounding apart: a contact made by rounding): once more with those vertices' status
  // flipped, which check_pattern verifies as it verifies any pattern.
  if ((pc.wrongA || pc.wrongB) && !top_pinned) {
    atA ^= pc.wrongA, atB ^= pc.wrongB;
    if (!check_pattern(h, conA, conB, a_static, top, atA, atB, pc)) return false;
  }
  if (top_pinned && !(pc.s.sumB > (512 * kUnitRoundoff * pc.Ha) * (1 + 0x1p-40) + 8 * pc.e_act)) return false;
  if (pc.wrongA || pc.wrongB) return false;
  if (pc.unsureA || pc.unsureB)
    return bracket && !top_pinned && bracketed(h, conA, conB, a_static, atA, atB, pc.unsureA, pc.unsureB, out, s);
  s = pc.s;
  out = pc.v;
  if (pattern) *pattern = {atA, atB, pc.Ha, pc.e_act};
  return true;
}

// pdd2_accel(A, B, 1)'s value along c when c is the exact rigid direction and the double
// heights cannot certify it: compensated_valued's case 2, certified on its own interval.
// Returns the verdict (checked: no failure on ~92 million heights against rationals and ~39k
// pdd2_accel1 values against an exact case-2 solver).
bool accel1_compensated(const TetVertices& A, const TetVertices& B, const Candidate& c, double& value) {
  Valued x;
  if (!compensated_valued(A, B, c, QpKind::Deformable, x)) return false;
  value = x.v;
  return certified_choice(upper_of(x.v, x.r), lower_of(x.v, x.r));
}

// pdd2_accel(A, B, 1) from the superset's rigid choice and its candidate c: the case-2 value
// along c, certified when the rigid direction is the exact one (`unique`, superset_depth.h)
// and the value's own interval meets definitions §8. Returns ch.certified.
bool accel1_of_rigid(const Choice& rigid, const Candidate& c, bool unique, const FilterBounds& fb,
                     Choice& ch) {
  const Valued x = deformable_valued(c, fb);
  ch = {x.v, -1, rigid.code};
  ch.certified = unique && certified_choice(upper_of(x.v, x.r), lower_of(x.v, x.r));
  return ch.certified;
}

// pdd2_accel(A, B, 1) where the superset's choice is certified but its exact first unknown
// (superset_depth.h's TieBand: the exact first is one of the band's candidates): every band
// entry's case-2 value v_i with its interval [lo_i, hi_i] (value_bounds.h); the exact value,
// some entry's, lies in [min lo_i, max hi_i], and so does the choice's computed value v_0. When
// that interval passes certified_choice, v_0 meets definitions §8 (accel_over_ties' argument on
// the candidate list). A translated copy's pairs: a face and its copy's, a rounding apart.
// Where the values differ (a grid against its copy shifted along its cube diagonals: exact ties
// of delta² between candidates whose case-2 values differ), the exact first itself
// (exact_first_of_band), and its own value when that passes certified_choice alone.
class Accel1OverBand final : public TieBandTest {
 public:
  bool agree(const TieBand& band, const FilterBounds& fb) override {
    double lo_min = kInf, hi_max = 0.0;
    for (int i = 0; i < band.count; ++i) {
      const Valued x = deformable_valued(band.entry[i], fb);
      if (!(x.v > 0.0) || !(x.v < kInf)) return false;
      const double lo = lower_of(x.v, x.r);
      lo_min = std::min(lo_min, lo >= 0.0 ? lo : 0.0);
      hi_max = std::max(hi_max, upper_of(x.v, x.r));
      if (!certified_choice(hi_max, lo_min)) return disagreed = true, false;
      if (i == 0) value = x.v;
    }
    return band.count > 0;
  }
  bool settle(const TieBand& band, const FilterBounds& fb) override {
    const int first = exact_first_of_band(band);
    if (first < 0) return false;
    const Valued x = deformable_valued(band.entry[first], fb);
    if (!(x.v > 0.0) || !(x.v < kInf) || !certified_choice(upper_of(x.v, x.r), lower_of(x.v, x.r))) return false;
    value = x.v;
    return true;
  }
  double value = 0.0;  // the exact first's case-2 value (any entry's where they all agree)

 private:
  // The band entry that is the list's exact first (stable delta order, definitions §5's case 3),
  // or −1: over the band pair's integer frame, each edge-pair entry's orientation kept only
  // where definitions §3's rule, decided exactly (classify_edge_pair_framed), makes it a
  // candidate (a decided pair has the one orientation; an undecidable pair both, + first); the
  // candidates in canonical order (faces FV then VF, then EE:a:b by a, b), and the first least
  // exact delta² among them (first_least_delta2_framed). −1 without a frame, or for an entry
  // that is no candidate the band could hold (a parallel or colinear pair: the band has none).
  static int exact_first_of_band(const TieBand& band) {
    detail::IntegerFrame frame(band.A, band.B);
    if (!frame.usable()) return -1;
    int order[TieBand::kMax], key[TieBand::kMax], n = 0;
    DirectionLabel labels[TieBand::kMax];
    for (int i = 0; i < band.count; ++i) {
      const DirectionLabel& l = band.entry[i].label;
      int k = l.kind == ContactKind::FV ? l.a : 4 + l.a;
      DirectionLabel as_listed = l;
      if (l.kind == ContactKind::EE) {
        const EdgePairClass c = detail::classify_edge_pair_framed(frame, l.a, l.b);
        if (c.kind != EdgePairKind::Generic) return -1;
        const bool plus = l.orientation == EdgeOrientation::Plus;
        if ((c.side == EdgePairSide::Keep && !plus) || (c.side == EdgePairSide::Flip && plus)) continue;
        if (c.side != EdgePairSide::Undecidable) as_listed.orientation = EdgeOrientation::Decided;
        k = 8 + 2 * (6 * l.a + l.b) + (plus ? 0 : 1);
      }
      int at = n++;  // insertion by key
      for (; at > 0 && key[at - 1] > k; --at) key[at] = key[at - 1], order[at] = order[at - 1], labels[at] = labels[at - 1];
      key[at] = k, order[at] = i, labels[at] = as_listed;
    }
    const int first = detail::first_least_delta2_framed(frame, labels, n);
    return first < 0 ? -1 : order[first];
  }
};

}  // namespace

double case2_upper(const TetVertices& As, const TetVertices& Bs, const Candidate& c) {
  const Valued x = deformable_valued(c, filter_bounds(As, Bs));
  double v = 0;
  return certified_choice(upper_of(x.v, x.r), lower_of(x.v, x.r)) ? x.v
         : accel1_compensated(As, Bs, c, v)                       ? v
                                                                  : INFINITY;
}

bool relaxed_compensated(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                         double& value, double& r, DirectionSolution& s, double hA[4], double hB[4],
                         const std::array<double, 3>& lo) {
  detail::CompensatedHeights h;
  Valued x;
  // At a minimiser where another vertex meets the plane (the shallow certificate's tilt, or the
  // exact minimiser's normal rounded: a contact made by rounding, its minimiser where pieces
  // meet) that vertex's margin is ~0: a pattern whose margins are unsure is bracketed
  // (valued_on_heights' bracket: its value's interval covers the vertex on either side).
  if (!detail::compensated_heights_along(A, B, v, h, lo) ||
      !valued_on_heights(h, 0u, 0u, QpKind::Relaxed, x, s, nullptr, true))
    return false;
  value = x.v, r = x.r;
  for (int i = 0; i < 4; ++i) hA[i] = h.hA[i], hB[i] = h.hB[i];
  return true;
}

bool relaxed_upper_compensated(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                               double& upper) {
  detail::CompensatedHeights h;
  Valued x;
  DirectionSolution s;
  if (!detail::compensated_heights_along(A, B, v, h) ||
      !valued_on_heights(h, 0u, 0u, QpKind::Relaxed, x, s, nullptr, true) || !(x.r < 1) || !(x.v >= 0))
    return false;
  upper = upper_of(x.v, x.r) * (1 + 8 * kUnitRoundoff);
  return upper >= DBL_MIN;
}

bool compensated_value(const TetVertices& A, const TetVertices& B, const Candidate& c, QpKind kind, double& value,
                       double& r, bool* bracketed) {
  Valued x;
  VerifiedPattern p;
  p.atA = p.atB = ~0u;
  if (!compensated_valued(A, B, c, kind, x, &p)) return false;
  value = x.v, r = x.r;
  if (bracketed) *bracketed = p.atA == ~0u;
  return true;
}

bool value_on_heights(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, QpKind kind, double& value,
                      double& r, bool* bracketed) {
  Valued x;
  DirectionSolution s;
  VerifiedPattern p;
  p.atA = p.atB = ~0u;
  if (!valued_on_heights(h, conA, conB, kind, x, s, &p, true)) return false;
  value = x.v, r = x.r;
  if (bracketed) *bracketed = p.atA == ~0u;
  return true;
}

bool rigid_and_accel1(const TetVertices& As, const TetVertices& Bs, Choice& rigid, Candidate& c,
                      Choice& accel1) {
  bool unique = false;
  Accel1OverBand band;
  if (!rigid_superset(As, Bs, rigid, &c, &unique, &band)) return false;
  if (band.accepted) {
    accel1 = {band.value, -1, rigid.code};
    accel1.certified = true;
    return true;
  }
  if (accel1_of_rigid(rigid, c, unique, filter_bounds(As, Bs), accel1)) return true;
  double v = 0;
  if (!unique || !accel1_compensated(As, Bs, c, v)) return false;
  accel1 = {v, -1, rigid.code};
  accel1.certified = true;
  return true;
}

namespace {

// The sweep's variants, as function objects (inlined): `solve` the QP (false: infeasible, not
// in the family), `bound` its solver bound. The sweep computes a bound only where it is used.
struct StaticVariant {
  static constexpr QpKind kKind = QpKind::Static;
  bool solve(const Candidate& c, DirectionSolution& s) const {
    if (c.label.orientation != EdgeOrientation::Decided) return false;  // definitions §5
    s = solve_static(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
    return true;
  }
  // C tied to A's constrained heights (FV, EE): only B's statuses; C_A empty (VF): wide.
  SolverBound bound(const Candidate& c, const DirectionSolution& s) const {
    return c.conA ? solver_bound(c, s, 0u, 0xFu & ~c.conB)
                  : SolverBound{kSolverDisplacementCoeff, detail::max_height(c)};
  }
};
struct DeformableVariant {
  static constexpr QpKind kKind = QpKind::Deformable;
  bool solve(const Candidate& c, DirectionSolution& s) const {
    s = solve_deformable(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
    return true;
  }
  SolverBound bound(const Candidate& c, const DirectionSolution& s) const {
    return solver_bound(c, s, 0xFu & ~c.conA, 0xFu & ~c.conB);
  }
};
struct RelaxedVariant {
  static constexpr QpKind kKind = QpKind::Relaxed;
  bool solve(const Candidate& c, DirectionSolution& s) const {
    s = solve_relaxed(c.hA, c.hB);
    return true;
  }
  SolverBound bound(const Candidate& c, const DirectionSolution& s) const {
    return solver_bound(c, s, 0xFu, 0xFu);
  }
};

// The exact values of refine.h, per variant (false: not in the family).
bool exact_static(const detail::ExactCandidate& c, detail::Q& v) {
  if (c.label.orientation != EdgeOrientation::Decided) return false;  // infeasible (definitions §5)
  v = detail::exact_static_value(c);
  return true;
}
bool exact_deformable(const detail::ExactCandidate& c, detail::Q& v) {
  v = detail::exact_deformable_value(c);
  return true;
}
bool exact_relaxed(const detail::ExactCandidate& c, detail::Q& v) {
  v = detail::exact_relaxed_value(c);
  return true;
}

// A lower bound of an exact value from a computed one (NaN or a failed bound: 0, i.e. nothing
// can be certified against it).
inline double safe_lower(double v, double r) {
  const double lo = lower_of(v, r);
  return lo >= 0.0 ? lo : 0.0;
}

// One evaluated candidate whose root bound is deferred: its solution and what the cheap bound
// test needs (n.n, Hm, degree class). evaluate() gives valued()'s value, root_bound() its
// root bound (0 when infeasible), deferred_small() qp_root_rel_small (value_bounds.h) with the
// wide solver bound, which covers the tight one: when true, lower_of(v, root_bound) >
// kSmallQpLower · v.
struct Pending {
  DirectionSolution s;
  double nn, Hm;
  bool feasible, parallel, own_bounds;  // the candidate's class (degree_bounds_of)
  double own_eh, own_en;
};
template <class Variant>
double evaluate(const Candidate& c, const Variant& variant, Pending& e) {
  e.feasible = variant.solve(c, e.s);
  e.nn = c.nn;
  e.Hm = detail::max_height(c);
  e.parallel = c.parallel;
  e.own_bounds = c.own_bounds;
  e.own_eh = c.own_eh;
  e.own_en = c.own_en;
  return e.feasible ? e.s.cost / (20.0 * c.nn) : kInf;  // valued()'s value
}
template <class List, class Variant>
double evaluate(const List& set, int i, const Variant& variant, Pending& e) {
  return evaluate(candidate(set, i), variant, e);
}
template <class Variant>
double root_bound(const Candidate& c, const FilterBounds& fb, const Variant& variant, const Pending& e) {
  if (!e.feasible) return 0.0;
  const SolverBound sb = variant.bound(c, e.s);
  return qp_root_rel(e.s.cost, c.nn, sb.H, degree_bounds_of(fb, c), sb.coeff);
}
template <class List, class Variant>
double root_bound(const List& set, int i, const Variant& variant, const Pending& e) {
  return e.feasible ? root_bound(candidate(set, i), set.fb, variant, e) : 0.0;
}
inline bool deferred_small(const Pending& e, const FilterBounds& fb) {
  return e.feasible && qp_root_rel_small(e.s.cost, e.nn, e.Hm, degree_bounds_of(fb, e));
}
// The lower bound of an evaluated candidate whose double value is not finite: +inf when it is
// not in the family (infeasible: case 1's undecidable edge pairs); else 0, nothing known. A
// feasible candidate's value is not finite when its n.n is 0 or below the double range: a face
// of A through a vertex ~1e17 times farther than the others (the rescaled pair's differences
// to it absorb the near vertices' coordinates and the normal comes out 0), whose exact value
// may be the minimum.
inline double infeasible_or_unknown(const Pending& e) { return e.feasible ? 0.0 : kInf; }

// A contender's interval for refine_tight (refine.h): compensated_valued's where it applies,
// else the double one (none, r = inf, where the doubles give no finite value: a face normal
// that underflows beside a far vertex); false when the candidate is not in the family.
template <class List, class Variant>
bool tight_interval(const List& set, int i, const Variant& variant, double& v, double& r, bool tight = true) {
  const Candidate c = candidate(set, i);
  Valued x;
  if (tight && set.A && compensated_valued(*set.A, *set.B, c, Variant::kKind, x)) {
    v = x.v, r = x.r;
    return true;
  }
  Pending p;
  v = evaluate(c, variant, p);
  if (!p.feasible) return false;  // (case 1's undecidable edge pairs)
  r = v < kInf ? root_bound(c, set.fb, variant, p) : kInf;  // (inf, NaN: no bound, an exact value is due)
  return true;
}

// sweep's choice where the double pass cannot certify one (sweep, "Below the doubles'
// resolution"): the hint (value v, root bound r) the only candidate evaluated, every other one
// bounded by coeff·delta² as sweep bounds a skipped one, the minimum refined (refine.h). Every
// contender's delta² lies below the doubles' error here, so its bound is the exact one the
// candidate set knows (delta2_known_lower: the contacts made by rounding's near-normal
// candidates, ~11 a pair, of which ~4.7 stay contenders on a grid against its copy moved by a
// cell) where it knows one.
template <class List, class Variant, class ExactValue>
Choice refined_below_doubles(const List& set, double coeff, int hint, double v, double r, Variant variant,
                             ExactValue exact_value) {
  Choice ch;
  ch.index = hint;
  ch.value = v;
  ch.code = label_code(set, hint);
  auto lower = [&](int i) {
    if (i != hint && along_face_of_A(set, i) >= 0) return kInf;
    const double lo = i == hint ? safe_lower(v, r) : coeff * safe_lower(delta2(set, i), detail::rigid_rel(set, i));
    return std::max(lo, coeff * delta2_known_lower(set, i));
  };
  auto interval = [&](int i, double& x, double& e) { return tight_interval(set, i, variant, x, e); };
  auto no_tie_order = [](const int*, int) { return -1; };
  const double hi = upper_of(v, r);
  if (!detail::refine_tight(set, lower, hi, interval, exact_value, no_tie_order, ch))
    detail::refine_minimum(set, lower, hi, exact_value, ch);
  return ch;
}

// Sweep in canonical order, skipping candidates whose lower bound coeff·delta² cannot reach
// the best value so far (header) and the edge pairs along a face of A (header: each is at or
// above its face's FV candidate, which precedes it), then pick the first tied minimum. List:
// CandidateSet or QuickCandidates (same candidates, same order, same values).
// definitions §8 (value_bounds.h): an evaluated candidate's exact value is >= lower_of(v, its QP
// bound); a skipped one's is >= coeff · lower_of(delta², its rigid bound) (the pruning bound,
// proven in the header, applied to the exact delta, or to the candidate set's known lower bound of
// it: delta2_known_lower); one along a face of A is >= its face's,
// which is bounded among the others, so it adds nothing to the minimum of the lower bounds.
template <class List, class Variant, class ExactValue>
Choice sweep(const List& set, double coeff, int hint, Variant variant, ExactValue exact_value) {
  if (!usable(set)) return {};
  // r[i], the root bound valued() would give, only where it is used (below).
  double v[kMaxCandidates], r[kMaxCandidates];
  Pending p[kMaxCandidates];
  bool done[kMaxCandidates];
  int evaluated[kMaxCandidates], n_evaluated = 0;  // the indices with done[i], any order
  double best = kInf, threshold = kInf;  // threshold = tie_threshold(best) >= the final one
  auto evaluate_ = [&](int i) {
    v[i] = evaluate(set, i, variant, p[i]);
    done[i] = true;
    evaluated[n_evaluated++] = i;
  };
  auto bound = [&](int i) { r[i] = root_bound(set, i, variant, p[i]); };
  // Below the doubles' resolution: where the hint's interval (the rigid choice's) has no correct
  // digit (r >= 1: lower bound 0), lo_min <= 0 below and no double choice can be certified (a
  // value of an intersecting pair is > 0): the refinement decides. Where moreover the hint's
  // delta² lies far below the doubles' u L² (a contact made by rounding: ~1e-34 of L², where
  // the contenders' double intervals all reach 0 and prune nothing), the double pass is not
  // run: the refinement bounds every other candidate by delta² alone, as a skipped one is
  // (~8 QPs and their bounds saved, ~10% of such a pair's time). (Elsewhere the pass's QP
  // bounds leave the refinement fewer contenders than delta² would.)
  bool below_doubles = false, hint_bounded = false;
  if (hint >= 0 && hint < set.count) {
    evaluate_(hint);
    best = v[hint];
    threshold = tie_threshold(best, set.tie_kappa);
    if (set.A && v[hint] < kInf && std::fabs(delta2(set, hint)) <= 0x1p-20 * set.fb.deg2 &&
        !deferred_small(p[hint], set.fb)) {  // (deferred_small: r < 0.02)
      bound(hint);
      hint_bounded = true;
      below_doubles = !(r[hint] < 1);
    }
  }
  if (below_doubles) return refined_below_doubles(set, coeff, hint, v[hint], r[hint], variant, exact_value);
  for (int i = 0; i < set.count; ++i) {
    if (i == hint) continue;
    const double bound = coeff * delta2(set, i);
    if (!(bound <= threshold) | (along_face_of_A(set, i) >= 0)) {
      v[i] = kInf;
      done[i] = false;
      continue;
    }
    evaluate_(i);
    if (v[i] < best) {
      best = v[i];
      threshold = tie_threshold(best, set.tie_kappa);
    }
  }
  Choice ch;
  ch.index = first_tied_minimum(v, set.count, set.tie_kappa);
  if (ch.index < 0) return {};  // no finite value (NaN): not certified
  ch.value = v[ch.index];
  ch.code = label_code(set, ch.index);
  auto lower = [&](int i) {
    if (done[i] && !(v[i] < kInf)) return infeasible_or_unknown(p[i]);
    if (!done[i] && along_face_of_A(set, i) >= 0) return kInf;
    const double lo = done[i] ? safe_lower(v[i], r[i]) : coeff * safe_lower(delta2(set, i), detail::rigid_rel(set, i));
    return std::max(lo, coeff * delta2_known_lower(set, i));
  };
  // lo_min = the minimum of lower(i) over every candidate, starting from the choice's own.
  // An evaluated candidate is left out, its bound not computed, when deferred_small shows
  // lower(i) > kSmallQpLower · v > lo_min so far; a skipped one when certify.h's cheap test
  // shows lower(i) > kSmallRigidLower · coeff delta² > lo_min so far. Either way lower(i)
  // exceeds a value >= the final lo_min, so it cannot be the minimum, and the minimum is
  // unchanged (min is exact in any order). Only the few others pay the divisions and square
  // roots of their bounds. (v = +inf or NaN: infeasible, lower = +inf, never the minimum; or
  // a feasible candidate whose double value is not finite, lower = 0: no certificate, and the
  // refinement below takes it among its contenders.)
  // (Without short-circuits where the test is almost always true: its branch predicts well.)
  // (The choice is an evaluated candidate unless every evaluated value is NaN; then r = 0
  // gives hi = +inf and no certificate, as any bound would.)
  if (!done[ch.index]) r[ch.index] = 0.0;
  else if (!(ch.index == hint && hint_bounded)) bound(ch.index);
  double lo_min = lower(ch.index);
  for (int j = 0; j < n_evaluated; ++j) {
    const int i = evaluated[j];
    if (i == ch.index) continue;
    if (!(v[i] < kInf)) {
      lo_min = std::min(lo_min, infeasible_or_unknown(p[i]));
      continue;
    }
    if ((kSmallQpLower * v[i] > lo_min) & deferred_small(p[i], set.fb)) continue;
    bound(i);
    const double lo = lower(i);
    lo_min = lo < lo_min ? lo : lo_min;
  }
  for (int i = 0; i < set.count; ++i) {
    if (done[i] | (along_face_of_A(set, i) >= 0) |
        (int(detail::kSmallRigidLower * (coeff * delta2(set, i)) > lo_min) &
         int(detail::rigid_rel_small(set, i))))  // (all evaluated: no branch)
      continue;
    const double lo = lower(i);
    lo_min = lo < lo_min ? lo : lo_min;
  }
  const double hi = upper_of(ch.value, r[ch.index]);
  ch.certified = certified_choice(hi, lo_min);
  // Not certified: the contenders exactly (refine.h), with every bound. A skipped candidate's
  // exact value is >= lower(i) (the pruning bound); an infeasible one (v = +inf) is not in the
  // family.
  // Compensated intervals first (refine.h's refine_tight: the contenders of a shallow contact,
  // whose double bounds carry u L^3 beside a value ~|n| depth, certify there at ~1 us each);
  // the rationals for every contender (refine_minimum) where that fails. The near ties the
  // intervals leave are not ordered: each is within definitions §8 of the exact minimum (the
  // contract lets either side be named), and the first in canonical order is named. (An exact
  // order, so that the label is the exact engine's, takes expansions of degree 10 for each tied
  // pair: a third of the depth stage on a grid against its copy shifted by whole cells of a
  // decimal size, whose contenders tie a rounding apart.)
  if (!ch.certified) {
    for (int j = 0; j < n_evaluated; ++j) bound(evaluated[j]);
    auto interval = [&](int i, double& v, double& r) { return tight_interval(set, i, variant, v, r); };
    auto no_tie_order = [](const int*, int) { return -1; };
    if (!detail::refine_tight(set, lower, hi, interval, exact_value, no_tie_order, ch))
      detail::refine_minimum(set, lower, hi, exact_value, ch);
  }
  return ch;
}

// The sweep over a quick list's lanes, before its edge list exists (quick_lanes), pruned by the
// dual lower bounds of qp_lower_bound.h: lo[e] <= the exact value of entry e (+inf: not a
// candidate of the family). Entries are visited as in sweep(): first the one of smallest bound
// (the hint), then in canonical order (entries ascend in it) every entry whose bound is <=
// tie_threshold(best so far); the choice is the first tied minimum of the evaluated values in
// canonical order, as sweep()'s. definitions §8: an evaluated entry's exact value is >= lower_of(v,
// its QP bound), a skipped one's >= lo[e]; certified as in sweep. Returns false (nothing decided)
// when the choice is not certified or more than kMaxLaneEvaluated entries pass (B deep inside a
// much larger A: many candidates of nearly equal value): the caller then builds the list and
// runs sweep(), which can refine (refine.h).
constexpr int kMaxLaneEvaluated = 40;  // (16 sent 3% of the nested family back to the list)

// lane_sweep's choice b where its own double interval is too wide to certify it: a shallow
// contact (a mesh against its copy shifted by a small offset: depth ~1e-4 of the size, the
// double bound ~u L / depth relative, ~1e-9 of the value). Its interval on compensated heights
// (compensated_valued, refine.h's tight intervals) against every other entry's bound as
// lane_sweep has them: the other evaluated entries' own double intervals (each bounded here,
// none deferred: their bounds were compared with b's double one), `above` for the entries
// above threshold0 and lo for the ones of `pass` not evaluated; an evaluated entry whose double
// interval reaches below b's, its compensated one too (both bound its exact value: the larger
// lower bound holds). Certified as sweep's choices are (the value within its bounds, every
// other exact value above the contract's share of it); false where the compensated heights do
// not apply or that fails (the caller builds the list: refine.h).
template <class Variant>
bool shallow_choice(const QuickCandidates& q, Variant variant, const int* idx, int n, const double* v, Pending* p,
                    int b, const int* pass, int m, double above, const double* lo, Choice& ch) {
  Valued x;
  if (!q.A || !compensated_valued(*q.A, *q.B, entry_candidate(q, idx[b]), Variant::kKind, x)) return false;
  const double hi = upper_of(x.v, x.r);
  double lo_min = std::min(safe_lower(x.v, x.r), above);
  for (int j = 0; j < n; ++j) {
    if (j == b) continue;
    if (!(v[j] < kInf)) {
      if (p[j].feasible) return false;  // (infeasible_or_unknown: nothing known)
      continue;
    }
    double l = safe_lower(v[j], root_bound(entry_candidate(q, idx[j]), q.fb, variant, p[j]));
    // an entry tied with b (the same depth along the same plane: a face and the edge pairs in
    // it) whose double interval reaches below b's: its compensated one
    Valued y;
    if (!certified_choice(hi, l) && compensated_valued(*q.A, *q.B, entry_candidate(q, idx[j]), Variant::kKind, y))
      l = std::max(l, safe_lower(y.v, y.r));
    lo_min = std::min(lo_min, l);
  }
  for (int j = 0; j < m; ++j) {
    bool evaluated = false;
    for (int t = 0; t < n; ++t) evaluated |= idx[t] == pass[j];
    if (!evaluated) lo_min = std::min(lo_min, lo[pass[j]]);
  }
  if (!certified_choice(upper_of(x.v, x.r), lo_min)) return false;
  ch = Choice{x.v, -1, entry_label_code(q, idx[b])};
  ch.certified = ch.refined = true;
  return true;
}
template <class Variant>
bool lane_sweep(const QuickCandidates& q, const detail::QpLowerBounds& bounds, Variant variant, Choice& ch) {
  constexpr int kN = detail::kQpEntries;
  const double* lo = bounds.lo;
  int idx[kMaxLaneEvaluated], n = 0;
  double v[kMaxLaneEvaluated];
  Pending p[kMaxLaneEvaluated];
  const double lmin = minimum(lo, kN);
  if (!(lmin < kInf)) return false;  // (bounds are never NaN)
  int first = 0;
  while (!(lo[first] == lmin)) ++first;  // (lmin is one of them)
  auto evaluate_ = [&](int e) {
    v[n] = evaluate(entry_candidate(q, e), variant, p[n]);
    idx[n++] = e;
  };
  evaluate_(first);
  double best = v[0], threshold = tie_threshold(best, q.tie_kappa);
  const double threshold0 = threshold;
  // The entries with lo <= threshold0 (often only `first`), in canonical order; of those, the
  // ones still <= the threshold when reached are evaluated. The others are skipped, their
  // smallest lo is `split.above`.
  const detail::QpSplit split = detail::split_at(bounds, threshold0);
  int pass[kN], m = 0;
  if (split.below > (lo[first] <= threshold0 ? 1 : 0))
    for (int e = 0; e < kN; ++e)
      if ((lo[e] <= threshold0) & (e != first)) pass[m++] = e;
  for (int j = 0; j < m; ++j) {
    const int e = pass[j];
    if (!(lo[e] <= threshold)) continue;
    if (n == kMaxLaneEvaluated) return false;
    evaluate_(e);
    if (v[n - 1] < best) {
      best = v[n - 1];
      threshold = tie_threshold(best, q.tie_kappa);
    }
  }
  const double vmin = minimum(v, n), tie = tie_threshold(vmin, q.tie_kappa);
  int b = -1;  // the first tied minimum in canonical order
  for (int j = 0; j < n; ++j)
    if (v[j] <= tie && (b < 0 || idx[j] < idx[b])) b = j;
  if (b < 0 || !(v[b] < kInf)) return false;
  const double r_b = root_bound(entry_candidate(q, idx[b]), q.fb, variant, p[b]);
  double lo_min = safe_lower(v[b], r_b);
  // the other evaluated entries (deferred_small as in sweep), then every skipped entry's lo:
  // those above threshold0 (one vectorised pass), and those of `pass` not evaluated
  for (int j = 0; j < n; ++j) {
    if (j == b) continue;
    if (!(v[j] < kInf)) {
      if (p[j].feasible) return false;  // (infeasible_or_unknown: the list's sweep refines it)
      continue;
    }
    if ((kSmallQpLower * v[j] > lo_min) & deferred_small(p[j], q.fb)) continue;
    const double l = safe_lower(v[j], root_bound(entry_candidate(q, idx[j]), q.fb, variant, p[j]));
    lo_min = l < lo_min ? l : lo_min;
  }
  lo_min = split.above < lo_min ? split.above : lo_min;
  for (int j = 0; j < m; ++j) {
    const int e = pass[j];
    bool evaluated = false;
    for (int t = 0; t < n; ++t) evaluated |= idx[t] == e;
    if (!evaluated) lo_min = lo[e] < lo_min ? lo[e] : lo_min;
  }
  if (certified_choice(upper_of(v[b], r_b), lo_min)) {
    ch = Choice{v[b], -1, entry_label_code(q, idx[b])};
    ch.certified = true;
    return true;
  }
  return shallow_choice(q, variant, idx, n, v, p, b, pass, m, split.above, lo, ch);
}

// delta²'s certified interval per candidate of a list, [safe_lower(delta², rigid_rel),
// upper_of(delta², rigid_rel)] (no upper bound: +inf), each computed on first use: case 3's
// passes (accel_of's separation test, accel_over_ties, accel_by_directions, accel_contenders)
// ask for the same candidates' bounds in turn.
template <class List>
class DeltaBounds {
 public:
  explicit DeltaBounds(const List& set) : set_(set) {}
  double lower(int i) { return fill(i), lo_[i]; }
  double upper(int i) { return fill(i), hi_[i]; }

 private:
  void fill(int i) {
    if (done_[i]) return;
    const double r = detail::rigid_rel(set_, i);
    lo_[i] = safe_lower(delta2(set_, i), r);
    hi_[i] = upper_of(delta2(set_, i), r);
    if (!(hi_[i] >= 0.0)) hi_[i] = kInf;  // (0 times an infinite bound: no bound)
    done_[i] = true;
  }
  const List& set_;
  double lo_[kMaxCandidates], hi_[kMaxCandidates];
  bool done_[kMaxCandidates] = {};
};

// The first k candidates in ascending delta order (tie band); -1 entries never written: returns
// the number found (< min(k, count) only on NaN input).
template <class List>
int accel_order_of(const List& set, int k, int* out) {
  double d[kMaxCandidates];
  for (int i = 0; i < set.count; ++i) d[i] = delta2(set, i);
  const int m = k < set.count ? k : set.count;
  for (int r = 0; r < m; ++r) {
    const int i = first_tied_minimum(d, set.count, set.tie_kappa);
    if (i < 0) return r;
    out[r] = i;
    d[i] = kInf;  // taken
  }
  return m;
}

// Case 3 refined (refine.h): the exact first k in ascending exact delta² (stable in canonical
// order), then the exact minimum of their case-2 values. `order` (m entries): the double path's
// first k when they are certainly the exact first k (separated), else nullptr: then the
// contenders are the candidates whose certified lower bound of delta² is <= hi_chosen (the
// largest certified upper bound among the double path's k choices). At least k candidates have
// exact delta² <= hi_chosen, so the exact k-th smallest is <= hi_chosen and every non-contender
// is strictly above it: the exact first k are the first k of the contenders in exact order.
constexpr int kMaxAccelContenders = kAccelWide + detail::kMaxRefined;

// The minimum of the case-2 values of chosen[0..k) (the exact first k), certified in doubles as
// in accel_of (the choice's value within its bounds, every other one's lower bound above it);
// false, ch unchanged, when the bounds cannot certify it.
// Each value's interval is the double one, or (tight) tight_interval's: compensated heights
// where they apply (the exact first k of a contact made by rounding, ~1e-17 of the size deep).
// Called with the double intervals first, so that what doubles certify keeps their bits.
template <class List>
bool certify_first_k(const List& set, const int* chosen, int k, Choice& ch, bool tight) {
  const DeformableVariant variant;
  double v[kMaxCandidates], r[kMaxCandidates];
  int best = -1;
  for (int j = 0; j < k; ++j) {
    if (!tight_interval(set, chosen[j], variant, v[j], r[j], tight) || !(v[j] > 0.0)) return false;
    if (best < 0 || v[j] < v[best]) best = j;
  }
  if (best < 0) return false;
  double lo_min = safe_lower(v[best], r[best]);
  for (int j = 0; j < k; ++j) {
    const double l = safe_lower(v[j], r[j]);
    lo_min = l < lo_min ? l : lo_min;
  }
  if (!certified_choice(upper_of(v[best], r[best]), lo_min)) return false;
  ch = Choice{v[best], chosen[best], label_code(set, chosen[best])};
  ch.certified = true;
  return true;
}

// pos[0..first): the first `first` of the contenders idx[0..n) (canonical order) in ascending
// exact delta², exact ties in canonical order (a stable insertion sort keeping the first `first`
// only: a later contender enters when strictly below the last kept; for first = 1 the first
// least one, certify.h's first_least_delta2), compared by expansions (depth_parts_exact,
// compare_delta2_exact: D_a² n_b.n_b against D_b² n_a.n_a, no division) where their
// certified intervals do not already order them; false when the expansions cannot decide a
// comparison (pos then unspecified).
template <class List>
bool exact_delta_order(const List& set, const int* idx, int n, int first, int* pos) {
  if (first == 1) {  // (compensated depths and exact directions first: certify.h)
    pos[0] = detail::first_least_delta2(set, idx, n);
    return pos[0] >= 0;
  }
  // Each contender's certified interval (compensated heights where they apply, tight_delta.h)
  // orders two contenders whose intervals are apart; the expansions' parts only the others.
  double lo[kMaxCandidates], hi[kMaxCandidates];
  for (int j = 0; j < n; ++j) {
    double v = 0, r = kInf;
    const bool tight = detail::tight_delta2(set, idx[j], v, r) && r < 1;
    lo[j] = tight ? lower_of(v, r) : 0.0, hi[j] = tight ? upper_of(v, r) : kInf;
    if (!(lo[j] <= hi[j])) lo[j] = 0.0, hi[j] = kInf;  // (NaN: no interval)
  }
  std::vector<ExactDepthParts> parts;  // (~0.8 KB each, up to kMaxCandidates: on the heap)
  // over the pair's integer frame where it has one (integer_depth.h), else by expansions
  detail::IntegerFrame frame(*set.A, *set.B);
  const bool framed = frame.usable();
  detail::FramedDepth fd[kMaxCandidates];
  bool have_fd[kMaxCandidates] = {};
  if (!framed) parts.resize(n);
  auto compare = [&](int a, int b) -> std::optional<int> {  // sign(delta²_a − delta²_b)
    if (hi[a] < lo[b]) return -1;
    if (hi[b] < lo[a]) return 1;
    if (framed) {
      for (const int x : {a, b})
        if (!have_fd[x] && !(have_fd[x] = detail::framed_depth(frame, unpack_label(label_code(set, idx[x])), fd[x])))
          return std::nullopt;
      return detail::compare_framed_delta2(fd[a], fd[b]);
    }
    for (const int x : {a, b})
      if (!parts[x].ok && !(parts[x] = depth_parts_exact(*set.A, *set.B, unpack_label(label_code(set, idx[x])))).ok)
        return std::nullopt;
    return compare_delta2_exact(parts[a], parts[b]);
  };
  int have = 0;  // pos[0..have): the first min(j, first) of idx[0..j) in exact order
  for (int j = 0; j < n; ++j) {
    if (have == first) {  // full: j enters only strictly below the last (ties stay after)
      const std::optional<int> s = compare(j, pos[have - 1]);
      if (!s) return false;
      if (*s >= 0) continue;
      --have;
    }
    int t = have++;
    pos[t] = j;
    while (t > 0) {
      const std::optional<int> s = compare(pos[t], pos[t - 1]);
      if (!s) return false;
      if (*s >= 0) break;  // not below: stays after (stable)
      std::swap(pos[t], pos[t - 1]);
      --t;
    }
  }
  return true;
}

// The contenders of refine_accel without an order (canonical order, their number returned):
// the candidates whose certified lower bound of delta² is <= U, U the k-th least upper bound
// (<= hi_chosen). At least k candidates have exact delta² <= U, so every candidate above U
// is not among the exact first k. The bounds are the double ones, and tighter ones for the
// candidates taken in ascending lower bound until the next one exceeds U: on a contact made by
// rounding every double bound is wide (hi_chosen ~ the pair's size), the tight ones leave the
// few candidates of that depth instead of every candidate. The tight ones are the exact depth
// and n.n over the pair's integer frame, rounded (integer_depth.h's framed_delta2), where it
// has one: the exact order of the contenders (exact_delta_order) takes the same depths again
// from their memo; else tight_delta2's, on compensated heights.
template <class List>
int accel_contenders(const List& set, int k, double hi_chosen, DeltaBounds<List>& db, int* idx) {
  int order[kMaxCandidates], m = 0;
  double lo[kMaxCandidates], up_k[kAccelWide];  // up_k: the k least upper bounds, ascending
  for (int i = 0; i < set.count; ++i) {
    const double x = db.lower(i);
    if (x > hi_chosen) continue;
    int t = m++;
    for (; t > 0 && x < lo[order[t - 1]]; --t) order[t] = order[t - 1];
    order[t] = i, lo[i] = x;
  }
  int have = 0;
  double U = hi_chosen;
  std::optional<detail::IntegerFrame> frame;
  if (set.A) frame.emplace(*set.A, *set.B);
  for (int j = 0; j < m && !(lo[order[j]] > U); ++j) {
    const int i = order[j];
    double v = 0, r = kInf;
    detail::FramedDepth fd;
    const bool framed = frame && frame->usable() &&
                        detail::framed_depth(*frame, unpack_label(label_code(set, i)), fd) &&
                        detail::framed_delta2(*frame, fd, v, r);
    if (!framed && set.A) detail::tight_delta2(set, i, v, r);
    if (!(r < 1)) continue;
    lo[i] = std::max(lo[i], lower_of(v, r));
    const double up = upper_of(v, r);
    int t = have < k ? have++ : k;
    for (; t > 0 && up < up_k[t - 1]; --t)
      if (t < k) up_k[t] = up_k[t - 1];
    if (t < k) up_k[t] = up;
    if (have == k) U = std::min(U, up_k[k - 1]);
  }
  int n = 0;
  for (int i = 0; i < set.count; ++i)
    if (!(db.lower(i) > U) && !(lo[i] > U)) idx[n++] = i;
  return n;
}

// Case 3 refined: the exact first k in ascending exact delta² (stable in canonical order), then
// the minimum of their case-2 values. `order` (m entries): the double path's first k when they
// are certainly the exact first k (separated), else nullptr: then the contenders are the
// candidates whose certified lower bound of delta² is <= hi_chosen (the largest certified upper
// bound among the double path's k choices). At least k candidates have exact delta² <=
// hi_chosen, so the exact k-th smallest is <= hi_chosen and every non-contender is strictly above
// it: the exact first k are the first k of the contenders in exact order. That order is taken
// by expansions (exact_delta_order) where they decide it, else in rationals; the value is
// certified in doubles over the exact first k where the bounds allow (certify_first_k), else
// the exact minimum of their case-2 values is evaluated (refine.h: refined).
// Any number of contenders is ordered by expansions (a symmetric aligned pair, e.g. a Kuhn grid
// against its copy shifted by half a cell along (1, 1, 1), ties 17 candidates exactly); only
// the rationals' order, ~20 µs a contender, is limited to kMaxAccelContenders.
template <class List>
void refine_accel(const List& set, int k, const int* order, int m, double hi_chosen, DeltaBounds<List>& db,
                  Choice& ch) {
  constexpr int kMax = kMaxCandidates;
  int idx[kMax], n = 0;
  if (order) {
    for (int r = 0; r < m; ++r) idx[n++] = order[r];
  } else {
    n = accel_contenders(set, k, hi_chosen, db, idx);
  }
  if (!set.A || n == 0) return;
  const int kk = k < n ? k : n;
  int pos[kMax];
  bool sorted = order != nullptr;
  if (!sorted && exact_delta_order(set, idx, n, kk, pos)) {
    sorted = true;
    int chosen[kMax];
    for (int r = 0; r < kk; ++r) chosen[r] = idx[pos[r]];
    if (certify_first_k(set, chosen, kk, ch, false) || certify_first_k(set, chosen, kk, ch, true)) return;
  }
  if (!sorted && n > kMaxAccelContenders) return;  // (the exact path is as cheap)
  if (order)
    for (int j = 0; j < n; ++j) pos[j] = j;
  const detail::ExactFrame f = detail::exact_frame(*set.A, *set.B);
  std::vector<detail::ExactCandidate> c(n);
  auto exact_candidate_of = [&](int j) -> const detail::ExactCandidate& {
    if (c[j].nn == 0) c[j] = detail::exact_candidate(f, unpack_label(label_code(set, idx[j])));
    return c[j];
  };
  if (!sorted) {
    for (int j = 0; j < n; ++j) pos[j] = j;
    std::vector<detail::Q> d(n);
    for (int j = 0; j < n; ++j) d[j] = detail::exact_delta2(exact_candidate_of(j));
    // idx ascends (canonical order), so a stable sort keeps exact ties in canonical order
    std::stable_sort(pos, pos + n, [&d](int a, int b) { return d[a] < d[b]; });
  }
  detail::Q best;
  int bi = -1;
  for (int r = 0; r < kk; ++r) {
    const detail::Q v = detail::exact_deformable_value(exact_candidate_of(pos[r]));
    if (bi < 0 || v < best || (v == best && idx[pos[r]] < idx[bi])) {
      best = v;
      bi = pos[r];
    }
  }
  bool ok = true;
  const double d = detail::rounded_value(detail::unscaled(f, best, 2), ok);
  if (!ok || !(d > 0.0)) return;
  ch.value = d;
  ch.index = idx[bi];
  ch.code = label_code(set, idx[bi]);
  ch.certified = ch.refined = true;
}

// Case 3. definitions §8: the chosen candidates must be exactly the first k of the exact order
// (every chosen exact delta² strictly below every other one; exact ties are left to the exact
// path), and the minimum of their QP values is certified as in sweep.
// Case 3 when the first k are not certainly known (exact or near ties in delta², common on
// aligned pairs): the exact first k lie among the contenders P = {i : certified lower bound of
// delta²_i <= hi_chosen} (refine_accel's argument), so the exact value min over the first k of
// the case-2 values lies in [min over P of their lower bounds, max over P of their upper
// bounds]. When that interval passes certified_choice, any value in it meets definitions §8:
// the computed choice's value (itself in it) is reported. (No label is reported for case 3.)
template <class List>
void accel_over_ties(const List& set, double hi_chosen, DeltaBounds<List>& db, Choice& ch) {
  if (!(hi_chosen < kInf)) return;
  const DeformableVariant variant;
  double lo_min = kInf, hi_max = 0.0;
  int n = 0;
  for (int i = 0; i < set.count; ++i) {
    if (db.lower(i) > hi_chosen) continue;
    if (++n > kAccelWide + detail::kMaxRefined) return;
    Pending p;
    const Candidate c = candidate(set, i);
    const double v = evaluate(c, variant, p);
    if (!p.feasible || !(v > 0.0)) return;
    const double r = root_bound(c, set.fb, variant, p);
    const double lo = safe_lower(v, r), hi = upper_of(v, r);
    lo_min = lo < lo_min ? lo : lo_min;
    hi_max = hi > hi_max ? hi : hi_max;
    if (!certified_choice(hi_max, lo_min)) return;
  }
  if (n > 0 && ch.value >= lo_min && ch.value <= hi_max) ch.certified = true;
}

// Case 3 when the first k are not certainly known, by exact directions: the contenders P (as
// in accel_over_ties) sorted by their computed delta² are split into a prefix S whose certified
// upper bounds all lie below the certified lower bounds of the rest T, and T, whose oriented
// normals all point exactly the same way (same_direction_exact): their exact delta are then
// equal, so the exact order (stable in canonical order) puts S first, then T in canonical order.
// When |S| < k <= |P|, the exact first k are S and the first k − |S| of T in canonical order, and
// their case-2 minimum is certified as in accel_of. (Aligned pairs: a face and the edge pairs
// of its plane give one direction exactly.)
template <class List>
void accel_by_directions(const List& set, int k, double hi_chosen, DeltaBounds<List>& db, Choice& ch) {
  if (!set.A || !(hi_chosen < kInf)) return;
  constexpr int kMax = kAccelWide + detail::kMaxRefined;
  int P[kMax], n = 0;
  double lo[kMaxCandidates], hi[kMaxCandidates];
  for (int i = 0; i < set.count; ++i) {
    lo[i] = db.lower(i);
    hi[i] = db.upper(i);
    if (lo[i] > hi_chosen) continue;
    if (n == kMax) return;
    P[n++] = i;
  }
  if (n < k) return;
  int sorted[kMax];
  for (int j = 0; j < n; ++j) sorted[j] = P[j];
  std::stable_sort(sorted, sorted + n, [&set](int a, int b) { return delta2(set, a) < delta2(set, b); });
  for (int s = 0; s < k; ++s) {
    // prefix S = sorted[0..s): certainly below the rest
    double hi_s = 0.0, lo_t = kInf;
    for (int j = 0; j < s; ++j) hi_s = hi[sorted[j]] > hi_s ? hi[sorted[j]] : hi_s;
    for (int j = s; j < n; ++j) lo_t = lo[sorted[j]] < lo_t ? lo[sorted[j]] : lo_t;
    if (s > 0 && !(hi_s < lo_t)) continue;
    // T = sorted[s..n) in canonical order (P ascends): one exact direction?
    int T[kMax], m = 0;
    for (int j = 0; j < n; ++j) {
      bool in_s = false;
      for (int q = 0; q < s; ++q) in_s = in_s || sorted[q] == P[j];
      if (!in_s) T[m++] = P[j];
    }
    const bool one = detail::one_exact_direction(set, T, m);  // (certify.h)
    if (!one) continue;
    int chosen[kMax], c = 0;
    for (int j = 0; j < s; ++j) chosen[c++] = sorted[j];
    for (int j = 0; c < k; ++j) chosen[c++] = T[j];
    if (!certify_first_k(set, chosen, k, ch, false)) certify_first_k(set, chosen, k, ch, true);
    return;
  }
}

inline Choice rigid_of_list(const CandidateSet& set) { return rigid_pd2_reusing(set); }
inline Choice rigid_of_list(const QuickCandidates& q) { return rigid_pd2(q); }

// k = 1 when the double path cannot certify the first in delta² order: the exact first is the
// rigid depth's exact choice (definitions §4 and §5: the same candidates in the same canonical
// order, ties to the first; delta > 0 on every candidate of an intersecting pair, so delta²
// orders as delta). Where rigid_pd2 certifies that its choice is it (exact_first: on aligned
// pairs its contenders' compensated intervals and exact direction ties settle what the double
// bounds leave tied), the case-2 value there is certified as a separated choice's: on its own
// interval in doubles, on compensated heights (accel1_compensated), else exactly (refine_accel).
// `given`: the caller's rigid_pd2 of the same list, or null (computed here, or the one
// rigid_pd2 left for this pair: rigid_depth.h's rigid_pd2_reusing).
template <class List>
bool accel1_at_rigid(const List& set, const Choice* given, double hi_chosen, DeltaBounds<List>& db, Choice& ch) {
  const Choice rigid = given ? *given : rigid_of_list(set);
  if (!rigid.certified || !rigid.exact_first || rigid.index < 0 || !set.A) return false;
  const int first = rigid.index;
  if (certify_first_k(set, &first, 1, ch, false)) return true;
  double value = 0;
  if (accel1_compensated(*set.A, *set.B, candidate(set, first), value)) {
    ch = Choice{value, first, label_code(set, first)};
    ch.certified = true;
    return true;
  }
  refine_accel(set, 1, &first, 1, hi_chosen, db, ch);
  return ch.certified;
}

template <class List>
Choice accel_of(const List& set, int k, const Choice* rigid = nullptr) {
  if (!usable(set) || k <= 0) return {};
  int order[kMaxCandidates];
  const int m = accel_order_of(set, k, order);
  if (m <= 0) return {};
  bool chosen[kMaxCandidates] = {};
  double hi_chosen = 0.0;
  for (int r = 0; r < m; ++r) {
    chosen[order[r]] = true;
    const double hi = upper_of(delta2(set, order[r]), detail::rigid_rel(set, order[r]));
    hi_chosen = !(hi <= hi_chosen) ? (hi >= 0.0 ? hi : kInf) : hi_chosen;  // (NaN: no bound)
  }
  bool separated = hi_chosen < kInf;
  DeltaBounds<List> db(set);
  // (certify.h: kSmallRigidLower delta² > hi_chosen with a small bound has lower bound
  // > hi_chosen, so the exact test below would pass: it is skipped)
  // k = 1: an edge pair along a face f of A is never the exact first: FV:f has its exact delta
  // and precedes it, and FV:f (index f < 8, tested first) is the choice, or certainly after it
  // (then so is the pair), or has ended the loop.
  for (int i = 0; i < set.count && separated; ++i)
    if (!chosen[i] && !(k == 1 && along_face_of_A(set, i) >= 0) &&
        !(detail::kSmallRigidLower * delta2(set, i) > hi_chosen && detail::rigid_rel_small(set, i)) &&
        !(db.lower(i) > hi_chosen))
      separated = false;
  const DeformableVariant variant;
  double v[kMaxCandidates];  // (k is any count on the lists' interface)
  Pending p[kMaxCandidates];
  // An edge pair along a face of A whose face is among the k: at or above the face in value and
  // after it in canonical order (along_face_of_A), so neither the minimum nor its first: left
  // out (as not in the family: +inf, no lower bound).
  for (int r = 0; r < m; ++r) {
    const int i = order[r];
    const int f = along_face_of_A(set, i);
    if (f >= 0 && chosen[f]) {
      v[r] = kInf;
      p[r].feasible = false;
      continue;
    }
    v[r] = evaluate(set, i, variant, p[r]);
  }
  const double vmin = minimum(v, m);
  int best = -1;  // among ties, the first in canonical order
  for (int r = 0; r < m; ++r)
    if (ties_with_min(v[r], vmin, set.tie_kappa) && (best < 0 || order[r] < order[best])) best = r;
  if (best < 0) return {};
  // lo_min = the minimum of safe_lower(v, root bound) over the k, as in sweep: the choice's
  // own first; another one's bound only when deferred_small cannot show its lower bound above
  // kSmallQpLower · v > lo_min so far (then it is not the minimum). (NaN v: never left out.)
  // (A value that is not finite: infeasible_or_unknown, case 2 having no infeasible candidate.)
  const double rel_best = root_bound(set, order[best], variant, p[best]);
  double lo_min = v[best] < kInf ? safe_lower(v[best], rel_best) : infeasible_or_unknown(p[best]);
  for (int r = 0; r < m; ++r) {
    if (r == best) continue;
    if (!(v[r] < kInf)) {
      lo_min = std::min(lo_min, infeasible_or_unknown(p[r]));
      continue;
    }
    if ((kSmallQpLower * v[r] > lo_min) & deferred_small(p[r], set.fb)) continue;
    const double lo = safe_lower(v[r], root_bound(set, order[r], variant, p[r]));
    lo_min = lo < lo_min ? lo : lo_min;
  }
  Choice ch{v[best], order[best], label_code(set, order[best])};
  ch.certified = separated && certified_choice(upper_of(v[best], rel_best), lo_min);
  // k = 1 along the exact rigid direction (separated): compensated heights before rationals
  // (accel1_compensated; rigid_and_accel1 takes the same step, so both paths agree bit for bit)
  if (!ch.certified && k == 1 && m == 1 && separated && set.A) {
    const Candidate c = candidate(set, order[0]);
    double value = 0;
    if (accel1_compensated(*set.A, *set.B, c, value)) ch.value = value, ch.certified = true;
  }
  if (!ch.certified && !separated) accel_over_ties(set, hi_chosen, db, ch);
  if (!ch.certified && !separated) accel_by_directions(set, k, hi_chosen, db, ch);
  if (!ch.certified && !separated && k == 1 && accel1_at_rigid(set, rigid, hi_chosen, db, ch)) return ch;
  if (!ch.certified) refine_accel(set, k, separated ? order : nullptr, m, hi_chosen, db, ch);
  return ch;
}

}  // namespace

double static_value(const Candidate& c) {
  if (c.label.orientation != EdgeOrientation::Decided) return kInf;  // infeasible (definitions §5)
  const DirectionSolution s = solve_static(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
  return s.cost / (20.0 * c.nn);
}

double deformable_value(const Candidate& c) {
  const DirectionSolution s =
      solve_deformable(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
  return s.cost / (20.0 * c.nn);
}

double relaxed_value(const Candidate& c) { return solve_relaxed(c.hA, c.hB).cost / (20.0 * c.nn); }

Choice pdd2_static(const CandidateSet& set, int hint) {
  return sweep(set, kStaticBoundCoeff, hint, StaticVariant{}, exact_static);
}
Choice pdd2(const CandidateSet& set, int hint) {
  return sweep(set, kDeformableBoundCoeff, hint, DeformableVariant{}, exact_deformable);
}
Choice pdd2_relaxed(const CandidateSet& set, int hint) {
  return sweep(set, kDeformableBoundCoeff, hint, RelaxedVariant{}, exact_relaxed);
}
Choice pdd2_static(const QuickCandidates& q, int hint) {
  return sweep(q, kStaticBoundCoeff, hint, StaticVariant{}, exact_static);
}
Choice pdd2(const QuickCandidates& q, int hint) {
  return sweep(q, kDeformableBoundCoeff, hint, DeformableVariant{}, exact_deformable);
}
Choice pdd2_relaxed(const QuickCandidates& q, int hint) {
  return sweep(q, kDeformableBoundCoeff, hint, RelaxedVariant{}, exact_relaxed);
}

Choice pdd2_accel(const CandidateSet& set, int k, const Choice* rigid) { return accel_of(set, k, rigid); }
Choice pdd2_accel(const QuickCandidates& q, int k) { return accel_of(q, k); }

void deformed_positions(const TetVertices& A, const TetVertices& B, const Candidate& c,
                        Positions<double>& qA, Positions<double>& qB) {
  const DirectionSolution s =
      solve_deformable(side_of(c.hA, c.conA), side_of(c.hB, c.conB));
  for (int i = 0; i < 4; ++i) {
    const double tA = displacement_below(c.hA[i], c.conA >> i & 1u, s) / c.nn;
    const double tB = displacement_above(c.hB[i], c.conB >> i & 1u, s) / c.nn;
    for (int k = 0; k < 3; ++k) {
      qA[i][k] = A[i][k] + tA * c.n[k];
      qB[i][k] = B[i][k] + tB * c.n[k];
    }
  }
}

namespace {
// compensated_positions on heights h: compensated_heights' (words) or expansion_heights'.
bool positions_on(const TetVertices& A, const TetVertices& B, const Candidate& c, const detail::CompensatedHeights& h,
                  bool words, Positions<double>& qA, Positions<double>& qB) {
  Valued x;
  DirectionSolution s;
  VerifiedPattern p;
  if (!valued_on_heights(h, c.conA, c.conB, QpKind::Deformable, x, s, &p)) return false;
  const double N = std::sqrt(h.nn), rho = std::sqrt(3.0) * h.e_n / N;
  if (!(rho <= 0.01)) return false;
  // Each vertex's displacement T along n* (T n*/(n*.n*) in space) within dT of the exact one:
  // the double solver's (above), else compensated_displacements' (a bound each: on the double
  // words of the label's heights, or on the given heights)
  const double dT = kSolverDisplacementCoeffTight * kUnitRoundoff * p.Ha + 8 * p.e_act;
  double T[2][4], eT[2][4];
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < 4; ++i) {
      const bool at = ((t ? p.atB : p.atA) >> i & 1u) != 0;
      T[t][i] = at ? s.c - (t ? h.hB[i] : h.hA[i]) : -(t ? s.sumB : s.sumA), eT[t][i] = dT;
    }
  double Q = 0, dA[4][3], dB[4][3];
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) Q = std::fmax(Q, std::fabs((t ? B : A)[i][k]));
  auto error = [&] {
    double eta = 0;
    for (int t = 0; t < 2; ++t)
      for (int i = 0; i < 4; ++i)
        eta = std::fmax(eta, (eT[t][i] + (std::fabs(T[t][i]) + eT[t][i]) * (4 * rho + 8 * kUnitRoundoff)) / N);
    return eta;
  };
  if (!(error() * 1.01 <= 2 * kUnitRoundoff * Q)) {
    detail::CompensatedDisplacements d;
    const detail::AtPlane at{p.atA, p.atB};
    if (!(words ? detail::compensated_displacements(A, B, c.label, at, d) : detail::compensated_displacements(h, at, d)))
      return false;
    for (int i = 0; i < 4; ++i) T[0][i] = d.tA[i], eT[0][i] = d.eA[i], T[1][i] = d.tB[i], eT[1][i] = d.eB[i];
    if (!(error() * 1.01 <= 2 * kUnitRoundoff * Q)) return false;  // (NaN: false)
  }
  for (int t = 0; t < 2; ++t)
    for (int i = 0; i < 4; ++i) {
      const double w = T[t][i] / h.nn;
      for (int k = 0; k < 3; ++k) (t ? dB : dA)[i][k] = w * h.n[k];
    }
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) qA[i][k] = A[i][k] + dA[i][k], qB[i][k] = B[i][k] + dB[i][k];
  return true;
}
}  // namespace

bool compensated_positions(const TetVertices& A, const TetVertices& B, const Candidate& c,
                           Positions<double>& qA, Positions<double>& qB) {
  detail::CompensatedHeights h;
  if (detail::compensated_heights(A, B, c, h) && positions_on(A, B, c, h, true, qA, qB)) return true;
  // heights by expansions: parallel and nearly parallel edge pairs (no double words, or double
  // words ~10 u off of themselves), and depths below the double words' u² term (compensated_valued)
  return detail::expansion_heights(A, B, c, h) && positions_on(A, B, c, h, false, qA, qB);
}

namespace {
// The sweeps' hint: the rigid direction's index (first tied minimum of delta²). Only the index
// is needed — the sweeps' results do not depend on the hint (header: it only seeds the
// pruning) — so rigid_pd2's certification and refinement are not run for it.
template <class List>
int rigid_hint(const List& s) {
  return s.count > 0 ? first_tied_minimum(s.delta_sq, s.count, s.tie_kappa) : -1;
}

// `lanes(q, ch)` on the quick lanes when it decides, else f on the quick list, else f on the full
// candidate set (all on the stack), on the rescaled pair; the exact path when the choice is not
// certified (hot_path.h).
template <class F, class Pick, class Lanes>
Choice on_list(const TetVertices& A, const TetVertices& B, F f, Pick pick, Lanes lanes) {
  return detail::certified_hot_path(
      A, B,
      [&](const TetVertices& As, const TetVertices& Bs, Choice& ch) {
        QuickCandidates q;
        if (quick_lanes(As, Bs, q)) {
          if (lanes(q, ch)) return true;
          quick_edge_list(q);
          ch = f(q);
          return true;
        }
        BuildStatus status;
        const CandidateSet& set = build_candidates_reusing(As, Bs, status, q.count == 8 ? &q : nullptr);
        if (status != BuildStatus::Ok || !set.intersecting) return false;
        ch = f(set);
        return true;
      },
      pick);
}

template <class Variant>
bool lanes_of(const QuickCandidates& q, Variant variant, detail::QpCase which, Choice& ch) {
  detail::QpLowerBounds lb;
  detail::qp_lower_bounds(q, which, lb);
  return lane_sweep(q, lb, variant, ch);
}
}  // namespace

bool pdd2_static_lanes(const QuickCandidates& q, Choice& ch) {
  return lanes_of(q, StaticVariant{}, detail::QpCase::Static, ch);
}
bool pdd2_lanes(const QuickCandidates& q, Choice& ch) {
  return lanes_of(q, DeformableVariant{}, detail::QpCase::Deformable, ch);
}
bool pdd2_relaxed_lanes(const QuickCandidates& q, Choice& ch) {
  return lanes_of(q, RelaxedVariant{}, detail::QpCase::Deformable, ch);
}

Choice pdd2_static_choice(const TetVertices& A, const TetVertices& B) {
  return on_list(
      A, B, [](const auto& s) { return pdd2_static(s, rigid_hint(s)); },
      [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
        l = r.pdd2_static_dir;
        return r.pdd2_static;
      },
      [](const QuickCandidates& q, Choice& ch) { return pdd2_static_lanes(q, ch); });
}
Choice pdd2_choice(const TetVertices& A, const TetVertices& B) {
  return on_list(
      A, B, [](const auto& s) { return pdd2(s, rigid_hint(s)); },
      [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
        l = r.pdd2_dir;
        return r.pdd2;
      },
      [](const QuickCandidates& q, Choice& ch) { return pdd2_lanes(q, ch); });
}
Choice pdd2_relaxed_choice(const TetVertices& A, const TetVertices& B) {
  return on_list(
      A, B, [](const auto& s) { return pdd2_relaxed(s, rigid_hint(s)); },
      [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
        l = r.pdd2_relaxed_dir;
        return r.pdd2_relaxed;
      },
      [](const QuickCandidates& q, Choice& ch) { return pdd2_relaxed_lanes(q, ch); });
}
namespace {

// rigid_superset_scaled's outputs on a raw pair with everything pdd2_accel(A, B, 1)'s first try
// asks of it: `first` as rigid_pd2_choice takes them (rigid_depth.h), the chosen candidate, its
// `unique`, the scaled pair's extent and the tie band's verdict.
struct SharedSuperset {
  SupersetFirstTry first;
  Candidate c;
  bool unique = false;
  double extent = 0;
  Accel1OverBand band;
};

// What accel1_choice's first branch learns, for the run's routes on the same rescaled pair:
// where the kernel ran and `unique` failed, rigid_and_accel1 there computes the same choice and
// fails too (it needs `unique`), as it does where the first branch's compensated value failed
// on that pair (compensated_tried); with unresolved edge pairs the quick list declines.
// (Either route skipped is only time saved: the next one computes the same value.)
struct Accel1Routes {
  bool ran = false, unique = false, unresolved = false, compensated_tried = false;
};

// The first branch of pdd2_accel(A, B, 1) on the raw pair (superset_depth.h: the same lanes,
// geometry and `unique` as on the rescaled pair; filter_bounds of the rescaled pair is
// filter_bounds_of_extent of the kernel's extent: the same maxima, minima and differences) and,
// where the double heights cannot certify the value along the unique pick, rigid_and_accel1's
// compensated value on the same rescaled pair (power_scaled's, 2^e). `shared` (optional): the
// first try's kernel and choice already run on this pair, taken instead of running them again.
bool accel1_first_branch(const TetVertices& A, const TetVertices& B, const SharedSuperset* shared, Accel1Routes& st,
                         Choice& ch, int& e) {
  Choice rigid;
  Candidate c;
  double extent = 0;
  Accel1OverBand own;
  const Accel1OverBand* band = &own;
  if (shared) {
    const SupersetFirstTry& f = shared->first;
    // no certified choice: what the recall below gives after rigid_pd2_choice(A, B, &f)
    if (f.ran && !(f.done && f.ch.certified)) return st.unresolved = f.unresolved, st.ran = true, false;
    st.ran = f.ran, st.unresolved = f.unresolved, e = f.e;
    if (!f.done) return false;
    rigid = f.ch, c = shared->c, st.unique = shared->unique, extent = shared->extent, band = &shared->band;
  } else {
    // rigid_pd2 just found no certified choice on this pair: the same run would not either
    if (recall_uncertified_superset(A, B, st.unresolved)) return st.ran = true, false;
    if (!rigid_superset_scaled(A, B, rigid, e, &c, &st.unique, &extent, &st.ran, &st.unresolved, &own)) return false;
  }
  if (band->accepted) {
    ch = {band->value, -1, rigid.code};
    ch.certified = true;
    return true;
  }
  if (accel1_of_rigid(rigid, c, st.unique, filter_bounds_of_extent(extent), ch)) return true;
  if (!st.unique) return false;
  const detail::ScaledPair sp = detail::power_scaled(A, B);
  if (!sp.finite || !sp.exact || sp.e != e) return false;
  st.compensated_tried = true;
  double v = 0;
  if (!accel1_compensated(sp.A, sp.B, c, v)) return false;
  ch = {v, -1, rigid.code};
  ch.certified = true;
  return true;
}

// The run of pdd2_accel(A, B, 1) on the rescaled pair after its first branch: rigid_and_accel1,
// the quick list, the candidate set (`given`: build_candidates(As, Bs) where the caller has it,
// else built here; `given_rigid`: rigid_pd2(*given), or null).
bool accel1_run(const TetVertices& As, const TetVertices& Bs, const Accel1Routes& st, const CandidateSet* given,
                const Choice* given_rigid, Choice& ch) {
  Choice rigid;
  Candidate c;
  if (!(st.ran && !st.unique) && !st.compensated_tried && rigid_and_accel1(As, Bs, rigid, c, ch)) return true;
  QuickCandidates q;
  if (!(st.ran && st.unresolved) && quick_candidates(As, Bs, q)) {
    ch = pdd2_accel(q, 1);
    return true;
  }
  if (given) {
    ch = pdd2_accel(*given, 1, given_rigid);
    return true;
  }
  BuildStatus status;
  const CandidateSet& set = build_candidates_reusing(As, Bs, status, q.count == 8 ? &q : nullptr);
  if (status != BuildStatus::Ok || !set.intersecting) return false;
  ch = pdd2_accel(set, 1);
  return true;
}

// pdd2_accel_choice(A, B, 1); `shared` as for accel1_first_branch.
Choice accel1_choice(const TetVertices& A, const TetVertices& B, const SharedSuperset* shared) {
  auto pick = [](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
    l = std::nullopt;
    return r.pdd2_accel1;
  };
  Accel1Routes st;
  return detail::fused_hot_path(
      A, B, [&](Choice& ch, int& e) { return accel1_first_branch(A, B, shared, st, ch, e); },
      [&](const TetVertices& As, const TetVertices& Bs, Choice& ch) { return accel1_run(As, Bs, st, nullptr, nullptr, ch); },
      pick);
}

}  // namespace

void rigid_and_accel1_choices(const TetVertices& A, const TetVertices& B, Choice& rigid, Choice& accel1) {
  SharedSuperset s;
  SupersetFirstTry& f = s.first;
  f.done = rigid_superset_scaled(A, B, f.ch, f.e, &s.c, &s.unique, &s.extent, &f.ran, &f.unresolved, &s.band);
  rigid = rigid_pd2_choice(A, B, &f);
  accel1 = accel1_choice(A, B, &s);
}

void rigid_and_accel1_of_rescaled(const TetVertices& As, const TetVertices& Bs, detail::SupersetLanes& K,
                                  const CandidateSet& set, const Choice& set_rigid, bool with_accel1, Choice& rigid,
                                  Choice& accel1) {
  rigid = accel1 = Choice{};
  if (!with_accel1) {
    Choice ch;
    if (rigid_superset_of_kernel(K, ch) && ch.certified) rigid = ch;
    return;
  }
  SharedSuperset s;
  SupersetFirstTry& f = s.first;
  f.ran = true;
  f.done = rigid_superset_of_kernel(K, f.ch, &s.c, &s.unique, &f.unresolved, &s.band);
  s.extent = K.extent;
  if (f.done && f.ch.certified) rigid = f.ch;
  Accel1Routes st;
  int e = 0;
  if (accel1_first_branch(As, Bs, &s, st, accel1, e) && accel1.certified) return;
  accel1 = Choice{};
  accel1_run(As, Bs, st, &set, &set_rigid, accel1);
}

Choice pdd2_accel_choice(const TetVertices& A, const TetVertices& B, int k) {
  auto pick = [k](const PairResult<double>& r, std::optional<DirectionLabel>& l) {
    l = std::nullopt;
    return k == 1 ? r.pdd2_accel1 : r.pdd2_accel6;
  };
  if (k != 1 && k != kAccelWide) return {};  // the exact path reports the paper's k = 1 and 6
  if (k == 1) return accel1_choice(A, B, nullptr);
  return on_list(A, B, [k](const auto& s) { return pdd2_accel(s, k); }, pick,
                 [](const QuickCandidates&, Choice&) { return false; });
}

}  // namespace pdd::fast
