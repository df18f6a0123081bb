// near_parallel_bound.h — internal to fast/src: a certified lower bound on the value of an edge
// pair whose direction n = eB × eA the doubles cannot resolve (every computed component within
// the degree-2 error bound E2, so the exact n may be 0 or a vector of any direction ⊥ eA), from
// well-conditioned quantities only. Aligned meshes (grids shifted by a non-grid offset, copies of
// a mesh) are full of such pairs: edges parallel up to the rounding of the coordinates.
//
// Inputs:  K   the superset kernel's lanes of the pair (superset_kernel.h), extent in the range of
//              filter_bounds.h;
//          fb  filter_bounds_of_extent(K.extent);
//          a, b  the edge pair: edge a = (s_u, s_v) of A, edge b = (r_x, r_y) of B.
// Output:  true with lo2 <= delta(n)² (definitions §4: the squared oriented depth along n) for
//          every orientation of n that is a facet normal of M = A ⊕ (−B); lo2 = +inf when no
//          orientation can be. False when the bound cannot be had in doubles (the caller then
//          decides the pair's facets exactly where it can, superset_depth.cpp's facet_bounds,
//          else takes the path that computes the pair's candidates).
//
// Why a bound on facet normals suffices: PD = max(0, min over candidates of delta) and every
// facet normal of M is a candidate (definitions §4); when every facet's delta is bounded below by
// a positive number, the origin is inside M and PD is the smallest facet delta, so candidates that
// are no facet normal need no bound (their delta is >= PD, as for every direction).
//
// The bound. Let n̂ be the unit facet normal of the pair, if there is one. It lies on the arc
// arc(a) of the great circle ⊥ eA between the outward normals of A's two faces at edge a (A's
// support along n̂ is edge a), and B's support along n̂ is edge b: n̂.(r_j − r_x) >= 0 for every
// vertex r_j of B. So delta(n̂) = n̂.(s_u − r_x) =: S(n̂), and n̂ lies in
//   F = arc(a) ∩ { m : m.(r_j − r_x) >= 0 for the two vertices j of B off edge b },
// (the constraint of r_y, whose tie with r_x defines n̂, is the ill-conditioned one and is left
// out: F only grows). F is an arc shorter than 180° (arc(a) is: its angle is 180° minus A's
// dihedral angle at a). On the great circle, S(m) = −R cos(θ − θ_x) with R the distance of r_x
// from the line of edge a and θ_x the direction d_x of r_x seen from that line: its only local
// minimum is at d_x. If d_x is not in F, the minimum of S over F is at an end of F, and
//   delta(n̂) = S(n̂) >= min over the ends of F of S.
// The ends of F are among: the outward normals N_f of A's faces f at edge a (arc(a)'s ends), and
// ±(e_b' × eA) for the edges b' = (r_x, r_j) of B (where a constraint m.(r_j − r_x) = 0 is
// tight). Points that are certainly not in F are dropped (certainly off arc(a): one of A's two
// other vertices certainly above edge a along it; or certainly violating a constraint); the
// others are kept (a kept point outside F can only lower the minimum: still a lower bound).
//   At N_f: S = H_x / |N_f| with H_x the kernel's depth of r_x below face f (superset_kernel.cpp).
//   At ±n' (n' = e_b' × eA, e_b' oriented from B's lower-numbered vertex r_w): S = ∓ h'/|n'| with
//   h' = n'.(r_w − s_u) (n' ⊥ e_b': both ends of b' are at the same height).
// d_x not in F, decided by signs of degree 4 (Lagrange: |eA|² d_x.w = (eA × p).(eA × w),
// p = r_x − s_u, d_x = the part of p ⊥ eA): d_x is certainly outside arc(a) when
// (eA × p).(eA × (s_k − s_u)) > E4 for one of A's other vertices s_k, or certainly violates a
// constraint when (eA × p).(eA × (r_j − r_x)) < −E4. (When the interiors intersect, d_x is never in
// F: there all of B but r_y would lie beyond r_x from the line of edge a, and A below it.)
//
// Errors: every degree-3 quantity used (H_x, h', the heights g of A's other vertices, the
// heights q of B's) has computed error <= 48 u L³ < E3, a difference of two <= 108 u L³ < E3;
// each degree-4 dot product of two cross products of differences <= 132 u L⁴ < E4
// (filter_bounds.h); the cross products' components <= 8 u L² < E2. A kept point's S is bounded
// below by (S̃ − E3) / ((|ñ| + √3 E2)(1 + 8u)) (1 − 4u): the exact numerator is > S̃ − E3, the
// exact |n| < |ñ| + √3 E2, and the factors cover the roundings of the square root, the sums and
// the division (at most 6 roundings, each <= u, against the 12 u taken); where |ñ| is far above
// its error, S² directly by (S̃ − E3)² / (ñ.ñ (1 + 4e-12)) (near_parallel_bound.cpp). A kept
// point whose S̃ is <= E3 (a possibly non-positive depth) makes the bound unavailable: false.
#pragma once

#include "certification/filter_bounds.h"
#include "kernel/superset_kernel.h"

namespace pdd::fast::detail {

bool near_parallel_bound(const SupersetLanes& K, const FilterBounds& fb, int a, int b, double& lo2);

// The sign alone: true when near_parallel_bound would give lo2 > 0 (every kept point's S̃ > E3),
// without the values (no division).
bool near_parallel_positive(const SupersetLanes& K, const FilterBounds& fb, int a, int b);

// Edges a of A and b of B exactly parallel, shown in doubles (false: not known).
bool exactly_parallel(const SupersetLanes& K, int a, int b);

// Structural zeros. For finite doubles, fl(a − b) = 0 iff a = b (gradual underflow), so a
// coordinate difference computed as 0 is exactly 0; a product with an exactly zero factor is
// exactly 0, and so is a sum of exactly zero terms. These tests are sufficient, not necessary:
// "false" only means "not known to be 0". Aligned pairs (shared axis directions, faces in the
// same coordinate planes) meet them often, without a single rounding.
//
// Component k of e × f, e = p1 − p0 and f = q1 − q0 (coordinate differences), is
// e_i f_j − e_j f_i with (i, j) = (k + 1, k + 2) mod 3: exactly 0 when both products have an
// exactly zero factor.
// (Bitwise & and |, not && and ||: every comparison is cheap, and on aligned pairs their
// outcomes follow no pattern a branch predictor learns.)
inline bool cross_component_zero(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  return ((p1[i] == p0[i]) | (q1[j] == q0[j])) & ((p1[j] == p0[j]) | (q1[i] == q0[i]));
}
inline bool cross_zero(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1) {
  return cross_component_zero(p0, p1, q0, q1, 0) & cross_component_zero(p0, p1, q0, q1, 1) &
         cross_component_zero(p0, p1, q0, q1, 2);
}

// (p1 − p0) × (q1 − q0) exactly 0, shown in doubles (false: not known): by structural zeros
// (cross_zero, no arithmetic: axis edges, edges in a coordinate plane), else exact coordinate
// differences whose cross products cancel as exact products (the test exactly_parallel makes).
bool cross_zero_in_doubles(const Vec3d& p0, const Vec3d& p1, const Vec3d& q0, const Vec3d& q1);

// The edge pairs (bit 8a + b) whose computed n = eB × eA has every component <= E2 in magnitude:
// the exact n may be 0 (no direction, or definitions §3's common perpendicular) or point anywhere ⊥ eA.
std::uint64_t unresolved_edge_pairs(const SupersetLanes& K, const FilterBounds& fb);

}  // namespace pdd::fast::detail
