// facet_bounds.h — internal to fast/src/global: the candidate facet normals of M = A - B
// bounded, and the two things the certificates prove with them: a lower bound on the
// rigid depth's square, and that the overlap is at least d0 along every unit normal off a cap.
//
// Input : the pair (engine units, global_depth.h).
// Output: FacetBounds::get(): the 44 candidate directions (SPEC §3's: A's and B's face normals,
//         the cross products of an edge of A and an edge of B), each n rounded componentwise, its
//         overlaps D(n), D(-n) bounded below and n.n above; computed on first use, n exactly
//         (~2 us over an integer frame, ~20 us by expansions), false where the pair is outside
//         the expansions' range or does not intersect. pd2_lower: PD^2 rounded down. polytope_inside_ball: every unit u with
//         u.d <= c0 has D(u) >= d0.
//
// Math. D(u) = max_i u.a_i - min_j u.b_j, the overlap along u, is the support function of M;
// the rigid depth PD is its least value over unit u, attained at a facet normal of M, and every
// facet normal is a candidate (up to orientation: both are bounded). Each candidate n is formed
// exactly and rounded; its overlaps are bounded from the heights in doubles with an error bound
// where that bound lies within 2^-42 of the overlap (most directions: an overlap of the pair's
// size), else from its heights taken exactly, the extreme ones compared exactly and each overlap
// rounded down from its exact value (the directions along a contact, whose overlap is far below
// |n| times the size); n.n rounded up. So PD^2 >= min D(n)^2 / n.n, rounded down, within a few
// 2^-42 of it. Exactly: over the pair's integer frame where it has one (integer_heights.h: n in
// __int128, each height a wide integer), else by expansions (expansion.h). The polytope test is
// argued at polytope_inside_ball (facet_bounds.cpp).
#pragma once

#include "global/vec3.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::global {

// One candidate direction n of M (exact), as bounds: its overlaps D(n) and D(-n) bounded below
// (in n's units: |n| times the overlap along n / |n|), n.n bounded above, and n rounded
// componentwise (each component within 4u of its exact value, approx_of's bound on a compressed
// expansion). zero: n = 0 exactly (parallel edges: no facet).
struct DirectionBounds {
  V3 n{};
  double nn_up = 0, plus_low = 0, minus_low = 0;
  bool zero = false;
};

inline constexpr int kDirections = 44;

// How the bounds are computed: over the pair's integer frame where it has one (integer_heights.h:
// coordinates on one grid of 60 bits, as decimal grids and their shifted copies are; ~10x faster),
// else by expansions; or by expansions only (tests compare the two).
enum class FacetArithmetic { IntegersWhereExact, Expansions };

// A pair's candidate bounds, computed on first use (shared by the certificates of one pair).
class FacetBounds {
 public:
  FacetBounds(const TetVertices& A, const TetVertices& B,
              FacetArithmetic arithmetic = FacetArithmetic::IntegersWhereExact)
      : A_(A), B_(B), arithmetic_(arithmetic) {}
  bool get();
  const DirectionBounds (&dirs() const)[kDirections] { return dirs_; }
  bool by_integers() const { return by_integers_; }  // (after get(): the frame's arithmetic was used)

 private:
  const TetVertices& A_;
  const TetVertices& B_;
  FacetArithmetic arithmetic_;
  DirectionBounds dirs_[kDirections];
  int state_ = 0;  // 0: not computed, 1: computed, -1: failed
  bool by_integers_ = false;
};

// PD^2 rounded down; false where the bounds are not available.
bool pd2_lower(FacetBounds& bounds, double& pd2_low);

// A proved lower bound on PD^2, the rigid depth squared (the least squared overlap over unit
// directions), within a few u of it; false where neither arithmetic can take the pair (a
// coordinate outside the expansions' exact range, an expansion over its capacity) or the pair
// does not intersect.
bool rigid_depth_squared_lower(const TetVertices& A, const TetVertices& B, double& pd2_low);

// Every unit u with u.d <= c0 has D(u) >= d0: the polytope {u : D(u) <= d0, u.d <= c0} lies inside
// the open unit ball (with the margin kInside); d is taken as given (exact).
bool polytope_inside_ball(FacetBounds& bounds, const V3& d, double c0, double d0);

// The same with two planes: every unit u with u.d1 <= c1 and u.d2 <= c2 has D(u) >= d0 (two
// lower bounds on the relaxed value that hold beyond a plane each, the overlap's between them).
bool polytope_inside_ball(FacetBounds& bounds, const V3& d1, double c1, const V3& d2, double c2, double d0);

// The same with k >= 1 planes: every unit u with u.d_i <= c_i for every i has D(u) >= d0 (caps
// about several tied minimisers). False also where a clip would keep more than 2^16 points or
// the last plane's crossings number more than 2^20 (not shown).
struct Halfspace {
  V3 d{};
  double c = 0;
};
bool polytope_inside_ball(FacetBounds& bounds, const Halfspace* planes, int k, double d0);

// The vertices shown to lie more than gamma from the plane of contact along every unit u with
// D(u) <= d0: A's vertex x more than gamma below A's highest (max_a u.(a - x) > gamma), B's y
// more than gamma above B's lowest (max_b u.(y - b) > gamma). For each, the polytope {u :
// D(u) <= d0, u.(a - x) <= gamma for every other vertex a} inside the unit ball (its three planes'
// directions rounded, each plane widened by its rounding). Bit i for A's vertex i, bit 4 + j for
// B's vertex j; 0 where the bounds are not available. The pair is (A, B) of `bounds`.
unsigned vertices_off_the_contact(FacetBounds& bounds, const TetVertices& A, const TetVertices& B, double d0,
                                  double gamma);

}  // namespace pdd::fast::global
