// deformable_depth.h — deformable penetration depth PD_d² over all candidates (definitions §5).
//
// Input:  a CandidateSet of an intersecting pair (candidate_directions.h).
// Output: Choice{value = PD_d², index and label of the argmin candidate, the first in canonical
//         order among ties}:
//   pdd2_static   case 1, A static (paper Sec. IV); undecidable EE directions are infeasible and
//                 skipped (definitions §5).
//   pdd2          case 2, both deform (paper Sec. V, eq. 10).
//   pdd2_relaxed  case 2 with every constraint an inequality.
//   pdd2_accel    case 3 (paper Sec. VI): the case-2 optimum over the first k candidates in
//                 ascending delta order (stable in canonical order; tie_tolerance.h).
// Per direction the QP is solved in closed form by direction_qp.h: value = F / (20 n.n).
//
// Exact pruning (lower bounds, proven here). Dropping constraints can only lower a minimum, so
// every variant's optimum along n is >= that of the relaxed problem restricted to the highest
// vertex a of A and the lowest vertex b of B, D = a − b > 0. One tetrahedron whose single vertex
// must move by x (others free) costs (1/20) min{t1² + 3 t² + (t1 + 3t)² : t1 >= x}: the free
// optimum t = −S = −t1/4 gives (5/4) t1²/20 = x²/16 (n-scaled: x²/(16 n.n)).
//   case 2 / relaxed:  split D = x + y between the two tets: min (x² + y²)/16 = D²/32
//                      ==> value(n) >= D²/(32 n.n) = delta²/32.
//   case 1:            A static, the plane is at or above a, so B's vertex moves by >= D
//                      ==> value(n) >= D²/(16 n.n) = delta²/16.
// The functions over raw tetrahedra (pdd2_static_choice, pdd2_choice, pdd2_relaxed_choice) prune
// with much stronger bounds first: qp_lower_bound.h's dual bounds (the k = m = 1 case is the
// bound above), computed for all candidates at once on the quick list's lanes, so that ~1.7
// candidates per sweep are solved instead of ~8; the list and the sweeps below are their
// fallback when that sweep cannot certify its choice.
// Edge pairs along a face of A (proof). Let EE:a:b have edge a on A's face f and eB.N_f = 0
// exactly (candidate_directions.h's along_face): its oriented n is a positive multiple of FV:f's
// outward normal (the face's third vertex w has g = 0, the opposite vertex i has g < 0), so both
// QPs see the same heights, A's face u, v, w at H and i below. EE:a:b constrains u, v (not w)
// and B's edge x, y to the plane; FV:f constrains u, v, w and frees all of B. Claim: in every
// variant value(EE:a:b) >= value(FV:f), and FV:f precedes it in canonical order, so it is never
// the first tied minimum and the minimum is the same without it.
//   relaxed: every constraint an inequality, so the QP depends on the oriented n alone: equal.
//   case 1:  A is static and C_A is not empty in either, so the plane is A's face plane, H, in
//            both; EE:a:b's feasible set is FV:f's with x, y moreover at the plane: >=.
//   case 2:  let (T, C) be EE:a:b's optimum, tau = C − H. For fixed C the tetrahedra's costs
//            separate; A's part minimises |T|² + (sum T)² with T_u = T_v = tau, T_w <= tau,
//            T_i <= tau_i = C − H_i > tau (stationarity: a free vertex off the plane has
//            T = −S, S = sum T). If w is off the plane, T_w = −S < tau: with i off the plane
//            too, S = 2 tau − 2S, S = 2 tau/3 and −2 tau/3 < tau needs tau > 0; with i at its
//            bound, S = (2 tau + tau_i)/2 and its multiplier needs tau_i + S <= 0, i.e.
//            3 tau_i <= −2 tau, while −S < tau needs tau_i > −4 tau: with tau_i > tau, no tau
//            satisfies both.
//            So tau <= 0 puts w at the plane: EE:a:b's optimum is feasible for FV:f, >=.
//            If tau > 0: FV:f with its plane at H and A at rest (feasible: A's face at H, i
//            below) costs B's least cost over B above H, g(H); g is nondecreasing in the plane
//            (a higher plane only shrinks B's feasible set), so g(H) <= g(C) <= B's part of
//            EE:a:b's optimum (its B is above C, x and y at it) <= EE:a:b's value.
// A candidate is skipped when its bound exceeds tie_threshold(best value so far) (tie_tolerance.h),
// so it can neither be the minimum nor tie with it (the threshold of the final minimum is lower). Starting from a good direction
// (the rigid one, `hint`) makes most bounds bite.
#pragma once

#include "certification/compensated_heights.h"
#include "kernel/candidate_directions.h"
#include "kernel/quick_candidates.h"
#include "kernel/rigid_depth.h"
#include "pdd/pair_result.h"
#include "qp/direction_qp.h"

namespace pdd::fast {

inline constexpr int kAccelWide = 6;  // pdd2_accel6: the paper's "first six directions" (definitions §5)
inline constexpr double kDeformableBoundCoeff = 1.0 / 32.0;  // case 2 and relaxed, see above
inline constexpr double kStaticBoundCoeff = 1.0 / 16.0;      // case 1, see above

// PD_d² along one candidate; +inf when infeasible (case 1 on an undecidable EE direction).
double static_value(const Candidate& c);
double deformable_value(const Candidate& c);
double relaxed_value(const Candidate& c);

// `hint`: index evaluated first to seed the pruning (e.g. rigid_pd2(set).index), or −1.
// The lists must be built on a pair rescaled by power_scale.h, as every caller in the engine
// does: the `certified` verdicts assume it (a list of an unscaled pair ~2^-174 across, inside
// filter_bounds.h's range, would certify values 2e-4 off: the QP's values underflow).
Choice pdd2_static(const CandidateSet& set, int hint = -1);
Choice pdd2(const CandidateSet& set, int hint = -1);
Choice pdd2_relaxed(const CandidateSet& set, int hint = -1);
// `rigid` (pdd2_accel): rigid_pd2(set) when the caller has it (k = 1 may use its choice), else
// null: computed where needed. The result does not depend on it.
Choice pdd2_accel(const CandidateSet& set, int k, const Choice* rigid = nullptr);

// The same over the hot-path list (quick_candidates): identical results.
Choice pdd2_static(const QuickCandidates& q, int hint = -1);
Choice pdd2(const QuickCandidates& q, int hint = -1);
Choice pdd2_relaxed(const QuickCandidates& q, int hint = -1);
Choice pdd2_accel(const QuickCandidates& q, int k);

// The lane sweeps of the functions over raw tetrahedra below, on a quick_lanes result of a
// rescaled pair (quick_candidates.h), pruned by qp_lower_bound.h's dual bounds: true with a
// certified choice (index −1, label code set), false when they cannot decide (then the list's
// or the set's sweeps above, which can refine). solve_pair uses them too, so that both report
// the same values and labels.
bool pdd2_static_lanes(const QuickCandidates& q, Choice& ch);
bool pdd2_lanes(const QuickCandidates& q, Choice& ch);
bool pdd2_relaxed_lanes(const QuickCandidates& q, Choice& ch);

// The first try of pdd2_accel(A, B, 1) on a pair rescaled by power_scale.h (As, Bs):
// rigid_superset's rigid choice and its candidate `c` (superset_depth.h), and `accel1`, the
// case-2 value along c. True when both are certified (the rigid direction is the exact one,
// `unique`, and accel1's own interval meets definitions §8); false: the caller takes the candidate
// list. On false, rigid.certified says that rigid and c still hold rigid_superset's certified
// choice and candidate (only `unique` or accel1's interval failed): case2_upper's input.
bool rigid_and_accel1(const TetVertices& As, const TetVertices& Bs, Choice& rigid, Candidate& c,
                      Choice& accel1);

// pdd2_global's start where the rigid direction is not certainly the exact one (aligned pairs,
// whose parallel faces tie), from rigid_and_accel1's certified rigid choice and its candidate c
// on the rescaled pair: the case-2 value along c where its own interval meets definitions §8,
// else +inf. Case 2 along c >= the relaxed value along c >= pdd2_global (definitions §5, §9).
double case2_upper(const TetVertices& As, const TetVertices& Bs, const Candidate& c);

// The relaxed value along a double normal v (A -> B; pdd2_global's, global_depth.h) where the
// double heights cannot certify it (a contact far shallower than the pair): on the heights of
// compensated_heights_along, each within its own u, the status pattern verified with certain
// margins and the root bound r counting only the vertices at the plane (compensated_valued's
// argument, deformable_depth.cpp). value, r (value_bounds.h: the exact value lies in
// [lower_of(value, r), upper_of(value, r)]), the solution s of that pattern and the heights
// (relative to A's vertex highest along v) it was computed on. False when not applicable or
// the pattern is neither verified nor bracketed. Precondition: a pair rescaled by power_scale.h.
// With `lo`: along the double-word normal v + lo (compensated_heights_along's). A pattern with
// unsure margins is bracketed (valued_on_heights' bracket: r covers the vertex on either side,
// s the pattern with it at the plane), as where v lies at a minimiser at which another vertex
// reaches the plane.
bool relaxed_compensated(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                         double& value, double& r, DirectionSolution& s, double hA[4], double hB[4],
                         const std::array<double, 3>& lo = {0, 0, 0});

// A certified upper bound on the exact relaxed value along the double normal v on the heights
// of relaxed_compensated, unsure margins bracketed (valued_on_heights' bracket) whether or not
// v is a double word: the exact value lies within upper_of(value, r), and the factor 1 + 8u
// covers upper_of's three roundings. False when not applicable (or the bound is below the
// normal range). Precondition: a pair rescaled by power_scale.h.
bool relaxed_upper_compensated(const TetVertices& A, const TetVertices& B, const std::array<double, 3>& v,
                               double& upper);

// Which per-direction QP (direction_qp.h) a compensated evaluation solves.
enum class QpKind { Static, Deformable, Relaxed };

// Candidate c's value of that QP where its double heights cannot certify it (the contenders of
// refine.h's refine_tight): on compensated_heights.h's heights (expansion_heights' for parallel
// and nearly parallel edge pairs), the status pattern verified by certain margins or, where a
// margin is at its threshold exactly (degenerate contacts), the value bracketed by weak duality
// (deformable_depth.cpp, valued_on_heights). value, r (value_bounds.h: the exact value lies in
// [lower_of(value, r), upper_of(value, r)]); `bracketed` (optional): whether it was bracketed.
// False when not applicable. Precondition: a pair rescaled by power_scale.h.
bool compensated_value(const TetVertices& A, const TetVertices& B, const Candidate& c, QpKind kind, double& value,
                       double& r, bool* bracketed = nullptr);

// The same on given heights h (each within its e_i of the exact one, the normal within e_n;
// constrained vertices conA, conB sharing one height a side).
bool value_on_heights(const detail::CompensatedHeights& h, unsigned conA, unsigned conB, QpKind kind, double& value,
                      double& r, bool* bracketed = nullptr);

// Case-2 deformed positions x + (T/n.n) n attaining deformable_value(c) (direction_qp.h).
void deformed_positions(const TetVertices& A, const TetVertices& B, const Candidate& c,
                        Positions<double>& qA, Positions<double>& qB);

// The same positions where the double heights cannot give them (a contact far shallower than
// the pair: its displacements have no correct digit in doubles), on compensated_heights.h's
// heights: each coordinate q within 3u max(Q, |q|) of the exact positions P + d* for c's exact
// direction (Q the pair's largest coordinate magnitude), as the exact positions rounded once are
// within u |q|. False (qA, qB unchanged) when the pattern cannot be verified or that bound fails.
// Argument. valued_on_heights verifies the status pattern of the heights H~ and of the exact
// H* alike, so both solutions are its closed form: the computed displacement T~_i is within
// 2^9 u Ha of the closed form on H~ (value_bounds.h's tight solver bound), which moves by at
// most 2 e_act (T = C - H_i at the plane: C a convex combination of heights at the plane) or
// 8 e_act (T = -S) from H~ to H*: |T~ - T*| <= dT = 2^9 u Ha + 8 e_act. The displacement is
// d = (T/|n|) n/|n|; the rounded normal is within rho = sqrt(3) e_n/|n~| of n* relative (<=
// 0.01 required), which moves 1/|n| by <= 1.02 rho and n/|n| by <= 2.04 rho; the double
// operations (n~.n~, the division, the product) add <= 5u. So |d~_ik - d*_ik| <= eta =
// (dT + (|T~| + dT)(4 rho + 8u)) / |n~| (1.01 covering the second-order terms), and the sum
// P + d~ rounded adds u |q|. Required: eta <= 2u Q, so each coordinate is within 3u max(Q, |q|)
// of P + d*, which attains c's exact value exactly; compare/'s judge allows 4u Q' a coordinate
// for positions rounded to doubles, Q' the largest magnitude of the pair's and the positions'
// coordinates (engine_comparison.cpp, position_tolerance). (The normal's term is rho / (1 -
// rho) <= 1.0102 rho exactly: 4 rho is slack.) Where dT is too wide for that (a contact made
// by rounding on a deep pair: 2^9 u Ha is hundreds of ulps of the coordinates), the
// displacements T~_i come from double-word heights instead (compensated_displacements.h's
// compensated_displacements: the same closed form of the same verified pattern, each within
// its own bound dT_i of T*_i, ~u |T*_i|), and eta is taken with those. Parallel and nearly
// parallel edge pairs, which have no double words or ones ~10 u off, take their heights by
// expansions (expansion_heights: each within a few u of its own exact value) and, where needed,
// their displacements from those (compensated_displacements on given heights).
bool compensated_positions(const TetVertices& A, const TetVertices& B, const Candidate& c,
                           Positions<double>& qA, Positions<double>& qB);

// Convenience over raw tetrahedra: the quick list when quick_candidates decides, else the full
// candidate set (on the stack), on the pair rescaled by a power of two; value 0 when not
// intersecting or invalid. The hot functions to time. definitions §8: the choice is certified
// (value_bounds.h) or comes from the exact path (certified = true either way); NaN with
// certified = false when the value is not a normal double. pdd2_accel(A, B, k): k = 1 or 6.
// pdd2_accel(A, B, 1) is the case-2 QP on the rigid direction of rigid_superset
// (superset_depth.h, index −1) when it decides: rigid PD plus one direction solve.
Choice pdd2_static_choice(const TetVertices& A, const TetVertices& B);
Choice pdd2_choice(const TetVertices& A, const TetVertices& B);
Choice pdd2_relaxed_choice(const TetVertices& A, const TetVertices& B);
Choice pdd2_accel_choice(const TetVertices& A, const TetVertices& B, int k);
// pdd2_accel_choice(A, B, 1) and rigid_pd2_choice(A, B), the same choices, with their common
// first try (rigid_superset_scaled on the raw pair: kernel, choice, certificate) run once: where
// it certifies, rigid_pd2's half of the two calls' work.
void rigid_and_accel1_choices(const TetVertices& A, const TetVertices& B, Choice& rigid, Choice& accel1);
// The same two choices where the caller (solve_pair) holds the pair rescaled, As, Bs =
// power_scaled(A, B) (exact), the superset kernel's lanes K of (As, Bs) (quick_lanes ran it; K is
// changed here), its candidate set build_candidates(As, Bs) and that set's rigid_pd2(set): the
// hot path's routes, without running the kernel, building the set or choosing over it again,
// values on the rescaled pair. `rigid`: the
// superset's certified choice, or uncertified with index -1 where it has none (the hot path then
// takes the set's: rigid_pd2(set)); `accel1` (with_accel1 only): pdd2_accel1's choice,
// uncertified where the hot path takes the exact path.
void rigid_and_accel1_of_rescaled(const TetVertices& As, const TetVertices& Bs, detail::SupersetLanes& K,
                                  const CandidateSet& set, const Choice& set_rigid, bool with_accel1, Choice& rigid,
                                  Choice& accel1);

}  // namespace pdd::fast
