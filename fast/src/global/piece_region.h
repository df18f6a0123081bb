// piece_region.h — internal to fast/src/global: the double path of piece_enumeration.cpp keeps
// only the pieces whose cones meet the region of the sphere where the relaxed value can lie
// below the window's top edge (global_depth.h's lower bound, turned into a region).
//
// Input : the pair's centred vertices (the enumeration's own doubles) and the window's top edge
//         `top` (piece_screen.h: an eigenpair can hold the minimiser only if its value is below it).
// Output: rows[ma] (ma = 1..15), bit mb set unless piece S = (S_A, S_B) = (ma, mb) certainly
//         cannot hold a minimiser u* of G with G(u*) < top; false (rows untouched) when the test
//         does not apply (a direction below its accuracy: nearly parallel edges, a zero cross
//         product; top not positive and finite). On the paper's pairs about 60 of the 225 pieces
//         remain (95.6 in the product of the rows and columns that remain).
//
// Why it is safe. Let D(n) = max_A a.n - min_B b.n (the overlap along unit n; a, b the centred
// vertices). G(n) >= D(n)^2 / 32 (global_depth.h), so a minimiser u* with G(u*) < top lies in
// Omega = {unit n : D(n) < rho}, rho^2 = 32 top. u* lies in the closed cone R_S of every active
// set S optimal there (global_depth.h), and R_S lies in the polyhedral cone
//     K(S) = {n : (a_i - a_j).n >= 0 for i in S_A, j not in S_A; (b_j - b_i).n >= 0 for i in S_B,
//            j not in S_B}
// (R_S's conditions: a_i.n >= (c + T_A).n exactly for i in S_A, <= for the others, and
// b_j.n <= (c - T_A).n exactly for j in S_B: S_A is a top set of A along n, S_B a bottom set of
// B). So a piece can hold u* only if K(S) meets Omega, i.e. the least D on K(S) and the unit
// sphere is below rho. Where is that least value attained? D = h_P, the support function of
// P = A - B = conv{a_i - b_j}, positive on the sphere when the origin is inside P (checked
// below: the pair of centred doubles intersects, as it does wherever the double path runs;
// else the test does not apply, for the arguments below need h > 0). At a minimiser n of
// D over K(S) and the sphere, let W be the walls of K(S) active at n (planes e.n = 0, e an edge
// vector of A or B):
//  - two independent walls: n is along e1 x e2;
//  - none: n is a local minimum of h_P on the sphere. The face F of P exposed by n must then be
//    a facet: if dim F <= 1, a tangent t at n orthogonal to F's direction gives every v in F the
//    same v.t = c, and along n cos s + t sin s the value max_F v.n = h cos s + c sin s falls for
//    small s of one sign (or both, c = 0), while the other vertices stay below; so n is a facet
//    normal of P;
//  - one wall e (or parallel ones): n is a local minimum of h_P on the great circle e.n = 0,
//    where h_P is the support function of P projected on the plane orthogonal to e; by the same
//    argument in the plane, the face of the projected polygon exposed by n is an edge, parallel
//    to the projection of an edge d of A or B (the edges of a Minkowski sum of polygons are
//    their summands' edges): n is along e x d.
// Facets of P are a face of A (with a vertex of B), a face of B, or two edges (a Minkowski sum's
// facets), so in every case n is along the cross product of two of the 12 edge vectors of A and
// B: a face normal of A or of B (two edges of one face), the cross product of two opposite
// edges of A or of B, or of an edge of A and one of B: 50 lines, 100 directions X. Hence: if
// every direction x of X with D(x) < rho (unit x; "close") lies outside K(S), K(S) misses Omega
// and S is dropped. (Parallel edges have no cross product, and no such minimiser either.)
// Positivity: the origin lies inside P exactly when every facet inequality of P holds strictly
// at it, h_P(facet normal) > 0; the facet normals are among the directions of X, so h > 0 on X
// (certified, below) gives h_P > 0 on the whole sphere.
//
// In doubles. The vertices are exact doubles, |coordinates| <= M. Each edge vector is rounded
// once (u relative per component), each cross product component x_c = f_a g_b - f_b g_a of
// rounded edges and rounded products errs by <= 4.02u (|f_a g_b| + |f_b g_a|) against the exact
// cross product x* of the exact edges (u = 2^-53); summed over c, computed, and doubled for the
// sum's own roundings: |x - x*| <= E = 8u m, m the computed sum of the six |products|. So the
// unit vectors differ by |x/|x| - x*/|x*|| <= 2E / |x| (|a/|a| - b/|b|| <= |a - b|/|a| +
// ||b| - |a||/|a|) <= delta = 17u m / sqrt(x.x) (the square root's and the dot's roundings
// inside 17/16). A direction is used only when delta <= 2^-20 and x.x >= 2^-900 (no product
// underflows enough to matter: the pair's scale is within 2^+-100 on the double path), else the
// test does not apply. A height a.x (a exact, x as computed) errs by <= 3.01u sum |a_c x_c| <=
// 5.3u M |x|; a difference of two, max_A - min_B, by <= 15u M |x| with its own rounding
// (|h| <= 2 sqrt(3) M |x|). h_P is R-Lipschitz on the sphere with R = max |a_i - b_j| <=
// 2 sqrt(3) M < 3.47 M. A direction is "far" when its computed h exceeds
// |x| (rho + w) (1 + 2^-40), w = M (3.47 delta + 16u) (every rounding of that expression inside
// the 2^-40): then the exact direction x*/|x*| has D >= h(x)/|x| - R delta > rho; likewise a
// computed h above tol = |x| w (1 + 2^-40) certifies D > 0 along x* (positivity, for x and -x
// of every line). Each exact direction of X whose D is below rho is therefore the computed x
// (or -x) of a direction that is not far ("close", kept). For a close x, piece (S_A, S_B) is
// kept when every condition of K(S) holds at x within tol: if x*/|x*| is in K(S),
// (a_i - a_j).x >= -|a_i - a_j| delta |x| >= -3.47 M delta |x| exactly, the computed heights'
// difference errs by <= 10.6u M |x| more, and its rounding by <= 3.5u M |x| (|a_i - a_j| <=
// 2 sqrt(3) M). So a piece holding u* is never dropped: the minimiser of D on K(S) is such an
// x*, below rho.
#pragma once

namespace pdd::fast::detail {

// The pieces that may hold a minimiser below top (above); false when the test does not apply.
bool region_pieces(const double (&pA)[4][3], const double (&pB)[4][3], double top, unsigned (&rows)[16]);

}  // namespace pdd::fast::detail
