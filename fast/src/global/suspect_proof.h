// suspect_proof.h — internal to fast/src/global: the exact path's check that the best double
// normal represents pdd2_global where the depth is far below the pair's size.
//
// Input : the best offer so far (exact path: its exact value q in the pair's units) and the
//         suspects the pieces left (best_offer.h: an exact H_S, the index k of an eigenvalue
//         whose eigenvector held S's sign conditions, S's exact conditions), and the floor
//         PD^2 / 32 (1 - 1e-8) below which no G(u) lies.
// Output: represented(): None when some suspect's eigenvalue mu_k may be a stationary value of
//         G below what the offers reach, i.e. when for a settled suspect's proved lower bound lo
//             q (1 + 2^-53) > lo (1 + 1e-9);
//         ByDouble when the best double offer's q meets every lo (the value is certified to
//         definitions §8 along a double normal); ByWitness when only a rational offer's does
//         (Best::witness: the value is certified, along a normal no double triple is). Its
//         offers (rounded eigenvectors, their neighbouring doubles, integer normals along them;
//         then the exact eigenvector shortened to rational components of 256 bits) may lower
//         the best. near_extent_sq: L^2, L the smaller tetrahedron's extent;
//         kUnrepresentedDepth: the depth (relative to L^2) below which the driver calls
//         represented().
//
// Exact path: whether the best offer may miss the minimum by more than definitions §8 allows
// because no double normal represents a better stationary point. An offered normal is an
// eigenvector rounded to doubles; along it the value exceeds the eigenvalue mu by up to
// ~|H| (u |v|)^2 / |v|^2, which is not small beside mu when the depth is far below the pair's
// size (a vertex 1e-18 inside a face: mu ~1e-37 beside |H| ~ 25). So every eigenvector that held its piece's
// signs when offered (the minimum may be there) is a suspect, and one whose exact eigenvalue
// lies in (floor, top), top = best (1 + 2^-53) / (1 + 1e-9), may be a stationary value (if the
// exact vector lies in the piece's cone, which the tolerant signs cannot tell) that beats every
// offer. Eigenvalues at or below the floor (PD^2 / 32 (1 - 1e-8), strictly below G everywhere;
// 0 when the rigid value is not known in doubles: G > 0 on the sphere of an intersecting pair)
// are not stationary values in the cone. Counted exactly (eigenvalues_below: the eigenvalue of
// index k lies in (floor, top) iff #at_or_below(floor) <= k < #below(top)).
// Each suspect in that window is then settled (represent_suspect): either its exact eigenvector
// is proved outside its piece's cone in both orientations (not a stationary value of G), or it
// yields a proved lower bound lo <= mu, and its eigenvector rounded, the neighbouring doubles
// and integer normals along it are offered (evaluated exactly: they only lower the best; the
// normal that attains pdd2_global on a generic near-coplanar contact is found by trying such
// triples, not excluded by a ratio of depth to size); where none of those meets lo, the exact
// eigenvector itself (exact steps of inverse iteration, shortened) is offered as a rational
// witness. The eigenvector is approached by exact steps until the bound is tight and every
// condition decided (mu located by exact counts where it lies next to another eigenvalue as
// small: a contact made by rounding, ~1e-33 |H| beside a zero one; suspect_proof.cpp).
// The pair is kept when the best exact value q after those offers satisfies
// q (1 + 2^-53) <= lo (1 + 1e-9) for every suspect kept, q the best double offer's value or
// else the witness's (kept only when below every double offer; the argument below holds for it
// word for word, its value being relaxed() along a normal too). Why that certifies definitions
// §8: the true minimum m* is G(u*) with u* an eigenvector of the H_S of a piece S whose cone
// holds u* (global_depth.h); q >= m* (q is G along a normal). If m* is a suspect's eigenvalue:
// at or below the floor it cannot be; at or above top, q (1 + 2^-53) <= q0 (1 + 2^-53) = top
// (1 + 1e-9) <= m* (1 + 1e-9) with q0 the best before the new offers (they only lower it); in
// the window, settled: not discarded (its eigenvector is in the cone), so m* >= lo and
// q (1 + 2^-53) <= lo (1 + 1e-9) <= m* (1 + 1e-9). Otherwise the enumeration itself offered
// m*'s own vector, and the bound holds without this check. The reported value is q rounded
// once (here by get_d, or again on the pair as given: within [q (1 - 2^-52), q (1 + 2^-53)]),
// so it lies within [m* (1 - 2^-52), m* (1 + 1e-9)].
// An unsettled suspect makes the caller reject the pair (kGlobalNotRepresentable), never
// report a value; so does a witness, where the caller needs a double normal attaining it.
// Walls' stationary points are not checked (the class below has no case of them).
#pragma once

#include "global/best_offer.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::global {

// represented()'s class: a rounded normal v~ (componentwise, |v~ - v| <= u |v|) changes the
// value of a stationary point mu of a piece by (v~ - v)^T (H - mu I) (v~ - v) / |v~|^2 <=
// |H|_2 u^2 (1 + 2u). When every vertex is within L of the centroid, H's entries
// (enumerate_pieces: (QA + QB - C S - S C + m C C + k T T) / 20 with |Q| <= 4 L^2, |C| <= L,
// |S| <= 8 L, |T| <= 2 L, m <= 8, k <= 8) are <= 76 L^2 / 20 < 4 L^2, so |H|_2 <= 12 L^2, and
// where mu >= 1e-20 L^2 the rounding costs <= 12 * 4.9e-32 / 1e-20 < 6e-11 relative, within
// kGlobalRel: the offers (eigenvectors polished exactly, rounded componentwise) represent it.
// Below that, represented() decides. L is taken as the SMALLER tetrahedron's extent: a
// contact much shallower than both tetrahedra (a vertex 1e-18 inside a face: adversarial-1-3,
// -13, -23, whose fast values would be 13%, 7% and 22% above the exact minimum without this rule)
// is rejected. Not proved: a pair whose one tetrahedron is far larger than the other (a vertex
// 1e18 away: the pieces with it active have |H| ~ 1e36) is not covered by the bound above;
// there the minimiser lies on the walls of the far vertex, offered from the near side, and
// the fast values agree with the exact engine's closed intervals (coordinates-1-to-1e18,
// adversarial-1-9, -19, the wide pair of tests/compare; -29 within its 1.7e-8 gap).
inline constexpr double kUnrepresentedDepth = 1e-20;
double near_extent_sq(const TetVertices& A, const TetVertices& B);

// floor_scaled: the floor PD^2 / 32 (1 - 1e-8) in the exact pieces' units (0 when unknown).
enum class Representation { ByDouble, ByWitness, None };
Representation represented(Best& best, double floor_scaled);

}  // namespace pdd::fast::global
