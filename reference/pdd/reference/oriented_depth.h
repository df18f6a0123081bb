// oriented_depth.h — the oriented depth of definitions §4 along one candidate direction.
//
//   delta(n) = (max_i n.s_i - min_j n.r_j) / |n|
//
// the length B must travel along n/|n| to clear A. Exact arithmetic never takes |n|, so the
// value is carried as its numerator D = max_i n.s_i - min_j n.r_j and compared through the
// rational signed square sign(D) D^2 / |n|^2, which orders candidates exactly as delta does.
#pragma once

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

// D = max_i n.s_i - min_j n.r_j  (delta(n) times |n|).
Rational oriented_depth_numerator(const ExactPair& pair, const Vector& n);

// sign(delta) * delta^2 = D |D| / n.n, a rational monotone in delta.
Rational oriented_depth_signed_square(const ExactPair& pair, const Vector& n);

// max / min of n.x over the four vertices of a tetrahedron.
Rational max_projection(const ExactTet& tet, const Vector& n);
Rational min_projection(const ExactTet& tet, const Vector& n);

}  // namespace pdd::reference
