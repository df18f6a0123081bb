// object_norm.h — the object norm of one tetrahedron moving from rest q0 to q1 (paper eq. 3,
// definitions §2), exactly:
//
//   sigma(q0, q1) = 1/10 * sum_{i>=j} d_i . d_j = 1/20 * ( sum_i |d_i|^2 + |sum_i d_i|^2 ),
//   d_i = p_i - r_i.
//
// A pure translation by t gives |t|^2.
#pragma once

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

Rational object_norm(const ExactTet& rest, const ExactTet& deformed);

}  // namespace pdd::reference
