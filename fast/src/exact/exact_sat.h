// exact_sat.h — the exact intersection decision of definitions §4 (touching is not intersecting)
// by the separating-axis theorem, with the signs the double filter cannot decide taken exactly by
// double words or floating-point expansions (expansion.h): no rationals. For the pairs overlap_filter leaves
// Unknown, typically aligned ones (parallel faces, parallel and colinear edges, touching and
// coplanar faces), whose deciding signs are exact zeros.
//
// Input:  tetrahedra A (s0..s3), B (r0..r3), raw doubles; precondition: every coordinate finite.
// Output: SatVerdict::Intersecting or Disjoint, exact; Disjoint when A or B is flat (no interior,
//         definitions §1). Undecided when an expansion is needed and the pair is outside
//         in_exact_range (expansion.h), or an expansion exceeded its capacity: the caller then
//         decides on its rational path. (Signs the filter or the double words decide are exact
//         at any scale.)
//
// Theorem (the axes). For non-flat A and B, M = A ⊕ (−B) is a full-dimensional polytope and the
// interiors meet iff 0 is interior to M, iff every facet of M (outward normal m) has offset
// c(m) = max_i m.s_i − min_j m.r_j > 0. A facet of M is F_A + (−F_B), F_A the face of A where
// m.s is maximal and F_B the face of B where m.r is minimal, of dimensions summing to >= 2; so m
// is (i) the outward normal of a face of A, (ii) minus the outward normal of a face of B, or
// (iii) ±(e_a × e_b) for an edge a of A in F_A and an edge b of B in F_B, not parallel (parallel
// edges sum to a segment, which lies in a facet only together with a face: cases i, ii).
// Interiors disjoint iff some such m has c(m) <= 0. Each test below is "c(m) <= 0 and m is a
// facet normal of that kind"; each is sufficient (it gives a weakly separating plane, and the
// interiors of non-flat tetrahedra lie strictly on its two sides) and together they are
// necessary (the facet with c <= 0 passes its test). Every quantity is a determinant of three
// coordinate differences, det[x, y, z] = (x × y).z, of degree 3:
//   (i)  face f of T (vertices t0, t1, t2 = kFace[f], opposite t3 = T[f]), N = (t1 − t0) × (t2 − t0),
//        σ = sign N.(t3 − t0) (= orientation(T) · kFaceParity[f], never 0 for non-flat T), the
//        other tetrahedron's vertices o_j: separating iff σ N.(o_j − t0) <= 0 for every j.
//        (T = A: m = −σN; T = B: m = σN, the same test by the symmetry A ⊕ −B ↔ B ⊕ −A.)
//   (iii) n = e_a × e_b (e_a = s_v − s_u, e_b = r_y − r_x), skipped when exactly 0; with
//        α_w = n.(s_w − s_u) (w the two vertices of A off edge a), β_j = n.(r_j − r_x) (j off
//        edge b), γ = n.(s_u − r_x): m = +n separates as a facet normal iff α_w <= 0, β_j >= 0,
//        γ <= 0; m = −n iff α_w >= 0, β_j <= 0, γ >= 0.
//
// Signs. Each determinant is first evaluated in doubles, error <= 48 u L³ < E3 = 512 u L³
// (filter_bounds.h, "triple product"); |value| > E3 fixes its sign. An axis is dropped as soon as
// certain signs violate its test (both orientations for iii); an edge pair whose normal is 0
// without arithmetic (each 2x2 minor with a zero factor in both products, or the same factors
// for exact differences) is skipped. The remaining axes are decided exactly. An undecided value
// of a face axis whose vertex is one of the face's own is 0. One the doubles computed as not
// exactly 0 (most often not 0 by a rounding: a grid's copy shifted by a non-dyadic offset) is
// taken next on the axis' normal in double words (compensated_heights.h's compensated_normal
// and compensated_height_sign: the exact sign where their bound of 25 u² M decides it; a
// certain sign is exact). Then each value still undecided (an exact 0, most often)
// n.(p − q) = Σ_k n_k (p_k − q_k); a term vanishes when p_k == q_k (n_k is then not computed) or
// n_k = 0; n_k is the exact 2x2 minor of the differences (expansions, when they are exact in
// doubles; else expansion.h's cross); with one term left the sign is sign(n_k)·sign(p_k − q_k)
// (the comparison p_k > q_k is exact); otherwise the expansions' dot product. An edge axis
// passing its test with α_w1 = α_w2 = 0 has n = 0 (n ⊥ e_a, s_w1 − s_u, s_w2 − s_u, which span
// space for non-flat A) and is skipped. No tolerance is involved anywhere: every sign used is
// the exact sign of the polynomial on the input doubles.
#pragma once

#include <cstdint>

#include "exact/integer_heights.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

enum class SatVerdict { Intersecting, Disjoint, Undecided };

// open_edges (optional): bit 8a + b set for every edge pair (a, b) that may separate, e.g. from
// the superset kernel's depths D(±n) (superset_kernel.h: computed D(±n) > E3 means the exact one
// is > 0, so ±n does not separate); null: all 36 are filtered here. faces_decided: the caller's
// face_axes_sat found no face axis separating (they are not tested again).
// frame (optional): the pair's integer frame (integer_heights.h), shared by a caller that makes
// both calls on one pair (its scale is then found once); null: a frame of its own.
SatVerdict interiors_intersect_sat(const TetVertices& A, const TetVertices& B,
                                   const std::uint64_t* open_edges = nullptr, bool faces_decided = false,
                                   IntegerFrame* frame = nullptr);

// The face planes' values in doubles, as a caller computed them with the operations of the
// filter above (overlap_filter.cpp's face stage): for face f of A (f = 0..3, against B) and of
// B (4 + f, against A), N = (t1 − t0) × (t2 − t0) over kFace[f] (differences from t0),
// hl = N.(t_f − t0) and h[j] = N.(o_j − t0). Each is a triple product of differences (error
// <= 48 u L³ < E3), so any correctly rounded evaluation serves.
struct FacePlaneValues {
  double hl[8];
  double h[8][4];
};

// The face axes alone (cases i and ii), decided as above: Disjoint when one separates;
// Intersecting when none does — a verdict on the face axes only (the edge-pair axes are still
// to be tested: interiors_intersect_sat with faces_decided); Undecided as above. values
// (optional): the face planes' values already computed (the filter's signs then come from
// them, and each tetrahedron's orientation from a certain hl).
SatVerdict face_axes_sat(const TetVertices& A, const TetVertices& B, IntegerFrame* frame = nullptr,
                         const FacePlaneValues* values = nullptr);

// sign det[t_f1 − t_f0, t_f2 − t_f0, t_f3 − t_f0] / sign det[t1 − t0, t2 − t0, t3 − t0] for face f
// (kFace[f] = (f0, f1, f2), f3 = f): the sign of the permutation (f0, f1, f2, f) of (0, 1, 2, 3).
inline constexpr int kFaceParity[4] = {-1, +1, -1, +1};

}  // namespace pdd::fast::detail
