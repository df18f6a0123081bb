// exact_predicates.h — exact signs for the inputs the filter cannot decide (floating-point
// expansions, expansion.h, in their exact range, some over a pair's integer frame where it has
// one, integer_heights.h; GMP rationals otherwise).
//
// Inputs are the raw doubles of the pair; each double is taken as the rational it denotes
// (definitions §1), so these functions agree with the exact engine by construction. They allocate
// and are slow (microseconds); the fast path calls them only when |value| <= filter bound
// (filter_bounds.h), which for generic inputs never happens.
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "exact/expansion.h"
#include "exact/integer_heights.h"
#include "pdd/direction_label.h"
#include "pdd/sign.h"
#include "pdd/tet_pair.h"
#include "pdd/tet_tables.h"

namespace pdd::fast {

// sign of det[t1 − t0, t2 − t0, t3 − t0] (6 × signed volume).
Sign orientation_sign_exact(const TetVertices& T);

// Classification of the edge pair EE:a:b by definitions §3, decided exactly.
enum class EdgePairSide { Keep, Flip, Undecidable };  // orientation rule on g_k
struct EdgePairClass {
  EdgePairKind kind = EdgePairKind::Generic;
  EdgePairSide side = EdgePairSide::Keep;
};
EdgePairClass classify_edge_pair_exact(const TetVertices& A, const TetVertices& B, int a, int b);

// sign of max_i n.s_i − min_j n.r_j for the exact oriented candidate n of `label`
// (definitions §3–4).
// Precondition: the label is a candidate of the pair (not a colinear edge pair).
Sign depth_sign_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label);

// The exact oriented candidate n of `label` (definitions §3: a face's outward or inward normal,
// eB × eA, or for parallel edges their common perpendicular (e.e) w − (w.e) e; an edge pair
// oriented by the rule, ':+' kept and ':−' flipped where it is undecidable), as expansions:
// degree 2 in coordinate differences, 3 for parallel edges. False outside the expansions'
// exact range (in_exact_range), beyond their capacity, or for a colinear edge pair.
bool oriented_normal_expansion(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                               detail::ExpVec& n);

// Whether the exact oriented candidates of labels l1 and l2 point the same way (n1 × n2 = 0 and
// n1.n2 > 0), so that their depths delta are exactly equal (delta depends on the direction
// only). nullopt when the expansions cannot decide it (every non-zero |coordinate| must lie in
// [2^-100, 2^100]: n1 × n2 has degree up to 6 in coordinate differences; or an expansion
// exceeds its capacity).
std::optional<bool> same_direction_exact(const TetVertices& A, const TetVertices& B,
                                         const DirectionLabel& l1, const DirectionLabel& l2);

// same_direction_exact against one label l1 for several l2: l1's exact normal computed once,
// at the first answer not already known. The answers for one pair are memoised per thread
// (kernel/pair_memo.h, keyed by both labels): the values of one solve_pair (the rigid tie
// order, pdd2_accel's) ask the same ties of the same pair, half of the
// questions on contacts made by rounding.
// Most answers are "no" by n1 not being orthogonal to a vector n2 is orthogonal to (two
// degree-3 signs); where the pair has an integer frame (integer_heights.h) and n1 has degree 2
// (a face, an edge pair that is not parallel), those signs are taken over integers: ~900
// instructions a question with the memo and the frame's setup, against ~3,700 with the
// expansions' n1 and two dots (callgrind, rigid_pd2_and_accel1 on a tetrahedron against its
// own translate, whose edge pairs are parallel up to the roundings of the shift: 1.3 questions
// a pair). The expansions keep the rest.
class ExactDirection {
 public:
  ExactDirection(const TetVertices& A, const TetVertices& B, const DirectionLabel& l1);
  std::optional<bool> same_as(const DirectionLabel& l2) const;  // same_direction_exact(A, B, l1, l2)
  // same_as given `side`, the sign of n1.n2 when known (+1, -1; 0: not known), for an l2 whose
  // normal is fixed by its two vectors (a face, or an edge pair that is not parallel): once n1
  // is orthogonal to both, n1 is a multiple of n2 and that sign is the answer, without n2.
  std::optional<bool> same_as(const DirectionLabel& l2, int side) const;
  // same_as with an edge pair's direction as labelled, not by the orientation rule: EE:a:b:+
  // is eB × eA (for parallel edges their common perpendicular, definitions §3) and EE:a:b:−
  // its negation whatever the rule says (a face: same_as).
  std::optional<bool> same_as_labelled(const DirectionLabel& l2) const;

 private:
  std::optional<bool> same(const DirectionLabel& l2, bool rule, int side = 0) const;
  std::optional<bool> computed(const DirectionLabel& l2, bool rule, int side) const;
  std::optional<bool> orthogonal_over_integers(const DirectionLabel& l2) const;
  const TetVertices& A_;
  const TetVertices& B_;
  DirectionLabel l1_;
  mutable detail::ExpVec n_;  // l1's normal, built at its first use (state_ 1; -1: not available),
                              // up to its sign until oriented_
  mutable int state_ = 0;
  mutable bool oriented_ = false;
  mutable int in_range_ = -1;  // the expansions' range holds (1) or not (0); -1: not checked
  mutable detail::IntegerFrame frame_{A_, B_};
  mutable __int128 ni_[3] = {0, 0, 0};  // l1's normal over the frame, up to its sign
  mutable int integer_state_ = 0;       // ni_ built (1), or no degree-2 normal / no frame (-1)
};

// A candidate's definitions §4 depth in two exact parts, for comparing delta² = D²/(n.n) without
// division: D = max_i n.s_i − min_j n.r_j and n.n, n the exact oriented candidate of the label.
// ok = false when expansions cannot give them: a coordinate outside [2^-40, 2^40] (non-zero),
// a colinear edge pair (no direction), or capacity. Range: every coordinate is then a multiple
// of 2^-92 (its last bit); n.n has degree 4 and D 3 in them, so every term of compare_delta2_exact's
// D_p² n_q.n_q (degree 10) is a multiple of 2^-920: normal (expansion.h's argument). A parallel
// edge pair's n = (e.e) w − (w.e) e has degree 3, D 4, n.n 6: degree 14 in those products, so
// its parts are given only when every non-zero |coordinate| of the pair is in [2^-20, 2^20]
// (multiples of 2^-72, products of 14 multiples of 2^-1008, still normal; magnitudes below
// 2^339, far from overflow: exact_predicates.cpp).
// The label's exact oriented normal (definitions §3) where the products of degree 10 in
// coordinate differences built on it stay exact (14 for a parallel edge pair, whose normal has
// degree 3): the range above; false outside it, for a colinear edge pair or past an
// expansion's capacity. depth_parts_exact's. `rule` (optional): an edge pair's orientation rule
// as evaluated (Keep or Flip: decided; faces leave it unchanged).
bool normal_for_degree_ten(const TetVertices& A, const TetVertices& B, const DirectionLabel& label,
                           detail::ExpVec& n, EdgePairSide* rule = nullptr);

struct ExactDepthIntegers;  // D² and n.n as integers times powers of two (exact_predicates.cpp)
struct ExactDepthParts {
  detail::Expansion D, nn;
  bool ok = false;
  // built at the parts' first comparison over integers, then kept (copies share it): a running
  // minimum or a sort compares one candidate's parts many times
  mutable std::shared_ptr<const ExactDepthIntegers> integers;
};
ExactDepthParts depth_parts_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel& label);

// delta² = D²/(n.n) of the label's exact candidate from depth_parts_exact, as a double v with a
// root bound r (value_bounds.h: the exact delta² lies in [lower_of(v, r), upper_of(v, r)]);
// false where depth_parts_exact cannot give the parts, D is 0 or a part's error exceeds 1%.
// For the contenders whose compensated heights (compensated_heights.h) cannot certify them: a
// nearly parallel edge pair of a contact made by rounding (n ~ u |e|², its height ~ u |n| L)
// or an exactly parallel one; a few microseconds where the rationals take tens.
// Bound. approx_of gives D~ within eD and n.n~ within en (rho_D = eD/|D~|, rho_n = en/n.n~);
// sqrt(v) = |D|/sqrt(n.n) is then within rho_D (1 + 2 rho_D) + rho_n/2 relative, and the
// product and the quotient add u each: r = 1.02 (rho_D + rho_n + 4u), the 4u covering those
// and the roundings of lower_of and upper_of, as finish_root_rel's (value_bounds.h).
bool delta2_by_expansions(const TetVertices& A, const TetVertices& B, const DirectionLabel& label, double& v,
                          double& r);

// Eq. 11 (definitions §4) over the candidates l[0..n) by expansions: each one's overlap O =
// min(hiA, hiB) − max(loA, loB) of the exact heights along its exact normal (the range of
// normal_for_degree_ten). `zero`: some O <= 0 exactly (E11 = 0 whatever the rest); else v, r:
// the least O²/(n.n) among them (exact comparisons, compare_delta2_exact on (O, n.n)) as a
// double with a root bound, as delta2_by_expansions. False where an expansion cannot be had
// (range, capacity) or a part's error exceeds 1%.
bool eq11_by_expansions(const TetVertices& A, const TetVertices& B, const DirectionLabel* l, int n, bool& zero,
                        double& v, double& r);

// sign(delta²_p − delta²_q) = sign(D_p² n_q.n_q − D_q² n_p.n_p) (n.n > 0), exactly; nullopt
// when an expansion exceeds its capacity. Both parts from depth_parts_exact (ok).
std::optional<int> compare_delta2_exact(const ExactDepthParts& p, const ExactDepthParts& q);

// The position in l[0..n) (labels of the pair's candidates in canonical order) of the first
// least exact delta², exact ties to the earliest; -1 where expansions cannot decide. A running
// minimum w: after step k it is the first least of l[0..k]. Each step takes, in this order,
//  - `decided(k, w)` when given and it answers: the sign of delta²_k − delta²_w found by the
//    caller by cheaper certified means (certify.h: compensated depths);
//  - an exact tie of direction (same_direction_exact: delta depends on the oriented direction
//    only, so they are equal and the earlier is kept), unless `approx` shows the two directions
//    certainly apart (its double normal per label and a bound on each component's error,
//    value_bounds.h's e_n: the double cross product certainly not 0); where `approx` also
//    shows the sign of their dot product and l[k] is not a parallel edge pair, that sign
//    answers once the exact normals are shown parallel (ExactDirection::same_as(l, side));
//  - the exact comparison (depth_parts_exact, compare_delta2_exact; w's parts kept).
// On an aligned pair the near ties of the least delta² are mostly one direction (a face and the
// edge pairs of its plane) or a rounding apart (decided by the caller): no parts.
struct ApproxNormal {
  double n[3];
  double e;
  bool parallel_pair = false;  // a parallel edge pair: its normal is not fixed by its edges
};
// The exact normals of p and q certainly not parallel (a component of the computed cross
// product beyond its error bound); false: not known.
bool certainly_not_parallel(const ApproxNormal& p, const ApproxNormal& q);
// The sign of the exact n_p.n_q from two double normals and their bounds, where the computed
// dot product exceeds its error bound; 0 otherwise.
int certain_dot_sign(const ApproxNormal& p, const ApproxNormal& q);
using DeltaOrderHint = std::function<std::optional<int>(int k, int w)>;
int first_least_delta2_exact(const TetVertices& A, const TetVertices& B, const DirectionLabel* l, int n,
                             const ApproxNormal* approx = nullptr, const DeltaOrderHint& decided = {});

}  // namespace pdd::fast
