// theorem_audit.h — the paper's appendix Theorem 1 (eq. 11 = PD) settled exactly, per pair.
//
// For one valid pair:
//   eq11_holds       E11^2 == PD^2 (both exact, definitions §4);
//   axis, nested     eq. 11's minimising candidate and whether A's and B's projections on it
//                    nest (one interval inside the other);
//   witness          when E11 < PD: the translation v = (o / n.n) n of length E11 along the
//                    minimising axis n (o its overlap), rational, and whether B + v and B - v
//                    still have interiors intersecting A (exact hull test);
//   corrected_holds  PD^2 == max(0, min over candidates of sign(delta) delta^2): the
//                    statement with oriented depths instead of eq. 11's overlaps;
//   nef_equal        (on request) our hull of the 16 differences equals CGAL's Nef
//                    minkowski_sum_3(A, -B) (same vertex set; both convex).
//
// Why a failure must nest (checked, not assumed): overlap(n) <= min(delta(n), delta(-n))
// always, with equality when the intervals do not nest; and delta(n) >= PD for every n,
// since the support function of A (+) (-B), which contains the ball of radius PD about 0, is
// at least PD in every unit direction. So E11 < PD only on an axis where the projections nest.
#pragma once

#include <optional>
#include <string>

#include "pdd/reference/exact_kernel.h"

namespace pdd::compare {

struct TheoremVerdict {
  std::string name;
  std::optional<std::string> error;  // rejected pair
  bool intersecting = false;
  reference::Rational pd2, e11_2;
  bool eq11_holds = false;
  std::string axis;  // label of eq. 11's minimising candidate ("" when E11 = 0)
  bool nested = false;
  bool corrected_holds = false;
  std::optional<reference::Vector> witness;  // when E11 < PD
  bool witness_plus_intersects = false, witness_minus_intersects = false;
  std::optional<bool> nef_equal;
};

TheoremVerdict theorem_verdict(const TetPair& pair, bool with_nef);

// CGAL Nef-polyhedron Minkowski sum A (+) (-B) against our convex hull (vertex sets).
bool nef_minkowski_equals_hull(const reference::ExactPair& pair);

}  // namespace pdd::compare
